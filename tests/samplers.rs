//! The direction samplers: sampling and pdf agree, always (docs/method.md, every pitfall a
//! test).
//!
//! Each configuration places particles in the local frame of a surface (normal +z) and runs
//! the footprint sampler (both radius rules) and the grid sampler through the chi-square
//! harness: a histogram of 10^6 sampled directions against the mixture pdf's mass per cell,
//! at significance 0.01 with a Šidák correction over every (configuration, sampler) tested.
//! Footprint caps can be far smaller than a cell (a door gap, grazing particles), so their
//! cell masses are integrated in each cap's own coordinates (400 x 400 points uniform
//! in solid angle) and the BSDF part by the midpoint rule; the pdf itself is checked against
//! that same cap mixture point by point, so sampling, pdf and mixture are tied together.

mod common;

use common::chi2::ChiSquareTest;
use common::sidak;
use footprint::Rgb;
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use footprint::guide::footprint::{Cap, FootprintDistribution, FootprintGuide, cap_solid_angle};
use footprint::guide::grid::GridDistribution;
use footprint::guide::particle_map::{MapKind, ParticleMap};
use footprint::guide::sampler::{GuideSource, GuidedSampler, SamplerState, ScatterPoint};
use footprint::guide::{ChannelMix, GuideDistribution, GuideParticle};
use footprint::math::Frame;
use footprint::rng::Rng;
use footprint::sampling::{sample_cosine_hemisphere, sample_uniform_sphere};
use footprint::settings::{GuideParams, RadiusRule};
use glam::Vec3;

fn dir(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

fn diffuse() -> Bsdf {
    Bsdf::new(
        Lobes::Diffuse {
            kd: Rgb::splat(0.7),
        },
        Vec3::Z,
        Vec3::Z,
    )
}

fn glossy(n: f32) -> Bsdf {
    Bsdf::new(
        Lobes::Glossy {
            kd: Rgb::splat(0.2),
            ks: Rgb::splat(0.7),
            exponent: n,
            p_glossy: 0.7,
        },
        Vec3::Z,
        Vec3::Z,
    )
}

/// Particles given in the local frame of `frame` with scalar contributions, as a guide
/// sees them: world directions, the contribution in every channel, inadmissible ones (zero,
/// grazing) left out as the samplers leave them out.
fn guide_particles(
    frame: &Frame,
    local: &[(Vec3, f32)],
    params: &GuideParams,
) -> Vec<GuideParticle> {
    local
        .iter()
        .map(|(d, c)| GuideParticle {
            dir: frame.to_world(*d).normalize(),
            weight: Rgb::splat(*c),
        })
        .filter(|p| p.admissible(frame.z, params))
        .collect()
}

/// A sampler that guides everywhere with one prepared distribution (no map).
fn fixed<'a>(dist: &'a dyn GuideDistribution, params: &GuideParams) -> GuidedSampler<'a> {
    GuidedSampler {
        source: GuideSource::Fixed(dist),
        params: params.clone(),
        soft_glossy_max: 1e9,
        selection: None,
    }
}

/// The channel mixture the sampler uses at `at` for `dist`.
fn mix_at(at: &ScatterPoint, dist: &dyn GuideDistribution) -> ChannelMix {
    ChannelMix::new(at.channel_factor(), dist.channel_totals()).unwrap()
}

struct Config {
    name: &'static str,
    particles: Vec<(Vec3, f32)>,
    bsdf: Bsdf,
    wo: Vec3,
    /// Harness region: axis and half-angle (π: whole sphere).
    axis: Vec3,
    theta_max: f64,
}

