//! The paper's tangent-plane grid (§2.2, the `k_g` grid of eq. 5): a hemisphere's directions
//! projected onto the tangent plane of the side normal, `side x side` cells over `[-1, 1]²`.
//! The footprints count particles per cell on it, and the combined image's direction tables
//! hold densities per cell of it.

use glam::Vec3;
use std::sync::OnceLock;

/// The cell `(i, j)` (column, row) of a local direction's tangent-plane projection; the
/// cell's index in a row-major grid is `j * side + i`.
#[inline]
pub fn cell(local: Vec3, side: usize) -> (usize, usize) {
    let s = side as f32;
    let i = (((local.x + 1.0) * 0.5 * s) as isize).clamp(0, side as isize - 1) as usize;
    let j = (((local.y + 1.0) * 0.5 * s) as isize).clamp(0, side as isize - 1) as usize;
    (i, j)
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

/// The cell solid angles for a grid side, computed once per side and kept.
pub(crate) fn cell_solid_angles_cached(side: usize) -> &'static [f32] {
    static CACHE: OnceLock<std::sync::Mutex<Vec<(usize, &'static [f32])>>> = OnceLock::new();
    let cache = CACHE.get_or_init(Default::default);
    let mut c = cache.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, w)) = c.iter().find(|(s, _)| *s == side) {
        return w;
    }
    let w: &'static [f32] = Box::leak(cell_solid_angles(side).into_boxed_slice());
    c.push((side, w));
    w
}
