"""Sending ready-made frames on a stream socket without ever blocking the sender.

The simulators' step threads write every frame themselves (rospy's per-subscriber queue
threads cost most of their CPU). A blocking write there would let one subscriber that stops
reading (a `rostopic echo` suspended with Ctrl-Z, a stuck node, a host whose cable is out)
freeze the simulation for everybody once the socket buffers fill. roscpp (turtlesim,
stageros) drops messages for such a subscriber and keeps its connection; so does this:
a frame that finds the buffers full is dropped whole, and a frame the buffers took only part
of (a 1081-beam scan is 8.7 kB) is finished before any later frame is sent, so the byte
stream stays aligned and the subscriber, once it reads again, receives whole messages.
"""
import socket
import struct

_U32 = struct.Struct('<I')


class FrameStream:
    """One connection's outgoing frames: each whole or not at all, in order.

    ``send`` is called from one thread per connection (the simulator's step thread).
    """

    def __init__(self):
        self._tail = b''  # the unsent end of the last frame the buffers took part of

    @property
    def pending(self):
        """Bytes of a frame cut short, still to be sent before the next frame."""
        return len(self._tail)

    def send(self, sock, frame):
        """Send ``frame`` on ``sock`` now, without blocking; True if it is on its way whole.

        ``sock`` is a socket in blocking mode without a Python timeout (as rospy leaves its
        TCPROS sockets), so MSG_DONTWAIT alone decides that the call returns at once.

        First the end of a frame cut short before is sent; while some of it is left, or
        when the peer's buffers are full, ``frame`` is dropped (False). A frame the buffers
        take only part of counts as sent (True): its end goes out ahead of the next frame.
        Raises the socket's own OSError (EPIPE, ECONNRESET, ...) if the connection is broken.
        """
        if self._tail:
            sent = self._send_now(sock, self._tail)
            self._tail = self._tail[sent:]
            if self._tail:
                return False
        sent = self._send_now(sock, frame)
        if sent == 0:
            return False
        if sent < len(frame):
            self._tail = bytes(frame[sent:])
        return True

    @staticmethod
    def _send_now(sock, data):
        try:
            return sock.send(data, socket.MSG_DONTWAIT)
        except (BlockingIOError, InterruptedError):
            return 0


def split_frames(data):
    """(bodies, used): the bodies of the whole frames at the start of ``data`` (each frame a
    little-endian uint32 length, then that many bytes), and how many bytes they took."""
    bodies = []
    pos, end = 0, len(data)
    while end - pos >= 4:
        (size,) = _U32.unpack_from(data, pos)
        if end - pos - 4 < size:
            break
        bodies.append(data[pos + 4:pos + 4 + size])
        pos += 4 + size
    return bodies, pos
