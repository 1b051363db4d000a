#!/usr/bin/env python3
"""Check that the README's first program is examples/hello_world.cpp.

The README shows the example without its opening comment; CI builds and
runs the example as a test, so this keeps the README's code compiled and
true. Exits 1, saying where they part, if they differ.
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent


def main() -> int:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    block = re.search(r"```cpp\n(.*?)```", readme, re.S)
    if not block:
        print("check_readme: the README has no C++ block", file=sys.stderr)
        return 1
    example = (ROOT / "examples" / "hello_world.cpp").read_text(encoding="utf-8")
    lines = example.splitlines(keepends=True)
    while lines and lines[0].startswith("//"):
        lines.pop(0)
    if block.group(1) != "".join(lines):
        shown, real = block.group(1).splitlines(), "".join(lines).splitlines()
        at = next((i for i, (a, b) in enumerate(zip(shown, real)) if a != b), min(len(shown), len(real)))
        print(f"check_readme: the README's first program differs from examples/hello_world.cpp "
              f"at its line {at + 1}:\n  README:  {shown[at] if at < len(shown) else '(ends)'}\n"
              f"  example: {real[at] if at < len(real) else '(ends)'}", file=sys.stderr)
        return 1
    print("check_readme: the README's first program is examples/hello_world.cpp")
    return 0


if __name__ == "__main__":
    sys.exit(main())
