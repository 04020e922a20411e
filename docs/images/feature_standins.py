#!/usr/bin/env python3
"""Writes glTF stand-ins built like the Khronos sample models (which cannot be committed here)
for the glass and texture effects: glass that colours its shadow, alpha-masked textures, a tinted
medium behind glass, textured and normal-mapped models. Geometry and textures are generated
here (pure standard library, look_standins.py's Gltf writer, PNG textures as data: URIs).

Feature scenes, committed under experiments/assets/gltf/ (tests load them; a test checks they
are this script's output, so regenerate rather than edit them):

  red-glass-slab.gltf         a red glass slab (KHR_materials_transmission 1, baseColor red,
                              KHR_materials_ior 1.5) held over a floor beside a white block,
                              lit by a spot light;
  alpha-mask-quad.gltf        a standing quad with a base-colour PNG whose alpha has round
                              cut-outs (0) and two bands just below (0.4) and above (0.6) the
                              cutoff, alphaMode MASK, alphaCutoff 0.5, over a floor, a spot light;
  tinted-medium-glass.gltf    a blue tinted medium (KHR_materials_volume attenuationColor in a
                              transmissive shell) behind a clear glass pane, over a floor, a spot
                              light shining through both;
  textured-torus.gltf         a torus with vertex NORMALs, TEXCOORD_0, a base-colour PNG and a
                              normalTexture (ridges across the tube; no TANGENT, as in most sample
                              models), no camera or lights.

Sample-model stand-ins for the thumbnails (docs/images/look_thumbnails.py --set samples):

  transmission-test.gltf      like TransmissionTest (look_standins.transmission);
  glass-vase-flowers.gltf     like GlassVaseFlowers: a clear glass vase (transmission 1, volume
                              thickness) with alpha-masked leaf and blossom quads;
  damaged-helmet.gltf         like DamagedHelmet: a white-ish textured rounded helmet with vertex
                              normals and an emissive visor;
  duck.gltf                   like Duck: a yellow textured duck with a camera in the file looking
                              from behind it (-z), no lights.

Shadow stand-ins of the shadow thumbnails and measurements (look_thumbnails.py --set shadows),
all without lights, so that `render` stages them (ground, key and fill):

  textured-glass-pane.gltf    like StainedGlassLamp's panes: a horizontal glass pane
                              (transmission 1, white factor) whose base-colour PNG holds red,
                              blue, yellow and green panels in dark leading, on an opaque post;
  glass-cube-contact.gltf     a red glass cube (transmission 1) resting on the staged ground;
  blend-quad-contact.gltf     a BLEND quad of alpha 0.5 lying on the staged ground;
  transmission-cloth.gltf     like TransmissionTest's cloth: a wavy, folded checker cloth under a
                              blue glass ellipsoid and a red glass sphere;
  translucent-cloth.gltf      the same with a translucent cloth (BLEND, alpha 0.6): grey layers
                              behind the tinted glass in the same texels;
  glass-over-translucent.gltf a blue glass pane (transmission 1) at y = 1 over grey BLEND quads
                              (alpha 0.6) at y = 0.5 and y = 0: the simplest such texel.

Usage: feature_standins.py [OUT_DIR]            the feature scenes (default experiments/assets/gltf)
       feature_standins.py --samples OUT_DIR    the sample-model stand-ins
       feature_standins.py --shadows OUT_DIR    the shadow stand-ins
       feature_standins.py --check DIR          exit 1 naming every feature scene in DIR that is
                                                not this script's output
"""
import math
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from look_standins import Gltf, box, lathe, png, transmission  # noqa: E402


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def look_rotation(eye, target, up=(0.0, 1.0, 0.0)):
    """The node rotation quaternion [x, y, z, w] that turns local -Z towards target and keeps
    local +Y up (cameras and lights shine along their node's -Z)."""
    z = normalize(tuple(e - t for e, t in zip(eye, target)))
    x = normalize(cross(up, z))
    y = cross(z, x)
    m = ((x[0], y[0], z[0]), (x[1], y[1], z[1]), (x[2], y[2], z[2]))
    w = math.sqrt(max(0.0, 1.0 + m[0][0] + m[1][1] + m[2][2])) / 2
    if w > 1e-6:
        q = ((m[2][1] - m[1][2]) / (4 * w), (m[0][2] - m[2][0]) / (4 * w),
             (m[1][0] - m[0][1]) / (4 * w), w)
    else:  # a half turn: about the axis with the largest diagonal entry
        i = max(range(3), key=lambda k: m[k][k])
        j, k = (i + 1) % 3, (i + 2) % 3
        s = math.sqrt(max(0.0, 1.0 + m[i][i] - m[j][j] - m[k][k])) * 2
        q = [0.0, 0.0, 0.0, (m[k][j] - m[j][k]) / s]
        q[i], q[j], q[k] = s / 4, (m[j][i] + m[i][j]) / s, (m[k][i] + m[i][k]) / s
    return [round(c, 7) for c in q]


