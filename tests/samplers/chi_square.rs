//! Every sampler through the chi-square harness in every configuration.

use crate::common::chi2::ChiSquareTest;
use crate::common::sidak;
use crate::configs::{configs, point};
use crate::masses::{footprint_masses, grid_masses};
use crate::{fixed, guide_particles, mix_at, params};
use footprint::guide::footprint::FootprintDistribution;
use footprint::guide::grid::GridDistribution;
use footprint::guide::sampler::{GuidedSampler, SamplerState};
use footprint::math::Frame;
use footprint::rng::Rng;
use footprint::sampling::sample_uniform_sphere;
use footprint::settings::{GuideParams, RadiusRule};

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
