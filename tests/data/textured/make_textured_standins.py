#!/usr/bin/env python3
"""Writes the textured glTF stand-ins that the texture tests read, built the way
sample models are (Khronos AlphaBlendModeTest-like cut-out quads, a textured and normal-mapped
model), since the real sample models cannot be committed here:

  alpha_mask_quad.gltf + alpha_mask.png
      a grey floor (y = 0, x and z in [-2, 2]) under two quads at y = 1 lit by a directional
      light straight down (no camera). Both quads use alpha_mask.png (8 x 8, NEAREST, CLAMP):
      texels with u < 0.5 have alpha 0, the others alpha 255, and the RGB is red.
        mask quad   x in [-1.5, -0.5], z in [-0.5, 0.5], alphaMode MASK, alphaCutoff 0.5;
        blend quad  x in [0.5, 1.5],   z in [-0.5, 0.5], alphaMode BLEND, baseColorFactor
                    alpha 0.4 (so its opaque texels let 0.6 of the light through).
      u runs with x across each quad, so the floor under each quad's x < centre half is lit.
  textured_sphere.glb
      a UV sphere (radius 1, 32 x 16 segments, smooth NORMALs, TEXCOORD_0) whose base-colour
      texture (a .glb image in a buffer view) is green for u < 0.5 and blue for u >= 0.5, with
      a flat normalTexture, on a white floor, lit by a directional light, seen by a camera on +z.
      u = 0 faces the camera (+z) and grows toward +x, so the camera sees green on its right
      (x > 0: u in (0, 0.25)) and blue on its left (x < 0: u in (0.75, 1)).

Pure standard library (PNG via zlib). Usage: make_textured_standins.py [OUT_DIR] (default:
beside this script).
"""
import base64
import json
import math
import os
import struct
import sys
import zlib


def png(width, height, rgba_rows):
    """PNG bytes of 8-bit RGBA rows (top row first), each a list of (r, g, b, a)."""
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rgba_rows)
    return (b"\x89PNG\r\n\x1a\n" +
            chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


class Gltf:
    def __init__(self):
        self.doc = {"asset": {"version": "2.0", "generator": "deepvox make_textured_standins.py"},
                    "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                    "materials": [], "accessors": [], "bufferViews": []}
        self.bin = bytearray()

    def view(self, data):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["bufferViews"].append(
            {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, values, width, kind, component=5126, fmt="f"):
        flat = [c for v in values for c in (v if width > 1 else (v,))]
        entry = {"bufferView": self.view(struct.pack("<%d%s" % (len(flat), fmt), *flat)),
                 "componentType": component, "count": len(values), "type": kind}
        if kind == "VEC3":
            entry["min"] = [min(v[i] for v in values) for i in range(3)]
            entry["max"] = [max(v[i] for v in values) for i in range(3)]
        self.doc["accessors"].append(entry)
        return len(self.doc["accessors"]) - 1

    def mesh(self, positions, triangles, material, uvs=None, normals=None):
        attributes = {"POSITION": self.accessor(positions, 3, "VEC3")}
        if uvs:
            attributes["TEXCOORD_0"] = self.accessor(uvs, 2, "VEC2")
        if normals:
            attributes["NORMAL"] = self.accessor(normals, 3, "VEC3")
        indices = self.accessor([i for t in triangles for i in t], 1, "SCALAR", 5125, "I")
        self.doc["meshes"].append({"primitives": [
            {"attributes": attributes, "indices": indices, "material": material}]})
        return len(self.doc["meshes"]) - 1

    def texture(self, image, sampler):
        self.doc.setdefault("images", []).append(image)
        self.doc.setdefault("samplers", []).append(sampler)
        self.doc.setdefault("textures", []).append(
            {"source": len(self.doc["images"]) - 1, "sampler": len(self.doc["samplers"]) - 1})
        return len(self.doc["textures"]) - 1

    def material(self, color, alpha=1.0, **fields):
        m = {"pbrMetallicRoughness": {"baseColorFactor": list(color) + [alpha],
                                      "metallicFactor": 0.0, "roughnessFactor": 0.8}}
        texture = fields.pop("texture", None)
        if texture is not None:
            m["pbrMetallicRoughness"]["baseColorTexture"] = {"index": texture}
        m.update(fields)
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def node(self, **fields):
        self.doc["nodes"].append(fields)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def sun(self, intensity):
        """A directional light straight down of `intensity` lux (683 lux: irradiance 1)."""
        self.doc["extensionsUsed"] = ["KHR_lights_punctual"]
        self.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
            {"type": "directional", "intensity": intensity, "color": [1, 1, 1]}]}}
        # The light shines along its node's -z: rotate -z onto -y (90 degrees about +x).
        s = math.sqrt(0.5)
        self.node(rotation=[-s, 0, 0, s], extensions={"KHR_lights_punctual": {"light": 0}})

    def write_gltf(self, path):
        self.doc["buffers"] = [{"byteLength": len(self.bin), "uri":
                                "data:application/octet-stream;base64," +
                                base64.b64encode(bytes(self.bin)).decode()}]
        with open(path, "w") as f:
            json.dump(self.doc, f, indent=1)
            f.write("\n")

    def write_glb(self, path):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["buffers"] = [{"byteLength": len(self.bin)}]
        text = json.dumps(self.doc).encode()
        text += b" " * (-len(text) % 4)
        body = bytes(self.bin)
        with open(path, "wb") as f:
            f.write(b"glTF" + struct.pack("<II", 2, 12 + 8 + len(text) + 8 + len(body)))
            f.write(struct.pack("<I", len(text)) + b"JSON" + text)
            f.write(struct.pack("<I", len(body)) + b"BIN\x00" + body)


