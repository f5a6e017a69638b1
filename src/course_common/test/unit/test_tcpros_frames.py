"""Unit tests of course_common.tcpros_frames: whole frames in order, never a blocked sender."""
import errno
import socket
import struct
import threading
import time

import numpy as np
import pytest
from course_common.tcpros_frames import FrameStream, send_keeping_gil, split_frames

FRAME = struct.Struct('<II')  # a sequence number and a marker, 8 bytes like a tiny message
MARKER = 0xC0FFEE
SEND_DEADLINE_S = 10.0  # generous: sending a few thousand frames takes milliseconds
# A send() that blocks makes no progress at all; a slow one (a loaded machine: 200000 sends
# took over 10 s beside the rest of the suite) does. Blocked = no send returned for this long.
STALL_S = 5.0


@pytest.fixture
def tcp_pair():
    """A connected loopback TCP pair with small buffers, so a reader that stalls fills them."""
    with socket.socket() as listener:
        listener.bind(('127.0.0.1', 0))
        listener.listen(1)
        reader = socket.socket()
        reader.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
        reader.connect(listener.getsockname())
        writer, _ = listener.accept()
    writer.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, 4096)
    yield writer, reader
    writer.close()
    reader.close()


def _read_all(sock):
    sock.setblocking(False)
    chunks = []
    while True:
        try:
            chunk = sock.recv(65536)
        except BlockingIOError:
            return b''.join(chunks)
        if not chunk:
            return b''.join(chunks)
        chunks.append(chunk)


def _frames(data):
    """The (sequence, marker) frames of data, which must hold whole frames only."""
    assert len(data) % FRAME.size == 0, 'a frame was cut: %d bytes' % len(data)
    return [FRAME.unpack_from(data, k) for k in range(0, len(data), FRAME.size)]


def test_frames_reach_a_reader_that_keeps_up(tcp_pair):
    writer, reader = tcp_pair
    stream = FrameStream()
    assert all(stream.send(writer, FRAME.pack(i, MARKER)) for i in range(10))
    data = b''
    while len(data) < 10 * FRAME.size:
        data += reader.recv(4096)
    assert _frames(data) == [(i, MARKER) for i in range(10)]


def test_a_stalled_reader_loses_whole_frames_and_never_blocks_the_sender(tcp_pair):
    writer, reader = tcp_pair
    stream = FrameStream()
    results = []

    def flood():
        for i in range(200000):
            results.append(stream.send(writer, FRAME.pack(i, MARKER)))

    sender = threading.Thread(target=flood, daemon=True)
    sender.start()
    done = -1
    while sender.is_alive() and len(results) > done:  # results grows by one per send
        done = len(results)
        sender.join(STALL_S)
    assert not sender.is_alive(), 'FrameStream.send blocked on a reader that does not read'
    assert False in results, 'the buffers never filled: the test did not exercise dropping'

    # The reader reads again: a last frame goes out after any cut one has been finished.
    data = _read_all(reader)
    last = len(results)
    deadline = time.monotonic() + SEND_DEADLINE_S
    while not stream.send(writer, FRAME.pack(last, MARKER)):
        assert time.monotonic() < deadline, 'the cut frame was never finished'
        data += _read_all(reader)
    while len(data) % FRAME.size or FRAME.unpack_from(data, len(data) - FRAME.size)[0] != last:
        assert time.monotonic() < deadline, 'the last frame never arrived'
        data += _read_all(reader)
    # What arrived is every frame send() called sent, whole and in order, then the last.
    frames = _frames(data)
    assert all(marker == MARKER for _, marker in frames)
    assert [seq for seq, _ in frames] == [i for i, sent in enumerate(results) if sent] + [last]


class _ShortWrites:
    """A socket's buffer that takes `room` more bytes, then nothing until it is given more:
    FrameStream's send_now."""

    def __init__(self, room):
        self.room = room
        self.data = b''

    def send_now(self, sock, data):
        assert sock is self
        n = min(self.room, len(data))
        self.room -= n
        self.data += bytes(data[:n])
        return n


