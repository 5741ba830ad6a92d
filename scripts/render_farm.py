#!/usr/bin/env python3
"""Run footprint on a Dask.distributed cluster: a sharded render and its merge, and
`footprint compare` ladders and sweeps fanned out task by task.

    # a cluster of your own (`dask scheduler` + `dask worker tcp://HOST:8786 --nthreads 1`)
    python3 scripts/render_farm.py render SCENE --shards 64 --out frame.exr \
        --scheduler tcp://HOST:8786 -- --spp 4096 --integrator pt --guide footprint
    # or a local cluster on this machine (loopback only)
    python3 scripts/render_farm.py render SCENE --shards 4 --local-workers 2 --out frame.exr -- --spp 64
    python3 scripts/render_farm.py compare SCENE [SCENE ...] --out DIR --time 16 \
        --sweep k_p=25,50,100 --local-workers 2 -- --resolution 128x128

What runs where:
* `render`: when the method is guided, one task runs `footprint maps SCENE --save` and its
  file (the passes' particles) is replicated to every worker once; then one task per shard
  runs `footprint render ... --shard i/N [--maps FILE]`, and one task runs `footprint merge`.
  Shard images travel through Dask (no shared writable filesystem is needed) and are kept in
  the work folder (`--work`, default OUT-shards/) as they finish: a failed or killed shard
  leaves no image there (footprint writes whole files or nothing), and running the same
  command again renders only the shards that are missing.
* `compare`: per scene, the reference (combined image, BSDF sampling, as `footprint compare`
  renders it) as a sharded render, then one task per method, swept value and rung of the
  ladder (`footprint compare --methods M --sweep NAME=V --time T --ladder T --reference
  REF`); the rows are gathered into DIR/SCENE/metrics.csv with the images of the top rung,
  and DIR/SCENE/summary.csv holds each curve's log-log slope.

The footprint binary and the scene files must be at the same paths on every worker (a shared
read-only filesystem or one container image, as in the Slurm and Kubernetes recipes of the
README). Equal-time comparisons are only fair when each worker has a machine to itself:
start workers with `--nthreads 1` (footprint uses every core of its machine).
"""

import argparse
import csv
import hashlib
import io
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import tomllib
import uuid

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_METHODS = "pt-bsdf,pt-grid,pt-footprint,lt-bsdf,lt-grid,lt-footprint,combined-footprint"
SWEEP_METHODS = "pt-footprint,lt-footprint"
REFERENCE_SEED = 0x5EED  # the seed `footprint compare` renders its references with

# Flags of `footprint render` that `footprint maps` does not take (each with one value).
RENDER_ONLY = {"--integrator", "--guide", "--spp", "--time", "--exposure", "--out", "-o",
               "--shard", "--maps"}


# ---------------------------------------------------------------- tasks (run on workers)

def _run(cmd):
    """Runs footprint; raises with its stderr when it fails."""
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr.strip()}")
    return p.stdout


def task_maps(footprint, scene, flags):
    """`footprint maps SCENE --save`: returns the file's bytes and the seconds it took."""
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "maps.fpm")
        t0 = time.time()
        _run([footprint, "maps", scene, "--save", path] + flags)
        with open(path, "rb") as f:
            return {"bytes": f.read(), "wall": time.time() - t0}


def _local_maps(maps):
    """The maps file on this worker: written once per worker machine (by content hash)."""
    digest = hashlib.blake2b(maps, digest_size=16).hexdigest()
    path = os.path.join(tempfile.gettempdir(), f"footprint-maps-{digest}.fpm")
    if not os.path.exists(path):
        tmp = f"{path}.tmp-{os.getpid()}-{uuid.uuid4().hex}"
        with open(tmp, "wb") as f:
            f.write(maps)
        os.replace(tmp, path)
    return path


def task_shard(footprint, scene, flags, index, count, maps):
    """`footprint render --shard index/count`: returns the shard's EXR and its timings."""
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, f"shard-{index}-of-{count}.exr")
        cmd = [footprint, "render", scene] + flags + ["--shard", f"{index}/{count}", "--out", out]
        if maps is not None:
            cmd += ["--maps", _local_maps(maps["bytes"])]
        t0 = time.time()
        _run(cmd)
        wall = time.time() - t0
        with open(out, "rb") as f:
            return {"index": index, "exr": f.read(), "wall": wall}


