//! A CWBVH leaf's triangles side by side, tested at once: each leaf (at most
//! [`LEAF_TRIANGLES`] triangles) gets a block of its triangles' vertices and edges in
//! four-lane vectors, structure of arrays, as Embree tests a leaf's triangles together
//! (its `Triangle4`). One block test is one ray against every triangle of the leaf: the
//! same Möller-Trumbore operations as [`TriangleGeom::intersect_range`], in the same order
//! on each lane, so a lane's distance and barycentrics are those of the one-at-a-time test
//! bit for bit (no fused multiply-add in either), and the closest of the lanes is the hit
//! the one-at-a-time loop keeps (the first of the least distance).
//!
//! The leaves are renumbered so that a leaf's first triangle is three times its block's
//! index: obvhs' nodes address a leaf's triangles by a base per node and an offset per
//! child below 24, and a node's eight leaves at most at offsets 0, 3, ..., 21 fit
//! ([`into_blocks`]).

use crate::scene::geometry::TriangleGeom;
use glam::{Vec3, Vec4};
use obvhs::cwbvh::node::CwBvhNode;

/// The most triangles an obvhs CWBVH leaf holds (three bits of unary count).
pub const LEAF_TRIANGLES: usize = 3;

/// One leaf's triangles, lane `i` the `i`-th, lanes without a triangle NaN (they never hit).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct TriangleBlock {
    /// `p0`, `e1`, `e2` of [`TriangleGeom`], per axis.
    p0: [Vec4; 3],
    e1: [Vec4; 3],
    e2: [Vec4; 3],
}

impl TriangleBlock {
    /// The block of `tris` (at most [`LEAF_TRIANGLES`]).
    pub fn new(tris: &[TriangleGeom]) -> Self {
        assert!(
            tris.len() <= LEAF_TRIANGLES,
            "{} triangles in a leaf",
            tris.len()
        );
        let lanes = |v: &dyn Fn(&TriangleGeom) -> Vec3| -> [Vec4; 3] {
            std::array::from_fn(|axis| {
                Vec4::from_array(std::array::from_fn(|i| {
                    tris.get(i).map_or(f32::NAN, |t| v(t)[axis])
                }))
            })
        };
        TriangleBlock {
            p0: lanes(&|t| t.p0),
            e1: lanes(&|t| t.e1),
            e2: lanes(&|t| t.e2),
        }
    }

    /// The lanes whose triangle the ray `origin + t dir` meets within `t_min < t < t_max`
    /// (bit `i` for lane `i`), and each lane's `t`, `b1`, `b2`:
    /// [`TriangleGeom::intersect_range`] on four lanes.
    #[inline(always)]
    fn hits(&self, origin: Vec3, dir: Vec3, t_min: f32, t_max: f32) -> (u32, [Vec4; 3]) {
        let [dx, dy, dz] = [dir.x, dir.y, dir.z].map(Vec4::splat);
        let [e1x, e1y, e1z] = self.e1;
        let [e2x, e2y, e2z] = self.e2;
        // pvec = dir x e2 (glam's `cross`, term by term).
        let px = dy * e2z - e2y * dz;
        let py = dz * e2x - e2z * dx;
        let pz = dx * e2y - e2x * dy;
        let det = e1x * px + e1y * py + e1z * pz;
        let inv_det = Vec4::ONE / det;
        let tx = Vec4::splat(origin.x) - self.p0[0];
        let ty = Vec4::splat(origin.y) - self.p0[1];
        let tz = Vec4::splat(origin.z) - self.p0[2];
        // qvec = tvec x e1.
        let qx = ty * e1z - e1y * tz;
        let qy = tz * e1x - e1z * tx;
        let qz = tx * e1y - e1x * ty;
        let b1 = (tx * px + ty * py + tz * pz) * inv_det;
        let b2 = (dx * qx + dy * qy + dz * qz) * inv_det;
        let t = (e2x * qx + e2y * qy + e2z * qz) * inv_det;
        let hit = b1.cmpge(Vec4::ZERO)
            & b2.cmpge(Vec4::ZERO)
            & (b1 + b2).cmple(Vec4::ONE)
            & t.cmpgt(Vec4::splat(t_min))
            & t.cmplt(Vec4::splat(t_max));
        (hit.bitmask(), [t, b1, b2])
    }

    /// The closest of the block's triangles the ray meets within `t_min < t < t_max`: its
    /// lane, `t`, `b1`, `b2` (the first lane of the least `t`, as a loop over the lanes that
    /// accepts only a closer hit keeps).
    #[inline(always)]
    pub fn closest(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_min: f32,
        t_max: f32,
    ) -> Option<(usize, f32, f32, f32)> {
        let (mut mask, [t, b1, b2]) = self.hits(origin, dir, t_min, t_max);
        if mask == 0 {
            return None;
        }
        let t = t.to_array();
        let mut best = mask.trailing_zeros() as usize;
        mask &= mask - 1;
        while mask != 0 {
            let lane = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            if t[lane] < t[best] {
                best = lane;
            }
        }
        Some((best, t[best], b1[best], b2[best]))
    }

