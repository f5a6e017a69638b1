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


# A rostest node's failure as rosunit's own XML writer records it: the message first, then
# the stack without the exception's line.
ROSUNIT_CASE = '''
import io, sys, unittest
from rosunit.xmlrunner import XMLTestRunner

def wait_for(what):
    raise AssertionError('timed out after 180.0 s waiting for ' + what)

class StageViewsTest(unittest.TestCase):
    def test_view(self):
        try:
            wait_for('rviz showing the scans')
        except AssertionError as err:
            raise AssertionError('%s; not shown: %s' % (err, ['robot_1 (red)'])) from None

stream = io.StringIO()
XMLTestRunner(stream).run(unittest.defaultTestLoader.loadTestsFromTestCase(StageViewsTest))
with open(sys.argv[1], 'w') as xml_file:  # stdout has rosunit's text report
    xml_file.write(stream.getvalue())
'''


def test_a_rosunit_failure_ends_with_its_message_below_its_last_frame(tmp_path):
    written = tmp_path / 'written.xml'
    subprocess.run(['/usr/bin/python3', '-c', ROSUNIT_CASE, str(written)], capture_output=True,
                   check=True)
    xml_text = written.read_text()
    code, lines = summarise(tmp_path, xml_text)
    assert code == 1
    start = lines.index('FAILED rosunit-graph_gui.xml: __main__.StageViewsTest.test_view')
    why = lines[start + 1:-1]
    assert why[-1] == ('    AssertionError: timed out after 180.0 s waiting for rviz showing '
                       "the scans; not shown: ['robot_1 (red)']")
    assert why[0].lstrip().startswith('File "<string>", line ')  # the frame that raised
    assert 'in test_view' in why[0]
    assert lines[-1].startswith('0 passed, 1 failed (')


def test_a_green_run_prints_no_failure(tmp_path):
    code, lines = summarise(tmp_path, FAILED_RUN.replace(
        'failures="1"', 'failures="0"').split('<failure')[0]
        + '</testcase>\n</testsuite>\n')
    assert code == 0
    assert not [line for line in lines if line.startswith('FAILED')]
    assert lines[-1].startswith('1 passed, 0 failed (')
