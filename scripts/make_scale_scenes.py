#!/usr/bin/env python3
"""Writes the scenes of the `scale` suite into experiments/scenes/scale/ (run from anywhere).

Each file is experiments/scenes/knecht-fig56.json with one axis grown and everything else left
as it is, so that a row differs from its neighbours in one cost only. The number at the end of
each file name is the axis's value (what the suite's line plots put on x):

  knecht-casters-N.json     N shadow-casting triangles in all: the bunny midpoint-subdivided k
                            times (3,674 * 4^k triangles; its shape, hence every shadow, is the
                            same) beside the 7,728 triangles of the other objects; k = 0 .. 5
  knecht-pixels-N.json      N pixels: the camera at 480x320 .. 3600x2400, all 3:2 (the aspect
                            of knecht-fig56's 720x480), so the view is the same and only the
                            pixel density grows
  knecht-spot-faces-N.json  N spot lights (1, 2, 4, .. 128; a spot is one map face)
  knecht-omni-faces-N.json  N / 6 omni lights (1, 2, 4, .. 128; an omni light is six map faces)
                            Lights stand on two rings around the scene, alternating between
                            them, spots aimed at the scene's centre; the total intensity of each
                            kind is that of knecht-fig56's one spot (spots) or a fixed 8 (omnis),
                            so exposure is comparable along each axis. One kind per file, so
                            the suite fits spots and omnis apart, both against map faces
  knecht-volume-N.json      both volumes (CT phantom and smoke) at N^3 samples: 64 .. 512

Generated, not copied, so that what they hold is stated here in one place; meshes and volumes
come from deepvox's generators when the scene loads (nothing is downloaded).
"""
import copy
import json
import math
import pathlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
BASE = ROOT / "experiments" / "scenes" / "knecht-fig56.json"
OUT = ROOT / "experiments" / "scenes" / "scale"

BUNNY_TRIANGLES = 3674  # `deepvox info experiments/scenes/knecht-fig56.json`
OTHER_TRIANGLES = 11402 - BUNNY_TRIANGLES
TARGET = [0.0, 0.4, 0.0]


def base():
    return json.loads(BASE.read_text())


def write(name, scene):
    path = OUT / name
    path.write_text(json.dumps(scene, indent=1) + "\n")
    print(path.relative_to(ROOT))


def casters(k):
    scene = base()
    bunny = next(o for o in scene["objects"] if o["name"] == "bunny")
    if k > 0:
        bunny["mesh"]["subdivide"] = {"scheme": "midpoint", "iterations": k}
    return OTHER_TRIANGLES + BUNNY_TRIANGLES * 4 ** k, scene


def pixels(width, height):
    scene = base()
    scene["camera"]["width"], scene["camera"]["height"] = width, height
    return width * height, scene


def ring_lights(n, kind):
    """n lights of one kind ("spot" or "omni") on two rings (radius 4.2 at height 4.4, radius
    3.6 at height 2.8), evenly spaced in angle, consecutive lights on alternate rings; one spot
    is knecht-fig56's spot itself."""
    if n == 1 and kind == "spot":
        return base()["lights"]
    lights = []
    for i in range(n):
        angle = 2.0 * math.pi * (i + 0.5) / n
        radius, height = (4.2, 4.4) if i % 2 == 0 else (3.6, 2.8)
        position = [round(radius * math.cos(angle), 5), height,
                    round(radius * math.sin(angle), 5)]
        if kind == "spot":
            d = [TARGET[a] - position[a] for a in range(3)]
            length = math.sqrt(sum(x * x for x in d))
            lights.append({"type": "spot", "position": position,
                           "direction": [round(x / length, 5) for x in d], "cutoff": 32,
                           "penumbra": 4, "intensity": round(22.0 / n, 5)})
        else:
            lights.append({"type": "omni", "position": position,
                           "intensity": round(8.0 / n, 5)})
    return lights


def lights(n, kind):
    """The scene with n lights of one kind and its number of map faces."""
    scene = base()
    scene["lights"] = ring_lights(n, kind)
    return n * (6 if kind == "omni" else 1), scene


def volume(n):
    scene = base()
    for v in scene["volumes"].values():
        v["dims"] = [n, n, n]
    # The ray-marching steps of knecht-fig56 are half a cell of its 128^3 grids; keep that.
    for o in scene["objects"]:
        interior = o.get("interior", {})
        if interior.get("type") == "volume":
            interior["step"] = round(interior["step"] * 128.0 / n, 8)
    return n, scene


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    for k in range(6):
        count, scene = casters(k)
        write("knecht-casters-%d.json" % count, scene)
    for w in (480, 720, 1200, 1800, 2400, 3600):
        count, scene = pixels(w, w * 2 // 3)
        write("knecht-pixels-%d.json" % count, scene)
    for kind in ("spot", "omni"):
        for n in (1, 2, 4, 8, 16, 32, 64, 128):
            count, scene = lights(n, kind)
            write("knecht-%s-faces-%d.json" % (kind, count), scene)
    for n in (64, 96, 128, 192, 256, 384, 512):
        count, scene = volume(n)
        write("knecht-volume-%d.json" % count, scene)


if __name__ == "__main__":
    main()
