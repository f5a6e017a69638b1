// Plans with Stage's own A* (examples/ctrl/astar/: findpath.cpp, stlastar.h, built beside this
// file, never copied here) on a few grids and prints each grid and its paths: the golden data
// of stage_lite's planner (../data/astar_paths.txt, replayed by test_stage_astar.py).
// A=STAGE_SRC/examples/ctrl/astar; g++ -O2 -std=c++11 -I$A astar_harness.cc $A/findpath.cpp
// ./a.out | grep -v "^Search terminated" > astar_paths.txt
#include <cstdio>
#include <cstdint>
#include <vector>
#include <string>
#include "astar.h"

static uint32_t lcg = 12345u;
static uint32_t next_rand() { lcg = lcg * 1103515245u + 12345u; return (lcg >> 8) & 0xffffff; }

struct Grid { unsigned w, h; std::vector<uint8_t> c; };

static void print_grid(const Grid &g) {
  printf("grid %u %u\n", g.w, g.h);
  for (unsigned y = 0; y < g.h; y++) {
    for (unsigned x = 0; x < g.w; x++) putchar(g.c[y * g.w + x] == 9 ? '#' : '.');
    putchar('\n');
  }
}

static void plan(Grid &g, unsigned sx, unsigned sy, unsigned gx, unsigned gy) {
  std::vector<ast::point_t> path;
  fflush(stdout);
  bool ok = ast::astar(g.c.data(), g.w, g.h, ast::point_t(sx, sy), ast::point_t(gx, gy), path);
  fflush(stdout);
  printf("plan %u %u %u %u:", sx, sy, gx, gy);
  if (!ok) printf(" none");
  for (size_t i = 0; i < path.size(); i++) printf(" %u,%u", path[i].x, path[i].y);
  printf("\n");
}

static Grid from_rows(unsigned w, unsigned h, const char *rows) {
  Grid g; g.w = w; g.h = h; g.c.resize(w * h);
  for (unsigned i = 0; i < w * h; i++) g.c[i] = rows[i] == '#' ? 9 : 1;
  return g;
}

int main() {
  Grid open = from_rows(6, 5, "..............................");
  print_grid(open);
  plan(open, 0, 0, 5, 4); plan(open, 5, 4, 0, 0); plan(open, 2, 2, 2, 2);
  plan(open, 0, 4, 5, 0); plan(open, 3, 0, 3, 4); plan(open, 0, 2, 5, 2);
  Grid walls = from_rows(7, 6,
    "......."
    ".#####."
    ".#...#."
    ".#.#.#."
    "...#..."
    "###.###");
  print_grid(walls);
  plan(walls, 0, 0, 2, 2);   // into the pocket
  plan(walls, 2, 2, 6, 0);
  plan(walls, 1, 1, 4, 4);   // start on a wall
  plan(walls, 0, 0, 3, 3);   // goal on a wall
  plan(walls, 0, 0, 3, 5);   // walled-off cell
  plan(walls, 6, 5, 0, 0);   // start walled in (corner reached from outside)
  plan(walls, 0, 4, 6, 4);
  for (int k = 0; k < 24; k++) {
    Grid g; g.w = 4 + next_rand() % 29; g.h = 4 + next_rand() % 29;
    if (k % 6 == 0) { g.w = 32; g.h = 32; }
    unsigned density = 10 + next_rand() % 30;
    g.c.resize(g.w * g.h);
    for (unsigned i = 0; i < g.w * g.h; i++) g.c[i] = (next_rand() % 100) < density ? 9 : 1;
    print_grid(g);
    for (int p = 0; p < 6; p++) {
      unsigned sx = next_rand() % g.w, sy = next_rand() % g.h;
      unsigned gx = next_rand() % g.w, gy = next_rand() % g.h;
      if (p == 5) { gx = sx; gy = sy; }
      plan(g, sx, sy, gx, gy);
    }
  }
  return 0;
}
