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
//! mixture over channels ([`ChannelMix`]); a cell's probability is quantised to multiples of 2^-15 and
//! `sample` and `pdf` read the same integers, so they agree exactly (see
//! [`GridDistribution`]).

use crate::Rgb;
use crate::guide::channel_mix::ChannelMix;
use crate::guide::distribution::{Guide, GuideDistribution, GuideParticle};
use crate::math::{Frame, PI, safe_sqrt};
use crate::rng::Rng;
use crate::settings::GuideParams;
use glam::{Vec2, Vec3};

/// The cell grid of both hemispheres at one point or region (local frame around the side
/// normal).
///
/// **Layout** (what a guided event reads, in as few cache lines as possible). Each
/// channel's cell probabilities are quantised to integers that sum to exactly
/// [`QUANTUM`] (largest remainders), stored per cell with the three channels side by
/// side, so that `pdf` reads one cell's six bytes. Sampling searches the cumulative sums
/// of the channel's *rows* (the `side` cells of one `φ` band of a hemisphere: one number
/// per held row, 32 bytes at side 16 for one hemisphere) and then walks the row's cells. Both read the
/// same integers, so sample and pdf agree exactly.
#[derive(Clone, Debug)]
pub struct GridDistribution {
    frame: Frame,
    side: usize,
    /// Per cell (hemisphere `+z` first), each channel's probability in units of
    /// `1 / QUANTUM`; all zero for a channel without mass.
    /// Only the rows held: the `+z` hemisphere's alone where no channel has mass below the
    /// horizon (an opaque surface's distributions: half the bytes, so more regions stay in
    /// cache), cells past the end having probability 0.
    counts: Box<[[u16; 3]]>,
    /// Rows held: `side` (the `+z` hemisphere) or `2·side` (both).
    rows: usize,
    /// Per channel, the cumulative counts over the held rows (`rows` each, channel after
    /// channel); the last of a channel with mass is [`QUANTUM`].
    row_cdf: Box<[u16]>,
    totals: Rgb,
}

/// The denominator of the quantised cell probabilities: a power of two, so that a uniform
/// number `u` (a multiple of 2^-24) picks quantum `floor(u · QUANTUM)` with probability
/// exactly `1 / QUANTUM` and sampling draws exactly the probabilities `pdf` reads.
pub const QUANTUM: u32 = 1 << 15;

impl GridDistribution {
    /// `(u, v)` in the unit square of a local direction's hemisphere.
    #[inline]
    fn square_of(d: Vec3) -> Vec2 {
        let mut phi = crate::math::atan2_fast(d.y, d.x);
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
        let local = points.into_iter().map(|(d, m)| (frame.to_local(d), m));
        Self::from_local_masses(frame, side, local)
    }

