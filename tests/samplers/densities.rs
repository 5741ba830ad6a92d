//! The footprint densities themselves: the pdf integrates to one, rasterising keeps the
//! density, and the cap solid angle is accurate in f32.

use crate::configs::configs;
use crate::masses::cap_grid;
use crate::{guide_particles, params};
use footprint::Rgb;
use footprint::guide::footprint::{FootprintDistribution, cap_solid_angle};
use footprint::guide::{ChannelMix, GuideDistribution};
use footprint::math::Frame;
use footprint::settings::RadiusRule;
use glam::Vec3;

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
            // The caps' probabilities are the steps of an f32 cdf that ends at exactly 1, each
            // rounded once (by at most 2⁻²⁵): they sum to 1 within 1e-5 for up to 300 caps.
            let sum: f64 = (0..caps.len())
                .map(|i| dist.probability(&mix, i) as f64)
                .sum();
            eprintln!(
                "{} {}: ∫ p_fp = {integral:.6} (cap probabilities sum to {sum:.7})",
                c.name,
                rule.name()
            );
            assert!(
                (sum - 1.0).abs() < 1e-5,
                "{} {}: cap probabilities sum to {sum}",
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
