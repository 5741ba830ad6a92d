//! The acceleration structure: a compressed wide BVH (CWBVH, Ylitie et al. 2017) built by
//! `obvhs` over the scene's triangles. Triangles are stored in the BVH's leaf
//! order so a leaf's triangles are contiguous in memory.
//!
//! obvhs culls CWBVH nodes whose box the ray leaves before `t = 1e-4` (a fixed epsilon in its
//! node test), which would miss surfaces closer than that to a ray's origin: in a corner, a
//! ray leaving one wall could pass through the next. Every query therefore starts
//! [`ORIGIN_BACKOFF`] behind its origin and accepts only triangles beyond that distance, so
//! every hit in front of the true origin lies in boxes the node test keeps. Directions have
//! their negative zeros made positive (see [`canonical_zeros`]).
//!
//! The walks are [`crate::scene::cwbvh_walk`]'s: children near to far by the distance at
//! which the ray enters their boxes, a pending child dropped once the closest hit lies
//! before its box.
//!
//! Shadow rays visit inner children near first, as closest hits do, or in the order of a
//! reordered copy of the nodes (by blocking chance, [`crate::scene::shadow_order`]),
//! whichever tests fewer nodes on the scene's own shadow rays ([`Bvh::choose_shadow_order`]).

use crate::scene::cwbvh_walk::{MAX_TRIANGLES, any_hit, closest_hit, stack_entries, with_stack};
use crate::scene::geometry::TriangleGeom;
use crate::scene::shadow_order::{RTSAH_MARGIN, ShadowOrder, Toward};
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
    /// The nodes as shadow rays visit them in [`ShadowOrder::Rtsah`] (`shadow_order`);
    /// empty when neither kind of shadow ray takes that order.
    shadow_nodes: Vec<CwBvhNode>,
    /// The order [`Bvh::unoccluded`] takes, by [`Toward`].
    shadow_orders: [ShadowOrder; 2],
    /// `ordered[i]` is triangle `original[i]`, in the BVH's primitive order.
    ordered: Vec<TriangleGeom>,
    original: Vec<u32>,
    /// The entries a walk's stack needs ([`stack_entries`]).
    stack_entries: usize,
}

impl Bvh {
    /// Builds the BVH over `triangles` (at least one).
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
        let bvh = build_cwbvh_from_tris(
            &tris,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let original: Vec<u32> = bvh.primitive_indices.clone();
        let ordered: Vec<TriangleGeom> = original.iter().map(|&i| triangles[i as usize]).collect();
        let shadow_nodes = crate::scene::shadow_order::shadow_nodes(&bvh.nodes, |p| {
            0.5 * ordered[p].cross().length()
        });
        Bvh {
            stack_entries: stack_entries(&bvh.nodes),
            bvh,
            shadow_nodes,
            shadow_orders: [ShadowOrder::NearFirst; 2],
            ordered,
            original,
        }
    }

