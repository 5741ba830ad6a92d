//! Mitsuba 3's `principled` BSDF: its values and densities against Mitsuba 3's own on both
//! sides and in both transport modes (`matches_mitsuba_3`, constants printed by
//! `scripts/mitsuba_bsdf_values.py principled`), importance mode as the adjoint of radiance
//! mode and radiance's generalised reciprocity across the surface, energy where the model
//! conserves it, one-sidedness, and where it guides.

use crate::common::{mean_stderr, normal_quantile, sidak};
use crate::configs::{ROUGH_GLASS_ETA, principled_configs, rough_glass};
use crate::principled_values::{
    MITSUBA_PRINCIPLED, MITSUBA_PRINCIPLED_ALBEDO, MITSUBA_PRINCIPLED_SETS, PrincipledSet,
};
use crate::reciprocity::check_adjoint_and_reciprocity;
use crate::{check_mitsuba_row, dir, flat_bsdf};
use footprint::Rgb;
use footprint::bsdf::material::{Material, MaterialKind};
use footprint::bsdf::microfacet::Microfacet;
use footprint::bsdf::principled::{PrincipledParams, SamplingRates, Scalar};
use footprint::bsdf::{Lobes, TransportMode};
use footprint::rng::Rng;
use glam::{Vec2, Vec3};

/// The one-sided material of a parameter set of the script.
pub fn principled_material(set: &PrincipledSet) -> Material {
    let (name, base, s, (index, value), rates) = *set;
    let scalar = |i: usize| Scalar::constant(s[i]);
    let eta = match index {
        "eta" => value,
        "specular" => PrincipledParams::eta_of_specular(value),
        _ => panic!("{name}: index property {index}"),
    };
    Material {
        name: name.to_string(),
        kind: MaterialKind::Principled,
        kd: Rgb::from(base),
        two_sided: false,
        principled: PrincipledParams {
            roughness: scalar(0),
            anisotropic: scalar(1),
            metallic: scalar(2),
            spec_trans: scalar(3),
            spec_tint: scalar(4),
            sheen: scalar(5),
            sheen_tint: scalar(6),
            flatness: scalar(7),
            clearcoat: scalar(8),
            clearcoat_gloss: scalar(9),
            eta,
            rates: SamplingRates {
                diffuse: rates[0],
                specular: rates[1],
                clearcoat: rates[2],
            },
        },
        ..Material::default()
    }
}

/// The material of the script's set `name`.
pub fn mitsuba_principled(name: &str) -> Material {
    let set = MITSUBA_PRINCIPLED_SETS
        .iter()
        .find(|s| s.0 == name)
        .unwrap_or_else(|| panic!("no principled set {name}"));
    principled_material(set)
}

/// `eval` and `pdf` agree with Mitsuba 3's to 1e-3 (relative) for every parameter set: each
/// lobe alone and mixed, anisotropic, smooth (roughness 0.05) and rough (1), with non-default
/// sampling rates; about the main lobe's peaks and in its tails; on both sides and in both
/// modes for the transmitting sets.
#[test]
fn principled_matches_mitsuba_3() {
    let mut worst = (0.0f32, 0.0f32);
    for row in MITSUBA_PRINCIPLED {
        let (f_err, pdf_err) = check_mitsuba_row(&flat_bsdf(&mitsuba_principled(row.0)), row, 1e-3);
        worst = (worst.0.max(f_err), worst.1.max(pdf_err));
    }
    eprintln!(
        "{} rows; largest relative difference: f {:.2e}, pdf {:.2e}",
        MITSUBA_PRINCIPLED.len(),
        worst.0,
        worst.1
    );
}

