#!/usr/bin/env python3
"""Generate the single headers in single_include/impulse/ from include/.

Five headers, each a layer over one before it:

  impulse.hpp        the core: everything reachable from include/impulse/impulse.hpp
                     (math, shapes, broad and narrow phase, dynamics, the world,
                     particles). Standard library only.
  impulse_io.hpp     #include "impulse.hpp", then the optional io headers that need
                     nothing but the standard library: io/gltf.hpp (recordings
                     for the viewer), io/particle_recording.hpp, io/shape_mesh.hpp,
                     io/picture.hpp.
  impulse_scene.hpp  #include "impulse_io.hpp", then io/scene.hpp (scene files),
                     which needs nlohmann-json: <nlohmann/json.hpp> stays a
                     system include, found on the include path.
  impulse_thread_pool.hpp  #include "impulse.hpp", then impulse/thread_pool.hpp:
                     a std::thread pool implementing the task hook.
  impulse_character.hpp  #include "impulse.hpp", then impulse/character.hpp:
                     the character controller.
  instantiate.hpp    #include "impulse.hpp", then impulse/instantiate.hpp: the
                     default configurations compiled in the one .cpp file of a
                     program built with IMPULSE_EXTERN_TEMPLATES=1.

io is kept out of the core header so that a program that only steps a world
parses less: io adds <string>, <charconv> and the file writers, and the scene
loader adds <fstream>, <sstream>, <map>, <variant> and nlohmann-json.

In each header, every `#include "..."` of one of the project's own headers is
replaced by that header's text, depth first, so each header appears once and
after everything it includes; a header already inlined in a lower layer is
not repeated. `#pragma once` lines of the inlined files are dropped (each
output has its own), and each system `#include <...>` is kept where it first
appears outside any #if block (in this layer or a lower one). Every header
under include/impulse/ must land in one of them (or be listed in
NOT_INLINED with its reason), or the script stops.
The output is deterministic, so CI regenerates it and fails when a
checked-in copy is stale.

Usage: python3 tools/amalgamate.py [--check] [--output PATH | --output-dir DIR]

  (no option)       write the headers into single_include/impulse/
  --check           write nothing; exit 1 if any checked-in header differs
                    from a fresh build
  --output PATH     the core header only (impulse.hpp), written to PATH (or,
                    with --check, compared with PATH)
  --output-dir DIR  all the headers, written to (or compared with) DIR
"""
import argparse
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
INCLUDE = ROOT / "include"
OUTPUT_DIR = ROOT / "single_include" / "impulse"

