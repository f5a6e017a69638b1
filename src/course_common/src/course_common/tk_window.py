"""Tk windows for the simulators: a root or a WARN (both), one picture on a timer (turtlesim's).

tkinter and PIL.ImageTk are imported only when a window is opened, so a headless node never
loads them. The window runs in the calling (main) thread; the pictures come from a callback.
With no display, or no Tk, open_root WARNs and the caller carries on headless.
"""
import contextlib
import os

import rospy


def open_root(no_display_warning, failed_warning):
    """A tkinter.Tk root, or None after a WARN: no_display_warning when DISPLAY is unset,
    failed_warning % (the error,) when Tk or ImageTk cannot be loaded or opened."""
    if not os.environ.get('DISPLAY'):
        rospy.logwarn(no_display_warning)
        return None
    try:
        import tkinter

        from PIL import ImageTk  # noqa: F401 (show_picture needs it: fail here, with a WARN)
        return tkinter.Tk()
    except Exception as exc:
        rospy.logwarn(failed_warning, exc)
        return None


def show_picture(root, title, image, next_image, refresh_ms, first_refresh_ms, finished,
                 geometry=None):
    """Shows image (a PIL image) in root until finished() or the window is closed.

    The window has the title and a fixed size (geometry 'WxH' if given). Every refresh_ms
    (the first time after first_refresh_ms) next_image() gives the picture to show, or None
    when nothing changed. Closing the window shuts ROS down. root is destroyed on return.
    """
    import tkinter

    from PIL import ImageTk
    root.title(title)
    root.resizable(False, False)
    photo = ImageTk.PhotoImage(image)
    label = tkinter.Label(root, image=photo, borderwidth=0, highlightthickness=0)
    label.pack()
    if geometry:
        root.geometry(geometry)

    def on_close():
        rospy.signal_shutdown('window closed')
        root.quit()

    def refresh():
        if finished():
            root.quit()
            return
        picture = next_image()
        if picture is not None:
            photo.paste(picture)
        root.after(refresh_ms, refresh)

    root.protocol('WM_DELETE_WINDOW', on_close)
    root.after(first_refresh_ms, refresh)
    try:
        root.mainloop()
    finally:
        with contextlib.suppress(Exception):
            root.destroy()