    /// [`GridDistribution::from_masses`] of directions given in `frame`'s local coordinates.
    pub fn from_local_masses(
        frame: &Frame,
        side: usize,
        points_local: impl IntoIterator<Item = (Vec3, [f32; 3])>,
    ) -> Self {
        let cells = 2 * side * side;
        let mut acc = vec![[0.0f64; 3]; cells];
        let mut totals = [0.0f64; 3];
        for (dir_local, m) in points_local {
            let cell = Self::cell_in(side, dir_local);
            for ch in 0..3 {
                acc[cell][ch] += m[ch] as f64;
                totals[ch] += m[ch] as f64;
            }
        }
        let below = acc[side * side..]
            .iter()
            .any(|a| a.iter().any(|&m| m > 0.0));
        let rows = if below { 2 * side } else { side };
        let mut counts = vec![[0u16; 3]; rows * side];
        let mut row_cdf = vec![0u16; 3 * rows];
        for ch in 0..3 {
            if !(totals[ch] > 0.0) {
                continue;
            }
            let q = quantise(acc.iter().map(|a| a[ch] / totals[ch]));
            let mut run = 0u32;
            // (Quantising leaves a cell without mass at 0, so the rows not held are all 0.)
            for (r, row) in q.chunks(side).take(rows).enumerate() {
                for (i, &c) in row.iter().enumerate() {
                    counts[r * side + i][ch] = c as u16;
                    run += c;
                }
                row_cdf[ch * rows + r] = run as u16;
            }
        }
        GridDistribution {
            frame: *frame,
            side,
            counts: counts.into_boxed_slice(),
            rows,
            row_cdf: row_cdf.into_boxed_slice(),
            totals: Rgb::new(totals[0] as f32, totals[1] as f32, totals[2] as f32),
        }
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

    /// Probability of channel `ch` for cell `cell`, as sampling draws it.
    #[inline]
    pub fn prob(&self, ch: usize, cell: usize) -> f32 {
        self.counts
            .get(cell)
            .map_or(0.0, |c| c[ch] as f32 / QUANTUM as f32)
    }

    /// A direction drawn as [`GuideDistribution::sample`] draws it, with the cell `pdf`
    /// puts it in when that is the cell it was drawn in (all but a rounding case).
    #[inline]
    fn draw(&self, mix: &ChannelMix, rng: &mut Rng) -> Option<(Vec3, Option<usize>)> {
        let ch = mix.pick(rng.uniform());
        let s = self.side;
        let n = self.rows;
        let rows = &self.row_cdf[ch * n..(ch + 1) * n];
        if rows[n - 1] == 0 {
            return None;
        }
        // The quantum below `u`: the row whose cumulative count first exceeds it, then the
        // cell of that row whose running count does.
        let t = ((rng.uniform() * QUANTUM as f32) as u32).min(QUANTUM - 1);
        let row = rows.partition_point(|&c| c as u32 <= t).min(n - 1);
        let mut left = t - if row > 0 { rows[row - 1] as u32 } else { 0 };
        let mut cell = row * s + s - 1;
        for (i, c) in self.counts[row * s..(row + 1) * s].iter().enumerate() {
            let c = c[ch] as u32;
            if left < c {
                cell = row * s + i;
                break;
            }
            left -= c;
        }
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
            let (sin_phi, cos_phi) = crate::math::sin_cos_turns(vv);
            let z = if hemi == 0 { cos_t } else { -cos_t };
            w = self
                .frame
                .to_world(Vec3::new(sin_t * cos_phi, sin_t * sin_phi, z))
                .normalize();
            if self.cell_of(self.frame.to_local(w)) == cell {
                return Some((w, Some(cell)));
            }
        }
        Some((w, None))
    }

    /// The density of every direction in `cell`.
    #[inline]
    fn cell_pdf(&self, mix: &ChannelMix, cell: usize) -> f32 {
        let Some(&c) = self.counts.get(cell) else {
            return 0.0;
        };
        let p = mix.0[0] * c[0] as f32 + mix.0[1] * c[1] as f32 + mix.0[2] * c[2] as f32;
        p / (QUANTUM as f32 * self.cell_solid_angle())
    }

    /// Asks the processor to bring the row sums of every channel, and the upper
    /// hemisphere's cell counts (at most 1.5 KB: 16x16 cells of three `u16`), into cache
    /// ahead of a draw (a guided event prepares its region's distribution, then does other
    /// work, next-event estimation or the camera connection, before it draws and before
    /// next-event estimation reads the density of its light direction: both arrive
    /// meanwhile). A hint only: nothing is read.
    #[inline]
    pub fn prefetch(&self) {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
            let bytes = std::mem::size_of_val(&*self.row_cdf);
            let base = self.row_cdf.as_ptr() as *const i8;
            for off in (0..bytes.min(256)).step_by(64) {
                // SAFETY: a prefetch never faults and reads nothing the program sees; the
                // address lies inside the live `row_cdf` allocation.
                unsafe { _mm_prefetch::<_MM_HINT_T0>(base.add(off)) };
            }
            let bytes = std::mem::size_of_val(&*self.counts);
            let base = self.counts.as_ptr() as *const i8;
            for off in (0..bytes.min(1536)).step_by(64) {
                // SAFETY: as above, inside the live `counts` allocation.
                unsafe { _mm_prefetch::<_MM_HINT_T0>(base.add(off)) };
            }
        }
    }

    /// [`GuideDistribution::sample`] and the [`GuideDistribution::pdf`] of the drawn
    /// direction, read from the cell it was drawn in (the same number `pdf` gives).
    #[inline]
    pub fn sample_with_pdf(&self, mix: &ChannelMix, rng: &mut Rng) -> Option<(Vec3, f32)> {
        let (w, cell) = self.draw(mix, rng)?;
        Some((
            w,
            match cell {
                Some(c) => self.cell_pdf(mix, c),
                None => self.pdf(mix, w),
            },
        ))
    }
}