fn configs() -> Vec<Config> {
    let mut rng = Rng::new(31, 0, 0);
    let mut v = Vec::new();
    let sphere = |name, particles, bsdf, wo| Config {
        name,
        particles,
        bsdf,
        wo,
        axis: Vec3::Z,
        theta_max: std::f64::consts::PI,
    };
    // Random particles, cosine-distributed, random contributions.
    let random: Vec<(Vec3, f32)> = (0..50)
        .map(|_| {
            (
                sample_cosine_hemisphere(rng.uniform2()),
                0.1 + rng.uniform(),
            )
        })
        .collect();
    v.push(sphere("random", random.clone(), diffuse(), dir(30.0, 0.0)));
    // All particles in a tiny cone (the door gap), 0.01 rad around a direction at 60 degrees.
    let centre = dir(60.0, 40.0);
    let f = Frame::from_z(centre);
    let cone: Vec<(Vec3, f32)> = (0..50)
        .map(|_| {
            let a = 0.01 * rng.uniform().sqrt();
            let p = 6.283 * rng.uniform();
            (
                f.to_world(Vec3::new(a * p.cos(), a * p.sin(), 1.0))
                    .normalize(),
                1.0 + rng.uniform(),
            )
        })
        .collect();
    v.push(Config {
        name: "tiny cone",
        particles: cone,
        bsdf: diffuse(),
        wo: dir(10.0, 0.0),
        axis: centre,
        theta_max: 0.05,
    });
    // Grazing particles, cos θ_p from 1e-6 to 1e-2 (those under 1e-3 are left out).
    let grazing: Vec<(Vec3, f32)> = (0..50)
        .map(|i| {
            let c = 10f32.powf(-6.0 + 4.0 * i as f32 / 49.0);
            let s = (1.0 - c * c).sqrt();
            let p = 0.2 * i as f32;
            (Vec3::new(s * p.cos(), s * p.sin(), c), 1.0)
        })
        .collect();
    v.push(Config {
        name: "grazing",
        particles: grazing,
        bsdf: diffuse(),
        wo: dir(20.0, 0.0),
        axis: Vec3::Z,
        theta_max: std::f64::consts::PI,
    });
    // Exactly along the normal and exactly on the horizon.
    let mut normal_horizon: Vec<(Vec3, f32)> = (0..25).map(|_| (Vec3::Z, 1.0)).collect();
    normal_horizon.extend((0..25).map(|i| (dir(90.0, 14.4 * i as f32), 1.0)));
    v.push(sphere(
        "normal and horizon",
        normal_horizon,
        diffuse(),
        dir(45.0, 90.0),
    ));
    // Both hemispheres (transmission).
    let both: Vec<(Vec3, f32)> = (0..50)
        .map(|_| (sample_uniform_sphere(rng.uniform2()), 0.5 + rng.uniform()))
        .collect();
    v.push(sphere(
        "both hemispheres",
        both,
        diffuse(),
        dir(30.0, 200.0),
    ));
    // One particle.
    v.push(sphere(
        "one particle",
        vec![(dir(35.0, 120.0), 1.0)],
        diffuse(),
        dir(0.0, 0.0),
    ));
    // Contributions spanning 60 orders of magnitude, some zero.
    let span: Vec<(Vec3, f32)> = (0..50)
        .map(|i| {
            let c = if i % 7 == 0 {
                0.0
            } else {
                10f32.powf(-30.0 + 60.0 * i as f32 / 49.0)
            };
            (sample_cosine_hemisphere(rng.uniform2()), c)
        })
        .collect();
    v.push(sphere(
        "60 orders of magnitude, some zero",
        span,
        diffuse(),
        dir(50.0, 0.0),
    ));
    // Flipped normals: the geometric and shading normals point down, the path arrives from
    // above, so the side normal is +z again.
    let flipped = Bsdf::new(
        Lobes::Diffuse {
            kd: Rgb::splat(0.5),
        },
        -Vec3::Z,
        -Vec3::Z,
    );
    v.push(sphere(
        "flipped normals",
        random.clone(),
        flipped,
        dir(40.0, 10.0),
    ));
    // Glossy Blinn exponent 10^4: a lobe 0.02 rad wide around the mirror direction.
    let wo = dir(30.0, 0.0);
    let mirror = Vec3::new(-wo.x, -wo.y, wo.z);
    let near_mirror: Vec<(Vec3, f32)> = (0..50)
        .map(|_| {
            let f = Frame::from_z(mirror);
            let a = 0.05 * rng.uniform().sqrt();
            let p = 6.283 * rng.uniform();
            (
                f.to_world(Vec3::new(a * p.cos(), a * p.sin(), 1.0))
                    .normalize(),
                1.0,
            )
        })
        .collect();
    v.push(Config {
        name: "glossy n=1e4",
        particles: near_mirror,
        bsdf: glossy(1.0e4),
        wo,
        axis: mirror,
        theta_max: 0.12,
    });
    v.push(sphere("glossy n=30", random, glossy(30.0), dir(60.0, 0.0)));
    v
}

fn point<'a>(c: &'a Config) -> ScatterPoint<'a> {
    ScatterPoint {
        p: Vec3::ZERO,
        bsdf: &c.bsdf,
        wo: c.wo,
        mode: TransportMode::Radiance,
        throughput: Rgb::ONE,
    }
}

fn params(rule: RadiusRule) -> GuideParams {
    GuideParams {
        radius_rule: rule,
        ..GuideParams::default()
    }
}

