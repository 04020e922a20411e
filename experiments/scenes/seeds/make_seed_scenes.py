#!/usr/bin/env python3
"""Writes the seeds scenes (experiments/scenes/seeds/*.json): stand-ins for the scenes of Knecht 2011
chapter 5, Hadwiger et al. 2006 and Buchacher 2014 that the paper tables of
experiments/papers/ were measured on (which file stands in for which figure, and how it differs:
experiments/scenes/seeds/README.md). Deterministic: run it from anywhere and commit the output;
`make_seed_scenes.py --check` exits 1 if a committed file differs from what it would write."""
import json
import math
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent

# ---------------------------------------------------------------- shared pieces

FLOOR_COLOR = [0.8, 0.8, 0.78]
STEAM_TRANSFER = [{"density": 0.05, "color": [0.9, 0.9, 1.0], "sigma": 0.0},
                  {"density": 0.5, "color": [1.0, 0.95, 0.9], "sigma": 8.0}]
SMOKE_TRANSFER = [{"density": 0.05, "color": [0.6, 0.6, 0.62], "sigma": 0.0},
                  {"density": 0.5, "color": [0.7, 0.7, 0.7], "sigma": 5.0}]
FOG_TRANSFER = [{"density": 0.0, "color": [0.85, 0.85, 0.9], "sigma": 0.4},
                {"density": 0.6, "color": [0.9, 0.9, 0.95], "sigma": 1.5}]
# The CT transfer function of experiments/scenes/ct-phantom.json (phantom densities: shell 1.0, inside 0.2,
# features 0.0..0.4).
CT_TRANSFER = [{"density": 0.0, "color": [1, 1, 1], "sigma": 0.0},
               {"density": 0.15, "color": [0.9, 0.7, 0.6], "sigma": 0.0},
               {"density": 0.2, "color": [0.9, 0.7, 0.6], "sigma": 4.0},
               {"density": 0.35, "color": [1.0, 0.9, 0.6], "sigma": 12.0},
               {"density": 1.0, "color": [1.0, 1.0, 0.95], "sigma": 20.0}]


def floor(x0, z0, x1, z1, name="floor"):
    return {"name": name, "mesh": {"generator": "box", "min": [x0, -0.05, z0], "max": [x1, 0, z1]},
            "material": {"color": FLOOR_COLOR}}


def wall(x0, x1, height, z, name="wall"):
    return {"name": name, "mesh": {"generator": "box", "min": [x0, 0, z - 0.1], "max": [x1, height, z]},
            "material": {"color": [0.85, 0.85, 0.85]}}


def volume_object(name, volume, translate, scale, transfer):
    return {"name": name, "mesh": "volume_bounds", "transform": {"translate": translate, "scale": scale},
            "material": {"alpha": 0.0}, "interior": {"type": "volume", "volume": volume, "transfer": transfer}}


# A teacup of rim radius 0.5 * scale and height 0.8 * scale standing at (x, 0, z), and a steam
# column (the grid "steam": 24 x 48 x 24 samples, 0.49 x 1 x 0.49 units) rising from its rim.
CUP_SCALE = 0.4
STEAM_SCALE = 0.45
STEAM_VOLUME = {"generator": "smoke", "dims": [24, 48, 24], "seed": 12}


def steaming_cup(index, x, z, cup_scale=CUP_SCALE, steam_scale=STEAM_SCALE, volume="steam"):
    rim = 0.8 * cup_scale
    return [{"name": f"cup-{index}", "mesh": {"generator": "cup"},
             "transform": {"translate": [x, 0.0, z], "scale": cup_scale},
             "material": {"color": [0.95, 0.95, 0.9]}},
            volume_object(f"steam-{index}", volume, [x, round(rim + 0.01 + 0.5 * steam_scale, 6), z],
                          steam_scale, STEAM_TRANSFER)]


