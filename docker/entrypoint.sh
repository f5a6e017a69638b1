#!/usr/bin/env bash
# Run any command inside the built workspace: Debian's python3 first, devel space sourced.
# `desktop [OPTIONS]`: the course's desktop in the browser, as the owner of the student's
# mounted folder, never as root (src/course_desktop/README.md).
set -e
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"
# shellcheck disable=SC1091
source /workspace/devel/setup.bash
if [[ ${1:-} == desktop ]]; then
  shift
  exec /usr/bin/python3 -m course_desktop.container_user "$@"
fi
exec "$@"
