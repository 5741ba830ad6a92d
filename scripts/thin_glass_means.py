#!/usr/bin/env python3
"""Image means of scenes/panes (a room seen only through two coloured thin-glass panes):
Mitsuba 3's `path` and `ptracer` against footprint's path tracer, light tracer and combined
image, each over several seeds, with the standard error of the mean. Mitsuba blocks connections at thin
sheets (its light tracer sees nothing through them) and footprint passes them with their
transmittance; footprint's means must agree with Mitsuba's `path`.

    python3 scripts/thin_glass_means.py [--spp 64] [--seeds 8] [--footprint target/release/footprint]

Needs `pip install mitsuba` (variant scalar_rgb) and numpy.
"""
import argparse
import os
import subprocess
import tempfile

import mitsuba as mi
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "scenes", "panes", "scene.xml")


def mean_and_se(means):
    a = np.array(means)
    return a.mean(0), a.std(0, ddof=1) / np.sqrt(len(a))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--footprint", default=os.path.join(ROOT, "target", "release", "footprint"))
    a = ap.parse_args()
    mi.set_variant("scalar_rgb")
    scene = mi.load_file(SCENE, resx=64, resy=64, spp=a.spp, max_depth=8)
    rows = []
    means = [np.array(mi.render(scene, seed=s, spp=a.spp)).reshape(-1, 3).mean(0) for s in range(a.seeds)]
    rows.append(("Mitsuba 3 path", *mean_and_se(means)))
    ptracer = mi.load_dict({"type": "ptracer", "max_depth": 8})
    means = [np.array(mi.render(scene, integrator=ptracer, seed=s, spp=a.spp)).reshape(-1, 3).mean(0)
             for s in range(a.seeds)]
    rows.append(("Mitsuba 3 ptracer", *mean_and_se(means)))
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "r.exr")
        for method in ["pt-bsdf", "lt-bsdf", "combined-bsdf"]:
            integrator, guide = method.split("-")
            means = []
            for s in range(a.seeds):
                subprocess.run(
                    [a.footprint, "render", SCENE, "--integrator", integrator, "--guide", guide,
                     "--spp", str(a.spp), "--seed", str(100 + s), "--out", out],
                    check=True, capture_output=True)
                img = np.array(mi.Bitmap(out).split()[0][1])
                means.append(img.reshape(-1, img.shape[-1])[:, :3].mean(0))
            rows.append((f"footprint {method}", *mean_and_se(means)))
    ref = rows[0][1]
    print(f"{'renderer':<26} {'mean (R, G, B)':<30} {'std. error':<30} ratio to Mitsuba")
    for name, m, se in rows:
        print(f"{name:<26} {np.array2string(m, precision=5):<30} {np.array2string(se, precision=5):<30} "
              f"{np.array2string(m / ref, precision=4)}")


if __name__ == "__main__":
    main()
