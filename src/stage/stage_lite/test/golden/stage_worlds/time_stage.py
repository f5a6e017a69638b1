#!/usr/bin/env python3
"""Time real `stage -g` on a world: its speed against real time, cores and peak memory.

usage: time_stage.py STAGE WORLD QUIT_TIME_S [--out JSON]

Writes a copy of WORLD beside it (so includes and bitmaps resolve) with `paused 0` and
`quit_time QUIT_TIME_S`, runs `/usr/bin/time -f ... STAGE -g -c COPY` from the world's
folder, and timestamps Stage's clock lines as they come: the first ("0m 00s", printed by
the first World::Update, after loading) ends the load; "[Stage: done]" the run. It reads
Stage's CPU time from /proc at the end of the load and at "done", so the step phase's cores
are known apart. Prints one JSON line. LD_LIBRARY_PATH must reach libstage.
"""
import argparse
import contextlib
import json
import os
import re
import subprocess
import time

TIME_FORMAT = 'TIME %e %U %S %P %M'
CLK_TCK = os.sysconf('SC_CLK_TCK')


def timed_copy(world, quit_time_s):
    with open(world) as f:
        text = f.read()
    text = re.sub(r'(?m)^(\s*)(quit_time|paused)\b.*$', r'\1# \2 (removed by time_stage.py)', text)
    copy = world[:-len('.world')] + '_timed.world'
    with open(copy, 'w') as f:
        f.write(text + '\npaused 0\nquit_time %g\n' % quit_time_s)
    return copy


def cpu_s(pid):
    """utime + stime (s) of a live process, from /proc/PID/stat."""
    with open('/proc/%d/stat' % pid) as f:
        fields = f.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / CLK_TCK


def child_pid(pid):
    """The one child of pid (stage under /usr/bin/time), waiting for it to appear."""
    for _ in range(200):
        try:
            with open('/proc/%d/task/%d/children' % (pid, pid)) as f:
                kids = f.read().split()
            if kids:
                return int(kids[0])
        except OSError:
            pass
        time.sleep(0.01)
    raise RuntimeError('no child of %d' % pid)


def run(stage, world, quit_time_s):
    copy = timed_copy(world, quit_time_s)
    cmd = ['/usr/bin/time', '-f', TIME_FORMAT, stage, '-g', '-c', os.path.basename(copy)]
    start = time.monotonic()
    proc = subprocess.Popen(cmd, cwd=os.path.dirname(os.path.abspath(copy)),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    pid = child_pid(proc.pid)
    loaded = load_cpu = done = done_cpu = None
    buf = b''
    while True:
        chunk = os.read(proc.stdout.fileno(), 4096)
        if not chunk:
            break
        buf += chunk
        now = time.monotonic()
        if loaded is None and b'[Stage:' in buf:
            loaded = now
            load_cpu = cpu_s(pid)
        if b'[Stage: done]' in buf and done is None:
            done = now
            # before the exit frees the world (11 GB for large.world takes seconds)
            with contextlib.suppress(OSError):
                done_cpu = cpu_s(pid)
    err = proc.stderr.read().decode()
    proc.wait()
    os.remove(copy)
    line = [x for x in err.splitlines() if x.startswith('TIME ')][-1].split()
    elapsed, user, system, _, max_kb = (float(line[1]), float(line[2]), float(line[3]),
                                        line[4], float(line[5]))
    if loaded is None or done is None:
        raise RuntimeError('stage printed no clock or no end: %s' % err[-500:])
    steps_wall = done - loaded
    steps_cpu = (done_cpu if done_cpu is not None else user + system) - load_cpu
    return dict(world=os.path.basename(world), quit_time_s=quit_time_s,
                load_s=round(loaded - start, 2), steps_wall_s=round(steps_wall, 2),
                rtf=round(quit_time_s / steps_wall, 2),
                rtf_with_load=round(quit_time_s / elapsed, 2),
                cores_steps=round(steps_cpu / steps_wall, 2),
                cores_total=round((user + system) / elapsed, 2),
                elapsed_s=elapsed, peak_rss_mb=round(max_kb / 1024, 1))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('stage')
    parser.add_argument('world')
    parser.add_argument('quit_time_s', type=float)
    args = parser.parse_args()
    print(json.dumps(run(args.stage, args.world, args.quit_time_s)), flush=True)


if __name__ == '__main__':
    main()
