//! Mitsuba 3's `bumpmap` (`footprint::bsdf::bump`): the BSDF against Mitsuba 3's own values at
//! points of `scenes/bumpmap` (printed by scripts/mitsuba_bumpmap_values.py), sampling
//! against the density (chi-square) and the sample weight against `f cos / pdf` under a
//! diffuse and a rough conductor, a constant height field that leaves the BSDF exactly as it
//! was, a linear ramp that tilts the normal by its analytic angle, and the importer's errors.
//! The scene's image against Mitsuba's is in tests/mitsuba.rs (`bumpmap_matches_mitsuba`).

mod common;

use common::chi2::ChiSquareTest;
use common::sidak;
use footprint::Rgb;
use footprint::bsdf::bump::{Bump, BumpMap};
use footprint::bsdf::material::{Material, MaterialKind};
use footprint::bsdf::microfacet::Microfacet;
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use footprint::scene::Scene;
use footprint::scene::mitsuba::{self, ImportOptions};
use glam::Vec3;
use std::path::{Path, PathBuf};

include!("bumpmap_values.rs");

fn scene_xml() -> PathBuf {
    common::scenes_dir().join("bumpmap").join("scene.xml")
}

fn load(path: &Path) -> Scene {
    mitsuba::load(path, &ImportOptions::default()).expect("the scene imports")
}

/// Relative agreement of `a` with `b` within `rel`, or both under `abs`.
fn close(a: f32, b: f32, rel: f32, abs: f32) -> bool {
    (a - b).abs() <= rel * b.abs().max(a.abs()) || (a - b).abs() <= abs
}

/// At every point and direction Mitsuba's `eval` (cosine included) and `pdf`, in both modes:
/// footprint's `f · |wi·n_s|` (the integrators' product) and its density. The tolerance is
/// float rounding (Mitsuba's frames and footprint's are built in other orders).
#[test]
fn matches_mitsuba_3_pointwise() {
    let scene = load(&scene_xml());
    let mut checked = 0;
    for &(o, t, wi, rad, imp, pdf) in MITSUBA_POINTS {
        let (o, t, wi) = (Vec3::from(o), Vec3::from(t), Vec3::from(wi));
        let dir = (t - o).normalize();
        let hit = scene
            .intersect(o, dir, f32::INFINITY)
            .expect("the ray hits");
        let bsdf = scene.bsdf(&hit);
        let wo = -dir;
        let cos = wi.dot(hit.ns).abs();
        for (mode, want) in [
            (TransportMode::Radiance, rad),
            (TransportMode::Importance, imp),
        ] {
            // Mitsuba's BSDF carries no adjoint correction (its ptracer applies it): take it
            // out of footprint's, which the flat planes make 1 anyway.
            let got = bsdf.eval(wo, wi, mode) * cos;
            let want = Rgb::from(want);
            for c in 0..3 {
                assert!(
                    close(got[c], want[c], 2e-3, 1e-6),
                    "{mode:?} eval at {t} from {o}, wi {wi}: footprint {got}, Mitsuba {want}"
                );
            }
        }
        let got = bsdf.pdf(wo, wi);
        assert!(
            close(got, pdf, 2e-3, 1e-6),
            "pdf at {t} from {o}, wi {wi}: footprint {got}, Mitsuba {pdf}"
        );
        checked += 1;
    }
    assert!(checked >= 90, "{checked} points");
}

/// A BSDF of `kind` on the plane `z = 0` (shading normal +z) bumped to the normal of tilt
/// `tilt_deg` toward +x (azimuth `phi_deg`), nested two-sided or not.
fn bumped(kind: MaterialKind, tilt_deg: f32, phi_deg: f32, nested_two_sided: bool) -> Bsdf {
    let m = Material {
        kind,
        kd: Rgb::new(0.7, 0.5, 0.3),
        ks: Rgb::ONE,
        eta: Rgb::new(0.2, 0.92, 1.1),
        k: Rgb::new(3.9, 2.45, 2.14),
        alpha: 0.3,
        microfacet: Microfacet::Ggx,
        two_sided: false,
        ..Material::default()
    }
    .prepared();
    let mut bsdf = Bsdf::new(Lobes::new(&m, m.kd, m.ks), Vec3::Z, Vec3::Z);
    let map = BumpMap {
        texture: 0,
        scale: 1.0,
        flip_invalid_normals: true,
        shadowing: true,
        nested_two_sided,
    };
    let (t, p) = (tilt_deg.to_radians(), phi_deg.to_radians());
    let n = Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
    bsdf.bump = Some(Bump::new(&map, &bsdf.frame, n));
    bsdf
}

