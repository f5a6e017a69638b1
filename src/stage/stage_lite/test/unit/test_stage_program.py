"""Stage's own program, `stage [-g] [-c] [-a ARGS] WORLD`, run as a user runs it (no ROS)."""
import os
import signal

import pytest
from course_common.processes import run_to_exit, spawn
from course_common.testing import wait_for
from course_common.waiting import WaitError
from stage_lite.node.stage_program import by_ctrl_c, clock_line

RUN_DEADLINE_S = 60.0
WORLD = '''resolution 0.02
interval_sim 100
%s
define laser ranger ( sensor( range [ 0 8 ] fov 180 samples 37 ) )
model( pose [ 0 0 0 0 ] size [ 6 6 0.5 ] boundary 1 noblocks 1 )
position( name "r" pose [ -1 0 0 0 ] size [ 0.4 0.4 0.3 ] laser( ) ctrl "%s" )
'''
ARGS_CONTROLLER = '''
def init(model, args):
    with open(%r, 'w') as f:
        f.write(args.worldfile + '|' + args.cmdline)
'''


def world(tmp_path, top='quit_time 5', ctrl='wander'):
    path = tmp_path / 'w.world'
    path.write_text(WORLD % (top, ctrl))
    return str(path)


def stage(*args, env=None):
    return run_to_exit(['stage', *args], RUN_DEADLINE_S, env=env)


def test_clock_line_is_stages():
    assert clock_line(0) == ' 0m 00s 000msec'
    assert clock_line(61_500_000) == ' 1m 01s 500msec'
    assert clock_line(3_723_004_000) == '1h 2m 03s 004msec'


def test_headless_with_the_clock_runs_to_quit_time(tmp_path):
    code, out = stage('-g', '-c', world(tmp_path, 'quit_time 25\nshow_clock_interval 100'))
    assert code == 0, out
    assert out.startswith('Stage 4.3.0 (stage_lite) [Clock enabled][GUI disabled]')
    assert out.rstrip().endswith('[Stage: done]')
    # printed before the steps 0, 100 and 200 (sim time 0, 10 and 20 s), rewritten in place
    assert out.count('\r[Stage:') == 3
    assert '\r[Stage:  0m 20s 000msec]' in out and 'Traceback' not in out


def test_a_paused_world_runs_headless_as_stage_does_and_args_reach_the_controllers(
        tmp_path, monkeypatch):
    got = tmp_path / 'args.txt'
    (tmp_path / 'echo_args.py').write_text(ARGS_CONTROLLER % str(got))
    monkeypatch.setenv('STAGEPATH', str(tmp_path))
    code, out = stage('-g', '-a', 'fast quiet', world(tmp_path, 'paused 1\nquit_time 1',
                                                       'echo_args one two'))
    assert code == 0, out
    assert got.read_text() == 'echo_args one two|fast quiet'



POLICY_CONTROLLER = '''
import os


def init(model, args):
    with open(%r, 'w') as f:
        f.write(os.environ.get('OMP_WAIT_POLICY', 'unset'))
'''


def test_headless_flat_out_its_kernel_threads_sleep_between_kernels_unless_told(
        tmp_path, monkeypatch):
    # OpenMP's default spin took a core from the moves' second thread (jit.py says why)
    got = tmp_path / 'policy.txt'
    (tmp_path / 'policy.py').write_text(POLICY_CONTROLLER % str(got))
    monkeypatch.setenv('STAGEPATH', str(tmp_path))
    path = world(tmp_path, 'quit_time 1', 'policy')
    assert stage('-g', path, env={'OMP_WAIT_POLICY': None})[0] == 0   # (None: not set)
    assert got.read_text() == 'PASSIVE'
    assert stage('-g', path, env={'OMP_WAIT_POLICY': 'ACTIVE'})[0] == 0
    assert got.read_text() == 'ACTIVE'       # the user's
    # stageros and anything else importing the model: asleep when idle too
    code, out = run_to_exit(['python3', '-c', 'import os, stage_lite.model.jit; '
                             'print(os.environ["OMP_WAIT_POLICY"])'], RUN_DEADLINE_S,
                            env={'OMP_WAIT_POLICY': None})
    assert code == 0 and out.strip() == 'PASSIVE'


