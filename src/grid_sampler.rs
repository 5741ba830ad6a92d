//! Classic photon-map importance sampling (Jensen 1995, "Importance Driven Path Tracing using
//! the Photon Map"), the baseline the paper compares with: the `k_p` nearest contributions are
//! inserted into a grid mapped onto each hemisphere, a cell is chosen by accumulated
//! contribution and a direction uniform within it, mixed with the BSDF at `p_BSDF`.
//!
//! The mapping from the unit square to a hemisphere is the area-preserving one (Shirley's
//! uniform warp): `cos θ = 1 - u`, `φ = 2π v`, so every cell has the same solid angle
//! `2π / side²`, a direction uniform in the cell's square is uniform in solid angle, and the
//! pdf is the cell's share of the contributions over the cell's solid angle.

use crate::direction_sampler::{GuideParams, GuideState, ParticleDistribution, ParticleGuide};
use crate::math::{PI, safe_sqrt};
use crate::particle_map::ParticleMap;
use glam::{Vec2, Vec3};

/// The cell grid of both hemispheres at one point (local frame).
#[derive(Clone, Debug, Default)]
pub struct GridDistribution {
    side: usize,
    /// Probability per cell: hemisphere `+z` first, then `-z`.
    prob: Vec<f32>,
    cdf: Vec<f32>,
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
        let s = self.side;
        let uv = Self::square_of(d);
        let i = ((uv.x * s as f32) as usize).min(s - 1);
        let j = ((uv.y * s as f32) as usize).min(s - 1);
        let base = if d.z >= 0.0 { 0 } else { s * s };
        base + j * s + i
    }

    /// Accumulates the contributions (at least one positive).
    pub fn build(&mut self, particles: &[(Vec3, f32)], side: usize) {
        self.side = side;
        self.prob.clear();
        self.prob.resize(2 * side * side, 0.0);
        let total: f64 = particles.iter().map(|p| p.1 as f64).sum();
        for (d, c) in particles {
            let cell = self.cell_of(*d);
            self.prob[cell] += (*c as f64 / total) as f32;
        }
        self.cdf.clear();
        let mut acc = 0.0f64;
        for p in &self.prob {
            acc += *p as f64;
            self.cdf.push(acc as f32);
        }
        if let Some(l) = self.cdf.last_mut() {
            *l = 1.0;
        }
    }

    /// Solid angle of one cell.
    #[inline]
    pub fn cell_solid_angle(&self) -> f32 {
        2.0 * PI / (self.side * self.side) as f32
    }

    pub fn sample(&self, u_cell: f32, u: Vec2) -> Option<Vec3> {
        let n = self.prob.len();
        let mut cell = self
            .cdf
            .partition_point(|&c| c <= u_cell)
            .min(n.checked_sub(1)?);
        while self.prob[cell] == 0.0 && cell > 0 {
            cell -= 1;
        }
        let s = self.side;
        let (hemi, rest) = (cell / (s * s), cell % (s * s));
        let (j, i) = (rest / s, rest % s);
        let vv = (j as f32 + u.y) / s as f32;
        // cos θ = 1 - (i + u)/s, written so that the horizon ring never rounds to cos θ = 0.
        let cos_t = ((s - i) as f32 - u.x) / s as f32;
        let sin_t = safe_sqrt(1.0 - cos_t * cos_t);
        let phi = 2.0 * PI * vv;
        let z = if hemi == 0 { cos_t } else { -cos_t };
        Some(Vec3::new(sin_t * phi.cos(), sin_t * phi.sin(), z))
    }

    #[inline]
    pub fn pdf(&self, d: Vec3) -> f32 {
        if self.prob.is_empty() {
            return 0.0;
        }
        self.prob[self.cell_of(d)] / self.cell_solid_angle()
    }
}

/// The grid as a [`ParticleDistribution`].
pub struct GridCells;

impl ParticleDistribution for GridCells {
    const NAME: &'static str = "grid";

    fn build(&self, particles: &[(Vec3, f32)], params: &GuideParams, state: &mut GuideState) {
        state.grid.build(particles, params.grid_side);
    }

    fn sample(&self, state: &GuideState, u_select: f32, u: Vec2) -> Option<Vec3> {
        state.grid.sample(u_select, u)
    }

    fn pdf(&self, state: &GuideState, local: Vec3) -> f32 {
        state.grid.pdf(local)
    }
}

/// The classic grid sampler over a particle map.
pub type GridSampler<'m> = ParticleGuide<'m, GridCells>;

impl<'m> ParticleGuide<'m, GridCells> {
    pub fn new(
        map: &'m ParticleMap,
        params: GuideParams,
        max_dist: f32,
        soft_glossy_max: f32,
    ) -> Self {
        ParticleGuide {
            map,
            params,
            max_dist,
            soft_glossy_max,
            distribution: GridCells,
        }
    }
}