# A stand-in car (the thesis's VW Beetle and orange car are not available): an opaque body, a
# translucent cabin (the windows cast a lighter shadow, Knecht Fig. 5.1) and four wheels.
def car(prefix, x, z, color, yaw=0.0):
    c, s = math.cos(math.radians(yaw)), math.sin(math.radians(yaw))

    def at(dx, dy, dz):
        return [round(x + c * dx + s * dz, 6), dy, round(z - s * dx + c * dz, 6)]
    parts = [{"name": f"{prefix}-body", "mesh": {"generator": "box", "min": [-0.9, -0.2, -0.4], "max": [0.9, 0.2, 0.4]},
              "transform": {"translate": at(0, 0.35, 0), "rotate": [0, yaw, 0]}, "material": {"color": color}},
             {"name": f"{prefix}-cabin", "mesh": {"generator": "box", "min": [-0.5, -0.18, -0.36], "max": [0.4, 0.18, 0.36]},
              "transform": {"translate": at(-0.05, 0.73, 0), "rotate": [0, yaw, 0]},
              "material": {"color": [0.6, 0.75, 0.85], "alpha": 0.35}}]
    for k, (dx, dz) in enumerate([(-0.55, -0.42), (-0.55, 0.42), (0.55, -0.42), (0.55, 0.42)]):
        parts.append({"name": f"{prefix}-wheel-{k}", "mesh": {"generator": "cylinder", "radius": 0.16, "height": 0.1},
                      "transform": {"translate": at(dx, 0.16, dz), "rotate": [90, yaw, 0]},
                      "material": {"color": [0.1, 0.1, 0.1]}})
    return parts


def spot(position, target, cutoff, intensity, penumbra=3):
    direction = [round(t - p, 6) for p, t in zip(position, target)]
    return {"type": "spot", "position": position, "direction": direction, "cutoff": cutoff,
            "penumbra": penumbra, "intensity": intensity}


def camera(position, target, width=720, height=480, fov=40):
    return {"position": position, "target": target, "fov": fov, "width": width, "height": height, "near": 0.05}


def scene(description, cam, lights, objects, volumes=None):
    """(description for README.md, scene JSON): the scene format has no description key."""
    out = {"camera": cam, "background": [0.02, 0.02, 0.03], "lights": lights}
    if volumes:
        out["volumes"] = volumes
    out["objects"] = objects
    return description, out


# ---------------------------------------------------------------- Knecht 2011

CUP_COUNTS = [1, 2, 4, 8, 12, 16, 20, 24]
CUP_SPACING = 0.75


def cups_scene(count):
    slots = [((i - 2.5) * CUP_SPACING, (j - 1.5) * CUP_SPACING) for j in range(4) for i in range(6)]
    objects = [floor(-2.6, -1.8, 2.6, 1.8)]
    for k, (x, z) in enumerate(slots[:count]):
        objects += steaming_cup(k, x, z)
    return scene(f"Knecht 2011 Fig. 5.12 / 5.13 stand-in: {count} steaming teacup(s) (cup mesh plus a 24x48x24 "
                 "smoke column above each; one steam grid shared by all cups) in the first slots, row by row, of a "
                 "6 x 4 array over a floor; one spot light, 720x480; camera and light identical for every count. "
                 "Knecht's teacup mesh, steam dataset and array spacing are not given.",
                 camera([0.0, 3.4, 5.0], [0.0, 0.2, 0.0]), [spot([1.5, 6.0, 3.0], [0.0, 0.0, 0.0], 35, 40.0)],
                 objects, {"steam": STEAM_VOLUME})


XRAY_DIMS = {"512x512x96": [512, 512, 96], "256x256x48": [256, 256, 48], "128x128x24": [128, 128, 24]}
XRAY_EXTENT = [1.0, 1.0, 23 * 0.031496]  # the world size of experiments/scenes/ct-phantom.json's phantom