    /// Closest hit along `origin + t dir`, `0 < t < t_max`.
    #[inline]
    pub fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<BvhHit> {
        let (start, dir, mut ray) = query_ray(origin, dir, t_max);
        let hit = with_stack(self.stack_entries, |stack| {
            closest_hit(
                &self.bvh.nodes,
                &self.ordered,
                (start, dir, ORIGIN_BACKOFF),
                &mut ray,
                stack,
            )
        });
        hit.map(|(id, b1, b2)| BvhHit {
            triangle: self.original[id as usize],
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
        match self.shadow_orders[toward as usize] {
            ShadowOrder::NearFirst => self.shadow_query::<false>(origin, dir, t_max).0,
            ShadowOrder::Rtsah => {
                // Only chosen while the copy is kept (a choice made after
                // `release_unused_shadow_nodes` measures near first twice).
                debug_assert!(!self.shadow_nodes.is_empty());
                self.shadow_query::<true>(origin, dir, t_max).0
            }
        }
    }

    /// Chooses the order of [`Bvh::unoccluded`] for shadow rays `toward` a light or the
    /// camera: the one that tests fewer nodes and triangles over `segments` (origin,
    /// direction, length: a sample of the scene's shadow rays of that kind), near first on a
    /// tie or a saving of at most 10% ([`RTSAH_MARGIN`]). Returns the choice and the nodes and
    /// triangles tested per segment in each order (near first, RTSAH).
    pub fn choose_shadow_order(
        &mut self,
        toward: Toward,
        segments: &[(Vec3, Vec3, f32)],
    ) -> (ShadowOrder, [f64; 2]) {
        let mut visits = [0u64; 2];
        for &(o, d, t) in segments {
            visits[0] += self.unoccluded_in(ShadowOrder::NearFirst, o, d, t).1 as u64;
            visits[1] += self.unoccluded_in(ShadowOrder::Rtsah, o, d, t).1 as u64;
        }
        let order = if (visits[1] as f64) < RTSAH_MARGIN * visits[0] as f64 {
            ShadowOrder::Rtsah
        } else {
            ShadowOrder::NearFirst
        };
        self.shadow_orders[toward as usize] = order;
        let n = segments.len().max(1) as f64;
        (order, [visits[0] as f64 / n, visits[1] as f64 / n])
    }

    /// Frees the RTSAH copy of the nodes when neither kind of shadow ray takes that order
    /// (call after [`Bvh::choose_shadow_order`] for both kinds); [`Bvh::unoccluded_in`]
    /// then takes near first for either order.
    pub fn release_unused_shadow_nodes(&mut self) {
        if !self.shadow_orders.contains(&ShadowOrder::Rtsah) {
            self.shadow_nodes = Vec::new();
        }
    }

    /// Whether the RTSAH copy of the nodes is kept.
    pub fn keeps_shadow_nodes(&self) -> bool {
        !self.shadow_nodes.is_empty()
    }

    /// The order shadow rays `toward` a light or the camera take.
    pub fn shadow_order(&self, toward: Toward) -> ShadowOrder {
        self.shadow_orders[toward as usize]
    }

    /// [`Bvh::unoccluded`] in the given order, and the nodes and triangles it tested.
    #[inline]
    pub fn unoccluded_in(
        &self,
        order: ShadowOrder,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
    ) -> (bool, u32) {
        match order {
            ShadowOrder::Rtsah if !self.shadow_nodes.is_empty() => {
                self.shadow_query::<true>(origin, dir, t_max)
            }
            _ => self.shadow_query::<false>(origin, dir, t_max),
        }
    }

    /// The shadow-ray walk over the closest-hit nodes (near first) or over the RTSAH copy
    /// (in its stored order), and the nodes and triangles it tested.
    #[inline(always)]
    fn shadow_query<const RTSAH: bool>(&self, origin: Vec3, dir: Vec3, t_max: f32) -> (bool, u32) {
        let (start, dir, ray) = query_ray(origin, dir, t_max);
        let nodes = if RTSAH {
            &self.shadow_nodes
        } else {
            &self.bvh.nodes
        };
        let (blocked, tested) = with_stack(self.stack_entries, |stack| {
            any_hit::<RTSAH>(
                nodes,
                &self.ordered,
                (start, dir, ORIGIN_BACKOFF),
                &ray,
                stack,
            )
        });
        (!blocked, tested)
    }

    pub fn node_count(&self) -> usize {
        self.bvh.nodes.len()
    }

    /// Bytes held by the nodes (both orders'), the reordered triangles and the index map.
    pub fn memory_bytes(&self) -> usize {
        (self.bvh.nodes.len() + self.shadow_nodes.len()) * std::mem::size_of::<CwBvhNode>()
            + self.ordered.len() * std::mem::size_of::<TriangleGeom>()
            + self.original.len() * 4
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

    /// The leaves under node `i` of `nodes`: each leaf child's world box and its first
    /// primitive and count; asserts that each inner child's node has its children inside
    /// the box its slot gives it (to one quantisation step of the child's grid, the
    /// rounding of its own boxes), so that a slot cannot point at another child's node.
    fn leaves(nodes: &[CwBvhNode], i: usize, out: &mut Vec<([u32; 6], u32, u32)>) {
        let node = &nodes[i];
        for s in 0..8 {
            let meta = node.child_meta[s];
            if meta == 0 {
                continue;
            }
            if node.imask & (1 << s) != 0 {
                let child = node.child_base_idx as usize
                    + (node.imask as u32 & ((1u32 << s) - 1)).count_ones() as usize;
                let b = node.child_aabb(s);
                let c = &nodes[child];
                let tol = c.compute_extent() + 1e-5 * (1.0 + b.max.abs().max(b.min.abs()));
                for t in (0..8).filter(|&t| c.child_meta[t] != 0) {
                    let cb = c.child_aabb(t);
                    assert!(
                        (b.min - tol).cmple(cb.min).all() && cb.max.cmple(b.max + tol).all(),
                        "node {i} slot {s}: child {child}'s box {cb:?} outside {b:?}"
                    );
                }
                leaves(nodes, child, out);
            } else {
                let b = node.child_aabb(s);
                let bits = [b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z].map(f32::to_bits);
                out.push((
                    bits,
                    node.primitive_base_idx + (meta & 0x1f) as u32,
                    (meta >> 5).count_ones(),
                ));
            }
        }
    }

    /// The shadow rays' copy of the nodes is the same tree with each node's children in
    /// another order: the same leaves (boxes and triangles) under the root, each inner
    /// slot pointing at its own child's node, leaves in the lowest slots and inner children
    /// above them in every node (a soup of 3000 triangles of mixed sizes, so that nodes mix
    /// leaves and inner children).
    #[test]
    fn the_shadow_copy_holds_the_same_tree() {
        let mut rng = Rng::new(32, 0, 0);
        let tris = soup(&mut rng, 3000, |i| if i % 10 == 0 { 4.0 } else { 0.3 });
        let bvh = Bvh::build(&tris);
        assert_eq!(bvh.bvh.nodes.len(), bvh.shadow_nodes.len());
        let (mut a, mut b) = (Vec::new(), Vec::new());
        leaves(&bvh.bvh.nodes, 0, &mut a);
        leaves(&bvh.shadow_nodes, 0, &mut b);
        a.sort_unstable();
        b.sort_unstable();
        assert!(a.len() > 500, "{} leaves", a.len());
        assert_eq!(a, b);
        let mut reordered = 0;
        for (i, node) in bvh.shadow_nodes.iter().enumerate() {
            let used = node.child_meta.iter().filter(|&&m| m != 0).count();
            let inner = node.imask.count_ones() as usize;
            // Leaves in slots 0.., inner children in the slots after them, none empty between.
            assert_eq!(
                node.imask as usize,
                ((1usize << inner) - 1) << (used - inner),
                "node {i}"
            );
            assert!(node.child_meta[used..].iter().all(|&m| m == 0), "node {i}");
            let original = &bvh.bvh.nodes[i];
            reordered += (node.child_meta != original.child_meta) as usize;
        }
        assert!(reordered > 10, "only {reordered} nodes reordered");
    }

    /// The walks on a stack of exactly `stack_entries` entries (a slice: one more would
    /// panic) over a soup of 3000 triangles of mixed sizes find what a loop over every
    /// triangle finds, for 2000 random rays: the closest hit's distance, and whether
    /// anything blocks a segment, in either order.
    #[test]
    fn walks_find_what_a_loop_over_every_triangle_finds() {
        use crate::sampling::sample_uniform_sphere;
        use crate::scene::cwbvh_walk::Pending;
        let mut rng = Rng::new(33, 0, 0);
        let tris = soup(&mut rng, 3000, |i| if i % 10 == 0 { 4.0 } else { 0.3 });
        let bvh = Bvh::build(&tris);
        assert!(
            bvh.stack_entries > 7,
            "a tree of {} stack entries tests nothing",
            bvh.stack_entries
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
            let found = closest_hit(&bvh.bvh.nodes, &bvh.ordered, query, &mut ray, &mut stack);
            match (expected, found) {
                (None, None) => {}
                (Some(t), Some(_)) => {
                    assert_eq!(ray.tmax, t, "ray {i}");
                    hits += 1;
                }
                (e, f) => panic!("ray {i}: every triangle {e:?}, the walk {f:?}"),
            }
            let ray = BvhRay::new(Vec3A::from(o), Vec3A::from(d), 0.0, t_max);
            for nodes in [&bvh.bvh.nodes, &bvh.shadow_nodes] {
                let near_first = any_hit::<false>(nodes, &bvh.ordered, query, &ray, &mut stack);
                let stored = any_hit::<true>(nodes, &bvh.ordered, query, &ray, &mut stack);
                assert_eq!(near_first.0, expected.is_some(), "ray {i}");
                assert_eq!(stored.0, expected.is_some(), "ray {i}");
            }
            blocked += expected.is_some() as usize;
        }
        assert!(
            hits > 500 && blocked < 1900,
            "{hits} hits, {blocked} blocked"
        );
    }
}
