#!/usr/bin/env python3
"""Makes the README's pictures from the examples' own snapshots.

The examples write their pictures with stored (uncompressed) deflate blocks
(impulse/io/snapshot.hpp), as large as the raw pixels. This runs the given
examples from the repository root and writes each picture to docs/images/,
deflated by Python's zlib (standard library only):

    tools/readme_pictures.py build/release/examples/rube_goldberg
"""
import pathlib
import struct
import subprocess
import sys
import zlib


def chunks(data):
    at = 8
    while at < len(data):
        (n,) = struct.unpack(">I", data[at:at + 4])
        yield data[at + 4:at + 8], data[at + 8:at + 8 + n]
        at += 12 + n


def chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


def recompress(source, target):
    data = source.read_bytes()
    header = b"".join(body for kind, body in chunks(data) if kind == b"IHDR")
    raw = zlib.decompress(b"".join(body for kind, body in chunks(data) if kind == b"IDAT"))
    target.write_bytes(data[:8] + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    print(f"{target}: {len(data)} -> {target.stat().st_size} bytes")


def main():
    root = pathlib.Path(__file__).resolve().parent.parent
    images = root / "docs" / "images"
    images.mkdir(parents=True, exist_ok=True)
    for program in sys.argv[1:]:
        name = pathlib.Path(program).name
        subprocess.run([program], cwd=root, check=True, stdout=subprocess.DEVNULL)
        recompress(root / "out" / f"{name}.png", images / f"{name}.png")


if __name__ == "__main__":
    main()