def xray_scene(dims_name, cam, description):
    dims = XRAY_DIMS[dims_name]
    spacing = [round(e / (n - 1), 9) for e, n in zip(XRAY_EXTENT, dims)]
    objects = [floor(-3.0, -1.6, 3.0, 3.5),
               wall(-3.0, 3.0, 3.0, -1.5, "screen-wall"),
               {"name": "table-top", "mesh": {"generator": "box", "min": [-0.8, 0.52, -0.6], "max": [0.8, 0.6, 0.6]},
                "material": {"color": [0.5, 0.55, 0.6]}},
               {"name": "table-stand", "mesh": {"generator": "cylinder", "radius": 0.12, "height": 0.52},
                "transform": {"translate": [0.0, 0.26, 0.0]}, "material": {"color": [0.3, 0.3, 0.32]}},
               {"name": "collimator-ring", "mesh": {"generator": "torus", "major_radius": 0.6, "minor_radius": 0.12},
                "transform": {"translate": [0.0, 1.2, 2.2], "rotate": [90, 0, 0]},
                "material": {"color": [0.7, 0.7, 0.75]}},
               {"name": "lead-glass", "mesh": {"generator": "box", "min": [0.1, 0.6, -0.85], "max": [1.2, 1.8, -0.8]},
                "material": {"color": [0.7, 0.85, 0.8], "alpha": 0.3}, "interior": {"type": "constant", "sigma": 2.0}},
               volume_object("ct", "ct", [0.0, 1.2, 0.0], 1.0, CT_TRANSFER)]
    volumes = {"ct": {"generator": "shepp_logan", "dims": dims, "spacing": spacing}}
    return scene(description, cam, [spot([0.0, 1.2, 3.0], [0.0, 1.2, -1.5], 25, 30.0, penumbra=2)],
                 objects, volumes)


XRAY_TEXT = ("one volume and six polygonal objects (floor, screen wall, table top, table stand, collimator ring, "
             "translucent lead-glass pane); a spot light shines along -z through the CT volume so its shadow is "
             "projected on the wall behind; 720x480. The CT is a Shepp-Logan phantom (same world extent 1 x 1 x 0.724 "
             "at every resolution; the thesis used a clinical-forensic CT), the six objects are our choice (the "
             "thesis does not describe them).")
XRAY_SIDE_CAMERA = camera([3.2, 2.2, 3.6], [0.0, 1.1, -0.6], fov=45)
XRAY_OVERVIEW_CAMERA = camera([4.2, 3.0, 5.5], [0.0, 1.1, -0.4], fov=45)


