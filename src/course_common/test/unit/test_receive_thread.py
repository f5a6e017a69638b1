"""ReceiveThread: one thread waiting on many sockets, each readable one handed to its reader."""
import socket
import threading

import pytest
from course_common.receive_thread import ReceiveThread
from course_common.waiting import wait_for

DEADLINE_S = 10.0


class Reader:
    """Reads what a socket has; keeps while told to; records the thread it ran in."""

    def __init__(self, sock, keep=True, fail=False):
        self.sock, self.keep, self.fail = sock, keep, fail
        self.data = b''
        self.calls = 0
        self.threads = set()
        self.lock = threading.Lock()

    def __call__(self):
        with self.lock:
            self.calls += 1
            self.threads.add(threading.current_thread().name)
            if self.fail:
                raise RuntimeError('reader broke')
            try:
                chunk = self.sock.recv(4096)
            except BlockingIOError:
                return True
            self.data += chunk
            return self.keep and bool(chunk)

    def received(self):
        with self.lock:
            return self.data


def serve_a_later_socket(receiver, pairs):
    """Waits until a socket added now is read: every change made before it has applied."""
    other_a, other_b = pairs()
    marker = Reader(other_b)
    receiver.add(other_b, marker)
    other_a.sendall(b'x')
    wait_for(lambda: marker.received() == b'x', DEADLINE_S, 'a later socket served')


@pytest.fixture
def pairs():
    made = []

    def make():
        a, b = socket.socketpair()
        b.setblocking(False)
        made.append((a, b))
        return a, b
    yield make
    for a, b in made:
        a.close()
        b.close()


def test_many_sockets_read_in_one_thread(pairs):
    errors = []
    receiver = ReceiveThread('receiver_under_test', lambda r, e: errors.append(e))
    links = [pairs() for _ in range(50)]
    readers = [Reader(b) for _, b in links]
    for (_, b), reader in zip(links, readers, strict=True):
        receiver.add(b, reader)
    for round_ in range(3):
        for i, (a, _) in enumerate(links):
            a.sendall(b'%d.%d;' % (i, round_))
    expected = [b''.join(b'%d.%d;' % (i, r) for r in range(3)) for i in range(50)]
    wait_for(lambda: [r.received() for r in readers] == expected, DEADLINE_S,
             'every byte to its own reader')
    assert all(r.threads == {'receiver_under_test'} for r in readers)
    assert errors == []


def test_reader_returning_false_is_not_called_again(pairs):
    receiver = ReceiveThread('receiver_drop', lambda r, e: None)
    a, b = pairs()
    reader = Reader(b, keep=False)
    receiver.add(b, reader)
    a.sendall(b'one')
    wait_for(lambda: reader.received() == b'one', DEADLINE_S, 'the first bytes')
    a.sendall(b'two')   # readable again, but the reader asked to be dropped
    serve_a_later_socket(receiver, pairs)   # changes apply in order: any drop first
    assert reader.calls == 1 and b.recv(10) == b'two'


def test_removed_socket_is_no_longer_read(pairs):
    receiver = ReceiveThread('receiver_remove', lambda r, e: None)
    a, b = pairs()
    reader = Reader(b)
    receiver.add(b, reader)
    receiver.remove(b)
    a.sendall(b'late')
    serve_a_later_socket(receiver, pairs)   # changes apply in order: any drop first
    assert reader.calls == 0 and b.recv(10) == b'late'


def test_socket_removed_after_its_bytes_came_is_not_read(pairs):
    # In the thread itself, b's bytes arrive first and its removal second: the next
    # wait sees both, and the removal must win (epoll lists b's bytes first).
    receiver = ReceiveThread('receiver_remove_late', lambda r, e: None)
    a, b = pairs()
    trigger_a, trigger_b = pairs()
    reader = Reader(b)
    receiver.add(b, reader)
    serve_a_later_socket(receiver, pairs)   # b is waited on from here

    def bytes_then_removal():
        trigger_b.recv(10)
        a.sendall(b'late')
        receiver.remove(b)
        return False
    receiver.add(trigger_b, bytes_then_removal)
    trigger_a.sendall(b'go')
    serve_a_later_socket(receiver, pairs)
    assert reader.calls == 0 and b.recv(10) == b'late'