def task_merge(footprint, shards):
    """`footprint merge`: returns the merged EXR and PNG."""
    with tempfile.TemporaryDirectory() as d:
        paths = []
        for i, s in enumerate(shards):
            p = os.path.join(d, f"input{i}-shard-{s['index']}.exr")
            with open(p, "wb") as f:
                f.write(s["exr"])
            paths.append(p)
        out = os.path.join(d, "merged.exr")
        t0 = time.time()
        _run([footprint, "merge", out] + paths)
        wall = time.time() - t0
        with open(out, "rb") as f, open(os.path.join(d, "merged.png"), "rb") as g:
            return {"exr": f.read(), "png": g.read(), "wall": wall}


def task_compare(footprint, scene, flags, method, sweep, rung, seed, reference):
    """One method (one swept value) at one rung of the ladder: `footprint compare`'s rows and,
    for the top rung, its images."""
    with tempfile.TemporaryDirectory() as d:
        ref = os.path.join(d, "reference.exr")
        with open(ref, "wb") as f:
            f.write(reference["exr"])
        out = os.path.join(d, "out")
        cmd = [footprint, "compare", scene, "--methods", method, "--time", repr(rung),
               "--ladder", repr(rung), "--reference", ref, "--seed", str(seed),
               "--out", out] + flags
        if sweep:
            cmd += ["--sweep", sweep]
        _run(cmd)
        with open(os.path.join(out, "metrics.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        images = {}
        for name in os.listdir(out):
            if name.endswith(".png"):
                with open(os.path.join(out, name), "rb") as f:
                    images[name] = f.read()
        return {"rows": rows, "images": images}


# ---------------------------------------------------------------- the client

def exr_text_attributes(data):
    """The text attributes of an EXR's first header (footprint writes its settings there)."""
    attrs, at = {}, 8
    while at < len(data) and data[at] != 0:
        end = data.index(b"\0", at)
        name = data[at:end].decode()
        end2 = data.index(b"\0", end + 1)
        kind = data[end + 1:end2].decode()
        (size,) = struct.unpack_from("<i", data, end2 + 1)
        value = data[end2 + 5:end2 + 5 + size]
        if kind == "string":
            attrs[name] = value.decode(errors="replace")
        at = end2 + 5 + size
    return attrs


def write_atomic(path, data):
    """Writes `data` to `path` whole or not at all (a temporary file renamed over it)."""
    d, name = os.path.split(os.path.abspath(path))
    tmp = os.path.join(d, f".{name}.tmp-{os.getpid()}")
    with open(tmp, "wb") as f:
        f.write(data)
    os.replace(tmp, path)


def flag_value(flags, name):
    for i, f in enumerate(flags[:-1]):
        if f == name:
            return flags[i + 1]
    return None


def without(flags, names):
    """`flags` without the flags `names` and their values."""
    out, skip = [], False
    for f in flags:
        if skip:
            skip = False
        elif f in names:
            skip = True
        else:
            out.append(f)
    return out


def is_guided(scene, flags):
    """Whether the render uses particle maps: `--guide`, else the scene file's render.guide."""
    guide = flag_value(flags, "--guide")
    if guide is None and scene.endswith(".toml"):
        with open(scene, "rb") as f:
            guide = tomllib.load(f).get("render", {}).get("guide")
    return guide not in (None, "bsdf")


def sharded_render(client, footprint, scene, flags, count, work, log):
    """Renders `count` shards (those not already in `work`) and merges them; returns the
    merge's result and the timings of each step."""
    os.makedirs(work, exist_ok=True)
    run = uuid.uuid4().hex[:8]
    stats = {"maps_wall": None, "shards": {}, "reused": []}
    have = {}
    for i in range(count):
        p = os.path.join(work, f"shard-{i}-of-{count}.exr")
        if os.path.exists(p):
            with open(p, "rb") as f:
                have[i] = {"index": i, "exr": f.read(), "wall": None}
    stats["reused"] = sorted(have)
    if have:
        log(f"{len(have)} of {count} shards already in {work}: rendering the other {count - len(have)}")
    todo = [i for i in range(count) if i not in have]
    maps = None
    if todo and is_guided(scene, flags):
        maps = client.submit(task_maps, footprint, scene, without(flags, RENDER_ONLY),
                             key=f"footprint-maps-{run}", pure=False)
        client.replicate([maps])  # waits for it, then ships the file to every worker once
        stats["maps_wall"] = maps.result()["wall"]
        log(f"maps saved and replicated to every worker ({len(maps.result()['bytes']) / 1e6:.1f} MB)")
    from dask.distributed import as_completed
    futures = [client.submit(task_shard, footprint, scene, flags, i, count, maps,
                             key=f"footprint-shard-{i}-of-{count}-{run}", pure=False,
                             retries=1) for i in todo]
    failed, done = [], {}
    for fut in as_completed(futures):
        try:
            r = fut.result()
        except Exception as e:  # a shard that failed twice: report it, keep the others
            failed.append(str(e))
            continue
        write_atomic(os.path.join(work, f"shard-{r['index']}-of-{count}.exr"), r["exr"])
        done[r["index"]] = fut
        stats["shards"][r["index"]] = {"wall": r["wall"], **exr_text_attributes(r["exr"])}
        log(f"shard {r['index']}/{count} done in {r['wall']:.2f} s")
    if failed:
        missing = [i for i in range(count)
                   if not os.path.exists(os.path.join(work, f"shard-{i}-of-{count}.exr"))]
        raise SystemExit(
            "error: shards failed:\n" + "\n".join(failed) +
            f"\nmissing: {', '.join(f'{i}/{count}' for i in missing)}; the finished shards are "
            f"kept in {work}: run the same command again to render only the missing ones")
    # (scatter takes a dict for a mapping of keys: wrap it in a list)
    inputs = [done[i] if i in done else client.scatter([have[i]])[0] for i in range(count)]
    merged = client.submit(task_merge, footprint, inputs, key=f"footprint-merge-{run}",
                           pure=False).result()
    stats["merge_wall"] = merged["wall"]
    return merged, stats


def connect(args):
    from dask.distributed import Client, LocalCluster
    if args.scheduler:
        return Client(args.scheduler), None
    # Loopback only; one task per worker process, footprint itself uses the cores.
    cluster = LocalCluster(n_workers=args.local_workers, threads_per_worker=1, processes=True,
                           host="127.0.0.1", dashboard_address=None)
    return Client(cluster), cluster


def log_to_stderr(m):
    print(m, file=sys.stderr, flush=True)


def render_command(args, flags, client):
    if flag_value(flags, "--time") is not None:
        raise SystemExit("error: a sharded render needs --spp (the total), not --time")
    if flag_value(flags, "--out") or flag_value(flags, "-o"):
        raise SystemExit("error: give the output as the driver's --out, not after --")
    out = args.out
    work = args.work or os.path.splitext(out)[0] + "-shards"
    t0 = time.time()
    merged, stats = sharded_render(client, args.footprint, args.scene, flags, args.shards, work,
                                   log_to_stderr)
    write_atomic(out, merged["exr"])
    write_atomic(os.path.splitext(out)[0] + ".png", merged["png"])
    print(f"{args.shards} shards merged -> {out} in {time.time() - t0:.1f} s")
    print("shard  wall_s  render_s  maps_load_s  tracing_s  start_and_write_s")
    for i, s in sorted(stats["shards"].items()):
        tracing = float(s.get("footprint/time_split_s", "tracing=nan").split("tracing=")[-1])
        render = float(s.get("footprint/render_time_s", "nan"))
        print(f"{i:5d}  {s['wall']:6.2f}  {render:8.2f}  {s.get('footprint/maps_load_s', '-'):>11}"
              f"  {tracing:9.2f}  {s['wall'] - render:17.2f}")
    if stats["maps_wall"] is not None:
        print(f"maps task: {stats['maps_wall']:.2f} s")
    print(f"merge task: {stats['merge_wall']:.2f} s")


def slope(points):
    """Least-squares slope of log(error) against log(time), as `footprint compare`'s."""
    pts = [(math.log(t), math.log(e)) for t, e in points if t > 0 and e > 0]
    if len(pts) < 2:
        return None
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx if sxx > 0 else None


def compare_command(args, flags, client):
    if flag_value(flags, "--seed") is not None:
        raise SystemExit("error: give the seed as the driver's --seed, not after --")
    ladder = ([float(t) for t in args.ladder.split(",")] if args.ladder
              else [args.time / 8, args.time / 4, args.time / 2, args.time])
    methods = (args.methods or (SWEEP_METHODS if args.sweep else DEFAULT_METHODS)).split(",")
    sweeps = [None]
    if args.sweep:
        name, values = args.sweep.split("=", 1)
        sweeps = [f"{name}={v}" for v in values.split(",")]
    os.makedirs(args.out, exist_ok=True)
    # References first (each a sharded render), then every (method, value, rung) as a task.
    jobs = []
    for scene in args.scene:
        stem = os.path.splitext(os.path.basename(scene))[0]
        dest = os.path.join(args.out, stem)
        os.makedirs(dest, exist_ok=True)
        ref_flags = flags + ["--integrator", "combined", "--guide", "bsdf",
                             "--spp", str(args.reference_spp), "--seed", str(REFERENCE_SEED)]
        log_to_stderr(f"{stem}: reference, {args.reference_spp} spp in {args.shards} shards")
        reference, _ = sharded_render(client, args.footprint, scene, ref_flags, args.shards,
                                      os.path.join(dest, "reference-shards"), log_to_stderr)
        write_atomic(os.path.join(dest, "reference.exr"), reference["exr"])
        ref = client.scatter([reference], broadcast=True)[0]
        for m in methods:
            for sw in sweeps:
                for t in ladder:
                    f = client.submit(task_compare, args.footprint, scene, flags, m, sw, t,
                                      args.seed, ref, pure=False, retries=1)
                    jobs.append((stem, dest, t, f))
    log_to_stderr(f"{len(jobs)} compare runs submitted")
    results = {}
    for stem, dest, t, f in jobs:
        r = f.result()
        results.setdefault((stem, dest), []).append((t, r))
    for (stem, dest), runs in results.items():
        rows = [row for _, r in runs for row in r["rows"]]
        rows.sort(key=lambda r: (r["method"], float(r["time_budget_s"])))
        buf = io.StringIO()
        w = csv.DictWriter(buf, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
        write_atomic(os.path.join(dest, "metrics.csv"), buf.getvalue().encode())
        for t, r in runs:
            if t == ladder[-1]:
                for name, data in r["images"].items():
                    write_atomic(os.path.join(dest, name), data)
        buf = io.StringIO()
        w = csv.writer(buf)
        w.writerow(["method", "slope", f"rel_mse_at_{ladder[-1]}s", "spp"])
        for m in sorted({r["method"] for r in rows}):
            mine = [r for r in rows if r["method"] == m]
            s = slope([(float(r["seconds"]), float(r["rel_mse"])) for r in mine])
            last = max(mine, key=lambda r: float(r["time_budget_s"]))
            w.writerow([m, "" if s is None else f"{s:.3f}", last["rel_mse"], last["spp"]])
        write_atomic(os.path.join(dest, "summary.csv"), buf.getvalue().encode())
        print(f"{stem}: {len(rows)} rows -> {dest}/metrics.csv, summary.csv")


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    flags = []
    if "--" in argv:
        i = argv.index("--")
        argv, flags = argv[:i], argv[i + 1:]
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="command", required=True)
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--scheduler", help="address of a running Dask scheduler (tcp://HOST:8786)")
    common.add_argument("--local-workers", type=int, default=2,
                        help="without --scheduler: workers of a local cluster (loopback only)")
    common.add_argument("--footprint", default=None,
                        help="the footprint binary, at this path on every worker "
                             "[default: target/release/footprint of this checkout, else PATH]")
    common.add_argument("--shards", type=int, default=4, help="shards of each render")
    r = sub.add_parser("render", parents=[common],
                       help="a sharded render and its merge; footprint render flags after --")
    r.add_argument("scene")
    r.add_argument("--out", required=True, help="merged EXR (the PNG is written beside it)")
    r.add_argument("--work", help="folder of the finished shards [default: OUT-shards]")
    c = sub.add_parser("compare", parents=[common],
                       help="footprint compare, one task per method, value and rung; "
                            "shared flags (--resolution, --max-depth, ...) after --")
    c.add_argument("scene", nargs="+")
    c.add_argument("--out", required=True, help="folder; one subfolder per scene")
    c.add_argument("--time", type=float, default=8.0)
    c.add_argument("--ladder", help="budgets T1,T2,... [default: time/8,time/4,time/2,time]")
    c.add_argument("--methods", help=f"[default: {DEFAULT_METHODS}; with --sweep {SWEEP_METHODS}]")
    c.add_argument("--sweep", help="NAME=V1,V2,...: one task per value")
    c.add_argument("--reference-spp", type=int, default=256)
    c.add_argument("--seed", type=int, default=1)
    args = p.parse_args(argv)
    if args.shards < 1:
        p.error("--shards must be at least 1")
    if args.footprint is None:
        built = os.path.join(REPO, "target", "release", "footprint")
        args.footprint = built if os.path.exists(built) else (shutil.which("footprint") or built)
    args.footprint = os.path.abspath(args.footprint)
    if args.command == "render":
        args.scene = os.path.abspath(args.scene)
    else:
        args.scene = [os.path.abspath(s) for s in args.scene]
    client, cluster = connect(args)
    try:
        (render_command if args.command == "render" else compare_command)(args, flags, client)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


if __name__ == "__main__":
    main()
