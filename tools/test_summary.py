#!/usr/bin/python3
"""Count every test of a ./ws test run from its JUnit XML files and print one closing line.

Unit tests (pytest) and integration tests (rostest) both leave JUnit XML under the results
directory. An expected file that is missing (a test that crashed before reporting) and a failed
non-test step (lint) count as failures, so a broken run can never look green.
"""
import argparse
import pathlib
import sys
import xml.etree.ElementTree as ET


def count_cases(path):
    """Return (passed, failed, skipped, failure descriptions) for one JUnit XML file."""
    passed = failed = skipped = 0
    failures = []
    root = ET.parse(path).getroot()
    for case in root.iter('testcase'):
        name = '%s.%s' % (case.get('classname', ''), case.get('name', ''))
        if case.find('failure') is not None or case.find('error') is not None:
            failed += 1
            failures.append(name)
        elif case.find('skipped') is not None:
            skipped += 1
        else:
            passed += 1
    return passed, failed, skipped, failures


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('results_dir', type=pathlib.Path)
    parser.add_argument('--expect', action='append', default=[],
                        help='a result file (relative to results_dir) that must exist')
    parser.add_argument('--failed-step', action='append', default=[],
                        help='a non-test step that failed (counts as one failure)')
    args = parser.parse_args()

    passed = failed = skipped = 0
    problems = []
    for rel in args.expect:
        path = args.results_dir / rel
        if not path.is_file():
            failed += 1
            problems.append('%s: no result file (the test crashed or never ran)' % rel)
            continue
        try:
            p, f, s, names = count_cases(path)
        except ET.ParseError as err:
            failed += 1
            problems.append('%s: unreadable result file (%s)' % (rel, err))
            continue
        print('  %-60s %3d passed, %d failed%s' % (rel, p, f, ', %d skipped' % s if s else ''))
        passed, failed, skipped = passed + p, failed + f, skipped + s
        problems += ['%s: %s' % (rel, n) for n in names]
    for step in args.failed_step:
        failed += 1
        problems.append('step %s failed' % step)
    for problem in problems:
        print('FAILED ' + problem)
    if passed + failed == 0:
        print('no test ran')
        failed = 1
    line = '%d passed, %d failed' % (passed, failed)
    print(line + (', %d skipped' % skipped if skipped else ''))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
