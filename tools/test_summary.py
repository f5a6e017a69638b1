#!/usr/bin/python3
"""Count every test of a ./ws test run from its JUnit XML and print one closing line.

pytest leaves one JUnit file. rostest leaves, per .test file, one rosunit-<test>.xml per <test>
node (the real test cases) and a rostest-*.xml that wraps each <test> node in a single case,
failing only when the node itself failed (crashed, timed out, wrote no results). So a .test
file counts its rosunit cases, plus the wrapper's failures. Anything expected but missing, and
a failed non-test step (lint), count as failures, so a broken run can never look green.
The closing line names the system it ran on (from /etc/os-release), so a CI log says which.
Each failure is printed with the end of its message just above that line, so the tail of a log
(often all a CI page keeps) says why a test failed, not only which.
"""
import argparse
import pathlib
import shlex
import sys
import xml.etree.ElementTree as ET

WHY_LINES = 6  # the end of a failure's message: the assertion and its text, not the stack

class Tally:
    """Passed/failed/skipped counts and the names of what failed."""

    def __init__(self):
        self.passed = self.failed = self.skipped = 0
        self.problems = []
        self.skip_reasons = {}  # (label, reason) -> count, printed so a skip is never silent

    def counts(self):
        return self.passed, self.failed, self.skipped

    def add_file(self, path, label, failures_only=False):
        """Count the test cases of one JUnit file; with failures_only, count only failed cases."""
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as err:
            self.fail('%s: unreadable result file (%s)' % (label, err))
            return
        for case in root.iter('testcase'):
            failure = case.find('failure')
            failure = case.find('error') if failure is None else failure
            if failure is not None:
                self.fail('%s: %s.%s' % (label, case.get('classname', ''), case.get('name', '')),
                          failure_text(failure))
            elif failures_only:
                continue
            elif case.find('skipped') is not None:
                self.skipped += 1
                key = (label, case.find('skipped').get('message', '') or 'no reason given')
                self.skip_reasons[key] = self.skip_reasons.get(key, 0) + 1
            else:
                self.passed += 1

    def fail(self, problem, why=''):
        self.failed += 1
        self.problems.append((problem, why))


def failure_text(element):
    """The end of a JUnit failure or error as Python prints one: the last frame, then the
    exception and its message, WHY_LINES lines at most. pytest's report ends with its message
    already; rosunit writes the message first and the stack after it (and no message
    attribute), so there the message is moved below the stack's last frame."""
    text = '\n'.join(part for part in (element.get('message', ''), element.text or '') if part)
    lines = [line.rstrip() for line in text.splitlines() if line.strip()]
    frames = [i for i, line in enumerate(lines) if line.lstrip().startswith('File "')]
    if (element.get('message') is None and frames and frames[0] > 0
            and not lines[0].startswith('Traceback')):
        message = lines[:frames[0]]
        message[0] = '%s: %s' % (element.get('type', 'Error'), message[0])
        message = message[-WHY_LINES:]
        last_frame = lines[frames[-1]:][:WHY_LINES - len(message)]
        lines = last_frame + message
    return '\n'.join(lines[-WHY_LINES:])


def count_rostest_dir(tally, directory, label):
    """Count one .test file's results."""
    unit_files = sorted(directory.rglob('rosunit-*.xml'))
    for path in unit_files:
        tally.add_file(path, label)
    failed_before_wrapper = tally.failed
    for path in sorted(directory.rglob('rostest-*.xml')):
        tally.add_file(path, label, failures_only=True)
    if not unit_files and tally.failed == failed_before_wrapper:
        # Nothing reported at all, not even rostest's own failure (a hung or killed launch).
        tally.fail('%s: no test results (see %s)' % (label, directory / 'rostest.log'))


def system_name(path=pathlib.Path('/etc/os-release')):
    """'Debian 13 trixie': the first word of os-release's NAME, VERSION_ID, VERSION_CODENAME
    (those it has: Debian testing has no VERSION_ID); 'unknown system' without the file."""
    try:
        text = path.read_text(encoding='utf-8')
    except OSError:
        return 'unknown system'
    fields = dict(line.split('=', 1) for line in shlex.split(text, comments=True) if '=' in line)
    parts = [fields.get('NAME', '').split(' ')[0], fields.get('VERSION_ID', ''),
             fields.get('VERSION_CODENAME', '')]
    return ' '.join(p for p in parts if p) or 'unknown system'


def report(label, before, after):
    """One line per result source: what it added to the tally."""
    passed, failed, skipped = (now - then for now, then in zip(after, before, strict=True))
    print('  %-50s %3d passed, %d failed%s'
          % (label, passed, failed, ', %d skipped' % skipped if skipped else ''))


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('--junit', action='append', default=[], type=pathlib.Path,
                        help='a JUnit file that must exist (pytest)')
    parser.add_argument('--rostest', action='append', default=[], type=pathlib.Path,
                        help="one .test file's results directory")
    parser.add_argument('--failed-step', action='append', default=[],
                        help='a non-test step that failed (counts as one failure)')
    args = parser.parse_args()

    tally = Tally()
    for path in args.junit:
        before = tally.counts()
        if path.is_file():
            tally.add_file(path, path.name)
        else:
            tally.fail('%s: no result file' % path)
        report(path.name, before, tally.counts())
    for directory in args.rostest:
        label = '/'.join(directory.parts[-2:])
        before = tally.counts()
        count_rostest_dir(tally, directory, label)
        report(label, before, tally.counts())
    for step in args.failed_step:
        tally.fail('step %s failed' % step)

    for (label, reason), count in sorted(tally.skip_reasons.items()):
        print('SKIPPED %s: %d test%s: %s' % (label, count, '' if count == 1 else 's', reason))
    for problem, why in tally.problems:
        print('FAILED ' + problem)
        for line in why.splitlines():
            print('    ' + line)
    if tally.passed + tally.failed == 0:
        tally.fail('no test ran')
        print('FAILED no test ran')
    line = '%d passed, %d failed' % (tally.passed, tally.failed)
    line += ', %d skipped' % tally.skipped if tally.skipped else ''
    print('%s (%s)' % (line, system_name()))
    return 1 if tally.failed else 0


if __name__ == '__main__':
    sys.exit(main())
