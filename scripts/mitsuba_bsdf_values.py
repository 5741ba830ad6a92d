#!/usr/bin/env python3
"""Reference values of Mitsuba 3's BSDFs for tests/bsdf.rs (`matches_mitsuba_3`).

Prints, for fixed directions in the local shading frame, what Mitsuba 3 (variant
`scalar_rgb`) returns for the BSDFs footprint reproduces: `eval` divided by the cosine of
the sampled direction (Mitsuba's `eval` includes it; footprint's does not), the `pdf` of the
rough BSDFs, and for the delta lobes the `sample` weight and discrete probability. The output
is Rust source: paste it into tests/bsdf/mitsuba.rs and tests/bsdf/rough_dielectric.rs
(`principled`: below the types in tests/bsdf/principled_values.rs; tests/bsdf.rs defines
`MitsubaRow`).

    pip install mitsuba              # once
    python3 scripts/mitsuba_bsdf_values.py              # tests/bsdf/mitsuba.rs and
                                                        # tests/bsdf/rough_dielectric.rs
    python3 scripts/mitsuba_bsdf_values.py principled   # tests/bsdf/principled_values.rs

Naming: Mitsuba's `si.wi` is footprint's `wo` (toward the camera in radiance mode) and
Mitsuba's `wo` is footprint's `wi` (the sampled direction). `ext_ior` is set to 1 so that
`int_ior` is footprint's relative `ni`.
"""
import math
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")


def d(theta_deg, phi_deg):
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return mi.Vector3f(math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t))


# (wo, wi) pairs in footprint's naming, as (theta, phi) in degrees.
PAIRS = [
    ((30.0, 0.0), (35.0, 180.0)),
    ((0.0, 0.0), (10.0, 40.0)),
    ((60.0, 0.0), (20.0, 120.0)),
    ((80.0, 10.0), (75.0, 200.0)),
    ((45.0, 0.0), (50.0, 170.0)),
    ((87.0, 0.0), (40.0, 90.0)),
]
# More pairs for the anisotropic distributions: incident and sampled azimuths off the axes,
# so that both roughnesses and their mix show.
ANISOTROPIC_PAIRS = [
    ((40.0, 90.0), (45.0, 270.0)),
    ((50.0, 60.0), (30.0, 250.0)),
    ((20.0, 135.0), (60.0, 300.0)),
    ((70.0, 300.0), (65.0, 110.0)),
]
COSINES = [1.0, 0.8, 0.5, 0.2, 0.05]

ETA = [0.2, 0.45, 1.4]
K = [3.2, 2.5, 1.9]
KD = [0.6, 0.3, 0.15]
KS = [0.9, 0.8, 1.0]


def rgb(v):
    return {"type": "rgb", "value": v}


def si_for(wo):
    si = mi.SurfaceInteraction3f()
    si.p = mi.Point3f(0, 0, 0)
    si.n = mi.Normal3f(0, 0, 1)
    si.sh_frame = mi.Frame3f(si.n)
    si.uv = mi.Point2f(0.5, 0.5)
    si.wi = wo
    return si


def fmt(v):
    return "[" + ", ".join(f"{float(x):.7e}" for x in v) + "]"


