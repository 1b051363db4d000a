#!/usr/bin/env bash
# Builds and runs tests/consumer/main.cpp the ways a downstream project uses
# impulse: (a) find_package against an install into a temporary prefix, and
# pkg-config against the same install; (b) add_subdirectory; (c) a Meson
# subproject; (d) nothing but -I single_include.
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
consumer=$repo/tests/consumer
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cxx=${CXX:-g++}

echo "consumer (a): find_package against an installed prefix"
cmake -S "$repo" -B "$work/impulse-build" -G Ninja -DCMAKE_INSTALL_PREFIX="$work/prefix" \
  -DIMPULSE_BUILD_TESTS=OFF -DIMPULSE_BUILD_EXAMPLES=OFF -DIMPULSE_BUILD_BENCHMARKS=OFF >/dev/null
cmake --install "$work/impulse-build" >/dev/null
test -f "$work/prefix/share/cmake/impulse/impulseConfigVersion.cmake"
cmake -S "$consumer" -B "$work/package" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" \
  -DIMPULSE_CONSUMER_MODE=package -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/package" >/dev/null
"$work/package/consumer"

echo "consumer (a'): pkg-config against the same prefix"
flags=$(PKG_CONFIG_PATH="$work/prefix/share/pkgconfig" pkg-config --cflags impulse)
"$cxx" $flags "$consumer/main.cpp" -o "$work/pkgconfig-consumer"
"$work/pkgconfig-consumer"

echo "consumer (b): add_subdirectory"
cmake -S "$consumer" -B "$work/subdirectory" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" \
  -DIMPULSE_CONSUMER_MODE=subdirectory -DIMPULSE_SOURCE_DIR="$repo" >/dev/null
cmake --build "$work/subdirectory" >/dev/null
"$work/subdirectory/consumer"

echo "consumer (c): Meson subproject"
mkdir -p "$work/meson-consumer/subprojects"
cp "$consumer/meson.build" "$consumer/main.cpp" "$work/meson-consumer/"
ln -s "$repo" "$work/meson-consumer/subprojects/impulse"
CXX="$cxx" meson setup "$work/meson-consumer/build" "$work/meson-consumer" >/dev/null
meson test -C "$work/meson-consumer/build" --print-errorlogs >/dev/null
"$work/meson-consumer/build/consumer"

echo "consumer (d): the single header alone"
"$cxx" -std=c++20 -Wall -Wextra -Wpedantic -Werror -I "$repo/single_include" \
  "$consumer/main.cpp" -o "$work/single-header-consumer"
"$work/single-header-consumer"

echo "consumer checks: 5 passed, 0 failed"
