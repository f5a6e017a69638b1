// stage_probe: a controller plugin for the REAL Stage 4.3.0 (built as a peer, never in this
// repository) that prints, after every World::Update's callbacks, what stage_lite's
// draws golden test compares (../make_draws.py turns it into ../data/draws.npz):
//   SCAN t_us token hits sum   each updated ranger's first sensor: beams under range max,
//                              and the ranges summed in beam order (doubles, %.17g)
//   POSE t_us token x y a stall   each position model's global pose
//   RNG t_us w0 .. w30          glibc's random() state words, read without drawing
//                               (initstate to a buffer of our own, setstate back)
// Build against the peer and name it on any model with `ctrl "stage_probe"` (it draws
// nothing, so the run is the one Stage makes without it):
//   g++ -O1 -fPIC -shared -I PEER/install/include -o stage_probe.so stage_probe.cc \
//       -L PEER/install/lib -lstage
//   STAGEPATH=. LD_LIBRARY_PATH=PEER/install/lib PEER/install/bin/stage -g WORLD > run.txt
#include <Stage-4.3/stage.hh>
#include <cstdio>
#include <cstdlib>
using namespace Stg;

static int PrintScan(Model *mod, void *) {
  ModelRanger *ranger = dynamic_cast<ModelRanger *>(mod);
  if (!ranger || ranger->GetSensors().empty()) return 0;
  const ModelRanger::Sensor &s = ranger->GetSensors()[0];
  if (s.ranges.empty()) return 0;  // never updated: nobody subscribes it
  int hits = 0;
  double sum = 0;
  for (size_t i = 0; i < s.ranges.size(); i++) {
    if (s.ranges[i] < s.range.max) hits++;
    sum += s.ranges[i];
  }
  printf("SCAN %llu %s %d %.17g\n", (unsigned long long)mod->GetWorld()->SimTimeNow(),
         mod->Token(), hits, sum);
  return 0;
}

static int PrintPose(Model *mod, void *) {
  ModelPosition *p = dynamic_cast<ModelPosition *>(mod);
  if (!p) return 0;
  Pose g = p->GetGlobalPose();
  printf("POSE %llu %s %.17g %.17g %.17g %d\n", (unsigned long long)mod->GetWorld()->SimTimeNow(),
         mod->Token(), g.x, g.y, g.a, p->Stalled() ? 1 : 0);
  return 0;
}

static char scratch_state[128];

static int AfterUpdate(World *world, void *) {
  world->ForEachDescendant((model_callback_t)PrintScan, NULL);
  world->ForEachDescendant((model_callback_t)PrintPose, NULL);
  // initstate returns the current state's type word; the 31 state words follow it
  char *current = initstate(1, scratch_state, sizeof scratch_state);
  int32_t *words = (int32_t *)current + 1;
  printf("RNG %llu", (unsigned long long)world->SimTimeNow());
  for (int i = 0; i < 31; i++) printf(" %u", (uint32_t)words[i]);
  printf("\n");
  setstate(current);
  return 0;
}

extern "C" int Init(Model *mod, CtrlArgs *) {
  mod->GetWorld()->AddUpdateCallback((world_callback_t)AfterUpdate, NULL);
  return 0;
}