ROUGH = [
    ("roughconductor_ggx_a0.1", {"type": "roughconductor", "distribution": "ggx", "alpha": 0.1,
                                 "eta": rgb(ETA), "k": rgb(K), "specular_reflectance": rgb(KS)}),
    ("roughconductor_ggx_a0.4", {"type": "roughconductor", "distribution": "ggx", "alpha": 0.4,
                                 "eta": rgb(ETA), "k": rgb(K), "specular_reflectance": rgb(KS)}),
    ("roughconductor_beckmann_a0.1", {"type": "roughconductor", "distribution": "beckmann",
                                      "alpha": 0.1, "eta": rgb(ETA), "k": rgb(K),
                                      "specular_reflectance": rgb(KS)}),
    ("roughconductor_beckmann_a0.4", {"type": "roughconductor", "distribution": "beckmann",
                                      "alpha": 0.4, "eta": rgb(ETA), "k": rgb(K),
                                      "specular_reflectance": rgb(KS)}),
    ("roughplastic_ggx_a0.2", {"type": "roughplastic", "distribution": "ggx", "alpha": 0.2,
                               "int_ior": 1.5, "ext_ior": 1.0, "diffuse_reflectance": rgb(KD),
                               "specular_reflectance": rgb(KS)}),
    ("roughplastic_beckmann_a0.3", {"type": "roughplastic", "distribution": "beckmann",
                                    "alpha": 0.3, "int_ior": 1.6, "ext_ior": 1.0,
                                    "diffuse_reflectance": rgb(KD)}),
    ("roughplastic_ggx_a0.05_nonlinear", {"type": "roughplastic", "distribution": "ggx",
                                          "alpha": 0.05, "int_ior": 1.45, "ext_ior": 1.0,
                                          "nonlinear": True, "diffuse_reflectance": rgb(KD)}),
    ("plastic", {"type": "plastic", "int_ior": 1.5, "ext_ior": 1.0,
                 "diffuse_reflectance": rgb(KD), "specular_reflectance": rgb(KS)}),
    ("plastic_nonlinear", {"type": "plastic", "int_ior": 1.7, "ext_ior": 1.0, "nonlinear": True,
                           "diffuse_reflectance": rgb(KD)}),
    # Anisotropic: alpha_u along the local x axis (the shading frame's dp/du), alpha_v along y.
    ("roughconductor_ggx_u0.1_v0.4", {"type": "roughconductor", "distribution": "ggx",
                                      "alpha_u": 0.1, "alpha_v": 0.4, "eta": rgb(ETA),
                                      "k": rgb(K), "specular_reflectance": rgb(KS)}),
    ("roughconductor_beckmann_u0.5_v0.15", {"type": "roughconductor", "distribution": "beckmann",
                                            "alpha_u": 0.5, "alpha_v": 0.15, "eta": rgb(ETA),
                                            "k": rgb(K), "specular_reflectance": rgb(KS)}),
]

DELTA = [
    ("conductor", {"type": "conductor", "eta": rgb(ETA), "k": rgb(K),
                   "specular_reflectance": rgb(KS)}),
    ("plastic", {"type": "plastic", "int_ior": 1.5, "ext_ior": 1.0,
                 "diffuse_reflectance": rgb(KD), "specular_reflectance": rgb(KS)}),
    ("thindielectric", {"type": "thindielectric", "int_ior": 1.5, "ext_ior": 1.0}),
]


# roughdielectric: (name, distribution, alpha, int_ior, specular_reflectance,
# specular_transmittance); ext_ior 1.
ROUGH_DIELECTRIC_KS = [0.9, 0.8, 1.0]
ROUGH_DIELECTRIC_KT = [0.7, 0.9, 0.8]
ROUGH_DIELECTRIC = [
    (f"roughdielectric_{dist}_a{alpha}", dist, alpha)
    for dist in ["ggx", "beckmann"]
    for alpha in [0.01, 0.1, 0.5]
] + [
    # Anisotropic: (alpha_u, alpha_v).
    ("roughdielectric_ggx_u0.1_v0.3", "ggx", (0.1, 0.3)),
    ("roughdielectric_beckmann_u0.3_v0.1", "beckmann", (0.3, 0.1)),
]
ROUGH_DIELECTRIC_IOR = 1.5
# Incident directions (theta, phi in degrees): entering from above, leaving from below (the
# last two beyond the critical angle of the smooth interface, 41.8 degrees from the normal).
ROUGH_DIELECTRIC_WO = [(5.0, 20.0), (35.0, 0.0), (70.0, 130.0), (160.0, 30.0), (135.0, 250.0),
                       (115.0, 60.0)]


def angles(v):
    """(theta, phi) in degrees of a unit vector, rounded as the table prints them."""
    t = math.degrees(math.acos(max(-1.0, min(1.0, v[2]))))
    p = math.degrees(math.atan2(v[1], v[0])) % 360.0
    return (round(t, 4), round(p, 4))


