//! Transport modes: reciprocity in radiance mode, and importance mode as the adjoint under
//! shading normals.

use crate::configs::configs;
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
