//! The hemispherical particle footprint guide (Hey & Purgathofer 2001, §2; docs/method.md).
//!
//! From the particles around a point (local frame around the side normal `N`):
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
//!   its cap (docs/method.md: eq. 16's disc is neither the whole disc nor uniform in solid
//!   angle). With per-channel weights the particle choice is a mixture over channels
//!   ([`ChannelMix`]).
//! * **Pdf** (eq. 12, 17 in per-steradian form, as the marginal over every choice):
//!   `p_fp(Ψ) = Σ_p (c_p / Σ c) · 1[Ψ ∈ cap_p] / ω_f(p)`, where `Ψ ∈ cap_p` means
//!   `1 - Ψ·Ψ_p < 1 - cos α_p`, tested as `|Ψ - Ψ_p|² < 2 (1 - cos α_p)` (eq. 14 without the
//!   antipodal cap). The sum runs over every particle; a bounding-volume hierarchy over the
//!   caps finds the few that contain `Ψ`.
//! * **Sample and pdf agree by construction**: a direction drawn in a cap that the f32
//!   membership test puts outside that cap (possible at the rim of a cap of 1e-3 radius) is
//!   drawn again, so `sample` only returns directions inside their own cap as `pdf` sees
//!   it. The particle probabilities `pdf` uses are differences of the same cumulative
//!   sums `sample` searches.

use crate::Rgb;
use crate::guide::channel_mix::ChannelMix;
use crate::guide::distribution::{Guide, GuideDistribution, GuideParticle};
use crate::guide::grid::GridDistribution;
use crate::guide::table::DirectionTable;
use crate::guide::tangent_grid::{cell, cell_solid_angles_cached};
use crate::math::{Frame, PI, safe_sqrt};
use crate::rng::Rng;
use crate::settings::{GuideParams, RadiusRule};
use glam::Vec3;

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

/// A footprint: a spherical cap around a particle direction (world frame).
#[derive(Clone, Copy, Debug)]
pub struct Cap {
    /// Centre, world, unit.
    pub dir: Vec3,
    /// `1 - cos α_max` (the cap is `1 - Ψ·dir < one_minus_cos`).
    pub one_minus_cos: f32,
    /// `1 / ω_f = 1 / (2π (1 - cos α_max))`.
    pub inv_solid_angle: f32,
}

impl Cap {
    /// The membership test `pdf` uses: `|Ψ - dir|² < 2 (1 - cos α)`, which is
    /// `1 - Ψ·dir < 1 - cos α` without cancellation (eq. 14, one cap only).
    #[inline]
    pub fn contains(&self, w: Vec3) -> bool {
        (w - self.dir).length_squared() < 2.0 * self.one_minus_cos
    }

    /// `n` directions spread uniformly in solid angle over the cap, deterministically: a
    /// spherical Fibonacci spiral (`1 - cos α` at the midpoints of `n` equal steps, the
    /// azimuth turning by the golden angle), a quadrature of the cap's uniform density.
    pub fn quadrature(&self, n: usize) -> impl Iterator<Item = Vec3> + '_ {
        let (t1, t2) = self.dir.any_orthonormal_pair();
        spiral(self.dir, t1, t2, self.one_minus_cos, n).map(Vec3::normalize)
    }

    /// [`Cap::quadrature`]'s points in `frame`'s local coordinates, the cap's axes taken to
    /// the frame once rather than every point (unit to rounding, not normalised: what a
    /// grid's cell lookup needs).
    fn quadrature_local(&self, frame: &Frame, n: usize) -> impl Iterator<Item = Vec3> {
        let (t1, t2) = self.dir.any_orthonormal_pair();
        let [d, t1, t2] = [self.dir, t1, t2].map(|v| frame.to_local(v));
        spiral(d, t1, t2, self.one_minus_cos, n)
    }

    /// A direction uniform in solid angle in the cap (`1 - cos α` uniform in
    /// `[0, 1 - cos α_max)`), redrawn until the membership test accepts it.
    fn sample(&self, rng: &mut Rng) -> Vec3 {
        let (t1, t2) = self.dir.any_orthonormal_pair();
        for _ in 0..16 {
            let omc = rng.uniform() * self.one_minus_cos;
            let cos_a = 1.0 - omc;
            let sin_a = safe_sqrt(omc * (2.0 - omc));
            let (sin_phi, cos_phi) = crate::math::sin_cos_turns(rng.uniform());
            let w = (self.dir * cos_a + (t1 * cos_phi + t2 * sin_phi) * sin_a).normalize();
            if self.contains(w) {
                return w;
            }
        }
        // Sixteen rim draws in a row: the centre is always inside.
        self.dir
    }
}

