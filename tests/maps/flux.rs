//! Flux conservation of the particle passes, unguided and guided by the other pass's map.

use crate::common::{mean_stderr, scene_path, sidak, t_critical};
use crate::pass_settings;
use footprint::Rgb;
use footprint::guide::particle_map::ParticleInput;
use footprint::guide::sampler::GuidedSampler;
use footprint::scene::Scene;
use footprint::scene::load::load_scene;
use footprint::settings::GuideParams;
use footprint_integrators::Method;
use footprint_integrators::maps::Guidance;
use footprint_integrators::passes::{PassOutput, light_pass, view_pass};
use glam::DVec3;

/// The diffuse albedo of the surface a particle lies on, found by a ray down its normal.
fn albedo_at(scene: &Scene, p: &ParticleInput) -> Rgb {
    let o = p.position + p.normal * 1e-3;
    let h = scene
        .intersect(o, -p.normal, 1e-2)
        .unwrap_or_else(|| panic!("no surface under the particle at {}", p.position));
    scene.materials[h.material as usize].kd
}

/// What a pass carried, summed in double precision (10^5 single-precision additions drift
/// by ~1e-3): the weights stored at first and second hits, the first hits' weights times
/// their surface's albedo, what escaped at once and after the first bounce, and what was
/// emitted.
struct Ledger {
    first: DVec3,
    second: DVec3,
    reflected: DVec3,
    escaped: [DVec3; 2],
    emitted: DVec3,
}

impl Ledger {
    fn of(scene: &Scene, out: &PassOutput) -> Self {
        let sum = |depth: u16, f: &dyn Fn(&ParticleInput) -> Rgb| {
            out.particles
                .iter()
                .filter(|p| p.depth == depth)
                .fold(DVec3::ZERO, |a, p| a + f(p).as_dvec3())
        };
        let escaped = |i: usize| {
            let e = out.stats.escaped.get(i).copied().unwrap_or_default();
            e.as_dvec3()
        };
        Ledger {
            first: sum(1, &|p| p.weight),
            second: sum(2, &|p| p.weight),
            reflected: sum(1, &|p| p.weight * albedo_at(scene, p)),
            escaped: [escaped(0), escaped(1)],
            emitted: out.stats.emitted.as_dvec3(),
        }
    }
}

/// Flux conservation on cornell (all surfaces diffuse, one light): every photon's first hit
/// is stored with the emitted flux per path, so first-hit flux plus the flux escaping
/// straight out of the open front equals the emitted power; and the flux stored at second
/// hits plus what escapes after the first bounce equals the first-hit flux times each hit
/// surface's reflectance share (no Russian roulette before the second hit, and a diffuse
/// bounce's weight is exactly its albedo), up to float rounding.
#[test]
fn light_pass_conserves_flux_on_cornell() {
    let scene = load_scene(&scene_path("cornell")).unwrap();
    let out = light_pass(&scene, &pass_settings(200_000, 5), &GuidedSampler::bsdf());
    let Ledger {
        first,
        second,
        reflected,
        escaped: [escaped0, escaped1],
        emitted,
    } = Ledger::of(&scene, &out);
    eprintln!(
        "emitted {emitted}, first {first}, escaped {escaped0}; reflected {reflected}, second {second}, escaped {escaped1}"
    );
    let rel = |a: DVec3, b: DVec3| ((a - b).abs() / b.max(DVec3::splat(1e-9))).max_element();
    assert!(rel(first + escaped0, emitted) < 1e-3, "first hits");
    assert!(
        escaped0.max_element() > 0.0 && escaped1.max_element() > 0.0,
        "cornell's open front lets some flux out"
    );
    assert!(rel(second + escaped1, reflected) < 1e-3, "second hits");
}

