//! The order in which a shadow ray visits a CWBVH node's children.
//!
//! A closest-hit query visits children near to far (the CWBVH's octant order, Ylitie et
//! al. 2017), so that the closest hit found early culls what lies behind it. A shadow ray
//! stops at the first hit anywhere on its segment, and near to far is then a guess that
//! the blocker lies near the ray's origin: where the light sits in a fixture (a lamp's
//! shade, a recessed bulb), the blocker lies near the far end, and the traversal visits
//! everything along the way first.
//!
//! Shadow rays therefore use a copy of the nodes whose inner children are ordered once, by
//! the *ray termination surface area heuristic* (RTSAH; Ize & Hansen 2011, "RTSAH Traversal
//! Order for Occlusion Rays"): a child `c` is visited before `d` when `alpha_c / cost_c >
//! alpha_d / cost_d`, where `alpha` is the probability that a ray entering the child's box
//! hits something in it and `cost` the expected work of finding out. For tasks that each
//! end the search with probability `alpha` at cost `cost`, this order minimises the
//! expected cost of the search (the classic ratio rule). Both are estimated bottom up from
//! surface areas, as the SAH estimates hit probabilities: a random line that meets a box
//! `B` meets a convex `K` inside it with probability `area(K) / area(B)` (Cauchy), and a
//! triangle's area counts twice (both sides).
//!
//! The order is the same for every ray; the copy holds only the nodes (the triangles and
//! their order are shared), and is traversed with the octant code 0, so that a node's
//! children are taken from its highest slot down.

use obvhs::aabb::Aabb;
use obvhs::cwbvh::node::CwBvhNode;

/// The expected work of testing one node's children, in units of one triangle test.
const NODE_COST: f32 = 1.0;

/// The inner child `slot` of `node` (its meta byte marks it so).
fn is_inner(node: &CwBvhNode, slot: usize) -> bool {
    node.imask & (1 << slot) != 0
}

/// Half the surface area of `b`.
fn half_area(b: &Aabb) -> f32 {
    let d = (b.max - b.min).max(glam::Vec3A::ZERO);
    d.x * d.y + d.y * d.z + d.z * d.x
}

/// `nodes` with every node's inner children moved to the slots above its leaves, in
/// increasing RTSAH priority (the highest priority in the highest slot). `triangle_area(i)`
/// is the area of the triangle at primitive position `i`.
pub fn shadow_nodes(nodes: &[CwBvhNode], triangle_area: impl Fn(usize) -> f32) -> Vec<CwBvhNode> {
    let n = nodes.len();
    // Children follow their parent in the array: bottom up is back to front.
    let mut alpha = vec![0.0f32; n];
    let mut cost = vec![0.0f32; n];
    let mut priority = vec![[0.0f32; 8]; n];
    for i in (0..n).rev() {
        let node = &nodes[i];
        let boxes: Vec<(usize, Aabb)> = (0..8)
            .filter(|&s| node.child_meta[s] != 0)
            .map(|s| (s, node.child_aabb(s)))
            .collect();
        let node_area = boxes.iter().fold(Aabb::empty(), |b, (_, c)| b.union(c));
        let node_area = half_area(&node_area).max(f32::MIN_POSITIVE);
        let mut miss = 1.0f32;
        let mut expected = NODE_COST;
        for &(s, b) in &boxes {
            let area = half_area(&b).max(f32::MIN_POSITIVE);
            let (a, c) = if is_inner(node, s) {
                let child = node.child_base_idx as usize
                    + (node.imask as u32 & ((1u32 << s) - 1)).count_ones() as usize;
                (alpha[child], cost[child])
            } else {
                let meta = node.child_meta[s];
                let first = node.primitive_base_idx as usize + (meta & 0x1f) as usize;
                let count = (meta >> 5).count_ones() as usize;
                let leaf_miss = (first..first + count)
                    .map(|p| 1.0 - (triangle_area(p) / area).min(1.0))
                    .product::<f32>();
                (1.0 - leaf_miss, count as f32)
            };
            let enter = (area / node_area).min(1.0);
            miss *= 1.0 - a * enter;
            expected += enter * c;
            priority[i][s] = a / c.max(f32::MIN_POSITIVE);
        }
        alpha[i] = 1.0 - miss;
        cost[i] = expected;
    }
    // Reorder top down: a node's inner children are moved with their records, whose own
    // children stay where they are.
    let mut out = nodes.to_vec();
    // `original[i]`: which of `nodes` the record at `out[i]` is.
    let mut original: Vec<usize> = (0..n).collect();
    for i in 0..n {
        let node = out[i];
        let rank = &priority[original[i]];
        let mut slots: Vec<usize> = (0..8).filter(|&s| node.child_meta[s] != 0).collect();
        // Leaves first (their order is their primitives'), then inner children by
        // increasing priority; ties keep the octant order.
        slots.sort_by(|&a, &b| {
            (is_inner(&node, a), rank[a])
                .partial_cmp(&(is_inner(&node, b), rank[b]))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        let child_of = |s: usize| {
            node.child_base_idx as usize
                + (node.imask as u32 & ((1u32 << s) - 1)).count_ones() as usize
        };
        let mut moved = node;
        moved.imask = 0;
        moved.child_meta = [0; 8];
        let mut records: Vec<(CwBvhNode, usize)> = Vec::new();
        for (new, &old) in slots.iter().enumerate() {
            moved.child_min_x[new] = node.child_min_x[old];
            moved.child_max_x[new] = node.child_max_x[old];
            moved.child_min_y[new] = node.child_min_y[old];
            moved.child_max_y[new] = node.child_max_y[old];
            moved.child_min_z[new] = node.child_min_z[old];
            moved.child_max_z[new] = node.child_max_z[old];
            if is_inner(&node, old) {
                moved.imask |= 1 << new;
                moved.child_meta[new] = (24 + new as u8) | 0b0010_0000;
                records.push((out[child_of(old)], original[child_of(old)]));
            } else {
                moved.child_meta[new] = node.child_meta[old];
            }
        }
        for new in slots.len()..8 {
            moved.child_min_x[new] = 0;
            moved.child_max_x[new] = 0;
            moved.child_min_y[new] = 0;
            moved.child_max_y[new] = 0;
            moved.child_min_z[new] = 0;
            moved.child_max_z[new] = 0;
        }
        for (k, (record, id)) in records.into_iter().enumerate() {
            out[node.child_base_idx as usize + k] = record;
            original[node.child_base_idx as usize + k] = id;
        }
        out[i] = moved;
    }
    out
}