/// `n x n` directions uniform in solid angle over a cap, by the midpoint rule in the cap's
/// own coordinates (`1 - cos α` and azimuth), in f64 before the final rounding: each stands
/// for `1 / n²` of the cap.
fn cap_grid(cap: &Cap, n: usize) -> impl Iterator<Item = Vec3> + '_ {
    let (t1, t2) = cap.dir.any_orthonormal_pair();
    (0..n).flat_map(move |a| {
        let omc = (a as f64 + 0.5) / n as f64 * cap.one_minus_cos as f64;
        let sin = (omc * (2.0 - omc)).max(0.0).sqrt();
        (0..n).map(move |b| {
            let phi = (b as f64 + 0.5) / n as f64 * std::f64::consts::TAU;
            (cap.dir.as_dvec3() * (1.0 - omc)
                + (t1.as_dvec3() * phi.cos() + t2.as_dvec3() * phi.sin()) * sin)
                .as_vec3()
        })
    })
}

/// Cell masses of the footprint mixture: BSDF part by the midpoint rule, caps exactly (in
/// each cap's own coordinates).
fn footprint_masses(
    test: &ChiSquareTest,
    at: &ScatterPoint,
    dist: &FootprintDistribution,
    mix: &ChannelMix,
    p_bsdf: f32,
) -> Vec<f64> {
    let mut m: Vec<f64> = test.masses_from_pdf(|d| p_bsdf as f64 * at.bsdf.pdf(at.wo, d) as f64);
    let n = 400;
    for (i, cap) in dist.caps.iter().enumerate() {
        let prob = dist.probability(mix, i);
        if prob == 0.0 {
            continue;
        }
        let w = (1.0 - p_bsdf) as f64 * prob as f64 / (n * n) as f64;
        for world in cap_grid(cap, n) {
            if let Some(c) = test.cell_of(world) {
                m[c] += w;
            }
        }
    }
    m
}

/// Cell masses of the grid mixture: BSDF part by the midpoint rule, the grid part exactly.
/// A grid cell is a rectangle in `(cos θ, φ)` (uniform density there) and so is a harness
/// cell (the harness here is the whole sphere around the same normal, in the same frame), so
/// their overlap is a product of two interval overlaps.
fn grid_masses(
    test: &ChiSquareTest,
    at: &ScatterPoint,
    frame: &Frame,
    grid: &GridDistribution,
    mix: &ChannelMix,
    params: &GuideParams,
) -> Vec<f64> {
    use std::f64::consts::{PI, TAU};
    assert_eq!(
        test.theta_max, PI,
        "the exact grid masses assume a whole-sphere harness"
    );
    let p_bsdf = params.p_bsdf;
    let mut m: Vec<f64> = test.masses_from_pdf(|d| p_bsdf as f64 * at.bsdf.pdf(at.wo, d) as f64);
    let side = grid.side();
    let overlap = |a0: f64, a1: f64, b0: f64, b1: f64| (a1.min(b1) - a0.max(b0)).max(0.0);
    for hemi in [1.0f64, -1.0] {
        for j in 0..side {
            for i in 0..side {
                // Grid cell: |cos θ| in [1 - (i+1)/side, 1 - i/side], φ in [j, j+1] * 2π/side.
                let (u0, u1) = (i as f64 / side as f64, (i + 1) as f64 / side as f64);
                let (f0, f1) = (
                    j as f64 / side as f64 * TAU,
                    (j + 1) as f64 / side as f64 * TAU,
                );
                let centre = {
                    let c = 1.0 - 0.5 * (u0 + u1);
                    let s = (1.0 - c * c).sqrt();
                    let ph = 0.5 * (f0 + f1);
                    Vec3::new(
                        (s * ph.cos()) as f32,
                        (s * ph.sin()) as f32,
                        (hemi * c) as f32,
                    )
                };
                let density = grid.pdf(mix, frame.to_world(centre)) as f64;
                if density == 0.0 {
                    continue;
                }
                let mass = (1.0 - p_bsdf) as f64 * density * grid.cell_solid_angle() as f64;
                // In signed cos θ: [c_lo, c_hi].
                let (c_lo, c_hi) = if hemi > 0.0 {
                    (1.0 - u1, 1.0 - u0)
                } else {
                    (-(1.0 - u0), -(1.0 - u1))
                };
                for it in 0..test.res_theta {
                    let t0 = it as f64 * PI / test.res_theta as f64;
                    let t1 = (it + 1) as f64 * PI / test.res_theta as f64;
                    let wc = overlap(t1.cos(), t0.cos(), c_lo, c_hi) / (c_hi - c_lo);
                    if wc == 0.0 {
                        continue;
                    }
                    for ip in 0..test.res_phi {
                        let p0 = ip as f64 * TAU / test.res_phi as f64;
                        let p1 = (ip + 1) as f64 * TAU / test.res_phi as f64;
                        let wp = overlap(p0, p1, f0, f1) / (f1 - f0);
                        m[it * test.res_phi + ip] += mass * wc * wp;
                    }
                }
            }
        }
    }
    m
}

