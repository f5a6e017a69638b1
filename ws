#!/usr/bin/env bash
# The workspace's one entry point: ./ws demo runs the main demo, ./ws test runs every test.
# Every step runs ROS under Debian's /usr/bin/python3 whatever python3 comes first on PATH.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
cd "$ROOT"

# Debian's ROS lives in /usr; a pyenv or venv python3 first on PATH cannot import rospy.
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"
unset PYTHONHOME PYTHONPATH VIRTUAL_ENV
export PYTHONDONTWRITEBYTECODE=1
# Several builds can share one checkout (a developer and a helper, say) by naming their own.
BUILD_DIR=${WS_BUILD_DIR:-build}
DEVEL_DIR=${WS_DEVEL_DIR:-devel}
RESULTS_DIR="$ROOT/$BUILD_DIR/ws-results"
LINT_VENV="$ROOT/$BUILD_DIR/lint-venv"
# How many test jobs (.test files, the unit, multi-host and browser tests) ./ws test runs side
# by side: one more than the cores, as most of a rostest's time is spent waiting on its nodes,
# but at most 4 (on 2 cores, side by side: 2 jobs 733 s, 3 jobs 630 s, 4 jobs 619 s, and the
# load of 4 made timing flakes).
CORES=$(nproc 2>/dev/null || echo 1)
TEST_JOBS=${WS_TEST_JOBS:-$((CORES + 1 > 4 ? 4 : CORES + 1))}

