"""Sending small ready-made frames on a stream socket without ever blocking the sender.

The simulator's tick thread writes every pose and colour frame itself (rospy's per-subscriber
queue threads cost most of its CPU). A blocking write there would let one subscriber that
stops reading (a `rostopic echo` suspended with Ctrl-Z, a stuck node) freeze the simulation
for everybody once the socket buffers fill. turtlesim (roscpp, queue size 1) drops messages
for such a subscriber instead; so does this: a frame that does not fit is skipped, whole.
"""
import socket


class PartialFrameError(OSError):
    """Only part of a frame fitted: the byte stream is misaligned and must be closed."""


def send_frame(sock, frame):
    """Send all of ``frame`` on ``sock`` now, or none of it.

    ``sock`` is a socket in blocking mode without a Python timeout (as rospy leaves its
    TCPROS sockets), so MSG_DONTWAIT alone decides that the call returns at once.

    Returns True if the frame was sent, False if the peer's buffers are full (the frame is
    dropped). Raises PartialFrameError if only part of it could be sent, and the socket's
    own OSError (EPIPE, ECONNRESET, ...) if the connection is broken.
    """
    try:
        sent = sock.send(frame, socket.MSG_DONTWAIT)
    except (BlockingIOError, InterruptedError):
        return False
    if sent != len(frame):
        raise PartialFrameError('sent %d of %d bytes of a frame' % (sent, len(frame)))
    return True