/// The spherical Fibonacci spiral of [`Cap::quadrature`] around the unit `dir` with the
/// orthonormal `t1`, `t2`, over `1 - cos α` in `[0, one_minus_cos)`.
fn spiral(
    dir: Vec3,
    t1: Vec3,
    t2: Vec3,
    one_minus_cos: f32,
    n: usize,
) -> impl Iterator<Item = Vec3> {
    let turns = golden_turns();
    (0..n).map(move |k| {
        let omc = one_minus_cos * (k as f32 + 0.5) / n as f32;
        let sin_a = safe_sqrt(omc * (2.0 - omc));
        let (cos_phi, sin_phi) = turns.get(k).copied().unwrap_or_else(|| golden_turn(k));
        dir * (1.0 - omc) + (t1 * cos_phi + t2 * sin_phi) * sin_a
    })
}

/// Cosine and sine of the `k`-th turn of [`Cap::quadrature`]'s spiral by the golden angle.
fn golden_turn(k: usize) -> (f32, f32) {
    let phi = PI * (3.0 - 5.0f32.sqrt()) * k as f32;
    (phi.cos(), phi.sin())
}

/// [`golden_turn`] of the first [`MAX_QUADRATURE`] turns, computed once (the same numbers):
/// rasterising the caps of the guide cache's regions spends most of its time on quadrature
/// points, and computing their sines and cosines at every point would be a large share of
/// it.
fn golden_turns() -> &'static [(f32, f32)] {
    static TURNS: std::sync::OnceLock<Vec<(f32, f32)>> = std::sync::OnceLock::new();
    TURNS.get_or_init(|| (0..MAX_QUADRATURE).map(golden_turn).collect())
}

/// Most quadrature points [`rasterise_caps`] spreads one cap over.
const MAX_QUADRATURE: usize = 512;

/// Fewest quadrature points [`rasterise_caps`] spreads a cap over that crosses a cell
/// boundary (two per cell it covers above this). Most of a region's caps are smaller than a
/// few cells and cross one (Bitterli's box: about 320 caps in each of 2,653 regions, all but
/// 1,032 of them crossing), so this floor sets most of the rasterisation's time, the larger
/// share of a cache build. With `n` points a crossing cap's mass lands in its cells to
/// within about `1/n` of it, errors of either sign from cap to cap: over the `N` caps that
/// make a cell, the relative error is about `1/(n √N)` beside the particles' own `1/√N`,
/// adding `1/n²` to the distribution's relative variance: 1.6% at 8, 0.4% at 16. At 8 the
/// photon cache builds a tenth to a fifth faster (docs/measurements/speed.md, "Maps and
/// caches before the first pass").
const MIN_QUADRATURE: usize = 8;

/// A node of the bounding-volume hierarchy over the caps: the box of its caps' boxes
/// (`dir ± chord`), and either two children (`right`, the left one follows) or a range of
/// caps.
#[derive(Clone, Copy, Debug)]
struct Node {
    lo: Vec3,
    hi: Vec3,
    /// Leaf: first cap; inner: index of the right child.
    index: u32,
    /// Leaf: number of caps (> 0); inner: 0.
    count: u32,
}

const LEAF_CAPS: usize = 4;

/// The footprint mixture of one point or region: caps in world space with per-channel
/// cumulative selection probabilities.
#[derive(Clone, Debug, Default)]
pub struct FootprintDistribution {
    pub caps: Vec<Cap>,
    /// Per channel, the cumulative probabilities over `caps` (empty when the channel's total
    /// is zero); a cap's probability is the difference of consecutive entries.
    cdf: [Vec<f32>; 3],
    /// Per cap, the three channels' selection probabilities: the differences of `cdf`
    /// (so `pdf` uses exactly what `sample` searches), kept together for `pdf`.
    probs: Vec<[f32; 3]>,
    totals: Rgb,
    nodes: Vec<Node>,
}

