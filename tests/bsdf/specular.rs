//! The delta lobes and Fresnel terms: the mirror, the smooth dielectric, the thin sheet and
//! the conductor Fresnel equations.

use crate::{dir, flat_bsdf, material};
use footprint::Rgb;
use footprint::bsdf::material::{Material, MaterialKind};
use footprint::bsdf::{Bsdf, Lobes, TransportMode, fresnel_conductor, fresnel_dielectric};
use footprint::rng::Rng;
use glam::{Vec2, Vec3};

#[test]
fn mirror_reflects_exactly() {
    let b = Bsdf::new(
        Lobes::Mirror {
            r: Rgb::new(0.9, 0.8, 0.7),
        },
        Vec3::Z,
        Vec3::Z,
    );
    let wo = dir(35.0, 60.0);
    let s = b
        .sample(wo, 0.5, Vec2::new(0.3, 0.3), TransportMode::Radiance)
        .unwrap();
    assert!(s.delta);
    assert!((s.wi - Vec3::new(-wo.x, -wo.y, wo.z)).length() < 1e-5);
    assert!((s.weight - Rgb::new(0.9, 0.8, 0.7)).abs().max_element() < 1e-6);
    assert_eq!(b.pdf(wo, s.wi), 0.0);
    assert_eq!(b.eval(wo, s.wi, TransportMode::Radiance), Rgb::ZERO);
}

/// The smooth dielectric reflects with probability F (binomial z-test, 5 standard errors),
/// refracts by Snell's law, scales radiance by 1/η² but not importance, and filters by √Tf at
/// each interface (Tf for a passage in and out).
#[test]
fn glass_fresnel_snell_and_modes() {
    let eta = 1.5;
    let tf = Rgb::new(0.9, 0.5, 0.2);
    let b = Bsdf::new(
        Lobes::Glass {
            eta,
            tf_sqrt: Rgb::new(tf.x.sqrt(), tf.y.sqrt(), tf.z.sqrt()),
        },
        Vec3::Z,
        Vec3::Z,
    );
    let mut rng = Rng::new(13, 0, 0);
    for (theta, entering) in [
        (10.0f32, true),
        (60.0, true),
        (85.0, true),
        (20.0, false),
        (40.0, false),
    ] {
        let wo = if entering {
            dir(theta, 30.0)
        } else {
            -dir(theta, 30.0)
        };
        let eta_rel = if entering { eta } else { 1.0 / eta };
        let f = fresnel_dielectric(wo.z.abs(), eta_rel) as f64;
        let n = 200_000;
        let mut reflected = 0usize;
        for _ in 0..n {
            let s = b
                .sample(wo, rng.uniform(), rng.uniform2(), TransportMode::Radiance)
                .unwrap();
            if s.wi.z * wo.z > 0.0 {
                reflected += 1;
            } else {
                // Snell: η_i sin θ_i = η_t sin θ_t.
                let sin_i = (1.0 - wo.z * wo.z).sqrt();
                let sin_t = (1.0 - s.wi.z * s.wi.z).sqrt();
                assert!((sin_i - eta_rel * sin_t).abs() < 1e-4, "Snell's law");
                let expect = Rgb::new(tf.x.sqrt(), tf.y.sqrt(), tf.z.sqrt()) / (eta_rel * eta_rel);
                assert!(
                    (s.weight - expect).abs().max_element() < 1e-5,
                    "radiance weight {} vs {expect}",
                    s.weight
                );
                let si = b
                    .sample(wo, 0.999_999, rng.uniform2(), TransportMode::Importance)
                    .unwrap();
                if si.wi.z * wo.z < 0.0 {
                    let expect = Rgb::new(tf.x.sqrt(), tf.y.sqrt(), tf.z.sqrt());
                    assert!(
                        (si.weight - expect).abs().max_element() < 1e-5,
                        "importance weight"
                    );
                }
            }
        }
        let p = reflected as f64 / n as f64;
        let se = (f * (1.0 - f) / n as f64).sqrt().max(1e-9);
        assert!(
            (p - f).abs() <= 5.0 * se,
            "theta {theta} entering {entering}: reflected {p} vs Fresnel {f}"
        );
    }
    // Total internal reflection beyond the critical angle.
    let wo = -dir(60.0, 0.0);
    assert!((fresnel_dielectric(wo.z.abs(), 1.0 / eta) - 1.0).abs() < 1e-6);
}

