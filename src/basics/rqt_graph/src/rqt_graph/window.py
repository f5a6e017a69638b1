"""The Tk window of rqt_graph: the rendered graph, redrawn when the graph changes.

A worker thread asks the master every refresh period and renders a new PNG only when the
DOT text changed; the Tk thread picks the newest picture up. Imported only when a window is
wanted, so writing a file never loads tkinter.
"""
import io
import os
import signal
import threading

from .dotcode import RenderError, render
from .graph_source import MasterUnreachableError

TITLE = 'rqt_graph'
POLL_MS = 200  # how often the Tk thread looks for a new picture: prompt, and cheap
SCREEN_MARGIN_PX = (40, 120)  # a picture larger than the screen is shrunk to fit, minus this


class WindowUnavailableError(RuntimeError):
    """No display, or Tk cannot open it."""


def open_root():
    """A Tk root window, or WindowUnavailableError saying why not."""
    if not os.environ.get('DISPLAY'):
        raise WindowUnavailableError('DISPLAY is not set')
    try:
        import tkinter
        root = tkinter.Tk()
    except Exception as err:  # TclError, ImportError: any reason means "no window"
        raise WindowUnavailableError('Tk cannot open display %s: %s'
                                % (os.environ['DISPLAY'], err)) from None
    root.title(TITLE)
    return root


class _Latest:
    """The newest (png or None, status) from the worker, handed over under a lock."""

    def __init__(self):
        self._lock = threading.Lock()
        self._value = None

    def put(self, png, status):
        with self._lock:
            self._value = (png, status)

    def take(self):
        with self._lock:
            value, self._value = self._value, None
            return value


def _worker(source, refresh_s, latest, stop):
    last_dot = None
    while not stop.is_set():
        try:
            graph, dot = source.read()
            text = dot.to_string()
            if text != last_dot:  # re-render only when the graph changed
                latest.put(render(dot, 'png'), graph.counts())
                last_dot = text
        except (MasterUnreachableError, RenderError) as err:
            latest.put(None, str(err))
            last_dot = None  # draw again once the master is back
        stop.wait(refresh_s)


def run_window(root, source, refresh_s):
    """Shows the graph until the window is closed or the process gets SIGINT/SIGTERM."""
    import tkinter

    from PIL import Image, ImageTk

    picture = tkinter.Label(root, background='white')
    picture.pack(fill='both', expand=True)
    status = tkinter.Label(root, anchor='w')
    status.pack(fill='x')
    max_size = (root.winfo_screenwidth() - SCREEN_MARGIN_PX[0],
                root.winfo_screenheight() - SCREEN_MARGIN_PX[1])
    latest, stop = _Latest(), threading.Event()
    worker = threading.Thread(target=_worker, args=(source, refresh_s, latest, stop),
                              name='rqt_graph_worker', daemon=True)
    shown = {}

    def poll():
        value = latest.take()
        if value is not None:
            png, text = value
            if png is not None:
                image = Image.open(io.BytesIO(png))
                image.thumbnail(max_size)
                shown['photo'] = ImageTk.PhotoImage(image)  # Tk keeps no reference itself
                picture.configure(image=shown['photo'])
                print('rqt_graph: showing %s' % text, flush=True)
            status.configure(text=text)
        root.after(POLL_MS, poll)

    # Ctrl-C in the terminal closes the window (Tk would otherwise swallow the interrupt).
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: root.quit())
    root.protocol('WM_DELETE_WINDOW', root.quit)
    worker.start()
    root.after(0, poll)
    try:
        root.mainloop()
    finally:
        stop.set()
        root.destroy()