def rough_dielectric_pairs(alpha):
    """(wo, wi) angle pairs about the smooth interface's mirror and refraction directions of
    each incident direction, offset by 0, 1 and 2.5 alpha, so that the rows sample the lobes
    where they are large and in their tails."""
    pairs = []
    for wo_a in ROUGH_DIELECTRIC_WO:
        wo = [float(x) for x in d(*wo_a)]
        s = 1.0 if wo[2] > 0 else -1.0
        eta = ROUGH_DIELECTRIC_IOR if s > 0 else 1.0 / ROUGH_DIELECTRIC_IOR
        targets = [[-wo[0], -wo[1], wo[2]]]
        cos_i = abs(wo[2])
        sin2_t = (1 - cos_i * cos_i) / (eta * eta)
        if sin2_t < 1:
            cos_t = math.sqrt(1 - sin2_t)
            targets.append([-wo[0] / eta, -wo[1] / eta, -s * cos_t])
        else:
            # Beyond the critical angle: the refraction of the most tilted facets.
            targets.append([-wo[0] * 0.3, -wo[1] * 0.3, -s * math.sqrt(1 - 0.09 * (1 - cos_i * cos_i))])
        for t in targets:
            pairs += offsets_about(wo_a, t, alpha, [(0.0, 0.0), (1.0, 70.0), (2.5, 200.0)])
    return pairs


def offsets_about(wo_a, target, alpha, steps):
    """(wo, wi) angle pairs with wi about the direction `target`: offset by k alpha radians
    away from the macro normal's axis, along the angle phi, for each (k, phi) of `steps`."""
    n = math.sqrt(sum(x * x for x in target))
    th, ph = angles([x / n for x in target])
    pairs = []
    for k, phi in steps:
        dth = math.degrees(k * alpha) * math.cos(math.radians(phi))
        dph = math.degrees(k * alpha) * math.sin(math.radians(phi))
        th2 = min(179.9, max(0.1, th + dth))
        if abs(th2 - 90.0) < 0.5:
            th2 = 89.5 if th < 90 else 90.5
        pairs.append((wo_a, (round(th2, 4), round((ph + dph) % 360.0, 4))))
    return pairs


def rough_dielectric_rows():
    print("// (name, importance mode, wo (theta, phi deg), wi (theta, phi deg), f = eval / |cos(wi)|,")
    print("// pdf); int_ior 1.5, ext_ior 1, specular_reflectance and _transmittance as in the test.")
    print("#[rustfmt::skip]")
    print("#[allow(clippy::excessive_precision)]")
    print("const MITSUBA_ROUGH_DIELECTRIC: &[MitsubaRow] = &[")
    for name, dist, alpha in ROUGH_DIELECTRIC:
        roughness = ({"alpha_u": alpha[0], "alpha_v": alpha[1]} if isinstance(alpha, tuple)
                     else {"alpha": alpha})
        bsdf = mi.load_dict({"type": "roughdielectric", "distribution": dist, **roughness,
                             "int_ior": ROUGH_DIELECTRIC_IOR, "ext_ior": 1.0,
                             "specular_reflectance": rgb(ROUGH_DIELECTRIC_KS),
                             "specular_transmittance": rgb(ROUGH_DIELECTRIC_KT)})
        width = max(alpha) if isinstance(alpha, tuple) else alpha
        print_rows(name, bsdf, rough_dielectric_pairs(width), [False, True])
    print("];")


def print_rows(name, bsdf, pairs, modes):
    """One row per (wo, wi) pair and transport mode: `eval / |cos(wi)|` and `pdf`."""
    for wo_a, wi_a in pairs:
        for importance in modes:
            mode = mi.TransportMode.Importance if importance else mi.TransportMode.Radiance
            ctx = mi.BSDFContext(mode)
            wo, wi = d(*wo_a), d(*wi_a)
            si = si_for(wo)
            value = bsdf.eval(ctx, si, wi)
            pdf = bsdf.pdf(ctx, si, wi)
            f = [value[i] / abs(wi.z) for i in range(3)]
            print(f'    ("{name}", {str(importance).lower()}, [{wo_a[0]:.4f}, {wo_a[1]:.4f}], '
                  f'[{wi_a[0]:.4f}, {wi_a[1]:.4f}], {fmt(f)}, {float(pdf):.7e}),')


