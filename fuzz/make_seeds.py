#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpus, fuzz/seeds/<target>/, from the bundled scenes.

    python3 fuzz/make_seeds.py target/release/footprint

Scenes and meshes are rewritten to the file names the harnesses use (footprint_app::fuzz:
scene.toml or scene.xml, mesh.obj, mesh.mtl, texture.png) and joined into one input with
the harnesses' separator line. The maps file and the shard EXRs are made by the binary
given (`footprint maps --save`, `footprint render --shard`) on the Cornell box at 4x4 pixels
with a few hundred paths, to keep them small.
"""
import os
import re
import subprocess
import sys
import tempfile

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
    if len(sys.argv) > 1:
        binary_seeds(sys.argv[1])
