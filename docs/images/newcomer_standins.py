#!/usr/bin/env python3
"""Writes and renders the stand-ins of the two newcomer items of the real-asset pass whose
models cannot be committed (thumbnails for docs/history.md, 200x150, CPU, render's defaults):

  texture-transform.gltf   like TextureTransformTest's Rotation panel: two quads side by side
                           with one asymmetric texture (red top, green bottom left, blue bottom
                           right); the left quad turns it with KHR_texture_transform rotation
                           0.6 rad, the right quad's UVs are turned by hand by the spec's matrix
                           R = [[cos, sin], [-sin, cos]] with no extension. Right as the spec
                           says when the two quads look the same.
  texture-transform-transposed.gltf
                           the same with the left quad's rotation negated: what a renderer that
                           turns with the transposed matrix (deepvox before the fix) draws for
                           the first file (the "before" thumbnail; no older binary is kept);
  missing-image.gltf       like MosquitoInAmber or FlightHelmet with one image absent: a quad
                           whose base-colour texture names missing-colour.png, factor orange.
                           Before the fix deepvox refused the whole model (exit 2); now it
                           warns once, naming the file, and draws the factor.

Usage: newcomer_standins.py DEEPVOX [OUT_DIR]   (OUT_DIR default docs/images)
"""
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from feature_standins import Gltf, png, quad, surface  # noqa: E402


def asymmetric(x, y):
    """64 x 64: red top half, green bottom left, blue bottom right, a white border."""
    if x < 2 or y < 2 or x > 61 or y > 61:
        return (255, 255, 255, 255)
    if y < 32:
        return (220, 40, 40, 255)
    return (40, 200, 60, 255) if x < 32 else (40, 80, 230, 255)


def turned(uv, angle):
    """The spec's rotation of a texture coordinate (KHR_texture_transform: rows of R)."""
    c, s = math.cos(angle), math.sin(angle)
    u, v = uv
    return (c * u + s * v, -s * u + c * v)


def texture_transform(path, angle):
    g = Gltf()
    g.use("KHR_texture_transform")
    texture = g.texture(png(64, 64, asymmetric))
    with_extension = g.material((1, 1, 1), fields={"doubleSided": True, "pbr": {
        "baseColorTexture": {"index": texture, "extensions": {
            "KHR_texture_transform": {"rotation": angle}}}}})
    by_hand = g.material((1, 1, 1), fields={"doubleSided": True,
                                             "pbr": {"baseColorTexture": {"index": texture}}})
    g.node(name="rotated by the extension", mesh=surface(g, quad(1.0, 1.0, (-0.6, 0.6, 0)),
                                                         with_extension))
    pos, tris, normals, uvs = quad(1.0, 1.0, (0.6, 0.6, 0))
    g.node(name="rotated by hand", mesh=g.mesh(pos, tris, by_hand, normals,
                                               [turned(uv, 0.6) for uv in uvs]))
    g.write(path)


def missing_image(path):
    g = Gltf()
    g.doc.setdefault("images", []).append({"uri": "missing-colour.png"})
    g.doc["samplers"] = [{"magFilter": 9729, "minFilter": 9729}]
    g.doc.setdefault("textures", []).append({"source": 0, "sampler": 0})
    orange = g.material((1.0, 0.55, 0.1), fields={
        "doubleSided": True, "pbr": {"baseColorTexture": {"index": 0}}})
    g.node(name="quad with a missing image", mesh=surface(g, quad(1.2, 1.2, (0, 0.6, 0)), orange))
    g.write(path)


def main():
    if len(sys.argv) not in (2, 3):
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    binary = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) == 3 else HERE
    with tempfile.TemporaryDirectory() as tmp:
        scenes = {"texture-transform-after": lambda p: texture_transform(p, 0.6),
                  "texture-transform-before": lambda p: texture_transform(p, -0.6),
                  "missing-image-after": missing_image}
        for name, make in scenes.items():
            scene = os.path.join(tmp, name + ".gltf")
            make(scene)
            result = subprocess.run([binary, "render", scene, "--backend", "cpu", "--width",
                                     "200", "--height", "150", "--out",
                                     os.path.join(out, name + ".png")],
                                    capture_output=True, text=True)
            print(f"{name}: exit {result.returncode}; {result.stderr.strip()}")


if __name__ == "__main__":
    main()
