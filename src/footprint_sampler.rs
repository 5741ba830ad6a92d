//! The hemispherical particle footprint sampler (Hey & Purgathofer 2001, §2; METHOD.md).
//!
//! At a scattering point the `k_p` nearest particles with a positive contribution `c_p`
//! (§2.1, eq. 1-2) are taken in a local frame around the side normal `N`.
//!
//! * **Directional density** (§2.2, eq. 5-6): each hemisphere's particle directions are
//!   projected onto the tangent plane, a `k_g = 32 x 32` grid over `[-1, 1]²`, and each
//!   particle adds 1 to the 3 x 3 block of cells around its own. The cells' solid angles `ω`
//!   are integrated once, exactly up to quadrature (`ω = ∬ dx dy / z` over the cell's part of
//!   the unit disc), instead of eq. 6's `4 / (k_g cos θ_cell)`, which has no value on the rim.
//! * **Footprint radius** (§2.3, eq. 7-11), two readings, [`RadiusRule`]:
//!   `SolidAngle` (default): `δ = g / (9 ω)` particles per steradian and a cap of solid angle
//!   `ω_f = k_r / δ`; `Literal`: `r = k_r / (g / ω)`. Either way the cap's sine-radius is
//!   clamped to `r_max = |Ψ_p · N|` (eq. 8-9) so the cap stays in its hemisphere, and its solid
//!   angle is `ω_f = 2π r² / (1 + √(1 - r²))` (eq. 10 without cancellation).
//! * **Sampling** (§2.4): a particle with probability `c_p / Σ c` — the hemisphere choice of
//!   eq. 3-4 times the particle choice of eq. 15 — then a direction uniform in solid angle in
//!   its cap (METHOD.md: eq. 16's disc is neither the whole disc nor uniform in solid angle).
//! * **Pdf** (eq. 12, 17 in per-steradian form, as the marginal over every choice):
//!   `p_fp(Ψ) = Σ_p (c_p / Σ c) · 1[Ψ ∈ cap_p] / ω_f(p)`, where `Ψ ∈ cap_p` means
//!   `Ψ · Ψ_p > 0` and `|Ψ × Ψ_p| < r_p` (eq. 14 without the antipodal cap). The sum runs over
//!   every particle: caps never leave their hemisphere, so this equals the sum over `Ψ`'s
//!   hemisphere, and a direction that rounding pushes across the horizon is still found.
//! * Particles with `|cos θ_p|` below `grazing_cos_min` are left out of both sampling and
//!   evaluation.

use crate::direction_sampler::{
    GuideParams, GuideState, ParticleDistribution, ParticleGuide, RadiusRule,
};
use crate::math::{PI, safe_sqrt};
use crate::particle_map::ParticleMap;
use glam::{Vec2, Vec3};

/// A footprint: a spherical cap around a particle direction.
#[derive(Clone, Copy, Debug)]
pub struct Cap {
    /// Centre, local frame, unit.
    pub dir: Vec3,
    /// Probability of choosing this cap, `c_p / Σ c`.
    pub prob: f32,
    /// Squared sine of the half-angle: `r²`.
    pub r2: f32,
    /// `1 - cos α_max = r² / (1 + √(1 - r²))`.
    pub one_minus_cos: f32,
    /// `1 / ω_f`.
    pub inv_solid_angle: f32,
}

/// `ω_f = 2π (1 - √(1 - r²))`, computed as `2π r² / (1 + √(1 - r²))` so that it keeps full
/// relative precision for small `r`.
#[inline]
pub fn cap_solid_angle(r: f32) -> f32 {
    let r2 = r * r;
    2.0 * PI * r2 / (1.0 + safe_sqrt(1.0 - r2))
}

/// The sine-radius of a cap of solid angle `omega` (at most a hemisphere).
#[inline]
fn cap_radius_for_solid_angle(omega: f32) -> f32 {
    // 1 - cos α = ω / 2π; r² = (1 - cos α)(1 + cos α).
    let omc = (omega / (2.0 * PI)).min(1.0);
    safe_sqrt(omc * (2.0 - omc))
}

/// The solid angles of the `side x side` tangent-plane grid's cells projected onto the
/// hemisphere, by a 16 x 16 midpoint rule per cell of `∬ dx dy / z` over the cell's part of
/// the unit disc.
pub fn cell_solid_angles(side: usize) -> Vec<f32> {
    let h = 2.0 / side as f64;
    let sub = 16;
    let mut out = vec![0.0f32; side * side];
    for j in 0..side {
        for i in 0..side {
            let mut s = 0.0f64;
            for b in 0..sub {
                for a in 0..sub {
                    let x = -1.0 + (i as f64 + (a as f64 + 0.5) / sub as f64) * h;
                    let y = -1.0 + (j as f64 + (b as f64 + 0.5) / sub as f64) * h;
                    let z2 = 1.0 - x * x - y * y;
                    if z2 > 0.0 {
                        s += 1.0 / z2.sqrt();
                    }
                }
            }
            out[j * side + i] = (s * h * h / (sub * sub) as f64) as f32;
        }
    }
    out
}

/// The footprint mixture at one point (local frame), reusable across points.
#[derive(Clone, Debug, Default)]
pub struct FootprintDistribution {
    pub caps: Vec<Cap>,
    cdf: Vec<f32>,
    /// Splat counts, two hemispheres.
    grid: Vec<u16>,
}

