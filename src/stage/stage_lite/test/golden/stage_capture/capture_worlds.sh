#!/usr/bin/env bash
# Capture Stage's own worlds with stage_capture, one run after another (never two at once).
# usage: capture_worlds.sh PEER WORLDS OUT RUNS SIM_S WORLD [WORLD..]
#   PEER    the peer build's prefix (PEER/install/lib holds libstage and Stage-4.3/*.so)
#   WORLDS  a copy of Stage's worlds/ folder (world files, .inc, bitmaps/)
#   OUT     folder for the captures: OUT/<world>/run<k>.stgcap (world's '/' becomes '_')
#   RUNS    runs per world; SIM_S  sim seconds per run (steps = SIM_S / interval_sim)
#   WORLD   a world file's name under WORLDS without .world, e.g. simple or benchmark/cave
# Each run starts at least 1.1 s of wall time after the last: Stg::Init seeds drand48 from
# time(NULL), so two runs in one second would share their seed.
set -euo pipefail
PEER=$1 WORLDS=$2 OUT=$3 RUNS=$4 SIM_S=$5
shift 5
export LD_LIBRARY_PATH="$PEER/install/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
CAPTURE="${STAGE_CAPTURE:-$PEER/bin/stage_capture}"
for world in "$@"; do
  file="$WORLDS/$world.world"
  interval_ms=$(sed -n 's/^[[:space:]]*interval_sim[[:space:]]\+\([0-9.]\+\).*/\1/p' "$file" | head -1)
  interval_ms=${interval_ms:-100}
  steps=$(python3 -c "print(int(round($SIM_S * 1000 / $interval_ms)))")
  dir="$OUT/${world//\//_}"
  mkdir -p "$dir"
  for k in $(seq 1 "$RUNS"); do
    start=$(date +%s.%N)
    # Stage resolves includes and bitmaps against the world file's folder; run from there.
    (cd "$(dirname "$file")" && "$CAPTURE" -n "$steps" -o "$dir/run$k.stgcap" \
      "$(basename "$file")" > "$dir/run$k.log" 2>&1)
    end=$(date +%s.%N)
    echo "$world run $k: $steps steps, $(python3 -c "print('%.1f' % ($end - $start))") s wall"
    sleep 1.1
  done
done
