#!/usr/bin/env python3
"""Writes the two glass spheres of scenes/glass: a UV sphere of radius 1 (12 stacks x 20
slices, 440 triangles) with a `vn` line per vertex (the exact sphere normal, pointing out),
wound counter-clockwise seen from outside (`sphere.obj`: winding and normals agree) and
clockwise (`sphere-cw.obj`: the faces' winding points in while the normals point out).
Deterministic; Python 3 standard library only."""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def write(path, clockwise, stacks=12, slices=20):
    v = [(0.0, 1.0, 0.0)]
    for i in range(1, stacks):
        th = math.pi * i / stacks
        for j in range(slices):
            ph = 2 * math.pi * j / slices
            v.append((math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph)))
    v.append((0.0, -1.0, 0.0))
    ring = lambda i, j: 2 + (i - 1) * slices + (j % slices)  # 1-based OBJ index
    faces = [(1, ring(1, j), ring(1, j + 1)) for j in range(slices)]
    for i in range(1, stacks - 1):
        for j in range(slices):
            a, b, c, d = ring(i, j), ring(i, j + 1), ring(i + 1, j), ring(i + 1, j + 1)
            faces += [(a, c, d), (a, d, b)]
    faces += [(ring(stacks - 1, j), len(v), ring(stacks - 1, j + 1)) for j in range(slices)]
    with open(path, "w") as o:
        o.write("# scenes/glass: unit UV sphere, %s seen from outside, normals out\n"
                % ("clockwise" if clockwise else "counter-clockwise"))
        for p in v:
            o.write("v %.6f %.6f %.6f\n" % p)
        for p in v:
            o.write("vn %.6f %.6f %.6f\n" % p)
        for f in faces:
            if clockwise:
                f = (f[0], f[2], f[1])
            o.write("f " + " ".join(f"{k}//{k}" for k in f) + "\n")


if __name__ == "__main__":
    write(os.path.join(HERE, "sphere.obj"), clockwise=False)
    write(os.path.join(HERE, "sphere-cw.obj"), clockwise=True)
