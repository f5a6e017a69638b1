// model_dump: a small program linked to the REAL Stage 4.3.0 (built as a peer, never in
// this repository). It loads a world as `stage -g` does, sets drand48 to glibc's unseeded
// state after Stg::Init (which seeds it from the clock), prints every model (token, type,
// parent, local and world pose, geometry, colour; a position model's odometry error) and,
// after each step, every position model's world pose and stall and every updated ranger's
// first sensor's ranges (%.17g). ../make_probe_golden.py keeps them (../README.md).
//   g++ -O2 -std=c++11 $(pkg-config --cflags stage) -I SRC/Stage/libstage -o model_dump \
//       model_dump.cc $(pkg-config --libs stage)
//   model_dump [-n STEPS] [-d "TOKEN VX VY VA"].. [-a "TOKEN AX AY AA"].. -o OUT.txt WORLD
// -d and -a subscribe the robot TOKEN and its rangers (as stageros would) and set its speed
// (SetSpeed) or its acceleration (SetAcceleration).
// The odometry error is private to ModelPosition: the access keywords are opened for this
// one read (a probe only; the class's layout is unchanged).
#define protected public
#define private public
#include "stage.hh"
#undef protected
#undef private
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>
using namespace Stg;

static FILE *out;

static int DumpModel(Model *m, void *) {
  Pose g = m->GetGlobalPose();
  Pose l = m->GetPose();
  Geom geom = m->GetGeom();
  Color c = m->GetColor();
  fprintf(out, "MODEL %s %s parent %s local %.17g %.17g %.17g %.17g global %.17g %.17g %.17g %.17g"
          " geom %.17g %.17g %.17g %.17g size %.17g %.17g %.17g color %.17g %.17g %.17g %.17g\n",
          m->Token(), m->GetModelType().c_str(), m->Parent() ? m->Parent()->Token() : "-",
          l.x, l.y, l.z, l.a, g.x, g.y, g.z, g.a, geom.pose.x, geom.pose.y, geom.pose.z,
          geom.pose.a, geom.size.x, geom.size.y, geom.size.z, c.r, c.g, c.b, c.a);
  ModelPosition *p = dynamic_cast<ModelPosition *>(m);
  if (p)
    fprintf(out, "ERROR %s %.17g %.17g %.17g %.17g\n", m->Token(), p->integration_error.x,
            p->integration_error.y, p->integration_error.z, p->integration_error.a);
  return 0;
}

static int DumpStep(Model *m, void *) {
  ModelPosition *p = dynamic_cast<ModelPosition *>(m);
  if (p) {
    Pose g = p->GetGlobalPose();
    fprintf(out, "POSE %llu %s %.17g %.17g %.17g %d\n",
            (unsigned long long)m->GetWorld()->SimTimeNow(), m->Token(), g.x, g.y, g.a,
            p->Stalled() ? 1 : 0);
  }
  ModelRanger *r = dynamic_cast<ModelRanger *>(m);
  if (r && !r->GetSensors().empty() && !r->GetSensors()[0].ranges.empty()) {
    const std::vector<meters_t> &s = r->GetSensors()[0].ranges;
    fprintf(out, "SCAN %llu %s", (unsigned long long)m->GetWorld()->SimTimeNow(), m->Token());
    for (size_t i = 0; i < s.size(); i++) fprintf(out, " %.17g", s[i]);
    fprintf(out, "\n");
  }
  return 0;
}

int main(int argc, char *argv[]) {
  Stg::Init(&argc, &argv);
  unsigned short zero[3] = {0, 0, 0};
  seed48(zero);  // glibc's drand48 state before any srand48: x = 0
  int steps = 0;
  std::vector<std::pair<char, std::string> > commands;   // 'd' speed, 'a' acceleration
  const char *outpath = NULL, *world_path = NULL;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "-n")) steps = atoi(argv[++i]);
    else if (!strcmp(argv[i], "-d") || !strcmp(argv[i], "-a"))   // "TOKEN X Y A"
      commands.push_back(std::make_pair(argv[i][1], std::string(argv[i + 1]))), ++i;
    else if (!strcmp(argv[i], "-o")) outpath = argv[++i];
    else world_path = argv[i];
  }
  out = fopen(outpath, "w");
  World world("probe");
  world.Load(world_path);
  fflush(stdout);
  world.ForEachDescendant(DumpModel, NULL);
  for (size_t c = 0; c < commands.size(); c++) {
    char token[256];
    double x, y, a;
    sscanf(commands[c].second.c_str(), "%255s %lf %lf %lf", token, &x, &y, &a);
    ModelPosition *p = dynamic_cast<ModelPosition *>(world.GetModel(token));
    p->Subscribe();
    for (int k = 0; k < 16; k++) {
      char name[300];
      snprintf(name, sizeof name, "%s.ranger:%d", token, k);
      Model *r = world.GetModel(name);
      if (r) r->Subscribe();
    }
    if (commands[c].first == 'a')
      p->SetAcceleration(x, y, a);
    else
      p->SetSpeed(x, y, a);
  }
  world.Start();
  world.ForEachDescendant(DumpStep, NULL);
  for (int s = 0; s < steps; s++) {
    world.Update();
    world.ForEachDescendant(DumpStep, NULL);
  }
  fclose(out);
  return 0;
}
