#!/usr/bin/env python3
"""Writes small glTF stand-ins for three Khronos sample models (which cannot be committed here)
into a folder, for the before/after thumbnails in docs/images (scripts/make-look-thumbnails.sh):

  lamp.gltf          like LightsPunctualLamp: a desk lamp on a table, point lights of 1.5 to
                     180 cd (the real model's range) and a 400 cd spot, no camera;
  transmission.gltf  like TransmissionTest: transmission-1 spheres with base colours over a
                     checker cloth, no camera or lights;
  attenuation.gltf   like AttenuationTest: KHR_materials_volume blocks with attenuationColor and
                     thickness over a checker cloth, no camera or lights.

Pure standard library: geometry is generated here, packed into one base64 buffer per file. The
Gltf writer (normals, texture coordinates, PNG textures from png()) also serves
feature_standins.py beside it.
Usage: look_standins.py OUT_DIR
"""
import base64
import json
import math
import os
import struct
import sys
import zlib


class Gltf:
    def __init__(self):
        self.doc = {"asset": {"version": "2.0", "generator": "deepvox look_standins.py"},
                    "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                    "materials": [], "accessors": [], "bufferViews": []}
        self.bin = bytearray()

    def _view(self, data):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["bufferViews"].append(
            {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def _floats(self, rows, kind, bounds=False):
        flat = [c for r in rows for c in r]
        accessor = {"bufferView": self._view(struct.pack("<%df" % len(flat), *flat)),
                    "componentType": 5126, "count": len(rows), "type": kind}
        if bounds:
            accessor["min"] = [min(r[i] for r in rows) for i in range(len(rows[0]))]
            accessor["max"] = [max(r[i] for r in rows) for i in range(len(rows[0]))]
        self.doc["accessors"].append(accessor)
        return len(self.doc["accessors"]) - 1

    def mesh(self, positions, triangles, material, normals=None, uvs=None):
        """A mesh of one primitive; NORMAL and TEXCOORD_0 when given (one per position)."""
        attributes = {"POSITION": self._floats(positions, "VEC3", bounds=True)}
        if normals:
            attributes["NORMAL"] = self._floats(normals, "VEC3")
        if uvs:
            attributes["TEXCOORD_0"] = self._floats(uvs, "VEC2")
        idx = [i for t in triangles for i in t]
        iv = self._view(struct.pack("<%dI" % len(idx), *idx))
        self.doc["accessors"].append({"bufferView": iv, "componentType": 5125,
                                      "count": len(idx), "type": "SCALAR"})
        self.doc["meshes"].append({"primitives": [
            {"attributes": attributes, "indices": len(self.doc["accessors"]) - 1,
             "material": material}]})
        return len(self.doc["meshes"]) - 1

    def texture(self, png_bytes):
        """A texture of an embedded PNG (a data: URI), sampled linearly with repeat."""
        self.doc.setdefault("images", []).append(
            {"uri": "data:image/png;base64," + base64.b64encode(png_bytes).decode()})
        if "samplers" not in self.doc:
            self.doc["samplers"] = [{"magFilter": 9729, "minFilter": 9729}]
        self.doc.setdefault("textures", []).append(
            {"source": len(self.doc["images"]) - 1, "sampler": 0})
        return len(self.doc["textures"]) - 1

    def material(self, color, roughness=0.6, alpha=1.0, fields=None, **extensions):
        """A dielectric PBR material; `fields` adds top-level material keys (alphaMode,
        normalTexture, ...) and pbrMetallicRoughness keys under "pbr"."""
        m = {"pbrMetallicRoughness": {"baseColorFactor": list(color) + [alpha],
                                      "metallicFactor": 0.0, "roughnessFactor": roughness}}
        for key, value in (fields or {}).items():
            if key == "pbr":
                m["pbrMetallicRoughness"].update(value)
            else:
                m[key] = value
        if extensions:
            m["extensions"] = extensions
            for name in extensions:
                self.use(name)
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def use(self, name):
        used = self.doc.setdefault("extensionsUsed", [])
        if name not in used:
            used.append(name)

    def node(self, **fields):
        self.doc["nodes"].append(fields)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def light(self, kind, intensity, color=(1, 1, 1), **fields):
        self.use("KHR_lights_punctual")
        lights = self.doc.setdefault("extensions", {}).setdefault(
            "KHR_lights_punctual", {"lights": []})["lights"]
        lights.append(dict(type=kind, intensity=intensity, color=list(color), **fields))
        return {"KHR_lights_punctual": {"light": len(lights) - 1}}

    def write(self, path):
        self.doc["buffers"] = [{"byteLength": len(self.bin), "uri":
                                "data:application/octet-stream;base64," +
                                base64.b64encode(bytes(self.bin)).decode()}]
        with open(path, "w") as f:
            json.dump(self.doc, f)


def png(width, height, pixel):
    """An 8-bit RGBA PNG of pixel(x, y) -> (r, g, b, a) bytes, rows from the top. The zlib
    stream holds stored (uncompressed) deflate blocks, so the bytes are the same with every
    zlib build (compressed streams differ between zlib versions)."""
    raw = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y))
                   for y in range(height))
    stream = bytearray(b"\x78\x01")
    for start in range(0, max(len(raw), 1), 65535):
        block = raw[start:start + 65535]
        last = start + 65535 >= len(raw)
        stream += struct.pack("<BHH", last, len(block), len(block) ^ 0xFFFF) + block
    stream += struct.pack(">I", zlib.adler32(raw))

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body)))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0,
                                                              0, 0)) +
            chunk(b"IDAT", bytes(stream)) + chunk(b"IEND", b""))


def box(lo, hi):
    p = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return p, [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]


