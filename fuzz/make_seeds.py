#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpus, fuzz/seeds/<target>/, from the bundled scenes.

    python3 fuzz/make_seeds.py target/release/footprint

Scenes and meshes are rewritten to the file names the harnesses use (footprint_app::fuzz:
scene.toml or scene.xml, mesh.obj, mesh.mtl, texture.png) and joined into one input with
the harnesses' separator line. The PLY and .serialized seeds are scenes/meshes' files and
small files written here (`ply_seeds`, `serialized_seeds`). The maps file and the shard EXRs are made by the binary
given (`footprint maps --save`, `footprint render --shard`) on the Cornell box at 4x4 pixels
with a few hundred paths, to keep them small.
"""
import os
import re
import struct
import subprocess
import sys
import tempfile
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SEEDS = os.path.join(ROOT, "fuzz", "seeds")
SEPARATOR = b"\n#%%next-file%%\n"
# Meshes larger than this are left out of the seeds (the fuzzer's inputs stay small).
MAX_MESH = 30_000


def read(rel):
    with open(os.path.join(ROOT, "scenes", rel), "rb") as f:
        return f.read()


def write(target, name, parts):
    d = os.path.join(SEEDS, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(SEPARATOR.join(parts))


def obj_as_mesh(obj):
    return re.sub(rb"mtllib \S+", b"mtllib mesh.mtl", obj)


def toml_seeds():
    for scene, obj, mtl in [
        ("cornell/cornell.toml", "cornell/cornell.obj", "cornell/cornell.mtl"),
        ("door/door.toml", "door/door.obj", "door/door.mtl"),
        ("desk/desk.toml", "desk/desk.obj", "desk/desk.mtl"),
    ]:
        text = re.sub(rb'file = "[^"]*"', b'file = "mesh.obj"', read(scene))
        name = os.path.basename(scene).removesuffix(".toml")
        write("toml_scene", name, [text, obj_as_mesh(read(obj)), read(mtl)])
        write("obj", name, [obj_as_mesh(read(obj)), read(mtl)])
    write("obj", "bent_panel", [read("ltcheck/bent_panel.obj")])
    write("obj", "lowpoly_sphere", [read("ltcheck/lowpoly_sphere.obj")])


def xml_seeds():
    for scene, mesh, texture in [
        ("cornell/mitsuba/scene.xml", "cornell/mitsuba/meshes/m0_white.obj", None),
        ("door/mitsuba/scene.xml", "door/mitsuba/meshes/m3_door.obj", None),
        ("desk/mitsuba/scene.xml", "desk/mitsuba/meshes/m8_book.obj", None),
        ("ltcheck/scene.xml", "ltcheck/bent_panel.obj", None),
        ("glass/scene.xml", "ltcheck/lowpoly_sphere.obj", None),
        ("features/scene.xml", None, "features/tiles.png"),
        ("panes/scene.xml", None, None),
        ("slit/scene.xml", None, None),
    ]:
        text = read(scene)
        text = re.sub(rb'value="[^"]*\.obj"', b'value="mesh.obj"', text)
        text = re.sub(rb'value="[^"]*\.png"', b'value="texture.png"', text)
        parts = [text, read(mesh) if mesh else b""]
        if texture:
            parts.append(read(texture))
        name = scene.split("/")[0] + ("-mitsuba" if "/mitsuba/" in scene else "")
        write("mitsuba_scene", name, parts)


def quad_mesh():
    """Two quads and a triangle, with normals and texture coordinates."""
    v = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (2, 0, 0), (2, 1, 0.5), (0.5, 0.5, 1)]
    n = [(0, 0, 1)] * 6 + [(0, 0.6, 0.8)]
    t = [(p[0] / 2, p[1]) for p in v]
    faces = [(0, 1, 2, 3), (1, 4, 5, 2), (0, 1, 6)]
    return v, n, t, faces


def ply_seeds():
    """PLY files: Mitsuba's own binary torus (scenes/meshes), an ASCII file of quads with
    normals, texture coordinates (s t), a comment and an extra element, and the same as big
    endian binary with double positions, a colour and uint lists."""
    write("ply", "torus-binary", [read("meshes/torus.ply")])
    v, n, t, faces = quad_mesh()
    head = ("ply\nformat {fmt} 1.0\ncomment fuzz seed\nelement vertex %d\n" % len(v)
            + "{x}{extra}property float nx\nproperty float ny\nproperty float nz\n"
            + "property float s\nproperty float t\n"
            + "element face %d\nproperty list {count} int vertex_indices\n" % len(faces)
            + "element note 1\nproperty uchar tag\nend_header\n")
    xyz = "property float x\nproperty float y\nproperty float z\n"
    text = head.format(fmt="ascii", x=xyz, extra="", count="uchar")
    for p, q, r in zip(v, n, t):
        text += " ".join("%g" % x for x in p + q + r) + "\n"
    for f in faces:
        text += "%d %s\n" % (len(f), " ".join(map(str, f)))
    text += "7\n"
    write("ply", "quads-ascii", [text.encode()])
    dxyz = xyz.replace("float", "double")
    data = head.format(fmt="binary_big_endian", x=dxyz, extra="property uchar red\n",
                       count="uint").encode()
    for p, q, r in zip(v, n, t):
        data += struct.pack(">dddB5f", *p, 200, *q, *r)
    for f in faces:
        data += struct.pack(">I%di" % len(f), len(f), *f)
    data += b"\x07"
    write("ply", "quads-big-endian", [data])


def serialized_mesh(version, v, n, t, tris):
    """One mesh of a .serialized file, single precision, with normals and texture
    coordinates (Mitsuba 3's documentation, "Serialized mesh loader")."""
    body = struct.pack("<I", 0x1003) + (b"seed\0" if version == 4 else b"")
    body += struct.pack("<QQ", len(v), len(tris))
    for arr in (v, n, t):
        body += b"".join(struct.pack("<f", x) for p in arr for x in p)
    body += b"".join(struct.pack("<III", *f) for f in tris)
    return struct.pack("<HH", 0x041C, version) + zlib.compress(body)


def serialized_seeds():
    """The first byte picks the mesh (shape_index = byte % 4), the rest is the file: both
    meshes of scenes/meshes/meshes.serialized (version 4), and a version 3 file of two
    meshes with its table of u32 offsets."""
    data = read("meshes/meshes.serialized")
    write("serialized", "meshes-0", [b"\x00" + data])
    write("serialized", "meshes-1", [b"\x01" + data])
    v, n, t, faces = quad_mesh()
    tris = [(f[0], f[k - 1], f[k]) for f in faces for k in range(2, len(f))]
    a = serialized_mesh(3, v, n, t, tris)
    b = serialized_mesh(3, v[:3], n[:3], t[:3], [(0, 1, 2)])
    v3 = a + b + struct.pack("<III", 0, len(a), 2)
    write("serialized", "v3-0", [b"\x00" + v3])
    write("serialized", "v3-1", [b"\x01" + v3])


def binary_seeds(footprint):
    scene = os.path.join(ROOT, "scenes", "cornell", "cornell.toml")
    with tempfile.TemporaryDirectory() as tmp:
        fpm = os.path.join(tmp, "maps.fpm")
        subprocess.run(
            [footprint, "maps", scene, "--save", fpm, "--resolution", "4x4",
             "--photons", "40", "--importons", "40", "--threads", "1"],
            check=True, stdout=subprocess.DEVNULL)
        with open(fpm, "rb") as f:
            data = f.read()
        # Mode 0: the file as it is; mode 1: its payload (the harness adds the header).
        write("maps_file", "cornell-file", [b"\x00" + data])
        write("maps_file", "cornell-payload", [b"\x01" + data[52:]])
        def shard(i, n):
            out = os.path.join(tmp, f"s{i}-{n}.exr")
            subprocess.run(
                [footprint, "render", scene, "--integrator", "pt", "--guide", "bsdf",
                 "--spp", "2", "--shard", f"{i}/{n}", "--resolution", "4x4",
                 "--threads", "1", "--out", out],
                check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            with open(out, "rb") as f:
                return f.read()
        write("shard_merge", "cornell-2-shards", [shard(0, 2), shard(1, 2)])
        write("shard_merge", "cornell-1-shard", [shard(0, 1)])


if __name__ == "__main__":
    toml_seeds()
    xml_seeds()
    ply_seeds()
    serialized_seeds()
    if len(sys.argv) > 1:
        binary_seeds(sys.argv[1])
