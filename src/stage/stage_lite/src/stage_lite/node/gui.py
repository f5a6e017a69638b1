"""stageros's optional Tk window: the world, robots, beams and trails, redrawn ~10 times a second.

Imported only without -g, so a headless node never loads tkinter or ImageTk. The window runs
in the main thread from snapshots taken under the node's lock; the simulation stays in the
step thread. With no display (or no Tk) the node WARNs and runs headless, where Stage would
fail to open its window.
"""
import os

import rospy
from course_common.tk_window import open_root, show_picture

from . import world_picture as picture

#: Redraw period: 10 frames/s, one per simulated step at real time; more would cost CPU
#: without showing anything new.
REFRESH_MS = 100
#: Window size when the world file has no window block (Stage's default is about this).
DEFAULT_SIZE_PX = (700, 700)
MAX_SIZE_PX = 1600


def _window_size(world):
    size = (world.window or {}).get('size')
    try:
        w, h = (int(v) for v in size)
    except (TypeError, ValueError):
        return DEFAULT_SIZE_PX
    if w < 50 or h < 50:
        return DEFAULT_SIZE_PX
    return min(w, MAX_SIZE_PX), min(h, MAX_SIZE_PX)


def run_window(world, view, snapshot):
    """Show the window until ROS shuts down or it is closed; False if none could be opened.

    world: the World (its path and window block); view: its WorldView; snapshot(): (steps so
    far, the robots' views), taken under the node's lock."""
    root = open_root('stageros: no display (DISPLAY is not set): running without a window '
                     '(use -g to ask for that)',
                     'stageros: the window could not be opened (%s): running without one')
    if root is None:
        return False
    fitted, base = view.floor(*_window_size(world))
    state = {'step': None}

    def next_image():
        step, robots = snapshot()
        if step == state['step']:  # redraw only when the world moved on
            return None
        state['step'] = step
        return picture.render(fitted, base, robots)

    show_picture(root, 'Stage: %s' % os.path.basename(world.path), base, next_image,
                 REFRESH_MS, 0, rospy.is_shutdown)
    return True
