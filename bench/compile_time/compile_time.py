#!/usr/bin/env python3
"""Time compiling a translation unit that includes impulse.

For g++ and clang++ at -O0 and -O2, compiles (to an object file):
  empty       an empty translation unit: the compiler's own start-up cost
  modular     #include "impulse/impulse.hpp" from include/
  single      #include "impulse/impulse.hpp" from single_include/
  single+use  the single header plus code that instantiates the math types
              for float and double
Each is compiled --runs times (default 7); the median wall time is reported,
with the header's own cost (median minus the empty TU's) beside it. The
machine is shared, so read the column of differences, not a lone figure.

Usage: python3 bench/compile_time/compile_time.py [--runs N] [--compilers g++,clang++]
"""
import argparse
import os
import pathlib
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]

USE = r"""
#include "impulse/impulse.hpp"
template <class T> T exercise(T s) {
  using namespace impulse;
  vec3<T> a{s, 2, 3}, b{1, s, 0};
  quat<T> q = quat<T>::from_axis_angle(normalize(a), s);
  q = integrate(q, cross(a, b), T(0.01));
  mat3<T> m = to_mat3(q) * skew(b) + outer(a, b);
  aabb<T> box = transform_aabb(aabb<T>{a, a + b}, transform<T>{b, q});
  return dot(rotate(q, a), b) + determinant(inverse(m + mat3<T>::identity())) +
         surface_area(box) + length(a - b);
}
float use_float(float s) { return exercise(s); }
double use_double(double s) { return exercise(s); }
"""

SOURCES = {
    "empty": ("", []),
    "modular": ('#include "impulse/impulse.hpp"\n', ["-I", str(ROOT / "include")]),
    "single": ('#include "impulse/impulse.hpp"\n', ["-I", str(ROOT / "single_include")]),
    "single+use": (USE, ["-I", str(ROOT / "single_include")]),
}


def time_compile(compiler, opt, source, flags, runs, work):
    path = work / "tu.cpp"
    path.write_text(source)
    command = [compiler, "-std=c++20", opt, *flags, "-c", str(path), "-o", str(work / "tu.o")]
    times = []
    for _ in range(runs):
        begin = time.perf_counter()
        subprocess.run(command, check=True)
        times.append(time.perf_counter() - begin)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--compilers", default="g++,clang++")
    args = parser.parse_args()
    compilers = [c for c in args.compilers.split(",") if shutil.which(c)]
    if not compilers:
        sys.exit("compile_time: none of the compilers was found")
    print(f"| compiler | flags | TU | median s | minus empty TU s |")
    print(f"| --- | --- | --- | ---: | ---: |")
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(tmp)
        for compiler in compilers:
            version = subprocess.run([compiler, "--version"], capture_output=True,
                                     text=True).stdout.splitlines()[0]
            for opt in ("-O0", "-O2"):
                empty = None
                for name, (source, flags) in SOURCES.items():
                    seconds = time_compile(compiler, opt, source, flags, args.runs, work)
                    if empty is None:
                        empty = seconds
                    print(f"| {version} | {opt} | {name} | {seconds:.3f} | {seconds - empty:.3f} |",
                          flush=True)
    print(f"\n{args.runs} runs each, median wall time; {os.cpu_count()} cores, shared machine.")


if __name__ == "__main__":
    main()
