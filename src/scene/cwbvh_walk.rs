//! Walking the CWBVH (Ylitie et al. 2017, as `obvhs` builds it): the node test and the two
//! walks over it, a closest hit and a shadow ray's first blocker.
//!
//! The walks keep a stack of pending children, each with the distance at which the ray
//! enters its box, as CPU ray tracers do (pbrt-v4's `BVHAggregate`, Embree's BVH8). A
//! closest-hit walk pushes a node's entered children farthest first, so the nearest is
//! taken next, and drops a popped child whose box begins beyond the closest hit so far,
//! without fetching it. (obvhs' own traversal, made for GPUs, keeps a child mask per node
//! in the approximate near-to-far order of the ray's octant and tests every pending node
//! again, however far behind the hit its box lies.)
//!
//! A shadow ray stops at its first blocker: each node's leaves are tested first, then its
//! inner children are taken near first or far-reaching first
//! ([`crate::scene::shadow_order`]).

use crate::scene::triangle_block::{LEAF_TRIANGLES, TriangleBlock};
use glam::Vec3;
use glam::Vec3A;
#[cfg(not(all(target_arch = "x86_64", target_feature = "sse4.1")))]
use glam::vec3a;
use obvhs::cwbvh::node::CwBvhNode;
use obvhs::ray::Ray as BvhRay;
use std::mem::MaybeUninit;

/// Boxes the ray leaves before this distance are culled (obvhs' own node test's constant,
/// kept so that the same boxes are entered).
pub const NODE_EPSILON: f32 = 1e-4;

/// Marks a pending item as a leaf: `first triangle << 2 | triangle count` below this bit;
/// without it, the item is an inner node's index.
const LEAF: u32 = 1 << 31;

/// The walks address triangles with 29 bits (see [`LEAF`]).
pub const MAX_TRIANGLES: usize = 1 << 29;

/// Entries of a walk's stack held on the machine stack (2 KiB); a deeper tree
/// ([`stack_entries`]) walks with one on the heap.
pub const STACK_ENTRIES: usize = 256;

/// A walk's pending items: an item (see [`LEAF`]) and the distance at which the ray
/// enters its box.
pub type Pending = MaybeUninit<(u32, f32)>;

/// Child `slot` of `node` (occupied) as a pending item: an inner node's index, or a leaf's
/// first triangle (position in the BVH's primitive order) and count.
#[inline(always)]
fn item(node: &CwBvhNode, slot: usize) -> u32 {
    if node.is_leaf(slot) {
        let (first, count) = node.child_primitives(slot);
        LEAF | first << 2 | count
    } else {
        node.child_node_index(slot)
    }
}

/// The stack entries a walk over `nodes` needs at most: a visit to an inner node pushes at
/// most its 8 children and takes one of them at once, so at most 7 wait per level of inner
/// nodes above the one visited, which pushes 8: `7 (levels - 1) + 8`.
pub fn stack_entries(nodes: &[CwBvhNode]) -> usize {
    if nodes.is_empty() {
        return 1;
    }
    // Depth first over (node, level), levels counted from 1 at the root.
    let mut depth = 0;
    let mut todo = vec![(0usize, 1usize)];
    while let Some((i, level)) = todo.pop() {
        depth = depth.max(level);
        let node = &nodes[i];
        for slot in (0..8).filter(|&s| !node.is_child_empty(s) && !node.is_leaf(s)) {
            todo.push((node.child_node_index(slot) as usize, level + 1));
        }
    }
    7 * depth + 1
}

/// A stack of `Pending` items over `STACK_ENTRIES` entries on the machine stack, or over
/// `entries` on the heap when a tree needs more, for the walk `f`.
#[inline(always)]
pub fn with_stack<R>(entries: usize, f: impl FnOnce(&mut [Pending]) -> R) -> R {
    if entries <= STACK_ENTRIES {
        let mut stack = [const { Pending::uninit() }; STACK_ENTRIES];
        f(&mut stack)
    } else {
        f(&mut vec![Pending::uninit(); entries])
    }
}

