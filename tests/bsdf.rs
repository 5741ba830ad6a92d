//! Every BSDF: sampling matches its pdf (chi-square), `sample` reports the pdf that `pdf`
//! gives, energy conservation (albedo at most 1), reciprocity in radiance mode, and the smooth
//! dielectric's Fresnel split, Snell's law and transport-mode scaling.

mod common;

use common::chi2::ChiSquareTest;
use common::{mean_stderr, sidak};
use footprint::Rgb;
use footprint::bsdf::{Bsdf, Lobes, TransportMode, fresnel_dielectric};
use footprint::rng::Rng;
use footprint::sampling::sample_uniform_sphere;
use glam::{Vec2, Vec3};

fn glossy(kd: f32, ks: f32, n: f32) -> Lobes {
    let (wd, wg) = (kd, ks);
    Lobes::Glossy {
        kd: Rgb::splat(kd),
        ks: Rgb::splat(ks),
        exponent: n,
        p_glossy: if wd + wg > 0.0 { wg / (wd + wg) } else { 0.5 },
    }
}

/// A direction at polar angle `theta_deg` from +z.
fn dir(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

struct Config {
    name: String,
    bsdf: Bsdf,
    wo: Vec3,
    mode: TransportMode,
    /// Cap around the mirror direction for narrow lobes, or the whole sphere.
    cap: Option<f64>,
}

fn configs() -> Vec<Config> {
    let flat = |l: Lobes| Bsdf::new(l, Vec3::Z, Vec3::Z);
    // A shading normal tilted 20 degrees from the geometric one.
    let tilted = |l: Lobes| Bsdf::new(l, dir(20.0, 90.0), Vec3::Z);
    let mut v = Vec::new();
    for (i, wo) in [dir(0.0, 0.0), dir(45.0, 30.0), dir(85.0, 200.0)]
        .into_iter()
        .enumerate()
    {
        v.push(Config {
            name: format!("diffuse wo#{i}"),
            bsdf: flat(Lobes::Diffuse {
                kd: Rgb::splat(0.7),
            }),
            wo,
            mode: TransportMode::Radiance,
            cap: None,
        });
    }
    v.push(Config {
        name: "diffuse below".into(),
        bsdf: flat(Lobes::Diffuse {
            kd: Rgb::splat(0.7),
        }),
        wo: -dir(30.0, 10.0),
        mode: TransportMode::Radiance,
        cap: None,
    });
    for n in [1.0, 10.0, 100.0] {
        for (i, wo) in [dir(10.0, 0.0), dir(60.0, 45.0), dir(88.0, 100.0)]
            .into_iter()
            .enumerate()
        {
            v.push(Config {
                name: format!("glossy n={n} wo#{i}"),
                bsdf: flat(glossy(0.3, 0.6, n)),
                wo,
                mode: TransportMode::Radiance,
                cap: None,
            });
        }
    }
    for n in [1000.0f32, 10000.0] {
        let cap = 6.0 / n.sqrt() as f64;
        for (i, wo) in [dir(5.0, 0.0), dir(50.0, 45.0)].into_iter().enumerate() {
            v.push(Config {
                name: format!("pure glossy n={n} wo#{i}"),
                bsdf: flat(glossy(0.0, 0.9, n)),
                wo,
                mode: TransportMode::Radiance,
                cap: Some(cap),
            });
        }
    }
    v.push(Config {
        name: "glossy n=20 tilted normal, importance".into(),
        bsdf: tilted(glossy(0.4, 0.5, 20.0)),
        wo: dir(40.0, 250.0),
        mode: TransportMode::Importance,
        cap: None,
    });
    v.push(Config {
        name: "diffuse tilted normal, radiance".into(),
        bsdf: tilted(Lobes::Diffuse {
            kd: Rgb::splat(0.5),
        }),
        wo: dir(70.0, 90.0),
        mode: TransportMode::Radiance,
        cap: None,
    });
    v
}

#[test]
fn sampling_matches_pdf_chi_square() {
    let configs = configs();
    let alpha = sidak(0.01, configs.len());
    for c in &configs {
        let test = match c.cap {
            None => ChiSquareTest::sphere(1_000_000),
            Some(theta_max) => {
                let mirror = Vec3::new(-c.wo.x, -c.wo.y, c.wo.z);
                ChiSquareTest {
                    axis: mirror,
                    theta_max,
                    res_theta: 30,
                    res_phi: 40,
                    samples: 1_000_000,
                    integration_res: 6,
                    seed: 3,
                }
            }
        };
        let (bsdf, wo, mode) = (c.bsdf, c.wo, c.mode);
        let r = test.run(
            |rng| {
                bsdf.sample(wo, rng.uniform(), rng.uniform2(), mode)
                    .map(|s| s.wi)
            },
            |wi| bsdf.pdf(wo, wi) as f64,
        );
        eprintln!(
            "{}: chi2 {:.1} dof {} p {:.3e} integral {:.4}",
            c.name, r.chi2, r.dof, r.p_value, r.integral
        );
        assert!(
            r.p_value > alpha,
            "{}: sampling disagrees with pdf (p = {:.3e} < {alpha:.3e})",
            c.name,
            r.p_value
        );
    }
}

#[test]
fn sample_reports_the_pdf_and_weight_of_its_direction() {
    let mut rng = Rng::new(5, 0, 0);
    for c in configs() {
        for _ in 0..20_000 {
            let Some(s) = c.bsdf.sample(c.wo, rng.uniform(), rng.uniform2(), c.mode) else {
                continue;
            };
            let pdf = c.bsdf.pdf(c.wo, s.wi);
            assert!(
                s.pdf_w > 0.0 && s.pdf_w.is_finite(),
                "{}: pdf {}",
                c.name,
                s.pdf_w
            );
            assert!(
                (s.pdf_w - pdf).abs() <= 1e-4 * pdf.max(1e-3),
                "{}: sample pdf {} vs pdf {}",
                c.name,
                s.pdf_w,
                pdf
            );
            let f = c.bsdf.eval(c.wo, s.wi, c.mode);
            let w = f * s.wi.dot(c.bsdf.frame.z).abs() / s.pdf_w;
            assert!(
                (w - s.weight).abs().max_element() <= 1e-3 * w.max_element().max(1e-3),
                "{}: weight",
                c.name
            );
            assert!(s.weight.is_finite() && s.weight.min_element() >= 0.0);
        }
    }
}

/// Albedo `∫ f cos` estimated by sampling: its mean must not exceed 1 by more than 5
/// standard errors (the estimator is unbiased, so a true albedo <= 1 passes with probability
/// above 1 - 3e-7), and for each lobe it must also not exceed the lobe's own reflectance.
#[test]
fn energy_is_conserved() {
    let mut rng = Rng::new(9, 0, 0);
    for c in configs() {
        for theta in [0.0f32, 30.0, 60.0, 80.0, 89.0] {
            let wo = dir(theta, 17.0);
            let xs: Vec<f64> = (0..50_000)
                .map(|_| {
                    c.bsdf
                        .sample(wo, rng.uniform(), rng.uniform2(), TransportMode::Radiance)
                        .map(|s| s.weight.max_element() as f64)
                        .unwrap_or(0.0)
                })
                .collect();
            let (m, se) = mean_stderr(&xs);
            assert!(
                m <= 1.0 + 5.0 * se,
                "{} theta {theta}: albedo {m} ± {se} exceeds 1",
                c.name
            );
        }
    }
    // Pure Blinn lobes of any exponent reflect at most k_s (the normalisation's claim).
    for n in [0.0f32, 1.0, 10.0, 1e3, 1e4] {
        let b = Bsdf::new(glossy(0.0, 1.0, n), Vec3::Z, Vec3::Z);
        for theta in [0.0f32, 45.0, 85.0] {
            let wo = dir(theta, 0.0);
            let xs: Vec<f64> = (0..50_000)
                .map(|_| {
                    b.sample(wo, rng.uniform(), rng.uniform2(), TransportMode::Radiance)
                        .map(|s| s.weight.x as f64)
                        .unwrap_or(0.0)
                })
                .collect();
            let (m, se) = mean_stderr(&xs);
            assert!(m <= 1.0 + 5.0 * se, "blinn n={n} theta {theta}: albedo {m}");
        }
    }
}

#[test]
fn reciprocity_in_radiance_mode() {
    let mut rng = Rng::new(11, 0, 0);
    for c in configs() {
        for _ in 0..2000 {
            let a = sample_uniform_sphere(rng.uniform2());
            let b = sample_uniform_sphere(rng.uniform2());
            let fab = c.bsdf.eval(a, b, TransportMode::Radiance);
            let fba = c.bsdf.eval(b, a, TransportMode::Radiance);
            assert!(
                (fab - fba).abs().max_element() <= 1e-4 * fab.max_element().max(1e-6),
                "{}: f(a,b) {fab} != f(b,a) {fba}",
                c.name
            );
        }
    }
}

#[test]
fn importance_mode_is_the_adjoint_under_shading_normals() {
    // f*(wo, wi) = f(wi, wo) |wo·ns||wi·ng| / (|wo·ng||wi·ns|) ... and the flux it carries,
    // f* |wi·ns|, equals f(wi, wo) |wo·ns| |wi·ng| / |wo·ng| (Veach 1997, eq. 5.19).
    let b = Bsdf::new(
        Lobes::Diffuse {
            kd: Rgb::splat(0.5),
        },
        dir(25.0, 0.0),
        Vec3::Z,
    );
    let mut rng = Rng::new(12, 0, 0);
    for _ in 0..1000 {
        let wo = dir(80.0 * rng.uniform(), 360.0 * rng.uniform());
        let wi = dir(80.0 * rng.uniform(), 360.0 * rng.uniform());
        let fi = b.eval(wo, wi, TransportMode::Importance);
        let fr = b.eval(wi, wo, TransportMode::Radiance);
        let ns = b.frame.z;
        let expect = fr
            * (wo.dot(ns).abs() * wi.dot(Vec3::Z).abs()
                / (wo.dot(Vec3::Z).abs() * wi.dot(ns).abs()));
        assert!((fi - expect).abs().max_element() <= 1e-4 * expect.max_element().max(1e-6));
    }
}

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