#[test]
fn every_sampler_passes_chi_square_in_every_configuration() {
    let configs = configs();
    let samplers = 4; // footprint (two rules), grid, bsdf
    let alpha = sidak(0.01, configs.len() * samplers);
    for c in &configs {
        let at = point(c);
        let frame = Frame::from_z(at.side_normal());
        let test = ChiSquareTest {
            axis: frame.to_world(c.axis),
            theta_max: c.theta_max,
            res_theta: if c.theta_max < 1.0 { 30 } else { 40 },
            res_phi: if c.theta_max < 1.0 { 40 } else { 80 },
            samples: 1_000_000,
            integration_res: if c.theta_max < 1.0 { 6 } else { 4 },
            seed: 17,
        };
        for rule in [RadiusRule::SolidAngle, RadiusRule::Literal] {
            let params = params(rule);
            let particles = guide_particles(&frame, &c.particles, &params);
            assert!(!particles.is_empty(), "{}: every particle left out", c.name);
            let dist = FootprintDistribution::build(&frame, &particles, &params);
            let fp = fixed(&dist, &params);
            let mut state = SamplerState::default();
            fp.prepare(&at, &mut state);
            assert!(state.guided(), "{}: unexpected fallback", c.name);
            let mix = mix_at(&at, &dist);
            let masses = footprint_masses(&test, &at, &dist, &mix, params.p_bsdf);
            let r = test.run_with_masses(|rng| fp.sample(&at, &state, rng).map(|s| s.wi), &masses);
            eprintln!(
                "{} footprint {}: chi2 {:.0} dof {} p {:.3e}",
                c.name,
                rule.name(),
                r.chi2,
                r.dof,
                r.p_value
            );
            assert!(
                r.p_value > alpha,
                "{} footprint {}: p = {:.3e}",
                c.name,
                rule.name(),
                r.p_value
            );
            // The pdf the sampler reports is that mixture, point by point: summed here over
            // every cap by brute force (no hierarchy, no channel code).
            let mut rng = Rng::new(5, 0, 0);
            for _ in 0..2000 {
                let d = if rng.uniform() < 0.5 {
                    sample_uniform_sphere(rng.uniform2())
                } else {
                    match fp.sample(&at, &state, &mut rng) {
                        Some(s) => s.wi,
                        None => continue,
                    }
                };
                let mut expect = params.p_bsdf as f64 * at.bsdf.pdf(at.wo, d) as f64;
                for (i, cap) in dist.caps.iter().enumerate() {
                    if cap.contains(d) {
                        expect += (1.0 - params.p_bsdf as f64) * dist.probability(&mix, i) as f64
                            / (2.0 * std::f64::consts::PI * cap.one_minus_cos as f64);
                    }
                }
                let got = fp.pdf(&at, &state, d) as f64;
                assert!(
                    (got - expect).abs() <= 1e-4 * expect.max(1e-6),
                    "{}: pdf {got} vs mixture {expect}",
                    c.name
                );
            }
        }
        // The grid sampler (its cells are far coarser than the narrow harness regions, so it
        // is tested where the harness covers the whole sphere).
        if c.theta_max == std::f64::consts::PI {
            let params = GuideParams::default();
            let particles = guide_particles(&frame, &c.particles, &params);
            let grid = GridDistribution::build(&frame, &particles, params.grid_side);
            let sampler = fixed(&grid, &params);
            let mut state = SamplerState::default();
            sampler.prepare(&at, &mut state);
            let mix = mix_at(&at, &grid);
            let masses = grid_masses(&test, &at, &frame, &grid, &mix, &params);
            let r = test.run_with_masses(
                |rng| sampler.sample(&at, &state, rng).map(|s| s.wi),
                &masses,
            );
            eprintln!(
                "{} grid: chi2 {:.0} dof {} p {:.3e}",
                c.name, r.chi2, r.dof, r.p_value
            );
            assert!(r.p_value > alpha, "{} grid: p = {:.3e}", c.name, r.p_value);
        }
        // BSDF sampling alone.
        let bsdf = GuidedSampler::bsdf();
        let state = SamplerState::default();
        let r = test.run(
            |rng| bsdf.sample(&at, &state, rng).map(|s| s.wi),
            |d| bsdf.pdf(&at, &state, d) as f64,
        );
        assert!(r.p_value > alpha, "{} bsdf: p = {:.3e}", c.name, r.p_value);
    }
}

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