/// Where the shading normal is tilted from the geometric one (a smooth mesh near its
/// silhouette), the smooth dielectric reads the side in the shading frame, as Mitsuba 3's
/// `dielectric` does (`cos θ_i = wo·n_s`), and keeps the direction that frame gives even where
/// it lies across the geometric plane from where reflection or refraction would put it. Here
/// `wo` is above the geometric normal (+z) but below the shading normal, tilted 60° toward +y:
/// the path arrives from inside. At `wo·n_s = -0.56` that is total internal reflection (weight
/// 1, about `n_s`, and the reflected direction goes through the geometric plane); at
/// `wo·n_s = -0.84` it refracts out to the shading normal's side by Snell's law with η = 1/1.5,
/// radiance scaled by 1.5². The winding's side would have refused both (`wo·n_s < 0`).
#[test]
fn glass_reads_its_side_in_the_shading_frame() {
    let eta = 1.5f32;
    let ns = Vec3::new(0.0, 60f32.to_radians().sin(), 60f32.to_radians().cos());
    let b = Bsdf::new(
        Lobes::Glass {
            eta,
            tf_sqrt: Rgb::ONE,
        },
        ns,
        Vec3::Z,
    );
    let mode = TransportMode::Radiance;
    // Total internal reflection.
    let wo = Vec3::new(0.0, -0.9, 0.436).normalize();
    assert!(wo.z > 0.0 && wo.dot(ns) < -0.5);
    assert_eq!(fresnel_dielectric(-wo.dot(ns), 1.0 / eta), 1.0);
    for u_lobe in [0.0, 0.5, 0.999_999] {
        let s = b
            .sample(wo, u_lobe, Vec2::splat(0.5), mode)
            .expect("glass refused a direction below its shading normal");
        let mirror = -wo + 2.0 * wo.dot(ns) * ns;
        assert!((s.wi - mirror).length() < 1e-5, "reflected about n_s");
        assert!(s.wi.z < 0.0, "the reflection crosses the geometric plane");
        assert!((s.weight - Rgb::ONE).abs().max_element() < 1e-5);
    }
    // Refraction out of the glass.
    let wo = Vec3::new(0.0, -1.0, 0.05).normalize();
    let cos_i = -wo.dot(ns);
    assert!(wo.z > 0.0 && cos_i > 0.8);
    let fr = fresnel_dielectric(cos_i, 1.0 / eta);
    assert!(fr < 1.0);
    let s = b.sample(wo, 0.999_999, Vec2::splat(0.5), mode).unwrap();
    let cos_t = s.wi.dot(ns);
    assert!(cos_t > 0.0, "refracted to the shading normal's side");
    let sin_i = (1.0 - cos_i * cos_i).sqrt();
    let sin_t = (1.0 - cos_t * cos_t).sqrt();
    assert!(
        (sin_i - sin_t / eta).abs() < 1e-4,
        "Snell's law, leaving the glass"
    );
    assert!((s.pdf_w - (1.0 - fr)).abs() < 1e-6);
    assert!((s.weight - Rgb::splat(eta * eta)).abs().max_element() < 1e-4);
}

/// The thin sheet reflects `R' = R + T²R/(1 - R²)` with `R` the Fresnel reflectance of one
/// interface and transmits straight through (`wi = -wo`) the rest: `R' + T' = 1` exactly,
/// the weights are `ks` and `tf`, no `1/η²` in either mode, on both sides.
#[test]
fn thin_glass_reflects_and_transmits_everything() {
    let (ks, tf) = (Rgb::new(0.9, 0.7, 0.5), Rgb::new(0.3, 0.6, 0.8));
    for two_sided in [true, false] {
        let m = Material {
            ni: 1.5,
            ks,
            tf,
            two_sided,
            ..material(MaterialKind::ThinGlass)
        };
        let b = flat_bsdf(&m);
        assert!(b.is_delta());
        for theta in [0.0f32, 30.0, 60.0, 85.0, 89.9] {
            for below in [false, true] {
                let mut wo = dir(theta, 40.0);
                if below {
                    wo.z = -wo.z;
                }
                let r1 = fresnel_dielectric(wo.z.abs(), 1.5);
                let expect_r = r1 + (1.0 - r1) * (1.0 - r1) * r1 / (1.0 - r1 * r1);
                for mode in [TransportMode::Radiance, TransportMode::Importance] {
                    let r = b.sample(wo, 0.0, Vec2::splat(0.5), mode).unwrap();
                    let t = b.sample(wo, 0.999_999_9, Vec2::splat(0.5), mode).unwrap();
                    assert!(r.delta && t.delta);
                    assert_eq!(r.pdf_w + t.pdf_w, 1.0, "θ {theta}: R + T");
                    assert!(
                        (r.pdf_w - expect_r).abs() < 1e-6,
                        "θ {theta}: R {}",
                        r.pdf_w
                    );
                    assert!((r.wi - Vec3::new(-wo.x, -wo.y, wo.z)).length() < 1e-5);
                    assert!((t.wi + wo).length() < 1e-6, "straight through");
                    assert!((r.weight - ks).abs().max_element() < 1e-6);
                    assert!((t.weight - tf).abs().max_element() < 1e-6);
                }
                assert_eq!(b.eval(wo, -wo, TransportMode::Radiance), Rgb::ZERO);
                assert_eq!(b.pdf(wo, -wo), 0.0);
            }
        }
    }
}

