//! The acceleration structure: a compressed wide BVH (CWBVH, Ylitie et al. 2017) built by
//! `obvhs` over the scene's triangles. Each leaf's triangles are stored together, in a
//! block of four-lane vectors, and tested at once ([`crate::scene::triangle_block`]).
//!
//! The node test culls boxes the ray leaves before `t = 1e-4` (obvhs' fixed epsilon, kept
//! so that the same boxes are entered), which would miss surfaces closer than that to a
//! ray's origin: in a corner, a ray leaving one wall could pass through the next. Every
//! query therefore starts
//! [`ORIGIN_BACKOFF`] behind its origin and accepts only triangles beyond that distance, so
//! every hit in front of the true origin lies in boxes the node test keeps. Directions have
//! their negative zeros made positive (see [`canonical_zeros`]).
//!
//! The walks are [`crate::scene::cwbvh_walk`]'s: children near to far by the distance at
//! which the ray enters their boxes, a pending child dropped once the closest hit lies
//! before its box.
//!
//! Shadow rays visit inner children near first, as closest hits do, or far-reaching first
//! ([`crate::scene::shadow_order`]), whichever tests fewer nodes and triangles on the
//! scene's own shadow rays ([`Bvh::choose_shadow_order`]).

use crate::scene::cwbvh_walk::{MAX_TRIANGLES, any_hit, closest_hit, stack_entries, with_stack};
use crate::scene::geometry::TriangleGeom;
use crate::scene::shadow_order::{ShadowOrder, Toward};
use crate::scene::triangle_block::{TriangleBlock, into_blocks};
use glam::{Vec3, Vec3A};
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

/// How far behind its origin a query ray starts (more than the node test's
/// [`NODE_EPSILON`](crate::scene::cwbvh_walk::NODE_EPSILON)).
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

pub struct Bvh {
    bvh: CwBvh,
    /// The order [`Bvh::unoccluded`] takes, by [`Toward`].
    shadow_orders: [ShadowOrder; 2],
    /// The leaves' triangles, a block per leaf ([`into_blocks`]): lane `i` of block `b` is
    /// triangle `bvh.primitive_indices[3 b + i]`.
    blocks: Vec<TriangleBlock>,
    /// The entries a walk's stack needs ([`stack_entries`]).
    stack_entries: usize,
    /// Whether this CPU runs the walks compiled for x86-64-v3 ([`wide_walks`]).
    wide: bool,
}

/// Whether the CPU has what the walks compiled for x86-64-v3 use (AVX2, BMI1/2, LZCNT;
/// every x86-64 CPU since 2013-2015): the release build targets x86-64-v2
/// (`.cargo/config.toml`), and the walks, most of a ray's time, are compiled a second time
/// with these features (VEX encodings of the node test's SSE4.1 operations, `tzcnt` for the
/// child masks) and chosen here at run time. No FMA: the results are those of the v2 walks,
/// bit for bit. `FOOTPRINT_WIDE_WALKS=0` keeps the v2 walks (for measuring the difference).
fn wide_walks() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::env::var("FOOTPRINT_WIDE_WALKS").map_or(true, |v| v != "0")
            && std::arch::is_x86_feature_detected!("avx2")
            && std::arch::is_x86_feature_detected!("bmi1")
            && std::arch::is_x86_feature_detected!("bmi2")
            && std::arch::is_x86_feature_detected!("lzcnt")
    }
    #[cfg(not(target_arch = "x86_64"))]
    false
}