def knecht_scenes():
    out = {}
    for n in CUP_COUNTS:
        out[f"knecht-fig512-cups-{n}.json"] = cups_scene(n)
    for name in XRAY_DIMS:
        out[f"knecht-fig510-xray-{name}.json"] = xray_scene(
            name, XRAY_SIDE_CAMERA,
            f"Knecht 2011 Fig. 5.10 (Tables 5.5-5.7) stand-in, CT dataset at {name.replace('x', ' x ')}: " + XRAY_TEXT)
    out["knecht-fig511-eps.json"] = xray_scene(
        "256x256x48", XRAY_OVERVIEW_CAMERA,
        "Knecht 2011 Fig. 5.11 (a) (Tables 5.8-5.10, eps sweep) stand-in: the virtual X-ray overview, CT at "
        "256 x 256 x 48 (the thesis does not state the dataset resolution of this test; ours is a choice): " + XRAY_TEXT)
    out["knecht-fig514-a-smoking-car.json"] = scene(
        "Knecht 2011 Fig. 5.1 stand-in (assumed Fig. 5.14 (a), Table 5.11): a car smoking out of its engine "
        "compartment under a spot light. The VW Beetle model is replaced by a box car with a translucent cabin "
        "(the windows) and four wheels; the smoke is a 48x64x48 plume at the rear.",
        camera([3.6, 2.0, 3.8], [0.0, 0.7, 0.0]), [spot([-2.5, 4.5, 2.5], [0.0, 0.5, 0.0], 40, 30.0)],
        [floor(-4, -3, 4, 4), wall(-4, 4, 3.5, -2.5)] + car("car", 0.0, 0.0, [0.55, 0.7, 0.55])
        + [volume_object("smoke", "smoke", [1.25, 1.05, 0.0], 1.4, SMOKE_TRANSFER)],
        {"smoke": {"generator": "smoke", "dims": [48, 64, 48], "seed": 51}})
    out["knecht-fig514-b-car-in-fog.json"] = scene(
        "Knecht 2011 Fig. 5.2 stand-in (assumed Fig. 5.14 (b), Table 5.11): an orange car intersecting fog; the fog "
        "shadows the car and the car shadows the fog. Box car for the thesis's car model; the fog is a wide, "
        "low-extinction 64x32x64 smoke grid (turbulence 2) around the car.",
        camera([3.8, 2.2, 4.2], [0.0, 0.6, 0.0]), [spot([-2.0, 5.0, 1.5], [0.0, 0.3, 0.0], 40, 30.0)],
        [floor(-4, -4, 4, 4)] + car("car", 0.0, 0.0, [1.0, 0.45, 0.05], yaw=20.0)
        + [volume_object("fog", "fog", [0.0, 0.75, 0.0], 3.2, FOG_TRANSFER)],
        {"fog": {"generator": "smoke", "dims": [64, 32, 64], "seed": 52, "turbulence": 2.0}})
    out["knecht-fig514-c-two-smoking-cars.json"] = scene(
        "Knecht 2011 Fig. 5.3 stand-in (assumed Fig. 5.14 (c), Table 5.11): two cars (blue and green) smoking out of "
        "their engine compartments; the two smoke shadows overlap on the wall behind. Box cars; two 48x64x48 plumes "
        "with different seeds.",
        camera([0.5, 2.2, 5.5], [0.0, 0.9, -0.5]), [spot([0.5, 4.0, 4.0], [0.0, 0.8, -2.0], 40, 40.0)],
        [floor(-5, -3, 5, 4), wall(-5, 5, 3.5, -2.5)] + car("blue-car", -1.6, 0.2, [0.2, 0.35, 0.9])
        + car("green-car", 1.6, 0.2, [0.25, 0.75, 0.3])
        + [volume_object("smoke-blue", "smoke-a", [-0.35, 1.05, 0.2], 1.4, SMOKE_TRANSFER),
           volume_object("smoke-green", "smoke-b", [2.85, 1.05, 0.2], 1.4, SMOKE_TRANSFER)],
        {"smoke-a": {"generator": "smoke", "dims": [48, 64, 48], "seed": 53},
         "smoke-b": {"generator": "smoke", "dims": [48, 64, 48], "seed": 54}})
    teapot = [{"name": "teapot-body", "mesh": {"generator": "uv_sphere", "radius": 0.45},
               "transform": {"translate": [-0.7, 0.36, 0.0], "scale": [1.0, 0.8, 1.0]},
               "material": {"color": [0.85, 0.85, 0.9]}},
              {"name": "teapot-spout", "mesh": {"generator": "cylinder", "radius": 0.06, "height": 0.5},
               "transform": {"translate": [-0.2, 0.55, 0.0], "rotate": [0, 0, -50]},
               "material": {"color": [0.85, 0.85, 0.9]}},
              {"name": "teapot-handle", "mesh": {"generator": "torus", "major_radius": 0.18, "minor_radius": 0.04},
               "transform": {"translate": [-1.17, 0.4, 0.0], "rotate": [90, 0, 0]},
               "material": {"color": [0.85, 0.85, 0.9]}}]
    out["knecht-fig514-d-teapot-teacup.json"] = scene(
        "Knecht 2011 Fig. 5.4 stand-in (assumed Fig. 5.14 (d), Table 5.11): a steaming teapot and a steaming teacup "
        "lit by a spot light on the left and an omni light between them. The teapot is a sphere body with a "
        "cylinder spout and a torus handle (no teapot mesh); the thesis marks the omni light with a white sphere, "
        "left out here because a closed sphere around an omni light would shadow everything.",
        camera([0.3, 1.8, 3.2], [0.0, 0.5, 0.0]),
        [spot([-3.0, 3.0, 1.0], [0.0, 0.3, 0.0], 35, 30.0), {"type": "omni", "position": [0.15, 0.9, 0.45], "intensity": 1.5}],
        [floor(-3, -2, 3, 2)] + teapot + steaming_cup(0, 0.9, 0.0, cup_scale=0.5, steam_scale=0.55)
        + [volume_object("teapot-steam", "steam", [0.05, 1.05, 0.0], 0.5, STEAM_TRANSFER)],
        {"steam": STEAM_VOLUME})
    out["knecht-fig514-f-filtering-cup.json"] = scene(
        "Knecht 2011 Fig. 5.9 stand-in (assumed Fig. 5.14 (f), Table 5.11): one steaming cup on a floor for the "
        "filtered vs unfiltered comparison; the thesis picks a very small DSM on purpose (size not stated), e.g. "
        "--dsm-res 64 with and without --filter bilinear.",
        camera([1.2, 1.3, 1.6], [0.0, 0.35, 0.0]), [spot([-1.5, 3.0, 0.8], [0.0, 0.2, 0.0], 30, 12.0)],
        [floor(-2, -2, 2, 2)] + steaming_cup(0, 0.0, 0.0, cup_scale=0.6, steam_scale=0.7),
        {"steam": STEAM_VOLUME})
    return out


