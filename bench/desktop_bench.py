"""What the desktop in the browser costs: start-up, idle, and the Stage lesson viewed in a page.

    ./ws bench desktop_bench [--runs N] [--window-s S] [--latency-samples N]

`./ws desktop` on a free port with a private master, opened in headless Chromium (the
browser's own CPU is not counted), in turn RUNS times (default 3):
* start: seconds from the command to its URL printed (serving), and to noVNC connected in a
  browser that was already open (a student's);
* idle, the page open and nothing moving, over WINDOW_S: the cores of the desktop's own
  processes (the gateway, Xvnc, openbox, xterm, bash) and their memory (PSS, MB);
* the lesson at real time, typed in the page as a student does (`roslaunch multi_sync
  multi_sync.launch`, then `rosrun multi_sync monitor 4` in a second terminal), over
  WINDOW_S: the cores of Stage, Xvnc, the gateway, openbox and the terminals together (the
  robots' nodes and the master apart); the pictures a second that reach the page (the page
  samples Stage's status line on every animation frame) against those Stage drew on the X
  display (sampled there every 2 ms); the bytes a second on the WebSocket (the kernel's
  bytes_sent of the gateway's connections, from ss);
* latency, Stage paused: one step (Stage's `.` key, sent with xdotool) at a time, LATENCY
  samples: from /clock advancing (the simulation changed) to the page's status line changing.
Medians of the runs; prints a markdown table.
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time

import multi_sync_bench  # bench/ is on sys.path: ./ws bench runs the files from there
from course_common.ports import free_port
from course_common.processes import ChildProcess, descendants, process_table
from course_common.waiting import WaitError, wait_for
from course_desktop.testing import Browser, LocalDesktop, colour_spot

RUNS = 3
WINDOW_S = 20.0
LATENCY_SAMPLES = 20
DESKTOP_PARTS = ('desktop', 'Xvnc', 'openbox', 'xterm', 'bash')
LESSON_VIEW = ('stageros', 'desktop', 'Xvnc', 'openbox', 'xterm')
X_SAMPLE_S = 0.002
WARM_PAGE = 'data:text/html,<title>a browser already open</title>'
STAGE_TITLE = 'willow-multi-erratic.world'
CLOCK_BOX_RGB = (204, 204, 255)  # Stage's status box (stage_lite.view.world_picture)
DISPLAY_LINE = re.compile(r'DISPLAY=(\S+) XAUTHORITY=(\S+)')
#: Page-side sampler: a cheap hash of the status strip on every animation frame; the wall
#: times (ms) at which it changed.
SAMPLER_JS = '''
const [x, y, w, h] = arguments;
const canvas = document.querySelector('canvas');
const ctx = canvas.getContext('2d');
window.__changes = [];
let last = null;
function tick() {
  const d = ctx.getImageData(x, y, w, h).data;
  let sum = 0;
  for (let i = 0; i < d.length; i += 4) sum = (sum * 31 + d[i] + 7 * d[i + 1] + 13 * d[i + 2]) | 0;
  if (sum !== last) { window.__changes.push(Date.now()); last = sum; }
  requestAnimationFrame(tick);
}
requestAnimationFrame(tick);
'''


def named(pid_table, root, names):
    """{name: [pids]} of root's tree whose program (argv[0]'s base, or a Python script's)
    is one of names."""
    found = {name: [] for name in names}
    for pid in descendants(root, pid_table):
        argv = pid_table[pid][1].split()
        words = [os.path.basename(a) for a in argv[:2]]
        for name in names:
            if name in words:
                found[name].append(pid)
                break
    return found


def cores_over(groups, window_s):
    """{name: cores} over window_s of each group of pids, and 'total' (multi_sync_bench's
    snapshots: a pid counts if it runs at both ends)."""
    before = multi_sync_bench.cpu_snapshot(groups)
    time.sleep(window_s)
    return multi_sync_bench.cores(groups, before, multi_sync_bench.cpu_snapshot(groups))


def pss_mb(pids):
    total = 0
    for pid in pids:
        try:
            with open('/proc/%d/smaps_rollup' % pid) as f:
                total += sum(int(line.split()[1]) for line in f if line.startswith('Pss:'))
        except OSError:
            pass
    return total / 1024.0


def xdotool(x_env, *args):
    return subprocess.run(('xdotool',) + args, env=x_env, capture_output=True, text=True,
                          timeout=30).stdout.strip()


def one_run(workspace, window_s, latency_samples):
    master_port = free_port()
    env = {'ROS_MASTER_URI': 'http://localhost:%d' % master_port}
    result = {}
    browser = Browser()
    browser.open(WARM_PAGE)  # the student's browser is open already
    t0 = time.monotonic()
    d = LocalDesktop(workspace, env=env).start()
    try:
        url = d.url()
        result['serving_s'] = time.monotonic() - t0
        browser.open(url).wait_connected()
        result['connected_s'] = time.monotonic() - t0
        display, xauthority = DISPLAY_LINE.search(d.output()).groups()
        os.environ['XAUTHORITY'] = xauthority  # for the X-side sampler (PIL's ImageGrab)
        x_env = dict(os.environ, DISPLAY=display, XAUTHORITY=xauthority)

        time.sleep(2.0)  # the first picture settles
        parts = named(process_table(), d.pid(), DESKTOP_PARTS)
        idle = cores_over(parts, window_s)
        result['idle_cores'] = idle['total']
        result['idle_mb'] = pss_mb([p for pids in parts.values() for p in pids])

        browser.type('roslaunch multi_sync multi_sync.launch\n')
        window = wait_for(lambda: xdotool(x_env, 'search', '--onlyvisible', '--name',
                                          STAGE_TITLE), 60, "Stage's window").split()[0]
        browser.open_terminal()
        browser.type('rosrun multi_sync monitor 4\n')
        # Stage's window on top (the second terminal may cover it); its status box, found
        # by its colour in the page, is what both samplers watch.
        xdotool(x_env, 'windowactivate', '--sync', window)
        wait_for(lambda: colour_spot(browser.screenshot(), (255, 0, 0))[0] > 0, 30,
                 'the robots in the page')
        time.sleep(3.0)  # GO is out, the robots drive
        box = wait_for(lambda: colour_box(browser.screenshot(), CLOCK_BOX_RGB), 30,
                       "Stage's status box in the page")
        view = named(process_table(), d.pid(), LESSON_VIEW)
        browser.driver.execute_script(SAMPLER_JS, box[0], box[1], box[2] - box[0],
                                      box[3] - box[1])
        bytes_before, start = bytes_sent(d.port), time.monotonic()
        n_before = page_changes(browser)
        cores = cores_over(view, window_s)
        took = time.monotonic() - start
        result['pictures_per_s'] = (page_changes(browser) - n_before) / took
        result['kb_per_s'] = (bytes_sent(d.port) - bytes_before) / took / 1000.0
        result['view_cores'] = cores.pop('total')
        result['stage_cores'] = cores['stageros']
        print('bench: cores by process: %s'
              % ', '.join('%s %.3f' % kv for kv in cores.items()), flush=True)
        # Then, apart (sampling X costs the X server), what Stage drew against what arrived.
        x_side = XSampler(display, box)
        n_before = page_changes(browser)
        x_side.start()
        time.sleep(window_s)
        x_changes = x_side.stop()
        result['page_share'] = (page_changes(browser) - n_before) / max(x_changes, 1)
        result['x_pictures_per_s'] = x_changes / window_s
        result['latency_ms'] = latency(browser, x_env, window, latency_samples, master_port)
    finally:
        browser.close()
        d.stop()
    return result


class XSampler:
    """Counts the changes of a box of the X display, sampled every SAMPLE_S in a thread:
    what Stage drew there, before VNC."""

    def __init__(self, display, box):
        self.display, self.box = display, box
        self.changes = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self):
        from PIL import ImageGrab
        last = None
        while not self._stop.is_set():
            try:
                now = ImageGrab.grab(bbox=self.box, xdisplay=self.display).tobytes()
            except OSError as err:
                print('bench: cannot sample the X display: %s' % err, flush=True)
                return
            if last is not None and now != last:
                self.changes += 1
            last = now
            time.sleep(X_SAMPLE_S)

    def start(self):
        self._thread.start()

    def stop(self):
        self._stop.set()
        self._thread.join()
        return self.changes


def bytes_sent(port):
    """Bytes the kernel has sent on the established TCP connections from port (ss -ti)."""
    out = subprocess.run(['ss', '-tinH', 'state', 'established', '( sport = :%d )' % port],
                         capture_output=True, text=True, timeout=30).stdout
    return sum(int(n) for n in re.findall(r'bytes_sent:(\d+)', out))


def colour_box(image, rgb, tolerance=6):
    """(left, top, right, bottom) around the pixels of image near rgb, or None."""
    import numpy as np
    near = (np.abs(np.asarray(image, dtype=np.int16) - np.array(rgb)) <= tolerance).all(axis=2)
    ys, xs = np.nonzero(near)
    if len(xs) < 100:
        return None
    return int(xs.min()), int(ys.min()), int(xs.max()) + 1, int(ys.max()) + 1


def page_changes(browser):
    return browser.driver.execute_script('return window.__changes.length')


#: A separate process (each run has a master of its own; rospy joins only one per process)
#: that prints the wall time, in ms, at which each /clock message arrives.
CLOCK_PRINTER = '''
import time, rospy
from rosgraph_msgs.msg import Clock
rospy.init_node('desktop_bench_clock', anonymous=True)
rospy.Subscriber('/clock', Clock, lambda _: print('%.3f' % (time.time() * 1000.0), flush=True))
rospy.spin()
'''


def latency(browser, x_env, window, samples, master_port):
    """Median ms from /clock advancing after one step to the page's status line changing."""
    clock = ChildProcess([sys.executable, '-c', CLOCK_PRINTER],
                         env={'ROS_MASTER_URI': 'http://localhost:%d' % master_port}).start()
    try:
        try:
            wait_for(lambda: len(clock.lines()) > 5, 30, '/clock to reach the bench')
        except WaitError as err:
            raise WaitError('%s; the listener said:\n%s' % (err, clock.tail())) from None
        xdotool(x_env, 'windowactivate', '--sync', window)
        xdotool(x_env, 'key', 'p')  # pause (Stage's key; its window has the keyboard)
        time.sleep(1.0)
        delays = []
        for _ in range(samples):
            ticks, changes = len(clock.lines()), page_changes(browser)
            xdotool(x_env, 'key', 'period')  # one step
            try:
                wait_for(lambda c=changes: page_changes(browser) > c, 5, 'the step in the page')
                wait_for(lambda t=ticks: len(clock.lines()) > t, 5, 'the step on /clock')
            except WaitError:
                continue
            time.sleep(0.3)
            shown = browser.driver.execute_script('return window.__changes')[changes]
            delays.append(shown - float(clock.lines()[ticks]))
        return statistics.median(delays) if delays else float('nan')
    finally:
        clock.stop()


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--runs', type=int, default=RUNS)
    ap.add_argument('--window-s', type=float, default=WINDOW_S)
    ap.add_argument('--latency-samples', type=int, default=LATENCY_SAMPLES)
    args = ap.parse_args(argv)
    runs = []
    for k in range(args.runs):
        print('bench: desktop, run %d of %d' % (k + 1, args.runs), flush=True)
        workspace = tempfile.mkdtemp(prefix='desktop-bench-ws-')
        try:
            runs.append(one_run(workspace, args.window_s, args.latency_samples))
        finally:
            shutil.rmtree(workspace, ignore_errors=True)
        print('bench: %s' % ', '.join('%s %.3f' % kv for kv in sorted(runs[-1].items())),
              flush=True)
    med = {key: statistics.median(r[key] for r in runs) for key in runs[0]}
    print()
    print('| the desktop in the browser (medians of %d runs) | figure |' % args.runs)
    print('|---|---|')
    rows = [('start: command to serving', '%.2f s' % med['serving_s']),
            ('start: command to the page connected (the browser open already)',
             '%.2f s' % med['connected_s']),
            ('idle, the page open: cores (gateway, Xvnc, openbox, xterm, bash)',
             '%.4f' % med['idle_cores']),
            ('idle: memory of those processes (PSS)', '%.0f MB' % med['idle_mb']),
            ('the lesson viewed: cores (Stage, Xvnc, gateway, openbox, terminals)',
             '%.3f' % med['view_cores']),
            ('  of which Stage', '%.3f' % med['stage_cores']),
            ("Stage's pictures reaching the page", '%.1f / s' % med['pictures_per_s']),
            ("  of those Stage drew on the X display (sampled apart)",
             '%.0f %% (of %.1f / s)' % (100 * med['page_share'], med['x_pictures_per_s'])),
            ('WebSocket traffic', '%.0f KB/s' % med['kb_per_s']),
            ('latency: /clock step to the page', '%.0f ms' % med['latency_ms'])]
    for label, value in rows:
        print('| %s | %s |' % (label, value))


if __name__ == '__main__':
    main()
