//! Classic photon-map importance sampling (Jensen 1995, "Importance Driven Path Tracing using
//! the Photon Map"), the baseline the paper compares with: the particles' contributions are
//! inserted into a grid mapped onto each hemisphere, a cell is chosen by accumulated
//! contribution and a direction uniform within it.
//!
//! The mapping from the unit square to a hemisphere is the area-preserving one (Shirley's
//! uniform warp): `cos θ = 1 - u`, `φ = 2π v`, so every cell has the same solid angle
//! `2π / side²`, a direction uniform in the cell's square is uniform in solid angle, and the
//! pdf is the cell's share of the contributions over the cell's solid angle. With
//! per-channel weights each channel has its own cell probabilities and the cell choice is a
//! mixture over channels ([`ChannelMix`]); a cell's probability is the difference of the
//! cumulative sums `sample` searches, so sample and pdf agree by construction.

use crate::Rgb;
use crate::guide::{ChannelMix, Guide, GuideDistribution, GuideParticle};
use crate::math::{Frame, PI, safe_sqrt};
use crate::rng::Rng;
use crate::settings::GuideParams;
use glam::{Vec2, Vec3};

/// The cell grid of both hemispheres at one point or region (local frame around the side
/// normal).
#[derive(Clone, Debug)]
pub struct GridDistribution {
    frame: Frame,
    side: usize,
    /// Per channel, cumulative probabilities over the cells (hemisphere `+z` first, then
    /// `-z`); empty when the channel's total is zero.
    cdf: [Vec<f32>; 3],
    totals: Rgb,
}

impl GridDistribution {
    /// `(u, v)` in the unit square of a local direction's hemisphere.
    #[inline]
    fn square_of(d: Vec3) -> Vec2 {
        let mut phi = d.y.atan2(d.x);
        if phi < 0.0 {
            phi += 2.0 * PI;
        }
        Vec2::new(
            (1.0 - d.z.abs()).clamp(0.0, 1.0),
            (phi / (2.0 * PI)).clamp(0.0, 1.0),
        )
    }

    #[inline]
    fn cell_of(&self, d: Vec3) -> usize {
        Self::cell_in(self.side, d)
    }

    /// The cell of the local direction `d` on grids of `side` cells per hemisphere's side
    /// (hemisphere `+z` first).
    #[inline]
    pub fn cell_in(side: usize, d: Vec3) -> usize {
        let s = side;
        let uv = Self::square_of(d);
        let i = ((uv.x * s as f32) as usize).min(s - 1);
        let j = ((uv.y * s as f32) as usize).min(s - 1);
        let base = if d.z >= 0.0 { 0 } else { s * s };
        base + j * s + i
    }

    /// Accumulates the particles' weights per channel into the cells of the grid around
    /// `frame.z`.
    pub fn build(frame: &Frame, particles: &[GuideParticle], side: usize) -> Self {
        Self::from_masses(
            frame,
            side,
            particles
                .iter()
                .map(|p| (p.dir, [p.weight.x, p.weight.y, p.weight.z])),
        )
    }

    /// The grid of the per-channel masses `points` (world direction, mass) accumulated into
    /// the cells their directions fall in; the channel totals are the masses' sums.
    pub fn from_masses(
        frame: &Frame,
        side: usize,
        points: impl IntoIterator<Item = (Vec3, [f32; 3])>,
    ) -> Self {
        let mut g = GridDistribution {
            frame: *frame,
            side,
            cdf: Default::default(),
            totals: Rgb::ZERO,
        };
        let cells = 2 * side * side;
        let mut acc = vec![[0.0f64; 3]; cells];
        let mut totals = [0.0f64; 3];
        for (dir, m) in points {
            let cell = g.cell_of(frame.to_local(dir));
            for ch in 0..3 {
                acc[cell][ch] += m[ch] as f64;
                totals[ch] += m[ch] as f64;
            }
        }
        for ch in 0..3 {
            if !(totals[ch] > 0.0) {
                continue;
            }
            let mut run = 0.0f64;
            g.cdf[ch] = acc
                .iter()
                .map(|a| {
                    run += a[ch] / totals[ch];
                    run as f32
                })
                .collect();
            if let Some(l) = g.cdf[ch].last_mut() {
                *l = 1.0;
            }
        }
        g.totals = Rgb::new(totals[0] as f32, totals[1] as f32, totals[2] as f32);
        g
    }

    /// Cells per side of each hemisphere's grid.
    pub fn side(&self) -> usize {
        self.side
    }

    /// Solid angle of one cell.
    #[inline]
    pub fn cell_solid_angle(&self) -> f32 {
        2.0 * PI / (self.side * self.side) as f32
    }

    #[inline]
    fn prob(&self, ch: usize, cell: usize) -> f32 {
        let cdf = &self.cdf[ch];
        if cdf.is_empty() {
            return 0.0;
        }
        cdf[cell] - if cell > 0 { cdf[cell - 1] } else { 0.0 }
    }
}

impl GuideDistribution for GridDistribution {
    fn channel_totals(&self) -> Rgb {
        self.totals
    }

    fn sample(&self, mix: &ChannelMix, rng: &mut Rng) -> Option<Vec3> {
        let cdf = &self.cdf[mix.pick(rng.uniform())];
        if cdf.is_empty() {
            return None;
        }
        let u_cell = rng.uniform();
        let cell = cdf.partition_point(|&c| c <= u_cell).min(cdf.len() - 1);
        let s = self.side;
        let (hemi, rest) = (cell / (s * s), cell % (s * s));
        let (j, i) = (rest / s, rest % s);
        // A direction uniform in the cell, drawn again in the rare case that rounding puts
        // it in a neighbouring cell as `pdf` sees it (sample and pdf agree by construction).
        let mut w = Vec3::ZERO;
        for _ in 0..16 {
            let u = rng.uniform2();
            let vv = (j as f32 + u.y) / s as f32;
            // cos θ = 1 - (i + u)/s, written so that the horizon ring never rounds to 0.
            let cos_t = ((s - i) as f32 - u.x) / s as f32;
            let sin_t = safe_sqrt(1.0 - cos_t * cos_t);
            let phi = 2.0 * PI * vv;
            let z = if hemi == 0 { cos_t } else { -cos_t };
            w = self
                .frame
                .to_world(Vec3::new(sin_t * phi.cos(), sin_t * phi.sin(), z))
                .normalize();
            if self.cell_of(self.frame.to_local(w)) == cell {
                return Some(w);
            }
        }
        Some(w)
    }

    fn pdf(&self, mix: &ChannelMix, wi: Vec3) -> f32 {
        let cell = self.cell_of(self.frame.to_local(wi));
        let mut p = 0.0;
        for ch in 0..3 {
            if mix.0[ch] > 0.0 {
                p += mix.0[ch] * self.prob(ch, cell);
            }
        }
        p / self.cell_solid_angle()
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn heap_bytes(&self) -> usize {
        self.cdf.iter().map(|c| c.capacity() * 4).sum()
    }
}

/// The classic grid as a [`Guide`].
pub struct GridGuide;

impl Guide for GridGuide {
    fn name(&self) -> &'static str {
        "grid"
    }

    fn about(&self) -> &'static str {
        "Classic photon-map importance sampling on a hemisphere grid (Jensen 1995)"
    }

    fn build(
        &self,
        frame: &Frame,
        particles: &[GuideParticle],
        params: &GuideParams,
    ) -> Option<Box<dyn GuideDistribution>> {
        if particles.is_empty() {
            return None;
        }
        Some(Box::new(GridDistribution::build(
            frame,
            particles,
            params.grid_side,
        )))
    }
}