# principled: (name, base_color, the scalar parameters in PRINCIPLED_SCALARS' order,
# (index property, value), sampling rates (diffuse, main specular, clearcoat)). Each set
# stresses some lobes; the last four transmit and are evaluated on both sides in both modes.
PRINCIPLED_SCALARS = ["roughness", "anisotropic", "metallic", "spec_trans", "spec_tint", "sheen",
                      "sheen_tint", "flatness", "clearcoat", "clearcoat_gloss"]
PRINCIPLED = [
    ("default", [0.5, 0.5, 0.5], [0.5, 0, 0, 0, 0, 0, 0, 0, 0, 0], ("specular", 0.5), [1, 1, 1]),
    ("dielectric_sheen", [0.8, 0.3, 0.2], [0.3, 0, 0, 0, 0.4, 0.5, 0.6, 0.3, 0, 0], ("specular", 0.6),
     [1, 1, 1]),
    ("metallic_anisotropic", [0.9, 0.6, 0.3], [0.2, 0.6, 0.8, 0, 0.2, 0, 0, 0, 0, 0], ("eta", 1.6),
     [1, 1, 1]),
    ("clearcoat", [0.2, 0.4, 0.8], [0.6, 0, 0, 0, 0, 0, 0, 0, 0.8, 0.7], ("specular", 0.7), [1, 1, 1]),
    ("smooth", [0.7, 0.7, 0.2], [0.05, 0, 0.5, 0, 0, 0, 0, 0, 0, 0], ("eta", 1.5), [1, 1, 1]),
    ("rough_sheen_flat", [0.6, 0.5, 0.4], [1.0, 0, 0, 0, 0, 1.0, 0.5, 0.7, 0, 0], ("specular", 0.3),
     [1, 1, 1]),
    ("rates", [0.3, 0.6, 0.5], [0.4, 0, 0.2, 0, 0, 0, 0, 0, 0.5, 0.2], ("eta", 1.4), [0.5, 2.0, 0.3]),
    ("spec_trans", [0.9, 0.8, 0.7], [0.25, 0.3, 0.1, 0.7, 0.3, 0.3, 0.2, 0, 0.4, 0.5], ("eta", 1.45),
     [1, 1, 1]),
    ("glass", [0.9, 0.9, 0.95], [0.1, 0, 0, 1.0, 0, 0, 0, 0, 0, 0], ("eta", 1.5), [1, 1, 1]),
    ("glass_rough_specular", [0.8, 0.9, 0.6], [0.6, 0, 0, 1.0, 0, 0, 0, 0, 0, 0], ("specular", 0.4),
     [1, 1, 1]),
    ("spec_trans_anisotropic", [0.5, 0.9, 0.9], [0.35, 0.8, 0, 0.5, 0, 0, 0, 0, 0, 0], ("eta", 1.3),
     [1, 1.5, 1]),
]


def principled_dict(base, scalars, ior, rates):
    d = {"type": "principled", "base_color": rgb(base), ior[0]: ior[1],
         "diffuse_reflectance_sampling_rate": rates[0], "main_specular_sampling_rate": rates[1],
         "clearcoat_sampling_rate": rates[2]}
    # Mitsuba treats a parameter given as 0 as absent (`get_flag`); leave zeros out.
    for k, v in zip(PRINCIPLED_SCALARS, scalars):
        if v != 0 or k == "roughness":
            d[k] = float(v)
    return d


def principled_pairs(scalars, eta):
    """(wo, wi) angle pairs: the generic PAIRS, then pairs about the mirror direction of a few
    incident directions (offset by 0, 1 and 3 of the main lobe's alpha) and, for the
    transmitting sets, about the refraction, from above and from below."""
    pairs = list(PAIRS)
    alpha = max(0.001, scalars[0] ** 2)
    transmits = scalars[3] > 0
    wos = [(25.0, 40.0), (70.0, 300.0)] + ([(150.0, 80.0), (120.0, 200.0)] if transmits else [])
    for wo_a in wos:
        wo = [float(x) for x in d(*wo_a)]
        s = 1.0 if wo[2] > 0 else -1.0
        e = eta if s > 0 else 1.0 / eta
        targets = [[-wo[0], -wo[1], wo[2]]]
        if transmits:
            sin2_t = (1 - wo[2] * wo[2]) / (e * e)
            if sin2_t < 1:
                targets.append([-wo[0] / e, -wo[1] / e, -s * math.sqrt(1 - sin2_t)])
        for t in targets:
            pairs += offsets_about(wo_a, t, alpha, [(0.0, 0.0), (1.0, 70.0), (3.0, 200.0)])
    return pairs