/// Integers `c_i` with `Σ c_i = QUANTUM` closest to `QUANTUM · p_i` for probabilities `p`
/// that sum to one (largest remainders: each `c_i` is `floor(QUANTUM · p_i)` or one more).
fn quantise(p: impl Iterator<Item = f64>) -> Vec<u32> {
    let scaled: Vec<f64> = p.map(|x| x.max(0.0) * QUANTUM as f64).collect();
    let mut c: Vec<u32> = scaled.iter().map(|&x| x.floor() as u32).collect();
    let mut given: u32 = c.iter().sum();
    // Probabilities that sum to a little more than one (rounding): take the excess from
    // the largest cells.
    while given > QUANTUM {
        if let Some(m) = c.iter_mut().max() {
            *m -= 1;
        }
        given -= 1;
    }
    let mut left = QUANTUM.saturating_sub(given) as usize;
    if left > 0 {
        let mut order: Vec<usize> = (0..c.len()).filter(|&i| scaled[i] > 0.0).collect();
        // Largest remainder first, the lower cell first among equal ones. Only the `left`
        // first are needed (more only by rounding of the sum, then all of them): they are
        // selected, not sorted.
        let first = |a: &usize, b: &usize| {
            (scaled[*b] - scaled[*b].floor())
                .total_cmp(&(scaled[*a] - scaled[*a].floor()))
                .then(a.cmp(b))
        };
        if left < order.len() {
            order.select_nth_unstable_by(left, first);
            order.truncate(left);
        }
        // More remainder than cells with mass happens only by rounding of the sum.
        while left > 0 && !order.is_empty() {
            for &i in order.iter().take(left) {
                c[i] += 1;
            }
            left = left.saturating_sub(order.len());
        }
    }
    c
}

impl GuideDistribution for GridDistribution {
    fn channel_totals(&self) -> Rgb {
        self.totals
    }

    fn sample(&self, mix: &ChannelMix, rng: &mut Rng) -> Option<Vec3> {
        self.draw(mix, rng).map(|(w, _)| w)
    }

