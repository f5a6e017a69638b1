"""Publishers without a send queue, through rospy's public API."""
import warnings

import rospy

#: The start of the SyntaxWarning rospy gives for a Publisher made without queue_size.
QUEUE_SIZE_WARNING = "The publisher should be created with an explicit keyword argument"


def unqueued_publisher(name, data_class, **kwargs):
    """A rospy Publisher without a send queue (rospy's documented ``queue_size=None``).

    publish() then writes to every subscriber's socket from the calling thread before it
    returns: no QueuedConnection, no sender thread per subscriber woken for each message.
    multi_sync uses it where a message must leave at once (GO, the first command) or before
    the process exits (the final stop); the simulator for its 62.5 Hz pose and colour topics,
    whose connections course_common.rospy_internals.write_frame() writes frames to.
    rospy's warning about the missing queue_size is silenced for this call only: here it is
    deliberate.
    """
    with warnings.catch_warnings():
        warnings.filterwarnings('ignore', message=QUEUE_SIZE_WARNING, category=SyntaxWarning)
        return rospy.Publisher(name, data_class, queue_size=None, **kwargs)