def spot(g, eye, target, candela, inner=0.35, outer=0.5):
    """A node with a spot light at eye shining at target. Its candela are meant for the
    exposure glTF lights are seen at, log2(683 / pi) EV (docs/rendering.md): 27.6 cd there look
    as 6000 cd did at 0 EV."""
    g.node(translation=list(eye), rotation=look_rotation(eye, target),
           extensions=g.light("spot", candela,
                              spot={"innerConeAngle": inner, "outerConeAngle": outer}))


def floor(g, half=2.0, color=(0.7, 0.7, 0.7)):
    g.node(mesh=g.mesh(*box((-half, -0.1, -half), (half, 0.0, half)), g.material(color)))


def ellipsoid(radii, centre=(0, 0, 0), segments=32, rings=16):
    """A closed UV ellipsoid with vertex normals and TEXCOORD_0 (u round +y, v from the top);
    the seam's vertices are doubled for the texture, the poles are single vertices."""
    pos, normals, uvs, tris = [], [], [], []
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for s in range(segments + 1 if 0 < i < rings else 1):
            phi = 2 * math.pi * s / segments
            unit = (math.sin(theta) * math.cos(phi), math.cos(theta),
                    -math.sin(theta) * math.sin(phi))
            pos.append(tuple(c + r * u for c, r, u in zip(centre, radii, unit)))
            normals.append(normalize(tuple(u / r for u, r in zip(unit, radii))))
            uvs.append((s / segments if 0 < i < rings else 0.5, i / rings))
    ring = segments + 1
    first = lambda i: 1 + (i - 1) * ring  # first vertex of ring i (1 <= i < rings)
    bottom = len(pos) - 1
    for s in range(segments):
        tris.append((0, first(1) + s, first(1) + s + 1))
        last = first(rings - 1)
        tris.append((last + s + 1, last + s, bottom))
        for i in range(1, rings - 1):
            a, b = first(i) + s, first(i + 1) + s
            tris += [(a, b, b + 1), (a, b + 1, a + 1)]
    return pos, tris, normals, uvs


def torus(major, minor, segments=48, sides=24):
    """A torus round +y with vertex normals and TEXCOORD_0 (u round the ring, v round the tube)."""
    pos, normals, uvs, tris = [], [], [], []
    for i in range(segments + 1):
        a = 2 * math.pi * i / segments
        for j in range(sides + 1):
            b = 2 * math.pi * j / sides
            n = (math.cos(b) * math.cos(a), math.sin(b), -math.cos(b) * math.sin(a))
            pos.append((major * math.cos(a) + minor * n[0], minor * n[1],
                        -major * math.sin(a) + minor * n[2]))
            normals.append(n)
            uvs.append((i / segments, j / sides))
    for i in range(segments):
        for j in range(sides):
            a, b = i * (sides + 1) + j, (i + 1) * (sides + 1) + j
            tris += [(a, b, b + 1), (a, b + 1, a + 1)]
    return pos, tris, normals, uvs


def quad(width, height, centre=(0, 0, 0), yaw=0.0):
    """A quad standing in the plane through centre, facing +z turned yaw radians about +y, with
    normals and TEXCOORD_0 (v down the quad, as glTF images run)."""
    c, s = math.cos(yaw), math.sin(yaw)
    corners = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
    pos = [(centre[0] + x * width * c, centre[1] + y * height, centre[2] - x * width * s)
           for x, y in corners]
    normal = (s, 0.0, c)
    return (pos, [(0, 1, 2), (0, 2, 3)], [normal] * 4,
            [(x + 0.5, 0.5 - y) for x, y in corners])