impl FootprintDistribution {
    /// Builds the caps from particles (world directions, per-channel weights) around a point
    /// with side normal `frame.z` (eq. 5-11). Particles with zero weight or grazing
    /// `|Ψ_p·N|` must already be left out.
    pub fn build(frame: &Frame, particles: &[GuideParticle], params: &GuideParams) -> Self {
        Self::from_caps(Self::caps(frame, particles, params))
    }

    /// The caps of `particles` with their per-channel weights (eq. 5-11), in particle order.
    pub fn caps(
        frame: &Frame,
        particles: &[GuideParticle],
        params: &GuideParams,
    ) -> Vec<(Cap, Rgb)> {
        let side = params.k_g_side;
        let omega = cell_solid_angles_cached(side);
        let local: Vec<Vec3> = particles.iter().map(|p| frame.to_local(p.dir)).collect();
        // ---- Directional density: 3 x 3 splats per hemisphere (eq. 5) ----
        let mut grid = vec![0u32; 2 * side * side];
        for d in &local {
            let base = if d.z >= 0.0 { 0 } else { side * side };
            let (ci, cj) = cell(*d, side);
            for j in cj.saturating_sub(1)..=(cj + 1).min(side - 1) {
                for i in ci.saturating_sub(1)..=(ci + 1).min(side - 1) {
                    grid[base + j * side + i] += 1;
                }
            }
        }
        // ---- Caps (eq. 7-11) ----
        let mut caps: Vec<(Cap, Rgb)> = Vec::with_capacity(particles.len());
        for (p, d) in particles.iter().zip(&local) {
            let base = if d.z >= 0.0 { 0 } else { side * side };
            let (ci, cj) = cell(*d, side);
            let g = grid[base + cj * side + ci].max(1) as f32;
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
            if !(one_minus_cos > 0.0) {
                continue;
            }
            caps.push((
                Cap {
                    dir: p.dir.normalize(),
                    one_minus_cos,
                    inv_solid_angle: 1.0 / (2.0 * PI * one_minus_cos),
                },
                p.weight,
            ));
        }
        caps
    }

    /// The mixture of `caps` (weighted per channel): the hierarchy over them and the
    /// per-channel selection probabilities (eq. 15).
    fn from_caps(mut caps: Vec<(Cap, Rgb)>) -> Self {
        let mut out = FootprintDistribution::default();
        if caps.is_empty() {
            return out;
        }
        // ---- The hierarchy over the caps (reorders them) ----
        build_nodes(&mut caps, 0, &mut out.nodes);
        // ---- Per-channel selection (eq. 15 with the channel mixture) ----
        let mut totals = [0.0f64; 3];
        for (_, w) in &caps {
            for (t, c) in totals.iter_mut().zip([w.x, w.y, w.z]) {
                *t += c as f64;
            }
        }
        for ch in 0..3 {
            if !(totals[ch] > 0.0) {
                continue;
            }
            let mut acc = 0.0f64;
            out.cdf[ch] = caps
                .iter()
                .map(|(_, w)| {
                    acc += w[ch] as f64 / totals[ch];
                    acc as f32
                })
                .collect();
            if let Some(last) = out.cdf[ch].last_mut() {
                *last = 1.0;
            }
        }
        out.totals = Rgb::new(totals[0] as f32, totals[1] as f32, totals[2] as f32);
        out.caps = caps.into_iter().map(|(c, _)| c).collect();
        out.probs = (0..out.caps.len())
            .map(|i| [out.prob(0, i), out.prob(1, i), out.prob(2, i)])
            .collect();
        out
    }

    /// The mixture rasterised for sampling (`raster`): each cap's mass per channel
    /// (`c_p` of eq. 15, the channel totals kept) into the equal-area grid of `side` cells
    /// per hemisphere's side around `frame.z` ([`GridDistribution`]): all of it into one
    /// cell when the cap's centre and its four extreme points lie in that cell, else spread
    /// over [`Cap::quadrature`] points, two per cell of the cap's size and at least
    /// [`MIN_QUADRATURE`]. Sampling and its pdf then cost a cell search and a lookup instead
    /// of a walk over the caps; the density is the footprints' smoothed over cells of
    /// `2π / side²` steradians.
    pub fn rasterise(&self, frame: &Frame, side: usize) -> GridDistribution {
        let totals = [self.totals.x, self.totals.y, self.totals.z];
        rasterise_caps(
            frame,
            side,
            self.caps.iter().enumerate().map(|(i, cap)| {
                let mass = [0, 1, 2].map(|ch| self.prob(ch, i) * totals[ch]);
                (*cap, mass)
            }),
        )
    }

