//! A cached region's guide density tabulated for the combined image's MIS weights.
//!
//! The combined image weighs its strategies with the densities the guided samplers draw
//! with (docs/method.md, "Guided MIS weights"): every vertex of both subpaths asks for the
//! guided density of the camera direction and of the light direction, three to four times
//! a vertex. With the exact footprint mixture (eq. 12, 17) each ask walks the caps, a large
//! share of a guided combined pass. The weights need not read the exact densities: any
//! densities give weights that are a partition of unity, so the image stays unbiased, as
//! long as every strategy of a path reads the *same* ones (Veach 1997, §9.2; pbrt-v4's and
//! Open PGL's guided MIS read approximations too). Sampling keeps the exact density:
//! `DirectionSample::pdf_w` divides the path's throughput.
//!
//! **The table.** In the region's frame (its side normal `z`), each hemisphere is the
//! paper's tangent-plane grid ([`crate::guide::tangent_grid`]: §2.2, the `k_g` grid of eq. 5
//! with `side x side` cells over `[-1, 1]²`, cells' solid angles integrated). Per channel a
//! cell holds the probability mass the distribution puts in it divided by its solid angle, so
//! every channel's table integrates to one like the density it stands for. A footprint
//! distribution puts each cap's probability on seven points of the cap
//! (`Cap::quadrature`): a quadrature of the cap, exact in total mass and in which
//! hemisphere it lies (caps never cross their horizon, eq. 8-9).

use crate::Rgb;
use crate::guide::channel_mix::ChannelMix;
use crate::guide::tangent_grid::{cell, cell_solid_angles_cached};
use crate::math::Frame;
use glam::Vec3;

/// Per-channel densities on each hemisphere's tangent-plane grid of a region's frame.
#[derive(Clone, Debug)]
pub struct DirectionTable {
    frame: Frame,
    side: u32,
    /// Per channel, the distribution's total weight (what [`ChannelMix`] reads).
    totals: Rgb,
    /// `side²` cells of the upper hemisphere (`z >= 0`), then, when any mass lies below
    /// the horizon, `side²` of the lower one. Densities per steradian, per channel.
    cells: Box<[[f32; 3]]>,
}

impl DirectionTable {
    /// The table of the masses `points` (world direction, per-channel probability) in the
    /// frame `frame`; each channel's masses should sum to one (or zero for an empty
    /// channel).
    pub fn from_masses(
        frame: Frame,
        side: usize,
        totals: Rgb,
        points: impl IntoIterator<Item = (Vec3, [f32; 3])>,
    ) -> Self {
        let n = side * side;
        let mut mass = vec![[0.0f64; 3]; 2 * n];
        let mut below = false;
        for (w, m) in points {
            let local = frame.to_local(w);
            let (cell, lower) = cell_of(local, side);
            below |= lower;
            let c = &mut mass[cell + if lower { n } else { 0 }];
            for ch in 0..3 {
                c[ch] += m[ch] as f64;
            }
        }
        let omega = cell_solid_angles_cached(side);
        let len = if below { 2 * n } else { n };
        let cells = (0..len)
            .map(|i| {
                let o = omega[i % n] as f64;
                if o > 1e-12 {
                    mass[i].map(|m| (m / o) as f32)
                } else {
                    [0.0; 3]
                }
            })
            .collect();
        DirectionTable {
            frame,
            side: side as u32,
            totals,
            cells,
        }
    }

    /// Per-channel totals of the distribution tabulated.
    #[inline]
    pub fn channel_totals(&self) -> Rgb {
        self.totals
    }

    /// The tabulated density per steradian of the world direction `wi` (unit) under `mix`.
    #[inline]
    pub fn pdf(&self, mix: &ChannelMix, wi: Vec3) -> f32 {
        let side = self.side as usize;
        let (cell, lower) = cell_of(self.frame.to_local(wi), side);
        let i = cell + if lower { side * side } else { 0 };
        match self.cells.get(i) {
            Some(d) => mix.0[0] * d[0] + mix.0[1] * d[1] + mix.0[2] * d[2],
            None => 0.0,
        }
    }

    pub fn heap_bytes(&self) -> usize {
        self.cells.len() * std::mem::size_of::<[f32; 3]>()
    }
}

/// The cell of a local direction on its hemisphere's grid, and whether it is the lower one.
#[inline]
fn cell_of(local: Vec3, side: usize) -> (usize, bool) {
    let (i, j) = cell(local, side);
    (j * side + i, local.z < 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::PI;

    /// A uniform density over the upper hemisphere (mass spread evenly over many points)
    /// reads about 1 / 2π everywhere above the horizon and 0 below it.
    #[test]
    fn a_uniform_hemisphere_tabulates_to_its_density() {
        let frame = Frame::from_z(Vec3::new(0.3, -0.2, 0.9).normalize());
        // Stratified points uniform in solid angle on the upper hemisphere.
        let (nu, nv) = (400, 400);
        let m = 1.0 / (nu * nv) as f32;
        let pts = (0..nu).flat_map(move |a| {
            (0..nv).map(move |b| {
                let z = (a as f32 + 0.5) / nu as f32;
                let phi = 2.0 * PI * (b as f32 + 0.5) / nv as f32;
                let r = (1.0 - z * z).sqrt();
                let local = Vec3::new(r * phi.cos(), r * phi.sin(), z);
                (frame.to_world(local), [m, m, m])
            })
        });
        let t = DirectionTable::from_masses(frame, 8, Rgb::ONE, pts);
        let mix = ChannelMix([1.0 / 3.0; 3]);
        // Cells away from the rim (where the grid cells are cut by the disc and the
        // stratification is coarse) hold 1/2π to within 3%.
        for local in [
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(0.3, 0.2, 0.93),
            Vec3::new(-0.5, 0.4, 0.77),
        ] {
            let p = t.pdf(&mix, frame.to_world(local.normalize()));
            assert!(
                (p * 2.0 * PI - 1.0).abs() < 0.03,
                "density {p} at {local:?}, expected {}",
                1.0 / (2.0 * PI)
            );
        }
        assert_eq!(t.pdf(&mix, frame.to_world(Vec3::new(0.1, 0.1, -0.99))), 0.0);
    }
}
