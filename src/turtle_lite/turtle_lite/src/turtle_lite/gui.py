"""The optional Tk window "TurtleSim": 500x500, the canvas with turtle sprites.

Imported only when ``~gui`` is true, so a headless node never loads tkinter or ImageTk.
The window runs in the main thread and redraws at most every REFRESH_MS from snapshots of
the simulator; the simulation itself stays in the tick thread.
"""

import contextlib
import os

import rospy

from .picture import render

#: Redraw period of the window. 33 ms (about 30 frames/s) looks as smooth as turtlesim's
#: 16 ms repaint for a person while costing half the CPU.
REFRESH_MS = 33
TITLE = 'TurtleSim'


def run_window(sim, done):
    """Show the window until ROS shuts down or the window is closed.

    Returns True if the window ran, False (after a WARN) if it could not be opened, in which
    case the caller carries on headless.
    """
    if not os.environ.get('DISPLAY'):
        rospy.logwarn('~gui is true but DISPLAY is not set: running headless')
        return False
    try:
        import tkinter

        from PIL import ImageTk
        root = tkinter.Tk()
    except Exception as exc:
        rospy.logwarn('~gui is true but the Tk window could not be opened (%s): '
                      'running headless', exc)
        return False

    root.title(TITLE)
    root.resizable(False, False)
    pixels, poses = sim.snapshot()
    height, width = pixels.shape[:2]
    photo = ImageTk.PhotoImage(render(pixels, poses))
    label = tkinter.Label(root, image=photo, borderwidth=0, highlightthickness=0)
    label.pack()
    root.geometry('%dx%d' % (width, height))
    state = {'last': None}

    def on_close():
        rospy.signal_shutdown('window closed')
        root.quit()

    def refresh():
        if done.is_set() or rospy.is_shutdown():
            root.quit()
            return
        key = sim.view_key()
        if key != state['last']:  # copy and redraw only when something changed
            state['last'] = key
            pixels, poses = sim.snapshot()
            photo.paste(render(pixels, poses))
        root.after(REFRESH_MS, refresh)

    root.protocol('WM_DELETE_WINDOW', on_close)
    root.after(REFRESH_MS, refresh)
    try:
        root.mainloop()
    finally:
        with contextlib.suppress(Exception):
            root.destroy()
    return True