usage() {
  cat <<EOF
usage: ./ws COMMAND [ARGS]
  demo [ARGS]        deps, build, then the demos: the convoy with its autopilot leader (ARGS go
                     to it), then the synchronisation lesson on Stage (build/demo/stage/)
  test               deps, build, lint, then the unit, integration, multi-host and browser
                     tests side by side (WS_TEST_JOBS at a time: the cores + 1, at most 4;
                     longest first, by their last run's times in build/test-durations), one
                     summary line
  deps               install the missing Debian packages of tools/debian-packages.txt
  build [ARGS]       catkin_make the workspace (ARGS go to catkin_make, e.g. install; run_tests
                     runs every unit test and rostest the catkin way, see src/course_pytest)
  lint               catkin_lint, tests registered with catkin, ruff, hadolint, actionlint
  unit [ARGS]        pytest on every package's test/unit (ARGS go to pytest)
  integration [F..]  rostest every test/*.test of every package (or just the files F),
                     WS_TEST_JOBS at a time, longest first
  multihost [ARGS]   the multi-host tests (test/hosts/, pytest; root and ip netns, else skipped)
  browser [ARGS]     the browser tests (test/browser/, pytest): the desktop in headless Chromium,
                     against ./ws desktop, or an image with DESKTOP_TEST_IMAGE=NAME
  bench [NAME..] [OPTIONS]
                     run the benchmarks under bench/ (all, or bench/NAME.py); options
                     (from the first one starting with -) go to each of them, e.g.
                     ./ws bench stage_bench --peer STAGEROS --map willow-full.pgm
  shell              a bash with the workspace sourced, for running things by hand
  desktop [OPTIONS]  the course's desktop in a web browser, on http://127.0.0.1:6080/ until
                     Ctrl-C (--listen ADDR, --port N, --token T, --workspace DIR, --help;
                     src/course_desktop/README.md)
  hosts CMD [ARGS]   hosts on this machine as network namespaces (root): up N | down | status |
                     exec I CMD.. | link I up/down | netem ARGS/off (src/multihost/README.md)
EOF
}

# demo, test and bench run every node on this machine: name it "localhost" in ROS URIs unless
# the user chose a name or address, so a hostname that does not resolve (a bare container, a
# renamed machine) cannot stop a node from reaching its own master.
local_ros_network() {
  if [[ -z ${ROS_HOSTNAME:-} && -z ${ROS_IP:-} ]]; then
    export ROS_HOSTNAME=localhost
  fi
}

source_devel() {
  [[ -f $DEVEL_DIR/setup.bash ]] || { echo "ws: $DEVEL_DIR/ is missing: run ./ws build" >&2; exit 1; }
  # setup.bash reads unset variables; relax nounset while it runs.
  set +u
  # shellcheck disable=SC1090,SC1091
  source "$DEVEL_DIR/setup.bash"
  set -u
}

cmd_deps() { bash tools/install-deps.sh; }

cmd_build() {
  catkin_make --build "$BUILD_DIR" -DCATKIN_DEVEL_PREFIX="$ROOT/$DEVEL_DIR" \
    -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCATKIN_ENABLE_TESTING=ON "$@"
  warm_kernels
}

# stage_lite's grid kernels are compiled by numba at their first call and cached: compile
# them now, so that the first stageros (a test's, the demo's) starts in well under a second.
warm_kernels() {
  (source_devel && /usr/bin/python3 -m stage_lite.model.warmup)
}

# The build as a step of demo/test: its log goes to a file, shown only if it fails.
build_step() {
  mkdir -p "$BUILD_DIR"
  local log="$ROOT/$BUILD_DIR/catkin_make.log"
  if cmd_build >"$log" 2>&1; then
    echo "build: ok (log: $log)"
  else
    tail -n 60 "$log" >&2
    echo "build: FAILED (log: $log)" >&2
    return 1
  fi
}

lint_venv() {
  if [[ ! -x $LINT_VENV/bin/ruff ]] || ! cmp -s tools/lint-requirements.txt "$LINT_VENV/requirements.txt"; then
    echo "lint: installing linters into $LINT_VENV"
    rm -rf "$LINT_VENV"
    /usr/bin/python3 -m venv "$LINT_VENV"
    "$LINT_VENV/bin/pip" install -q --disable-pip-version-check -r tools/lint-requirements.txt \
      >"$ROOT/$BUILD_DIR/lint-install.log" 2>&1 || { cat "$ROOT/$BUILD_DIR/lint-install.log" >&2; return 1; }
    cp tools/lint-requirements.txt "$LINT_VENV/requirements.txt"
  fi
}

# Every package's tests run under `catkin_make run_tests` too: a package with launch files,
# .test files or unit tests calls course_add_tests() in its testing block (src/course_pytest).
check_tests_registered() {
  local d failed=0 what=()
  for d in $(package_dirs); do
    what=()
    [[ ! -d $d/launch ]] || what+=("$d/launch")
    ! compgen -G "$d/test/*.test" >/dev/null || what+=("$d/test/*.test")
    [[ ! -d $d/test/unit ]] || what+=("$d/test/unit")
    ((${#what[@]})) || continue
    grep -q '^ *course_add_tests()' "$d/CMakeLists.txt" || {
      echo "$d/CMakeLists.txt: add course_add_tests() to its testing block" \
        "(catkin_make run_tests would not run ${what[*]})" >&2
      failed=1
    }
  done
  return $failed
}

cmd_lint() {
  lint_venv
  source_devel
  local failed=0
  echo "lint: catkin_lint"; catkin_lint --strict -W2 --quiet src || failed=1
  echo "lint: tests registered"; check_tests_registered || failed=1
  echo "lint: ruff"; "$LINT_VENV/bin/ruff" check --quiet . || failed=1
  echo "lint: hadolint"; "$LINT_VENV/bin/hadolint" docker/Dockerfile || failed=1
  echo "lint: actionlint"; "$LINT_VENV/bin/actionlint" .github/workflows/*.yml || failed=1
  if ((failed)); then echo "lint: FAILED" >&2; return 1; fi
  echo "lint: clean"
}

# Every catkin package under src/, at any depth (src/turtle_lite/turtlesim, src/basics/chat_pkg).
package_dirs() { find src -name package.xml -not -path '*/.*' -printf '%h\n' | sort; }

# Every package's rostest files.
integration_files() { local d; for d in $(package_dirs); do compgen -G "$d/test/*.test" || true; done; }
# Every package's test/NAME folder: test/unit (pytest), test/hosts (pytest on network namespaces).
test_dirs() { local d; for d in $(package_dirs); do [[ ! -d $d/test/$1 ]] || echo "$d/test/$1"; done; }

cmd_unit() {
  source_devel
  # A few unit tests start a node against a master in the test's own process.
  local_ros_network
  mkdir -p "$RESULTS_DIR"
  local status=0 dirs
  mapfile -t dirs < <(test_dirs unit)
  dirs+=(tools/test)  # the workspace's own tools (the test summary)
  /usr/bin/python3 -m pytest -q -p no:cacheprovider --junitxml="$RESULTS_DIR/unit.xml" \
    "${dirs[@]}" "$@" || status=$?
  # 5 = no tests collected: the summary reports that as a failure, not pytest's exit code.
  ((status == 0 || status == 5))
}

cmd_integration() {
  local files=("$@")
  ((${#files[@]})) || mapfile -t files < <(integration_files)
  mapfile -t files < <(longest_first "${files[@]}")
  run_test_jobs "${files[@]}"
}

# One .test file: rostest starts a master of its own on a free port, so files running side by
# side never share a master; its results and log stay in the file's own directory.
run_rostest_file() {
  local f=$1 dir
  dir=$(integration_results_dir "$f")
  rm -rf "$dir" && mkdir -p "$dir"
  # rostest limits each test node itself (time-limit); the outer timeout catches a hung launch
  # (it signals its own process group: the launch and everything the test started).
  timeout --kill-after=10 600 rostest --results-base-dir="$dir" \
    "$(package_of "$f")" "$(basename "$f")" >"$dir/rostest.log" 2>&1 || return
  # rostest passes a test node that died before writing its results (an import error, say)
  # as "0 tests": that is a failure.
  if grep -q 'results summary: .*, 0 tests$' "$dir/rostest.log"; then
    echo "ws: a test node of $f ran no test (it died: see its log under ~/.ros/log)" \
      >>"$dir/rostest.log"
    return 1
  fi
}

# A job of the test steps that run side by side: a .test file, or one of the pytest steps
# `unit`, `multihost`, `browser` (its output in build/ws-results/NAME.log).
run_test_job() {
  case $1 in
    unit | multihost | browser) "cmd_$1" >"$RESULTS_DIR/$1.log" 2>&1 ;;
    *) run_rostest_file "$1" ;;
  esac
}

test_job_log() {
  case $1 in
    unit | multihost | browser) echo "$RESULTS_DIR/$1.log" ;;
    *) echo "$(integration_results_dir "$1")/rostest.log" ;;
  esac
}

test_job_label() {
  case $1 in
    unit | multihost | browser) echo "$1:" ;;
    *) echo "integration: $(package_of "$1")/$(basename "$1" .test)" ;;
  esac
}