    /// Probability with which `sample` chooses cap `i` under the channel mixture `mix`.
    #[inline]
    pub fn probability(&self, mix: &ChannelMix, i: usize) -> f32 {
        let p = &self.probs[i];
        mix.0[0] * p[0] + mix.0[1] * p[1] + mix.0[2] * p[2]
    }

    /// Probability of choosing cap `i` in channel `ch`.
    #[inline]
    fn prob(&self, ch: usize, i: usize) -> f32 {
        let cdf = &self.cdf[ch];
        if cdf.is_empty() {
            return 0.0;
        }
        cdf[i] - if i > 0 { cdf[i - 1] } else { 0.0 }
    }

    /// Calls `f` with the index of every cap whose box contains `w`.
    #[inline]
    fn for_caps_near(&self, w: Vec3, mut f: impl FnMut(usize)) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let ni = stack[top] as usize;
            let n = &self.nodes[ni];
            if w.cmplt(n.lo).any() || w.cmpgt(n.hi).any() {
                continue;
            }
            if n.count > 0 {
                for i in n.index..n.index + n.count {
                    f(i as usize);
                }
            } else if top + 2 <= stack.len() {
                // The left child follows its parent.
                stack[top] = n.index;
                stack[top + 1] = ni as u32 + 1;
                top += 2;
            }
        }
    }
}

/// Builds the hierarchy over `caps` (reordering them so that every leaf is a range);
/// `offset` is the index of `caps[0]` in the whole array. Returns the node's index.
fn build_nodes(caps: &mut [(Cap, Rgb)], offset: usize, nodes: &mut Vec<Node>) -> u32 {
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    let (mut clo, mut chi) = (lo, hi);
    for (c, _) in caps.iter() {
        let chord = (2.0 * c.one_minus_cos).sqrt() * 1.0001 + 1e-6;
        lo = lo.min(c.dir - Vec3::splat(chord));
        hi = hi.max(c.dir + Vec3::splat(chord));
        clo = clo.min(c.dir);
        chi = chi.max(c.dir);
    }
    let me = nodes.len() as u32;
    nodes.push(Node {
        lo,
        hi,
        index: offset as u32,
        count: caps.len() as u32,
    });
    if caps.len() <= LEAF_CAPS {
        return me;
    }
    let ext = chi - clo;
    let axis = if ext.x >= ext.y && ext.x >= ext.z {
        0
    } else if ext.y >= ext.z {
        1
    } else {
        2
    };
    let mid = caps.len() / 2;
    caps.select_nth_unstable_by(mid, |a, b| a.0.dir[axis].total_cmp(&b.0.dir[axis]));
    let (left, right) = caps.split_at_mut(mid);
    build_nodes(left, offset, nodes);
    let r = build_nodes(right, offset + mid, nodes);
    nodes[me as usize].index = r;
    nodes[me as usize].count = 0;
    me
}

impl GuideDistribution for FootprintDistribution {
    fn channel_totals(&self) -> Rgb {
        self.totals
    }

    fn sample(&self, mix: &ChannelMix, rng: &mut Rng) -> Option<Vec3> {
        let ch = mix.pick(rng.uniform());
        let cdf = &self.cdf[ch];
        if cdf.is_empty() {
            return None;
        }
        let u = rng.uniform();
        let i = cdf.partition_point(|&c| c <= u).min(cdf.len() - 1);
        Some(self.caps[i].sample(rng))
    }

    fn pdf(&self, mix: &ChannelMix, wi: Vec3) -> f32 {
        let mut p = 0.0;
        self.for_caps_near(wi, |i| {
            let cap = &self.caps[i];
            if cap.contains(wi) {
                p += self.probability(mix, i) * cap.inv_solid_angle;
            }
        });
        p
    }

