// stage_capture: run one of Stage's own world files headless, the way `stage -g` does,
// and record every position model's world pose, stall flag and every recorded model's
// flag count after each World::Update().
//
// Loading and stepping are Stage's own: Stg::Init (which seeds drand48 from the wall
// clock, as `stage` does), World(path) + World::Load (which loads the `ctrl` plugins and
// runs their Init), then World::Update() per step with the world file's `threads`.
// The only addition is a read of the models' state between two updates, and, in the
// header, every model's name in World::models' order: the models' addresses, which order
// the controllers' Init, the moves and a fiducial finder's readings. That order is the
// heap's, so it follows the allocations made before loading, the command line's too: a
// world file or output path too long for a short string (over 15 characters) takes a
// heap block and moves the models. Run a capture and the run it is compared with the same
// way (capture_worlds.sh does) and read the order from here.
//
// Output (little endian):
//   8 bytes  magic "STGCAP1\0"
//   uint32   length of a JSON header, then the header (UTF-8, no terminator)
//   records, one per state (state 0 = after loading, before the first update):
//     uint64   sim time in microseconds
//     float64  x, y, a for each position model (world frame, m and rad)
//     uint8    stall flag for each position model
//     uint32   flag count for each flag model
// The record count follows from the file length, so a cut-short run is still readable.

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "stage.hh"
#include "worldfile.hh"

namespace {

// A World that lets us read what the world file said; it changes no behaviour.
class CaptureWorld : public Stg::World {
public:
  explicit CaptureWorld(const std::string &name) : Stg::World(name) {}
  double ReadWorldFloat(const char *key, double def) { return wf->ReadFloat(0, key, def); }
  int ReadWorldInt(const char *key, int def) { return wf->ReadInt(0, key, def); }
};

std::string JsonEscape(const std::string &s)
{
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out;
}

// Depth-first, in the order the world file made the models (children vectors keep it).
void Collect(Stg::Model *mod, int depth, std::vector<Stg::Model *> &positions,
             std::vector<Stg::Model *> &flagged)
{
  const bool is_position = mod->GetModelType() == "position";
  if (is_position)
    positions.push_back(mod);
  if (depth == 0 || is_position)
    flagged.push_back(mod);
  for (Stg::Model *child : mod->GetChildren())
    Collect(child, depth + 1, positions, flagged);
}

// Every model but the World's own ground, in World::models' order: by address (a
// std::set<Model *>), read after loading (no allocation before it).
std::vector<Stg::Model *> ByAddress(Stg::World *world)
{
  std::vector<Stg::Model *> all, todo(world->GetChildren().begin(), world->GetChildren().end());
  while (!todo.empty()) {
    Stg::Model *mod = todo.back();
    todo.pop_back();
    if (strcmp(mod->Token(), "_ground_model") != 0)
      all.push_back(mod);
    for (Stg::Model *child : mod->GetChildren())
      todo.push_back(child);
  }
  std::sort(all.begin(), all.end());
  return all;
}

std::string NameList(const std::vector<Stg::Model *> &mods)
{
  std::string s = "[";
  for (size_t i = 0; i < mods.size(); ++i) {
    if (i)
      s += ", ";
    s += "\"" + JsonEscape(mods[i]->Token()) + "\"";
  }
  return s + "]";
}

// World poses [x, y, a] of the models, as JSON (to find the foraging worlds' sources and sinks).
std::string PoseList(const std::vector<Stg::Model *> &mods)
{
  std::string s = "[";
  char buf[128];
  for (size_t i = 0; i < mods.size(); ++i) {
    const Stg::Pose p = mods[i]->GetGlobalPose();
    snprintf(buf, sizeof buf, "%s[%.17g, %.17g, %.17g]", i ? ", " : "", p.x, p.y, p.a);
    s += buf;
  }
  return s + "]";
}

void Usage()
{
  fputs("usage: stage_capture [-n STEPS] [-a CTRLARGS] -o OUT WORLDFILE\n"
        "  -n STEPS   number of World::Update() calls (default 200)\n"
        "  -a STR     argument string for every controller (as stage -a)\n"
        "  -o OUT     output file\n",
        stderr);
}

} // namespace