impl FootprintDistribution {
    /// Builds the caps from local particle directions and contributions (`c > 0`, at least
    /// one; grazing ones already removed). `omega` holds the grid's cell solid angles.
    pub fn build(&mut self, particles: &[(Vec3, f32)], params: &GuideParams, omega: &[f32]) {
        let side = params.k_g_side;
        self.grid.clear();
        self.grid.resize(2 * side * side, 0);
        let cell = |d: Vec3| -> (usize, usize) {
            let i =
                (((d.x + 1.0) * 0.5 * side as f32) as isize).clamp(0, side as isize - 1) as usize;
            let j =
                (((d.y + 1.0) * 0.5 * side as f32) as isize).clamp(0, side as isize - 1) as usize;
            (i, j)
        };
        // ---- Directional density: 3 x 3 splats per hemisphere (eq. 5) ----
        for (d, _) in particles {
            let base = if d.z >= 0.0 { 0 } else { side * side };
            let (ci, cj) = cell(*d);
            for j in cj.saturating_sub(1)..=(cj + 1).min(side - 1) {
                for i in ci.saturating_sub(1)..=(ci + 1).min(side - 1) {
                    let g = &mut self.grid[base + j * side + i];
                    *g = g.saturating_add(1);
                }
            }
        }
        // ---- Caps (eq. 7-11) ----
        let total: f64 = particles.iter().map(|p| p.1 as f64).sum();
        self.caps.clear();
        self.cdf.clear();
        let mut acc = 0.0f64;
        for (d, c) in particles {
            let base = if d.z >= 0.0 { 0 } else { side * side };
            let (ci, cj) = cell(*d);
            let g = self.grid[base + cj * side + ci].max(1) as f32;
            let w = omega[cj * side + ci].max(1e-9);
            let r_max = d.z.abs();
            let r = match params.radius_rule {
                RadiusRule::SolidAngle => {
                    let density = g / (9.0 * w);
                    cap_radius_for_solid_angle(params.k_r / density)
                }
                RadiusRule::Literal => params.k_r / (g / w),
            }
            .min(r_max);
            let r2 = r * r;
            let one_minus_cos = r2 / (1.0 + safe_sqrt(1.0 - r2));
            let omega_f = 2.0 * PI * one_minus_cos;
            let prob = (*c as f64 / total) as f32;
            acc += *c as f64 / total;
            self.caps.push(Cap {
                dir: *d,
                prob,
                r2,
                one_minus_cos,
                inv_solid_angle: 1.0 / omega_f,
            });
            self.cdf.push(acc as f32);
        }
        if let Some(last) = self.cdf.last_mut() {
            *last = 1.0;
        }
    }

    /// A direction (local): a cap chosen by contribution, a point uniform in it.
    pub fn sample(&self, u_cap: f32, u: Vec2) -> Option<Vec3> {
        let i = self
            .cdf
            .partition_point(|&c| c <= u_cap)
            .min(self.caps.len().checked_sub(1)?);
        let cap = &self.caps[i];
        // 1 - cos α uniform in [0, 1 - cos α_max]: uniform in solid angle.
        let omc = u.x * cap.one_minus_cos;
        let cos_a = 1.0 - omc;
        let sin_a = safe_sqrt(omc * (2.0 - omc));
        let phi = 2.0 * PI * u.y;
        let (t1, t2) = cap.dir.any_orthonormal_pair();
        Some((cap.dir * cos_a + (t1 * phi.cos() + t2 * phi.sin()) * sin_a).normalize())
    }

    /// `p_fp(Ψ)` per steradian for a local unit direction.
    #[inline]
    pub fn pdf(&self, d: Vec3) -> f32 {
        let mut p = 0.0;
        for cap in &self.caps {
            let cos = d.dot(cap.dir);
            if cos > 0.0 && d.cross(cap.dir).length_squared() < cap.r2 {
                p += cap.prob * cap.inv_solid_angle;
            }
        }
        p
    }
}

/// The footprints as a [`ParticleDistribution`], with the density grid's cell solid angles
/// computed once.
pub struct Footprints {
    omega: Vec<f32>,
}

impl ParticleDistribution for Footprints {
    const NAME: &'static str = "footprint";

    fn build(&self, particles: &[(Vec3, f32)], params: &GuideParams, state: &mut GuideState) {
        state.footprint.build(particles, params, &self.omega);
    }

    fn sample(&self, state: &GuideState, u_select: f32, u: Vec2) -> Option<Vec3> {
        state.footprint.sample(u_select, u)
    }

    fn pdf(&self, state: &GuideState, local: Vec3) -> f32 {
        state.footprint.pdf(local)
    }
}

/// The footprint sampler over a particle map.
pub type FootprintSampler<'m> = ParticleGuide<'m, Footprints>;

impl<'m> ParticleGuide<'m, Footprints> {
    pub fn new(
        map: &'m ParticleMap,
        params: GuideParams,
        max_dist: f32,
        soft_glossy_max: f32,
    ) -> Self {
        let omega = cell_solid_angles(params.k_g_side);
        ParticleGuide {
            map,
            params,
            max_dist,
            soft_glossy_max,
            distribution: Footprints { omega },
        }
    }
}
