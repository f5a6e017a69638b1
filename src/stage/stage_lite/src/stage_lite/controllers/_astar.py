"""The grid A* planner Stage's fasr2 plans with (examples/ctrl/astar/: Justin Heyes-Jones's
STL A* search, findpath.cpp's grid), written anew so that it finds the same path: not any
shortest path, but the one its search order leads to. Not a controller itself (no init).

The rules that decide the path:
- a cost grid of width x height cells, row y from the bottom (index y * width + x); a cell
  of cost 9 or more cannot be entered, and any cell outside the grid costs 9;
- moving out of a cell costs that cell's cost (so leaving a blocked start costs 9);
- the heuristic is the Manhattan distance to the goal; g, h and f = g + h are floats
  (float32), compared as such;
- a node's successors come in the order west (x - 1), south (y - 1), east (x + 1), north
  (y + 1), each skipped when it cannot be entered or is the node's parent's cell;
- the open list is a binary heap on f in a vector, kept with the C++ library's (libstdc++)
  push_heap, pop_heap and make_heap: ties in f come off in whatever order those leave them;
- a successor already open (or closed) with g no worse than its own is dropped; otherwise
  the old node leaves its list (erased from the open vector, which is then re-made as a
  heap) and the new one is pushed onto the open heap;
- the search ends when the goal comes off the heap (the start itself when start == goal:
  a path of that one cell), or fails when the heap is empty (no path).
"""
import numpy as np

from stage_lite.model.jit import kernel, njit

BLOCKED = 9      # a cell of this cost or more cannot be entered
NO_PATH = -1


def astar(costs, width, height, start, goal):
    """The path from start to goal (cells (x, y), start first, goal last) over a cost grid
    (width * height costs, row y from the bottom), as Stage's astar() finds it; [] when
    the goal cannot be reached."""
    grid = np.ascontiguousarray(costs, dtype=np.uint8).reshape(-1)
    if grid.shape[0] != width * height:
        raise ValueError('a %d x %d cost grid needs %d cells, got %d'
                         % (width, height, width * height, grid.shape[0]))
    out = np.empty((width * height + 1, 2), np.int64)
    n = _search(grid, width, height, int(start[0]), int(start[1]), int(goal[0]),
                int(goal[1]), out)
    return [] if n == NO_PATH else [(int(x), int(y)) for x, y in out[:n]]


@kernel
def _cost(grid, width, height, x, y):
    if x < 0 or y < 0 or x >= width or y >= height:
        return BLOCKED
    return grid[y * width + x]


@kernel
def _heuristic(x, y, gx, gy):
    return np.float32(abs(np.float32(x) - np.float32(gx))) + \
        np.float32(abs(np.float32(y) - np.float32(gy)))


# libstdc++'s heap algorithms on a vector of node ids, ordered by "a after b" = f[a] > f[b]
@kernel
def _sift_up(heap, f, hole, top, node):
    parent = (hole - 1) // 2
    while hole > top and f[heap[parent]] > f[node]:
        heap[hole] = heap[parent]
        hole = parent
        parent = (hole - 1) // 2
    heap[hole] = node


@kernel
def _adjust(heap, f, hole, length, node):
    top = hole
    child = hole
    while child < (length - 1) // 2:
        child = 2 * (child + 1)
        if f[heap[child]] > f[heap[child - 1]]:
            child -= 1
        heap[hole] = heap[child]
        hole = child
    if length % 2 == 0 and child == (length - 2) // 2:
        child = 2 * (child + 1)
        heap[hole] = heap[child - 1]
        hole = child - 1
    _sift_up(heap, f, hole, top, node)


@kernel
def _pop(heap, f, length):
    """pop_heap: the front moves to the back (length - 1)."""
    if length > 1:
        last = length - 1
        node = heap[last]
        heap[last] = heap[0]
        _adjust(heap, f, 0, last, node)


@kernel
def _make(heap, f, length):
    if length < 2:
        return
    parent = (length - 2) // 2
    while True:
        _adjust(heap, f, parent, length, heap[parent])
        if parent == 0:
            return
        parent -= 1


@njit(cache=True)
def _search(grid, width, height, sx, sy, gx, gy, out):
    cells = width * height
    capacity = 8 * cells + 8
    nx = np.empty(capacity, np.int64)
    ny = np.empty(capacity, np.int64)
    parent = np.empty(capacity, np.int64)
    g = np.empty(capacity, np.float32)
    f = np.empty(capacity, np.float32)
    heap = np.empty(capacity, np.int64)
    # the node of a cell on the open list or the closed list (each holds a cell once)
    open_of = np.full(cells, -1, np.int64)
    closed_of = np.full(cells, -1, np.int64)
    nx[0] = sx
    ny[0] = sy
    parent[0] = -1
    g[0] = np.float32(0.0)
    f[0] = g[0] + _heuristic(sx, sy, gx, gy)
    nodes = 1
    heap[0] = 0
    n_open = 1
    if 0 <= sx < width and 0 <= sy < height:
        open_of[sy * width + sx] = 0
    step_x = (-1, 0, 1, 0)
    step_y = (0, -1, 0, 1)
    while n_open > 0:
        n = heap[0]
        _pop(heap, f, n_open)
        n_open -= 1
        x = nx[n]
        y = ny[n]
        inside = 0 <= x < width and 0 <= y < height
        if inside:
            open_of[y * width + x] = -1
        if x == gx and y == gy:
            length = 0
            k = n
            while k >= 0:
                length += 1
                k = parent[k]
            k = n
            for i in range(length - 1, -1, -1):
                out[i, 0] = nx[k]
                out[i, 1] = ny[k]
                k = parent[k]
            return length
        px = -1
        py = -1
        if parent[n] >= 0:
            px = nx[parent[n]]
            py = ny[parent[n]]
        leave = np.float32(_cost(grid, width, height, x, y))
        for d in range(4):
            sx2 = x + step_x[d]
            sy2 = y + step_y[d]
            if _cost(grid, width, height, sx2, sy2) >= BLOCKED or (sx2 == px and sy2 == py):
                continue
            new_g = np.float32(g[n] + leave)
            cell = sy2 * width + sx2
            on_open = open_of[cell]
            if on_open >= 0 and g[on_open] <= new_g:
                continue
            on_closed = closed_of[cell]
            if on_closed >= 0 and g[on_closed] <= new_g:
                continue
            if nodes == capacity:
                raise RuntimeError('astar: out of nodes')
            k = nodes
            nodes += 1
            nx[k] = sx2
            ny[k] = sy2
            parent[k] = n
            g[k] = new_g
            f[k] = new_g + _heuristic(sx2, sy2, gx, gy)
            if on_closed >= 0:
                closed_of[cell] = -1
            if on_open >= 0:
                at = 0
                while heap[at] != on_open:
                    at += 1
                for i in range(at, n_open - 1):
                    heap[i] = heap[i + 1]
                n_open -= 1
                _make(heap, f, n_open)
            heap[n_open] = k
            n_open += 1
            _sift_up(heap, f, n_open - 1, 0, k)
            open_of[cell] = k
        if inside:
            closed_of[y * width + x] = n
    return NO_PATH
