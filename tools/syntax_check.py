#!/usr/bin/env python3
"""Compile some of a build's translation units with -fsyntax-only.

Reads BUILD/compile_commands.json (CMake: -DCMAKE_EXPORT_COMPILE_COMMANDS=ON)
and runs the command of every source under one of the given folders with
its object output dropped and -fsyntax-only added: every error and warning
the compiler's front end gives (and -Werror turns into errors), with no
code generated or optimised, in a fraction of a full build's time. CI
checks the benchmarks this way with clang, whose optimised build it does not
need, while g++ builds and links them.

Usage: tools/syntax_check.py BUILD FOLDER... [--jobs N]
Exits 1 if any file fails, after printing its diagnostics.
"""
import argparse
import concurrent.futures
import json
import os
import pathlib
import shlex
import subprocess
import sys
import time


def syntax_only(entry: dict) -> list:
    """The entry's command with -fsyntax-only and without -o FILE or a launcher."""
    words = entry["arguments"] if "arguments" in entry else shlex.split(entry["command"])
    if pathlib.Path(words[0]).name == "ccache":
        words = words[1:]
    out, skip = [], False
    for word in words:
        if skip:
            skip = False
        elif word == "-o":
            skip = True
        elif not word.startswith(("-MD", "-MF", "-MT", "-MQ")):
            out.append(word)
    return out + ["-fsyntax-only"]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("build", type=pathlib.Path)
    parser.add_argument("folders", nargs="+", type=pathlib.Path)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    args = parser.parse_args()
    entries = json.loads((args.build / "compile_commands.json").read_text(encoding="utf-8"))
    folders = [folder.resolve() for folder in args.folders]
    chosen = [e for e in entries
              if any(pathlib.Path(e["directory"], e["file"]).resolve().is_relative_to(f) for f in folders)]
    if not chosen:
        print("syntax_check: no source under " + ", ".join(map(str, args.folders)), file=sys.stderr)
        return 1
    begin = time.perf_counter()

    def run(entry):
        done = subprocess.run(syntax_only(entry), cwd=entry["directory"], capture_output=True, text=True)
        return entry["file"], done.returncode, done.stdout + done.stderr

    failed = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for file, code, output in pool.map(run, chosen):
            print(f"{'ok  ' if code == 0 else 'FAIL'} {os.path.relpath(file)}", flush=True)
            if code != 0:
                failed += 1
                print(output, end="")
    print(f"syntax_check: {len(chosen) - failed} of {len(chosen)} files compile "
          f"({time.perf_counter() - begin:.0f} s)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
