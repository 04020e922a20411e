#!/usr/bin/env python3
"""Writes the scenes of the `scale` suite into experiments/scenes/scale/ (run from anywhere).

Each file is experiments/scenes/knecht-fig56.json with one axis grown and everything else left
as it is, so that a row differs from its neighbours in one cost only. The number at the end of
each file name is the axis's value (what the suite's line plots put on x):

  knecht-casters-N.json   N shadow-casting triangles in all: the bunny midpoint-subdivided k
                          times (3,674 * 4^k triangles; its shape, hence every shadow, is the
                          same) beside the 7,728 triangles of the other objects; k = 0, 2, 3, 4, 5
  knecht-pixels-N.json    N pixels: the camera at 720x480, 1920x1080 and 3840x2160
  knecht-lights-N.json    N lights (1, 8, 32, 128): two rings around the scene, spot and omni
                          alternating, spots aimed at the scene's centre; the total intensity of
                          each kind stays that of the one spot, so exposure is comparable
  knecht-volume-N.json    both volumes (CT phantom and smoke) at N^3 samples: 64, 128, 256, 512

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


def ring_lights(n):
    """n lights on two rings (radius 4.2 at height 4.4, radius 3.6 at height 2.8), evenly spaced
    in angle, spot and omni alternating; n = 1 is knecht-fig56's spot itself."""
    if n == 1:
        return base()["lights"]
    spots, omnis = (n + 1) // 2, n // 2
    lights = []
    for i in range(n):
        angle = 2.0 * math.pi * (i + 0.5 * (i % 2)) / n
        radius, height = (4.2, 4.4) if i % 4 < 2 else (3.6, 2.8)
        position = [round(radius * math.cos(angle), 5), height,
                    round(radius * math.sin(angle), 5)]
        if i % 2 == 0:
            d = [TARGET[a] - position[a] for a in range(3)]
            length = math.sqrt(sum(x * x for x in d))
            lights.append({"type": "spot", "position": position,
                           "direction": [round(x / length, 5) for x in d], "cutoff": 32,
                           "penumbra": 4, "intensity": round(22.0 / spots, 5)})
        else:
            lights.append({"type": "omni", "position": position,
                           "intensity": round(8.0 / omnis, 5)})
    return lights


def lights(n):
    scene = base()
    scene["lights"] = ring_lights(n)
    return n, scene


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
    for k in (0, 2, 3, 4, 5):
        count, scene = casters(k)
        write("knecht-casters-%d.json" % count, scene)
    for w, h in ((720, 480), (1920, 1080), (3840, 2160)):
        count, scene = pixels(w, h)
        write("knecht-pixels-%d.json" % count, scene)
    for n in (1, 8, 32, 128):
        count, scene = lights(n)
        write("knecht-lights-%d.json" % count, scene)
    for n in (64, 128, 256, 512):
        count, scene = volume(n)
        write("knecht-volume-%d.json" % count, scene)


if __name__ == "__main__":
    main()
