#!/usr/bin/env bash
# Lockstep determinism across builds (docs/world.md, "Lockstep determinism"):
# compiles tests/lockstep/lockstep.cpp once per compiler and set of flags
# below, runs every build, and fails unless each prints the hashes recorded
# in the program (600 steps of pile, pile on two workers, large_pyramid, a
# joint scene and the particles scene, with cross_platform_determinism on).
#
#   tools/lockstep_check.sh                  every build below
#   tools/lockstep_check.sh BUILD...         the named ones (e.g. g++-O2 clang-native)
#   tools/lockstep_check.sh --except "A B"   every build but A and B
#
# The builds (the deterministic flags are impulse::deterministic's:
# -ffp-contract=off, and -fno-tree-slp-vectorize for g++):
#   g++-O2            g++ -O2 -march=x86-64: SSE2 (elsewhere the default, e.g. NEON on ARM)
#   clang-O2          clang++ -O2 -march=x86-64
#   g++-native        g++ -O3 -march=native: AVX2 or AVX-512 where the machine has it
#   clang-native      clang++ -O3 -march=native
#   g++-no-avx512     g++ -O3 -march=native -mno-avx512f (only on a machine with AVX-512)
#   single-header     g++ -O3 -march=native with no flags at all: the single header with
#                     IMPULSE_CROSS_PLATFORM_DETERMINISM turns contraction off for its own code
#                     (60 steps, without large_pyramid: it checks the header's route, not the scenes)
# Two builds run at a time, into build/lockstep/. CXX_GNU and CXX_CLANG name
# other compilers; LOCKSTEP_LAUNCHER is put in front of each (CI: ccache).
# On another machine (ARM, another OS): run it there; the hashes recorded
# are x86-64's, so equal hashes mean the same bits as this machine's.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
work=${LOCKSTEP_WORK:-$repo/build/lockstep}
mkdir -p "$work"
gnu=${CXX_GNU:-g++}
clang=${CXX_CLANG:-clang++}
common=(-std=c++20 -Wall -Wextra -Wpedantic -Werror -pthread)
# g++ notes that 64-byte batches are passed as in GCC 4.6 and later: not a warning.
gnu_only=(-Wno-psabi)
source=$repo/tests/lockstep/lockstep.cpp

declare -A command quick
# The baseline instruction set, named: x86-64 is SSE2 (a distribution may
# default to more); elsewhere the compiler's default.
baseline=""
[ "$(uname -m)" = x86_64 ] && baseline=-march=x86-64
command[g++-O2]="$gnu -O2 $baseline -ffp-contract=off -fno-tree-slp-vectorize ${gnu_only[*]} -I$repo/include"
command[clang-O2]="$clang -O2 $baseline -ffp-contract=off -I$repo/include"
command[g++-native]="$gnu -O3 -march=native -ffp-contract=off -fno-tree-slp-vectorize ${gnu_only[*]} -I$repo/include"
command[clang-native]="$clang -O3 -march=native -ffp-contract=off -I$repo/include"
command[g++-no-avx512]="$gnu -O3 -march=native -mno-avx512f -ffp-contract=off -fno-tree-slp-vectorize ${gnu_only[*]} \
-I$repo/include"
command[single-header]="$gnu -O3 -march=native ${gnu_only[*]} -DIMPULSE_CROSS_PLATFORM_DETERMINISM \
-DIMPULSE_LOCKSTEP_SINGLE_HEADER -I$repo/single_include"
quick[single-header]=1
order=(g++-O2 clang-O2 g++-native clang-native g++-no-avx512 single-header)

except=""
if [ "${1:-}" = --except ]; then
  except=" $2 "
  shift 2
fi
if (($#)); then
  builds=("$@")
else
  builds=()
  for b in "${order[@]}"; do
    if [ "$b" = g++-no-avx512 ] && ! grep -q -w avx512f /proc/cpuinfo 2>/dev/null; then
      echo "lockstep: g++-no-avx512 skipped: this machine has no AVX-512"
      continue
    fi
    [[ "$except" == *" $b "* ]] && continue
    compiler=${command[$b]%% *}
    if ! command -v "$compiler" >/dev/null; then
      echo "lockstep: $b skipped: no $compiler here"
      continue
    fi
    builds+=("$b")
  done
fi

one() {  # one BUILD: compile and run, the output in $work/BUILD.log
  local b=$1 began=$SECONDS
  # shellcheck disable=SC2086  # the command is words
  ${LOCKSTEP_LAUNCHER:-} ${command[$b]} "${common[@]}" "$source" -o "$work/$b" >"$work/$b.log" 2>&1 || return 1
  local compiled=$((SECONDS - began))
  local length=--full
  [ -z "${quick[$b]:-}" ] || length=--quick
  "$work/$b" $length >>"$work/$b.log" 2>&1 || { echo "(compile ${compiled} s)" >>"$work/$b.log"; return 1; }
  echo "(compile ${compiled} s, run $((SECONDS - began - compiled)) s)" >>"$work/$b.log"
}

failed=0
for ((i = 0; i < ${#builds[@]}; i += 2)); do
  pids=()
  for b in "${builds[@]:i:2}"; do
    [ -n "${command[$b]:-}" ] || { echo "lockstep: no build named $b (${order[*]})" >&2; exit 2; }
    one "$b" &
    pids+=($!)
  done
  for ((k = 0; k < ${#pids[@]}; ++k)); do
    b=${builds[i + k]}
    if wait "${pids[k]}"; then status=ok; else status=FAILED; failed=$((failed + 1)); fi
    echo "== $b: ${command[$b]%% -I*} ($status)"
    sed 's/^/   /' "$work/$b.log"
  done
done
if ((failed)); then
  echo "lockstep: $failed of ${#builds[@]} builds differ from the recorded hashes or failed"
  exit 1
fi
echo "lockstep: all ${#builds[@]} builds give the recorded hashes"