def lathe(profile, segments=32):
    """Closed surface of revolution about +y through (radius, y) points, first and last on
    the axis or closed by caps."""
    pos, tris = [], []
    rings = []
    for r, y in profile:
        ring = []
        for s in range(segments if r > 0 else 1):
            a = 2 * math.pi * s / segments
            ring.append(len(pos))
            pos.append((r * math.cos(a), y, -r * math.sin(a)))
        rings.append(ring)
    for lower, upper in zip(rings, rings[1:]):
        for s in range(segments):
            a0, a1 = lower[s % len(lower)], lower[(s + 1) % len(lower)]
            b0, b1 = upper[s % len(upper)], upper[(s + 1) % len(upper)]
            if a0 != a1:
                tris.append((a0, a1, b1) if b0 == b1 else (a0, a1, b0))
            if b0 != b1:
                tris.append((a1, b1, b0))
    return pos, tris


def sphere(radius, segments=24, rings=12):
    profile = [(radius * math.sin(math.pi * i / rings), -radius * math.cos(math.pi * i / rings))
               for i in range(rings + 1)]
    profile[0], profile[-1] = (0.0, -radius), (0.0, radius)
    return lathe(profile, segments)


def checker(size, cells, y, materials, g):
    """A checker cloth as two meshes of alternating squares (deepvox reads no textures)."""
    parts = ([], []), ([], [])
    step = 2 * size / cells
    for i in range(cells):
        for j in range(cells):
            pos, tris = parts[(i + j) % 2]
            x0, z0 = -size + i * step, -size + j * step
            base = len(pos)
            pos += [(x0, y, z0), (x0, y, z0 + step), (x0 + step, y, z0 + step), (x0 + step, y, z0)]
            tris += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    for (pos, tris), m in zip(parts, materials):
        g.node(mesh=g.mesh(pos, tris, m))


def lamp(path):
    g = Gltf()
    wood = g.material((0.45, 0.28, 0.15))
    metal = g.material((0.8, 0.8, 0.75), roughness=0.3)
    shade = g.material((0.95, 0.9, 0.8), KHR_materials_transmission={"transmissionFactor": 0.5})
    g.node(mesh=g.mesh(*box((-1.2, -0.1, -1.2), (1.2, 0.0, 1.2)), wood))
    g.node(mesh=g.mesh(*lathe([(0, 0), (0.35, 0), (0.3, 0.06), (0, 0.06)]), metal))
    g.node(mesh=g.mesh(*box((-0.03, 0.06, -0.03), (0.03, 0.9, 0.03)), metal))
    g.node(mesh=g.mesh(*lathe([(0.2, 1.15), (0.42, 0.75), (0.4, 0.75), (0.18, 1.15)]), shade))
    g.node(mesh=g.mesh(*sphere(0.12), wood), translation=[0.7, 0.12, 0.5])
    # The real model's point lights: warm bulb 180 cd, two teal 80 cd, warm 15 cd, white 1.5 cd.
    g.node(translation=[0, 0.9, 0], extensions=g.light("point", 180, (1, 0.63, 0.5)))
    g.node(translation=[-1.0, 0.6, 0.8], extensions=g.light("point", 80, (0.21, 0.59, 0.56)))
    g.node(translation=[1.0, 0.6, -0.8], extensions=g.light("point", 80, (0.21, 0.59, 0.56)))
    g.node(translation=[0.3, 1.4, 0.9], extensions=g.light("point", 15, (1, 0.63, 0.24)))
    g.node(translation=[-0.5, 1.6, -0.5], extensions=g.light("point", 1.5))
    # A spot of 400 cd from above and in front, shining down at 60 degrees.
    g.node(translation=[0, 2.2, 1.6], rotation=[-0.5, 0, 0, 0.8660254],
           extensions=g.light("spot", 400, spot={"innerConeAngle": 0.3, "outerConeAngle": 0.6}))
    g.write(path)


def transmission(path):
    g = Gltf()
    checker(1.6, 8, 0.0, [g.material((0.8, 0.8, 0.8)), g.material((0.15, 0.15, 0.2))], g)
    colours = [(1, 1, 1), (1, 0.3, 0.3), (0.3, 1, 0.3), (0.3, 0.4, 1)]
    for i, c in enumerate(colours):
        m = g.material(c, roughness=0.05,
                       KHR_materials_transmission={"transmissionFactor": 1.0})
        g.node(mesh=g.mesh(*sphere(0.3), m), translation=[-1.05 + 0.7 * i, 0.35, 0])
    g.write(path)


def attenuation(path):
    g = Gltf()
    checker(1.6, 8, 0.0, [g.material((0.8, 0.8, 0.8)), g.material((0.15, 0.15, 0.2))], g)
    colours = [(0.9, 0.2, 0.2), (0.2, 0.8, 0.3), (0.2, 0.4, 0.9), (0.9, 0.7, 0.2)]
    for i, c in enumerate(colours):
        m = g.material((1, 1, 1), roughness=0.05,
                       KHR_materials_transmission={"transmissionFactor": 1.0},
                       KHR_materials_volume={"thicknessFactor": 0.4, "attenuationColor": list(c),
                                             "attenuationDistance": 0.3})
        g.node(mesh=g.mesh(*box((-0.25, 0.0, -0.25), (0.25, 0.6, 0.25)), m),
               translation=[-1.05 + 0.7 * i, 0.0, 0])
    g.write(path)


if __name__ == "__main__":
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    lamp(os.path.join(out, "lamp.gltf"))
    transmission(os.path.join(out, "transmission.gltf"))
    attenuation(os.path.join(out, "attenuation.gltf"))
