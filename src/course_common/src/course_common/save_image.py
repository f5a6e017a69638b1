"""The ~save_image services' handler (turtlesim's canvas, stageros's world): write a PNG.

Both simulators answer course_msgs/SaveImage (string path in, the absolute path written out)
through here.
write_png is the one PNG writer of both simulators' pictures.
"""
import os

import rospy


def image_path(requested, default):
    """The file a request asks for (its path, or the node's ~image_path when empty),
    absolute, with ~ expanded."""
    return os.path.abspath(os.path.expanduser(requested or default))


def write_png(path, image):
    """Writes image (a Pillow Image) to path as PNG, its folders made; ~ expanded. Returns the
    absolute path written."""
    path = os.path.abspath(os.path.expanduser(path))
    directory = os.path.dirname(path)
    if directory:
        os.makedirs(directory, exist_ok=True)
    image.save(path, format='PNG')
    return path


def save_logged(requested, default, write, subject):
    """Writes the picture and returns the path written, logging the outcome.

    write(absolute path) writes the PNG (making the folders) and returns the path written.
    subject names what was saved in the INFO line ('canvas', 'world'); an OSError or
    ValueError from write is logged (ERROR, naming the path) and raised again.
    """
    path = requested or default
    try:
        written = write(image_path(requested, default))
    except (OSError, ValueError) as exc:
        rospy.logerr('Could not save the image to [%s]: %s', path, exc)
        raise
    rospy.loginfo('Saved the %s to [%s]', subject, written)
    return written


def answer_save_image(requested, default, write, subject, failure):
    """save_logged for a service: its error is answered as rospy.ServiceException
    '<failure>: <error>' (the caller gets it, the node goes on)."""
    try:
        return save_logged(requested, default, write, subject)
    except (OSError, ValueError) as exc:
        raise rospy.ServiceException('%s: %s' % (failure, exc)) from exc
