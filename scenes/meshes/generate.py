#!/usr/bin/env python3
"""Writes the mesh files of scenes/meshes, each small (deterministic):

* `torus.obj`: a torus (major radius 0.5, minor 0.2; 24 x 12 quads as 576 triangles) with
  the exact normals (`vn`) and texture coordinates (`vt`, u around the main ring, v around
  the tube), written here as text.
* `torus.ply`: the same torus as Mitsuba 3 reads the OBJ and writes it (`Mesh.write_ply`,
  binary little endian, with normals and texture coordinates; Mitsuba flips the OBJ's v on
  reading, so the PLY holds 1 - v).
* `meshes.serialized`: Mitsuba's .serialized format, version 4, two meshes, written here
  with zlib (Mitsuba 3 writes no .serialized files): mesh 0 an octahedron of radius 0.35 in
  single precision without normals or texture coordinates (the reader computes the normals),
  mesh 1 the torus in double precision with its normals and texture coordinates (Mitsuba's
  v, as in the PLY), then the table of offsets. The format is Mitsuba 3's documentation,
  "Serialized mesh loader".

    python3 scenes/meshes/generate.py     # needs the `mitsuba` package for the PLY
"""
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
MAJOR, MINOR, RINGS, SIDES = 0.5, 0.2, 24, 12


def torus():
    """Vertices (position, normal, OBJ uv) on a (RINGS + 1) x (SIDES + 1) grid, seams
    duplicated, and triangles wound counter-clockwise seen from outside."""
    verts = []
    for i in range(RINGS + 1):
        a = 2 * math.pi * i / RINGS
        for j in range(SIDES + 1):
            b = 2 * math.pi * j / SIDES
            n = (math.cos(a) * math.cos(b), math.sin(a) * math.cos(b), math.sin(b))
            c = (MAJOR * math.cos(a), MAJOR * math.sin(a), 0.0)
            p = tuple(c[k] + MINOR * n[k] for k in range(3))
            verts.append((p, n, (i / RINGS, j / SIDES)))
    tris = []
    row = SIDES + 1
    for i in range(RINGS):
        for j in range(SIDES):
            a, b = i * row + j, i * row + j + 1
            c, d = a + row, b + row
            tris += [(a, c, d), (a, d, b)]
    return verts, tris


def octahedron(r=0.35):
    p = [(r, 0, 0), (-r, 0, 0), (0, r, 0), (0, -r, 0), (0, 0, r), (0, 0, -r)]
    tris = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4),
            (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    return p, tris


def write_obj(path, verts, tris):
    with open(path, "w") as o:
        o.write("# scenes/meshes: torus, normals and texture coordinates (generate.py)\n")
        for p, _, _ in verts:
            o.write("v %.6f %.6f %.6f\n" % p)
        for _, n, _ in verts:
            o.write("vn %.6f %.6f %.6f\n" % n)
        for _, _, t in verts:
            o.write("vt %.6f %.6f\n" % t)
        for f in tris:
            o.write("f " + " ".join(f"{k + 1}/{k + 1}/{k + 1}" for k in f) + "\n")


def serialized_mesh(positions, tris, normals=None, uvs=None, double=False):
    """One mesh of a version 4 .serialized file: the header and the zlib stream."""
    flags = (0x2000 if double else 0x1000) | (0x0001 if normals else 0) | (0x0002 if uvs else 0)
    fmt = "<d" if double else "<f"
    body = struct.pack("<I", flags) + b"mesh\0" + struct.pack("<QQ", len(positions), len(tris))
    for arr in [positions, normals, uvs]:
        if arr:
            body += b"".join(struct.pack(fmt, x) for v in arr for x in v)
    body += b"".join(struct.pack("<III", *t) for t in tris)
    return struct.pack("<HH", 0x041C, 4) + zlib.compress(body, 9)


def main():
    verts, tris = torus()
    obj = os.path.join(HERE, "torus.obj")
    write_obj(obj, verts, tris)

    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    mi.load_dict({"type": "obj", "filename": obj}).write_ply(os.path.join(HERE, "torus.ply"))

    op, ot = octahedron()
    meshes = [
        serialized_mesh(op, ot),
        serialized_mesh([p for p, _, _ in verts], tris, normals=[n for _, n, _ in verts],
                        uvs=[(t[0], 1 - t[1]) for _, _, t in verts], double=True),
    ]
    out, offsets = b"", []
    for m in meshes:
        offsets.append(len(out))
        out += m
    out += b"".join(struct.pack("<Q", o) for o in offsets) + struct.pack("<I", len(meshes))
    with open(os.path.join(HERE, "meshes.serialized"), "wb") as f:
        f.write(out)


if __name__ == "__main__":
    main()
