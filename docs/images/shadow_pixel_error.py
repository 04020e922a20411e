#!/usr/bin/env python3
"""Measures how far a shadow method's image is from the exact oracle's: renders SCENE with
`--shadows reference` and then once per given flag set (at `render`'s defaults plus those
flags), and prints, per flag set, the share of pixels where some channel differs from the
reference by more than 8/255 (and by more than 2/255). This is the number the docs quote for
TransmissionTest's cloth (docs/images/feature_standins.py --shadows writes a stand-in).

Usage: shadow_pixel_error.py DEEPVOX SCENE [--size WxH] [--keep DIR] [--] "FLAGS" ["FLAGS" ...]
       e.g. shadow_pixel_error.py build/bin/deepvox cloth.gltf "" "--dsm-res 4096"
An empty FLAGS string is the defaults (`--shadows auto`).
"""
import argparse
import os
import shlex
import struct
import subprocess
import sys
import tempfile
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from look_thumbnails import read_png_rgb  # noqa: E402


def render(binary, scene, out, size, flags):
    w, h = size.split("x")
    subprocess.run([binary, "render", scene, "--backend", "cpu", "--out", out, "--width", w,
                    "--height", h, *flags], check=True, stdout=subprocess.DEVNULL)


def write_png_rgb(path, width, rows):
    """An 8-bit RGB PNG of rows of bytes."""
    raw = b"".join(b"\0" + bytes(row) for row in rows)

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xffffffff))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, len(rows),
                                                                    8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def off_fractions(reference, image, thresholds=(8, 2), marked=None):
    """Shares of pixels where some channel differs by more than each threshold (in 1/255);
    with `marked`, writes the reference there, dimmed, with the pixels off by more than the
    first threshold in red."""
    w0, h0, a = read_png_rgb(reference)
    w1, h1, b = read_png_rgb(image)
    assert (w0, h0) == (w1, h1), "images differ in size"
    counts = [0] * len(thresholds)
    mask = []
    for row_a, row_b in zip(a, b):
        out = bytearray(row_a)
        for x in range(w0):
            d = max(abs(row_a[3 * x + c] - row_b[3 * x + c]) for c in range(3))
            for i, t in enumerate(thresholds):
                counts[i] += d > t
            out[3 * x:3 * x + 3] = (bytes((255, 0, 0)) if d > thresholds[0] else
                                    bytes(v // 3 for v in row_a[3 * x:3 * x + 3]))
        mask.append(out)
    if marked:
        write_png_rgb(marked, w0, mask)
    return [c / (w0 * h0) for c in counts]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("deepvox")
    parser.add_argument("scene")
    parser.add_argument("flags", nargs="+")
    parser.add_argument("--size", default="640x480")
    parser.add_argument("--keep", help="write the images into this folder, and per flag set "
                        "off-N.png: the reference with the pixels off by > 8/255 in red")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        out = args.keep or tmp
        os.makedirs(out, exist_ok=True)
        reference = os.path.join(out, "reference.png")
        render(args.deepvox, args.scene, reference, args.size, ["--shadows", "reference"])
        for i, flags in enumerate(args.flags):
            image = os.path.join(out, f"method-{i}.png")
            render(args.deepvox, args.scene, image, args.size, shlex.split(flags))
            marked = os.path.join(out, f"off-{i}.png") if args.keep else None
            over8, over2 = off_fractions(reference, image, marked=marked)
            print(f"{flags or '(defaults)':40s} off by > 8/255: {100 * over8:6.2f} % of pixels, "
                  f"> 2/255: {100 * over2:6.2f} %")


if __name__ == "__main__":
    main()