    fn pdf(&self, mix: &ChannelMix, wi: Vec3) -> f32 {
        self.cell_pdf(mix, self.cell_of(self.frame.to_local(wi)))
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(&*self.counts) + std::mem::size_of_val(&*self.row_cdf)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    #[test]
    fn quantised_probabilities_sum_to_the_quantum_and_stay_within_one() {
        let mut rng = Rng::new(7, 0, 0);
        for n in [1usize, 2, 5, 512] {
            // Masses spanning ten decades, some cells empty.
            let m: Vec<f64> = (0..n)
                .map(|i| {
                    if i % 3 == 1 {
                        0.0
                    } else {
                        10f64.powf(10.0 * rng.uniform() as f64 - 5.0)
                    }
                })
                .collect();
            let total: f64 = m.iter().sum();
            if total == 0.0 {
                continue;
            }
            let c = quantise(m.iter().map(|x| x / total));
            assert_eq!(c.iter().sum::<u32>(), QUANTUM, "{n} cells");
            for (ci, mi) in c.iter().zip(&m) {
                let exact = mi / total * QUANTUM as f64;
                assert!((*ci as f64 - exact).abs() < 1.0, "{ci} against {exact}");
                if *mi == 0.0 {
                    assert_eq!(*ci, 0, "an empty cell keeps no probability");
                }
            }
        }
    }

    /// A grid keeps the lower hemisphere's rows only when some mass lies below the horizon:
    /// without, half the bytes, no draw below and density 0 there; with, draws reach the
    /// lower cell and its density is the upper one's (equal masses).
    #[test]
    fn the_lower_hemisphere_is_held_only_when_it_has_mass() {
        let frame = Frame::from_z(Vec3::new(-0.4, 0.1, 0.9).normalize());
        let up = frame.to_world(Vec3::new(0.3, 0.2, 0.93).normalize());
        let down = frame.to_world(Vec3::new(-0.1, 0.5, -0.86).normalize());
        let upper = GridDistribution::from_masses(&frame, 16, [(up, [1.0, 1.0, 1.0])]);
        let both = GridDistribution::from_masses(
            &frame,
            16,
            [(up, [1.0, 1.0, 1.0]), (down, [1.0, 1.0, 1.0])],
        );
        assert_eq!(2 * upper.heap_bytes(), both.heap_bytes());
        let white = ChannelMix([0.2, 0.7, 0.1]);
        assert_eq!(upper.pdf(&white, down), 0.0);
        assert!(upper.pdf(&white, up) > 0.0);
        let (p_up, p_down) = (both.pdf(&white, up), both.pdf(&white, down));
        assert!(p_down > 0.0 && (p_up - p_down).abs() < 1e-6 * p_up);
        let mut rng = Rng::new(5, 2, 0);
        let mut below = 0;
        for _ in 0..2000 {
            let w = upper.sample(&white, &mut rng).expect("mass above");
            assert!(frame.to_local(w).z >= 0.0);
            let w = both.sample(&white, &mut rng).expect("mass on both sides");
            below += usize::from(frame.to_local(w).z < 0.0);
        }
        // Half the draws below: 1000 of 2000 with standard deviation 22 (binomial); the
        // bound is 6 of them.
        assert!((below as i64 - 1000).abs() < 135, "{below} of 2000 below");
    }

    #[test]
    fn draws_land_in_cells_of_the_drawn_channel_and_pdf_reads_their_count() {
        let frame = Frame::from_z(Vec3::new(0.3, -0.2, 0.9).normalize());
        // Red mass in one direction, green in another, no blue.
        let a = frame.to_world(Vec3::new(0.5, 0.1, 0.86).normalize());
        let b = frame.to_world(Vec3::new(-0.2, -0.7, 0.68).normalize());
        let g =
            GridDistribution::from_masses(&frame, 16, [(a, [1.0, 0.0, 0.0]), (b, [0.0, 3.0, 0.0])]);
        let (ca, cb) = (g.cell_of(frame.to_local(a)), g.cell_of(frame.to_local(b)));
        assert_eq!(g.prob(0, ca), 1.0);
        assert_eq!(g.prob(1, cb), 1.0);
        let red = ChannelMix([1.0, 0.0, 0.0]);
        let green = ChannelMix([0.0, 1.0, 0.0]);
        let mut rng = Rng::new(3, 1, 0);
        for _ in 0..1000 {
            let w = g.sample(&red, &mut rng).expect("red has mass");
            assert_eq!(g.cell_of(frame.to_local(w)), ca);
            let w = g.sample(&green, &mut rng).expect("green has mass");
            assert_eq!(g.cell_of(frame.to_local(w)), cb);
        }
        assert!(g.sample(&ChannelMix([0.0, 0.0, 1.0]), &mut rng).is_none());
        let expected = 1.0 / g.cell_solid_angle();
        assert!((g.pdf(&red, a) - expected).abs() < 1e-6 * expected);
        assert_eq!(g.pdf(&red, b), 0.0);
    }
}