/// The albedo, the mean sample weight `f cos / pdf`, against Mitsuba's (its own `sample`,
/// 1,000,000 samples per row, printed by the script) from near-normal and grazing incidence,
/// and from inside for the transmitting sets, in both modes: the samples' weights agree with
/// Mitsuba's in expectation (which `eval` and `pdf` agreeing pointwise does not show where a
/// sampler misses part of a lobe).
///
/// Bound: per row and channel a two-sided z-test of the difference of the two means (of
/// 200,000 and 1,000,000 independent samples of bounded weights, so close to normal), error
/// `sqrt(se² + se_mitsuba²)`, at 1% Šidák-corrected over all rows and channels (fixed seed):
/// agreeing samplers fail it with probability 1%.
#[test]
fn principled_albedo_matches_mitsuba_3() {
    let z = normal_quantile(1.0 - 0.5 * sidak(0.01, 3 * MITSUBA_PRINCIPLED_ALBEDO.len()));
    let mut rng = Rng::new(43, 0, 0);
    let n = 200_000;
    let mut worst = 0.0f64;
    for &(name, importance, wo, mean_ref, se_ref) in MITSUBA_PRINCIPLED_ALBEDO {
        let b = flat_bsdf(&mitsuba_principled(name));
        let wo = dir(wo[0], wo[1]);
        let mode = if importance {
            TransportMode::Importance
        } else {
            TransportMode::Radiance
        };
        let weights: Vec<Rgb> = (0..n)
            .map(|_| {
                b.sample(wo, rng.uniform(), rng.uniform2(), mode)
                    .map_or(Rgb::ZERO, |s| s.weight)
            })
            .collect();
        for c in 0..3 {
            let xs: Vec<f64> = weights.iter().map(|w| w[c] as f64).collect();
            let (m, se) = mean_stderr(&xs);
            let (mr, sr) = (mean_ref[c] as f64, se_ref[c] as f64);
            let t = (m - mr).abs() / (se * se + sr * sr).sqrt();
            worst = worst.max(t);
            assert!(
                t <= z,
                "{name} {mode:?} {wo} channel {c}: albedo {m:.5} ± {se:.5}, Mitsuba {mr:.5} ± {sr:.5} (|z| {t:.2} > {z:.2})"
            );
        }
    }
    eprintln!(
        "{} rows: largest |z| {worst:.2} (bound {z:.2})",
        MITSUBA_PRINCIPLED_ALBEDO.len()
    );
}

/// The white furnace where the Disney model conserves energy: all metal with a white base
/// colour (Schlick's Fresnel term of a white `R0` is 1: the GGX lobe's single scattering
/// alone, whose weights `G1(wi)` are at most 1) and white glass in importance mode (`R + T`),
/// smooth to rough, anisotropic too. Elsewhere the model does not conserve energy, in Mitsuba
/// as here: the diffuse lobe is not reduced by the specular lobe's Fresnel term, and its
/// retro-reflection exceeds Lambert's towards grazing angles (Mitsuba's default principled
/// material with a white base colour reflects 1.04 at normal incidence, 1.19 at 87°).
///
/// Bound: a one-sided z-test of each sampled albedo (200,000 samples of weights in [0, 1],
/// so a mean close to normal) against 1 at 1% Šidák-corrected over all cases (fixed seed).
#[test]
fn principled_white_furnace() {
    let white = |roughness: f32, anisotropic: f32, metallic: f32, spec_trans: f32| Material {
        kind: MaterialKind::Principled,
        kd: Rgb::ONE,
        two_sided: false,
        principled: PrincipledParams {
            roughness: Scalar::constant(roughness),
            anisotropic: Scalar::constant(anisotropic),
            metallic: Scalar::constant(metallic),
            spec_trans: Scalar::constant(spec_trans),
            ..PrincipledParams::default()
        },
        ..Material::default()
    };
    let mut cases = Vec::new();
    for (r, a) in [(0.05, 0.0), (0.3, 0.0), (0.7, 0.0), (1.0, 0.0), (0.5, 0.9)] {
        cases.push((
            format!("metal r={r} anisotropic={a}"),
            white(r, a, 1.0, 0.0),
        ));
        cases.push((
            format!("glass r={r} anisotropic={a}"),
            white(r, a, 0.0, 1.0),
        ));
    }
    let thetas = [0.0f32, 45.0, 75.0, 87.0, 150.0];
    let z = normal_quantile(1.0 - sidak(0.01, cases.len() * thetas.len()));
    let mut rng = Rng::new(47, 0, 0);
    let n = 200_000;
    for (name, m) in &cases {
        let b = flat_bsdf(m);
        for theta in thetas {
            let xs: Vec<f64> = (0..n)
                .map(|_| {
                    b.sample(
                        dir(theta, 10.0),
                        rng.uniform(),
                        rng.uniform2(),
                        TransportMode::Importance,
                    )
                    .map_or(0.0, |s| s.weight.max_element() as f64)
                })
                .collect();
            let (a, se) = mean_stderr(&xs);
            eprintln!("{name} θ={theta}: {a:.5} ± {se:.5}");
            assert!(a <= 1.0 + z * se, "{name} θ={theta}: albedo {a} ± {se}");
        }
    }
}

