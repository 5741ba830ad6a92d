//! Path tracing and light tracing estimate the same image: on the Cornell box at 64x64, the
//! mean of every 8x8-pixel region agrees between the two integrators within statistical
//! bounds; through a thin lens, the combined image too.
//!
//! Bound: each integrator renders `R` independent images (different seeds); for every region
//! and channel the difference of the two means is compared with its standard error
//! `sqrt(s_pt²/R + s_lt²/R)` estimated from the spread of the replicates. The critical value
//! is Student's t with `R - 1` degrees of freedom (conservative for Welch's test) at
//! significance 0.01, Šidák-corrected over all region x channel tests.

mod common;

use common::{scene_path, sidak, t_critical};
use footprint::scene::Scene;
use footprint::scene::load::load_scene;
use footprint_integrators::{Method, RenderOptions, render};

/// `renders` independent images of `scene` by `integrator` (unguided), `spp` samples each,
/// seeds from `seed`: the means of their `side` x `side` regions.
fn replicates(
    scene: &Scene,
    integrator: &str,
    (renders, spp, max_depth, seed): (usize, u32, u32, u64),
    side: u32,
) -> Vec<Vec<[f64; 3]>> {
    (0..renders)
        .map(|r| {
            let opts = RenderOptions {
                method: Method::from_names(integrator, "bsdf").unwrap(),
                spp,
                time: None,
                max_depth,
                seed: seed + r as u64,
                ..Default::default()
            };
            let out = render(scene, &opts, |_| {});
            assert!(out.image.all_valid());
            common::region_means(&out.image, side)
        })
        .collect()
}

/// Welch's |t| of every region and channel between two sets of replicates, with the
/// failures above `crit` described; and the largest |t|.
fn disagreements(
    a: &[Vec<[f64; 3]>],
    b: &[Vec<[f64; 3]>],
    crit: f64,
    names: (&str, &str),
) -> (Vec<String>, f64) {
    let stats = |reps: &[Vec<[f64; 3]>], i: usize, c: usize| {
        let xs: Vec<f64> = reps.iter().map(|r| r[i][c]).collect();
        common::mean_stderr(&xs)
    };
    let mut worst = 0.0f64;
    let mut failures = Vec::new();
    for i in 0..a[0].len() {
        for c in 0..3 {
            let (ma, sa) = stats(a, i, c);
            let (mb, sb) = stats(b, i, c);
            let t = (ma - mb).abs() / (sa * sa + sb * sb).sqrt().max(1e-12);
            worst = worst.max(t);
            if t > crit {
                failures.push(format!(
                    "{} vs {}: region {i} channel {c}: {ma:.4} ± {sa:.4} vs {mb:.4} ± {sb:.4}, |t| = {t:.2}",
                    names.0, names.1
                ));
            }
        }
    }
    (failures, worst)
}

#[test]
fn path_tracer_and_light_tracer_agree_on_cornell() {
    let mut scene = load_scene(&scene_path("cornell")).expect("cornell loads");
    scene.camera = scene.camera.with_resolution(64, 64).unwrap();
    let renders = 40;
    let block = 8;
    let regions = (64 / block) * (64 / block);
    let crit = t_critical(sidak(0.01, regions as usize * 3), (renders - 1) as f64);
    let pt = replicates(&scene, "pt", (renders, 8, 6, 7), 64 / block);
    let lt = replicates(&scene, "lt", (renders, 8, 6, 7), 64 / block);
    let (failures, worst) = disagreements(&pt, &lt, crit, ("pt", "lt"));
    eprintln!("largest |t| = {worst:.2}, critical {crit:.2}");
    assert!(
        failures.is_empty(),
        "regions disagree (critical |t| {crit:.2}):\n{}",
        failures.join("\n")
    );
}

/// Path tracing, light tracing and the combined image agree through a thin lens
/// (`scenes/thinlens`, Mitsuba's `thinlens` sensor, at 32x32): every 8x8-pixel region's
/// mean, pairwise, within the bound above (20 replicates of 8 spp each, Šidák-corrected over
/// the three pairs' region x channel tests). The camera paths start on the lens, the light
/// paths' connections sample it, and the combined image weighs both by densities per unit
/// lens area.
#[test]
fn path_tracing_light_tracing_and_the_combined_image_agree_through_a_thin_lens() {
    let xml = common::scenes_dir().join("thinlens").join("scene.xml");
    let mut scene = footprint::scene::mitsuba::load(&xml, &Default::default()).unwrap();
    assert!(scene.camera.has_lens());
    scene.camera = scene.camera.with_resolution(32, 32).unwrap();
    let (renders, block) = (20, 8);
    let regions = (32 / block) * (32 / block);
    let crit = t_critical(sidak(0.01, 3 * regions as usize * 3), (renders - 1) as f64);
    let images = ["pt", "lt", "combined"].map(|name| {
        (
            name,
            replicates(&scene, name, (renders, 8, 3, 300), 32 / block),
        )
    });
    let mut failures = Vec::new();
    for (a, b) in [(0, 1), (0, 2), (1, 2)] {
        let names = (images[a].0, images[b].0);
        let (f, worst) = disagreements(&images[a].1, &images[b].1, crit, names);
        eprintln!(
            "{} vs {}: largest |t| = {worst:.2}, critical {crit:.2}",
            names.0, names.1
        );
        failures.extend(f);
    }
    assert!(
        failures.is_empty(),
        "regions disagree:\n{}",
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
