"""stageros's window, as Stage 4.3's: the world's view, a status line, pan, zoom, the Run menu.

Imported only without -g, so a headless node never loads tkinter or ImageTk. The window runs
in the main thread; the simulation stays in the step thread and never waits for a frame: when
a step has been taken (looked at every POLL_MS, one number read without the lock), or every
CHECK_S for what changes without a step, the window takes a snapshot under the node's lock (a
copy of the robots' views and the status line) and draws it outside the lock, so a slow frame
is a frame dropped, never a step. With no display (or no Tk) the node WARNs and runs headless,
where Stage would fail.

What the user does, as in Stage's window (libstage/worldgui.cc, canvas.cc):
- the world file's ``window( size center rotate scale show_data show_grid show_clock
  show_trailfast )`` sets the view and what is drawn (camera.window_camera, draw_options);
- drag with the left button to pan, turn the wheel to zoom about the pointer; resizing the
  window keeps the centre and the scale; View -> Reset (space) goes back to the world's view;
- View: Data (d), Grid (g), Clock (c), Trails (Ctrl+F) switch those drawings;
- Run: Pause (p), One step (.), Faster (]: x1.2), Slower ([: x0.8), Realtime ({), Fast (}:
  as fast as possible): the same speed-up as ~speedup, which only sets the speed at start;
- closing the window leaves the simulation running headless (a line in the log says so);
  File -> Exit (Ctrl+Q) ends stageros, as Stage's File -> Exit ends Stage.
"""
import contextlib
import os
import time
from dataclasses import replace

import rospy
from course_common.tk_window import open_root

from . import world_picture as picture
from .camera import MIN_SIZE_PX

#: Frames follow the steps: at real time (10 steps/s) each step gets its frame, soon after it
#: (a fixed 100 ms timer beside the 100 ms steps drifts against them and drops one in ten).
POLL_MS = 10  # how often the window looks for a new step: one int read, no lock
#: At most about 10 frames/s, flat out too; a step due at real time is never held back more
#: than the poll (a frame is drawn only when the world or the view changed).
FRAME_MIN_S = 0.095
CHECK_S = 0.1  # pause, speed and view changes show within this, step or no step
REST_MS = int(FRAME_MIN_S * 1000) - 2 * POLL_MS  # after a frame: no new one is due sooner


