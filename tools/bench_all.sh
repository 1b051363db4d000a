#!/usr/bin/env bash
# tools/bench_all.sh — reruns every benchmark on this machine and rewrites
# everything the docs take from them: the CSVs and plots in docs/,
# bench/scenes/results.csv (and peers_results.csv, the peers' rows of the
# same run), bench/joints/results.txt, and every table in docs/*.md between
# `<!-- bench_all: NAME begin -->` and `<!-- bench_all: NAME end -->`
# (rendered by tools/bench_docs.py, each headed by a line giving the date,
# the machine, the compiler and flags, and the peers' versions).
# docs/benchmarks.md lists the steps, what each writes, and the provenance
# of each.
#
#   tools/bench_all.sh                        every step: 28 minutes on 2 cores here
#   tools/bench_all.sh --only scenes,joints   some steps (--list names them)
#   tools/bench_all.sh --quick                every program in its smoke mode, everything
#                                             written under build/bench/quick (docs/ is not
#                                             touched): tests this script in a few minutes
#   --jobs N    parallel jobs for the build (default: every core)
#
# It builds build/bench with the native preset's flags (g++ -O3
# -march=native, warnings as errors, no tests or examples); Bullet
# (libbullet-dev), ODE (libode-dev) and libccd (libccd-dev) are compared
# when CMake finds them, and a peer that is missing is reported and left out
# of the tables, never an error. The plots need matplotlib (Debian:
# python3-matplotlib, seen by /usr/bin/python3): without it the PNGs are
# left as they were and the run says so. Each step writes its outputs only
# once its programs have succeeded; a failed step is reported at the end
# (exit 1) and the other steps still run. Logs: build/bench/logs/STEP.log.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

steps_all=(compile_time particles speed_vs_error rigid_motion broadphase narrowphase joints scenes contact_memory)
declare -A about=(
  [compile_time]="compile time of the headers (bench/compile_time/compile_time.py)"
  [particles]="particle-steps per second (bench/particles)"
  [speed_vs_error]="integrators' error against cost (bench/speed_vs_error)"
  [rigid_motion]="rigid body motion and free rotation (bench/rigid_motion)"
  [broadphase]="broad phases against each other and Bullet (bench/broadphase)"
  [narrowphase]="pair tests against libccd and Bullet (bench/narrowphase)"
  [joints]="joint grid and ragdoll pile against Bullet (bench/joints)"
  [scenes]="rigid-body scenes on impulse, Bullet and ODE (bench/scenes)"
  [contact_memory]="bytes per contact pair against Bullet (bench/contact_memory)"
)
declare -A targets=(
  [compile_time]=""
  [particles]="particles"
  [speed_vs_error]="speed_vs_error"
  [rigid_motion]="rigid_motion rigid_motion_speed_vs_error"
  [broadphase]="broadphase"
  [narrowphase]="narrowphase"
  [joints]="joints"
  [scenes]="scenes"
  [contact_memory]="contact_memory"
)

usage() {
  sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'
}

quick=0
only=""
jobs=$(nproc 2>/dev/null || echo 1)
while (($#)); do
  case $1 in
    --quick) quick=1 ;;
    --only)
      [[ $# -ge 2 ]] || { echo "bench_all: --only needs a list of steps" >&2; exit 2; }
      only=$2
      shift ;;
    --only=*) only=${1#--only=} ;;
    --jobs)
      [[ $# -ge 2 && $2 =~ ^[1-9][0-9]*$ ]] || { echo "bench_all: --jobs needs a number" >&2; exit 2; }
      jobs=$2
      shift ;;
    --list)
      for s in "${steps_all[@]}"; do printf '%-15s %s\n' "$s" "${about[$s]}"; done
      exit 0 ;;
    -h | --help) usage; exit 0 ;;
    *) echo "bench_all: unknown argument $1 (--help)" >&2; exit 2 ;;
  esac
  shift
done

steps=()
if [[ -n $only ]]; then
  IFS=, read -r -a wanted <<<"$only"
  for w in "${wanted[@]}"; do
    [[ -n ${about[$w]+x} ]] || { echo "bench_all: no step $w (steps: ${steps_all[*]})" >&2; exit 2; }
  done
  for s in "${steps_all[@]}"; do  # in the usual order, whatever the order asked
    for w in "${wanted[@]}"; do [[ $w == "$s" ]] && steps+=("$s"); done
  done
else
  steps=("${steps_all[@]}")
fi

build=build/bench
python=python3
command -v "$python" >/dev/null || python=/usr/bin/python3
docs_tool=("$python" "$root/tools/bench_docs.py")

