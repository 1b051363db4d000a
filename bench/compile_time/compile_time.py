#!/usr/bin/env python3
"""Time compiling translation units that use impulse, per compiler, in one run.

For each compiler, compiles to an object file:
  std            the standard headers a world program parses: every <...>
                 that include/impulse/world.hpp reaches, and those of
                 examples/hello_world.cpp; nothing of impulse
  single         #include "impulse/impulse.hpp" from single_include/:
                 everything but io, parsed, nothing instantiated
  hello          examples/hello_world.cpp: creates a world, steps it, prints
  hello extern   the same file with IMPULSE_EXTERN_TEMPLATES=1: the world is
                 declared extern and only parsed (core/extern_templates.hpp)
  instantiate    #include "impulse/instantiate.hpp": the one file of such a
                 program that compiles the default configurations (paid once)
std and single at -O0 (they hold no code to optimise); the others at -O0
and -O2. The rounds are interleaved (every TU once, then again), so that a
change in the machine's load falls on all of them alike; each figure is the
median wall time of --runs rounds, and "× std" its ratio to the std TU of
the same compiler in the same run.

The target: the extern path's TU at -O0 with g++ in at most 1.5 s and at
most 3× the std TU. The last line says whether this run met it.

Usage: python3 bench/compile_time/compile_time.py [--runs N] [--compilers g++,clang++]
Prints a Markdown table (tools/bench_all.sh puts it in docs/performance.md).
"""
import argparse
import pathlib
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
INCLUDE = ROOT / "include"
HELLO = ROOT / "examples" / "hello_world.cpp"
LOCAL = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)
SYSTEM = re.compile(r"^\s*#\s*include\s*<([^>]+)>", re.M)


def standard_headers(start: pathlib.Path) -> list:
    """Every <...> reached from `start` through the project's own headers."""
    seen, found, todo = set(), set(), [start]
    while todo:
        path = todo.pop()
        if path in seen:
            continue
        seen.add(path)
        text = path.read_text(encoding="utf-8")
        found.update(SYSTEM.findall(text))
        for name in LOCAL.findall(text):
            for base in (path.parent, INCLUDE):
                candidate = (base / name).resolve()
                if candidate.is_file():
                    todo.append(candidate)
                    break
    return sorted(found)


def translation_units() -> list:
    """(name, source text, extra flags, optimisation levels)."""
    std = sorted(set(standard_headers(INCLUDE / "impulse" / "world.hpp")) | set(SYSTEM.findall(HELLO.read_text())))
    hello = HELLO.read_text(encoding="utf-8")
    modular = ["-I", str(INCLUDE)]
    return [
        ("std", "".join(f"#include <{h}>\n" for h in std), [], ["-O0"]),
        ("single", '#include "impulse/impulse.hpp"\n', ["-I", str(ROOT / "single_include")], ["-O0"]),
        ("hello", hello, modular, ["-O0", "-O2"]),
        ("hello extern", hello, modular + ["-DIMPULSE_EXTERN_TEMPLATES=1"], ["-O0", "-O2"]),
        ("instantiate", '#include "impulse/instantiate.hpp"\n', modular + ["-DIMPULSE_EXTERN_TEMPLATES=1"],
         ["-O0", "-O2"]),
    ]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--compilers", default="g++,clang++")
    args = parser.parse_args()
    compilers = [c for c in args.compilers.split(",") if shutil.which(c)]
    if not compilers:
        sys.exit("compile_time: none of the compilers was found")
    units = translation_units()
    met = None
    print("| compiler | TU | flags | median s | × std |")
    print("| --- | --- | --- | ---: | ---: |")
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(tmp)
        for compiler in compilers:
            banner = subprocess.run([compiler, "--version"], capture_output=True, text=True).stdout.splitlines()[0]
            number = re.search(r"\d+\.\d+\.\d+", banner)
            version = f"{pathlib.Path(compiler).name} {number.group(0) if number else '?'}"
            jobs = []
            for name, source, flags, levels in units:
                path = work / (re.sub(r"\W", "_", name) + ".cpp")
                path.write_text(source, encoding="utf-8")
                for level in levels:
                    command = [compiler, "-std=c++20", level, *flags, "-c", str(path), "-o", str(work / "tu.o")]
                    jobs.append((name, level, command))
            times = {(name, level): [] for name, level, _ in jobs}
            for _ in range(args.runs):
                for name, level, command in jobs:
                    begin = time.perf_counter()
                    subprocess.run(command, check=True)
                    times[(name, level)].append(time.perf_counter() - begin)
            std = statistics.median(times[("std", "-O0")])
            for (name, level), samples in times.items():
                seconds = statistics.median(samples)
                print(f"| {version} | {name} | {level} | {seconds:.2f} | {seconds / std:.1f} |", flush=True)
                if compiler.startswith("g++") and name == "hello extern" and level == "-O0":
                    met = seconds <= 1.5 and seconds <= 3 * std
    print(f"\nMedians of {args.runs} interleaved rounds; \"× std\" is the time over the std TU's, same compiler, "
          "same run.")
    if met is not None:
        print(f"Target (g++, hello extern, -O0: at most 1.5 s and 3× std): {'met' if met else 'NOT met'}.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
