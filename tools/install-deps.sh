#!/usr/bin/env bash
# Install the Debian packages listed in tools/debian-packages.txt, only those missing.
# Idempotent: when everything is present it downloads nothing. Uses sudo when not root.
set -euo pipefail

list="$(dirname "${BASH_SOURCE[0]}")/debian-packages.txt"
# The release names the list's 'CODENAME: package' lines (see the list's header).
release=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")

# The list's packages for this release: comments and blanks dropped, a 'CODENAME:' line kept
# (without its prefix) only on that release.
packages_for_release() {
  sed -e 's/#.*//' -e 's/[[:space:]]//g' "$list" | awk -F: -v release="$release" '
    NF == 1 && $1 != "" { print $1 }
    NF == 2 && $1 == release { print $2 }'
}
mapfile -t wanted < <(packages_for_release)
case $release in
  bookworm | trixie) ;;
  *) echo "deps: the list is tested on Debian bookworm and trixie; this is '${release:-unknown}'," \
       "so no release-specific line applies" >&2 ;;
esac

missing=()
for pkg in "${wanted[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  [[ $status == "install ok installed" ]] || missing+=("$pkg")
done

if ((${#missing[@]} == 0)); then
  echo "deps: all ${#wanted[@]} Debian packages present ($release)"
  exit 0
fi

as_root=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  as_root=(sudo)
fi
echo "deps: installing ${#missing[@]} Debian packages ($release): ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -q
"${as_root[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
