"""fasr2's A* planner (controllers/_astar.py) against Stage's own: every path Stage 4.3.0's
examples/ctrl/astar found on the grids of ../golden/data/astar_paths.txt (printed by
../golden/astar/astar_harness.cc built against it), cell for cell: ties broken as its heap
breaks them, blocked goals, blocked starts, start == goal, unreachable goals."""
import os

import pytest
from stage_lite.controllers._astar import BLOCKED, astar

GOLDEN = os.path.join(os.path.dirname(__file__), '..', 'golden', 'data', 'astar_paths.txt')


def golden_plans():
    """(grid name, costs, width, height, start, goal, path) of every plan in the file; the
    comment lines come before the first grid (a grid row may start with '#')."""
    plans = []
    grids = 0
    rows = costs = None
    with open(GOLDEN) as f:
        for line in f:
            line = line.rstrip('\n')
            if line.startswith('grid '):
                _, width, height = line.split()
                width, height = int(width), int(height)
                rows, costs, grids = [], None, grids + 1
            elif line.startswith('plan '):
                if costs is None:
                    assert len(rows) == height and all(len(r) == width for r in rows)
                    costs = [BLOCKED if c == '#' else 1 for r in rows for c in r]
                head, tail = line.split(':')
                sx, sy, gx, gy = map(int, head.split()[1:])
                path = [] if tail.strip() == 'none' else [
                    tuple(map(int, p.split(','))) for p in tail.split()]
                plans.append(('grid %d' % grids, costs, width, height, (sx, sy), (gx, gy), path))
            elif rows is not None and line:
                rows.append(line)
    return plans


PLANS = golden_plans()


def test_the_golden_file_has_every_kind_of_case():
    paths = [p[-1] for p in PLANS]
    assert len(PLANS) > 100
    assert sum(1 for p in paths if not p) > 5                  # unreachable or blocked goals
    assert any(p[4] == p[5] and p[-1] == [p[4]] for p in PLANS)     # start == goal
    # a start on a wall, left all the same
    assert any(p[1][p[4][1] * p[2] + p[4][0]] == BLOCKED and p[-1] for p in PLANS)


@pytest.mark.parametrize('name, costs, width, height, start, goal, path', PLANS,
                         ids=['%s %s->%s' % (p[0], p[4], p[5]) for p in PLANS])
def test_paths_equal_stages_own_astar(name, costs, width, height, start, goal, path):
    assert astar(costs, width, height, start, goal) == path


def test_a_grid_of_the_wrong_size_is_refused():
    with pytest.raises(ValueError, match='a 3 x 3 cost grid needs 9 cells, got 8'):
        astar([1] * 8, 3, 3, (0, 0), (2, 2))