if ((quick)); then
  # Everything goes to a scratch tree shaped like the repository, so that
  # the docs' blocks are rewritten in copies.
  dest=$root/$build/quick
  rm -rf "$dest"
  mkdir -p "$dest/docs" "$dest/bench/scenes" "$dest/bench/joints"
  cp docs/*.md "$dest/docs/"
  logs=$dest/logs
else
  dest=$root
  logs=$root/$build/logs
fi
mkdir -p "$logs"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prov=$logs/provenance.txt
notes=$work/notes  # said again at the end (a file: steps run in subshells)
: >"$notes"

stamp() { date +%T; }
duration() {
  local s=$1
  if ((s >= 60)); then printf '%d min %02d s' $((s / 60)) $((s % 60)); else printf '%d s' "$s"; fi
}
say() { printf '%s\n' "$*"; }
note() {
  say "    note: $*"
  printf '%s\n' "$*" >>"$notes"
}

# The markers must all be in place before an hour is spent measuring.
"${docs_tool[@]}" check --root "$dest" >/dev/null

heading="bench_all: $(date '+%F %T'), ${#steps[@]} step(s): ${steps[*]}"
if ((quick)); then heading+=" (--quick: smoke runs, everything written under $build/quick)"; fi
say "$heading"

# ---- build ----------------------------------------------------------------------
build_start=$SECONDS
say "==> [$(stamp)] build: configure and build $build (g++ -O3 -march=native)"
configure=(cmake -S . -B "$build"
  -DCMAKE_BUILD_TYPE=Release
  -DCMAKE_CXX_COMPILER=g++
  -DCMAKE_CXX_FLAGS=-march=native
  "-DCMAKE_CXX_FLAGS_RELEASE=-O3 -DNDEBUG"
  -DIMPULSE_BUILD_TESTS=OFF
  -DIMPULSE_BUILD_EXAMPLES=OFF
  -DIMPULSE_BUILD_BENCHMARKS=ON
  -DIMPULSE_WARNINGS_AS_ERRORS=ON)
if [[ ! -f $build/CMakeCache.txt ]] && command -v ninja >/dev/null; then
  configure+=(-G Ninja)
fi
if ! "${configure[@]}" >"$logs/configure.log" 2>&1; then
  say "bench_all: configuring $build failed; see $logs/configure.log" >&2
  exit 1
fi
build_targets=()
for s in "${steps[@]}"; do
  for t in ${targets[$s]}; do build_targets+=("$t"); done
done
if ((${#build_targets[@]})); then
  if ! cmake --build "$build" -j "$jobs" --target "${build_targets[@]}" >"$logs/build.log" 2>&1; then
    tail -n 30 "$logs/build.log" >&2
    say "bench_all: the build failed; see $logs/build.log" >&2
    exit 1
  fi
fi
say "    [$(stamp)] build done in $(duration $((SECONDS - build_start)))"

# ---- provenance -----------------------------------------------------------------
peer_in_build() {  # the version CMake reported for a peer it compiles in, or nothing
  sed -n "s/^-- bench\/[a-z_]*: comparing with $1 \([^ ]*\).*/\1/p" "$logs/configure.log" | head -n 1
}
package_version() {  # pkg-config's version of a module, or Debian's of a package, or nothing
  pkg-config --modversion "$1" 2>/dev/null ||
    dpkg-query -W -f='${Version}' "$2" 2>/dev/null | sed 's/^[0-9]*://; s/[-+~].*//' || true
}
cpu_flag() { grep -m 1 -qw "$1" /proc/cpuinfo 2>/dev/null && echo yes || echo no; }
{
  echo "date=$(date +%F)"
  model=$(lscpu 2>/dev/null | sed -n 's/^Model name:[[:space:]]*//p' | head -n 1)
  [[ -n $model ]] || model=$(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo | head -n 1)
  echo "machine=${model:-unknown}"
  echo "cores=$(nproc)"
  echo "avx2=$(cpu_flag avx2)"
  echo "avx512f=$(cpu_flag avx512f)"
  echo "fma=$(cpu_flag fma)"
  echo "cxx=g++ $(g++ -dumpfullversion)"
  echo "cxx_flags=-O3 -march=native"
  echo "gxx=g++ $(g++ -dumpfullversion)"
  if command -v clang++ >/dev/null; then echo "clangxx=clang++ $(clang++ -dumpversion)"; fi
  # A peer's version only when CMake compiled it in; pkg-config's version
  # (Debian's package version for libccd, whose own files say 2.0 for 2.1).
  [[ -n $(peer_in_build Bullet) ]] && echo "bullet=$(package_version bullet libbullet-dev)"
  [[ -n $(peer_in_build ODE) ]] && echo "ode=$(package_version ode libode-dev)"
  if [[ -n $(peer_in_build libccd) ]]; then
    ccd=$(dpkg-query -W -f='${Version}' libccd-dev 2>/dev/null | sed 's/^[0-9]*://; s/[-+~].*//' || true)
    echo "libccd=${ccd:-$(peer_in_build libccd)}"
  fi
  echo "quick=$quick"
} >"$prov"
grep -q '^bullet=' "$prov" || note "Bullet not found (apt-get install libbullet-dev): its columns are left out"
grep -q '^ode=' "$prov" || note "ODE not found (apt-get install libode-dev): its columns are left out"
grep -q '^libccd=' "$prov" || note "libccd not found (apt-get install libccd-dev): its columns are left out"
say "    machine: $(sed -n 's/^machine=//p' "$prov"), $(nproc) cores; $(sed -n 's/^cxx=//p' "$prov");" \
  "peers: $(grep -E '^(bullet|ode|libccd)=' "$prov" | tr '\n' ' ')"

