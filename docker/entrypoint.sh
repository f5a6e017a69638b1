#!/usr/bin/env bash
# Run any command inside the built workspace: Debian's python3 first, devel space sourced.
set -e
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"
# shellcheck disable=SC1091
source /workspace/devel/setup.bash
exec "$@"
