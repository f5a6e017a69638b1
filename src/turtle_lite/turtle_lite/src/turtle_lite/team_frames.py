"""Every turtle of a simulator as a tf frame: changes in its pose topics, pose -> transform.

No rospy. The nodes find the pose topics with course_common.pose_topics (a turtle's frame is
the robot name it gives, e.g. '/sim/turtle1/pose' below '/sim' -> 'turtle1') and pass poses
in as plain numbers. Units are metres and radians; the transform is the one the ROS tf2
tutorials broadcast for turtlesim: parent ``world``, translation (x, y, 0), rotation the yaw
theta about z (counter-clockwise positive).
"""

import math
from collections import namedtuple

from course_common.finite import check_finite

Transform = namedtuple('Transform', 'x y z qx qy qz qw')
"""Translation (m) and unit quaternion (x, y, z, w) of a frame in its parent."""


def diff_topics(old, new):
    """(added, removed) between two {topic: frame} maps: added a dict, removed a sorted list.

    A topic whose frame changed (it cannot, for one namespace) counts as removed and added.
    """
    added = {t: f for t, f in new.items() if old.get(t) != f}
    removed = sorted(t for t, f in old.items() if new.get(t) != f)
    return added, removed


def pose_to_transform(x, y, theta):
    """The Transform of a turtle at (x, y) m heading theta rad. Raises ValueError if not finite."""
    for label, value in (('x', x), ('y', y), ('theta', theta)):
        check_finite('pose ' + label, value)
    half = 0.5 * theta
    return Transform(float(x), float(y), 0.0, 0.0, 0.0, math.sin(half), math.cos(half))
