"""One thread that waits on many sockets at once and hands each readable one to its reader.

A rospy node gives every subscribed connection a thread of its own blocked in recv(); a
node with thousands of connections (a swarm controller: two per robot) spends its time
switching between them and fighting over the GIL. ReceiveThread does what roscpp's poll
set does: one epoll wait over every socket, and for each socket with bytes, its reader,
called in this thread. course_common.rospy_internals.one_receive_thread() plugs it under
rospy's subscriptions. Imports no rospy.
"""
import contextlib
import selectors
import socket
import threading


class ReceiveThread:
    """Waits on sockets; calls ``reader()`` for one that is readable, in its own thread.

    ``add(sock, reader, first=None)``: from now on, ``reader()`` runs whenever ``sock`` has
    bytes (or an error, or has been closed by the peer: recv tells the reader which);
    ``first()``, if given, runs once in the thread before that (for bytes read from the
    socket before it was added), and returning False drops the socket. A reader returns
    True to be called again, False to be dropped (it then owns the socket again). A reader
    that raises is dropped too, and ``on_error(reader, error)`` is told. ``remove(sock)``
    drops a socket: call it before closing the socket, so that its descriptor number is not
    reused while still waited on. Both may be called from any thread; they take effect
    before the thread next waits: bytes that come after a socket's remove() are not read,
    and a reader's own remove() of another socket holds for the rest of its round.
    """

    def __init__(self, name, on_error):
        self._on_error = on_error
        self._selector = selectors.DefaultSelector()
        self._changes = []              # ('add', sock, reader, first) / ('remove', sock)
        self._removed_now = set()       # sockets a reader removed in this round
        self._lock = threading.Lock()
        self._wake_read, self._wake_write = socket.socketpair()
        self._wake_read.setblocking(False)
        self._wake_write.setblocking(False)
        self._selector.register(self._wake_read, selectors.EVENT_READ, None)
        self._thread = threading.Thread(target=self._run, name=name, daemon=True)
        self._thread.start()

    def add(self, sock, reader, first=None):
        self._change(('add', sock, reader, first))

    def remove(self, sock):
        if threading.current_thread() is self._thread:
            self._removed_now.add(sock)     # a reader's call: not read later in this round
        self._change(('remove', sock))

    def _change(self, change):
        with self._lock:
            self._changes.append(change)
        with contextlib.suppress(BlockingIOError):  # full: the thread is awake already
            self._wake_write.send(b'.')

    def _apply_changes(self):
        with contextlib.suppress(BlockingIOError):
            while self._wake_read.recv(4096):
                pass
        with self._lock:
            changes, self._changes = self._changes, []
        for change in changes:
            if change[0] == 'add':
                _, sock, reader, first = change
                try:
                    self._selector.register(sock, selectors.EVENT_READ, reader)
                except (KeyError, ValueError, OSError) as err:
                    self._on_error(reader, err)    # closed before it could be waited on
                    continue
                if first is not None:
                    self._call(first, sock)
            else:
                with contextlib.suppress(KeyError, ValueError):  # never added, or dropped
                    self._selector.unregister(change[1])

    def _run(self):
        while True:
            ready = self._selector.select()
            self._removed_now.clear()
            # Changes first: a socket removed before its bytes came must not be read, even
            # when epoll lists its bytes ahead of the wake-up that carries the removal.
            if any(key.data is None for key, _ in ready):
                self._apply_changes()
            for key, _ in ready:
                if key.data is not None and self._still_waited_on(key):
                    self._call(key.data, key.fileobj)

    def _still_waited_on(self, key):
        """False once key's socket was dropped (or dropped and added again) in this round."""
        if key.fileobj in self._removed_now:
            return False
        try:
            return self._selector.get_key(key.fileobj) is key
        except (KeyError, ValueError):              # dropped, or closed since
            return False

    def _call(self, reader, sock):
        """reader() for sock; sock no longer waited on if it returns False or raises."""
        try:
            keep = reader()
        except Exception as err:                    # a reader's bug must not stop the others
            keep = False
            self._on_error(reader, err)
        if not keep:
            with contextlib.suppress(KeyError, ValueError):
                self._selector.unregister(sock)
