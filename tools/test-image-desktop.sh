#!/usr/bin/env bash
# The desktop's browser tests against a built image, as the README runs it: each test starts
# `docker run --rm -p 127.0.0.1:PORT:6080 -v FOLDER:/home/student/catkin_ws IMAGE desktop` with a
# folder of this (non-root) user, and drives it from the image's own Chromium (chromedriver in
# a second container on the host's network: a browser for every architecture the image has).
#   tools/test-image-desktop.sh IMAGE       (CI's image jobs; needs docker, or ENGINE=podman)
set -euo pipefail
image=${1:?usage: tools/test-image-desktop.sh IMAGE}
engine=${ENGINE:-docker}
cd "$(dirname "${BASH_SOURCE[0]}")/.."

# What the test code needs on the host (Debian or Ubuntu): Selenium, pytest, Pillow, numpy.
if ! python3 -c 'import selenium, pytest, PIL, numpy' 2>/dev/null; then
  sudo apt-get update -q
  sudo apt-get install -y -q --no-install-recommends python3-selenium python3-pytest \
    python3-pil python3-numpy
fi

port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
driver=course-desktop-chromedriver
"$engine" rm -f "$driver" >/dev/null 2>&1 || true
"$engine" run -d --rm --name "$driver" --network host --shm-size 1g "$image" \
  chromedriver --port="$port" --allowed-ips=127.0.0.1 >/dev/null
trap '"$engine" stop -t 5 "$driver" >/dev/null 2>&1 || true' EXIT
for _ in $(seq 100); do
  curl -fsS "http://127.0.0.1:$port/status" >/dev/null 2>&1 && break
  sleep 0.2
done

export DESKTOP_TEST_IMAGE=$image DESKTOP_TEST_ENGINE=$engine
export DESKTOP_TEST_WEBDRIVER=http://127.0.0.1:$port
export PYTHONPATH=$PWD/src/course_desktop/src:$PWD/src/course_common/src
python3 -m pytest -q -p no:cacheprovider -rs src/course_desktop/test/browser