/// cornell with 40,000 photons and importons, and the maps of an unguided round of the
/// combined method on it (default guide settings), for guiding the passes of the next round.
fn first_round() -> (Scene, Guidance, Method, GuideParams) {
    let mut scene = load_scene(&scene_path("cornell")).unwrap();
    scene.maps.photons = 40_000;
    scene.maps.importons = 40_000;
    let method = Method::parse("combined-footprint").unwrap();
    let params = GuideParams::default();
    let g = Guidance::build(&scene, &method, &params, &pass_settings(0, 77), &|| None);
    (scene, g, method, params)
}

/// A light pass guided by an importance map (the maps refining each other) still conserves
/// flux, now in expectation: every guided direction weighs its photon by `f cos / pdf`, so
/// per batch the first hits plus the flux escaping at once equal the emitted power, and the
/// second hits plus the second escape equal the first hits times their albedo, up to noise.
/// t-tests on 16 batch values against the exact laws (Student's quantile at 0.01, Šidák over
/// 2 laws x 3 channels).
#[test]
fn a_guided_light_pass_conserves_flux_in_expectation() {
    let (scene, g, method, params) = first_round();
    let sampler = g.light_sampler(&scene, &method, &params);
    let batches = 16;
    let (mut first_law, mut second_law) = (vec![Vec::new(); 3], vec![Vec::new(); 3]);
    let mut guided = 0;
    for b in 0..batches {
        let out = light_pass(&scene, &pass_settings(20_000, 300 + b), &sampler);
        guided += out.stats.guided_events - out.stats.fallbacks;
        let l = Ledger::of(&scene, &out);
        for c in 0..3 {
            // Relative deviations from the laws, one value per batch.
            first_law[c].push((l.first[c] + l.escaped[0][c]) / l.emitted[c] - 1.0);
            second_law[c].push((l.second[c] + l.escaped[1][c]) / l.reflected[c] - 1.0);
        }
    }
    assert!(
        guided > 100_000,
        "the light pass was hardly guided ({guided} events)"
    );
    let crit = t_critical(sidak(0.01, 6), (batches - 1) as f64);
    for (law, devs) in [("first hits", &first_law), ("second hits", &second_law)] {
        for (c, d) in devs.iter().enumerate() {
            let (m, se) = mean_stderr(d);
            let t = m.abs() / se.max(1e-12);
            eprintln!("{law}, channel {c}: relative deviation {m:.5} ± {se:.5} (|t| {t:.2})");
            assert!(t <= crit, "{law}, channel {c}: {m} ± {se}");
        }
    }
}

/// A view pass guided by a photon map still carries the camera's importance: its first hits
/// are not guided (they leave the camera), and after the first guided bounce the importance
/// reaching the second hits plus what escapes equals the first hits' importance times their
/// albedo in expectation (t-tests on 16 batch values against 0, Student's quantile at 0.01,
/// Šidák over the channels).
#[test]
fn a_guided_view_pass_keeps_the_cameras_importance() {
    let (scene, g, method, params) = first_round();
    let sampler = g.camera_sampler(&scene, &method, &params);
    let batches = 16;
    let mut law = vec![Vec::new(); 3];
    let mut guided = 0;
    for b in 0..batches {
        let out = view_pass(&scene, &pass_settings(20_000, 400 + b), &sampler);
        guided += out.stats.guided_events - out.stats.fallbacks;
        let l = Ledger::of(&scene, &out);
        for c in 0..3 {
            law[c].push((l.second[c] + l.escaped[1][c]) / l.reflected[c] - 1.0);
        }
    }
    assert!(
        guided > 50_000,
        "the view pass was hardly guided ({guided} events)"
    );
    let crit = t_critical(sidak(0.01, 3), (batches - 1) as f64);
    for (c, d) in law.iter().enumerate() {
        let (m, se) = mean_stderr(d);
        let t = m.abs() / se.max(1e-12);
        eprintln!("importance after the first bounce, channel {c}: {m:.5} ± {se:.5} (|t| {t:.2})");
        assert!(t <= crit, "channel {c}: {m} ± {se}");
    }
}
