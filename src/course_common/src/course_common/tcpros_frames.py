"""Sending ready-made frames on a stream socket without ever blocking the sender.

The simulators' step threads write every frame themselves (rospy's per-subscriber queue
threads cost most of their CPU). A blocking write there would let one subscriber that stops
reading (a `rostopic echo` suspended with Ctrl-Z, a stuck node, a host whose cable is out)
freeze the simulation for everybody once the socket buffers fill. roscpp (turtlesim,
stageros) drops messages for such a subscriber and keeps its connection; so does this:
a frame that finds the buffers full is dropped whole, and a frame the buffers took only part
of (a 1081-beam scan is 8.7 kB) is finished before any later frame is sent, so the byte
stream stays aligned and the subscriber, once it reads again, receives whole messages.

Each frame is sent by libc's send() called with the GIL kept (send_keeping_gil), not by
socket.send, which gives the GIL up for the call: a non-blocking send takes microseconds,
but taking the GIL back waits for whichever thread took it meanwhile (up to the
interpreter's switch interval, 5 ms). stageros with 1,000 robots sends 2,000 frames a step
while its receiving thread takes 1,000 cmd_vels: under a profiler, half of its step went to
those waits.
"""
import ctypes
import errno
import os
import socket
import struct

_U32 = struct.Struct('<I')

# PyDLL: ctypes keeps the GIL during the call (CDLL would give it up, as socket.send does).
_LIBC = ctypes.PyDLL(None, use_errno=True)
_libc_send = _LIBC.send
_libc_send.argtypes = (ctypes.c_int, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_int)
_libc_send.restype = ctypes.c_ssize_t
_SEND_FLAGS = socket.MSG_DONTWAIT | socket.MSG_NOSIGNAL
_FULL = (errno.EAGAIN, errno.EWOULDBLOCK)


def send_keeping_gil(sock, data):
    """Bytes of ``data`` the buffers of stream socket ``sock`` take now (0 when they are
    full), sent without blocking and without giving the GIL up. ``data``: bytes or a
    buffer (a memoryview of a frame batch's array). Raises OSError as socket.send does
    (EPIPE, ECONNRESET, EBADF for a closed socket, ...)."""
    if not isinstance(data, bytes):
        data = bytes(data)      # (a copy costs less than ctypes' look at a buffer's address)
    while True:
        sent = _libc_send(sock.fileno(), data, len(data), _SEND_FLAGS)
        if sent >= 0:
            return sent
        code = ctypes.get_errno()
        if code in _FULL:
            return 0
        if code != errno.EINTR:     # a signal came first: send again (PEP 475)
            raise OSError(code, os.strerror(code))


class FrameStream:
    """One connection's outgoing frames: each whole or not at all, in order.

    ``send`` is called from one thread per connection (the simulator's step thread).
    """

    def __init__(self, send_now=send_keeping_gil):
        """send_now(sock, data): the bytes of data the socket takes now, 0 when its buffers
        are full, never blocking (send_keeping_gil)."""
        self._tail = b''  # the unsent end of the last frame the buffers took part of
        self._send_now = send_now

    @property
    def pending(self):
        """Bytes of a frame cut short, still to be sent before the next frame."""
        return len(self._tail)

    def send(self, sock, frame):
        """Send ``frame`` on ``sock`` now, without blocking; True if it is on its way whole.

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