/// `Re |z|²` helpers for the complex Fresnel equations written out independently.
fn fresnel_conductor_reference(cos_i: f64, eta: f64, k: f64) -> f64 {
    // Complex arithmetic on (re, im) pairs.
    let mul = |a: (f64, f64), b: (f64, f64)| (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
    let div = |a: (f64, f64), b: (f64, f64)| {
        let d = b.0 * b.0 + b.1 * b.1;
        ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
    };
    let sqrt = |a: (f64, f64)| {
        let r = (a.0 * a.0 + a.1 * a.1).sqrt();
        let re = ((r + a.0) / 2.0).sqrt();
        let im = ((r - a.0) / 2.0).sqrt().copysign(a.1);
        (re, im)
    };
    let n = (eta, k);
    let n2 = mul(n, n);
    let sin2 = 1.0 - cos_i * cos_i;
    // n cos θ_t = sqrt(n² - sin²θ_i)
    let n_cos_t = sqrt((n2.0 - sin2, n2.1));
    let c = (cos_i, 0.0);
    let rs = div((c.0 - n_cos_t.0, -n_cos_t.1), (c.0 + n_cos_t.0, n_cos_t.1));
    let n2c = mul(n2, c);
    let rp = div(
        (n2c.0 - n_cos_t.0, n2c.1 - n_cos_t.1),
        (n2c.0 + n_cos_t.0, n2c.1 + n_cos_t.1),
    );
    0.5 * (rs.0 * rs.0 + rs.1 * rs.1 + rp.0 * rp.0 + rp.1 * rp.1)
}

#[test]
fn conductor_fresnel_values() {
    let eta = Rgb::new(0.2, 1.0, 2.5);
    let k = Rgb::new(3.5, 2.0, 0.5);
    // Normal incidence: ((η-1)² + k²) / ((η+1)² + k²).
    let f = fresnel_conductor(1.0, eta, k);
    for c in 0..3 {
        let (n, kk) = (eta[c], k[c]);
        let expect = ((n - 1.0).powi(2) + kk * kk) / ((n + 1.0).powi(2) + kk * kk);
        assert!(
            (f[c] - expect).abs() < 1e-6,
            "normal incidence: {} vs {expect}",
            f[c]
        );
    }
    // By hand: η = 0.2, k = 3.5 at normal incidence, (0.64 + 12.25) / (1.44 + 12.25).
    assert!((f.x - 0.941_563).abs() < 1e-5, "{}", f.x);
    // Oblique angles against the complex Fresnel equations; grazing reflects everything.
    for cos in [0.9f32, 0.6, 0.3, 0.1, 0.01] {
        let f = fresnel_conductor(cos, eta, k);
        for c in 0..3 {
            let expect = fresnel_conductor_reference(cos as f64, eta[c] as f64, k[c] as f64);
            assert!(
                (f[c] as f64 - expect).abs() < 2e-6,
                "cos {cos}: {} vs {expect}",
                f[c]
            );
        }
    }
    assert!(
        (fresnel_conductor(0.0, eta, k) - Rgb::ONE)
            .abs()
            .max_element()
            < 1e-6
    );
    // Mitsuba's `material="none"` is η = 0, k = 1: |r_s| = |r_p| = 1 at every angle.
    for cos in [1.0f32, 0.7, 0.2, 0.0] {
        let f = fresnel_conductor(cos, Rgb::ZERO, Rgb::ONE);
        assert!(
            (f - Rgb::ONE).abs().max_element() < 1e-6,
            "cos {cos}: {f:?}"
        );
    }
    // k = 0 is a dielectric (η > 1: from outside).
    for eta in [1.2f32, 1.5, 2.4] {
        for cos in [1.0f32, 0.8, 0.5, 0.2, 0.05, 0.0] {
            let fc = fresnel_conductor(cos, Rgb::splat(eta), Rgb::ZERO);
            let fd = fresnel_dielectric(cos, eta);
            assert!(
                (fc.x - fd).abs() < 1e-6,
                "η {eta} cos {cos}: {} vs {fd}",
                fc.x
            );
        }
    }
}