def surface(g, shape, material):
    """A mesh of a shape with normals and texture coordinates (positions, triangles, normals,
    uvs)."""
    positions, triangles, normals, uvs = shape
    return g.mesh(positions, triangles, material, normals, uvs)


def red_glass_slab(path):
    g = Gltf()
    floor(g)
    glass = g.material((1.0, 0.1, 0.1), roughness=0.05,
                       KHR_materials_transmission={"transmissionFactor": 1.0},
                       KHR_materials_ior={"ior": 1.5})
    g.node(name="red glass", mesh=g.mesh(*box((-0.6, 0.7, -0.6), (0.6, 0.8, 0.6)), glass))
    g.node(name="block", mesh=g.mesh(*box((0.9, 0.0, -0.2), (1.3, 0.4, 0.2)),
                                     g.material((0.9, 0.9, 0.9))))
    spot(g, (0.8, 3.0, 1.0), (0.2, 0.0, 0.0), 34.5, inner=0.45, outer=0.6)
    g.write(path)


def alpha_mask_quad(path):
    g = Gltf()
    floor(g)

    def pixel(x, y):  # 64 x 64: stripes, round holes, then bands at alpha 0.4 and 0.6
        colour = (230, 120, 40) if (x // 8) % 2 else (40, 90, 200)
        if y >= 56:
            return colour + (153,)  # 0.6: kept by the 0.5 cutoff
        if y >= 48:
            return colour + (102,)  # 0.4: cut
        cx, cy = x % 16 - 7.5, y % 16 - 7.5
        return colour + (0 if cx * cx + cy * cy < 25 else 255,)
    texture = g.texture(png(64, 64, pixel))
    cutout = g.material((1, 1, 1), fields={"alphaMode": "MASK", "alphaCutoff": 0.5,
                                           "doubleSided": True,
                                           "pbr": {"baseColorTexture": {"index": texture}}})
    g.node(name="cut-out quad", mesh=surface(g, quad(1.6, 1.6, (0, 0.9, 0)), cutout))
    spot(g, (0.3, 2.6, 2.6), (0.0, 0.0, -0.8), 27.6, inner=0.5, outer=0.65)
    g.write(path)


def tinted_medium_glass(path):
    g = Gltf()
    floor(g)
    pane = g.material((1, 1, 1), roughness=0.02,
                      KHR_materials_transmission={"transmissionFactor": 1.0},
                      KHR_materials_ior={"ior": 1.5})
    g.node(name="glass pane", mesh=g.mesh(*box((-0.8, 0.0, 0.9), (0.8, 1.4, 0.95)), pane))
    medium = g.material((1, 1, 1), roughness=0.05,
                        KHR_materials_transmission={"transmissionFactor": 1.0},
                        KHR_materials_volume={"thicknessFactor": 1.0,
                                              "attenuationColor": [0.2, 0.5, 0.95],
                                              "attenuationDistance": 0.5})
    g.node(name="blue medium", mesh=g.mesh(*box((-0.5, 0.0, -0.5), (0.5, 1.0, 0.5)), medium))
    spot(g, (0.4, 2.8, 3.2), (0.0, 0.3, -0.2), 41.4, inner=0.45, outer=0.6)
    g.write(path)


def textured_torus(path):
    g = Gltf()

    def colour(x, y):  # terracotta with cream bands round the tube
        return (235, 215, 170, 255) if (y // 8) % 2 else (190, 80, 50, 255)

    def ridges(x, y):  # height h = sin(2 pi 8 u): tangent-space normal (-dh/du, 0, 1)
        slope = 0.8 * math.cos(2 * math.pi * 8 * x / 64)
        n = normalize((-slope, 0.0, 1.0))
        return tuple(round(255 * (c * 0.5 + 0.5)) for c in n) + (255,)
    base, normal = g.texture(png(64, 64, colour)), g.texture(png(64, 64, ridges))
    material = g.material((1, 1, 1), roughness=0.4,
                          fields={"normalTexture": {"index": normal, "scale": 1.0},
                                  "pbr": {"baseColorTexture": {"index": base}}})
    g.node(name="torus", mesh=surface(g, torus(0.6, 0.25), material),
           rotation=[0.5, 0.0, 0.0, 0.8660254])  # 60 degrees about +x: standing, leaning back
    g.write(path)


def glass_vase_flowers(path):
    g = Gltf()
    glass = g.material((1, 1, 1), roughness=0.05,
                       KHR_materials_transmission={"transmissionFactor": 1.0},
                       KHR_materials_volume={"thicknessFactor": 0.05})
    profile = [(0, 0), (0.3, 0), (0.36, 0.3), (0.2, 0.7), (0.26, 0.9), (0.23, 0.9), (0.17, 0.7),
               (0.33, 0.3), (0.27, 0.03), (0, 0.03)]
    g.node(name="vase", mesh=g.mesh(*lathe(profile, 40), glass))
    stem = g.material((0.2, 0.45, 0.15))

    def leaf(x, y):  # a pointed leaf with a pale vein, cut out of a transparent square
        u, v = (x + 0.5) / 32 - 0.5, (y + 0.5) / 64
        inside = abs(u) < 0.45 * math.sin(math.pi * v)
        green = (200, 230, 150) if abs(u) < 0.03 else (40, 120 + int(60 * v), 40)
        return green + (255 if inside else 0,)

    def blossom(x, y):  # five round petals and a yellow heart
        u, v = (x - 31.5) / 32, (y - 31.5) / 32
        r, a = math.hypot(u, v), math.atan2(v, u)
        petal = r < 0.55 + 0.4 * abs(math.cos(2.5 * a))
        colour = (250, 210, 40) if r < 0.25 else (220, 50, 90)
        return colour + (255 if petal and r < 0.95 else 0,)
    masked = {"alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True}
    leaf_m = g.material((1, 1, 1), fields=dict(masked, pbr={"baseColorTexture": {
        "index": g.texture(png(32, 64, leaf))}}))
    blossom_m = g.material((1, 1, 1), fields=dict(masked, pbr={"baseColorTexture": {
        "index": g.texture(png(64, 64, blossom))}}))
    for i, (dx, dz, top) in enumerate([(-0.06, 0.0, 1.5), (0.07, 0.05, 1.35), (0.0, -0.07, 1.6)]):
        g.node(mesh=g.mesh(*box((dx - 0.01, 0.03, dz - 0.01), (dx + 0.01, top, dz + 0.01)), stem))
        yaw = 1.1 * i
        g.node(mesh=surface(g, quad(0.45, 0.45, (dx, top + 0.1, dz), yaw), blossom_m))
        g.node(mesh=surface(g, quad(0.25, 0.5, (dx + 0.12 * math.cos(yaw), 0.95 + 0.12 * i,
                                             dz - 0.12 * math.sin(yaw)), yaw + 0.8), leaf_m))
    g.write(path)


def damaged_helmet(path):
    g = Gltf()

    def shell(x, y):  # scuffed white-grey panels with dark seams
        seam = x % 32 in (0, 1) or y % 21 in (0, 1)
        scuff = ((x * 7 + y * 13) % 29) < 3
        grey = 60 if seam else 170 if scuff else 225
        return (grey, grey, grey - 8 if grey > 100 else grey, 255)
    helmet = g.material((1, 1, 1), roughness=0.5,
                        fields={"pbr": {"baseColorTexture": {
                            "index": g.texture(png(64, 64, shell))}}})
    visor = g.material((0.08, 0.08, 0.1), roughness=0.1,
                       fields={"emissiveFactor": [1.0, 0.6, 0.2]})
    g.node(name="helmet", mesh=surface(g, ellipsoid((0.9, 1.0, 0.95)), helmet))
    g.node(name="visor", mesh=surface(g, ellipsoid((0.6, 0.4, 0.35), (0.0, 0.1, 0.7)), visor))
    g.write(path)


def duck(path):
    g = Gltf()

    def feathers(x, y):  # yellow with soft darker streaks
        shade = 20 if (x + 2 * y) % 16 < 3 else 0
        return (250 - shade, 215 - shade, 40, 255)
    yellow = g.material((1, 1, 1), roughness=0.5,
                        fields={"pbr": {"baseColorTexture": {
                            "index": g.texture(png(32, 32, feathers))}}})
    g.node(name="body", mesh=surface(g, ellipsoid((0.9, 0.55, 0.65), (0.0, 0.55, 0.0)), yellow))
    g.node(name="head", mesh=surface(g, ellipsoid((0.38, 0.38, 0.38), (-0.6, 1.25, 0.0)), yellow))
    g.node(name="beak", mesh=surface(g, ellipsoid((0.25, 0.08, 0.18), (-1.0, 1.2, 0.0)),
                                    g.material((0.95, 0.45, 0.1))))
    eye = g.material((0.02, 0.02, 0.02), roughness=0.2)
    for side in (-1, 1):
        g.node(mesh=surface(g, ellipsoid((0.06, 0.06, 0.06), (-0.82, 1.38, 0.2 * side), 12, 6),
                            eye))
    # Like the real file's camera: from behind and to the side of the duck, above it.
    g.doc["cameras"] = [{"type": "perspective", "perspective": {
        "yfov": 0.66, "aspectRatio": 1.5, "znear": 0.1, "zfar": 100.0}}]
    eye_at = (2.8, 2.9, -3.0)
    g.node(camera=0, translation=list(eye_at), rotation=look_rotation(eye_at, (-0.2, 0.7, 0.0)))
    g.write(path)


def textured_glass_pane(path):
    g = Gltf()
    colours = [(220, 40, 40), (40, 70, 220), (240, 200, 40), (40, 170, 70)]

    def panel(x, y):  # 2 x 2 coloured panels of 16 texels in 2-texel dark leading
        if x % 16 < 2 or y % 16 < 2:
            return (40, 40, 40, 255)
        return colours[(x // 16) + 2 * (y // 16)] + (255,)
    stained = g.material((1, 1, 1), roughness=0.05,
                         fields={"pbr": {"baseColorTexture": {
                             "index": g.texture(png(32, 32, panel))}}},
                         KHR_materials_transmission={"transmissionFactor": 1.0})
    pos, tris = box((-0.6, 0.7, -0.6), (0.6, 0.74, 0.6))
    uvs = [((p[0] + 0.6) / 1.2, (p[2] + 0.6) / 1.2) for p in pos]
    g.node(name="stained pane", mesh=g.mesh(pos, tris, stained, None, uvs))
    g.node(name="post", mesh=g.mesh(*box((-0.04, 0.0, -0.04), (0.04, 0.7, 0.04)),
                                    g.material((0.3, 0.25, 0.2))))
    g.write(path)


def glass_cube_contact(path):
    g = Gltf()
    red = g.material((1.0, 0.2, 0.2), roughness=0.05,
                     KHR_materials_transmission={"transmissionFactor": 1.0})
    g.node(name="red glass cube", mesh=g.mesh(*box((-0.5, 0.0, -0.5), (0.5, 1.0, 0.5)), red))
    g.write(path)


def blend_quad_contact(path):
    g = Gltf()
    half = g.material((0.2, 0.4, 0.9), alpha=0.5, fields={"alphaMode": "BLEND",
                                                          "doubleSided": True})
    pos = [(-0.5, 0.0, -0.5), (0.5, 0.0, -0.5), (0.5, 0.0, 0.5), (-0.5, 0.0, 0.5)]
    g.node(name="blend quad", mesh=g.mesh(pos, [(0, 2, 1), (0, 3, 2)], half))
    g.write(path)


def transmission_cloth(path, cells=96, cloth_alpha=1.0):
    """A cloth draped in folds (height a sum of waves across x and z; steep enough that folds
    shadow their neighbours under the staged key) in 8 x 8 checker squares, two meshes with
    smooth vertex normals; a blue glass ellipsoid and a red glass sphere above it. Below 1,
    cloth_alpha makes the cloth translucent (alphaMode BLEND, double-sided)."""
    g = Gltf()
    size = 1.6
    k1, k2 = 2 * math.pi / 0.5, 2 * math.pi / 0.9

    def height(x, z):
        return 0.12 * math.sin(k1 * x) + 0.04 * math.sin(k2 * (z + 0.3 * x))

    def normal(x, z):
        dx = 0.12 * k1 * math.cos(k1 * x) + 0.04 * k2 * 0.3 * math.cos(k2 * (z + 0.3 * x))
        dz = 0.04 * k2 * math.cos(k2 * (z + 0.3 * x))
        return normalize((-dx, 1.0, -dz))
    parts = ([], [], []), ([], [], [])
    step = 2 * size / cells
    for i in range(cells):
        for j in range(cells):
            pos, normals, tris = parts[(i * 8 // cells + j * 8 // cells) % 2]
            n = len(pos)
            for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                x, z = -size + (i + di) * step, -size + (j + dj) * step
                pos.append((x, height(x, z), z))
                normals.append(normal(x, z))
            tris += [(n, n + 2, n + 1), (n, n + 3, n + 2)]
    blend = {"alphaMode": "BLEND", "doubleSided": True} if cloth_alpha < 1.0 else None
    for (pos, normals, tris), colour in zip(parts, ((0.8, 0.8, 0.8), (0.15, 0.15, 0.2))):
        material = g.material(colour, alpha=cloth_alpha, fields=blend)
        g.node(name="cloth", mesh=g.mesh(pos, tris, material, normals))
    blue = g.material((0.3, 0.45, 1.0), roughness=0.05,
                      KHR_materials_transmission={"transmissionFactor": 1.0})
    red = g.material((1.0, 0.25, 0.25), roughness=0.05,
                     KHR_materials_transmission={"transmissionFactor": 1.0})
    g.node(name="blue glass",
           mesh=surface(g, ellipsoid((0.45, 0.25, 0.3), (-0.45, 0.5, 0.1)), blue))
    g.node(name="red sphere",
           mesh=surface(g, ellipsoid((0.3, 0.3, 0.3), (0.5, 0.5, -0.1)), red))
    g.write(path)


def glass_over_translucent(path):
    g = Gltf()
    blue = g.material((0.3, 0.45, 1.0), roughness=0.05,
                      KHR_materials_transmission={"transmissionFactor": 1.0})
    grey = g.material((0.8, 0.8, 0.8), alpha=0.6, fields={"alphaMode": "BLEND",
                                                          "doubleSided": True})

    def level(y, half):
        return [(-half, y, -half), (half, y, -half), (half, y, half), (-half, y, half)]
    g.node(name="blue glass", mesh=g.mesh(level(1.0, 0.6), [(0, 2, 1), (0, 3, 2)], blue))
    for name, y in (("upper grey", 0.5), ("lower grey", 0.0)):
        g.node(name=name, mesh=g.mesh(level(y, 1.0), [(0, 2, 1), (0, 3, 2)], grey))
    g.write(path)


FEATURES = {"red-glass-slab.gltf": red_glass_slab, "alpha-mask-quad.gltf": alpha_mask_quad,
            "tinted-medium-glass.gltf": tinted_medium_glass,
            "textured-torus.gltf": textured_torus}
SAMPLES = {"transmission-test.gltf": transmission, "glass-vase-flowers.gltf": glass_vase_flowers,
           "damaged-helmet.gltf": damaged_helmet, "duck.gltf": duck}
SHADOWS = {"textured-glass-pane.gltf": textured_glass_pane,
           "glass-cube-contact.gltf": glass_cube_contact,
           "blend-quad-contact.gltf": blend_quad_contact,
           "transmission-cloth.gltf": transmission_cloth,
           "translucent-cloth.gltf": lambda path: transmission_cloth(path, cloth_alpha=0.6),
           "glass-over-translucent.gltf": glass_over_translucent}


def write_all(scenes, out):
    os.makedirs(out, exist_ok=True)
    for name, make in scenes.items():
        make(os.path.join(out, name))


def check(folder):
    """Names of the feature scenes in folder that differ from (or lack) this script's output."""
    with tempfile.TemporaryDirectory() as tmp:
        write_all(FEATURES, tmp)
        stale = []
        for name in FEATURES:
            committed = os.path.join(folder, name)
            fresh = open(os.path.join(tmp, name), "rb").read()
            if not os.path.exists(committed) or open(committed, "rb").read() != fresh:
                stale.append(name)
        return stale


if __name__ == "__main__":
    args = sys.argv[1:]
    if args[:1] == ["--check"] and len(args) == 2:
        stale = check(args[1])
        for name in stale:
            print(f"{os.path.join(args[1], name)} is not feature_standins.py's output: "
                  "regenerate it with docs/images/feature_standins.py", file=sys.stderr)
        sys.exit(1 if stale else 0)
    if args[:1] == ["--samples"] and len(args) == 2:
        write_all(SAMPLES, args[1])
    elif args[:1] == ["--shadows"] and len(args) == 2:
        write_all(SHADOWS, args[1])
    elif len(args) <= 1 and not (args and args[0].startswith("-")):
        default = os.path.join(ROOT, "experiments", "assets", "gltf")
        write_all(FEATURES, args[0] if args else default)
    else:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
