//! The exact cell masses of the guided mixtures for the chi-square harness: caps integrated
//! in their own coordinates, grid cells as exact overlaps.

use crate::common::chi2::ChiSquareTest;
use footprint::guide::footprint::{Cap, FootprintDistribution};
use footprint::guide::grid::GridDistribution;
use footprint::guide::sampler::ScatterPoint;
use footprint::guide::{ChannelMix, GuideDistribution};
use footprint::math::Frame;
use footprint::settings::GuideParams;
use glam::Vec3;

/// `n x n` directions uniform in solid angle over a cap, by the midpoint rule in the cap's
/// own coordinates (`1 - cos α` and azimuth), in f64 before the final rounding: each stands
/// for `1 / n²` of the cap.
pub fn cap_grid(cap: &Cap, n: usize) -> impl Iterator<Item = Vec3> + '_ {
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
pub fn footprint_masses(
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
pub fn grid_masses(
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
