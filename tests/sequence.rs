//! The number sequences paths draw (`footprint::rng::Sequence`): Owen-scrambled Sobol points
//! converge to the same image as independent numbers, with less noise per sample.

mod common;

use common::{mean_stderr, scene_path, sidak, t_critical};
use footprint::rng::Sequence;
use footprint::scene::load::load_scene;
use footprint_integrators::{Method, RenderOptions, render};

/// On the bundled Cornell box (32x32, 16 samples per pixel), `R` renders with different
/// seeds per sequence and method:
///
/// * **Same image.** The image means of the two sequences agree per channel: Welch's
///   difference of the means of the `R` image means, against Student's t at 0.01
///   (Šidák-corrected over the 3 channels x 3 methods) times its standard error from the
///   renders' spread. Every render is an independent estimate with either sequence (each
///   seed scrambles every pixel's sequence anew).
/// * **Less noise.** The variance of a pixel over the `R` renders is lower with Sobol in more
///   pixels than equally noisy sequences would allow (a sign test over the pixels, 4 standard
///   deviations of the binomial count; summed variances are dominated by a few pixels at the
///   light's edge, so their ratio is only printed). For the camera-path methods (pt,
///   combined): a light path's slot is not tied to a pixel, so light tracing's pixels gain
///   little (its image mean does) and it is only printed.
#[test]
fn sobol_points_give_the_same_image_with_less_noise() {
    let mut scene = load_scene(&scene_path("cornell")).expect("cornell loads");
    scene.camera = scene.camera.with_resolution(32, 32).unwrap();
    let renders = 12;
    let methods = ["pt-bsdf", "lt-bsdf", "combined-bsdf"];
    let crit = t_critical(sidak(0.01, 3 * methods.len()), (2 * renders - 2) as f64);
    for m in methods {
        // images[sequence][render] = pixel values
        let mut images: Vec<Vec<Vec<[f32; 3]>>> = vec![Vec::new(), Vec::new()];
        for (s, sequence) in [Sequence::Sobol, Sequence::Independent]
            .into_iter()
            .enumerate()
        {
            for r in 0..renders {
                let opts = RenderOptions {
                    method: Method::parse(m).unwrap(),
                    sequence,
                    spp: 16,
                    time: None,
                    seed: 7000 + r as u64,
                    ..Default::default()
                };
                let out = render(&scene, &opts, |_| {});
                assert!(out.image.all_valid() && out.stats.rejected == 0, "{m}");
                images[s].push(out.image.pixels.iter().map(|p| p.to_array()).collect());
            }
        }
        for c in 0..3 {
            let means: Vec<(f64, f64)> = images
                .iter()
                .map(|rs| {
                    let per_render: Vec<f64> = rs
                        .iter()
                        .map(|px| px.iter().map(|p| p[c] as f64).sum::<f64>() / px.len() as f64)
                        .collect();
                    mean_stderr(&per_render)
                })
                .collect();
            let diff = means[0].0 - means[1].0;
            let se = (means[0].1.powi(2) + means[1].1.powi(2)).sqrt();
            eprintln!(
                "{m} channel {c}: Sobol {:.5} ± {:.5}, independent {:.5} ± {:.5}",
                means[0].0, means[0].1, means[1].0, means[1].1
            );
            assert!(
                diff.abs() <= crit * se,
                "{m} channel {c}: Sobol's mean {} and independent's {} differ by more than {}",
                means[0].0,
                means[1].0,
                crit * se
            );
        }
        // Per pixel, the variance over the renders (sum of the channels): a sign test over
        // the pixels, which are independent of each other.
        let variances = |rs: &[Vec<[f32; 3]>]| -> Vec<f64> {
            (0..rs[0].len())
                .map(|i| {
                    let v: Vec<f64> = rs
                        .iter()
                        .map(|px| px[i].iter().sum::<f32>() as f64)
                        .collect();
                    let mean = v.iter().sum::<f64>() / v.len() as f64;
                    v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (v.len() - 1) as f64
                })
                .collect()
        };
        let (vs, vi) = (variances(&images[0]), variances(&images[1]));
        let (mut lower, mut untied) = (0usize, 0usize);
        for (s, i) in vs.iter().zip(&vi) {
            if s != i {
                untied += 1;
                lower += (s < i) as usize;
            }
        }
        let (sum_s, sum_i) = (vs.iter().sum::<f64>(), vi.iter().sum::<f64>());
        // Were both sequences equally noisy, each untied pixel would be lower with Sobol with
        // probability 1/2: the count is Binomial(n, 1/2), mean n/2, standard deviation
        // sqrt(n)/2; the test asks for 4 of those above the mean (one-sided p < 4e-5).
        let bound = untied as f64 / 2.0 + 4.0 * (untied as f64).sqrt() / 2.0;
        eprintln!(
            "{m}: pixel variance lower with Sobol in {lower} of {untied} pixels (bound {bound:.0}); summed variance ratio {:.3}",
            sum_s / sum_i
        );
        // Light paths are not tied to pixels (a pass's slot splats wherever its path lands):
        // their pixels gain little, so the noise test is for the camera-path methods.
        assert!(
            m == "lt-bsdf" || (untied > 100 && lower as f64 > bound),
            "{m}: Sobol's pixel variance is lower in only {lower} of {untied} pixels (needs more than {bound:.0})"
        );
    }
}
