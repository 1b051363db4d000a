#!/usr/bin/env bash
# Builds and runs the consumer programs the ways a downstream project uses
# impulse, each in a fresh temporary directory:
#   (a)  find_package(impulse) against an install made with
#        `cmake --install --prefix`, and find_package(impulse COMPONENTS scene)
#        with impulse::scene (scene_main.cpp);
#   (a') pkg-config against the same install, then against a copy of it
#        moved elsewhere (the .pc file is relocatable);
#   (b)  add_subdirectory, whose `cmake --install` must not install impulse
#        (IMPULSE_INSTALL is off there) unless the consumer turns it on;
#   (b') FetchContent, pointed at this checkout, configured only (it is
#        add_subdirectory underneath);
#   (c)  a Meson subproject;
#   (d)  the single headers alone: impulse_io.hpp (with impulse.hpp) and
#        impulse_scene.hpp, copied out of the repository.
# main.cpp makes a world, drops a box on the ground and records the run as
# .glb; scene_main.cpp loads a scene from JSON. The scene checks need
# nlohmann-json and are skipped without it.
#
#   tests/consumer/run.sh               (CXX=clang++ tests/consumer/run.sh)
#
# With IMPULSE_CONSUMER_RECORDING=FILE, the single-header program's .glb is
# kept there (CI then opens it in the viewer).
#
# One line per check, then a summary line; a failed check's log is printed
# after its line. Exits 1 if any check failed.
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
consumer=$repo/tests/consumer
# IMPULSE_CONSUMER_WORK=DIR works in DIR, emptied first, instead of a
# temporary directory: CI puts it inside the clone, where ccache (named in
# CMAKE_CXX_COMPILER_LAUNCHER) takes paths relative to the clone and a later
# run hits the same entries.
if [ -n "${IMPULSE_CONSUMER_WORK:-}" ]; then
  work=$IMPULSE_CONSUMER_WORK
  rm -rf "$work"
  mkdir -p "$work"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
launcher=${CMAKE_CXX_COMPILER_LAUNCHER:-}
cxx=${CXX:-g++}
warnings=(-Wall -Wextra -Wpedantic -Werror)
export CXX=$cxx

if printf '#include <nlohmann/json.hpp>\n' | "$cxx" -std=c++20 -fsyntax-only -x c++ - 2>/dev/null; then
  json=1
else
  json=0
fi

passed=0 failed=0 skipped=0 start=$SECONDS
# check LABEL FUNCTION: runs FUNCTION under set -e in a subshell, its output in a log.
check() {
  local label=$1 function=$2 began=$SECONDS status
  set +e
  (set -e; "$function") >"$work/$function.log" 2>&1
  status=$?
  set -e
  if ((status == 0)); then
    passed=$((passed + 1))
    printf 'consumer %-60s ok (%d s)\n' "$label" $((SECONDS - began))
  else
    failed=$((failed + 1))
    printf 'consumer %-60s FAILED (%d s)\n' "$label" $((SECONDS - began))
    tail -n 40 "$work/$function.log" | sed 's/^/    /'
  fi
}
skip() {
  skipped=$((skipped + 1))
  printf 'consumer %-60s skipped (%s)\n' "$1" "$2"
}

cmake_consumer() {  # cmake_consumer BUILD_DIR ARGS...: configure tests/consumer
  local build=$1
  shift
  cmake -S "$consumer" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_CXX_FLAGS="${warnings[*]}" "$@"
}

same_dir() { [ "$(cd "$1" && pwd -P)" = "$(cd "$2" && pwd -P)" ]; }

# (a) impulse configured for the default prefix and installed elsewhere with --prefix.
package() {
  cmake -S "$repo" -B "$work/impulse-build" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" \
    -DIMPULSE_BUILD_TESTS=OFF -DIMPULSE_BUILD_EXAMPLES=OFF -DIMPULSE_BUILD_BENCHMARKS=OFF
  cmake --install "$work/impulse-build" --prefix "$work/prefix"
  test -f "$work/prefix/include/impulse/impulse.hpp"
  test -f "$work/prefix/include/impulse/io/scene.hpp"
  test -f "$work/prefix/share/cmake/impulse/impulseConfigVersion.cmake"
  test -f "$work/prefix/share/cmake/impulse/impulseSceneTargets.cmake"
  test -f "$work/prefix/share/pkgconfig/impulse.pc"
  grep -q "impulse::deterministic" "$work/prefix/share/cmake/impulse/impulseTargets.cmake"
  cmake_consumer "$work/package" -DIMPULSE_CONSUMER_MODE=package -DCMAKE_PREFIX_PATH="$work/prefix"
  grep -qx "impulse_DIR:PATH=$work/prefix/share/cmake/impulse" "$work/package/CMakeCache.txt"
  cmake --build "$work/package" --target consumer
  "$work/package/consumer" "$work/package/run.glb"
}

package_scene() {  # the same build, reconfigured with COMPONENTS scene
  cmake_consumer "$work/package" -DIMPULSE_CONSUMER_SCENE=ON
  cmake --build "$work/package" --target scene_consumer
  "$work/package/scene_consumer"
}

pkgconfig() {
  export PKG_CONFIG_PATH=$work/prefix/share/pkgconfig
  same_dir "$(pkg-config --variable=includedir impulse)" "$work/prefix/include"
  # shellcheck disable=SC2046  # the flags are words
  $launcher "$cxx" "${warnings[@]}" $(pkg-config --cflags impulse) "$consumer/main.cpp" -o "$work/pkgconfig-consumer"
  "$work/pkgconfig-consumer" "$work/pkgconfig.glb"
}

