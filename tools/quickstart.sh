#!/usr/bin/env bash
# The README's quick start on a fresh Debian 12 machine:
#   tools/quickstart.sh demo   builds and runs the demo (the Rube Goldberg machine;
#                              writes out/rube_goldberg.glb)
#   tools/quickstart.sh test   builds and runs the test suite: every test, example
#                              and header (CMake preset native: g++ -O3
#                              -march=native, this machine's full SIMD width)
# Installs the Debian packages it needs first if any is missing (apt-get, via
# sudo when not root), and says which.
set -euo pipefail
cd "$(dirname "$0")/.."

needed=(g++ cmake ninja-build doctest-dev nlohmann-json3-dev)
missing=()
for package in "${needed[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" \
    || missing+=("$package")
done
if ((${#missing[@]})); then
  echo "quickstart: installing ${missing[*]} with apt-get"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi

case "${1:-}" in
  demo)
    cmake --preset native >/dev/null
    cmake --build --preset native --target rube_goldberg
    exec build/native/examples/rube_goldberg
    ;;
  test)
    exec cmake --workflow --preset native
    ;;
  *)
    echo "usage: tools/quickstart.sh demo|test" >&2
    exit 2
    ;;
esac