impl Bvh {
    /// Builds the BVH over `triangles` (at least one): obvhs' `medium_build` (PLOC with
    /// reinsertion) with its spatial pre-splits, which give a triangle whose box is large
    /// several tight boxes over its parts (a leaf may then list a triangle another leaf lists
    /// too). Long thin triangles, a lamp shade's fan, otherwise overlap in boxes that every
    /// ray near them enters: Veach Bidir's next-event rays test 21 triangles each without
    /// the splits (docs/measurements/speed.md).
    pub fn build(triangles: &[TriangleGeom]) -> Self {
        assert!(!triangles.is_empty(), "a BVH needs at least one triangle");
        assert!(
            triangles.len() < MAX_TRIANGLES,
            "the CWBVH holds fewer than 2^29 triangles ({} given)",
            triangles.len()
        );
        let tris: Vec<BvhTriangle> = triangles
            .iter()
            .map(|t| BvhTriangle {
                v0: Vec3A::from(t.p0),
                v1: Vec3A::from(t.p0 + t.e1),
                v2: Vec3A::from(t.p0 + t.e2),
            })
            .collect();
        let mut bvh = build_cwbvh_from_tris(
            &tris,
            BvhBuildParams {
                pre_split: true,
                ..BvhBuildParams::medium_build()
            },
            &mut Duration::default(),
        );
        // The leaves address the list of references, which the pre-splits lengthen.
        assert!(
            bvh.primitive_indices.len() < MAX_TRIANGLES,
            "the CWBVH holds fewer than 2^29 triangle references ({} after pre-splits)",
            bvh.primitive_indices.len()
        );
        let blocks = into_blocks(&mut bvh.nodes, &mut bvh.primitive_indices, |i| {
            triangles[i as usize]
        });
        assert!(
            bvh.primitive_indices.len() < MAX_TRIANGLES,
            "the CWBVH holds fewer than 2^29 triangle lanes ({} in the leaves' blocks)",
            bvh.primitive_indices.len()
        );
        Bvh {
            stack_entries: stack_entries(&bvh.nodes),
            bvh,
            shadow_orders: [ShadowOrder::NearFirst; 2],
            blocks,
            wide: wide_walks(),
        }
    }

    /// Closest hit along `origin + t dir`, `0 < t < t_max`.
    #[inline]
    pub fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<BvhHit> {
        #[cfg(target_arch = "x86_64")]
        if self.wide {
            // SAFETY: `wide` is set only where the CPU has the features (`wide_walks`).
            return unsafe { self.intersect_wide(origin, dir, t_max) };
        }
        self.intersect_walk(origin, dir, t_max)
    }