pkgconfig_relocated() {  # the install copied elsewhere, the original gone
  mkdir "$work/elsewhere"
  cp -R "$work/prefix" "$work/elsewhere/impulse"
  rm -rf "$work/prefix"
  export PKG_CONFIG_PATH=$work/elsewhere/impulse/share/pkgconfig
  same_dir "$(pkg-config --variable=includedir impulse)" "$work/elsewhere/impulse/include"
  # shellcheck disable=SC2046
  $launcher "$cxx" "${warnings[@]}" $(pkg-config --cflags impulse) "$consumer/main.cpp" -o "$work/relocated-consumer"
  "$work/relocated-consumer" "$work/relocated.glb"
}

subdirectory() {
  local scene=OFF
  ((json)) && scene=ON  # impulse::scene must then exist, and resolve, in the consumer
  cmake_consumer "$work/subdirectory" -DIMPULSE_CONSUMER_MODE=subdirectory -DIMPULSE_SOURCE_DIR="$repo" \
    -DIMPULSE_CONSUMER_SCENE=$scene
  cmake --build "$work/subdirectory" --target consumer
  "$work/subdirectory/consumer" "$work/subdirectory/run.glb"
  # The consumer's install holds the consumer and nothing of impulse's...
  cmake --install "$work/subdirectory" --prefix "$work/consumer-prefix"
  installed=$(cd "$work/consumer-prefix" && find . -type f)
  if [ "$installed" != "./bin/consumer" ]; then
    printf "the consumer's install holds more than bin/consumer:\n%s\n" "$(head -n 10 <<<"$installed")" >&2
    exit 1
  fi
  # ...unless the consumer asks for it.
  cmake_consumer "$work/subdirectory" -DIMPULSE_INSTALL=ON
  cmake --install "$work/subdirectory" --prefix "$work/consumer-prefix-with-impulse"
  test -f "$work/consumer-prefix-with-impulse/include/impulse/impulse.hpp"
  test -f "$work/consumer-prefix-with-impulse/share/pkgconfig/impulse.pc"
}

fetchcontent() {  # configure only: the same targets and options as add_subdirectory
  local scene=OFF
  ((json)) && scene=ON
  cmake_consumer "$work/fetchcontent" -DIMPULSE_CONSUMER_MODE=fetchcontent \
    -DFETCHCONTENT_SOURCE_DIR_IMPULSE="$repo" -DIMPULSE_CONSUMER_SCENE=$scene
  grep -qx "IMPULSE_INSTALL:BOOL=OFF" "$work/fetchcontent/CMakeCache.txt"
  grep -qx "IMPULSE_BUILD_TESTS:BOOL=OFF" "$work/fetchcontent/CMakeCache.txt"
}

meson_subproject() {
  mkdir -p "$work/meson-consumer/subprojects"
  cp "$consumer/meson.build" "$consumer/main.cpp" "$work/meson-consumer/"
  ln -s "$repo" "$work/meson-consumer/subprojects/impulse"
  meson setup "$work/meson-consumer/build" "$work/meson-consumer" -Dwarning_level=3 -Dwerror=true
  meson compile -C "$work/meson-consumer/build"
  "$work/meson-consumer/build/consumer" "$work/meson-consumer/run.glb"
}

single_io() {  # the three single headers copied out alone; main.cpp includes impulse_io.hpp
  mkdir -p "$work/single/impulse"
  cp "$repo"/single_include/impulse/impulse.hpp "$repo"/single_include/impulse/impulse_io.hpp \
    "$repo"/single_include/impulse/impulse_scene.hpp "$work/single/impulse/"
  $launcher "$cxx" -std=c++20 "${warnings[@]}" -DIMPULSE_CONSUMER_SINGLE_HEADER -I "$work/single" \
    "$consumer/main.cpp" -o "$work/single-header-consumer"
  "$work/single-header-consumer" "$work/single.glb"
  # CI opens this recording in the viewer (viewer/test): IMPULSE_CONSUMER_RECORDING names where to keep it.
  if [ -n "${IMPULSE_CONSUMER_RECORDING:-}" ]; then
    mkdir -p "$(dirname "$IMPULSE_CONSUMER_RECORDING")"
    cp "$work/single.glb" "$IMPULSE_CONSUMER_RECORDING"
  fi
}

single_scene() {
  $launcher "$cxx" -std=c++20 "${warnings[@]}" -DIMPULSE_CONSUMER_SINGLE_HEADER -I "$work/single" \
    "$consumer/scene_main.cpp" -o "$work/single-header-scene-consumer"
  "$work/single-header-scene-consumer"
}

echo "consumer checks with $cxx ($("$cxx" --version | head -n 1))"
check "(a)  find_package(impulse), installed with --prefix" package
if ((json)); then
  check "(a)  find_package(impulse COMPONENTS scene), impulse::scene" package_scene
else
  skip "(a)  find_package(impulse COMPONENTS scene), impulse::scene" "no nlohmann-json"
fi
check "(a') pkg-config, the same install" pkgconfig
check "(a') pkg-config, the install copied elsewhere" pkgconfig_relocated
check "(b)  add_subdirectory, impulse's install rules off" subdirectory
check "(b') FetchContent (configured, not built)" fetchcontent
check "(c)  Meson subproject" meson_subproject
check "(d)  single headers alone: impulse_io.hpp + impulse.hpp" single_io
if ((json)); then
  check "(d)  single headers alone: impulse_scene.hpp" single_scene
else
  skip "(d)  single headers alone: impulse_scene.hpp" "no nlohmann-json"
fi
echo "consumer checks: $passed passed, $failed failed, $skipped skipped ($((SECONDS - start)) s)"
((failed == 0))
