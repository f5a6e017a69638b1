"""stageros's optional Tk window: the world, robots, beams and trails, redrawn ~10 times a second.

Imported only without -g, so a headless node never loads tkinter or ImageTk. The window runs
in the main thread from snapshots taken under the node's lock; the simulation stays in the
step thread. With no display (or no Tk) the node WARNs and runs headless, where Stage would
fail to open its window.
"""
import contextlib
import os

import rospy

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


def run_window(node):
    """Show the window until ROS shuts down or it is closed; False if none could be opened."""
    if not os.environ.get('DISPLAY'):
        rospy.logwarn('stageros: no display (DISPLAY is not set): running without a window '
                      '(use -g to ask for that)')
        return False
    try:
        import tkinter

        from PIL import ImageTk
        root = tkinter.Tk()
    except Exception as exc:
        rospy.logwarn('stageros: the window could not be opened (%s): running without one', exc)
        return False

    world = node.world
    width, height = _window_size(world)
    occupancy = world.occupancy()
    view = picture.fit_view(picture.world_bounds(occupancy, [r.start_pose for r in world.robots]),
                            width, height)
    base = picture.floor_image(view, occupancy)
    root.title('Stage: %s' % os.path.basename(world.path))
    root.resizable(False, False)
    photo = ImageTk.PhotoImage(base)
    label = tkinter.Label(root, image=photo, borderwidth=0, highlightthickness=0)
    label.pack()
    state = {'step': None}

    def on_close():
        rospy.signal_shutdown('window closed')
        root.quit()

    def refresh():
        if rospy.is_shutdown():
            root.quit()
            return
        with node.lock:
            step = node.clock.steps
            robots = node.services.robot_views() if step != state['step'] else None
        if robots is not None:  # redraw only when the world moved on
            state['step'] = step
            photo.paste(picture.render(view, base, robots))
        root.after(REFRESH_MS, refresh)

    root.protocol('WM_DELETE_WINDOW', on_close)
    root.after(0, refresh)
    try:
        root.mainloop()
    finally:
        with contextlib.suppress(Exception):
            root.destroy()
    return True