/// The children of `node` the ray enters within `[NODE_EPSILON, ray.tmax]`, as a mask over
/// the node's eight slots, and the distances at which the ray enters and leaves each slot's
/// box (within that interval).
///
/// The slab test is obvhs' `intersect_ray_simd` operation for operation: the quantised
/// planes (bytes) widened to floats, scaled by the node's power-of-two extent and offset,
/// four children at a time, so the same children are entered.
#[cfg(all(target_arch = "x86_64", target_feature = "sse4.1"))]
#[inline(always)]
pub fn child_entries(node: &CwBvhNode, ray: &BvhRay) -> (u32, [f32; 8], [f32; 8]) {
    use std::arch::x86_64::*;
    let extent = node.compute_extent();
    let scale = extent * ray.inv_direction;
    let offset = (Vec3A::from(node.p) - ray.origin) * ray.inv_direction;
    let mut t_enter = [0.0f32; 8];
    let mut t_leave = [0.0f32; 8];
    let mut mask = 0u32;
    // SAFETY: SSE4.1 is enabled for this build (the cfg above); the loads read plain
    // integers out of the node's byte arrays, and each store writes four floats into
    // `t_enter[4 * half..4 * half + 4]` or `t_leave[4 * half..4 * half + 4]`.
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
            mask |= (_mm_movemask_ps(_mm_cmple_ps(t_near, t_far)) as u32) << (4 * half);
            _mm_storeu_ps(t_enter.as_mut_ptr().add(4 * half), t_near);
            _mm_storeu_ps(t_leave.as_mut_ptr().add(4 * half), t_far);
        }
        // Empty slots (meta 0) hold no child, whatever their planes.
        let meta = _mm_cvtsi64_si128(i64::from_le_bytes(node.child_meta));
        let empty = _mm_movemask_epi8(_mm_cmpeq_epi8(meta, _mm_setzero_si128())) as u32;
        (mask & !empty & 0xff, t_enter, t_leave)
    }
}

/// Without SSE4.1: the same slab test (obvhs' `intersect_ray_basic`), a child at a time.
#[cfg(not(all(target_arch = "x86_64", target_feature = "sse4.1")))]
#[inline(always)]
pub fn child_entries(node: &CwBvhNode, ray: &BvhRay) -> (u32, [f32; 8], [f32; 8]) {
    let scale = node.compute_extent() * ray.inv_direction;
    let offset = (Vec3A::from(node.p) - ray.origin) * ray.inv_direction;
    let negative = ray.direction.cmplt(Vec3A::ZERO);
    let mut t_enter = [0.0f32; 8];
    let mut t_leave = [0.0f32; 8];
    let mut mask = 0u32;
    for slot in (0..8).filter(|&s| node.child_meta[s] != 0) {
        let lo = vec3a(
            node.child_min_x[slot] as f32,
            node.child_min_y[slot] as f32,
            node.child_min_z[slot] as f32,
        );
        let hi = vec3a(
            node.child_max_x[slot] as f32,
            node.child_max_y[slot] as f32,
            node.child_max_z[slot] as f32,
        );
        let near = Vec3A::select(negative, hi, lo) * scale + offset;
        let far = Vec3A::select(negative, lo, hi) * scale + offset;
        let t_near = near.max_element().max(NODE_EPSILON);
        let t_far = far.min_element().min(ray.tmax);
        t_enter[slot] = t_near;
        t_leave[slot] = t_far;
        mask |= u32::from(t_near <= t_far) << slot;
    }
    (mask, t_enter, t_leave)
}

/// Pushes `(item, t)` onto `stack[..*top]`, keeping `stack[first..]` ordered by decreasing
/// `t` (the smallest on top).
#[inline(always)]
fn push_in_order(stack: &mut [Pending], first: usize, top: &mut usize, item: u32, t: f32) {
    let mut at = *top;
    while at > first {
        // SAFETY: the entries below `top` are written.
        let below = unsafe { stack[at - 1].assume_init() };
        if below.1 >= t {
            break;
        }
        stack[at] = Pending::new(below);
        at -= 1;
    }
    stack[at] = Pending::new((item, t));
    *top += 1;
}

