#!/usr/bin/env python3
"""Writes bench_voxelizer's meshes as OBJ files, for the peer voxelizer comparison.

bench_voxelizer (experiments/bench_voxelizer.cpp) builds its meshes at run time with deepvox's
generators (render/load/mesh_generators.cpp); the peer (cuda_voxelizer) reads mesh files. This
script writes the same triangles, so both sides can read one file each:

  bunny2.obj  make_bunny(assets, 2): experiments/assets/meshes/stanford-bunny-lowres.obj
              (1,839 vertices, 3,674 triangles) midpoint-subdivided twice: 58,784 triangles
  bunny3.obj  the same subdivided three times: 235,136 triangles
  cube.obj    make_box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}): 8 vertices, 12 triangles

Same vertex order, triangle order and corner order as the generators. make_bunny also passes
the scan through orient_outward (CGAL), which leaves this scan unchanged: it is closed and
wound outward (positive signed volume); a round trip through the same CGAL calls kept every
vertex, triangle and corner in place. This script checks the first two facts and stops if they
fail. Coordinates are written as the shortest decimal that reads back as the same double (so
deepvox's loader gets the generator's doubles exactly; trimesh2 rounds them to float).

Usage: write_bench_meshes.py [OUT_DIR] (default: .peer/meshes of this checkout). Pure Python.
"""
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
SCAN = ROOT / "experiments" / "assets" / "meshes" / "stanford-bunny-lowres.obj"


def read_obj(path):
    """Vertices and triangles as deepvox's load_mesh_file reads them (polygons fanned around
    their first corner)."""
    positions, triangles = [], []
    for line in path.read_text().splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            positions.append(tuple(float(x) for x in parts[1:4]))
        elif parts[0] == "f":
            face = [int(c.split("/")[0]) for c in parts[1:]]
            face = [i - 1 if i > 0 else len(positions) + i for i in face]
            for k in range(1, len(face) - 1):
                triangles.append((face[0], face[k], face[k + 1]))
    return positions, triangles


def check_closed_outward(positions, triangles):
    directed, undirected = {}, {}
    for t in triangles:
        for k in range(3):
            a, b = t[k], t[(k + 1) % 3]
            directed[(a, b)] = directed.get((a, b), 0) + 1
            key = (min(a, b), max(a, b))
            undirected[key] = undirected.get(key, 0) + 1
    closed = all(n == 2 for n in undirected.values()) and all(n == 1 for n in directed.values())
    volume = 0.0
    for a, b, c in triangles:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = positions[a], positions[b], positions[c]
        volume += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
    if not closed or volume <= 0.0:
        sys.exit("write_bench_meshes.py: %s is no longer closed and wound outward: deepvox's "
                 "orient_outward/close_holes would change it; this script cannot follow" % SCAN)


def midpoint_subdivide_once(positions, triangles):
    """deepvox's midpoint_subdivide_once: new vertices in order of first use, 4 triangles each."""
    out = list(positions)
    index = {}

    def midpoint(a, b):
        key = (min(a, b), max(a, b))
        if key not in index:
            index[key] = len(out)
            pa, pb = positions[a], positions[b]
            out.append(tuple(0.5 * (pa[i] + pb[i]) for i in range(3)))
        return index[key]

    result = []
    for x, y, z in triangles:
        ab, bc, ca = midpoint(x, y), midpoint(y, z), midpoint(z, x)
        result += [(x, ab, ca), (ab, y, bc), (ca, bc, z), (ab, bc, ca)]
    return out, result


def make_box(lo, hi):
    positions = [(hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2])
                 for i in range(8)]
    faces = [(0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6)]
    triangles = []
    for q in faces:
        triangles += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
    return positions, triangles


def write_obj(path, what, positions, triangles):
    lines = ["# %s: %d vertices, %d triangles (experiments/peer/write_bench_meshes.py)"
             % (what, len(positions), len(triangles))]
    lines += ["v %r %r %r" % p for p in positions]
    lines += ["f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in triangles]
    path.write_text("\n".join(lines) + "\n")
    print("%s: %d triangles" % (path, len(triangles)))


def main():
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / ".peer" / "meshes"
    out.mkdir(parents=True, exist_ok=True)
    positions, triangles = read_obj(SCAN)
    check_closed_outward(positions, triangles)
    for k in range(1, 4):
        positions, triangles = midpoint_subdivide_once(positions, triangles)
        if k >= 2:
            write_obj(out / ("bunny%d.obj" % k), "bunny midpoint-subdivided %d times" % k,
                      positions, triangles)
    write_obj(out / "cube.obj", "box -0.5..0.5", *make_box((-0.5,) * 3, (0.5,) * 3))


if __name__ == "__main__":
    main()
