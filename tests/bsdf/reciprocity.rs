//! Transport modes: reciprocity in radiance mode, and importance mode as the adjoint under
//! shading normals; the check of both on pairs a BSDF samples, across the surface too
//! ([`check_adjoint_and_reciprocity`]).

use crate::configs::{Config, configs};
use crate::dir;
use footprint::Rgb;
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use footprint::rng::Rng;
use footprint::sampling::sample_uniform_sphere;
use glam::Vec3;

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

/// `f*(wo, wi) = f(wi, wo) |wo·n_s| |wi·n_g| / (|wo·n_g| |wi·n_s|)` (Veach 1997, eq. 5.19) for
/// every configuration, flat or under a tilted shading normal, and on the flat ones radiance
/// reciprocal in the generalised sense `f(a, b) / η_a² = f(b, a) / η_b²` (eq. 5.14), `η_x`
/// = `index(config, x)` the index on `x`'s side; on 2000 pairs per configuration that it
/// samples itself (so that they lie where narrow lobes are non-zero), to 2e-3. Returns how
/// many pairs were checked.
pub fn check_adjoint_and_reciprocity(
    configs: &[Config],
    seed: u64,
    index: impl Fn(&Config, Vec3) -> f32,
) -> usize {
    let mut rng = Rng::new(seed, 0, 0);
    let mut checked = 0;
    for c in configs {
        let flat = c.bsdf.frame.z == c.bsdf.ng;
        for _ in 0..2000 {
            let wo = c.wo;
            let Some(s) = c.bsdf.sample(wo, rng.uniform(), rng.uniform2(), c.mode) else {
                continue;
            };
            let wi = s.wi;
            let fi = c.bsdf.eval(wo, wi, TransportMode::Importance);
            let fr_back = c.bsdf.eval(wi, wo, TransportMode::Radiance);
            let (ns, ng) = (c.bsdf.frame.z, c.bsdf.ng);
            let corr = wo.dot(ns).abs() * wi.dot(ng).abs() / (wo.dot(ng).abs() * wi.dot(ns).abs());
            let expect = fr_back * corr;
            let tol = 2e-3 * expect.max_element().max(fi.max_element()) + 1e-7;
            assert!(
                (fi - expect).abs().max_element() <= tol,
                "{}: f*(wo, wi) {fi} != f(wi, wo) · correction {expect} (wo {wo}, wi {wi})",
                c.name
            );
            if flat {
                let fr = c.bsdf.eval(wo, wi, TransportMode::Radiance);
                let (eta_o, eta_i) = (index(c, wo), index(c, wi));
                let a = fr / (eta_o * eta_o);
                let b = fr_back / (eta_i * eta_i);
                assert!(
                    (a - b).abs().max_element() <= 2e-3 * a.max_element().max(b.max_element()),
                    "{}: f(wo, wi)/η_o² {a} != f(wi, wo)/η_i² {b}",
                    c.name
                );
            }
            checked += 1;
        }
    }
    checked
}
