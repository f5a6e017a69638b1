"""The optional Tk window "TurtleSim": 500x500, the canvas with turtle sprites.

Imported only when ``~gui`` is true, so a headless node never loads tkinter or ImageTk.
The window runs in the main thread and redraws at most every REFRESH_MS from snapshots of
the simulator; the simulation itself stays in the tick thread.
"""

import rospy
from course_common.tk_window import open_root, show_picture

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
    root = open_root('~gui is true but DISPLAY is not set: running headless',
                     '~gui is true but the Tk window could not be opened (%s): '
                     'running headless')
    if root is None:
        return False
    pixels, poses = sim.snapshot()
    height, width = pixels.shape[:2]
    state = {'last': None}

    def next_image():
        key = sim.view_key()
        if key == state['last']:  # copy and redraw only when something changed
            return None
        state['last'] = key
        return render(*sim.snapshot())

    show_picture(root, TITLE, render(pixels, poses), next_image, REFRESH_MS, REFRESH_MS,
                 lambda: done.is_set() or rospy.is_shutdown(),
                 geometry='%dx%d' % (width, height))
    return True
