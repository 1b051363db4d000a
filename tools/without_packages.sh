#!/usr/bin/env bash
# Runs a command as if some installed Debian packages were not installed:
#
#   tools/without_packages.sh libbullet-dev libode-dev -- cmake --workflow --preset release
#
# In a private mount namespace (root and unshare needed; nothing outside the
# command sees it), every directory that belongs to one of the packages alone
# (its headers, its CMake package) is covered by an empty tmpfs, and each of
# its pkg-config files, which share a directory with others, by /dev/null.
# So a build finds neither the packages nor their headers, as on a machine
# that never had them: CI runs the README's commands this way, since CI
# itself installs every optional package.
set -euo pipefail

packages=()
while (($#)) && [ "$1" != "--" ]; do
  packages+=("$1")
  shift
done
[ "${1:-}" = "--" ] && shift
if ((${#packages[@]} == 0 || $# == 0)); then
  echo "usage: tools/without_packages.sh PACKAGE... -- COMMAND [ARG...]" >&2
  exit 2
fi

if [ -z "${IMPULSE_WITHOUT_PACKAGES_INSIDE:-}" ]; then
  [ "$(id -u)" -eq 0 ] || { echo "without_packages: needs root (a mount namespace)" >&2; exit 2; }
  exec env IMPULSE_WITHOUT_PACKAGES_INSIDE=1 unshare --mount --propagation private "$0" "${packages[@]}" -- "$@"
fi

hidden=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || continue
  covered=""
  while IFS= read -r path; do
    [ -e "$path" ] || continue
    # Inside a directory already covered: nothing left to hide.
    if [ -n "$covered" ] && [[ "$path" == "$covered"/* ]]; then continue; fi
    owners=$(dpkg-query -S "$path" 2>/dev/null | sed -E 's/: [^:]*$//; s/:[a-z0-9]+$//' || true)
    if [ -d "$path" ] && [ "$owners" = "$package" ]; then
      mount -t tmpfs -o size=1m,mode=0755 "without_$package" "$path"
      covered=$path
      hidden+=("$path/")
    elif [ -f "$path" ] && [[ "$path" == *.pc ]]; then
      mount --bind /dev/null "$path"
      hidden+=("$path")
    fi
  done < <(dpkg-query -L "$package" | sort)
done
echo "without_packages: hid ${#hidden[@]} paths of ${packages[*]}"
exec "$@"