def quad_y(x0, x1, z0, z1, y):
    """A quad facing +y with u along x and v along z."""
    positions = [(x0, y, z0), (x1, y, z0), (x1, y, z1), (x0, y, z1)]
    uvs = [(0, 0), (1, 0), (1, 1), (0, 1)]
    return positions, [(0, 3, 2), (0, 2, 1)], uvs


def alpha_mask_quad(out_dir):
    g = Gltf()
    red, clear = (200, 30, 30, 255), (200, 30, 30, 0)
    rows = [[clear] * 4 + [red] * 4 for _ in range(8)]
    with open(os.path.join(out_dir, "alpha_mask.png"), "wb") as f:
        f.write(png(8, 8, rows))
    texture = g.texture({"uri": "alpha_mask.png"},
                        {"magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 33071})
    floor_positions, floor_tris, _ = quad_y(-2, 2, -2, 2, 0)
    g.node(mesh=g.mesh(floor_positions, floor_tris, g.material((0.7, 0.7, 0.7))), name="floor")
    mask = g.material((1, 1, 1), texture=texture, alphaMode="MASK", alphaCutoff=0.5)
    blend = g.material((1, 1, 1), alpha=0.4, texture=texture, alphaMode="BLEND")
    for name, material, x0 in (("mask", mask, -1.5), ("blend", blend, 0.5)):
        positions, tris, uvs = quad_y(x0, x0 + 1, -0.5, 0.5, 1)
        g.node(mesh=g.mesh(positions, tris, material, uvs=uvs), name=name)
    g.sun(1366.0)
    g.write_gltf(os.path.join(out_dir, "alpha_mask_quad.gltf"))


def textured_sphere(out_dir):
    g = Gltf()
    green, blue = (20, 200, 40, 255), (30, 40, 220, 255)
    image = png(16, 8, [[green] * 8 + [blue] * 8 for _ in range(8)])
    texture = g.texture({"bufferView": g.view(image), "mimeType": "image/png"},
                        {"magFilter": 9728, "minFilter": 9728})
    flat = png(1, 1, [[(128, 128, 255, 255)]])
    normal_map = g.texture({"bufferView": g.view(flat), "mimeType": "image/png"}, {})
    positions, normals, uvs, tris = [], [], [], []
    slices, stacks = 32, 16
    for j in range(stacks + 1):
        theta = math.pi * j / stacks
        for i in range(slices + 1):
            phi = 2 * math.pi * i / slices
            n = (math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi))
            positions.append(n)
            normals.append(n)
            uvs.append((i / slices, j / stacks))
    for j in range(stacks):
        for i in range(slices):
            a, b = j * (slices + 1) + i, (j + 1) * (slices + 1) + i
            if j > 0:
                tris.append((a, b, a + 1))
            if j < stacks - 1:
                tris.append((a + 1, b, b + 1))
    material = g.material((1, 1, 1), texture=texture, normalTexture={"index": normal_map})
    g.node(mesh=g.mesh(positions, tris, material, uvs=uvs, normals=normals), name="sphere")
    floor_positions, floor_tris, _ = quad_y(-3, 3, -3, 3, -1)
    g.node(mesh=g.mesh(floor_positions, floor_tris, g.material((1, 1, 1))), name="floor")
    g.doc["cameras"] = [{"type": "perspective",
                         "perspective": {"yfov": 0.7, "znear": 0.1, "aspectRatio": 1.0}}]
    g.node(camera=0, translation=[0, 0, 5])
    g.sun(1366.0)
    g.write_glb(os.path.join(out_dir, "textured_sphere.glb"))


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    alpha_mask_quad(out)
    textured_sphere(out)
