//! Path tracing and light tracing estimate the same image: on the Cornell box at 64x64, the
//! mean of every 8x8-pixel region agrees between the two integrators within statistical
//! bounds.
//!
//! Bound: each integrator renders `R` independent images (different seeds); for every region
//! and channel the difference of the two means is compared with its standard error
//! `sqrt(s_pt²/R + s_lt²/R)` estimated from the spread of the replicates. The critical value
//! is Student's t with `R - 1` degrees of freedom (conservative for Welch's test) at
//! significance 0.01, Šidák-corrected over all region x channel tests.

mod common;

use common::{scene_path, sidak, t_critical};
use footprint::scene::load::load_scene;
use footprint_integrators::{Method, RenderOptions, render};

#[test]
fn path_tracer_and_light_tracer_agree_on_cornell() {
    let mut scene = load_scene(&scene_path("cornell")).expect("cornell loads");
    scene.camera = scene.camera.with_resolution(64, 64).unwrap();
    let renders = 40;
    let block = 8;
    let regions = (64 / block) * (64 / block);
    let crit = t_critical(sidak(0.01, regions as usize * 3), (renders - 1) as f64);
    let replicate = |integrator: &str| -> Vec<Vec<[f64; 3]>> {
        (0..renders)
            .map(|r| {
                let opts = RenderOptions {
                    method: Method::from_names(integrator, "bsdf").unwrap(),
                    spp: 8,
                    time: None,
                    max_depth: 6,
                    seed: 7 + r as u64,
                    ..Default::default()
                };
                let out = render(&scene, &opts, |_| {});
                assert!(out.image.all_valid());
                common::region_means(&out.image, 64 / block)
            })
            .collect()
    };
    let pt = replicate("pt");
    let lt = replicate("lt");
    let stats = |reps: &Vec<Vec<[f64; 3]>>, i: usize, c: usize| {
        let xs: Vec<f64> = reps.iter().map(|r| r[i][c]).collect();
        common::mean_stderr(&xs)
    };
    let mut worst = 0.0f64;
    let mut failures = Vec::new();
    for i in 0..regions as usize {
        for c in 0..3 {
            let (mp, sp) = stats(&pt, i, c);
            let (ml, sl) = stats(&lt, i, c);
            let se = (sp * sp + sl * sl).sqrt();
            let z = (mp - ml).abs() / se.max(1e-12);
            worst = worst.max(z);
            if z > crit {
                failures.push(format!("region {i} channel {c}: pt {mp:.4} ± {sp:.4}, lt {ml:.4} ± {sl:.4}, |t| = {z:.2}"));
            }
        }
    }
    eprintln!("largest |t| = {worst:.2}, critical {crit:.2}");
    assert!(
        failures.is_empty(),
        "regions disagree (critical |t| {crit:.2}):\n{}",
        failures.join("\n")
    );
}

/// The statistics helpers every statistical test relies on (in `common`), against known values.
#[test]
fn statistics_helpers_are_right() {
    // Known values: z_{0.975} = 1.959964, t_{0.975, 30} = 2.042272, P(chi2_10 >= 18.307) = 0.05.
    assert!((common::normal_quantile(0.975) - 1.959964).abs() < 1e-5);
    assert!((common::t_critical(0.05, 30.0) - 2.042272).abs() < 2e-3);
    assert!((common::chi2_sf(18.307038, 10.0) - 0.05).abs() < 1e-5);
    assert!((common::chi2_sf(3.0, 200.0) - 1.0).abs() < 1e-9);
    assert!((common::sidak(0.01, 1) - 0.01).abs() < 1e-12);
}