# matplotlib: Debian's python3-matplotlib is seen by /usr/bin/python3, often
# not by a python3 found earlier on PATH.
plot_python=""
for candidate in /usr/bin/python3 python3; do
  if command -v "$candidate" >/dev/null && "$candidate" -c 'import matplotlib' 2>/dev/null; then
    plot_python=$candidate
    break
  fi
done
if [[ -z $plot_python ]]; then
  note "matplotlib not found (apt-get install python3-matplotlib): the PNGs are not redrawn"
fi

# ---- the steps ------------------------------------------------------------------
bin=$build/bench
quick_flag=()
if ((quick)); then quick_flag=(--quick); fi

# update STEP [bench_docs.py update options]: rewrites STEP's blocks and provenance.
update() {
  local step=$1
  shift
  "${docs_tool[@]}" update --step "$step" --root "$dest" --prov "$prov" --date "$(date +%F)" "$@" >>"$log"
}
# plot SCRIPT ARGS... PNG: draws a figure; returns 1 if there is no matplotlib
# to draw it with, and fails the step if the script fails.
plot() {
  [[ -n $plot_python ]] || return 1
  if ! "$plot_python" "$@" >>"$log" 2>&1; then
    say "    $1 failed (see the log)" >&2
    exit 1
  fi
}
# place TEMPORARY FILE: moves a finished output into place.
place() { mv "$1" "$dest/$2"; }

step_compile_time() {
  if ! "$python" tools/amalgamate.py --check >/dev/null 2>&1; then
    note "single_include/ differs from include/ (python3 tools/amalgamate.py regenerates it):" \
      "the 'single' row measures the checked-in file"
  fi
  local args=()
  if ((quick)); then args=(--runs 1 --compilers g++); fi
  "$python" bench/compile_time/compile_time.py "${args[@]}" >"$work/compile_time.md" 2>>"$log"
  cat "$work/compile_time.md" >>"$log"
  say "    $(tail -n 1 "$work/compile_time.md")"
  update compile_time --input "compile_time=$work/compile_time.md"
}

step_particles() {
  "$bin/particles/particles" "${quick_flag[@]}" >"$work/particles.csv" 2>>"$log"
  place "$work/particles.csv" docs/particles_benchmark.csv
  update particles
}

step_speed_vs_error() {
  "$bin/speed_vs_error/speed_vs_error" "${quick_flag[@]}" >"$work/speed_vs_error.csv" 2>>"$log"
  place "$work/speed_vs_error.csv" docs/speed_vs_error.csv
  local plotted=()
  plot bench/speed_vs_error/plot.py "$dest/docs/speed_vs_error.csv" "$dest/docs/speed_vs_error.png" ||
    plotted=(--no-plots)
  update speed_vs_error "${plotted[@]}"
}

step_rigid_motion() {
  "$bin/rigid_motion/rigid_motion" "${quick_flag[@]}" >"$work/rigid_motion.csv" 2>>"$log"
  "$bin/rigid_motion/rigid_motion_speed_vs_error" "${quick_flag[@]}" >"$work/rigid_motion_speed_vs_error.csv" 2>>"$log"
  place "$work/rigid_motion.csv" docs/rigid_motion.csv
  place "$work/rigid_motion_speed_vs_error.csv" docs/rigid_motion_speed_vs_error.csv
  local plotted=()
  plot bench/rigid_motion/plot.py "$dest/docs/rigid_motion.csv" "$dest/docs/rigid_motion_speed_vs_error.csv" \
    "$dest/docs/rigid_motion.png" || plotted=(--no-plots)
  update rigid_motion "${plotted[@]}"
}