# Each layer: its file name, the single header it includes first (None for
# the core; a layer before it in this list), the modular headers it inlines
# (none already in the base or below), and what its first comment says.
LAYERS = [
    ("impulse.hpp", None, ["impulse/impulse.hpp"], [
        "The core: everything reachable from include/impulse/impulse.hpp, standard",
        "library only. The optional io headers are in impulse_io.hpp (recordings,",
        "pictures) and impulse_scene.hpp (scene files, needs nlohmann-json): kept",
        "out of here so that a program that only steps a world parses less.",
    ]),
    ("impulse_io.hpp", "impulse.hpp", [
        "impulse/io/gltf.hpp",
        "impulse/io/particle_recording.hpp",
        "impulse/io/shape_mesh.hpp",
        "impulse/io/picture.hpp",
    ], [
        "The optional io headers that need only the standard library: io/gltf.hpp",
        "(runs recorded as .glb for the viewer), io/particle_recording.hpp (.ipr),",
        "io/shape_mesh.hpp and io/picture.hpp (PNG pictures). Includes the core",
        "single header impulse.hpp, which must sit beside this file. Kept out of",
        "impulse.hpp so that a program that only steps a world does not parse them",
        "(<string>, <charconv>, the file writers).",
    ]),
    ("impulse_scene.hpp", "impulse_io.hpp", ["impulse/io/scene.hpp"], [
        "The scene loader, io/scene.hpp (scene files in JSON: docs/scenes.md). Needs",
        "nlohmann-json: <nlohmann/json.hpp> must be on the include path (Debian:",
        "nlohmann-json3-dev). Includes impulse_io.hpp and impulse.hpp, which must",
        "sit beside this file.",
    ]),
    ("impulse_thread_pool.hpp", "impulse.hpp", ["impulse/thread_pool.hpp"], [
        "impulse::thread_pool, a small std::thread pool that implements the task",
        "hook (core/task_system.hpp) for programs without a scheduler of their own.",
        "Includes impulse.hpp, which must sit beside this file. Kept out of",
        "impulse.hpp so that a program that brings its own scheduler, or runs on",
        "one thread, never parses <thread>, <mutex> and <condition_variable>.",
    ]),
    ("impulse_character.hpp", "impulse.hpp", ["impulse/character.hpp"], [
        "impulse::character, a character controller: an upright capsule that walks,",
        "slides, climbs steps and walkable slopes, falls, rides platforms, pushes",
        "bodies and crouches, moved by the world's shape casts. Includes",
        "impulse.hpp, which must sit beside this file. Kept out of impulse.hpp so",
        "that a program without a character does not parse it.",
    ]),
    ("instantiate.hpp", "impulse.hpp", ["impulse/instantiate.hpp"], [
        "Compiles the default configurations' world, rigid-body system and particle",
        "system: include it in exactly one .cpp file of a program whose files are",
        "built with IMPULSE_EXTERN_TEMPLATES=1, which then only parse them",
        "(core/extern_templates.hpp). Includes impulse.hpp, which must sit beside it.",
    ]),
]
CORE = LAYERS[0][0]
# The layers whose code steps a simulation. Defining
# IMPULSE_CROSS_PLATFORM_DETERMINISM before including them turns off the
# fusing of multiplies and adds for their own code alone
# (core/floating_point.hpp): clang's scoped `fp contract(off)`, GCC's
# optimize options (with no SLP vectorisation, which fuses a quaternion
# product's terms even with contraction off) for the functions defined in
# between. Each system header
# is included outside that region, so the standard library keeps the
# program's own flags.
CONTRACTION_OFF = {"impulse.hpp", "impulse_character.hpp"}
CONTRACTION_MACROS = """
// IMPULSE_CROSS_PLATFORM_DETERMINISM: this header's code is compiled with no
// fused multiply-add contraction, whatever the program's flags, so that a
// config with cross_platform_determinism steps to the same bits in every
// build (docs/world.md). With GCC, the program's own functions then do not
// inline impulse's (their options differ).
#if defined(IMPULSE_CROSS_PLATFORM_DETERMINISM) && defined(__clang__)
#define IMPULSE_DETAIL_CONTRACTION_OFF _Pragma("float_control(push)") _Pragma("clang fp contract(off)")
#define IMPULSE_DETAIL_CONTRACTION_RESTORED _Pragma("float_control(pop)")
#elif defined(IMPULSE_CROSS_PLATFORM_DETERMINISM) && defined(__GNUC__)
#define IMPULSE_DETAIL_CONTRACTION_OFF \\
  _Pragma("GCC push_options") _Pragma("GCC optimize(\\"fp-contract=off\\", \\"no-tree-slp-vectorize\\")")
#define IMPULSE_DETAIL_CONTRACTION_RESTORED _Pragma("GCC pop_options")
#else
#define IMPULSE_DETAIL_CONTRACTION_OFF
#define IMPULSE_DETAIL_CONTRACTION_RESTORED
#endif
"""
# Modular headers deliberately in no single header, with the reason.
NOT_INLINED: set = set()

LOCAL_INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
SYSTEM_INCLUDE = re.compile(r"^\s*#\s*include\s*<([^>]+)>")
PRAGMA_ONCE = re.compile(r"^\s*#\s*pragma\s+once\b")
CONDITIONAL_OPEN = re.compile(r"^\s*#\s*if")  # #if, #ifdef, #ifndef
CONDITIONAL_CLOSE = re.compile(r"^\s*#\s*endif\b")


def resolve(name: str, including: pathlib.Path) -> pathlib.Path:
    """A quoted include is looked up beside the including file, then in include/."""
    for base in (including.parent, INCLUDE):
        candidate = (base / name).resolve()
        if candidate.is_file():
            return candidate
    sys.exit(f"amalgamate: {including.relative_to(ROOT)}: cannot find \"{name}\"")


