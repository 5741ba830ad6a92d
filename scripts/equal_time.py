#!/usr/bin/env python3
"""Equal-time comparison of footprint's integrator x guide pairs on one scene.

Renders a reference once (combined image, BSDF sampling, many passes), then every pair for the
same wall-clock budget (map passes included) and prints the relative MSE against the
reference: mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01), both images first
divided by the reference's mean (so that the 0.01 means the same in a dark scene such as door
as in a bright one). Needs numpy and
mitsuba (for reading EXR): pip install numpy mitsuba.

    cargo build --release
    python3 scripts/equal_time.py scenes/door/door.toml --time 20 --resolution 96x96 --ref-time 240

This is the measurement behind the README's equal-time table until `footprint compare`
(issue 6) replaces it.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np


def read_layer(path, layer):
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    b = mi.Bitmap(path)
    for name, sub in b.split():
        if name == layer or name.startswith(layer + "."):
            return np.array(sub, dtype=np.float64)[..., :3]
    return np.array(b, dtype=np.float64)[..., :3]


def rel_mse(x, ref):
    scale = 1.0 / max(float(ref.mean()), 1e-12)
    x, ref = x * scale, ref * scale
    return float(np.mean((x - ref) ** 2 / (ref ** 2 + 1e-2)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--time", type=float, default=20.0)
    ap.add_argument("--ref-time", type=float, default=240.0)
    ap.add_argument("--resolution", default="96x96")
    ap.add_argument("--footprint", default="target/release/footprint")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("extra", nargs="*", help="more flags for every render (e.g. --photons 400000)")
    a = ap.parse_args()
    out = tempfile.mkdtemp(prefix="footprint-equal-time-")
    base = [a.footprint, "render", a.scene, "--resolution", a.resolution] + a.extra
    ref = os.path.join(out, "ref.exr")
    subprocess.run(base + ["--integrator", "combined", "--guide", "bsdf", "--time", str(a.ref_time), "--seed", "999", "--out", ref], check=True)
    reference = read_layer(ref, "combined")
    print(f"scene {a.scene}, {a.resolution}, {a.time} s per run (maps included), reference {a.ref_time} s combined/bsdf")
    print(f"{'integrator':>10} {'guide':>10} {'relMSE':>10} {'spp':>5}  summary")
    for integ in ["pt", "lt", "combined"]:
        for guide in ["bsdf", "grid", "footprint"]:
            path = os.path.join(out, f"{integ}-{guide}.exr")
            r = subprocess.run(base + ["--integrator", integ, "--guide", guide, "--time", str(a.time), "--seed", str(a.seed), "--out", path], check=True, capture_output=True, text=True)
            img = read_layer(path, integ)
            line = r.stdout.strip().split(" -> ")[0]
            spp = line.split(") ")[1].split(" spp")[0] if ") " in line else "?"
            print(f"{integ:>10} {guide:>10} {rel_mse(img, reference):10.4g} {spp:>5}  {line}", flush=True)


if __name__ == "__main__":
    main()