step_broadphase() {
  "$bin/broadphase/broadphase" "${quick_flag[@]}" >"$work/broadphase.csv" 2>>"$log"
  place "$work/broadphase.csv" docs/broadphase.csv
  local plotted=()
  plot bench/broadphase/plot.py "$dest/docs/broadphase.csv" "$dest/docs/broadphase.png" || plotted=(--no-plots)
  update broadphase "${plotted[@]}"
}

step_narrowphase() {
  # CSV on stdout, its Markdown table on stderr (kept in the log).
  "$bin/narrowphase/narrowphase" "${quick_flag[@]}" >"$work/narrowphase.csv" 2>>"$log"
  place "$work/narrowphase.csv" docs/narrowphase_bench.csv
  update narrowphase
}

step_joints() {
  local args=(--runs 3)
  if ((quick)); then args=(--n 8 --steps 20 --runs 2); fi
  "$bin/joints/joints" "${args[@]}" >"$work/joints.txt" 2>>"$log"
  cat "$work/joints.txt" >>"$log"
  "${docs_tool[@]}" joints-results "$work/joints.txt" --prov "$prov" --date "$(date +%F)" >"$work/results.txt"
  place "$work/results.txt" bench/joints/results.txt
  update joints
}

step_contact_memory() {
  # Counted allocations: the same on every run of the same build.
  "$bin/contact_memory/contact_memory" "${quick_flag[@]}" >"$work/contact_memory.md" 2>>"$log"
  cat "$work/contact_memory.md" >>"$log"
  update contact_memory --input "contact_memory=$work/contact_memory.md"
}

step_scenes() {
  local args=()
  if ((quick)); then  # the scenes that take seconds, not minutes
    for s in pyramid_nosleep bounce incline incline_static tower10 heavy_on_light cradle; do args+=(--scene "$s"); done
  fi
  # Progress (one line per scene and engine) goes to the log: tail -f it.
  if ! "$bin/scenes/scenes" "${args[@]}" --csv "$work/results.csv" >/dev/null 2>>"$log"; then
    cp "$work/results.csv" "$logs/scenes.partial.csv" 2>/dev/null || true
    say "    a scene failed (see the log); the rows that ran are in $logs/scenes.partial.csv" >&2
    return 1
  fi
  # peers_results.csv: the peers' rows of the same run (docs/world.md cites them).
  awk -F, 'NR == 1 || $1 != "impulse"' "$work/results.csv" >"$work/peers_results.csv"
  place "$work/results.csv" bench/scenes/results.csv
  if (($(wc -l <"$work/peers_results.csv") > 1)); then
    place "$work/peers_results.csv" bench/scenes/peers_results.csv
  else
    note "no peer compiled in: bench/scenes/peers_results.csv left as it was"
  fi
  update scenes
}

# ---- run ------------------------------------------------------------------------
failed=()
summary=()
for step in "${steps[@]}"; do
  log=$logs/$step.log
  : >"$log"
  start=$SECONDS
  say "==> [$(stamp)] $step: ${about[$step]} (log: ${log#"$root"/})"
  set +e
  (
    set -euo pipefail
    "step_$step"
  )
  status=$?
  set -e
  took=$(duration $((SECONDS - start)))
  if ((status == 0)); then
    say "    [$(stamp)] $step done in $took"
    summary+=("$(printf '%-15s %-8s %s' "$step" ok "$took")")
  else
    say "    [$(stamp)] $step FAILED (exit $status) after $took; its outputs were not replaced; see ${log#"$root"/}" >&2
    tail -n 15 "$log" | sed 's/^/      /' >&2
    failed+=("$step")
    summary+=("$(printf '%-15s %-8s %s' "$step" FAILED "$took")")
  fi
done

say ""
say "bench_all: finished $(date '+%F %T'), $(duration $((SECONDS))) in all"
printf '    %s\n' "${summary[@]}"
sed 's/^/    note: /' "$notes"
if ((quick)); then
  "${docs_tool[@]}" check --root "$dest" >/dev/null
  say "    --quick: outputs in ${dest#"$root"/} (docs/ untouched); the blocks' markers are intact"
fi
if ((${#failed[@]})); then
  say "bench_all: failed: ${failed[*]} (rerun with --only $(
    IFS=,
    echo "${failed[*]}"
  ))" >&2
  exit 1
fi