def principled_rows():
    print(f"// Generated by scripts/mitsuba_bsdf_values.py principled with Mitsuba {mi.__version__} "
          "(variant scalar_rgb).")
    print("// (name, base_color, [" + ", ".join(PRINCIPLED_SCALARS) + "],")
    print("// (\"eta\" or \"specular\", value), sampling rates [diffuse, main specular, clearcoat])")
    print("#[rustfmt::skip]")
    print("#[allow(clippy::excessive_precision)]")
    print("pub const MITSUBA_PRINCIPLED_SETS: &[PrincipledSet] = &[")
    for name, base, scalars, ior, rates in PRINCIPLED:
        print(f'    ("{name}", {[float(x) for x in base]}, {[float(x) for x in scalars]}, '
              f'("{ior[0]}", {float(ior[1])}), {[float(x) for x in rates]}),')
    print("];")
    print("// (set, importance mode, wo (theta, phi deg), wi (theta, phi deg), f = eval / |cos(wi)|, pdf)")
    print("#[rustfmt::skip]")
    print("#[allow(clippy::excessive_precision)]")
    print("pub const MITSUBA_PRINCIPLED: &[MitsubaRow] = &[")
    for name, base, scalars, ior, rates in PRINCIPLED:
        bsdf = mi.load_dict(principled_dict(base, scalars, ior, rates))
        eta = ior[1] if ior[0] == "eta" else 2.0 / (1.0 - math.sqrt(0.08 * ior[1])) - 1.0
        modes = [False, True] if scalars[3] > 0 else [False]
        print_rows(name, bsdf, principled_pairs(scalars, eta), modes)
    print("];")


# The albedo `E[weight]` of Mitsuba's `sample` per principled set: the incident polar angles
# (phi 40 degrees), both sides for the transmitting sets, and the number of samples.
PRINCIPLED_ALBEDO_THETAS = [20.0, 80.0]
PRINCIPLED_ALBEDO_THETAS_BELOW = [150.0]
PRINCIPLED_ALBEDO_SAMPLES = 1_000_000


def principled_albedo_rows():
    """Mean and standard error per channel of Mitsuba's sample weight (Python's random,
    seeded: the table is reproducible)."""
    import random

    print(f"// (set, importance mode, wo (theta, phi deg), mean weight, its standard error), "
          f"{PRINCIPLED_ALBEDO_SAMPLES} samples of Mitsuba's `sample` each")
    print("#[rustfmt::skip]")
    print("#[allow(clippy::excessive_precision)]")
    print("pub const MITSUBA_PRINCIPLED_ALBEDO: &[AlbedoRow] = &[")
    rng = random.Random(7)
    n = PRINCIPLED_ALBEDO_SAMPLES
    for name, base, scalars, ior, rates in PRINCIPLED:
        bsdf = mi.load_dict(principled_dict(base, scalars, ior, rates))
        transmits = scalars[3] > 0
        thetas = PRINCIPLED_ALBEDO_THETAS + (PRINCIPLED_ALBEDO_THETAS_BELOW if transmits else [])
        for theta in thetas:
            for importance in ([False, True] if transmits else [False]):
                mode = mi.TransportMode.Importance if importance else mi.TransportMode.Radiance
                ctx = mi.BSDFContext(mode)
                si = si_for(d(theta, 40.0))
                s1, s2 = [0.0] * 3, [0.0] * 3
                for _ in range(n):
                    _, w = bsdf.sample(ctx, si, rng.random(), mi.Point2f(rng.random(), rng.random()))
                    for c in range(3):
                        s1[c] += w[c]
                        s2[c] += w[c] * w[c]
                mean = [x / n for x in s1]
                se = [math.sqrt(max(0.0, s2[c] / n - mean[c] ** 2) / (n - 1)) for c in range(3)]
                print(f'    ("{name}", {str(importance).lower()}, [{theta:.1f}, 40.0], {fmt(mean)}, '
                      f'{fmt(se)}),')
    print("];")


