//! The acceleration structure: a compressed wide BVH (CWBVH, Ylitie et al. 2017) built and
//! traversed by `obvhs`, over the scene's triangles. Triangles are stored in the BVH's leaf
//! order so a leaf's triangles are contiguous in memory.
//!
//! obvhs culls CWBVH nodes whose box the ray leaves before `t = 1e-4` (a fixed epsilon in its
//! node test), which would miss surfaces closer than that to a ray's origin: in a corner, a
//! ray leaving one wall could pass through the next. Every query therefore starts
//! [`ORIGIN_BACKOFF`] behind its origin and accepts only triangles beyond that distance, so
//! every hit in front of the true origin lies in boxes the node test keeps. Directions have
//! their negative zeros made positive (see [`canonical_zeros`]).
//!
//! The traversal is obvhs' (`obvhs::traverse!`) with a node test of our own,
//! [`child_hits`]: the same slab arithmetic as obvhs' `intersect_ray_simd`, so the same
//! children are entered and every image is the same bit for bit, but the mask of entered
//! children is assembled without a branch per child (obvhs tests each of the eight lanes
//! with a branch the ray's data decides, which mispredicts).

use crate::scene::geometry::TriangleGeom;
use glam::{UVec2, Vec3, Vec3A};
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::node::CwBvhNode;
use obvhs::ray::Ray as BvhRay;
use obvhs::triangle::Triangle as BvhTriangle;
use obvhs::{BvhBuildParams, cwbvh::builder::build_cwbvh_from_tris};
use std::time::Duration;

/// A closest hit: the original triangle index, distance and barycentrics.
#[derive(Clone, Copy, Debug)]
pub struct BvhHit {
    pub triangle: u32,
    pub t: f32,
    pub b1: f32,
    pub b2: f32,
}

/// `-0.0` components become `+0.0`: obvhs takes the slab order from `d < 0` but the
/// inverse from the sign bit, so a `-0.0` component would swap a node's slabs and miss it.
#[inline(always)]
fn canonical_zeros(d: Vec3) -> Vec3 {
    d + Vec3::ZERO
}

/// How far behind its origin a query ray starts (more than the node test's [`NODE_EPSILON`]).
pub const ORIGIN_BACKOFF: f32 = 4e-4;

/// A query's ray as the traversal takes it: the direction without negative zeros, the
/// start [`ORIGIN_BACKOFF`] behind `origin`, and the end moved back as far.
#[inline(always)]
fn query_ray(origin: Vec3, dir: Vec3, t_max: f32) -> (Vec3, Vec3, BvhRay) {
    let dir = canonical_zeros(dir);
    let start = origin - ORIGIN_BACKOFF * dir;
    let ray = BvhRay::new(
        Vec3A::from(start),
        Vec3A::from(dir),
        0.0,
        t_max + ORIGIN_BACKOFF,
    );
    (start, dir, ray)
}

/// Boxes the ray leaves before this distance are culled (obvhs' own node test's constant,
/// kept so that the same boxes are entered).
const NODE_EPSILON: f32 = 1e-4;