    /// [`Bvh::intersect`] compiled for x86-64-v3 ([`wide_walks`]).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt")]
    unsafe fn intersect_wide(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<BvhHit> {
        self.intersect_walk(origin, dir, t_max)
    }

    #[inline(always)]
    fn intersect_walk(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<BvhHit> {
        let (start, dir, mut ray) = query_ray(origin, dir, t_max);
        let hit = with_stack(
            self.stack_entries,
            #[inline(always)]
            |stack| {
                closest_hit(
                    &self.bvh.nodes,
                    &self.blocks,
                    (start, dir, ORIGIN_BACKOFF),
                    &mut ray,
                    stack,
                )
            },
        );
        hit.map(|(id, b1, b2)| BvhHit {
            triangle: self.bvh.primitive_indices[id as usize],
            t: (ray.tmax - ORIGIN_BACKOFF).max(f32::MIN_POSITIVE),
            b1,
            b2,
        })
    }

    /// True when nothing blocks `origin + t dir` for `0 < t < t_max` (a shadow ray
    /// `toward` a light or the camera), in the order [`Bvh::choose_shadow_order`] chose for
    /// it (near first until then). The answer is the same in either order; only the work
    /// differs.
    #[inline]
    pub fn unoccluded(&self, toward: Toward, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        let order = self.shadow_orders[toward as usize];
        #[cfg(target_arch = "x86_64")]
        if self.wide {
            // SAFETY: `wide` is set only where the CPU has the features (`wide_walks`).
            return unsafe { self.unoccluded_wide(order, origin, dir, t_max) };
        }
        self.unoccluded_in(order, origin, dir, t_max).0
    }

    /// [`Bvh::unoccluded`] compiled for x86-64-v3 ([`wide_walks`]).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt")]
    unsafe fn unoccluded_wide(&self, order: ShadowOrder, o: Vec3, d: Vec3, t_max: f32) -> bool {
        self.unoccluded_in(order, o, d, t_max).0
    }

    /// Chooses the order of [`Bvh::unoccluded`] for shadow rays `toward` a light or the
    /// camera: the one that tests fewer nodes and triangles over `segments` (origin,
    /// direction, length: a sample of the scene's shadow rays of that kind), near first on a
    /// tie. Returns the choice and the nodes and triangles tested per segment in each order
    /// (as [`ShadowOrder::ALL`] lists them).
    pub fn choose_shadow_order(
        &mut self,
        toward: Toward,
        segments: &[(Vec3, Vec3, f32)],
    ) -> (ShadowOrder, [f64; 2]) {
        let mut visits = [0u64; 2];
        for &(o, d, t) in segments {
            for (v, order) in visits.iter_mut().zip(ShadowOrder::ALL) {
                *v += self.unoccluded_in(order, o, d, t).1 as u64;
            }
        }
        // The first of the fewest (near first on a tie).
        let best = (1..visits.len()).fold(0, |b, i| if visits[i] < visits[b] { i } else { b });
        let order = ShadowOrder::ALL[best];
        self.shadow_orders[toward as usize] = order;
        let n = segments.len().max(1) as f64;
        (order, visits.map(|v| v as f64 / n))
    }

    /// The order shadow rays `toward` a light or the camera take.
    pub fn shadow_order(&self, toward: Toward) -> ShadowOrder {
        self.shadow_orders[toward as usize]
    }

    /// [`Bvh::unoccluded`] in the given order, and the nodes and triangles it tested.
    #[inline(always)]
    pub fn unoccluded_in(
        &self,
        order: ShadowOrder,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
    ) -> (bool, u32) {
        let (start, dir, ray) = query_ray(origin, dir, t_max);
        let query = (start, dir, ORIGIN_BACKOFF);
        let (nodes, blocks) = (&self.bvh.nodes, &self.blocks);
        let (blocked, tested) = with_stack(
            self.stack_entries,
            #[inline(always)]
            |stack| match order {
                ShadowOrder::NearFirst => any_hit::<false>(nodes, blocks, query, &ray, stack),
                ShadowOrder::FarReaching => any_hit::<true>(nodes, blocks, query, &ray, stack),
            },
        );
        (!blocked, tested)
    }

    pub fn node_count(&self) -> usize {
        self.bvh.nodes.len()
    }

    /// Bytes held by the nodes, the leaves' triangle blocks and the index map.
    pub fn memory_bytes(&self) -> usize {
        self.bvh.nodes.len() * std::mem::size_of::<CwBvhNode>()
            + self.blocks.len() * std::mem::size_of::<TriangleBlock>()
            + self.bvh.primitive_indices.len() * 4
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    /// `n` random triangles in a 10 m cube, triangle `i` spanning about `size(i)`.
    fn soup(rng: &mut Rng, n: usize, size: impl Fn(usize) -> f32) -> Vec<TriangleGeom> {
        let mut p = || Vec3::new(rng.uniform(), rng.uniform(), rng.uniform());
        (0..n)
            .map(|i| {
                let c = p() * 10.0;
                TriangleGeom::new(c, c + (p() - 0.5) * size(i), c + (p() - 0.5) * size(i))
            })
            .collect()
    }

    /// The walks on a stack of exactly `stack_entries` entries (a slice: one more would
    /// panic) over a soup of 3000 triangles of mixed sizes find what a loop over every
    /// triangle finds, for 2000 random rays: the closest hit's distance, and whether
    /// anything blocks a segment, in either order. The large triangles are pre-split, so
    /// that leaves list some triangles more than once.
    #[test]
    fn walks_find_what_a_loop_over_every_triangle_finds() {
        use crate::sampling::sample_uniform_sphere;
        use crate::scene::cwbvh_walk::Pending;
        let mut rng = Rng::new(33, 0, 0);
        let tris = soup(&mut rng, 3000, |i| if i % 10 == 0 { 4.0 } else { 0.3 });
        let bvh = Bvh::build(&tris);
        let references = bvh
            .bvh
            .primitive_indices
            .iter()
            .filter(|&&i| i != u32::MAX)
            .count();
        assert!(
            references > tris.len(),
            "no triangle pre-split: {references} references"
        );
        let mut stack = vec![Pending::uninit(); bvh.stack_entries];
        let (mut hits, mut blocked) = (0, 0);
        for i in 0..2000 {
            let o = Vec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * 12.0 - 1.0;
            let d = sample_uniform_sphere(rng.uniform2());
            let t_max = if i % 2 == 0 { f32::INFINITY } else { 3.0 };
            let expected = tris
                .iter()
                .filter_map(|t| t.intersect_range(o, d, 0.0, t_max).map(|h| h.0))
                .fold(None, |best: Option<f32>, t| {
                    Some(best.map_or(t, |b| b.min(t)))
                });
            let query = (o, d, 0.0);
            let mut ray = BvhRay::new(Vec3A::from(o), Vec3A::from(d), 0.0, t_max);
            let found = closest_hit(&bvh.bvh.nodes, &bvh.blocks, query, &mut ray, &mut stack);
            match (expected, found) {
                (None, None) => {}
                (Some(t), Some(_)) => {
                    assert_eq!(ray.tmax, t, "ray {i}");
                    hits += 1;
                }
                (e, f) => panic!("ray {i}: every triangle {e:?}, the walk {f:?}"),
            }
            let ray = BvhRay::new(Vec3A::from(o), Vec3A::from(d), 0.0, t_max);
            let nodes = &bvh.bvh.nodes;
            let near_first = any_hit::<false>(nodes, &bvh.blocks, query, &ray, &mut stack);
            let far_reaching = any_hit::<true>(nodes, &bvh.blocks, query, &ray, &mut stack);
            assert_eq!(near_first.0, expected.is_some(), "ray {i}");
            assert_eq!(far_reaching.0, expected.is_some(), "ray {i}");
            blocked += expected.is_some() as usize;
        }
        assert!(
            hits > 500 && blocked < 1900,
            "{hits} hits, {blocked} blocked"
        );
    }

    /// Where the CPU runs them, the walks compiled for x86-64-v3 ([`wide_walks`]) find what
    /// the v2 walks find, bit for bit: the closest hit's triangle, distance and barycentrics,
    /// and whether a segment is blocked toward a light and the camera, for 2000 random rays
    /// over a soup of 3000 triangles. Without those features the test has nothing to compare
    /// and says so.
    #[test]
    fn the_wide_walks_find_what_the_v2_walks_find() {
        use crate::sampling::sample_uniform_sphere;
        if !wide_walks() {
            eprintln!("skipped: this CPU has no x86-64-v3 walks (or FOOTPRINT_WIDE_WALKS=0)");
            return;
        }
        let mut rng = Rng::new(34, 0, 0);
        let tris = soup(&mut rng, 3000, |i| if i % 10 == 0 { 4.0 } else { 0.3 });
        let wide = Bvh::build(&tris);
        assert!(wide.wide);
        let v2 = Bvh {
            wide: false,
            ..Bvh::build(&tris)
        };
        let mut hits = 0;
        for i in 0..2000 {
            let o = Vec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * 12.0 - 1.0;
            let d = sample_uniform_sphere(rng.uniform2());
            let t_max = if i % 2 == 0 { f32::INFINITY } else { 3.0 };
            let bits =
                |h: Option<BvhHit>| h.map(|h| (h.triangle, [h.t, h.b1, h.b2].map(f32::to_bits)));
            let (a, b) = (wide.intersect(o, d, t_max), v2.intersect(o, d, t_max));
            hits += a.is_some() as usize;
            assert_eq!(bits(a), bits(b), "ray {i}");
            for toward in [Toward::Light, Toward::Camera] {
                assert_eq!(
                    wide.unoccluded(toward, o, d, t_max),
                    v2.unoccluded(toward, o, d, t_max),
                    "ray {i}"
                );
            }
        }
        assert!(hits > 500, "{hits} hits");
    }
}