# How long each job took at its last run (seconds, job), kept in the build directory.
TEST_DURATIONS="$ROOT/$BUILD_DIR/test-durations"

# The jobs, longest first (so that no long job starts last and runs alone at the end): by the
# time each took at its last run; one never run here by its rostest time-limits (a fresh
# clone: rough, but long files have long limits), the pytest steps first of all.
longest_first() {
  local -A took=()
  local seconds job
  if [[ -f $TEST_DURATIONS ]]; then
    while read -r seconds job; do took[$job]=$seconds; done <"$TEST_DURATIONS"
  fi
  for job in "$@"; do
    if [[ -n ${took[$job]:-} ]]; then
      seconds=${took[$job]}
    else
      case $job in
        unit | multihost | browser) seconds=1000 ;;
        *) seconds=$(grep -o 'time-limit="[0-9.]*"' "$job" | awk -F'"' '{s += $2} END {printf "%d", s / 5}') ;;
      esac
    fi
    printf '%s\t%s\n' "$seconds" "$job"
  done | sort -s -t$'\t' -k1,1nr | cut -f2
}

# Records how long job took at this run (seconds), replacing its last time.
record_duration() {
  local job=$1 seconds=$2 tmp="$TEST_DURATIONS.new"
  { [[ ! -f $TEST_DURATIONS ]] || awk -v job="$job" '$2 != job' "$TEST_DURATIONS"
    echo "$seconds $job"; } >"$tmp"
  mv "$tmp" "$TEST_DURATIONS"
}

