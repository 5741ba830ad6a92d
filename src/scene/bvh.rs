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

use crate::scene::geometry::TriangleGeom;
use glam::{Vec3, Vec3A};
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray as BvhRay, RayHit};
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

/// How far behind its origin a query ray starts (more than obvhs' node epsilon of 1e-4).
pub const ORIGIN_BACKOFF: f32 = 4e-4;

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
        let dir = canonical_zeros(dir);
        let start = origin - ORIGIN_BACKOFF * dir;
        let ray = BvhRay::new(
            Vec3A::from(start),
            Vec3A::from(dir),
            0.0,
            t_max + ORIGIN_BACKOFF,
        );
        let mut hit = RayHit::none();
        let mut best = (0.0f32, 0.0f32);
        let found = self.bvh.ray_traverse(ray, &mut hit, |r, id| {
            match self.ordered[id].intersect_range(start, dir, ORIGIN_BACKOFF, r.tmax) {
                Some((t, b1, b2)) => {
                    best = (b1, b2);
                    t
                }
                None => f32::INFINITY,
            }
        });
        // `best` holds the barycentrics of the last accepted (closest so far) candidate: the
        // traversal only accepts a t below the current t_max, and it passes that t_max in.
        if !found {
            return None;
        }
        let (b1, b2) = best;
        Some(BvhHit {
            triangle: self.original[hit.primitive_id as usize],
            t: (hit.t - ORIGIN_BACKOFF).max(f32::MIN_POSITIVE),
            b1,
            b2,
        })
    }

    /// True when nothing blocks `origin + t dir` for `0 < t < t_max` (shadow rays).
    #[inline]
    pub fn unoccluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        let dir = canonical_zeros(dir);
        let start = origin - ORIGIN_BACKOFF * dir;
        let ray = BvhRay::new(
            Vec3A::from(start),
            Vec3A::from(dir),
            0.0,
            t_max + ORIGIN_BACKOFF,
        );
        self.bvh.ray_traverse_miss(ray, |r, id| {
            match self.ordered[id].intersect_range(start, dir, ORIGIN_BACKOFF, r.tmax) {
                Some((t, _, _)) => t,
                None => f32::INFINITY,
            }
        })
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