/// The closest hit of the query ray (`origin + t dir`, the traversal's `ray`) among the
/// leaves' triangles ([`TriangleBlock`]s, a leaf's first triangle three times its block's
/// index) within `t_min < t < ray.tmax`: the hit's
/// triangle position and barycentrics, with `ray.tmax` moved to its distance.
#[inline(always)]
pub fn closest_hit(
    nodes: &[CwBvhNode],
    blocks: &[TriangleBlock],
    (origin, dir, t_min): (Vec3, Vec3, f32),
    ray: &mut BvhRay,
    stack: &mut [Pending],
) -> Option<(u32, f32, f32)> {
    let mut best = None;
    let mut top = 0usize;
    let mut current = 0u32;
    loop {
        if current & LEAF == 0 {
            let node = &nodes[current as usize];
            let (mut entered, t_enter, _) = child_entries(node, ray);
            if entered != 0 && entered & (entered - 1) == 0 {
                // One child entered: straight to it.
                current = item(node, entered.trailing_zeros() as usize);
                continue;
            }
            let first = top;
            while entered != 0 {
                let slot = entered.trailing_zeros() as usize;
                entered &= entered - 1;
                push_in_order(stack, first, &mut top, item(node, slot), t_enter[slot]);
            }
        } else {
            // The leaf's triangles at once; only a t below the closest so far is
            // accepted, and the ray's end moves there: `best` is the closest candidate.
            let first = ((current & !LEAF) >> 2) as usize;
            if let Some((lane, t, b1, b2)) =
                blocks[first / LEAF_TRIANGLES].closest(origin, dir, t_min, ray.tmax)
            {
                ray.tmax = t;
                best = Some(((first + lane) as u32, b1, b2));
            }
        }
        // The nearest pending child whose box begins before the closest hit so far.
        loop {
            if top == 0 {
                return best;
            }
            top -= 1;
            // SAFETY: the entries below `top` are written.
            let (pending, t_enter) = unsafe { stack[top].assume_init() };
            if t_enter <= ray.tmax {
                current = pending;
                break;
            }
        }
    }
}