# blendbsdf: (name, weight, bsdf_0, bsdf_1); eval/pdf rows as ROUGH (delta samples are not
# compared: Mitsuba 3.9's blend adds the other component's density and value to a delta
# sample, which footprint does not; docs/mitsuba.md).
BLEND = [
    ("blend_diffuse_roughconductor_w0.3", 0.3, {"type": "diffuse", "reflectance": rgb(KD)},
     dict(dict(ROUGH)["roughconductor_ggx_a0.4"])),
    ("blend_roughplastic_diffuse_w0.75", 0.75, dict(dict(ROUGH)["roughplastic_ggx_a0.2"]),
     {"type": "diffuse", "reflectance": rgb([0.2, 0.5, 0.7])}),
    ("blend_plastic_roughconductor_w0.5", 0.5, dict(dict(DELTA)["plastic"]),
     dict(dict(ROUGH)["roughconductor_beckmann_a0.1"])),
]


def blend(weight, a, b):
    return mi.load_dict({"type": "blendbsdf", "weight": weight, "bsdf_0": a, "bsdf_1": b})


def eval_rows(table, bsdfs):
    """A table of `eval / cos` and `pdf` rows of the BSDFs `(name, bsdf, pairs)`."""
    ctx = mi.BSDFContext()
    print("// (name, wo (theta, phi deg), wi (theta, phi deg), f = eval / cos(wi), pdf)")
    print("#[rustfmt::skip]")
    print("#[allow(clippy::excessive_precision)]")
    print(f"const {table}: &[EvalRow] = &[")
    for name, bsdf, pairs in bsdfs:
        for wo_a, wi_a in pairs:
            wo, wi = d(*wo_a), d(*wi_a)
            si = si_for(wo)
            value = bsdf.eval(ctx, si, wi)
            pdf = bsdf.pdf(ctx, si, wi)
            f = [value[i] / wi.z for i in range(3)]
            print(f'    ("{name}", [{wo_a[0]:.1f}, {wo_a[1]:.1f}], [{wi_a[0]:.1f}, '
                  f'{wi_a[1]:.1f}], {fmt(f)}, {float(pdf):.7e}),')
    print("];")


def main():
    if sys.argv[1:] == ["principled"]:
        principled_rows()
        principled_albedo_rows()
        return
    ctx = mi.BSDFContext()
    print(f"// Generated by scripts/mitsuba_bsdf_values.py with Mitsuba {mi.__version__} "
          "(variant scalar_rgb).")
    eval_rows("MITSUBA_EVAL", [(name, mi.load_dict(desc),
                                PAIRS + (ANISOTROPIC_PAIRS if "alpha_u" in desc else []))
                               for name, desc in ROUGH])
    print("// (name, cos(wo), lobe sample number, sample weight, discrete probability)")
    print("#[rustfmt::skip]")
    print("#[allow(clippy::excessive_precision)]")
    print("const MITSUBA_DELTA: &[DeltaRow] = &[")
    for name, desc in DELTA:
        bsdf = mi.load_dict(desc)
        for c in COSINES:
            wo = mi.Vector3f(math.sqrt(1 - c * c), 0, c)
            si = si_for(wo)
            # u = 0 picks the reflection lobe wherever it has positive probability.
            for u in [0.0]:
                bs, w = bsdf.sample(ctx, si, u, mi.Point2f(0.5, 0.5))
                print(f'    ("{name}", {c:.2f}, {u:.1f}, {fmt(w)}, {float(bs.pdf):.7e}),')
    print("];")
    rough_dielectric_rows()
    print(f"// Generated by scripts/mitsuba_bsdf_values.py with Mitsuba {mi.__version__} "
          "(variant scalar_rgb).")
    eval_rows("MITSUBA_BLEND_EVAL", [(name, blend(w, a, b), PAIRS) for name, w, a, b in BLEND])


if __name__ == "__main__":
    main()