def test_a_socket_a_reader_removes_is_not_read_later_in_the_same_round(pairs):
    # both sockets have bytes when the thread first waits on them (both added while the
    # thread is held inside another reader, so that one round takes both); each reader
    # removes the other: whichever runs first, the other is not read in that round nor later
    receiver = ReceiveThread('receiver_remove_each_other', lambda r, e: None)
    (a1, b1), (a2, b2), (gate_a, gate_b) = pairs(), pairs(), pairs()
    inside, release = threading.Event(), threading.Event()
    calls = []

    def hold():
        gate_b.recv(10)
        inside.set()
        release.wait(DEADLINE_S)
        return True

    def reader(own, other, name):
        def read():
            own.recv(10)
            calls.append(name)
            receiver.remove(other)
            return True
        return read
    receiver.add(gate_b, hold)
    gate_a.sendall(b'g')
    wait_for(inside.is_set, DEADLINE_S, 'the thread held in a reader')
    a1.sendall(b'x')
    a2.sendall(b'y')
    receiver.add(b1, reader(b1, b2, 'b1'))
    receiver.add(b2, reader(b2, b1, 'b2'))
    release.set()
    serve_a_later_socket(receiver, pairs)
    assert len(calls) == 1


def test_a_failing_reader_is_reported_and_the_others_go_on(pairs):
    errors = []
    receiver = ReceiveThread('receiver_fail', lambda r, e: errors.append((r, e)))
    bad_a, bad_b = pairs()
    good_a, good_b = pairs()
    bad, good = Reader(bad_b, fail=True), Reader(good_b)
    receiver.add(bad_b, bad)
    receiver.add(good_b, good)
    bad_a.sendall(b'boom')
    good_a.sendall(b'fine')
    wait_for(lambda: good.received() == b'fine' and errors, DEADLINE_S, 'both handled')
    assert errors[0][0] is bad and 'reader broke' in str(errors[0][1])
    bad_a.sendall(b'again')
    good_a.sendall(b'more')
    wait_for(lambda: good.received() == b'finemore', DEADLINE_S, 'the good one again')
    assert bad.calls == 1


def test_a_socket_closed_before_it_is_waited_on_is_reported(pairs):
    errors = []
    receiver = ReceiveThread('receiver_closed', lambda r, e: errors.append(r))
    _, b = pairs()
    reader = Reader(b)
    b.close()
    receiver.add(b, reader)
    wait_for(lambda: errors, DEADLINE_S, 'the closed socket reported')
    assert errors == [reader] and reader.calls == 0


def test_peer_closing_wakes_the_reader(pairs):
    receiver = ReceiveThread('receiver_eof', lambda r, e: None)
    a, b = pairs()
    reader = Reader(b)
    receiver.add(b, reader)
    a.close()
    wait_for(lambda: reader.calls >= 1, DEADLINE_S, 'the end of the stream read')
    assert reader.received() == b''


class First:
    """A `first` call: records its thread and what it saw; keeps or drops the socket."""

    def __init__(self, keep=True):
        self.keep = keep
        self.threads = []

    def __call__(self):
        self.threads.append(threading.current_thread().name)
        return self.keep


def test_first_runs_once_in_the_thread_before_the_reader(pairs):
    receiver = ReceiveThread('receiver_first', lambda r, e: None)
    a, b = pairs()
    reader = Reader(b)
    first = First()
    receiver.add(b, reader, first)
    wait_for(lambda: first.threads, DEADLINE_S, 'the first call, with nothing to read')
    assert reader.calls == 0                # first runs without bytes on the socket
    a.sendall(b'later')
    wait_for(lambda: reader.received() == b'later', DEADLINE_S, 'the later bytes')
    assert first.threads == ['receiver_first'] and reader.threads == {'receiver_first'}


def test_first_returning_false_drops_the_socket(pairs):
    receiver = ReceiveThread('receiver_first_drop', lambda r, e: None)
    a, b = pairs()
    reader = Reader(b)
    first = First(keep=False)
    receiver.add(b, reader, first)
    a.sendall(b'unread')
    wait_for(lambda: first.threads, DEADLINE_S, 'the first call')
    serve_a_later_socket(receiver, pairs)   # changes apply in order: any drop first
    assert reader.calls == 0 and b.recv(10) == b'unread'