/// The footprint part of the pdf integrates to 1 over the sphere, by quadrature of `pdf`
/// itself: inside each cap, 300 x 300 points uniform in solid angle, each weighted by the
/// cap's solid angle over the number of caps containing the point (a partition of unity over
/// the union of caps; outside every cap the footprint part is zero). Tolerance 1e-3.
#[test]
fn footprint_pdf_integrates_to_one() {
    let frame = Frame::from_z(Vec3::Z);
    let mix = ChannelMix([1.0, 0.0, 0.0]);
    for c in configs() {
        for rule in [RadiusRule::SolidAngle, RadiusRule::Literal] {
            let params = params(rule);
            let particles = guide_particles(&frame, &c.particles, &params);
            let dist = FootprintDistribution::build(&frame, &particles, &params);
            let caps = &dist.caps;
            if caps.is_empty() {
                continue;
            }
            let n = 300;
            let mut integral = 0.0f64;
            for cap in caps {
                let omega = 2.0 * std::f64::consts::PI * cap.one_minus_cos as f64;
                for d in cap_grid(cap, n) {
                    let cover = caps.iter().filter(|k| k.contains(d)).count();
                    if cover > 0 {
                        integral +=
                            dist.pdf(&mix, d) as f64 * omega / (n * n) as f64 / cover as f64;
                    }
                }
            }
            let expect: f64 = (0..caps.len())
                .map(|i| dist.probability(&mix, i) as f64)
                .sum();
            eprintln!(
                "{} {}: ∫ p_fp = {integral:.6} (cap probabilities sum to {expect:.6})",
                c.name,
                rule.name()
            );
            assert!(
                (integral - 1.0).abs() < 1e-3,
                "{} {}: ∫ p_fp = {integral}",
                c.name,
                rule.name()
            );
        }
    }
}

/// The rasterised footprint mixture (`raster`, what sampling reads when it is on) is the
/// footprints' density smoothed over its cells: on bins of 4 x 4 of its cells (the
/// equal-area `(1 - |cos θ|, φ)` square, 8 x 8 bins per hemisphere) its masses agree with
/// the caps' masses integrated in each cap's own coordinates (100 x 100 points), and its
/// channel totals, which the channel mixture reads, are the footprints'. The quadrature
/// puts each cap's mass on points inside the cap, so mass can only move between bins a cap
/// straddles, by less than one cell's width; bound: total variation 0.05 (a wrong frame, a
/// channel scaled by the wrong total or a hemisphere swapped moves far more).
#[test]
fn rasterised_footprints_keep_the_footprint_density() {
    let side = 32;
    let bins = 8;
    let bin_of = |frame: &Frame, w: Vec3| -> usize {
        let d = frame.to_local(w);
        let mut phi = d.y.atan2(d.x);
        if phi < 0.0 {
            phi += std::f32::consts::TAU;
        }
        let u = (1.0 - d.z.abs()).clamp(0.0, 1.0);
        let v = (phi / std::f32::consts::TAU).clamp(0.0, 1.0);
        let i = ((u * bins as f32) as usize).min(bins - 1);
        let j = ((v * bins as f32) as usize).min(bins - 1);
        (if d.z >= 0.0 { 0 } else { bins * bins }) + j * bins + i
    };
    let frame = Frame::from_z(Vec3::Z);
    let params = params(RadiusRule::SolidAngle);
    for c in configs() {
        let particles = guide_particles(&frame, &c.particles, &params);
        let dist = FootprintDistribution::build(&frame, &particles, &params);
        if dist.caps.is_empty() {
            continue;
        }
        let raster = dist.rasterise(&frame, side);
        let (a, b) = (dist.channel_totals(), raster.channel_totals());
        assert!(
            ((a - b).abs() / a.max(Rgb::splat(1e-30))).max_element() < 1e-4,
            "{}: totals {a:?} against {b:?}",
            c.name
        );
        for mix in [ChannelMix([1.0, 0.0, 0.0]), ChannelMix([0.2, 0.3, 0.5])] {
            let mut exact = vec![0.0f64; 2 * bins * bins];
            let n = 100;
            for (i, cap) in dist.caps.iter().enumerate() {
                let prob = dist.probability(&mix, i) as f64;
                for w in cap_grid(cap, n) {
                    exact[bin_of(&frame, w)] += prob / (n * n) as f64;
                }
            }
            // The raster's cells are uniform: its mass in a cell is pdf x solid angle.
            let mut rast = vec![0.0f64; 2 * bins * bins];
            let cell = raster.cell_solid_angle() as f64;
            for hemi in [1.0f32, -1.0] {
                for j in 0..side {
                    for i in 0..side {
                        let cos_t = 1.0 - (i as f32 + 0.5) / side as f32;
                        let phi = std::f32::consts::TAU * (j as f32 + 0.5) / side as f32;
                        let sin_t = (1.0 - cos_t * cos_t).sqrt();
                        let w = frame.to_world(Vec3::new(
                            sin_t * phi.cos(),
                            sin_t * phi.sin(),
                            hemi * cos_t,
                        ));
                        rast[bin_of(&frame, w)] += raster.pdf(&mix, w) as f64 * cell;
                    }
                }
            }
            let total: f64 = rast.iter().sum();
            let tv: f64 = 0.5
                * exact
                    .iter()
                    .zip(&rast)
                    .map(|(x, y)| (x - y).abs())
                    .sum::<f64>();
            eprintln!(
                "{}, mix {:?}: rasterised mass {total:.5}, total variation to the caps {tv:.4}",
                c.name, mix.0
            );
            assert!((total - 1.0).abs() < 1e-3, "{}: mass {total}", c.name);
            assert!(tv < 0.05, "{}: total variation {tv}", c.name);
        }
    }
}

