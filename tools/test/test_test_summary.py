"""The closing summary of ./ws test: what it counts, and why a failure failed."""
import pathlib
import subprocess
import sys

SUMMARY = pathlib.Path(__file__).resolve().parents[1] / 'test_summary.py'

FAILED_RUN = '''<?xml version="1.0" encoding="utf-8"?>
<testsuite name="graph_gui" tests="2" failures="1" errors="0">
  <testcase classname="__main__.TestGraphGui" name="test_window_follows_the_graph">
    <failure type="AssertionError"><![CDATA[
Traceback (most recent call last):
  File "test_graph_gui_node.py", line 51, in test_window_follows_the_graph
    self.wait_line('rqt_graph: showing 3 nodes, 1 topic')
  File "course_common/testing/waiting.py", line 20, in wait_for
    raise WaitTimeout(message)
WaitTimeout: "rqt_graph: showing 3 nodes" (x1) from the window; output so far:
rqt_graph: showing 2 nodes, 1 topic
    ]]></failure>
  </testcase>
  <testcase classname="__main__.TestGraphGui" name="test_other"/>
</testsuite>
'''


def summarise(tmp_path, xml_text):
    path = tmp_path / 'rosunit-graph_gui.xml'
    path.write_text(xml_text)
    out = subprocess.run([sys.executable, str(SUMMARY), '--junit', str(path)],
                         capture_output=True, text=True, check=False)
    return out.returncode, out.stdout.splitlines()


def test_a_failure_is_printed_with_the_end_of_its_message_above_the_closing_line(tmp_path):
    code, lines = summarise(tmp_path, FAILED_RUN)
    assert code == 1
    start = lines.index('FAILED rosunit-graph_gui.xml: '
                        '__main__.TestGraphGui.test_window_follows_the_graph')
    why = lines[start + 1:-1]
    assert why[-2:] == ['    WaitTimeout: "rqt_graph: showing 3 nodes" (x1) from the window; '
                        'output so far:', '    rqt_graph: showing 2 nodes, 1 topic']
    assert len(why) == 6  # the end of the message, not the whole stack
    assert lines[-1].startswith('1 passed, 1 failed (')


def test_a_green_run_prints_no_failure(tmp_path):
    code, lines = summarise(tmp_path, FAILED_RUN.replace(
        'failures="1"', 'failures="0"').split('<failure')[0]
        + '</testcase>\n</testsuite>\n')
    assert code == 0
    assert not [line for line in lines if line.startswith('FAILED')]
    assert lines[-1].startswith('1 passed, 0 failed (')