    /// Each cap's per-channel probability on seven of its quadrature points
    /// ([`Cap::quadrature`]).
    fn tabulate(&self, frame: &Frame, side: usize) -> Option<DirectionTable> {
        let points = self.caps.iter().zip(&self.probs).flat_map(|(cap, p)| {
            let m = p.map(|x| x / 7.0);
            cap.quadrature(7).map(move |w| (w, m))
        });
        Some(DirectionTable::from_masses(
            *frame,
            side,
            self.totals,
            points,
        ))
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn heap_bytes(&self) -> usize {
        self.caps.capacity() * std::mem::size_of::<Cap>()
            + self.cdf.iter().map(|c| c.capacity() * 4).sum::<usize>()
            + self.probs.capacity() * 12
            + self.nodes.capacity() * std::mem::size_of::<Node>()
    }
}

/// [`FootprintDistribution::rasterise`] of caps given with their per-channel masses (what
/// a guide cache's region needs: no hierarchy, no selection tables).
pub fn rasterise_caps(
    frame: &Frame,
    side: usize,
    caps: impl ExactSizeIterator<Item = (Cap, [f32; 3])>,
) -> GridDistribution {
    let cell = 2.0 * PI / (side * side) as f32;
    // Points in the frame's local coordinates: the grid's cells are read there.
    let mut points: Vec<(Vec3, [f32; 3])> = Vec::with_capacity(caps.len() * 4);
    for (cap, mass) in caps {
        let (t1, t2) = cap.dir.any_orthonormal_pair();
        let omc = cap.one_minus_cos;
        let sin_a = safe_sqrt(omc * (2.0 - omc));
        let cell_of = |w: Vec3| GridDistribution::cell_in(side, frame.to_local(w));
        let home = cell_of(cap.dir);
        let inside = [t1, -t1, t2, -t2].iter().all(|t| {
            let rim = (cap.dir * (1.0 - omc) + *t * sin_a).normalize();
            cell_of(rim) == home
        });
        if inside {
            points.push((frame.to_local(cap.dir), mass));
            continue;
        }
        let omega = 2.0 * PI * omc;
        let n = ((2.0 * omega / cell).ceil() as usize).clamp(MIN_QUADRATURE, MAX_QUADRATURE);
        let m = mass.map(|x| x / n as f32);
        points.extend(cap.quadrature_local(frame, n).map(|w| (w, m)));
    }
    GridDistribution::from_local_masses(frame, side, points)
}

/// The paper's footprints as a [`Guide`].
pub struct FootprintGuide;

impl Guide for FootprintGuide {
    fn name(&self) -> &'static str {
        "footprint"
    }

    fn about(&self) -> &'static str {
        "Hemispherical particle footprints (Hey & Purgathofer 2001)"
    }

    fn build(
        &self,
        frame: &Frame,
        particles: &[GuideParticle],
        params: &GuideParams,
    ) -> Option<Box<dyn GuideDistribution>> {
        if params.raster > 0 {
            // Straight from the caps: the hierarchy and selection tables would go unused.
            let caps = FootprintDistribution::caps(frame, particles, params);
            if caps.is_empty() {
                return None;
            }
            let masses = caps.iter().map(|(c, w)| (*c, [w.x, w.y, w.z]));
            return Some(Box::new(rasterise_caps(frame, params.raster, masses)));
        }
        let d = FootprintDistribution::build(frame, particles, params);
        (!d.caps.is_empty()).then(|| Box::new(d) as Box<dyn GuideDistribution>)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The quadrature that places a cap's mass in the table keeps it inside the cap.
    #[test]
    fn cap_quadrature_points_lie_in_their_cap() {
        let dir = Vec3::new(0.2, 0.5, -0.8).normalize();
        for omc in [1e-4f32, 0.01, 0.3, 1.0] {
            let cap = Cap {
                dir,
                one_minus_cos: omc,
                inv_solid_angle: 1.0 / (2.0 * PI * omc),
            };
            for n in [7, 16, 100] {
                for p in cap.quadrature(n) {
                    assert!((p.length() - 1.0).abs() < 1e-5);
                    assert!(1.0 - p.dot(dir) <= omc * 1.0001 + 1e-6, "{omc} {n}");
                }
            }
        }
    }
}