/// Whether a triangle blocks the query ray within `t_min < t < ray.tmax`, and the nodes and
/// triangles the walk tested. A node's leaves are tested first, then its inner children
/// are taken near first, or with `FAR_REACHING` the one whose box the ray leaves last
/// first ([`crate::scene::shadow_order::ShadowOrder`]).
#[inline(always)]
pub fn any_hit<const FAR_REACHING: bool>(
    nodes: &[CwBvhNode],
    blocks: &[TriangleBlock],
    (origin, dir, t_min): (Vec3, Vec3, f32),
    ray: &BvhRay,
    stack: &mut [Pending],
) -> (bool, u32) {
    let mut top = 0usize;
    let mut current = 0usize;
    let mut tested = 0u32;
    loop {
        let node = &nodes[current];
        tested += 1;
        let (entered, t_enter, t_leave) = child_entries(node, ray);
        let mut leaves = entered & !(node.imask as u32);
        while leaves != 0 {
            let slot = leaves.trailing_zeros() as usize;
            leaves &= leaves - 1;
            let (first, count) = node.child_primitives(slot);
            tested += count;
            if blocks[first as usize / LEAF_TRIANGLES].any(origin, dir, t_min, ray.tmax) {
                return (true, tested);
            }
        }
        let mut inner = entered & node.imask as u32;
        let first = top;
        while inner != 0 {
            let slot = inner.trailing_zeros() as usize;
            inner &= inner - 1;
            // The smallest key is taken first.
            let key = if FAR_REACHING {
                -t_leave[slot]
            } else {
                t_enter[slot]
            };
            push_in_order(stack, first, &mut top, node.child_node_index(slot), key);
        }
        if top == 0 {
            return (false, tested);
        }
        top -= 1;
        // SAFETY: the entries below `top` are written.
        current = unsafe { stack[top].assume_init() }.0 as usize;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;
    use crate::sampling::sample_uniform_sphere;
    use crate::scene::geometry::TriangleGeom;
    use crate::scene::triangle_block::into_blocks;
    use obvhs::BvhBuildParams;
    use obvhs::cwbvh::builder::build_cwbvh_from_tris;
    use obvhs::triangle::Triangle as BvhTriangle;
    use std::time::Duration;

    /// The bits obvhs' node test (`CwBvhNode::intersect_ray`) sets for child `slot` when
    /// the ray enters it: the slot's traversal priority bit for an inner child, its
    /// triangles' bits for a leaf.
    fn obvhs_bits(node: &CwBvhNode, slot: usize, oct_inv4: u32) -> u32 {
        let (child_bits8, bit_index8) = node.get_child_and_index_bits(oct_inv4);
        let byte = |x: u64| ((x >> (8 * slot)) & 0xff) as u32;
        byte(child_bits8) << byte(bit_index8)
    }

    /// `child_entries` enters exactly the children obvhs' own node test enters, for every
    /// node of a CWBVH over a random soup of 2000 triangles and rays from random points in
    /// random directions (axis-aligned ones included, whose reciprocals are huge), with
    /// finite and infinite ends; and each entered child's entry and exit distances are
    /// where the ray enters and leaves the child's box (the slab test in f64 on the
    /// dequantised box, to a relative 1e-4 of the box's size).
    #[test]
    fn child_entries_enter_the_children_obvhs_enters() {
        let mut rng = Rng::new(31, 0, 0);
        let p = |rng: &mut Rng| Vec3A::new(rng.uniform(), rng.uniform(), rng.uniform());
        let tris: Vec<BvhTriangle> = (0..2000)
            .map(|_| {
                let c = p(&mut rng) * 10.0;
                BvhTriangle {
                    v0: c,
                    v1: c + (p(&mut rng) - 0.5) * 0.8,
                    v2: c + (p(&mut rng) - 0.5) * 0.8,
                }
            })
            .collect();
        let bvh = build_cwbvh_from_tris(
            &tris,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        assert!(bvh.nodes.len() > 50);
        let mut entered = 0usize;
        for i in 0..400 {
            let o = p(&mut rng) * 12.0 - 1.0;
            let d = match i % 8 {
                0 => Vec3A::X,
                // Zeros in x and y (positive, as the queries make them).
                1 => Vec3A::new(0.0, 0.0, -1.0),
                _ => Vec3A::from(sample_uniform_sphere(rng.uniform2())),
            };
            let t_max = if i % 2 == 0 { f32::INFINITY } else { 4.0 };
            let ray = BvhRay::new(o, d, 0.0, t_max);
            let oct_inv4 = bvh.new_traversal(ray.direction).oct_inv4;
            for node in &bvh.nodes {
                let (mask, t_enter, t_leave) = child_entries(node, &ray);
                let theirs = node.intersect_ray(&ray, oct_inv4);
                let ours = (0..8)
                    .filter(|&s| mask & (1 << s) != 0)
                    .fold(0, |bits, s| bits | obvhs_bits(node, s, oct_inv4));
                assert_eq!(ours, theirs, "ray {i}");
                for slot in (0..8).filter(|&s| mask & (1 << s) != 0) {
                    entered += 1;
                    let b = node.child_aabb(slot);
                    // The slab's entry and exit along axis `a` (both infinite for a
                    // direction without that component: the ray is inside the slab).
                    let slab = |a: usize| {
                        let (lo, hi) = (b.min[a] as f64, b.max[a] as f64);
                        let (o, d) = (o[a] as f64, d[a] as f64);
                        if d == 0.0 {
                            (f64::NEG_INFINITY, f64::INFINITY)
                        } else {
                            let (u, v) = ((lo - o) / d, (hi - o) / d);
                            (u.min(v), u.max(v))
                        }
                    };
                    let (x, y, z) = (slab(0), slab(1), slab(2));
                    let enter = x.0.max(y.0).max(z.0).max(NODE_EPSILON as f64);
                    let leave = x.1.min(y.1).min(z.1).min(t_max as f64);
                    let size = (b.max - b.min).max_element().max(1e-3) as f64;
                    let close = |ours: f32, exact: f64| {
                        exact.is_infinite() && ours as f64 == exact
                            || (ours as f64 - exact).abs() <= 1e-4 * size + 1e-4 * exact.abs()
                    };
                    assert!(
                        close(t_enter[slot], enter),
                        "ray {i}: entry {} against {enter}",
                        t_enter[slot]
                    );
                    assert!(
                        close(t_leave[slot], leave),
                        "ray {i}: exit {} against {leave}",
                        t_leave[slot]
                    );
                }
            }
        }
        assert!(
            entered > 1000,
            "too few children entered ({entered}) to test anything"
        );
    }

    /// `stack_entries` covers a visit that pushes all eight children: eight triangles in a
    /// row, far apart, under one node with a leaf in each slot, and a ray along the row
    /// that enters every leaf's box. The closest-hit walk runs on a stack of exactly
    /// `stack_entries` entries (a slice: a ninth push would panic) and finds the first.
    #[test]
    fn the_stack_holds_a_visit_that_enters_every_child() {
        let tris: Vec<BvhTriangle> = (0..8)
            .map(|i| {
                let c = Vec3A::new(10.0 * i as f32, 0.0, 0.0);
                BvhTriangle {
                    v0: c + Vec3A::new(0.0, -1.0, -1.0),
                    v1: c + Vec3A::new(0.0, 1.0, -1.0),
                    v2: c + Vec3A::new(0.0, 0.0, 1.0),
                }
            })
            .collect();
        let mut bvh = build_cwbvh_from_tris(
            &tris,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        assert_eq!(bvh.nodes.len(), 1, "one node holds the eight leaves");
        assert_eq!(
            bvh.nodes[0].child_meta.iter().filter(|&&m| m != 0).count(),
            8
        );
        assert_eq!(stack_entries(&bvh.nodes), 8);
        let blocks = into_blocks(&mut bvh.nodes, &mut bvh.primitive_indices, |i| {
            let t = &tris[i as usize];
            TriangleGeom::new(t.v0.into(), t.v1.into(), t.v2.into())
        });
        let origin = Vec3::new(-5.0, 0.0, 0.0);
        let mut ray = BvhRay::new(origin.into(), Vec3A::X, 0.0, f32::INFINITY);
        let (entered, _, _) = child_entries(&bvh.nodes[0], &ray);
        assert_eq!(entered, 0xff);
        let mut stack = vec![Pending::uninit(); 8];
        let hit = closest_hit(
            &bvh.nodes,
            &blocks,
            (origin, Vec3::X, 0.0),
            &mut ray,
            &mut stack,
        );
        assert!(hit.is_some());
        assert!((ray.tmax - 5.0).abs() < 1e-5, "hit at {}", ray.tmax);
    }

    /// The levels of inner nodes under node `i`, counted recursively.
    fn levels(nodes: &[CwBvhNode], i: usize) -> usize {
        let node = &nodes[i];
        1 + (0..8)
            .filter(|&s| node.child_meta[s] != 0 && node.imask & (1 << s) != 0)
            .map(|s| levels(nodes, node.child_node_index(s) as usize))
            .max()
            .unwrap_or(0)
    }

    /// `stack_entries` is `7 levels + 1` on a tree of several levels (2000 triangles in a
    /// 10 m cube), the levels counted recursively here.
    #[test]
    fn stack_entries_count_seven_per_level_and_one() {
        let mut rng = Rng::new(34, 0, 0);
        let tris: Vec<BvhTriangle> = (0..2000)
            .map(|_| {
                let c = Vec3A::new(rng.uniform(), rng.uniform(), rng.uniform()) * 10.0;
                BvhTriangle {
                    v0: c,
                    v1: c + Vec3A::X * 0.2,
                    v2: c + Vec3A::Y * 0.2,
                }
            })
            .collect();
        let bvh = build_cwbvh_from_tris(
            &tris,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let depth = levels(&bvh.nodes, 0);
        assert!(depth >= 3, "{depth} levels test little");
        assert_eq!(stack_entries(&bvh.nodes), 7 * depth + 1);
    }

    /// `push_in_order` keeps each node's run ordered with the smallest key on top, above
    /// and apart from what was pushed before: eight random keys pushed above two entries
    /// pop in increasing order, then the two come back as they were.
    #[test]
    fn pushes_keep_the_smallest_key_on_top() {
        let mut rng = Rng::new(35, 0, 0);
        let mut stack = vec![Pending::uninit(); 10];
        let mut top = 0;
        push_in_order(&mut stack, 0, &mut top, 100, 5.0);
        push_in_order(&mut stack, 0, &mut top, 101, 9.0);
        let first = top;
        for item in 0..8 {
            push_in_order(&mut stack, first, &mut top, item, rng.uniform());
        }
        assert_eq!(top, 10);
        let mut popped = Vec::new();
        while top > 0 {
            top -= 1;
            // SAFETY: the entries below `top` are written.
            popped.push(unsafe { stack[top].assume_init() });
        }
        let run: Vec<f32> = popped[..8].iter().map(|e| e.1).collect();
        assert!(run.windows(2).all(|w| w[0] <= w[1]), "{run:?}");
        let mut items: Vec<u32> = popped[..8].iter().map(|e| e.0).collect();
        items.sort_unstable();
        assert_eq!(items, (0..8).collect::<Vec<_>>());
        // The earlier run, ordered within itself: 5.0 on top of 9.0.
        assert_eq!(popped[8], (100, 5.0));
        assert_eq!(popped[9], (101, 9.0));
    }
}