# Runs the jobs TEST_JOBS at a time, in the order given, each in the background with its output
# in its log; prints one line per job as it ends (the log's tail if it failed). Non-zero if
# any job failed.
run_test_jobs() {
  source_devel
  local_ros_network
  # No window on the developer's screen: a test that wants one starts its own Xvfb.
  unset DISPLAY WAYLAND_DISPLAY
  mkdir -p "$RESULTS_DIR"
  # install_space.test installs from this build directory.
  export WS_BUILD_PATH="$ROOT/$BUILD_DIR"
  local -A running=() started=()
  local job pid failed=0
  for job in "$@"; do
    while ((${#running[@]} >= TEST_JOBS)); do end_test_job || failed=1; done
    # bash starts a background job with SIGINT and SIGQUIT ignored, and every process the
    # test starts would inherit that: a test's Ctrl-C (ChildProcess.stop, roslaunch's own
    # SIGINT to its nodes) would then wait out its timeout on any program that does not set
    # its own handler (sleep, rosbag, a shell). The job's subshell takes the defaults back.
    (trap - INT QUIT; run_test_job "$job") &
    running[$!]=$job started[$!]=$SECONDS
  done
  while ((${#running[@]})); do end_test_job || failed=1; done
  return $failed
}

# Waits for one job of run_test_jobs (its `running` and `started`) to end and reports it.
end_test_job() {
  local pid status=0
  wait -n -p pid "${!running[@]}" || status=$?
  local job=${running[$pid]} took=$((SECONDS - started[$pid]))
  unset "running[$pid]" "started[$pid]"
  record_duration "$job" "$took"
  if ((status == 0)); then
    echo "$(test_job_label "$job") ok (${took} s)"
    return 0
  fi
  echo "$(test_job_label "$job") FAILED (exit $status, ${took} s); the end of $(test_job_log "$job"):"
  tail -n 30 "$(test_job_log "$job")"
  return 1
}

# The lessons across hosts (network namespaces): pytest, as they run one master per test, on
# hosts rostest cannot start. Without root or `ip netns` each test reports itself skipped.
cmd_multihost() {
  source_devel
  mkdir -p "$RESULTS_DIR"
  # Leftovers of a run that was killed outright (SIGKILL skips its clean-up).
  if [[ $(id -u) == 0 ]] && command -v ip >/dev/null; then rosrun multihost hosts down --stale || true; fi
  pytest_test_dirs hosts multihost "$@"
}

# pytest on every package's test/NAME folder, under a timeout, its results in
# build/ws-results/LABEL.xml; skips reported with their reasons; "no test" is not a failure
# here (the summary counts what ran).
pytest_test_dirs() {
  local name=$1 label=$2 status=0 dirs
  shift 2
  mapfile -t dirs < <(test_dirs "$name")
  timeout --kill-after=10 1200 /usr/bin/python3 -m pytest -q -p no:cacheprovider \
    --junitxml="$RESULTS_DIR/$label.xml" -rs "${dirs[@]}" "$@" || status=$?
  ((status == 0 || status == 5))
}

# The desktop in a real browser (test/browser/, pytest): each test starts its own desktop on a
# free port and a headless Chromium.
cmd_browser() {
  source_devel
  local_ros_network
  export COURSE_WS_SETUP="$ROOT/$DEVEL_DIR/setup.bash"
  mkdir -p "$RESULTS_DIR"
  pytest_test_dirs browser browser "$@"
}

# src/.../<pkg>/test/<name>.test -> <pkg>
package_of() { basename "$(dirname "$(dirname "$1")")"; }

# Each .test file reports into a directory of its own, so test names never collide.
integration_results_dir() { echo "$RESULTS_DIR/integration/$(package_of "$1")/$(basename "$1" .test)"; }

cmd_summary() {
  /usr/bin/python3 tools/test_summary.py "$@"
}

cmd_test() {
  cmd_deps
  build_step
  rm -rf "$RESULTS_DIR"
  local lint_ok=1
  cmd_lint || lint_ok=0
  # The unit tests, the multi-host and browser tests and the .test files side by side.
  local files jobs
  mapfile -t files < <(integration_files)
  mapfile -t jobs < <(longest_first unit multihost browser "${files[@]}")
  run_test_jobs "${jobs[@]}" || true
  local expected=(--junit "$RESULTS_DIR/unit.xml" --junit "$RESULTS_DIR/multihost.xml"
    --junit "$RESULTS_DIR/browser.xml") f
  for f in "${files[@]}"; do
    expected+=(--rostest "$(integration_results_dir "$f")")
  done
  ((lint_ok)) || expected+=(--failed-step lint)
  cmd_summary "${expected[@]}"
}

cmd_demo() {
  cmd_deps
  build_step
  source_devel
  local_ros_network
  # ARGS are the convoy demo's; a failing convoy demo ends ./ws demo with its exit code.
  rosrun convoy convoy_demo --out "$ROOT/$BUILD_DIR/demo" "$@"
  # `./ws demo --help` asked for the convoy demo's usage, not for a run of the next demo.
  case " $* " in *" -h "* | *" --help "*) return 0 ;; esac
  # Then the synchronisation lesson on the workspace's Stage, headless.
  rosrun multi_sync stage_demo --out "$ROOT/$BUILD_DIR/demo/stage"
}

cmd_bench() {
  source_devel
  local_ros_network
  local names=() n
  while (($#)) && [[ $1 != -* ]]; do names+=("$1"); shift; done
  ((${#names[@]})) || mapfile -t names < <(cd bench && ls ./*.py | sed 's|^\./||; s|\.py$||')
  for n in "${names[@]}"; do
    echo "bench: $n"
    /usr/bin/python3 "bench/$n.py" "$@"
  done
}

cmd_hosts() {
  source_devel
  exec rosrun multihost hosts "$@"
}

# The desktop runs what the student starts in its terminals, as this user: no deps or build
# step (a student's container has no root), the built workspace is all it needs.
cmd_desktop() {
  source_devel
  local_ros_network
  export COURSE_WS_SETUP="$ROOT/$DEVEL_DIR/setup.bash"
  # The devel space's relay itself: rosrun would look it up for most of a second.
  exec "$ROOT/$DEVEL_DIR/lib/course_desktop/desktop" "$@"
}

cmd_shell() {
  source_devel
  exec bash --rcfile <(echo "source ~/.bashrc 2>/dev/null; export PATH=\"$PATH\"; source \"$ROOT/$DEVEL_DIR/setup.bash\"; PS1=\"(ws) \$PS1\"")
}

command=${1:-}
[[ -n $command ]] || { usage; exit 2; }
shift
case $command in
  demo|test|deps|build|lint|unit|integration|multihost|browser|summary|bench|shell|hosts|desktop) "cmd_$command" "$@" ;;
  -h|--help|help) usage ;;
  *) echo "ws: unknown command '$command'" >&2; usage >&2; exit 2 ;;
esac
