"""The windows on an X display, for the GUI tests: names, places, sizes, and a polite close.

Just enough Xlib through ctypes (no extra package): list the named windows with their
geometry, and ask one to close as a window manager's close button does (a WM_DELETE_WINDOW
client message: the program decides what closing means). Under a bare Xvfb there is no
window manager, so a top-level window's place is its place on the screen.
"""
import ctypes
import ctypes.util
from collections import namedtuple

#: One named window: its name, size, whether it is mapped, its id and its place on the screen.
XWindow = namedtuple('XWindow', 'name width height mapped id x y')

_CLIENT_MESSAGE = 33
_NO_EVENT_MASK = 0
_IS_VIEWABLE = 2


class _Attributes(ctypes.Structure):
    _fields_ = [('x', ctypes.c_int), ('y', ctypes.c_int), ('width', ctypes.c_int),
                ('height', ctypes.c_int), ('border_width', ctypes.c_int),
                ('depth', ctypes.c_int), ('visual', ctypes.c_void_p),
                ('root', ctypes.c_ulong), ('class', ctypes.c_int),
                ('bit_gravity', ctypes.c_int), ('win_gravity', ctypes.c_int),
                ('backing_store', ctypes.c_int), ('backing_planes', ctypes.c_ulong),
                ('backing_pixel', ctypes.c_ulong), ('save_under', ctypes.c_int),
                ('colormap', ctypes.c_ulong), ('map_installed', ctypes.c_int),
                ('map_state', ctypes.c_int), ('all_event_masks', ctypes.c_long),
                ('your_event_mask', ctypes.c_long),
                ('do_not_propagate_mask', ctypes.c_long),
                ('override_redirect', ctypes.c_int), ('screen', ctypes.c_void_p)]


class _ClientMessage(ctypes.Structure):
    _fields_ = [('type', ctypes.c_int), ('serial', ctypes.c_ulong),
                ('send_event', ctypes.c_int), ('display', ctypes.c_void_p),
                ('window', ctypes.c_ulong), ('message_type', ctypes.c_ulong),
                ('format', ctypes.c_int), ('data', ctypes.c_long * 5)]


class _Event(ctypes.Union):
    _fields_ = [('xclient', _ClientMessage), ('pad', ctypes.c_long * 24)]


#: Xlib's error handler type. Its default handler ends the process on any error, and a window
#: can vanish between listing it and asking its name (a program starting or closing): the
#: handler here ignores errors, and such a window is left out.
_ERROR_HANDLER = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p)
_ignore_errors = _ERROR_HANDLER(lambda _display, _event: 0)


class XWindows:
    """A connection to display (':N'); close() when done."""

    def __init__(self, display):
        x = ctypes.cdll.LoadLibrary(ctypes.util.find_library('X11') or 'libX11.so.6')
        x.XSetErrorHandler.argtypes = [_ERROR_HANDLER]
        x.XSetErrorHandler.restype = ctypes.c_void_p
        x.XSetErrorHandler(_ignore_errors)
        x.XOpenDisplay.restype = ctypes.c_void_p
        x.XOpenDisplay.argtypes = [ctypes.c_char_p]
        x.XDefaultRootWindow.restype = ctypes.c_ulong
        x.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
        x.XQueryTree.argtypes = [ctypes.c_void_p, ctypes.c_ulong,
                                 ctypes.POINTER(ctypes.c_ulong), ctypes.POINTER(ctypes.c_ulong),
                                 ctypes.POINTER(ctypes.POINTER(ctypes.c_ulong)),
                                 ctypes.POINTER(ctypes.c_uint)]
        x.XFetchName.argtypes = [ctypes.c_void_p, ctypes.c_ulong,
                                 ctypes.POINTER(ctypes.c_char_p)]
        x.XGetWindowAttributes.argtypes = [ctypes.c_void_p, ctypes.c_ulong,
                                           ctypes.POINTER(_Attributes)]
        x.XInternAtom.restype = ctypes.c_ulong
        x.XInternAtom.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int]
        x.XSendEvent.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_long,
                                 ctypes.POINTER(_Event)]
        x.XFlush.argtypes = [ctypes.c_void_p]
        x.XFree.argtypes = [ctypes.c_void_p]
        x.XCloseDisplay.argtypes = [ctypes.c_void_p]
        self.x = x
        self.dpy = x.XOpenDisplay(display.encode())
        if not self.dpy:
            raise RuntimeError('cannot open display %s' % display)

    def close(self):
        self.x.XCloseDisplay(self.dpy)

    def windows(self):
        """[XWindow] of every named window on the screen."""
        found = []
        stack = [self.x.XDefaultRootWindow(self.dpy)]
        while stack:
            win = stack.pop()
            name = ctypes.c_char_p()
            attrs = _Attributes()
            if self.x.XFetchName(self.dpy, win, ctypes.byref(name)) and name.value \
                    and self.x.XGetWindowAttributes(self.dpy, win, ctypes.byref(attrs)):
                found.append(XWindow(name.value.decode(), attrs.width, attrs.height,
                                     attrs.map_state == _IS_VIEWABLE, win, attrs.x, attrs.y))
            root = ctypes.c_ulong()
            parent = ctypes.c_ulong()
            children = ctypes.POINTER(ctypes.c_ulong)()
            count = ctypes.c_uint()
            if self.x.XQueryTree(self.dpy, win, ctypes.byref(root), ctypes.byref(parent),
                                 ctypes.byref(children), ctypes.byref(count)):
                stack.extend(children[i] for i in range(count.value))
                if children:
                    self.x.XFree(children)
        return found

    def mapped(self, name):
        """The mapped windows called name."""
        return [w for w in self.windows() if w.name == name and w.mapped]

    def ask_to_close(self, window_id):
        """What a window manager's close button sends: WM_PROTOCOLS / WM_DELETE_WINDOW."""
        event = _Event()
        message = event.xclient
        message.type = _CLIENT_MESSAGE
        message.window = window_id
        message.message_type = self.x.XInternAtom(self.dpy, b'WM_PROTOCOLS', False)
        message.format = 32
        message.data[0] = self.x.XInternAtom(self.dpy, b'WM_DELETE_WINDOW', False)
        self.x.XSendEvent(self.dpy, window_id, False, _NO_EVENT_MASK, ctypes.byref(event))
        self.x.XFlush(self.dpy)
