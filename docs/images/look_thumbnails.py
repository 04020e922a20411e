#!/usr/bin/env python3
"""Regenerates the before/after thumbnails in docs/images (200x150 PNG) and prints the fraction
of pure-white pixels of each render, of the whole image and of the pixels that are not
background. --size 640x480 measures at the default resolution. Two sets:

  --set looks (the default): the stand-ins of look_standins.py (beside it) and the bunny from
          experiments/assets/ (the lamp's clipping was the symptom of the appearance work);
          before: a binary built from the code before that work (commit c79d56e), at its
          defaults; after: this tree's binary at its defaults (the bunny with --ground, a
          flag the old binary lacks);
  --set samples: the sample-model stand-ins of feature_standins.py (TransmissionTest,
          GlassVaseFlowers, DamagedHelmet, Duck), both binaries at their defaults (
          before = the code before it, after = this tree);
  --set shadows: the shadow stand-ins of feature_standins.py (a glass pane coloured by its
          texture, a red glass cube and a BLEND quad resting on the ground, a folded cloth under
          glass, opaque and translucent, a glass pane over grey BLEND quads), both binaries at
          their defaults.

Usage: look_thumbnails.py BEFORE_DEEPVOX AFTER_DEEPVOX [--set looks|samples|shadows] [--size WxH]
                          [--out docs/images]
(scripts/make-look-thumbnails.sh runs it.)
"""
import argparse
import os
import struct
import subprocess
import sys
import tempfile
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import feature_standins  # noqa: E402
import look_standins  # noqa: E402


def read_png_rgb(path):
    """Pixels of an 8-bit RGB PNG as written by deepvox (non-interlaced): a list of bytes rows."""
    data = open(path, "rb").read()
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour == 2, "expected 8-bit RGB"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride, rows, prev = zlib.decompress(idat), width * 3, [], bytearray(width * 3)
    for y in range(height):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - 3] if i >= 3 else 0
            b, c = prev[i], prev[i - 3] if i >= 3 else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return width, height, rows


def white_fractions(path):
    """Fractions of pure-white pixels among all pixels and among the scene's own (the
    background is black)."""
    width, height, rows = read_png_rgb(path)
    pixels = [bytes(row[3 * x:3 * x + 3]) for row in rows for x in range(width)]
    white = sum(1 for p in pixels if p == b"\xff\xff\xff")
    covered = sum(1 for p in pixels if p != b"\x00\x00\x00")
    return white / len(pixels), white / max(covered, 1)


def render(binary, scene, out, size, extra=()):
    w, h = size.split("x")
    subprocess.run([binary, "render", scene, "--backend", "cpu", "--out", out, "--width", w,
                    "--height", h, *extra], check=True, stdout=subprocess.DEVNULL)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--set", default="looks", choices=("looks", "samples", "shadows"))
    parser.add_argument("--size", default="200x150")
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "images"))
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        look_standins.lamp(os.path.join(tmp, "lamp.gltf"))
        look_standins.transmission(os.path.join(tmp, "transmission.gltf"))
        look_standins.attenuation(os.path.join(tmp, "attenuation.gltf"))
        bunny = os.path.join(ROOT, "experiments", "assets", "meshes", "stanford-bunny-lowres.obj")
        scenes = [("lamp", os.path.join(tmp, "lamp.gltf"), ()),
                  ("transmission", os.path.join(tmp, "transmission.gltf"), ()),
                  ("attenuation", os.path.join(tmp, "attenuation.gltf"), ()),
                  ("bunny", bunny, ("--ground",))]
        if args.set in ("samples", "shadows"):
            chosen = feature_standins.SAMPLES if args.set == "samples" else feature_standins.SHADOWS
            feature_standins.write_all(chosen, tmp)
            scenes = [(name[:-len(".gltf")], os.path.join(tmp, name), ()) for name in chosen]
        for name, scene, after_flags in scenes:
            for when, binary, flags in (("before", args.before, ()),
                                        ("after", args.after, after_flags)):
                out = os.path.join(args.out, f"{name}-{when}.png")
                render(binary, scene, out, args.size, flags)
                everywhere, on_scene = white_fractions(out)
                print(f"{name:13s} {when:6s} pure white: {100 * everywhere:5.1f} % of the image, "
                      f"{100 * on_scene:5.1f} % of the non-background pixels  {out}")


if __name__ == "__main__":
    main()