# ---------------------------------------------------------------- Hadwiger 2006

# Sharp steps (an isosurface-like, high-frequency transfer function, what Hadwiger's
# pre-compressed visibility table is for): the phantom's inside (0.2) is clear, its features
# (0.3) dense, its shell (1.0) translucent (a step down at 0.5) so the features show through.
HADWIGER_TRANSFER = [{"density": 0.24, "color": [0.9, 0.75, 0.65], "sigma": 0.0},
                     {"density": 0.26, "color": [0.9, 0.75, 0.65], "sigma": 30.0},
                     {"density": 0.5, "color": [0.9, 0.75, 0.65], "sigma": 30.0},
                     {"density": 0.55, "color": [1.0, 0.97, 0.9], "sigma": 8.0}]


def hadwiger_scenes():
    return {"hadwiger-fig4-ct-volume.json": scene(
        "Hadwiger et al. 2006 Fig. 4 / Table 1 stand-in: direct volume rendering of one CT volume with self-shadowing "
        "(volume only: their method handles no geometry), 512x512 viewport, one spot light. The CT scan of a human "
        "hand (resolution, transfer function and light not given) is replaced by a 256^3 Shepp-Logan phantom with "
        "a sharp, isosurface-like transfer function.",
        camera([0.8, 0.55, 1.0], [0.0, 0.0, 0.0], width=512, height=512),
        [spot([-1.6, 2.0, 1.2], [0.0, 0.0, 0.0], 30, 8.0)],
        [{"name": "ct", "mesh": "volume_bounds", "material": {"alpha": 0.0},
          "interior": {"type": "volume", "volume": "ct", "transfer": HADWIGER_TRANSFER}}],
        {"ct": {"generator": "shepp_logan", "dims": [256, 256, 256]}})}


# ---------------------------------------------------------------- Knecht 2011 §4.2.1: the 3D texture's layer limit

LAYER_SLABS = 64


def layer_limit_scenes():
    """No figure of the thesis: a scene deep enough to exceed the 3D texture's 64 layers."""
    objects = [floor(-1.5, -1.5, 1.5, 1.5)]
    for k in range(LAYER_SLABS):
        y = round(0.3 + 0.02 * k, 6)
        objects.append({"name": f"slab-{k}", "mesh": {"generator": "box", "min": [-0.6, y, -0.6], "max": [0.6, round(y + 0.01, 6), 0.6]},
                        "material": {"color": [0.85, 0.8, 0.7], "alpha": 0.03}})
    return {"knecht-layer-limit-64-slabs.json": scene(
        f"Knecht 2011 §4.2.1 layer limit (no figure): {LAYER_SLABS} stacked translucent slabs (alpha 0.03 each, "
        f"{2 * LAYER_SLABS} surfaces on every light ray through the stack) over a floor under one spot light, 720x480, "
        "so that a texel's compressed visibility needs more than the 3D texture's 64 layers at a small eps. No thesis "
        "scene is given for the limit; every other seeds scene stays below 18 layers.",
        camera([2.2, 2.6, 3.0], [0.0, 0.6, 0.0]),
        [spot([0.3, 4.0, 0.2], [0.0, 0.0, 0.0], 30, 10.0)],
        objects)}


# ---------------------------------------------------------------- Buchacher 2014

