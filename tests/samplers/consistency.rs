//! Sample and pdf agree and stay finite on random configurations, every draw has positive
//! density, and too few particles fall back to the BSDF.

use crate::{diffuse, dir, fixed, guide_particles, params};
use footprint::Rgb;
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use footprint::guide::footprint::{FootprintDistribution, FootprintGuide};
use footprint::guide::grid::GridDistribution;
use footprint::guide::particle_map::{MapKind, ParticleMap};
use footprint::guide::sampler::{GuideSource, GuidedSampler, SamplerState, ScatterPoint};
use footprint::guide::{ChannelMix, GuideDistribution};
use footprint::math::Frame;
use footprint::rng::Rng;
use footprint::sampling::{sample_cosine_hemisphere, sample_uniform_sphere};
use footprint::settings::{GuideParams, RadiusRule};
use glam::Vec3;

/// Random configurations (random particle counts, directions including grazing, horizon and
/// both hemispheres, contributions over many orders of magnitude, diffuse and glossy BSDFs up
/// to n = 10^4, both modes, tilted shading normals): `sample` and `pdf` never give NaN,
/// infinity or a negative value, `sample` reports the pdf that `pdf` gives for its direction,
/// and wherever `f · cos > 0` the mixture pdf is positive (no coverage holes).
#[test]
fn random_configurations_stay_finite_and_consistent() {
    let mut rng = Rng::new(99, 0, 0);
    for config in 0..300 {
        let n = 1 + (rng.uniform() * 80.0) as usize;
        let particles: Vec<(Vec3, f32)> = (0..n)
            .map(|_| {
                let d = match (rng.uniform() * 4.0) as u32 {
                    0 => sample_uniform_sphere(rng.uniform2()),
                    1 => {
                        let c = 10f32.powf(-7.0 * rng.uniform());
                        let p = 6.283 * rng.uniform();
                        let s = (1.0 - c * c).sqrt();
                        Vec3::new(
                            s * p.cos(),
                            s * p.sin(),
                            if rng.uniform() < 0.5 { c } else { -c },
                        )
                    }
                    2 => Vec3::Z,
                    _ => sample_cosine_hemisphere(rng.uniform2()),
                };
                (
                    d,
                    10f32.powf(30.0 * rng.uniform() - 15.0) * (rng.uniform() > 0.1) as u32 as f32,
                )
            })
            .collect();
        let exponent = 10f32.powf(4.0 * rng.uniform());
        let ns = (Vec3::Z + 0.3 * sample_uniform_sphere(rng.uniform2())).normalize();
        let lobes = if rng.uniform() < 0.5 {
            Lobes::Diffuse {
                kd: Rgb::splat(0.8),
            }
        } else {
            Lobes::Glossy {
                kd: Rgb::splat(0.3),
                ks: Rgb::splat(0.6),
                exponent,
                p_glossy: 0.6,
            }
        };
        let bsdf = Bsdf::new(lobes, ns, Vec3::Z);
        let wo = sample_cosine_hemisphere(rng.uniform2());
        let mode = if rng.uniform() < 0.5 {
            TransportMode::Radiance
        } else {
            TransportMode::Importance
        };
        let at = ScatterPoint {
            p: Vec3::ZERO,
            bsdf: &bsdf,
            wo,
            mode,
            throughput: Rgb::ONE,
        };
        let frame = Frame::from_z(at.side_normal());
        let rule = if rng.uniform() < 0.5 {
            RadiusRule::SolidAngle
        } else {
            RadiusRule::Literal
        };
        let params = params(rule);
        let particles = guide_particles(&frame, &particles, &params);
        let fp_dist = FootprintDistribution::build(&frame, &particles, &params);
        let grid_dist = GridDistribution::build(&frame, &particles, params.grid_side);
        let samplers = [
            ("footprint", fixed(&fp_dist, &params)),
            ("grid", fixed(&grid_dist, &params)),
            ("bsdf", GuidedSampler::bsdf()),
        ];
        for (name, sampler) in &samplers {
            let mut state = SamplerState::default();
            sampler.prepare(&at, &mut state);
            let state = &state;
            for _ in 0..200 {
                if let Some(s) = sampler.sample(&at, state, &mut rng) {
                    assert!(
                        s.wi.is_finite() && (s.wi.length() - 1.0).abs() < 1e-3,
                        "config {config}: direction"
                    );
                    assert!(
                        s.pdf_w.is_finite() && s.pdf_w > 0.0,
                        "config {config} {}: pdf {}",
                        name,
                        s.pdf_w
                    );
                    assert!(
                        s.weight.is_finite() && s.weight.min_element() >= 0.0,
                        "config {config}: weight {}",
                        s.weight
                    );
                    let p = sampler.pdf(&at, state, s.wi);
                    assert!(
                        (p - s.pdf_w).abs() <= 1e-4 * p.max(1e-6),
                        "config {config} {}: sample pdf {} vs pdf {p}",
                        name,
                        s.pdf_w
                    );
                }
                let d = sample_uniform_sphere(rng.uniform2());
                let p = sampler.pdf(&at, state, d);
                assert!(p.is_finite() && p >= 0.0, "config {config}: pdf {p}");
                let fc = bsdf.eval(wo, d, mode).max_element() * d.dot(ns).abs();
                if fc > 0.0 {
                    assert!(
                        p > 0.0,
                        "config {config} {}: coverage hole (f cos = {fc})",
                        name
                    );
                }
            }
        }
    }
}