def inline(path: pathlib.Path, done: set, system: set, out: list, contraction_off: bool) -> None:
    done.add(path)
    out.append(f"// ---- begin {path.relative_to(INCLUDE).as_posix()} ----\n")
    depth = 0  # preprocessor conditional nesting within this file
    for line in path.read_text(encoding="utf-8").splitlines(keepends=True):
        if PRAGMA_ONCE.match(line):
            continue
        if CONDITIONAL_OPEN.match(line):
            depth += 1
        elif CONDITIONAL_CLOSE.match(line):
            depth -= 1
        local = LOCAL_INCLUDE.match(line)
        if local:
            target = resolve(local.group(1), path)
            if target not in done:
                inline(target, done, system, out, contraction_off)
            continue
        system_header = SYSTEM_INCLUDE.match(line)
        if system_header:
            if system_header.group(1) in system:
                continue
            if depth == 0:  # one inside #if may be skipped, so it does not count as seen
                system.add(system_header.group(1))
            if contraction_off:
                out.extend(["IMPULSE_DETAIL_CONTRACTION_RESTORED\n", line, "IMPULSE_DETAIL_CONTRACTION_OFF\n"])
                continue
        out.append(line)
    out.append(f"// ---- end {path.relative_to(INCLUDE).as_posix()} ----\n")


def amalgamate() -> dict:
    """Every single header's text, by file name, core first."""
    version = (ROOT / "VERSION").read_text(encoding="utf-8").strip()
    # What each single header holds, with what it includes: the modular
    # headers inlined, and the system headers included outside any #if.
    holds: dict = {}
    texts = {}
    for name, base, entries, about in LAYERS:
        done, system = (set(holds[base][0]), set(holds[base][1])) if base else (set(), set())
        out = [
            "// impulse — header-only C++20 library for real-time 3D physics.\n",
            f"// Version {version}. MIT licence: see LICENSE in the impulse repository.\n",
            "//\n",
            f"// single_include/impulse/{name}: single-header build, generated by\n",
            "// tools/amalgamate.py from include/. Do not edit: change the modular\n",
            "// headers and regenerate.\n",
            "//\n",
            *(f"// {line}\n" for line in about),
            "#pragma once\n",
        ]
        if base is None:
            out.append(CONTRACTION_MACROS)
        else:
            out.append(f'\n#include "{base}"\n\n')
        contraction_off = name in CONTRACTION_OFF
        if contraction_off:
            out.append("IMPULSE_DETAIL_CONTRACTION_OFF\n")
        for entry in entries:
            path = (INCLUDE / entry).resolve()
            if path not in done:
                inline(path, done, system, out, contraction_off)
        if contraction_off:
            out.append("IMPULSE_DETAIL_CONTRACTION_RESTORED\n")
        texts[name] = "".join(out)
        holds[name] = (done, system)
    inlined = set().union(*(done for done, _ in holds.values()))
    missing = sorted(name for name in (p.relative_to(INCLUDE).as_posix()
                                       for p in (INCLUDE / "impulse").rglob("*.hpp")
                                       if p.resolve() not in inlined)
                     if name not in NOT_INLINED)
    if missing:
        sys.exit("amalgamate: in no single header: " + ", ".join(missing)
                 + "\n  (add each to a layer in tools/amalgamate.py's LAYERS, or to NOT_INLINED with its reason)")
    return texts


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--output", type=pathlib.Path,
                       help=f"the core header ({CORE}) only, at this path")
    where.add_argument("--output-dir", type=pathlib.Path, default=OUTPUT_DIR,
                       help="the directory of all the headers (default: the checked-in one)")
    parser.add_argument("--check", action="store_true",
                        help="write nothing; exit 1 if an output file differs from a fresh build")
    args = parser.parse_args()
    texts = amalgamate()
    if args.output is not None:
        targets = {args.output: texts[CORE]}
    else:
        targets = {args.output_dir / name: text for name, text in texts.items()}
    if args.check:
        stale = [path for path, text in targets.items()
                 if (path.read_text(encoding="utf-8") if path.exists() else "") != text]
        for path in stale:
            print(f"amalgamate: {path} is stale; run python3 tools/amalgamate.py",
                  file=sys.stderr)
        return 1 if stale else 0
    for path, text in targets.items():
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