fn unit(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// The bumped configurations the sampling tests run: (name, BSDF, wo). `wo` at 70° toward -x
/// lies below a normal tilted 30° toward -x... and is flipped; the others are not.
fn configs() -> Vec<(String, Bsdf, Vec3)> {
    let mut out = Vec::new();
    for (kind, name) in [
        (MaterialKind::Diffuse, "diffuse"),
        (MaterialKind::RoughConductor, "roughconductor"),
    ] {
        for (tilt, phi, two) in [
            (25.0, 0.0, false),
            (50.0, 120.0, true),
            (35.0, 180.0, false),
        ] {
            for wo in [unit(20.0, 10.0), unit(70.0, 0.0), unit(85.0, 200.0)] {
                out.push((
                    format!("{name} tilt {tilt} phi {phi} nested two-sided {two}, wo {wo}"),
                    bumped(kind, tilt, phi, two),
                    wo,
                ));
            }
        }
    }
    out
}

/// Sampling draws directions with the density `pdf` reports (chi-square over the sphere,
/// Šidák-corrected over the configurations).
#[test]
fn sampling_matches_pdf_chi_square() {
    let configs = configs();
    let alpha = sidak(0.01, configs.len());
    for (name, bsdf, wo) in &configs {
        let test = ChiSquareTest::sphere(300_000);
        let r = test.run(
            |rng| {
                bsdf.sample(*wo, rng.uniform(), rng.uniform2(), TransportMode::Radiance)
                    .map(|s| s.wi)
            },
            |wi| bsdf.pdf(*wo, wi) as f64,
        );
        eprintln!(
            "{name}: chi2 {:.1} dof {} p {:.3e} integral {:.4}",
            r.chi2, r.dof, r.p_value, r.integral
        );
        assert!(r.p_value > alpha, "{name}: p = {:.3e}", r.p_value);
    }
}

/// Every sample reports the density and `f` that `pdf` and `eval` give for its direction, and
/// its weight is `f |wi·n_s| / pdf` (radiance and importance mode); the weights' mean is the
/// albedo, which the terminator's shadowing keeps at most 1.
#[test]
fn sample_weight_is_eval_cos_over_pdf() {
    for (name, bsdf, wo) in configs() {
        for mode in [TransportMode::Radiance, TransportMode::Importance] {
            let mut rng = footprint::rng::Rng::new(5, 0xB0, 0);
            let (mut sum, n) = (Rgb::ZERO, 20_000);
            for _ in 0..n {
                let Some(s) = bsdf.sample(wo, rng.uniform(), rng.uniform2(), mode) else {
                    continue;
                };
                let f = bsdf.eval(wo, s.wi, mode);
                let pdf = bsdf.pdf(wo, s.wi);
                let want = f * (s.wi.dot(Vec3::Z).abs() / pdf);
                assert!(
                    close(s.pdf_w, pdf, 1e-5, 0.0)
                        && (s.f - f).abs().max_element() <= 1e-5 * f.max_element(),
                    "{name}: sample reports pdf {} f {}, eval gives {pdf} {f}",
                    s.pdf_w,
                    s.f
                );
                assert!(
                    (s.weight - want).abs().max_element() <= 1e-4 * want.max_element(),
                    "{name} {mode:?}: weight {} against f cos / pdf {want}",
                    s.weight
                );
                sum += s.weight;
            }
            let albedo = sum / n as f32;
            assert!(albedo.max_element() <= 1.02, "{name}: albedo {albedo}");
        }
    }
}
