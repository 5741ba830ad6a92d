#!/usr/bin/env python3
"""footprint against Mitsuba 3 (variant scalar_rgb): references, image checks, speed.

    python3 scripts/vs_mitsuba.py references   # Mitsuba renders of the bundled scenes' XML,
                                            # committed in tests/mitsuba-references/
    python3 scripts/vs_mitsuba.py check        # both renderers on ../shared/scenes-ext (or the
                                            # scenes given), per-block z-test + image means
    python3 scripts/vs_mitsuba.py bench        # time per sample, Mitsuba `path` vs footprint pt
    python3 scripts/vs_mitsuba.py compare      # Veach Ajar at equal time: Mitsuba `path` next to
                                            # footprint's unguided, grid and footprint runs

Mitsuba 3 is installed from PyPI on first use (`pip install mitsuba numpy`); footprint is
built with `cargo build --release` first. Both renderers read the same Mitsuba XML file with
the same `-D` parameters.

The image test (as Mitsuba's own render tests): each renderer renders K independent batches
(different seeds); per block of BxB pixels and channel the batch means give a mean and its
standard error; Welch's t = (a - b) / sqrt(se_a^2 + se_b^2) must stay below the Student-t
quantile at a Sidak-corrected significance of 1% over all blocks and channels, with
min(K) - 1 degrees of freedom (conservative); and the image means must agree within 1%.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FOOTPRINT = os.path.join(ROOT, "target", "release", "footprint")
EXT = os.path.join(os.path.dirname(ROOT), "shared", "scenes-ext")
REF_DIR = os.path.join(ROOT, "tests", "mitsuba-references")

# The bundled scenes' references: resolution, filter, batches x spp. The Rust test
# (tests/mitsuba.rs) renders with the same parameters.
BUNDLED = {
    "cornell": dict(resx=48, resy=48, rfilter="tent", max_depth=8, batches=32, spp=128),
    "door": dict(resx=48, resy=32, rfilter="box", max_depth=8, batches=32, spp=512),
    "desk": dict(resx=48, resy=48, rfilter="gaussian", max_depth=12, batches=32, spp=256),
    "features": dict(resx=64, resy=48, rfilter="tent", max_depth=6, batches=32, spp=256),
}

# The public scenes (../shared/scenes-ext): parameters of the check.
EXTERNAL = {
    "cornell-box-bitterli/scene.xml": dict(defines=dict(resx=64, resy=64, max_depth=8), batches=32, spp=128),
    "cornell-box-mcguire/mitsuba/scene.xml": dict(defines=dict(res=64), batches=32, spp=128),
    "veach-ajar/scene.xml": dict(defines=dict(resx=96, resy=54), batches=32, spp=256),
}


def mitsuba():
    try:
        import mitsuba as mi
    except ImportError:
        print("installing Mitsuba 3 from PyPI ...", flush=True)
        subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", "mitsuba", "numpy"])
        import mitsuba as mi
    mi.set_variant("scalar_rgb")
    return mi


def mitsuba_batches(xml, defines, batches, spp):
    import numpy as np

    mi = mitsuba()
    scene = mi.load_file(xml, **{k: str(v) for k, v in defines.items()})
    t0 = time.time()
    out = [np.array(mi.render(scene, spp=spp, seed=k), dtype=np.float64) for k in range(batches)]
    return np.stack(out), time.time() - t0


def footprint_batches(xml, defines, batches, spp, extra=()):
    import numpy as np

    mi = mitsuba()
    if not os.path.exists(FOOTPRINT):
        sys.exit(f"{FOOTPRINT} is missing: run `cargo build --release` first")
    out = []
    t0 = time.time()
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(batches):
            exr = os.path.join(tmp, f"b{k}.exr")
            cmd = [FOOTPRINT, "render", xml, "--spp", str(spp), "--seed", str(1000 + k), "-o", exr, *extra]
            for key, v in defines.items():
                cmd += ["-D", f"{key}={v}"]
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            layers = mi.Bitmap(exr).split()
            out.append(np.array(layers[0][1], dtype=np.float64)[..., :3])
    return np.stack(out), time.time() - t0


def t_cdf(t, dof):
    """Student-t cdf by Simpson integration of the density (no scipy needed)."""
    c = math.exp(math.lgamma((dof + 1) / 2) - math.lgamma(dof / 2)) / math.sqrt(dof * math.pi)
    f = lambda x: c * (1 + x * x / dof) ** (-(dof + 1) / 2)
    n = 4000
    a, b = 0.0, abs(t)
    h = (b - a) / n
    s = f(a) + f(b) + sum((4 if i % 2 else 2) * f(a + i * h) for i in range(1, n))
    half = s * h / 3
    return 0.5 + half if t >= 0 else 0.5 - half


def t_quantile(p, dof):
    lo, hi = 0.0, 1e3
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if t_cdf(mid, dof) < p:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def block_stats(batches, block):
    """Per block and channel: mean over batches and its standard error."""
    import numpy as np

    k, h, w, _ = batches.shape
    bh, bw = h // block, w // block
    b = batches[:, : bh * block, : bw * block, :].reshape(k, bh, block, bw, block, 3).mean(axis=(2, 4))
    return b.mean(axis=0), b.std(axis=0, ddof=1) / math.sqrt(k)


def compare(a, b, block, alpha=0.01):
    """Welch t per block and channel with a Sidak-corrected threshold; image means."""
    import numpy as np

    ma, sa = block_stats(a, block)
    mb, sb = block_stats(b, block)
    se = np.sqrt(sa**2 + sb**2)
    n = ma.size
    dof = min(a.shape[0], b.shape[0]) - 1
    per_test = 1 - (1 - alpha) ** (1 / n)
    crit = t_quantile(1 - per_test / 2, dof)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(se > 0, (ma - mb) / se, np.where(ma == mb, 0.0, np.inf))
    worst = np.unravel_index(np.argmax(np.abs(t)), t.shape)
    mean_a, mean_b = a.mean(axis=(0, 1, 2)), b.mean(axis=(0, 1, 2))
    ratio = mean_a / np.maximum(mean_b, 1e-30)
    ok_t = bool(np.all(np.abs(t) <= crit))
    ok_mean = bool(np.all(np.abs(ratio - 1) <= 0.01))
    return dict(
        blocks=int(n), crit=float(crit), max_t=float(np.abs(t).max()), worst=[int(x) for x in worst],
        failing=int(np.sum(np.abs(t) > crit)), mean_footprint=mean_a.tolist(), mean_mitsuba=mean_b.tolist(),
        mean_ratio=ratio.tolist(), ok=ok_t and ok_mean, ok_t=ok_t, ok_mean=ok_mean,
    )


def cmd_references(args):
    import numpy as np

    mi = mitsuba()
    os.makedirs(REF_DIR, exist_ok=True)
    meta_path = os.path.join(REF_DIR, "references.json")
    meta = json.load(open(meta_path)) if os.path.exists(meta_path) else {}
    meta.update({"mitsuba": mi.__version__, "variant": "scalar_rgb"})
    meta.setdefault("scenes", {})
    only = set(args.only or BUNDLED)
    for name, p in ((k, v) for k, v in BUNDLED.items() if k in only):
        xml = os.path.join(ROOT, "scenes", name, "mitsuba", "scene.xml")
        if not os.path.exists(xml):
            xml = os.path.join(ROOT, "scenes", name, "scene.xml")
        defines = {k: p[k] for k in ("resx", "resy", "rfilter", "max_depth")}
        imgs, secs = mitsuba_batches(xml, defines, p["batches"], p["spp"])
        mean = imgs.mean(axis=0).astype(np.float32)
        stderr = (imgs.std(axis=0, ddof=1) / math.sqrt(imgs.shape[0])).astype(np.float32)
        mi.Bitmap(mean).write(os.path.join(REF_DIR, f"{name}-mean.exr"))
        mi.Bitmap(stderr).write(os.path.join(REF_DIR, f"{name}-stderr.exr"))
        meta["scenes"][name] = dict(p, seconds=round(secs, 1), mean=mean.mean(axis=(0, 1)).tolist())
        print(f"{name}: {p['batches']} x {p['spp']} spp at {p['resx']}x{p['resy']} in {secs:.1f} s, mean {mean.mean(axis=(0, 1))}")
    with open(os.path.join(REF_DIR, "references.json"), "w") as f:
        json.dump(meta, f, indent=2)


def cmd_check(args):
    scenes = args.scenes
    if not scenes:
        if not os.path.isdir(EXT):
            print(f"SKIPPED: {EXT} is absent (the public scenes live beside the repository, not in it)")
            return 0
        scenes = [os.path.join(EXT, s) for s in EXTERNAL]
    failed = 0
    for xml in scenes:
        key = next((k for k in EXTERNAL if xml.endswith(k)), None)
        p = EXTERNAL.get(key, dict(defines={}, batches=16, spp=64))
        defines = dict(p["defines"])
        for d in args.define:
            k, v = d.split("=", 1)
            defines[k] = v
        batches, spp = args.batches or p["batches"], args.spp or p["spp"]
        a, ta = footprint_batches(xml, defines, batches, spp, ["--integrator", args.integrator])
        b, tb = mitsuba_batches(xml, defines, batches, spp)
        r = compare(a, b, args.block)
        status = "PASS" if r["ok"] else "FAIL"
        failed += not r["ok"]
        print(f"{status} {xml}: {batches} x {spp} spp, -D {defines}")
        print(f"     means footprint {['%.5f' % x for x in r['mean_footprint']]} mitsuba {['%.5f' % x for x in r['mean_mitsuba']]} ratio {['%.4f' % x for x in r['mean_ratio']]}")
        print(f"     {r['blocks']} block-channels ({args.block}x{args.block}), max |t| {r['max_t']:.2f} (limit {r['crit']:.2f}), failing {r['failing']}, worst block {r['worst']}")
        print(f"     time footprint {ta:.1f} s, mitsuba {tb:.1f} s (both including their loading)")
    return 1 if failed else 0


def cmd_bench(args):
    """Time per sample at equal resolution, spp and depth: Mitsuba `path` vs footprint pt."""
    mi = mitsuba()
    scenes = args.scenes or [
        os.path.join(ROOT, "scenes", "cornell", "mitsuba", "scene.xml"),
        *([os.path.join(EXT, "cornell-box-bitterli", "scene.xml"), os.path.join(EXT, "veach-ajar", "scene.xml")]
          if os.path.isdir(EXT) else []),
    ]
    if not os.path.isdir(EXT):
        print(f"note: {EXT} is absent: Veach Ajar and Bitterli's Cornell box are skipped")
    print(f"machine: {os.cpu_count()} logical cores; Mitsuba {mi.__version__} scalar_rgb; footprint release build")
    for xml in scenes:
        defines = {"resx": args.resx, "resy": args.resy, "max_depth": args.max_depth}
        text = open(xml).read()
        defines = {k: v for k, v in defines.items() if f"${k}" in text}
        times = {}
        for rep in range(args.repeat):
            cmd = [FOOTPRINT, "render", xml, "--spp", str(args.spp), "--seed", "7", "-o",
                   os.path.join(tempfile.gettempdir(), "fp-bench.exr")]
            for k, v in defines.items():
                cmd += ["-D", f"{k}={v}"]
            t0 = time.time()
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            times.setdefault("footprint", []).append(time.time() - t0)
            t0 = time.time()
            scene = mi.load_file(xml, **{k: str(v) for k, v in defines.items()})
            mi.render(scene, spp=args.spp, seed=rep)
            times.setdefault("mitsuba", []).append(time.time() - t0)
        fp, ms = min(times["footprint"]), min(times["mitsuba"])
        print(f"{os.path.relpath(xml, os.path.dirname(ROOT))}: {args.spp} spp, -D {defines}: "
              f"footprint {fp:.2f} s, mitsuba {ms:.2f} s (best of {args.repeat}, loading included) -> "
              f"mitsuba/footprint = {ms / fp:.2f}x")


def metrics(image, reference):
    out = subprocess.run([FOOTPRINT, "metrics", image, "--reference", reference], check=True,
                         capture_output=True, text=True).stdout
    return {k: float(v) for k, v in (t.split("=") for t in out.split())}


def cmd_compare(args):
    """Equal time on one scene: `footprint compare` for footprint's methods, and Mitsuba's
    `path` given the same wall-clock budgets (rendering only; footprint's budgets include
    its map passes), all measured against the same reference with the same metrics."""
    import csv

    mi = mitsuba()
    xml = args.scene or os.path.join(EXT, "veach-ajar", "scene.xml")
    if not os.path.exists(xml):
        print(f"SKIPPED: {xml} is absent (the public scenes live beside the repository, not in it)")
        return 0
    out = args.out or "compare-" + os.path.basename(os.path.dirname(os.path.abspath(xml)))
    os.makedirs(out, exist_ok=True)
    defines = {"resx": args.resx, "resy": args.resy}
    dflags = [x for k, v in defines.items() for x in ("-D", f"{k}={v}")]
    ladder = [args.time / 8, args.time / 4, args.time / 2, args.time]
    cmd = [FOOTPRINT, "compare", xml, *dflags, "--time", str(args.time), "--methods", args.methods,
           "--reference-spp", str(args.reference_spp), "--reference-cache", out, "-o", out]
    print(" ".join(cmd), flush=True)
    subprocess.run(cmd, check=True)
    ref = os.path.join(out, f".scene-reference-{args.resx}x{args.resy}.exr")
    scene = mi.load_file(xml, **{k: str(v) for k, v in defines.items()})
    t0 = time.time()
    mi.render(scene, spp=args.calibration_spp, seed=999)
    per_spp = (time.time() - t0) / args.calibration_spp
    rows = []
    for t in ladder:
        spp = max(1, int(t / per_spp))
        t0 = time.time()
        img = mi.render(scene, spp=spp, seed=int(t * 1000))
        secs = time.time() - t0
        path = os.path.join(out, f"mitsuba-path-{t:g}s.exr")
        mi.Bitmap(img).write(path)
        m = metrics(path, ref)
        rows.append(dict(method="mitsuba-path", time_budget_s=t, seconds=round(secs, 4), map_seconds=0,
                         tracing_seconds=round(secs, 4), spp=spp, rel_mse=m["rel_mse"], mae=m["mae"],
                         spots=int(m["spots"])))
    with open(os.path.join(out, "mitsuba.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    ours = list(csv.DictReader(open(os.path.join(out, "metrics.csv"))))
    ours = [{k.strip(): v.strip().strip('"') for k, v in r.items()} for r in ours]
    print(f"\nequal time {args.time:g} s, {args.resx}x{args.resy}, reference: {ref}")
    print(f"{'method':<22}{'seconds':>9}{'spp':>7}{'rel. MSE':>12}{'MAE':>12}{'spots':>7}")
    for r in [*ours, *[{k: str(v) for k, v in r.items()} for r in rows]]:
        if abs(float(r["time_budget_s"]) - args.time) > 1e-9:
            continue
        print(f"{r['method']:<22}{float(r['seconds']):>9.2f}{r['spp']:>7}{float(r['rel_mse']):>12.4e}"
              f"{float(r['mae']):>12.4e}{r['spots']:>7}")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("references", help="render the bundled scenes' references with Mitsuba")
    r.add_argument("only", nargs="*", help=f"scenes to render [default: all of {', '.join(BUNDLED)}]")
    c = sub.add_parser("check", help="compare both renderers on Mitsuba XML scenes")
    c.add_argument("scenes", nargs="*", help="XML scenes [default: ../shared/scenes-ext]")
    c.add_argument("-D", dest="define", action="append", default=[], help="name=value for both renderers")
    c.add_argument("--batches", type=int)
    c.add_argument("--spp", type=int, help="samples per pixel per batch")
    c.add_argument("--block", type=int, default=4, help="block side in pixels")
    c.add_argument("--integrator", default="pt", help="footprint's integrator: pt, lt or combined")
    b = sub.add_parser("bench", help="time per sample against Mitsuba 3")
    b.add_argument("scenes", nargs="*")
    b.add_argument("--spp", type=int, default=64)
    b.add_argument("--resx", type=int, default=256)
    b.add_argument("--resy", type=int, default=256)
    b.add_argument("--max-depth", type=int, default=8)
    b.add_argument("--repeat", type=int, default=3)
    q = sub.add_parser("compare", help="equal time against Mitsuba's path on Veach Ajar (or SCENE)")
    q.add_argument("scene", nargs="?")
    q.add_argument("--time", type=float, default=16.0, help="equal-time budget in seconds")
    q.add_argument("--resx", type=int, default=128)
    q.add_argument("--resy", type=int, default=72)
    q.add_argument("--methods", default="pt-bsdf,pt-grid,pt-footprint")
    q.add_argument("--reference-spp", type=int, default=2048)
    q.add_argument("--calibration-spp", type=int, default=4)
    q.add_argument("-o", "--out")
    args = ap.parse_args()
    sys.exit({"references": cmd_references, "check": cmd_check, "bench": cmd_bench,
              "compare": cmd_compare}[args.cmd](args) or 0)


if __name__ == "__main__":
    main()
