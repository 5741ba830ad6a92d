//! The analytic scene (as pbrt-v4's integrator tests): the camera inside a closed sphere
//! whose inner surface is Lambertian with albedo 0.5 and emits radiance 0.5, so that the
//! radiance is exactly `0.5 / (1 - 0.5) = 1` everywhere, whatever the tessellation. Both
//! integrators must find 1 within a bound derived from their standard error.
//!
//! Bound: each render is an independent estimate of the image; over `R` renders with
//! different seeds, the mean of the image means has a standard error estimated from their
//! spread. The test fails when `|mean - 1|` exceeds the two-sided Student-t critical value at
//! significance 0.01 (Šidák-corrected over the 6 channel x integrator tests) times that
//! standard error, plus the deterministic truncation bias `0.5^max_depth` (below 1e-19 here).

mod common;

use common::{mean_stderr, scene_path, sidak, t_critical};
use footprint::loader::load_scene;
use footprint_integrators::{Integrator, RenderOptions, render};

#[test]
fn furnace_radiance_is_one_for_both_integrators() {
    let scene = load_scene(&scene_path("furnace")).expect("furnace scene loads");
    let renders = 24;
    let tests = 6;
    let crit = t_critical(sidak(0.01, tests), (renders - 1) as f64);
    for integrator in [Integrator::Pt, Integrator::Lt] {
        let mut means = [Vec::new(), Vec::new(), Vec::new()];
        for r in 0..renders {
            let opts = RenderOptions {
                integrator,
                spp: 4,
                time: None,
                max_depth: 64,
                seed: 1000 + r as u64,
                progress: false,
                ..Default::default()
            };
            let out = render(&scene, &opts, |_| {});
            assert!(out.image.all_valid(), "{integrator:?}: invalid pixel");
            assert_eq!(out.stats.rejected, 0);
            let m = out.image.mean();
            for c in 0..3 {
                means[c].push(m[c] as f64);
            }
        }
        for (c, m) in means.iter().enumerate() {
            let (mean, se) = mean_stderr(m);
            let bound = crit * se + 0.5f64.powi(64);
            eprintln!("{integrator:?} channel {c}: mean {mean:.5} ± {se:.5} (bound {bound:.5})");
            assert!(
                se > 0.0 && se < 0.02,
                "{integrator:?}: standard error {se} is implausible"
            );
            assert!(
                (mean - 1.0).abs() <= bound,
                "{integrator:?} channel {c}: mean radiance {mean} differs from 1 by more than {bound}"
            );
        }
    }
}