/// A principled BSDF that only transmits (`spec_trans` 1; no metal, tint, sheen or
/// clearcoat) with a white base colour is the rough dielectric of GGX roughness `r²` and
/// white factors: the same `f` on both sides in both modes, and the same density, to f32
/// rounding (2e-4 relative), at pairs drawn from either BSDF.
#[test]
fn principled_glass_is_the_rough_dielectric() {
    let mut rng = Rng::new(53, 0, 0);
    for roughness in [0.1f32, 0.4, 0.8] {
        let mut m = mitsuba_principled("glass");
        m.kd = Rgb::ONE;
        m.principled.roughness = Scalar::constant(roughness);
        let principled = flat_bsdf(&m);
        let glass = flat_bsdf(&rough_glass(
            Microfacet::Ggx,
            roughness * roughness,
            Rgb::ONE,
            Rgb::ONE,
        ));
        let eta = m.principled.eta;
        assert_eq!(eta, ROUGH_GLASS_ETA);
        for k in 0..4000 {
            let wo = dir(180.0 * rng.uniform(), 360.0 * rng.uniform());
            let from = if k % 2 == 0 { &principled } else { &glass };
            let mode = if k % 4 < 2 {
                TransportMode::Radiance
            } else {
                TransportMode::Importance
            };
            let Some(s) = from.sample(wo, rng.uniform(), rng.uniform2(), mode) else {
                continue;
            };
            let close = |a: f32, b: f32| (a - b).abs() <= 2e-4 * a.abs().max(b.abs()) + 1e-12;
            let (fp, fg) = (principled.eval(wo, s.wi, mode), glass.eval(wo, s.wi, mode));
            assert!(
                (0..3).all(|c| close(fp[c], fg[c])),
                "r {roughness} {mode:?} wo {wo} wi {}: f {fp} vs rough dielectric {fg}",
                s.wi
            );
            let (pp, pg) = (principled.pdf(wo, s.wi), glass.pdf(wo, s.wi));
            assert!(
                close(pp, pg),
                "r {roughness} wo {wo} wi {}: pdf {pp} vs rough dielectric {pg}",
                s.wi
            );
        }
    }
}

/// Radiance mode is reciprocal, `f(a, b) = f(b, a)` for the sets that reflect only and
/// `f(a, b) / η_a² = f(b, a) / η_b²` across the surface of those that transmit (Veach 1997,
/// eq. 5.14, `η_x` the index on `x`'s side); importance mode is the adjoint,
/// `f*(wo, wi) = f(wi, wo) |wo·n_s| |wi·n_g| / (|wo·n_g| |wi·n_s|)` (eq. 5.19), flat and
/// under a tilted shading normal. Pairs from the BSDF's own sampling, where its lobes are.
#[test]
fn principled_reciprocity_and_adjoint() {
    let configs = principled_configs();
    let checked = check_adjoint_and_reciprocity(&configs, 59, |c, v| match c.bsdf.lobes {
        Lobes::Principled(p) if p.transmits() && v.dot(c.bsdf.frame.z) < 0.0 => p.eta,
        Lobes::Principled(_) => 1.0,
        _ => panic!("{}: not principled", c.name),
    });
    assert!(checked > configs.len() * 1000, "only {checked} pairs");
}

