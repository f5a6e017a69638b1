"""The workspace's package graph, read from every package.xml and every Python file (no rospy).

- The neutral packages are leaves: course_common (shared code) and course_msgs (the types more
  than one package speaks) depend on no package of the workspace (course_pytest, CMake only,
  aside), so every package can depend on them.
- No dependency cycle but the interface/implementation pairs (turtlesim and turtle_lite,
  stage_ros and stage_lite), and each side of a pair says why in a comment above the line.
- No lesson imports a simulator's Python, its generated types included: lessons use the
  interface (its executables, messages and services), course_msgs for the simulators' shared
  extensions (SaveImage), and course_common.
"""
import ast
import glob
import os
import re
import xml.etree.ElementTree as ET

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.normpath(os.path.join(HERE, '..', '..', '..'))  # the workspace's src/
PAIRS = ({'turtlesim', 'turtle_lite'}, {'stage_ros', 'stage_lite'})
SIMULATORS = {'turtle_lite', 'stage_lite'}
NEUTRAL = {'course_common', 'course_msgs', 'course_pytest'}
CMAKE_ONLY = {'course_pytest'}


def manifests():
    """{package name: (path of its package.xml, [(tag, depended-on name)])}."""
    found = {}
    for path in glob.glob(os.path.join(SRC, '**', 'package.xml'), recursive=True):
        root = ET.parse(path).getroot()
        found[root.findtext('name')] = (path, [(e.tag, e.text) for e in root
                                               if e.tag.endswith('depend')])
    return found


MANIFESTS = manifests()


def workspace_deps(name):
    return {dep for _, dep in MANIFESTS[name][1] if dep in MANIFESTS}


def cycles():
    """Every pair of packages that reach each other through dependencies."""
    reach = {}
    for start in MANIFESTS:
        seen, todo = set(), [start]
        while todo:
            for dep in workspace_deps(todo.pop()):
                if dep not in seen:
                    seen.add(dep)
                    todo.append(dep)
        reach[start] = seen
    return {frozenset((a, b)) for a in MANIFESTS for b in reach[a] if a != b and a in reach[b]}


def test_the_workspace_is_found():
    assert {'course_common', 'course_msgs', 'turtlesim', 'turtle_lite', 'stage_ros',
            'stage_lite', 'multi_sync', 'convoy'} <= set(MANIFESTS)


def test_neutral_packages_depend_on_no_workspace_package():
    assert {name: workspace_deps(name) - CMAKE_ONLY for name in NEUTRAL} == \
        {name: set() for name in NEUTRAL}


def test_the_only_cycles_are_interface_and_implementation():
    assert cycles() <= {frozenset(p) for p in PAIRS}


@pytest.mark.parametrize('package, other', [(a, b) for p in PAIRS for a, b in (sorted(p),
                                                                                sorted(p)[::-1])])
def test_each_pair_says_why_in_both_manifests(package, other):
    with open(MANIFESTS[package][0]) as f:
        text = f.read()
    # a comment, then (possibly) more depend lines, then the depend on the other side
    assert re.search(r'-->\s*\n\s*<(\w+_)?depend>%s</' % re.escape(other), text), \
        '%s: no comment above its dependency on %s' % (package, other)


def imported_modules(path):
    with open(path) as f:
        tree = ast.parse(f.read(), path)
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield from (a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
            yield node.module


def lesson_python_files():
    for name, (manifest, _) in MANIFESTS.items():
        if name in SIMULATORS | NEUTRAL or any(name in p for p in PAIRS):
            continue
        folder = os.path.dirname(manifest)
        for path in glob.glob(os.path.join(folder, '**', '*.py'), recursive=True):
            yield name, path
        for path in glob.glob(os.path.join(folder, 'scripts', '*')):
            with open(path, 'rb') as f:
                if b'python' in f.readline():
                    yield name, path


def test_no_lesson_imports_a_simulators_python():
    found = []
    for package, path in lesson_python_files():
        for module in imported_modules(path):
            if module.partition('.')[0] in SIMULATORS:
                found.append('%s: %s imports %s' % (package, os.path.relpath(path, SRC), module))
    assert found == []