/// Fewer than k_p particles with a positive contribution: the guided samplers fall back to the
/// BSDF, in sampling and pdf alike, and count the fallback.
#[test]
fn too_few_particles_fall_back_to_the_bsdf() {
    let particles: Vec<footprint::guide::particle_map::ParticleInput> = (0..30)
        .map(|i| footprint::guide::particle_map::ParticleInput {
            position: Vec3::new(0.01 * i as f32, 0.0, 0.0),
            dir: dir(30.0, 12.0 * i as f32).normalize(),
            normal: Vec3::Z,
            weight: Rgb::ONE,
            depth: 1,
            specular_chain: true,
        })
        .collect();
    let map = ParticleMap::build(MapKind::Photons, &particles);
    let bsdf = diffuse();
    let at = ScatterPoint {
        p: Vec3::new(0.1, 0.0, 0.0),
        bsdf: &bsdf,
        wo: dir(20.0, 0.0),
        mode: TransportMode::Radiance,
        throughput: Rgb::ONE,
    };
    let per_event = |k_p: usize| GuidedSampler {
        source: GuideSource::PerEvent {
            map: &map,
            guide: &FootprintGuide,
            max_dist: 1.0,
        },
        params: GuideParams {
            k_p,
            ..GuideParams::default()
        },
        soft_glossy_max: 100.0,
        selection: None,
    };
    for k_p in [10usize, 50] {
        let fp = per_event(k_p);
        let mut state = SamplerState::default();
        fp.prepare(&at, &mut state);
        assert_eq!(state.guided(), k_p <= 30, "k_p = {k_p}");
        assert_eq!(state.fallbacks, (k_p > 30) as u64);
        let d = dir(40.0, 100.0);
        if !state.guided() {
            assert_eq!(fp.pdf(&at, &state, d), bsdf.pdf(at.wo, d));
        } else {
            assert_ne!(
                fp.pdf(&at, &state, dir(30.0, 0.0)),
                bsdf.pdf(at.wo, dir(30.0, 0.0))
            );
        }
    }
    // A mirror is never guided.
    let mirror = Bsdf::new(Lobes::Mirror { r: Rgb::ONE }, Vec3::Z, Vec3::Z);
    let at = ScatterPoint {
        bsdf: &mirror,
        ..at
    };
    let fp = per_event(10);
    let mut state = SamplerState::default();
    fp.prepare(&at, &mut state);
    assert!(!state.guided());
}

/// Every direction a guide's distribution draws lies where that distribution's density is
/// positive: a draw at the rim of a tiny cap that the membership test of `pdf` puts outside
/// (f32 rounding) would have density zero there, and a guided estimate would weigh it by the
/// BSDF branch alone, 1e4 to 1e6 times too much. Isolated caps of 1e-6 to 1e-3 sr (the
/// literal radius rule, few particles far apart, grazing ones whose caps are clamped to
/// `|cos θ_p|`), a million draws each, under tilted frames; the same for the grid's cells.
#[test]
fn every_drawn_direction_has_positive_guide_density() {
    let mut rng = Rng::new(8, 8, 8);
    for trial in 0..6 {
        let n = (Vec3::Z + 0.5 * sample_uniform_sphere(rng.uniform2())).normalize();
        let frame = Frame::from_z(n);
        let local: Vec<(Vec3, f32)> = (0..8)
            .map(|i| {
                let c = if i % 2 == 0 {
                    10f32.powf(-2.9 + 0.4 * rng.uniform())
                } else {
                    0.2 + 0.8 * rng.uniform()
                };
                let s = (1.0 - c * c).sqrt();
                let p = 6.283 * rng.uniform();
                (Vec3::new(s * p.cos(), s * p.sin(), c), 1.0)
            })
            .collect();
        for rule in [RadiusRule::Literal, RadiusRule::SolidAngle] {
            let params = GuideParams {
                k_r: if rule == RadiusRule::Literal {
                    0.05
                } else {
                    0.01
                },
                ..params(rule)
            };
            let ps = guide_particles(&frame, &local, &params);
            let dist = FootprintDistribution::build(&frame, &ps, &params);
            let smallest = dist
                .caps
                .iter()
                .map(|c| c.one_minus_cos * 2.0 * std::f32::consts::PI)
                .fold(f32::MAX, f32::min);
            let mix = ChannelMix([0.2, 0.5, 0.3]);
            let mut zero = 0;
            for _ in 0..1_000_000 {
                if let Some(w) = dist.sample(&mix, &mut rng) {
                    if !(dist.pdf(&mix, w) > 0.0) {
                        zero += 1;
                    }
                }
            }
            eprintln!(
                "trial {trial} {}: smallest cap {smallest:.2e} sr, {zero} draws of density zero",
                rule.name()
            );
            assert_eq!(
                zero,
                0,
                "trial {trial} {}: draws outside every cap",
                rule.name()
            );
        }
        // The grid: few particles leave most cells empty; a draw that rounding moved into
        // an empty neighbour would have density zero.
        let params = GuideParams {
            grid_side: 64,
            ..GuideParams::default()
        };
        let ps = guide_particles(&frame, &local, &params);
        let grid = GridDistribution::build(&frame, &ps, params.grid_side);
        let mix = ChannelMix([0.2, 0.5, 0.3]);
        let zero = (0..1_000_000)
            .filter_map(|_| grid.sample(&mix, &mut rng))
            .filter(|w| !(grid.pdf(&mix, *w) > 0.0))
            .count();
        assert_eq!(zero, 0, "trial {trial} grid: draws in empty cells");
    }
}
