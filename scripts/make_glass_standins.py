#!/usr/bin/env python3
"""Writes the glass stand-in scenes into experiments/scenes/ (run from anywhere):

  glass-red-slab.json       a red glass slab (KHR_materials_transmission 1, ior 1.5) over a white
                            floor under a spot light: its shadow is partial and red
  glass-tinted-medium.json  a clear glass pane over a box of tinted absorbing medium (extinction
                            per channel) over the floor: Fresnel-grey glass, then a coloured medium

The scenes are generated, not copied, so that what they hold is stated here in one place; the
tests (tests/strategies/shadow/test_glass_shadows.cpp) load the committed files.
"""
import json
import pathlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
OUT = ROOT / "experiments" / "scenes"

FLOOR = {"name": "floor",
         "mesh": {"generator": "box", "min": [-3, -0.05, -3], "max": [3, 0, 3]},
         "material": {"color": [0.9, 0.9, 0.9], "specular": 0.0}}
CAMERA = {"position": [0.0, 2.2, 4.0], "target": [0.0, 0.3, 0.0], "fov": 45, "width": 320,
          "height": 240}
SPOT = {"type": "spot", "position": [0.3, 3.5, 0.2], "direction": [-0.08, -1.0, -0.05],
        "cutoff": 40, "penumbra": 3, "intensity": 12.0}


def glass(color, ior=1.5):
    return {"color": color, "alpha": 0.0, "transmission": 1.0, "ior": ior, "specular": 0.6,
            "shininess": 200}


def scene(objects):
    return {"camera": CAMERA, "background": [0.0, 0.0, 0.0], "lights": [SPOT],
            "objects": [FLOOR] + objects}


def main():
    red_slab = scene([{"name": "red glass slab",
                       "mesh": {"generator": "box", "min": [-0.6, 0.6, -0.4],
                                "max": [0.6, 0.75, 0.4]},
                       "material": glass([1.0, 0.15, 0.15])}])
    tinted_medium = scene([
        {"name": "clear glass pane",
         "mesh": {"generator": "box", "min": [-0.8, 1.2, -0.6], "max": [0.8, 1.28, 0.6]},
         "material": glass([1.0, 1.0, 1.0])},
        {"name": "tinted medium",
         "mesh": {"generator": "box", "min": [-0.5, 0.3, -0.4], "max": [0.5, 0.8, 0.4]},
         "material": {"alpha": 0.0},
         "interior": {"type": "constant", "sigma": [0.3, 2.0, 3.5]}}])
    for name, content in (("glass-red-slab.json", red_slab),
                          ("glass-tinted-medium.json", tinted_medium)):
        path = OUT / name
        path.write_text(json.dumps(content, indent=1) + "\n")
        print(path.relative_to(ROOT))


if __name__ == "__main__":
    main()