int main(int argc, char *argv[])
{
  const time_t wall_before_init = time(NULL);
  // Same first call as Stage's main(): copies argv for controllers, seeds drand48.
  Stg::Init(&argc, &argv);
  const time_t wall_after_init = time(NULL);

  long steps = 200;
  std::string out_path;
  std::string world_path;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-n" && i + 1 < argc)
      steps = strtol(argv[++i], NULL, 10);
    else if (arg == "-o" && i + 1 < argc)
      out_path = argv[++i];
    else if (arg == "-a" && i + 1 < argc)
      Stg::World::ctrlargs = argv[++i];
    else if (!arg.empty() && arg[0] != '-' && world_path.empty())
      world_path = arg;
    else {
      Usage();
      return 2;
    }
  }
  if (world_path.empty() || out_path.empty() || steps < 0) {
    Usage();
    return 2;
  }

  CaptureWorld *world = new CaptureWorld(world_path);
  if (!world->Load(world_path)) {
    fprintf(stderr, "stage_capture: cannot load %s\n", world_path.c_str());
    return 1;
  }
  // main() of `stage` calls Start() unless paused; headless World::Update ignores
  // `paused` anyway (only WorldGui reads it from the file), so we start it regardless.
  world->Start();

  std::vector<Stg::Model *> positions, flagged;
  for (Stg::Model *mod : world->GetChildren())
    if (strcmp(mod->Token(), "_ground_model") != 0) // the World's own, holds nothing
      Collect(mod, 0, positions, flagged);

  FILE *out = fopen(out_path.c_str(), "wb");
  if (!out) {
    perror(out_path.c_str());
    return 1;
  }

  char num[512];
  std::string header = "{";
  header += "\"format\": 1";
  header += ", \"world\": \"" + JsonEscape(world_path) + "\"";
  snprintf(num, sizeof num,
           ", \"interval_sim_us\": %.0f, \"quit_time_s\": %.17g, \"threads\": %d"
           ", \"resolution\": %.17g, \"paused_in_file\": %d, \"steps_requested\": %ld"
           ", \"drand48_seed_time\": %lld, \"seed_time_certain\": %s",
           world->ReadWorldFloat("interval_sim", 100.0) * 1e3,
           world->ReadWorldFloat("quit_time", 0.0), world->ReadWorldInt("threads", 1),
           world->ReadWorldFloat("resolution", 0.02), world->ReadWorldInt("paused", 0), steps,
           static_cast<long long>(wall_before_init),
           wall_before_init == wall_after_init ? "true" : "false");
  header += num;
  header += ", \"ctrlargs\": \"" + JsonEscape(Stg::World::ctrlargs) + "\"";
  header += ", \"position_models\": " + NameList(positions);
  header += ", \"flag_models\": " + NameList(flagged);
  header += ", \"flag_model_poses\": " + PoseList(flagged);
  header += ", \"model_order\": " + NameList(ByAddress(world));
  header += "}";

  fwrite("STGCAP1\0", 1, 8, out);
  const uint32_t header_len = static_cast<uint32_t>(header.size());
  fwrite(&header_len, sizeof header_len, 1, out);
  fwrite(header.data(), 1, header.size(), out);

  const size_t n_pos = positions.size();
  const size_t n_flag = flagged.size();
  std::vector<double> pose(3 * n_pos);
  std::vector<uint8_t> stall(n_pos);
  std::vector<uint32_t> flags(n_flag);

  auto write_state = [&]() {
    const uint64_t t = world->SimTimeNow();
    for (size_t i = 0; i < n_pos; ++i) {
      const Stg::Pose p = positions[i]->GetGlobalPose();
      pose[3 * i] = p.x;
      pose[3 * i + 1] = p.y;
      pose[3 * i + 2] = p.a;
      stall[i] = positions[i]->Stalled() ? 1 : 0;
    }
    for (size_t i = 0; i < n_flag; ++i)
      flags[i] = flagged[i]->GetFlagCount();
    fwrite(&t, sizeof t, 1, out);
    fwrite(pose.data(), sizeof(double), pose.size(), out);
    fwrite(stall.data(), 1, stall.size(), out);
    fwrite(flags.data(), sizeof(uint32_t), flags.size(), out);
  };

  write_state();
  for (long s = 0; s < steps; ++s) {
    if (world->Update()) // true: past quit_time
      break;
    write_state();
  }
  fclose(out);
  // Like `stage`, do not tear the world down: the controllers' threads and
  // plugins are left to the process exit.
  fflush(stdout);
  _exit(0);
}