def buchacher_scene(description, mesh, transform, cam):
    obj = {"name": "model", "mesh": mesh, "material": {"color": [0.8, 0.8, 0.8]}}
    if transform:
        obj["transform"] = transform
    return scene(description, cam, [{"type": "directional", "direction": [0.3, -1.0, -0.5], "intensity": 1.0}], [obj])


# The quads' y = 0 plane turned exactly onto z = 0 (normal +z): (x, y, z) -> (x, -z, y). A
# "rotate" of 90 degrees would leave the quad 1e-17 off the plane; with the default cubic bounds
# z = 0 is the middle slice plane of every even depth, the thesis's quad-on-a-slice-boundary case.
QUAD_TO_Z = {"matrix": [1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1]}

BUCHACHER_VOXELIZE = (" Voxelize with `deepvox voxelize FILE --res WxWx32`, the depth axis (z) as the voxelization "
                      "camera's view direction; the thesis's grid is 1.5 x the quad (`--bounds=-0.75,-0.75,-0.75,0.75,"
                      "0.75,0.75` reproduces its Compute counts for the simple quad), its margin for the other models "
                      "is unknown (default bounds: the model's bounding cube).")


def buchacher_scenes():
    front = camera([0.0, 0.0, 2.2], [0.0, 0.0, 0.0], width=512, height=512)
    oblique = camera([1.6, 1.2, 1.9], [0.0, 0.0, 0.0], width=512, height=512)
    bunny_cam = camera([0.0, 0.8, 2.2], [0.0, 0.6, 0.0], width=512, height=512)
    return {
        "buchacher-simple-quad.json": buchacher_scene(
            "Buchacher 2014 Tab. 1/2 'Simplex Quad' (the text's Simple Quad): a square of 2 triangles facing the "
            "voxelization camera (the quad generator turned exactly from the y = 0 plane into z = 0, the middle slice plane of the default bounds)." + BUCHACHER_VOXELIZE,
            {"generator": "quad", "size": 1.0}, QUAD_TO_Z, front),
        "buchacher-complex-quad.json": buchacher_scene(
            "Buchacher 2014 Tab. 1/2 'Komplexes Quad': the same square cut into exactly 11,858 triangles (77 x 77 "
            "cells; the thesis subdivided its quad 'several times', tessellation unknown)." + BUCHACHER_VOXELIZE,
            {"generator": "subdivided_quad", "size": 1.0, "target_triangles": 11858}, QUAD_TO_Z, front),
        "buchacher-cube.json": buchacher_scene(
            "Buchacher 2014 Tab. 1/2 'Achsenparalleler Würfel': a cube of 12 triangles with its sides axis-parallel "
            "to the voxelization camera." + BUCHACHER_VOXELIZE,
            {"generator": "box", "size": 1.0}, None, oblique),
        "buchacher-bunny.json": buchacher_scene(
            "Buchacher 2014 Tab. 1/2 'Stanford Bunny' stand-in: the shared low-resolution scan midpoint-subdivided "
            "twice, 58,784 triangles (the thesis's bunny has 69,451)." + BUCHACHER_VOXELIZE,
            {"generator": "bunny", "subdivisions": 2}, {"scale": 0.08}, bunny_cam),
        "buchacher-buddha-standin.json": buchacher_scene(
            "Buchacher 2014 Tab. 1/2 'Stanford Happy Buddha' (1,087,716 triangles) stand-in: the bunny "
            "midpoint-subdivided 4 times, 940,544 triangles, so the ~1M-triangle load matches but not the Buddha's "
            "concave detail (midpoint subdivision adds no detail). Loads in about 1.5 s on the 2-core host "
            "(see Loading below)." + BUCHACHER_VOXELIZE,
            {"generator": "bunny", "subdivisions": 4}, {"scale": 0.08}, bunny_cam),
    }


# ---------------------------------------------------------------- output