/// The cap solid angle in f32 matches an f64 reference for sine-radii from 1e-6 to 1.
#[test]
fn cap_solid_angle_is_accurate_in_f32() {
    for i in 0..=60 {
        let r = 10f64.powf(-6.0 + 6.0 * i as f64 / 60.0);
        let reference = 2.0 * std::f64::consts::PI * r * r / (1.0 + (1.0 - r * r).sqrt());
        let got = cap_solid_angle(r as f32) as f64;
        assert!(
            ((got - reference) / reference).abs() < 1e-5,
            "r = {r}: {got} vs {reference}"
        );
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

/// The estimator a path tracer forms at a vertex, `f · |cos θ_s| / pdf` over sampled
/// directions, has the mean `∫ f |cos θ_s| dω` whatever the sampler: for a white Lambertian
/// that is its albedo with respect to the shading normal, 1 when the shading normal is the
/// geometric one. Checked for every guide (footprints under both radius rules, footprints
/// rasterised for sampling, the grid) at
/// tiny caps (particles in a cone of 0.01 rad, and the literal rule's caps of about 1e-3
/// sr), grazing particles and tilted shading normals. A sample whose pdf misses its own cap
/// (the f32 round trip at a cap's rim) would weigh 1e4 to 1e6 times too much and move the
/// mean by far more than the bound. Tilted normals: the reference is BSDF sampling's
/// estimate (independent streams). Bound: Welch's t against Student's quantile at 0.01,
/// Šidák-corrected over every configuration x sampler, from the estimators' standard errors
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
    let samplers = 5;
    let tests = 2 * tilts.len() * samplers;
    let crit = common::t_critical(sidak(0.01, tests), (n - 1) as f64);
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
                (state.guided(), common::mean_stderr(&xs))
            };
            let (_, (ref_mean, ref_se)) = estimate(&GuidedSampler::bsdf(), 3);
            let (reference, reference_se) = if ns == Vec3::Z {
                (1.0, 0.0)
            } else {
                (ref_mean, ref_se)
            };
            for (label, rule, kind) in [
                ("footprint solid-angle", RadiusRule::SolidAngle, "caps"),
                ("footprint literal", RadiusRule::Literal, "caps"),
                ("footprint rasterised", RadiusRule::SolidAngle, "raster"),
                ("grid", RadiusRule::SolidAngle, "grid"),
            ] {
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

/// The guide cache end to end: particles on a wall (a photon map), the other pass's
/// scattering points on the same wall as seeds, the region found by a lookup, and the
/// sampler over it run through the chi-square harness against its exact masses (caps
/// integrated in their own coordinates, grid cells as exact overlaps). The particles are
/// strongly coloured per direction (red light from one side at grazing angles, blue light
/// from above), the path's throughput is almost pure red, the BSDF is a glossy lobe over a
/// tilted shading normal: the channel mixture must follow the throughput, and sample and
/// pdf must agree. Significance 0.01, Šidák over the guides tested.
#[test]
fn cached_regions_pass_chi_square_with_coloured_throughput() {
    use footprint::guide::Guide;
    use footprint::guide::cache::{GuideCache, Seed};
    use footprint::guide::grid::GridGuide;
    use footprint::guide::particle_map::ParticleInput;
    use footprint::guide::selection::{MIN_RECORDS, SelectionLearner, SelectionRecord};
    let mut rng = Rng::new(5, 5, 5);
    let mut particles = Vec::new();
    for i in 0..4000 {
        let pos = Vec3::new(rng.uniform() * 0.2, rng.uniform() * 0.2, 0.0);
        let (d, w) = if i % 2 == 0 {
            // Red, grazing: 3 to 10 degrees above the wall, from -x.
            let elev = (3.0 + 7.0 * rng.uniform()).to_radians();
            let az = std::f32::consts::PI + 0.4 * (rng.uniform() - 0.5);
            (
                Vec3::new(elev.cos() * az.cos(), elev.cos() * az.sin(), elev.sin()),
                Rgb::new(1.0, 0.02, 0.0),
            )
        } else {
            // Blue, from near the normal.
            (
                (Vec3::Z + 0.3 * sample_uniform_sphere(rng.uniform2())).normalize(),
                Rgb::new(0.0, 0.05, 1.0),
            )
        };
        particles.push(ParticleInput {
            position: pos,
            dir: d,
            normal: Vec3::Z,
            weight: w,
            depth: 1,
            specular_chain: true,
        });
    }
    let map = ParticleMap::build(MapKind::Photons, &particles);
    let seeds: Vec<Seed> = (0..200)
        .map(|_| Seed {
            position: Vec3::new(0.05 + 0.1 * rng.uniform(), 0.05 + 0.1 * rng.uniform(), 0.0),
            normal: Vec3::Z,
        })
        .collect();
    let bsdf = Bsdf::new(
        Lobes::Glossy {
            kd: Rgb::new(0.5, 0.4, 0.3),
            ks: Rgb::splat(0.3),
            exponent: 20.0,
            p_glossy: 0.4,
        },
        (Vec3::Z + Vec3::new(0.2, 0.1, 0.0)).normalize(),
        Vec3::Z,
    );
    // Footprints rasterised for sampling (the default), footprints sampled from their caps,
    // and the grid; the default once more with the region's BSDF probability learned
    // (src/guide/selection.rs) down to 0.1, which sample and pdf must both use.
    let guides: [(&dyn Guide, usize, bool); 4] = [
        (&FootprintGuide, 16, false),
        (&FootprintGuide, 0, false),
        (&GridGuide, 0, false),
        (&FootprintGuide, 16, true),
    ];
    let alpha = sidak(0.01, guides.len());
    for (guide, raster, learned) in guides {
        let params = GuideParams {
            region_particles: 1000,
            raster,
            ..GuideParams::default()
        };
        let cache = GuideCache::build(&map, guide, &seeds, &params, 0.2);
        let x = Vec3::new(0.1, 0.1, 0.0);
        let region = cache.lookup(x, Vec3::Z).expect("a region holds the point");
        let dist = region
            .distribution
            .as_ref()
            .expect("the region guides")
            .get();
        let learner = SelectionLearner::new(cache.regions().len(), params.p_bsdf);
        let i = cache.lookup_index(x, Vec3::Z).unwrap();
        // Returns only where the guide is dense and the BSDF is not: the least BSDF share.
        let records: Vec<SelectionRecord> = (0..MIN_RECORDS)
            .map(|_| SelectionRecord {
                region: i,
                x2: 1.0,
                pdf_bsdf_w: 0.01,
                pdf_guide_w: 1.0,
                pdf_w: 0.505,
            })
            .collect();
        learner.absorb(&records);
        assert_eq!(learner.p_bsdf(i), 0.1);
        let sampler = GuidedSampler {
            source: GuideSource::Cached(&cache),
            params: params.clone(),
            soft_glossy_max: 100.0,
            selection: learned.then_some(&learner),
        };
        // The masses of the mixture with the probability the sampler uses.
        let params = GuideParams {
            p_bsdf: if learned { 0.1 } else { params.p_bsdf },
            ..params.clone()
        };
        let at = ScatterPoint {
            p: x,
            bsdf: &bsdf,
            wo: dir(40.0, 60.0),
            mode: TransportMode::Radiance,
            throughput: Rgb::new(1.0, 0.01, 0.001),
        };
        let mut state = SamplerState::default();
        sampler.prepare(&at, &mut state);
        assert!(state.guided(), "{}: not guided", guide.name());
        let mix = mix_at(&at, dist);
        assert!(
            mix.0[0] > 0.9,
            "{}: the red throughput should pick the red channel: {:?}",
            guide.name(),
            mix
        );
        let frame = Frame::from_z(region.normal);
        let test = ChiSquareTest {
            axis: region.normal,
            theta_max: std::f64::consts::PI,
            res_theta: 60,
            res_phi: 80,
            samples: 1_000_000,
            integration_res: 4,
            seed: 23,
        };
        let masses = if let Some(fp) = dist.as_any().downcast_ref::<FootprintDistribution>() {
            footprint_masses(&test, &at, fp, &mix, params.p_bsdf)
        } else {
            let grid = dist
                .as_any()
                .downcast_ref::<GridDistribution>()
                .expect("a grid");
            grid_masses(&test, &at, &frame, grid, &mix, &params)
        };
        let r = test.run_with_masses(
            |rng| sampler.sample(&at, &state, rng).map(|s| s.wi),
            &masses,
        );
        eprintln!(
            "cached {} (raster {raster}, p_bsdf {}, {} particles): chi2 {:.0} dof {} p {:.3e}, channel mixture {:?}",
            guide.name(),
            params.p_bsdf,
            region.particles,
            r.chi2,
            r.dof,
            r.p_value,
            mix.0
        );
        assert!(
            r.p_value > alpha,
            "cached {}: p = {:.3e}",
            guide.name(),
            r.p_value
        );
        // The density a draw reports is what `pdf` and (for a white path) the combined
        // image's `mis_pdf` give the same direction, with the same (learned) probability:
        // a sampler that kept the default 0.5 in either would be off by far more than 1e-4.
        let white = ScatterPoint {
            throughput: Rgb::ONE,
            ..at
        };
        let mut white_state = SamplerState::default();
        sampler.prepare(&white, &mut white_state);
        let mut rng = Rng::new(31, 0, 0);
        for _ in 0..200 {
            let Some(s) = sampler.sample(&white, &white_state, &mut rng) else {
                continue;
            };
            let pdf = sampler.pdf(&white, &white_state, s.wi);
            let mis = sampler.mis_pdf(&white, s.wi);
            let close = |a: f32, b: f32| (a - b).abs() <= 1e-4 * b.abs().max(1e-6);
            assert!(close(s.pdf_w, pdf), "sample {} vs pdf {pdf}", s.pdf_w);
            // (Footprints sampled from their caps give the weights a tabulated density.)
            if region.table.is_none() {
                assert!(close(s.pdf_w, mis), "sample {} vs mis_pdf {mis}", s.pdf_w);
            }
        }
    }
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

/// A cached region's particle density (`Region::density`, what guided Russian roulette
/// reads) estimates the weight per unit area: particles spread uniformly over a unit square
/// with a known total give `Σ w / (π r²)` over the disc holding a region's particles. Its
/// relative standard deviation is about `1/sqrt(k)` for `k` particles (a k-nearest density
/// estimate); every interior region must lie within 5 of those and their median (the regions
/// share particles, so the median is no better than one region) within 3.
#[test]
fn cached_regions_estimate_the_particle_density() {
    use footprint::guide::cache::{GuideCache, Seed};
    use footprint::guide::particle_map::ParticleInput;
    let mut rng = Rng::new(8, 8, 8);
    let n = 40_000;
    let w = Rgb::new(2.0, 1.0, 0.5) / n as f32;
    let particles: Vec<ParticleInput> = (0..n)
        .map(|_| ParticleInput {
            position: Vec3::new(rng.uniform(), rng.uniform(), 0.0),
            dir: (Vec3::Z + 0.5 * sample_uniform_sphere(rng.uniform2())).normalize(),
            normal: Vec3::Z,
            weight: w,
            depth: 2,
            specular_chain: false,
        })
        .collect();
    let map = ParticleMap::build(MapKind::Photons, &particles);
    // Seeds in the middle, so that every region's disc lies inside the square.
    let seeds: Vec<Seed> = (0..400)
        .map(|_| Seed {
            position: Vec3::new(0.3 + 0.4 * rng.uniform(), 0.3 + 0.4 * rng.uniform(), 0.0),
            normal: Vec3::Z,
        })
        .collect();
    let params = GuideParams {
        region_seeds: 40,
        ..GuideParams::default()
    };
    let cache = GuideCache::build(&map, &FootprintGuide, &seeds, &params, 0.2);
    let expected = w * n as f32; // per unit area: the square's area is 1
    let mut ratios = Vec::new();
    for r in cache.regions().iter().filter(|r| r.distribution.is_some()) {
        let sd = 1.0 / (r.particles as f32).sqrt();
        let density = r.density.expect("a finite density");
        let ratio = density / expected;
        // One colour: every channel is the same ratio.
        assert!((ratio.x - ratio.z).abs() < 1e-4 && (ratio.x - ratio.y).abs() < 1e-4);
        assert!(
            (ratio.x - 1.0).abs() < 5.0 * sd,
            "region at {:?}: density {:?} against {expected:?} ({} particles)",
            r.centre,
            density,
            r.particles
        );
        ratios.push((ratio.x, sd));
    }
    assert!(
        ratios.len() >= 5,
        "{} regions: too few to test",
        ratios.len()
    );
    ratios.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (median, sd) = ratios[ratios.len() / 2];
    eprintln!(
        "{} regions, median density ratio {median:.4} (sd {sd:.4})",
        ratios.len()
    );
    assert!((median - 1.0).abs() < 3.0 * sd, "median ratio {median}");
}
