"""Unit tests of course_common.tcpros_frames: a whole frame or nothing, never a blocked sender."""
import socket
import struct
import threading

import pytest
from course_common.tcpros_frames import PartialFrameError, send_frame

FRAME = struct.Struct('<II')  # a sequence number and a marker, 8 bytes like a tiny message
MARKER = 0xC0FFEE
SEND_DEADLINE_S = 10.0  # generous: sending a few thousand frames takes milliseconds


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


def test_frames_reach_a_reader_that_keeps_up(tcp_pair):
    writer, reader = tcp_pair
    assert all(send_frame(writer, FRAME.pack(i, MARKER)) for i in range(10))
    data = b''
    while len(data) < 10 * FRAME.size:
        data += reader.recv(4096)
    assert [FRAME.unpack_from(data, k * FRAME.size) for k in range(10)] == [
        (i, MARKER) for i in range(10)]


def test_a_stalled_reader_loses_whole_frames_and_never_blocks_the_sender(tcp_pair):
    writer, reader = tcp_pair
    results = []

    def flood():
        results.extend(send_frame(writer, FRAME.pack(i, MARKER)) for i in range(200000))

    sender = threading.Thread(target=flood, daemon=True)
    sender.start()
    sender.join(SEND_DEADLINE_S)
    assert not sender.is_alive(), 'send_frame blocked on a reader that does not read'
    assert False in results, 'the buffers never filled: the test did not exercise dropping'

    # What did arrive is a whole number of intact frames, in order: nothing was half-sent.
    data = _read_all(reader)
    assert len(data) % FRAME.size == 0
    frames = [FRAME.unpack_from(data, k) for k in range(0, len(data), FRAME.size)]
    assert all(marker == MARKER for _, marker in frames)
    sequence = [seq for seq, _ in frames]
    assert sequence == sorted(sequence)
    assert sequence == [i for i, sent in enumerate(results) if sent]


class _ShortWriteSocket:
    """A socket whose buffer has room for only part of the next frame."""

    def __init__(self, room):
        self.room = room

    def send(self, data, flags):
        assert flags & socket.MSG_DONTWAIT, 'frames must be sent without blocking'
        return min(self.room, len(data))


@pytest.mark.parametrize('room', [1, 7])
def test_a_partly_sent_frame_is_an_error(room):
    with pytest.raises(PartialFrameError):
        send_frame(_ShortWriteSocket(room), FRAME.pack(1, MARKER))


def test_a_broken_connection_raises_the_socket_error(tcp_pair):
    writer, reader = tcp_pair
    reader.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack('ii', 1, 0))
    reader.close()  # RST: the next writes fail with ECONNRESET or EPIPE
    with pytest.raises(OSError) as err:
        for i in range(1000):
            send_frame(writer, FRAME.pack(i, MARKER))
    assert not isinstance(err.value, PartialFrameError)