def dump(value, indent=0):
    """JSON with one top-level key, object or volume per line, so diffs stay readable."""
    pad = "  " * (indent + 1)
    if indent == 0 and isinstance(value, dict):
        body = ",\n".join(f"{pad}{json.dumps(k)}: {dump(v, 1)}" for k, v in value.items())
        return "{\n" + body + "\n}\n"
    if indent == 1 and isinstance(value, list) and value and isinstance(value[0], dict):
        return "[\n" + ",\n".join(pad + json.dumps(v, ensure_ascii=False) for v in value) + "\n  ]"
    if indent == 1 and isinstance(value, dict) and value and all(isinstance(v, dict) for v in value.values()):
        body = ",\n".join(f"{pad}{json.dumps(k)}: {json.dumps(v, ensure_ascii=False)}" for k, v in value.items())
        return "{\n" + body + "\n  }"
    return json.dumps(value, ensure_ascii=False)


README_HEAD = """# seeds scenes

Stand-ins for the scenes the paper tables of `experiments/papers/` were measured on (Knecht 2011
chapter 5, Bornik et al. 2012, Hadwiger et al. 2006, Buchacher 2014), for the `seeds` experiment
suite (plan: `experiments/suites/seeds-plan.md`). None of the papers' models or datasets (VW
Beetle, clinical-forensic CT, CT of a hand, Stanford Happy Buddha, the thesis teacup and steam) is
available, so every file is a stand-in built from the scene format's generators; the table says
what each stands in for and how it differs.

GENERATED by `make_seed_scenes.py` (this README included): edit the script, run
`python3 experiments/scenes/seeds/make_seed_scenes.py`, commit both; `--check` exits 1 when a committed file
is stale.

Not here because it exists: `experiments/scenes/knecht-fig56.json` is the scene of Knecht Figs. 5.5-5.7 and
Bornik Fig. 3 (Knecht Tables 5.1-5.4, Bornik Tables 1 and 3; assumed Fig. 5.14 (e)). It has two
128^3 volumes and six purely polygonal objects where the papers list two volumes and eight
polygonal objects.

Figure 5.14 (Knecht Table 5.11) is a gallery of "all scenes presented in this chapter" whose
letters the text never assigns; the files below assume chapter order: (a) Fig. 5.1, (b) Fig. 5.2,
(c) Fig. 5.3, (d) Fig. 5.4, (e) Figs. 5.5-5.7 = `experiments/scenes/knecht-fig56.json`, (f) Fig. 5.9,
(g) Figs. 5.10/5.11 = `knecht-fig510-xray-256x256x48.json` (dataset resolution unknown),
(h) Fig. 5.12 = `knecht-fig512-cups-24.json`. That mapping is an assumption, not the thesis's.

| file | stands in for | how it differs / notes |
| --- | --- | --- |
"""

README_TAIL = """
## Loading

Every file loads: `build-cpu/bin/deepvox info FILE` exits 0 for all of them (measured with
`/usr/bin/time` on the shared 2-core host, Release CPU build, when they were generated): most
take 0.7-0.8 s (the program's start-up included; the bunny 1.07 s), `hadwiger-fig4-ct-volume.json` 1.29 s
(256^3 samples), `knecht-fig510-xray-512x512x96.json` 1.70 s and 225 MB (25 M samples),
`buchacher-buddha-standin.json` 1.53 s and 185 MB (940,544 triangles). Loading is cheap; the heavy
runs (the 512 x 512 x 96 X-ray rendered at 720 x 480, every voxelization of the Buddha stand-in
at 512 x 512 x 32) are meant for the GPU node and were not timed on the CPU.
"""


def readme(descriptions):
    rows = []
    for name, text in descriptions.items():
        figure, _, rest = text.partition(": ")
        rows.append(f"| `{name}` | {figure} | {rest} |")
    return README_HEAD + "\n".join(rows) + "\n" + README_TAIL


def main():
    check = "--check" in sys.argv[1:]
    made = {**knecht_scenes(), **layer_limit_scenes(), **hadwiger_scenes(), **buchacher_scenes()}
    files = {name: dump(content) for name, (_, content) in made.items()}
    files["README.md"] = readme({name: description for name, (description, _) in made.items()})
    stale = []
    for name, text in files.items():
        path = HERE / name
        if check:
            if not path.exists() or path.read_text() != text:
                stale.append(name)
        else:
            path.write_text(text)
    if stale:
        print("stale or missing:", ", ".join(stale))
        return 1
    print(("checked " if check else "wrote ") + str(len(files)) + " files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