/// The traversal's mask of the children of `node` the ray enters within `[NODE_EPSILON,
/// ray.tmax]` (obvhs' `CwBvhNode::intersect_ray` contract: for an inner child its bit in
/// the top byte, for a leaf its triangles' bits in the low 24).
///
/// The slab test is obvhs' `intersect_ray_simd` operation for operation: the quantised
/// planes (bytes) widened to floats, scaled by the node's power-of-two extent and offset,
/// four children at a time, so the same children are entered. Each entered child's bits
/// are `child_bits << bit_index`, computed for four lanes at once: `2^bit_index` is built
/// as a float's exponent and converted (2^31 converts to `0x8000_0000`, the one
/// out-of-range case, whose result is that same bit pattern), multiplied by the child bits
/// (at most 7, below bit 24 for leaves; 1 for inner children), masked with the slab test's
/// lanes and or-ed across lanes.
#[cfg(all(target_arch = "x86_64", target_feature = "sse4.1"))]
#[inline(always)]
fn child_hits(node: &CwBvhNode, ray: &BvhRay, oct_inv4: u32) -> u32 {
    use std::arch::x86_64::*;
    let extent = Vec3A::new(
        f32::from_bits((node.e[0] as u32) << 23),
        f32::from_bits((node.e[1] as u32) << 23),
        f32::from_bits((node.e[2] as u32) << 23),
    );
    let scale = extent * ray.inv_direction;
    let offset = (Vec3A::from(node.p) - ray.origin) * ray.inv_direction;
    let (child_bits8, bit_index8) = node.get_child_and_index_bits(oct_inv4);
    // SAFETY: SSE4.1 is enabled for this build (the cfg above); the loads read plain
    // integers out of the node's byte arrays.
    unsafe {
        let planes = |bytes: &[u8; 8], half: usize| -> __m128 {
            let word = u32::from_le_bytes([
                bytes[4 * half],
                bytes[4 * half + 1],
                bytes[4 * half + 2],
                bytes[4 * half + 3],
            ]);
            _mm_cvtepi32_ps(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(word as i32)))
        };
        let lanes = |x: u64, half: usize| -> __m128i {
            _mm_cvtepu8_epi32(_mm_cvtsi32_si128((x >> (32 * half)) as u32 as i32))
        };
        let (sx, sy, sz) = (
            _mm_set1_ps(scale.x),
            _mm_set1_ps(scale.y),
            _mm_set1_ps(scale.z),
        );
        let (ox, oy, oz) = (
            _mm_set1_ps(offset.x),
            _mm_set1_ps(offset.y),
            _mm_set1_ps(offset.z),
        );
        let near_far = |lo: __m128, hi: __m128, negative: bool| {
            if negative { (hi, lo) } else { (lo, hi) }
        };
        let mut hits = _mm_setzero_si128();
        for half in 0..2 {
            let (nx, fx) = near_far(
                planes(&node.child_min_x, half),
                planes(&node.child_max_x, half),
                ray.direction.x < 0.0,
            );
            let (ny, fy) = near_far(
                planes(&node.child_min_y, half),
                planes(&node.child_max_y, half),
                ray.direction.y < 0.0,
            );
            let (nz, fz) = near_far(
                planes(&node.child_min_z, half),
                planes(&node.child_max_z, half),
                ray.direction.z < 0.0,
            );
            let t_near = _mm_max_ps(
                _mm_add_ps(_mm_mul_ps(nx, sx), ox),
                _mm_max_ps(
                    _mm_add_ps(_mm_mul_ps(ny, sy), oy),
                    _mm_add_ps(_mm_mul_ps(nz, sz), oz),
                ),
            );
            let t_far = _mm_min_ps(
                _mm_add_ps(_mm_mul_ps(fx, sx), ox),
                _mm_min_ps(
                    _mm_add_ps(_mm_mul_ps(fy, sy), oy),
                    _mm_add_ps(_mm_mul_ps(fz, sz), oz),
                ),
            );
            let t_near = _mm_max_ps(t_near, _mm_set1_ps(NODE_EPSILON));
            let t_far = _mm_min_ps(t_far, _mm_set1_ps(ray.tmax));
            let entered = _mm_castps_si128(_mm_cmple_ps(t_near, t_far));
            let exponent = _mm_add_epi32(lanes(bit_index8, half), _mm_set1_epi32(127));
            let pow2 = _mm_cvttps_epi32(_mm_castsi128_ps(_mm_slli_epi32(exponent, 23)));
            let bits = _mm_mullo_epi32(lanes(child_bits8, half), pow2);
            hits = _mm_or_si128(hits, _mm_and_si128(bits, entered));
        }
        let hits = _mm_or_si128(hits, _mm_shuffle_epi32(hits, 0b01_00_11_10));
        let hits = _mm_or_si128(hits, _mm_shuffle_epi32(hits, 0b10_11_00_01));
        _mm_cvtsi128_si32(hits) as u32
    }
}

/// Without SSE4.1: obvhs' own node test.
#[cfg(not(all(target_arch = "x86_64", target_feature = "sse4.1")))]
#[inline(always)]
fn child_hits(node: &CwBvhNode, ray: &BvhRay, oct_inv4: u32) -> u32 {
    node.intersect_ray(ray, oct_inv4)
}

pub struct Bvh {
    bvh: CwBvh,
    /// `ordered[i]` is triangle `original[i]`, in the BVH's primitive order.
    ordered: Vec<TriangleGeom>,
    original: Vec<u32>,
}

