#!/usr/bin/env python3
"""Reference values of Mitsuba 3's `bumpmap` for tests/bumpmap.rs (`matches_mitsuba_3_pointwise`).

Loads scenes/bumpmap/scene.xml in Mitsuba 3 (`scalar_rgb`), shoots rays from fixed origins to
fixed points on its two bump-mapped planes and prints, for fixed world directions `wi`, what
Mitsuba's BSDF at the hit returns: `eval` (which includes the cosine) and `pdf`, in radiance
and importance mode. The output is Rust source: paste it into tests/bumpmap.rs.

    python3 scripts/mitsuba_bumpmap_values.py

Naming: Mitsuba's `si.wi` (toward the ray's origin) is footprint's `wo`; Mitsuba's `wo` is
footprint's `wi`.
"""
import math
import os

import mitsuba as mi

mi.set_variant("scalar_rgb")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Ray origins (footprint's wo side) and target points on the planes (z = 0).
ORIGINS = [(0.0, -2.6, 2.4), (-0.3, 1.5, 0.35), (2.5, 0.4, 0.6)]
TARGETS = [(-1.3, 0.2, 0.0), (-0.7, -0.9, 0.0), (-1.6, 1.1, 0.0), (0.9, 0.3, 0.0), (1.5, -0.8, 0.0), (1.2, 1.0, 0.0),
           (0.25, 1.2, 0.0), (2.2, -1.0, 0.0), (-0.3, 0.6, 0.0)]
# The area light's centre: one more wi per point, toward it.
LIGHT = (0.0, 2.6, 1.1)
# Directions wi as (theta, phi) in degrees about +z.
WIS = [(10.0, 30.0), (40.0, 100.0), (65.0, 200.0), (80.0, 290.0), (88.0, 45.0), (55.0, 0.0)]


def unit(t, p):
    t, p = math.radians(t), math.radians(p)
    return mi.Vector3f(math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t))


def main():
    scene = mi.load_file(os.path.join(ROOT, "scenes/bumpmap/scene.xml"))
    print(f"// Mitsuba {mi.__version__}, scalar_rgb: (origin, target, wi, radiance eval, importance eval, pdf)")
    print("/// (origin, target, wi, radiance eval, importance eval, pdf).")
    print("type Point = ([f32; 3], [f32; 3], [f32; 3], [f32; 3], [f32; 3], f32);")
    print("#[allow(clippy::excessive_precision)]")
    print("const MITSUBA_POINTS: &[Point] = &[")
    for o in ORIGINS:
        for t in TARGETS:
            d = mi.Vector3f(t) - mi.Vector3f(o)
            ray = mi.Ray3f(mi.Point3f(o), d / math.sqrt(sum(x * x for x in d)))
            si = scene.ray_intersect(ray)
            if not si.is_valid():
                continue
            bsdf = si.bsdf(ray)
            to_light = mi.Vector3f(LIGHT) - si.p
            for wi in [unit(*w) for w in WIS] + [to_light / math.sqrt(sum(x * x for x in to_light))]:
                local = si.to_local(wi)
                rad = bsdf.eval(mi.BSDFContext(mi.TransportMode.Radiance), si, local)
                imp = bsdf.eval(mi.BSDFContext(mi.TransportMode.Importance), si, local)
                pdf = bsdf.pdf(mi.BSDFContext(), si, local)
                f = lambda v: "[" + ", ".join(f"{x:.7e}" for x in v) + "]"
                print(f"    ({f(o)}, {f(t)}, {f(wi)}, {f(rad)}, {f(imp)}, {pdf:.7e}),")
    print("];")


main()
