//! The estimator a path tracer forms with each guide is unbiased.

use crate::common::sidak;
use crate::{dir, fixed, guide_particles, params};
use footprint::Rgb;
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use footprint::guide::GuideDistribution;
use footprint::guide::footprint::FootprintDistribution;
use footprint::guide::grid::GridDistribution;
use footprint::guide::sampler::{GuidedSampler, SamplerState, ScatterPoint};
use footprint::math::Frame;
use footprint::rng::Rng;
use footprint::settings::RadiusRule;
use glam::Vec3;

/// The estimator a path tracer forms at a vertex, `f · |cos θ_s| / pdf` over sampled
/// directions, has the mean `∫ f |cos θ_s| dω` whatever the sampler: for a white Lambertian
/// that is its albedo with respect to the shading normal, 1 when the shading normal is the
/// geometric one. Checked for every guide (footprints under both radius rules, footprints
/// rasterised for sampling, the grid) at tiny caps (particles in a cone of 0.01 rad, and the literal rule's caps of about 1e-3
/// sr), grazing particles and tilted shading normals. A sample whose pdf misses its own cap
/// (the f32 round trip at a cap's rim) would weigh 1e4 to 1e6 times too much and move the
/// mean by far more than the bound. Tilted normals: the reference is BSDF sampling's
/// estimate (independent streams). Bound: Welch's t against Student's quantile at 0.01,
/// Šidák-corrected over every particle set x tilt x guide, from the estimators' standard errors
/// (the guided weights are bounded by `1 / p_BSDF` times the BSDF's, so the variance is
/// finite).
#[test]
fn guided_samplers_estimate_the_albedo_of_a_white_lambertian() {
    let mut rng = Rng::new(77, 0, 0);
    let centre = dir(70.0, 30.0);
    let f = Frame::from_z(centre);
    let cone: Vec<(Vec3, f32)> = (0..60)
        .map(|_| {
            let a = 0.01 * rng.uniform().sqrt();
            let p = 6.283 * rng.uniform();
            (
                f.to_world(Vec3::new(a * p.cos(), a * p.sin(), 1.0))
                    .normalize(),
                0.5 + rng.uniform(),
            )
        })
        .collect();
    let grazing: Vec<(Vec3, f32)> = (0..60)
        .map(|i| {
            let c = 10f32.powf(-2.9 + 2.0 * i as f32 / 59.0);
            let s = (1.0 - c * c).sqrt();
            let p = 0.3 * i as f32;
            (Vec3::new(s * p.cos(), s * p.sin(), c), 1.0)
        })
        .collect();
    let tilts = [Vec3::Z, (Vec3::Z + Vec3::new(0.35, -0.2, 0.0)).normalize()];
    let n = 400_000;
    let guides = [
        ("footprint solid-angle", RadiusRule::SolidAngle, "caps"),
        ("footprint literal", RadiusRule::Literal, "caps"),
        ("footprint rasterised", RadiusRule::SolidAngle, "raster"),
        ("grid", RadiusRule::SolidAngle, "grid"),
    ];
    // Particle sets x tilts x guides (BSDF sampling is the reference, not a test).
    let tests = 2 * tilts.len() * guides.len();
    let crit = crate::common::t_critical(sidak(0.01, tests), (n - 1) as f64);
    for (name, particles) in [("tiny cone", &cone), ("grazing", &grazing)] {
        for ns in tilts {
            let bsdf = Bsdf::new(Lobes::Diffuse { kd: Rgb::ONE }, ns, Vec3::Z);
            let at = ScatterPoint {
                p: Vec3::ZERO,
                bsdf: &bsdf,
                wo: dir(25.0, 200.0),
                mode: TransportMode::Radiance,
                throughput: Rgb::new(1.0, 0.3, 0.05),
            };
            let frame = Frame::from_z(at.side_normal());
            let estimate = |sampler: &GuidedSampler, seed: u64| {
                let mut state = SamplerState::default();
                sampler.prepare(&at, &mut state);
                let mut rng = Rng::new(seed, 1, 0);
                let xs: Vec<f64> = (0..n)
                    .map(|_| {
                        sampler
                            .sample(&at, &state, &mut rng)
                            .map_or(0.0, |s| s.weight.x as f64)
                    })
                    .collect();
                (state.guided(), crate::common::mean_stderr(&xs))
            };
            let (_, (ref_mean, ref_se)) = estimate(&GuidedSampler::bsdf(), 3);
            let (reference, reference_se) = if ns == Vec3::Z {
                (1.0, 0.0)
            } else {
                (ref_mean, ref_se)
            };
            for (label, rule, kind) in guides {
                let params = params(rule);
                let ps = guide_particles(&frame, particles, &params);
                let fp = FootprintDistribution::build(&frame, &ps, &params);
                let dist: Box<dyn GuideDistribution> = match kind {
                    "grid" => Box::new(GridDistribution::build(&frame, &ps, params.grid_side)),
                    "raster" => Box::new(fp.rasterise(&frame, 32)),
                    _ => Box::new(fp),
                };
                let (guided, (mean, se)) = estimate(&fixed(dist.as_ref(), &params), 11);
                assert!(guided, "{name} {label}: not guided");
                let t = (mean - reference).abs() / (se * se + reference_se * reference_se).sqrt();
                eprintln!(
                    "{name}, tilt {:.2}, {label}: mean {mean:.5} ± {se:.5}, reference {reference:.5} (|t| {t:.2}, limit {crit:.2})",
                    ns.dot(Vec3::Z)
                );
                assert!(
                    t <= crit,
                    "{name}, {label}: f cos / pdf averages {mean} ± {se}, expected {reference}"
                );
            }
        }
    }
}
