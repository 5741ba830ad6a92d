#!/usr/bin/env python3
"""Speed (and a sanity check of the image) against Mitsuba 3 on a bundled scene.

Renders the same scene with footprint's unguided path tracer and with Mitsuba 3's `path`
integrator (variant `scalar_rgb`, the CPU variant that runs everywhere) at the same
resolution, samples per pixel and maximum depth, box pixel filter, both on all cores, and
prints the wall times, the time ratio and the image means.

    pip install mitsuba numpy          # once
    cargo build --release
    python3 scripts/bench_mitsuba.py --scene scenes/cornell/cornell.toml --spp 64

The scene's OBJ/MTL is read here and handed to Mitsuba as one mesh per material (diffuse
`Kd`, area emitter `Ke`); only what the bundled diffuse scenes use is translated. Depth:
footprint's max_depth counts path segments, as Mitsuba's max_depth does (1 = emitters seen
directly). Both use Russian roulette (footprint from depth 3, Mitsuba from depth 5).
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time
import tomllib

import numpy as np


def read_mtl(path):
    mats, cur = {}, None
    for line in open(path):
        t = line.split()
        if not t or t[0].startswith("#"):
            continue
        if t[0] == "newmtl":
            cur = mats.setdefault(t[1], {})
        elif cur is not None and t[0] in ("Kd", "Ke", "Ks"):
            cur[t[0]] = [float(x) for x in t[1:4]]
        elif cur is not None and t[0] in ("illum", "Ns"):
            cur[t[0]] = float(t[1])
    return mats


def read_obj(path):
    """Triangles grouped by material: {material: [(v0, v1, v2), ...]}."""
    verts, groups, mtllib, cur = [], {}, None, None
    for line in open(path):
        t = line.split()
        if not t:
            continue
        if t[0] == "v":
            verts.append([float(x) for x in t[1:4]])
        elif t[0] == "mtllib":
            mtllib = t[1]
        elif t[0] == "usemtl":
            cur = t[1]
        elif t[0] == "f":
            idx = [int(x.split("/")[0]) for x in t[1:]]
            idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
            for k in range(1, len(idx) - 1):
                groups.setdefault(cur, []).append((verts[idx[0]], verts[idx[k]], verts[idx[k + 1]]))
    return groups, mtllib


def mitsuba_scene(scene_path, spp, max_depth):
    import mitsuba as mi

    sc = tomllib.load(open(scene_path, "rb"))
    base = os.path.dirname(scene_path)
    cam = sc["camera"]
    w, h = cam["resolution"]
    d = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": max_depth},
        "sensor": {
            "type": "perspective",
            "fov": cam["fov_y"],
            "fov_axis": "y",
            "to_world": mi.ScalarTransform4f().look_at(
                origin=cam["position"], target=cam["look_at"], up=cam.get("up", [0, 1, 0])
            ),
            "sampler": {"type": "independent", "sample_count": spp},
            "film": {"type": "hdrfilm", "width": w, "height": h, "rfilter": {"type": "box"}, "pixel_format": "rgb"},
        },
    }
    if sc.get("light"):
        sys.exit("point/spot lights are not translated by this script")
    for mi_idx, m in enumerate(sc["mesh"]):
        if "transform" in m or "material" in m:
            sys.exit("mesh transforms/overrides are not translated by this script")
        groups, mtllib = read_obj(os.path.join(base, m["file"]))
        mats = read_mtl(os.path.join(base, mtllib))
        for gi, (name, tris) in enumerate(groups.items()):
            mat = mats.get(name, {"Kd": [0.5, 0.5, 0.5]})
            if mat.get("illum", 1) > 2 or max(mat.get("Ks", [0, 0, 0])) > 0:
                sys.exit(f"material {name} is not diffuse: not translated by this script")
            v = np.array([p for tri in tris for p in tri], dtype=np.float32)
            f = np.arange(len(v), dtype=np.uint32).reshape(-1, 3)
            bsdf = {"type": "diffuse", "reflectance": {"type": "rgb", "value": mat.get("Kd", [0.5] * 3)}}
            key = f"m{mi_idx}_{gi}"
            d[key] = {"type": "obj", "filename": write_obj(v, f), "bsdf": bsdf, "face_normals": True}
            if max(mat.get("Ke", [0, 0, 0])) > 0:
                d[key]["emitter"] = {"type": "area", "radiance": {"type": "rgb", "value": mat["Ke"]}}
    return d


_tmp = tempfile.mkdtemp(prefix="footprint-mitsuba-")


def write_obj(v, f):
    path = os.path.join(_tmp, f"mesh{len(os.listdir(_tmp))}.obj")
    with open(path, "w") as out:
        for p in v:
            out.write(f"v {p[0]:.9g} {p[1]:.9g} {p[2]:.9g}\n")
        for t in f:
            out.write(f"f {t[0] + 1} {t[1] + 1} {t[2] + 1}\n")
    return path


def read_exr_mean(path):
    import mitsuba as mi

    return np.array(mi.Bitmap(path)).reshape(-1, 3).mean(axis=0)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="scenes/cornell/cornell.toml")
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--max-depth", type=int, default=8)
    ap.add_argument("--footprint", default="target/release/footprint")
    ap.add_argument("--repeats", type=int, default=3, help="runs of each renderer; the fastest counts")
    args = ap.parse_args()

    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    scene = mi.load_dict(mitsuba_scene(args.scene, args.spp, args.max_depth))

    out = os.path.join(_tmp, "fp.exr")
    fp_times = []
    for _ in range(args.repeats):
        t0 = time.perf_counter()
        subprocess.run(
            [args.footprint, "render", args.scene, "--integrator", "pt", "--spp", str(args.spp), "--max-depth", str(args.max_depth), "--out", out],
            check=True, stdout=subprocess.DEVNULL,
        )
        fp_times.append(time.perf_counter() - t0)
    fp_mean = read_exr_mean(out)

    mi_times = []
    for r in range(args.repeats):
        t0 = time.perf_counter()
        img = mi.render(scene, spp=args.spp, seed=r)
        mi_times.append(time.perf_counter() - t0)
    mi_mean = np.array(img).reshape(-1, 3).mean(axis=0)
    mi.Bitmap(img).write(os.path.join(_tmp, "mitsuba.exr"))

    fp_t, mi_t = min(fp_times), min(mi_times)
    print(f"scene {args.scene}: {args.spp} spp, max_depth {args.max_depth}, {os.cpu_count()} cores")
    print(f"footprint pt (whole command, incl. loading and writing): {fp_t:.3f} s  image mean {fp_mean}")
    print(f"mitsuba 3 scalar_rgb path (render call only):            {mi_t:.3f} s  image mean {mi_mean}")
    print(f"time ratio mitsuba / footprint: {mi_t / fp_t:.2f}x")


if __name__ == "__main__":
    main()