impl Bvh {
    /// Builds the BVH over `triangles` (at least one).
    pub fn build(triangles: &[TriangleGeom]) -> Self {
        assert!(!triangles.is_empty(), "a BVH needs at least one triangle");
        let tris: Vec<BvhTriangle> = triangles
            .iter()
            .map(|t| BvhTriangle {
                v0: Vec3A::from(t.p0),
                v1: Vec3A::from(t.p0 + t.e1),
                v2: Vec3A::from(t.p0 + t.e2),
            })
            .collect();
        let bvh = build_cwbvh_from_tris(
            &tris,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let original: Vec<u32> = bvh.primitive_indices.clone();
        let ordered = original.iter().map(|&i| triangles[i as usize]).collect();
        Bvh {
            bvh,
            ordered,
            original,
        }
    }

    /// Closest hit along `origin + t dir`, `0 < t < t_max`.
    #[inline]
    pub fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<BvhHit> {
        let (start, dir, mut ray) = query_ray(origin, dir, t_max);
        let mut best: Option<(u32, f32, f32)> = None;
        let mut state = self.bvh.new_traversal(ray.direction);
        let mut node: &CwBvhNode;
        obvhs::traverse!(
            self.bvh,
            node,
            state,
            child_hits(node, &ray, state.oct_inv4),
            {
                let id = state.primitive_id;
                // Only a t below the closest so far is accepted, and the ray's end moves
                // there: `best` is the closest candidate.
                if let Some((t, b1, b2)) =
                    self.ordered[id as usize].intersect_range(start, dir, ORIGIN_BACKOFF, ray.tmax)
                {
                    ray.tmax = t;
                    best = Some((id, b1, b2));
                }
            }
        );
        best.map(|(id, b1, b2)| BvhHit {
            triangle: self.original[id as usize],
            t: (ray.tmax - ORIGIN_BACKOFF).max(f32::MIN_POSITIVE),
            b1,
            b2,
        })
    }

    /// True when nothing blocks `origin + t dir` for `0 < t < t_max` (shadow rays).
    #[inline]
    pub fn unoccluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        let (start, dir, ray) = query_ray(origin, dir, t_max);
        let mut state = self.bvh.new_traversal(ray.direction);
        let mut node: &CwBvhNode;
        let mut clear = true;
        'traversal: {
            obvhs::traverse!(
                self.bvh,
                node,
                state,
                child_hits(node, &ray, state.oct_inv4),
                {
                    if self.ordered[state.primitive_id as usize]
                        .intersect_range(start, dir, ORIGIN_BACKOFF, ray.tmax)
                        .is_some()
                    {
                        clear = false;
                        break 'traversal;
                    }
                }
            );
        }
        clear
    }

    pub fn node_count(&self) -> usize {
        self.bvh.nodes.len()
    }

    /// Bytes held by the nodes, the reordered triangles and the index map.
    pub fn memory_bytes(&self) -> usize {
        self.bvh.nodes.len() * std::mem::size_of_val(&self.bvh.nodes[0])
            + self.ordered.len() * std::mem::size_of::<TriangleGeom>()
            + self.original.len() * 4
            + self.bvh.primitive_indices.len() * 4
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;
    use crate::sampling::sample_uniform_sphere;

    /// Our node test enters exactly the children obvhs' own does (`intersect_ray`), for
    /// every node of a BVH over a random soup of 2000 triangles and rays from random
    /// points in random directions (axis-aligned ones included, whose reciprocals are
    /// huge), with finite and infinite ends.
    #[test]
    fn node_test_enters_the_children_obvhs_enters() {
        let mut rng = Rng::new(31, 0, 0);
        let p = |rng: &mut Rng| Vec3::new(rng.uniform(), rng.uniform(), rng.uniform());
        let tris: Vec<TriangleGeom> = (0..2000)
            .map(|_| {
                let c = p(&mut rng) * 10.0;
                TriangleGeom::new(
                    c,
                    c + (p(&mut rng) - 0.5) * 0.8,
                    c + (p(&mut rng) - 0.5) * 0.8,
                )
            })
            .collect();
        let bvh = Bvh::build(&tris);
        assert!(bvh.node_count() > 50);
        let mut entered = 0usize;
        for i in 0..400 {
            let o = p(&mut rng) * 12.0 - 1.0;
            let d = match i % 8 {
                0 => Vec3::X,
                // Negative zeros in x and y (the node test reads the sign for the slab order).
                1 => -Vec3::Z,
                _ => sample_uniform_sphere(rng.uniform2()),
            };
            let t_max = if i % 2 == 0 { f32::INFINITY } else { 4.0 };
            let ray = BvhRay::new(Vec3A::from(o), Vec3A::from(d), 0.0, t_max);
            let state = bvh.bvh.new_traversal(ray.direction);
            for node in &bvh.bvh.nodes {
                let ours = child_hits(node, &ray, state.oct_inv4);
                assert_eq!(ours, node.intersect_ray(&ray, state.oct_inv4), "ray {i}");
                entered += (ours != 0) as usize;
            }
        }
        assert!(
            entered > 1000,
            "too few nodes entered ({entered}) to test anything"
        );
    }
}