/// Sidedness, as Mitsuba's: a principled BSDF that reflects only is black from below its
/// shading normal (no value, density or sample) unless wrapped in `twosided`, where it
/// reflects as from above; one that transmits scatters from below whatever the flag.
#[test]
fn principled_sidedness() {
    let back = |v: Vec3| Vec3::new(v.x, v.y, -v.z);
    let (wo, wi) = (dir(40.0, 0.0), dir(45.0, 170.0));
    for name in ["default", "clearcoat", "metallic_anisotropic", "spec_trans"] {
        for two_sided in [false, true] {
            let m = Material {
                two_sided,
                ..mitsuba_principled(name)
            };
            let transmits = m.principled.may_transmit();
            let b = flat_bsdf(&m);
            let front = b.eval(wo, wi, TransportMode::Radiance);
            let from_back = b.eval(back(wo), back(wi), TransportMode::Radiance);
            let pdf_back = b.pdf(back(wo), back(wi));
            let sampled = b
                .sample(back(wo), 0.3, Vec2::new(0.4, 0.6), TransportMode::Radiance)
                .is_some();
            assert!(front.max_element() > 0.0, "{name}: black from the front");
            if transmits {
                assert!(
                    from_back.max_element() > 0.0 && pdf_back > 0.0 && sampled,
                    "{name}"
                );
            } else if two_sided {
                assert_eq!(from_back, front, "{name}: two-sided differs from the back");
                assert_eq!(pdf_back, b.pdf(wo, wi), "{name}");
                assert!(sampled, "{name}");
            } else {
                assert_eq!(
                    from_back,
                    Rgb::ZERO,
                    "{name}: one-sided not black from the back"
                );
                assert_eq!(pdf_back, 0.0, "{name}");
                assert!(!sampled, "{name}: one-sided sampled from the back");
            }
        }
    }
}

/// Guiding by the main lobe's Blinn-equivalent exponent `2/α² - 2` (`α` the roughness
/// squared; `α² = α_u α_v` when anisotropic), never delta; the textured scalars
/// take the lookup's values where textures are looked up, their untextured values elsewhere.
#[test]
fn principled_guides_by_its_main_lobe_and_reads_textures() {
    use footprint::guide::guides_at;
    let lobes = |roughness: f32, anisotropic: f32| {
        let mut m = mitsuba_principled("clearcoat");
        m.principled.roughness = Scalar::constant(roughness);
        m.principled.anisotropic = Scalar::constant(anisotropic);
        flat_bsdf(&m).lobes
    };
    // r 0.6: α 0.36, exponent 2/0.1296 - 2 = 13.43.
    assert!(!lobes(0.6, 0.0).is_delta());
    assert!(guides_at(&lobes(0.6, 0.0), 13.5) && !guides_at(&lobes(0.6, 0.0), 13.4));
    // Anisotropic 0.8: α_u = 0.36 / sqrt(0.28), α_v = 0.36 sqrt(0.28): the product, and so the
    // lobe's solid angle and exponent, stay those of the isotropic lobe.
    assert!(guides_at(&lobes(0.6, 0.8), 13.5) && !guides_at(&lobes(0.6, 0.8), 13.4));
    assert!(!guides_at(&lobes(0.1, 0.0), 100.0));
    let mut m = mitsuba_principled("default");
    m.principled.roughness = Scalar {
        value: 0.5,
        texture: Some(3),
    };
    let at = |lookup: Option<f32>| match Lobes::new_at(&m, m.kd, m.ks, |t| {
        assert_eq!(t, 3);
        lookup
    })
    .lobes
    {
        Lobes::Principled(p) => p.roughness,
        _ => panic!("not principled"),
    };
    assert_eq!(at(Some(0.9)), 0.9);
    assert_eq!(at(None), 0.5);
}

/// The lobes a material resolves to at a hit stay small with the principled ones among them
/// (they are made and copied at every hit; nothing is boxed).
#[test]
fn lobes_stay_small() {
    let size = std::mem::size_of::<Lobes>();
    eprintln!("Lobes: {size} bytes");
    assert!(size <= 80, "Lobes takes {size} bytes");
}