@pytest.mark.parametrize('room', [1, 7])
def test_a_cut_frame_is_finished_before_the_next_and_later_ones_wait_whole(room):
    sock = _ShortWrites(room)
    stream = FrameStream(sock.send_now)
    assert stream.send(sock, FRAME.pack(1, MARKER))  # on its way: part sent, part pending
    assert stream.pending == FRAME.size - room
    assert not stream.send(sock, FRAME.pack(2, MARKER))  # no room: frame 2 dropped whole
    sock.room = FRAME.size - room - 1
    assert not stream.send(sock, FRAME.pack(3, MARKER))  # frame 1 not finished: 3 dropped
    assert stream.pending == 1
    sock.room = 100
    assert stream.send(sock, FRAME.pack(4, MARKER))  # the end of 1, then 4 whole
    assert stream.pending == 0
    assert _frames(sock.data) == [(1, MARKER), (4, MARKER)]


def test_full_buffers_drop_the_frame_whole():
    sock = _ShortWrites(0)
    stream = FrameStream(sock.send_now)
    assert not stream.send(sock, FRAME.pack(1, MARKER))
    assert stream.pending == 0 and sock.data == b''


def test_a_broken_connection_raises_the_socket_error(tcp_pair):
    writer, reader = tcp_pair
    reader.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack('ii', 1, 0))
    reader.close()  # RST: the next writes fail with ECONNRESET or EPIPE
    stream = FrameStream()
    with pytest.raises(OSError):
        for i in range(1000):
            stream.send(writer, FRAME.pack(i, MARKER))


@pytest.mark.parametrize('make', [
    bytes,
    lambda b: memoryview(np.frombuffer(bytearray(b'..' + b), np.uint8))[2:],   # a frame of a batch
    lambda b: memoryview(b),                                                 # read-only
])
def test_send_keeping_gil_sends_bytes_and_buffers(tcp_pair, make):
    writer, reader = tcp_pair
    frame = FRAME.pack(7, MARKER)
    assert send_keeping_gil(writer, make(frame)) == FRAME.size
    data = b''
    while len(data) < FRAME.size:
        data += reader.recv(4096)
    assert data == frame


def test_send_keeping_gil_takes_nothing_once_the_buffers_are_full(tcp_pair):
    writer, _ = tcp_pair
    chunk = bytes(1024)
    taken = []
    while len(taken) < 100000 and (not taken or taken[-1]):   # never blocks: 0 when full
        taken.append(send_keeping_gil(writer, chunk))
    assert taken[-1] == 0 and sum(taken) > 0
    assert send_keeping_gil(writer, b'') == 0 and send_keeping_gil(writer, bytearray()) == 0


def test_send_keeping_gil_raises_the_socket_errors(tcp_pair):
    writer, reader = tcp_pair
    reader.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack('ii', 1, 0))
    reader.close()
    with pytest.raises((ConnectionResetError, BrokenPipeError)):
        for _ in range(1000):
            send_keeping_gil(writer, b'x')
    writer.close()
    with pytest.raises(OSError) as closed:
        send_keeping_gil(writer, b'x')
    assert closed.value.errno == errno.EBADF


@pytest.mark.parametrize('data, bodies, used', [
    (b'', [], 0),
    (b'\x02\x00', [], 0),                                     # a length cut short
    (b'\x02\x00\x00\x00ab', [b'ab'], 6),
    (b'\x02\x00\x00\x00ab\x00\x00\x00\x00\x03\x00\x00\x00xy', [b'ab', b''], 10),  # 3rd cut
    (b'\x01\x00\x00\x00a\x01\x00\x00\x00b', [b'a', b'b'], 10),
])
def test_split_frames_takes_the_whole_frames_only(data, bodies, used):
    assert split_frames(data) == (bodies, used)
