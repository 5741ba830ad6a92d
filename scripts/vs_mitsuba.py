#!/usr/bin/env python3
"""footprint against Mitsuba 3 (variant scalar_rgb): references, image checks, speed.

    python3 scripts/vs_mitsuba.py references   # Mitsuba renders of the bundled scenes' XML and
                                            # of scenes/public, in tests/mitsuba-references/
    python3 scripts/vs_mitsuba.py check        # both renderers on ../shared/scenes-ext (or the
                                            # scenes given), per-block z-test + image means
    python3 scripts/vs_mitsuba.py bench        # time per sample, Mitsuba `path` vs footprint pt
    python3 scripts/vs_mitsuba.py compare      # equal time (30 s) against Mitsuba `path` on the
                                            # public scenes and the bundled scenes' XML

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
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The binary to measure: $FOOTPRINT_BIN (the tests pass their own), else the release build.
FOOTPRINT = os.environ.get("FOOTPRINT_BIN") or os.path.join(ROOT, "target", "release", "footprint")
EXT = os.path.join(os.path.dirname(ROOT), "shared", "scenes-ext")
REF_DIR = os.path.join(ROOT, "tests", "mitsuba-references")

# The bundled scenes' references: resolution, filter, batches x spp. The Rust test
# (tests/mitsuba.rs) renders with the same parameters.
BUNDLED = {
    "cornell": dict(resx=48, resy=48, rfilter="tent", max_depth=8, batches=32, spp=128),
    "door": dict(resx=48, resy=32, rfilter="box", max_depth=8, batches=32, spp=512),
    "desk": dict(resx=48, resy=48, rfilter="gaussian", max_depth=12, batches=32, spp=256),
    "features": dict(resx=64, resy=48, rfilter="tent", max_depth=6, batches=32, spp=256),
    "glass": dict(resx=48, resy=48, rfilter="box", max_depth=4, batches=32, spp=512),
    "roughglass": dict(resx=48, resy=48, rfilter="box", max_depth=4, batches=32, spp=512),
    "principled": dict(resx=64, resy=48, rfilter="box", max_depth=5, batches=32, spp=512),
    "panes": dict(resx=48, resy=48, rfilter="box", max_depth=8, batches=32, spp=512),
    "slit": dict(resx=64, resy=48, rfilter="box", max_depth=10, batches=32, spp=1024),
    "ltcheck": dict(resx=32, resy=32, rfilter="box", max_depth=8, batches=32, spp=1024),
    "bumpmap": dict(resx=32, resy=32, rfilter="box", max_depth=3, batches=32, spp=512),
    # Mitsuba's particle tracer on the same scene: the bump map is not reciprocal, so its
    # `ptracer` and `path` differ there (tests/mitsuba.rs compares footprint's light tracer).
    "bumpmap-ptracer": dict(scene="bumpmap", integrator="ptracer", resx=32, resy=32, rfilter="box", max_depth=3,
                            batches=32, spp=512),
    "normalmap": dict(resx=32, resy=32, rfilter="box", max_depth=3, batches=32, spp=512),
    "normalmap-ptracer": dict(scene="normalmap", integrator="ptracer", resx=32, resy=32, rfilter="box", max_depth=3,
                              batches=32, spp=512),
    "meshes": dict(resx=48, resy=48, rfilter="box", max_depth=4, batches=32, spp=256),
    # Cut-outs: Mitsuba's `volpath`, which passes them as footprint does (its `path` loses
    # light seen through them: docs/mitsuba.md, "Cut-outs").
    "cutout": dict(integrator="volpath", resx=48, resy=48, rfilter="box", max_depth=6, batches=32, spp=256),
    # Mitsuba's thinlens sensor: path tracing and the combined image against `path`, light
    # tracing against `ptracer` (whose camera connections sample the aperture).
    "thinlens": dict(resx=48, resy=48, rfilter="box", max_depth=3, batches=32, spp=512),
    # Anisotropic roughconductor (alpha_u != alpha_v), oriented by dp/du.
    "anisotropic": dict(resx=32, resy=32, rfilter="box", max_depth=2, batches=32, spp=512),
    "thinlens-ptracer": dict(scene="thinlens", integrator="ptracer", resx=48, resy=48, rfilter="box", max_depth=3,
                             batches=32, spp=512),
}

# The public scenes kept in the repository (scenes/public/<name>/scene.xml, unchanged but for
# what each SOURCE.md says) or fetched by scripts/public_scenes.py (scenes/public/fetched/):
# their own -D parameters, batches x spp. Their references sit beside the bundled ones as
# public/<name>-{mean,stderr}.exr.
PUBLIC = {
    "veach-mis": dict(defines=dict(resx=64, resy=36), batches=32, spp=1024),
    "veach-bidir": dict(defines=dict(res=48), batches=32, spp=256),
    "staircase": dict(defines=dict(resx=36, resy=64), batches=32, spp=256),
    "modern-hall": dict(defines=dict(resx=64, resy=36), batches=32, spp=256),
    "matpreview": dict(defines=dict(width=64, height=48), batches=32, spp=256),
    "dining-room": dict(defines=dict(resx=48, resy=48), batches=32, spp=256),
    # Its leaves are cut-outs: Mitsuba's `volpath` (its `path` loses light seen through them).
    "living-room": dict(defines=dict(resx=64, resy=36, integrator="volpath"), batches=32, spp=128),
}

# The public scenes beside the repository (../shared/scenes-ext): parameters of the check.
EXTERNAL = {
    "cornell-box-bitterli/scene.xml": dict(defines=dict(resx=64, resy=64, max_depth=8), batches=32, spp=128),
    "cornell-box-mcguire/mitsuba/scene.xml": dict(defines=dict(res=64), batches=32, spp=128),
    "veach-ajar/scene.xml": dict(defines=dict(resx=96, resy=54), batches=32, spp=256),
}


def mitsuba():
    """Mitsuba 3 in its `scalar_rgb` variant, with numpy beside it; both are installed from
    PyPI when either is missing (a machine may have one without the other)."""
    try:
        import mitsuba as mi
        import numpy  # noqa: F401
    except ImportError:
        print("installing Mitsuba 3 from PyPI ...", flush=True)
        subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", "mitsuba", "numpy"])
        import mitsuba as mi
    mi.set_variant("scalar_rgb")
    return mi


def mitsuba_batches(xml, defines, batches, spp):
    mi = mitsuba()
    import numpy as np

    scene = mi.load_file(xml, **{k: str(v) for k, v in defines.items()})
    t0 = time.time()
    out = [np.array(mi.render(scene, spp=spp, seed=k), dtype=np.float64) for k in range(batches)]
    return np.stack(out), time.time() - t0


def footprint_batches(xml, defines, batches, spp, extra=()):
    mi = mitsuba()
    import numpy as np

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
    mi = mitsuba()
    import numpy as np

    os.makedirs(REF_DIR, exist_ok=True)
    meta_path = os.path.join(REF_DIR, "references.json")
    meta = json.load(open(meta_path)) if os.path.exists(meta_path) else {}
    meta.update({"mitsuba": mi.__version__, "variant": "scalar_rgb"})
    meta.setdefault("scenes", {})
    jobs = []
    for name, p in BUNDLED.items():
        folder = p.get("scene", name)
        xml = os.path.join(ROOT, "scenes", folder, "mitsuba", "scene.xml")
        if not os.path.exists(xml):
            xml = os.path.join(ROOT, "scenes", folder, "scene.xml")
        keys = ("resx", "resy", "rfilter", "max_depth", "integrator")
        jobs.append((name, xml, {k: p[k] for k in keys if k in p}, p))
    for name, p in PUBLIC.items():
        xml = os.path.join(ROOT, "scenes", "public", name, "scene.xml")
        if not os.path.exists(xml):
            # Fetched by scripts/public_scenes.py, where it is.
            xml = os.path.join(ROOT, "scenes", "public", "fetched", name, "scene.xml")
            if not os.path.exists(xml):
                print(f"public/{name}: skipped, {xml} is absent (scripts/public_scenes.py fetch {name})")
                continue
        jobs.append((f"public/{name}", xml, p["defines"], p))
    only = set(args.only or [j[0] for j in jobs])
    for name, xml, defines, p in (j for j in jobs if j[0] in only):
        imgs, secs = mitsuba_batches(xml, defines, p["batches"], p["spp"])
        mean = imgs.mean(axis=0).astype(np.float32)
        stderr = (imgs.std(axis=0, ddof=1) / math.sqrt(imgs.shape[0])).astype(np.float32)
        os.makedirs(os.path.dirname(os.path.join(REF_DIR, name)), exist_ok=True)
        mi.Bitmap(mean).write(os.path.join(REF_DIR, f"{name}-mean.exr"))
        mi.Bitmap(stderr).write(os.path.join(REF_DIR, f"{name}-stderr.exr"))
        # The image mean's standard error, from the spread of the batches' image means.
        mean_stderr = imgs.mean(axis=(1, 2)).std(axis=0, ddof=1) / math.sqrt(imgs.shape[0])
        meta["scenes"][name] = dict(p, seconds=round(secs, 1), mean=mean.mean(axis=(0, 1)).tolist(),
                                    mean_stderr=mean_stderr.tolist())
        print(f"{name}: {p['batches']} x {p['spp']} spp, -D {defines}, in {secs:.1f} s, mean {mean.mean(axis=(0, 1))}")
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
        *([os.path.join(EXT, "cornell-box-bitterli", "scene.xml"),
           os.path.join(EXT, "cornell-box-mcguire", "mitsuba", "scene.xml"),
           os.path.join(EXT, "veach-ajar", "scene.xml")]
          if os.path.isdir(EXT) else []),
    ]
    if not os.path.isdir(EXT):
        print(f"note: {EXT} is absent: Veach Ajar and both public Cornell boxes are skipped")
    print(f"machine: {os.cpu_count()} logical cores; Mitsuba {mi.__version__} scalar_rgb; footprint release build"
          f" ({args.sequence or 'sobol'} numbers{'' if args.sequence else ', its default'})")
    for xml in scenes:
        # McGuire's box takes one side, `res` (square): the bench's width there.
        defines = {"resx": args.resx, "resy": args.resy, "res": args.resx, "max_depth": args.max_depth}
        text = open(xml).read()
        defines = {k: v for k, v in defines.items() if re.search(rf"\${k}\b", text)}
        times = {}
        for rep in range(args.repeat):
            # Russian roulette from Mitsuba's depth (5; footprint's own default is 8): equal
            # work per sample, which is what this times.
            cmd = [FOOTPRINT, "render", xml, "--spp", str(args.spp), "--seed", "7", "--rr-depth", "5", "-o",
                   os.path.join(tempfile.gettempdir(), "fp-bench.exr")]
            for k, v in defines.items():
                cmd += ["-D", f"{k}={v}"]
            if args.sequence:
                cmd += ["--sequence", args.sequence]
            t0 = time.time()
            out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
            times.setdefault("footprint", []).append(time.time() - t0)
            # The render alone: the run summary's "N spp WxH in T s".
            m = re.search(r" spp \d+x\d+ in ([0-9.]+) s", out)
            if m:
                times.setdefault("footprint render", []).append(float(m.group(1)))
            t0 = time.time()
            scene = mi.load_file(xml, **{k: str(v) for k, v in defines.items()})
            t1 = time.time()
            mi.render(scene, spp=args.spp, seed=rep)
            times.setdefault("mitsuba", []).append(time.time() - t0)
            times.setdefault("mitsuba render", []).append(time.time() - t1)
        fp, ms = min(times["footprint"]), min(times["mitsuba"])
        line = (f"{os.path.relpath(xml, os.path.dirname(ROOT))}: {args.spp} spp, -D {defines}: "
                f"footprint {fp:.2f} s, mitsuba {ms:.2f} s (best of {args.repeat}, loading included) -> "
                f"mitsuba/footprint = {ms / fp:.2f}x")
        if "footprint render" in times:
            fr, mr = min(times["footprint render"]), min(times["mitsuba render"])
            line += f"; rendering alone {fr:.2f} s against {mr:.2f} s -> {mr / fr:.2f}x"
        print(line)


def metrics(image, reference):
    out = subprocess.run([FOOTPRINT, "metrics", image, "--reference", reference], check=True,
                         capture_output=True, text=True).stdout
    return {k: float(v) for k, v in (t.split("=") for t in out.split())}


# The scenes of the equal-time table: (name, XML, -D parameters). The public scenes live in
# ../shared/scenes-ext (skipped when absent); the bundled ones are footprint's own exports.
TABLE = [
    ("Veach Ajar 128x72", os.path.join(EXT, "veach-ajar", "scene.xml"), dict(resx=128, resy=72)),
    ("Bitterli Cornell 64x64", os.path.join(EXT, "cornell-box-bitterli", "scene.xml"), dict(resx=64, resy=64)),
    ("Bitterli Cornell 256x256", os.path.join(EXT, "cornell-box-bitterli", "scene.xml"), dict(resx=256, resy=256)),
    ("McGuire Cornell 64x64", os.path.join(EXT, "cornell-box-mcguire", "mitsuba", "scene.xml"), dict(res=64)),
    ("McGuire Cornell 256x256", os.path.join(EXT, "cornell-box-mcguire", "mitsuba", "scene.xml"), dict(res=256)),
    ("Veach MIS 128x72", os.path.join(ROOT, "scenes", "public", "veach-mis", "scene.xml"), dict(resx=128, resy=72)),
    ("Veach Bidir 96x96", os.path.join(ROOT, "scenes", "public", "veach-bidir", "scene.xml"), dict(res=96)),
    ("torus 128x96", os.path.join(ROOT, "scenes", "public", "fetched", "torus", "scene.xml"), dict(resx=128, resy=96)),
    ("staircase 72x128", os.path.join(ROOT, "scenes", "public", "fetched", "staircase", "scene.xml"), dict(resx=72, resy=128)),
    ("Modern Hall 128x72", os.path.join(ROOT, "scenes", "public", "fetched", "modern-hall", "scene.xml"), dict(resx=128, resy=72)),
    ("matpreview 128x96", os.path.join(ROOT, "scenes", "public", "fetched", "matpreview", "scene.xml"), dict(width=128, height=96)),
    ("dining room 96x96", os.path.join(ROOT, "scenes", "public", "fetched", "dining-room", "scene.xml"), dict(resx=96, resy=96)),
    # Cut-out leaves: Mitsuba's `volpath` (its `path` loses light seen through them).
    ("living room 128x72", os.path.join(ROOT, "scenes", "public", "fetched", "living-room", "scene.xml"),
     dict(resx=128, resy=72, integrator="volpath")),
    ("cornell (bundled) 128x128", os.path.join(ROOT, "scenes", "cornell", "mitsuba", "scene.xml"), dict(resx=128, resy=128)),
    ("door (bundled) 128x128", os.path.join(ROOT, "scenes", "door", "mitsuba", "scene.xml"), dict(resx=128, resy=128)),
    ("desk (bundled) 128x128", os.path.join(ROOT, "scenes", "desk", "mitsuba", "scene.xml"), dict(resx=128, resy=128)),
]

# References already rendered elsewhere, by table name (Mitsuba 3, ~164k spp).
SHARED_REFS = {"Veach Ajar 128x72": os.path.join(os.path.dirname(ROOT), "shared", "refs", "veach-ajar_128x72.exr")}


def rel_mse(x, r):
    """The metric of `footprint metrics` (and of ../shared/refs/README.md)."""
    import numpy as np
    x, r = np.asarray(x, dtype=np.float64)[..., :3], np.asarray(r, dtype=np.float64)[..., :3]
    m = (0.2126 * r[..., 0] + 0.7152 * r[..., 1] + 0.0722 * r[..., 2]).mean()
    a, b = x / m, r / m
    return float(((a - b) ** 2 / (b * b + 0.01)).mean())


def mitsuba_reference(mi, name, xml, defines, out, seconds):
    """A high-sample Mitsuba render of the scene, cached in `out` (rendered for `seconds`)."""
    import numpy as np
    if name in SHARED_REFS and os.path.exists(SHARED_REFS[name]):
        return np.array(mi.Bitmap(SHARED_REFS[name]))
    path = os.path.join(out, "reference-" + "".join(c if c.isalnum() else "_" for c in name) + ".exr")
    if os.path.exists(path):
        return np.array(mi.Bitmap(path))
    scene = mi.load_file(xml, **{k: str(v) for k, v in defines.items()})
    t0 = time.time()
    mi.render(scene, spp=16, seed=7)
    per_spp = (time.time() - t0) / 16
    batches, spp = 8, max(16, int(seconds / per_spp / 8))
    print(f"  reference: {batches} x {spp} spp ({seconds:.0f} s)", flush=True)
    acc = None
    for b in range(batches):
        img = np.array(mi.render(scene, spp=spp, seed=10_000 + b))
        acc = img if acc is None else acc + img
    ref = acc / batches
    mi.Bitmap(ref.astype(np.float32)).write(path)
    return ref


def load_with_sampler(mi, xml, defines, sampler, rr_depth=None):
    """The scene, with its `<sampler type=...>` replaced by `sampler` when one is given and
    `rr_depth` given to its integrator when one is (the edited XML goes to a temporary folder;
    the scene's own folder stays on the file resolver's path, so its meshes and textures are
    found)."""
    import re
    import tempfile
    params = {k: str(v) for k, v in defines.items()}
    if not sampler and rr_depth is None:
        return mi.load_file(xml, **params)
    edited = open(xml).read()
    if sampler:
        edited, n = re.subn(r'<sampler\s+type="[^"]*"', f'<sampler type="{sampler}"', edited)
        if n != 1:
            sys.exit(f"{xml}: expected one <sampler type=...>, found {n}")
    if rr_depth is not None:
        if "rr_depth" in edited:
            sys.exit(f"{xml}: the integrator sets rr_depth already; --rr-depth would repeat it")
        edited = re.sub(r'(<integrator\b[^>]*?)\s*/>', r'\1></integrator>', edited)
        edited, n = re.subn(r'(<integrator\b[^>]*>)', rf'\1<integer name="rr_depth" value="{rr_depth}"/>', edited)
        if n != 1:
            sys.exit(f"{xml}: expected one <integrator ...>, found {n}")
    mi.file_resolver().append(os.path.dirname(os.path.abspath(xml)))
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "scene.xml")
        with open(path, "w") as f:
            f.write(edited)
        return mi.load_file(path, **params)


def cmd_compare(args):
    """Equal time against Mitsuba 3 `path`: both renderers get the same wall-clock budget for
    rendering (footprint's includes its map passes; neither includes loading the scene), on
    the public scenes and the bundled scenes' XML, several seeds each; one table with the
    median relative MSE of Mitsuba and of each footprint method, and their ratios."""
    mi = mitsuba()
    import numpy as np
    out = args.out or "compare-mitsuba"
    os.makedirs(out, exist_ok=True)
    methods = args.methods.split(",") if args.methods else [f"{args.integrator}-{args.guide}"]
    for m in methods:
        if m.count("-") != 1:
            sys.exit(f"--methods: {m!r} is not INTEGRATOR-GUIDE (pt-bsdf, lt-footprint, ...)")
    rows = []
    for name, xml, defines in TABLE:
        if args.only and not any(o.lower() in name.lower() for o in args.only):
            continue
        if not os.path.exists(xml):
            print(f"SKIPPED {name}: {xml} is absent (../shared/scenes-ext lives beside the repository; "
                  f"scripts/public_scenes.py fetches scenes/public/fetched)")
            continue
        print(f"{name}", flush=True)
        ref = mitsuba_reference(mi, name, xml, defines, out, args.reference_time)
        scene = load_with_sampler(mi, xml, defines, args.mitsuba_sampler, args.rr_depth)
        # Mitsuba renders a sample count, not a time: its count comes from two timings (4 and
        # 20 spp), so that the cost every render call has whatever its samples does not count
        # as samples (a 4-spp timing alone left Mitsuba 15% short of the budget at 64x64).
        def timed(n):
            t0 = time.time()
            mi.render(scene, spp=n, seed=999)
            return time.time() - t0
        timed(4)  # warm-up
        t4, t20 = timed(4), timed(20)
        per_spp = max((t20 - t4) / 16, 1e-9)
        fixed = max(t4 - 4 * per_spp, 0.0)
        dflags = [x for k, v in defines.items() for x in ("-D", f"{k}={v}")]
        theirs, their_spp, their_secs = [], [], []
        ours = {m: [] for m in methods}
        our_spp = {m: [] for m in methods}
        for s in range(args.seeds):
            spp = max(1, int((args.time - fixed) / per_spp))
            t0 = time.time()
            img = np.array(mi.render(scene, spp=spp, seed=100 + s))
            their_s = time.time() - t0
            theirs.append(rel_mse(img, ref))
            their_spp.append(spp)
            their_secs.append(their_s)
            line = f"  seed {s}: Mitsuba {theirs[-1]:.4g} ({spp} spp in {their_s:.1f} s)"
            for m in methods:
                integrator, guide = m.split("-")
                exr = os.path.join(out, "footprint.exr")
                extra = ["--sequence", args.sequence] if args.sequence else []
                extra += ["--rr-depth", str(args.rr_depth)] if args.rr_depth is not None else []
                run = subprocess.run([FOOTPRINT, "render", xml, *dflags, "--integrator", integrator,
                                      "--guide", guide, "--time", str(args.time), "--seed", str(100 + s),
                                      *extra, "-o", exr], check=True, capture_output=True, text=True)
                our_spp[m].append(int(run.stdout.split(" spp ")[0].split()[-1]))
                ours[m].append(rel_mse(np.array(mi.Bitmap(exr))[..., :3], ref))
                line += f", {m} {ours[m][-1]:.4g} ({our_spp[m][-1]} spp)"
            print(line, flush=True)
        rows.append((name, {m: (float(np.median(ours[m])), int(np.median(our_spp[m]))) for m in methods},
                     float(np.median(theirs)), int(np.median(their_spp)), float(np.median(their_secs))))
    print(f"\nequal time {args.time:g} s per render, {args.seeds} seeds, footprint {', '.join(methods)}"
          f" ({args.sequence or 'default'} numbers), Mitsuba sampler {args.mitsuba_sampler or 'as the XML says'}, "
          f"Russian roulette from depth {args.rr_depth if args.rr_depth is not None else 'as each renderer defaults'}; medians")
    # Mitsuba's sample count comes from timings taken before its renders; where the machine's
    # speed drifts, its renders end short of (or past) the budget. Relative MSE falls as
    # 1/time, so MSE x seconds compares the two at exactly equal time: the ratios below.
    if len(methods) == 1:
        m = methods[0]
        print(f"| scene | footprint `{m}` rel. MSE (spp) | Mitsuba 3 `path` rel. MSE (spp, seconds) | ratio "
              f"| ratio of MSE x seconds |")
        print("|---|---|---|---|---|")
        for name, o, t, ts, tsec in rows:
            e, n = o[m]
            print(f"| {name} | {e:.4g} ({n}) | {t:.4g} ({ts}, {tsec:.1f} s) | {e / t:.2f} "
                  f"| {e * args.time / (t * tsec):.2f} |")
        return 0
    # Several methods: each one's median relative MSE, and its ratio of MSE x seconds to
    # Mitsuba's (below 1: footprint's method is better at equal time); the best in bold.
    print("| scene | Mitsuba 3 `path` (spp) | " + " | ".join(f"`{m}`" for m in methods) + " |")
    print("|---|---|" + "---|" * len(methods))
    for name, o, t, ts, tsec in rows:
        ratios = {m: o[m][0] * args.time / (t * tsec) for m in methods}
        best = min(ratios, key=ratios.get)
        cells = [(f"**{ratios[m]:.2f}**" if m == best else f"{ratios[m]:.2f}") + f" ({o[m][0]:.3g})"
                 for m in methods]
        print(f"| {name} | {t:.3g} ({ts}) | " + " | ".join(cells) + " |")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("references", help="render the bundled scenes' references with Mitsuba")
    r.add_argument("only", nargs="*", help=f"scenes to render [default: all of {', '.join(BUNDLED)}, "
                   f"{', '.join('public/' + k for k in PUBLIC)}]")
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
    b.add_argument("--sequence", choices=["sobol", "independent"],
                   help="footprint's --sequence [default: its default, Sobol; `independent`: independent uniform "
                        "numbers, as Mitsuba's `independent` sampler draws]")
    q = sub.add_parser("compare", help="equal time against Mitsuba's path on Veach Ajar (or SCENE)")
    q.add_argument("only", nargs="*", help="scenes of the table whose name contains one of these words")
    q.add_argument("--time", type=float, default=30.0, help="equal-time budget in seconds")
    q.add_argument("--seeds", type=int, default=3, help="renders per renderer and scene")
    q.add_argument("--integrator", default="pt")
    q.add_argument("--guide", default="bsdf")
    q.add_argument("--methods", help="footprint methods, comma-separated INTEGRATOR-GUIDE (pt-bsdf,pt-footprint,"
                   "lt-grid,...), each rendered per seed at the budget [default: INTEGRATOR-GUIDE from --integrator and --guide]; with "
                   "several, the table gives each one's ratio of MSE x seconds to Mitsuba's")
    q.add_argument("--reference-time", type=float, default=600.0, help="seconds of a Mitsuba reference")
    q.add_argument("--sequence", choices=["sobol", "independent"], help="footprint's --sequence [default: its default]")
    q.add_argument("--mitsuba-sampler", help="replace the XML's sampler type for Mitsuba (e.g. multijitter, ldsampler)")
    q.add_argument("--rr-depth", type=int, help="Russian roulette from this depth in both renderers [default: each "
                   "its own: Mitsuba 5, footprint 8]")
    q.add_argument("-o", "--out")
    args = ap.parse_args()
    sys.exit({"references": cmd_references, "check": cmd_check, "bench": cmd_bench,
              "compare": cmd_compare}[args.cmd](args) or 0)


if __name__ == "__main__":
    main()
