#!/usr/bin/env python3
"""Capture one frame of a camera from a running stageros (real or ours) into an npz.

Usage: capture_camera.py PREFIX OUT.npz [SUFFIX]  (PREFIX: the camera topics' prefix,
'/robot_0/'; SUFFIX: a robot's k-th of several cameras, '_k': image_k, depth_k, ...).
Waits (named deadline) for image, depth and camera_info of one step (equal stamps) and
saves rgba (h, w, 4) uint8, depth (h, w) float32, the messages' fields and the stamp.
"""
import sys
import time

import numpy as np
import rospy
from sensor_msgs.msg import CameraInfo, Image

DEADLINE_S = 60.0


def main():
    prefix, out = sys.argv[1], sys.argv[2]
    suffix = sys.argv[3] if len(sys.argv) > 3 else ''
    rospy.init_node('capture_camera', anonymous=True)
    got = {}

    def keep(name):
        def cb(msg):
            got.setdefault(name, {})[msg.header.stamp.to_nsec()] = msg
        return cb
    subs = [rospy.Subscriber(prefix + 'image' + suffix, Image, keep('image')),
            rospy.Subscriber(prefix + 'depth' + suffix, Image, keep('depth')),
            rospy.Subscriber(prefix + 'camera_info' + suffix, CameraInfo, keep('info'))]
    deadline = time.monotonic() + DEADLINE_S
    while time.monotonic() < deadline:
        if len(got) == 3:
            common = set(got['image']) & set(got['depth']) & set(got['info'])
            later = sorted(s for s in common if s >= 1_000_000_000)   # after 1 s of sim time
            if later:
                stamp = later[0]
                break
        time.sleep(0.05)
    else:
        sys.exit('no image, depth and camera_info of one step within %g s' % DEADLINE_S)
    for s in subs:
        s.unregister()
    im, de, info = got['image'][stamp], got['depth'][stamp], got['info'][stamp]
    rgba = np.frombuffer(im.data, np.uint8).reshape(im.height, im.width, 4)
    depth = np.frombuffer(de.data, '<f4').reshape(de.height, de.width)
    np.savez_compressed(
        out, rgba=rgba, depth=depth, stamp_ns=stamp,
        image_fields=np.array([im.encoding, im.header.frame_id, str(im.step),
                               str(im.is_bigendian)]),
        depth_fields=np.array([de.encoding, de.header.frame_id, str(de.step),
                               str(de.is_bigendian)]),
        info_frame=info.header.frame_id, info_size=np.array([info.width, info.height]),
        K=np.array(info.K), R=np.array(info.R), P=np.array(info.P), D=np.array(info.D),
        distortion_model=info.distortion_model)
    print('saved %s: stamp %d ns, %dx%d' % (out, stamp, im.width, im.height))


if __name__ == '__main__':
    main()