@pytest.mark.parametrize('args, code, what', [
    ([], 2, 'usage: stage [-g] [-c] [-a ARGS] WORLD'),
    (['-g', '/nonexistent.world'], 1, '[FATAL] /nonexistent.world: the world file does not'),
    (['-g', '--speed', 'x.world'], 2, 'unrecognized arguments: --speed'),
])
def test_wrong_command_lines(args, code, what):
    got, out = stage(*args)
    assert got == code and what in out and 'Traceback' not in out, out


def test_a_world_stage_refuses_is_one_fatal_line(tmp_path):
    path = world(tmp_path, ctrl='no_such')
    code, out = stage('-g', path)
    assert code == 1 and 'Traceback' not in out, out
    fatal = [line for line in out.splitlines() if '[FATAL]' in line]
    assert len(fatal) == 1 and fatal[0].startswith('[FATAL] %s:6: ctrl "no_such"' % path)


def test_ctrl_c_ends_it_at_once_without_a_traceback(tmp_path):
    # faulthandler: if it ever outlives Ctrl-C, SIGABRT makes it print where each thread is
    proc = spawn(['stage', '-g', '-c', world(tmp_path, 'quit_time 0\nshow_clock_interval 10')],
                 env={'PYTHONFAULTHANDLER': '1'})
    try:
        wait_for(lambda: proc.output().count('\r[Stage:') >= 2, RUN_DEADLINE_S,
                 'stage stepping; output:\n%s' % proc.output(), alive=proc.alive)
        proc.interrupt()
        try:
            code = proc.wait_exit(RUN_DEADLINE_S)
        except WaitError:
            os.kill(proc.pid, signal.SIGABRT)
            proc.wait_exit(RUN_DEADLINE_S)
            raise AssertionError('still running %.0f s after Ctrl-C; where it was:\n%s'
                                 % (RUN_DEADLINE_S, proc.output()[-4000:])) from None
        assert code == 130
    finally:
        proc.stop()
    assert '[Stage: interrupted]' in proc.output() and 'Traceback' not in proc.output()


def test_with_its_window_it_runs_at_the_worlds_speedup_and_ends_at_quit_time(tmp_path):
    from course_common.xvfb import Xvfb
    with Xvfb() as xvfb:
        code, out = stage(world(tmp_path, 'quit_time 2\nspeedup 4'), env={'DISPLAY': xvfb.display})
    assert code == 0, out
    assert out.startswith('Stage 4.3.0 (stage_lite) \n') and 'GUI disabled' not in out
    assert 'running without' not in out, out      # the window opened on the display
    assert out.rstrip().endswith('[Stage: done]') and 'Traceback' not in out


def test_ctrl_c_surfacing_inside_a_kernel_s_call_is_still_ctrl_c():
    """A kernel that returns arrays calls back into Python to box them (numba's
    _numba_unpickle); Ctrl-C there surfaces as a SystemError of the kernel's call, caused by
    one of the callback, caused by the KeyboardInterrupt: still Ctrl-C (exit 130), and other
    errors are not."""
    def kernel_call():
        try:
            try:
                raise KeyboardInterrupt
            except KeyboardInterrupt as interrupt:
                raise SystemError('_numba_unpickle returned a result with an exception set'
                                  ) from interrupt
        except SystemError as boxing:
            raise SystemError('CPUDispatcher returned a result with an exception set'
                              ) from boxing
    with pytest.raises(SystemError) as caught:
        kernel_call()
    assert by_ctrl_c(caught.value) and by_ctrl_c(KeyboardInterrupt())
    assert not by_ctrl_c(SystemError('a kernel failed')) and not by_ctrl_c(ValueError())