    /// Whether any of the block's triangles meets the ray within `t_min < t < t_max`.
    #[inline(always)]
    pub fn any(&self, origin: Vec3, dir: Vec3, t_min: f32, t_max: f32) -> bool {
        self.hits(origin, dir, t_min, t_max).0 != 0
    }
}

/// Renumbers the leaves of `nodes` so that each leaf's first triangle is
/// `LEAF_TRIANGLES` times its block's index, and returns the blocks; `primitive_indices`
/// (the triangle of each position, as obvhs leaves it) becomes the triangle of each lane,
/// `u32::MAX` for a lane without one. `triangle(i)` is triangle `i` of the scene. A node's
/// leaves take consecutive blocks in slot order.
pub fn into_blocks(
    nodes: &mut [CwBvhNode],
    primitive_indices: &mut Vec<u32>,
    triangle: impl Fn(u32) -> TriangleGeom,
) -> Vec<TriangleBlock> {
    let mut blocks = Vec::new();
    let mut lanes = Vec::new();
    for node in nodes.iter_mut() {
        let base = blocks.len();
        let mut k = 0;
        for slot in 0..8 {
            if node.is_child_empty(slot) || !node.is_leaf(slot) {
                continue;
            }
            let (first, count) = node.child_primitives(slot);
            let ids = &primitive_indices[first as usize..(first + count) as usize];
            let mut tris = [triangle(ids[0]); LEAF_TRIANGLES];
            for (t, &i) in tris.iter_mut().zip(ids).skip(1) {
                *t = triangle(i);
            }
            blocks.push(TriangleBlock::new(&tris[..ids.len()]));
            lanes.extend((0..LEAF_TRIANGLES).map(|i| ids.get(i).copied().unwrap_or(u32::MAX)));
            // The count's unary bits stay; the offset is the block's within the node's.
            let offset = (LEAF_TRIANGLES * k) as u8;
            debug_assert!(offset < 24);
            node.child_meta[slot] = (node.child_meta[slot] & 0b1110_0000) | offset;
            k += 1;
        }
        node.primitive_base_idx = (LEAF_TRIANGLES * base) as u32;
    }
    *primitive_indices = lanes;
    blocks
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;
    use crate::sampling::sample_uniform_sphere;

    /// A block of one, two or three random triangles finds, for random rays, what a loop
    /// over its triangles with [`TriangleGeom::intersect_range`] finds, bit for bit: the
    /// triangle (the first of the least distance), `t`, `b1`, `b2`; and `any` agrees. Half
    /// of the blocks repeat a triangle, so that ties are tested.
    #[test]
    fn a_block_finds_what_a_loop_over_its_triangles_finds() {
        let mut rng = Rng::new(41, 0, 0);
        let p = |rng: &mut Rng| Vec3::new(rng.uniform(), rng.uniform(), rng.uniform());
        let mut hits = 0;
        for i in 0..20_000 {
            let n = 1 + i % LEAF_TRIANGLES;
            let mut tris: Vec<TriangleGeom> = (0..n)
                .map(|_| {
                    let c = p(&mut rng) * 2.0;
                    TriangleGeom::new(c, c + p(&mut rng) - 0.5, c + p(&mut rng) - 0.5)
                })
                .collect();
            if i % 2 == 1 && n > 1 {
                tris[n - 1] = tris[0];
            }
            let block = TriangleBlock::new(&tris);
            // From a random point, toward a point near one of the triangles (or anywhere).
            let o = p(&mut rng) * 4.0 - 1.0;
            let aim = &tris[i % n];
            let d = if i % 5 == 0 {
                sample_uniform_sphere(rng.uniform2())
            } else {
                let (u, v) = (rng.uniform() * 0.8, rng.uniform() * 0.8);
                (aim.point(u, v * (1.0 - u)) - o).normalize()
            };
            let (t_min, t_max) = (1e-4, if i % 3 == 0 { 1.0 } else { f32::INFINITY });
            let mut expected = None;
            let mut end = t_max;
            for (lane, tri) in tris.iter().enumerate() {
                if let Some((t, b1, b2)) = tri.intersect_range(o, d, t_min, end) {
                    end = t;
                    expected = Some((lane, t, b1, b2));
                }
            }
            let bits = |h: Option<(usize, f32, f32, f32)>| {
                h.map(|(l, t, b1, b2)| (l, [t, b1, b2].map(f32::to_bits)))
            };
            assert_eq!(
                bits(block.closest(o, d, t_min, t_max)),
                bits(expected),
                "ray {i}"
            );
            assert_eq!(block.any(o, d, t_min, t_max), expected.is_some(), "ray {i}");
            hits += expected.is_some() as usize;
        }
        assert!(hits > 10_000, "{hits} hits");
    }
}