class StageWindow:
    """The window's state and its Tk widgets (made in the main thread by run_window).

    view: the node's WorldView; snapshot(): (steps, robots' views, status line) under the
    node's lock; steps(): the steps so far, read without it; loop: the StepLoop (the Run
    menu's pause and speed). The window closes when ROS shuts down.
    """

    def __init__(self, root, world, view, snapshot, loop, steps):
        import tkinter
        self.root = root
        self.view = view
        self.snapshot = snapshot
        self.steps = steps
        self.loop = loop
        self._frame_at = self._checked_at = float('-inf')  # monotonic s
        # One Tcl command for every poll: tkinter's after() registers (and later deletes) a
        # new command at each call, which at 100 polls a second costs more than the polls.
        self._poll = root.register(self.refresh)
        screen = (root.winfo_screenwidth(), root.winfo_screenheight())
        self.home = view.camera(screen)
        self.camera = self.home
        self.options = view.options
        self._drawn = None         # (step, camera, options, status) of the picture shown
        self._drag = None          # the pointer's last position while dragging
        root.title('Stage: %s' % os.path.basename(world.path))
        root.geometry('%dx%d' % self.home.size_px)
        root.minsize(MIN_SIZE_PX, MIN_SIZE_PX)
        self._menus(tkinter)
        self.canvas = tkinter.Canvas(root, width=self.home.width_px,
                                     height=self.home.height_px, borderwidth=0,
                                     highlightthickness=0, background='#b3b3cc')
        self.canvas.pack(fill='both', expand=True)
        self._photo = None
        self._image_item = None
        self._bind()
        root.protocol('WM_DELETE_WINDOW', self.close)

    def _commands(self):
        """Stage's menus: {menu: [(label, key as shown, Tk event, action) or None (a line)]}."""
        def view(option):
            return lambda: self.toggle(option)

        def run(action):
            return lambda: getattr(self.loop, action)()
        return {
            'File': [('Exit', 'Ctrl+Q', '<Control-q>', self.exit)],
            'View': [('Reset', 'space', '<KeyPress-space>', self.reset_view), None,
                     ('Data', 'd', '<KeyPress-d>', view('data')),
                     ('Grid', 'g', '<KeyPress-g>', view('grid')),
                     ('Clock', 'c', '<KeyPress-c>', view('clock')),
                     ('Trails', 'Ctrl+F', '<Control-f>', view('trails'))],
            'Run': [('Pause', 'p', '<KeyPress-p>', self.toggle_pause),
                    ('One step', '.', '<KeyPress-period>', run('step_once')), None,
                    ('Faster', ']', '<KeyPress-bracketright>', run('faster')),
                    ('Slower', '[', '<KeyPress-bracketleft>', run('slower')), None,
                    ('Realtime', '{', '<KeyPress-braceleft>', run('realtime')),
                    ('Fast', '}', '<KeyPress-braceright>', run('flat_out'))],
            'Help': [('About stageros...', '', None, self.about)],
        }

    def _menus(self, tkinter):
        """File, View, Run and Help as Stage has them (a bar inside the window, as FLTK's),
        each command on its key too."""
        bar = tkinter.Frame(self.root, borderwidth=1, relief='raised')
        bar.pack(side='top', fill='x')
        for title, items in self._commands().items():
            button = tkinter.Menubutton(bar, text=title, underline=0)
            menu = tkinter.Menu(button, tearoff=False)
            for item in items:
                if item is None:
                    menu.add_separator()
                    continue
                label, key, event, action = item
                menu.add_command(label=label, accelerator=key, command=action)
                if event:
                    self.root.bind(event, lambda _e, a=action: a())
            button['menu'] = menu
            button.pack(side='left')

    def _bind(self):
        """The mouse: drag to pan, the wheel to zoom; the canvas's size follows the window."""
        canvas = self.canvas
        canvas.bind('<ButtonPress-1>', self._press)
        canvas.bind('<B1-Motion>', self._motion)
        canvas.bind('<ButtonRelease-1>', lambda _e: setattr(self, '_drag', None))
        canvas.bind('<Button-4>', lambda e: self.zoom(1, e.x, e.y))     # X11's wheel
        canvas.bind('<Button-5>', lambda e: self.zoom(-1, e.x, e.y))
        canvas.bind('<MouseWheel>', lambda e: self.zoom(1 if e.delta > 0 else -1, e.x, e.y))
        canvas.bind('<Configure>', lambda e: self.resize(e.width, e.height))

    # what the user does
    def toggle_pause(self):
        self.loop.pause(not self.loop.paused)

    def toggle(self, option):
        self.options = replace(self.options, **{option: not getattr(self.options, option)})

    def reset_view(self):
        self.camera = self.home.resized(*self.camera.size_px)

    def zoom(self, notches, x, y):
        self.camera = self.camera.zoomed(notches, (x, y))

    def resize(self, width, height):
        if (width, height) != self.camera.size_px:
            self.camera = self.camera.resized(width, height)

    def _press(self, event):
        self.canvas.focus_set()
        self._drag = (event.x, event.y)

    def _motion(self, event):
        if self._drag is not None:
            dx, dy = event.x - self._drag[0], event.y - self._drag[1]
            self.camera = self.camera.panned(dx, dy)
            self._drag = (event.x, event.y)

    def about(self):
        from tkinter import messagebox
        messagebox.showinfo('About stageros', 'stageros (stage_lite): Stage 4.3 and '
                            'stage_ros 1.8.0 in Python, for the course.', parent=self.root)

    def close(self):
        """The window's close button: the window goes, the simulation runs on."""
        rospy.loginfo('stageros: window closed; the simulation runs on without it '
                      '(Ctrl-C, or File -> Exit in the window, ends stageros)')
        self.root.quit()

    def exit(self):
        """File -> Exit: stageros ends, as Stage does."""
        rospy.loginfo('stageros: user exited via File -> Exit')
        rospy.signal_shutdown('File -> Exit in the window')
        self.root.quit()

    # drawing
    def frame(self):
        """The picture to show now, or None when nothing changed since the last one."""
        step, robots, status = self.snapshot()
        state = (step, self.camera, self.options, status)
        if state == self._drawn:
            return None
        self._drawn = state
        base = self.view.floor(self.camera, self.options.grid)
        return picture.render(self.camera, base, robots, self.options, status)

    def refresh(self):
        if rospy.is_shutdown():
            self.root.quit()
            return
        now = time.monotonic()
        drawn_step = self._drawn[0] if self._drawn else None
        stepped = self.steps() != drawn_step and now - self._frame_at >= FRAME_MIN_S
        drawn = False
        if stepped or now - self._checked_at >= CHECK_S:
            self._checked_at = now
            image = self.frame()
            if image is not None:
                self._show(image)
                self._frame_at = now
                drawn = True
        # Just after a frame the next one cannot be due before FRAME_MIN_S: look again then.
        self.root.tk.call('after', REST_MS if drawn else POLL_MS, self._poll)

    def _show(self, image):
        from PIL import ImageTk
        if self._photo is None or (self._photo.width(), self._photo.height()) != image.size:
            self._photo = ImageTk.PhotoImage(image)
            if self._image_item is None:
                self._image_item = self.canvas.create_image(0, 0, anchor='nw',
                                                            image=self._photo)
            else:
                self.canvas.itemconfigure(self._image_item, image=self._photo)
        else:
            self._photo.paste(image)


def run_window(world, view, snapshot, loop, steps):
    """Show the window until ROS shuts down, File -> Exit or the window is closed; False if
    none could be opened. world: the World (its path); view: its WorldView; snapshot():
    (steps, robots' views, status line) under the node's lock; loop: the StepLoop; steps():
    the steps so far (read without the lock)."""
    root = open_root('stageros: no display (DISPLAY is not set): running without a window '
                     '(use -g to ask for that)',
                     'stageros: the window could not be opened (%s): running without one')
    if root is None:
        return False
    window = StageWindow(root, world, view, snapshot, loop, steps)
    root.after(0, window.refresh)
    try:
        root.mainloop()
    finally:
        with contextlib.suppress(Exception):
            root.destroy()
    return True
