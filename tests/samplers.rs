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
//!
//! The parts live in `tests/samplers/`; this root holds what they share.

mod common;

#[path = "samplers/cache.rs"]
mod cache;
#[path = "samplers/chi_square.rs"]
mod chi_square;
#[path = "samplers/configs.rs"]
mod configs;
#[path = "samplers/consistency.rs"]
mod consistency;
#[path = "samplers/densities.rs"]
mod densities;
#[path = "samplers/estimates.rs"]
mod estimates;
#[path = "samplers/masses.rs"]
mod masses;

use footprint::Rgb;
use footprint::bsdf::{Bsdf, Lobes};
use footprint::guide::sampler::{GuideSource, GuidedSampler, ScatterPoint};
use footprint::guide::{ChannelMix, GuideDistribution, GuideParticle};
use footprint::math::Frame;
use footprint::settings::{GuideParams, RadiusRule};
use glam::Vec3;

/// A direction at polar angle `theta_deg` from +z.
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

/// The default guide parameters with radius rule `rule`.
fn params(rule: RadiusRule) -> GuideParams {
    GuideParams {
        radius_rule: rule,
        ..GuideParams::default()
    }
}
