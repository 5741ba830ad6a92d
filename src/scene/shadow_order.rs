//! The order in which a shadow ray visits a CWBVH node's children.
//!
//! A closest-hit query visits children near to far (by the distance at which the ray
//! enters their boxes, [`crate::scene::cwbvh_walk`]), so that the closest hit found early
//! culls what lies behind it. A shadow ray stops at the first hit anywhere on its segment,
//! and near to far is then a guess that
//! the blocker lies near the ray's origin: where the light sits in a fixture (a lamp's
//! shade, a recessed bulb), the blocker lies near the far end, and the traversal visits
//! everything along the way first.
//!
//! The other order ([`ShadowOrder::Rtsah`]) uses a copy of the nodes whose inner children
//! are ordered once, by the *ray termination surface area heuristic* (RTSAH; Ize & Hansen
//! 2011, "RTSAH Traversal Order for Occlusion Rays"): child `c` is visited before `d` when
//! `alpha_c / cost_c > alpha_d / cost_d`, where `alpha` is the probability that a ray
//! entering the child's box hits something in it and `cost` the expected work of finding
//! out. For tasks that each end the search with probability `alpha` at cost `cost`, this
//! order minimises the expected cost of the search (the ratio rule). Both are estimated
//! bottom up from surface areas, as the SAH estimates hit probabilities: a random line that
//! meets a box `B` meets a convex `K` inside it with probability `area(K) / area(B)`
//! (Cauchy), a triangle's area counting twice (both sides); a node's cost counts each
//! child's work times the chance that the ray enters it and nothing tested before it
//! blocked the ray (its leaves first, as the shadow walk tests a node's leaves before
//! descending, then its inner children in their order).
//!
//! The order is the same for every ray; the copy holds only the nodes (the triangles and
//! their order are shared), and a node's inner children are taken from its highest slot
//! down. Which order a scene's shadow rays take is
//! chosen per kind of shadow ray ([`Toward`]) when the scene is built
//! (`Bvh::choose_shadow_order`).

use crate::scene::cwbvh_walk::{inner_child, is_inner};
use obvhs::aabb::Aabb;
use obvhs::cwbvh::node::CwBvhNode;

/// The order in which a shadow ray visits a node's children.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadowOrder {
    /// Near to far from the ray's origin (the closest-hit order).
    NearFirst,
    /// By each child's chance of blocking over its cost, the same for every ray.
    Rtsah,
}

impl ShadowOrder {
    /// How the order reads in a report.
    pub fn describe(self) -> &'static str {
        match self {
            ShadowOrder::NearFirst => "near first",
            ShadowOrder::Rtsah => "by blocking chance (RTSAH)",
        }
    }
}

/// Where a shadow ray ends: the two kinds of shadow rays are blocked in different places (a
/// light inside a lamp's shade is hidden near the light; the camera stands in the open), so
/// each kind has its own [`ShadowOrder`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Toward {
    /// Next-event estimation: from a surface to a point on a light.
    Light,
    /// A connection to the camera's lens (light tracing, the importance map's particles).
    Camera,
}

impl Toward {
    /// How the kind reads in a report.
    pub fn describe(self) -> &'static str {
        match self {
            Toward::Light => "a light",
            Toward::Camera => "the camera",
        }
    }
}

/// Shadow rays take [`ShadowOrder::Rtsah`] only when it tests fewer than this fraction of
/// the nodes and triangles near first tests (a saving of more than 10%): its nodes are a
/// copy that closest-hit rays do not keep in the cache, so a saving within the probes'
/// noise is not worth them.
pub const RTSAH_MARGIN: f64 = 0.9;

/// The expected work of testing one node's children, in units of one triangle test.
const NODE_COST: f32 = 1.0;

/// Half the surface area of `b` (0 for a box with a negative extent).
fn half_area(b: &Aabb) -> f32 {
    let d = (b.max - b.min).max(glam::Vec3A::ZERO);
    d.x * d.y + d.y * d.z + d.z * d.x
}

/// The occupied slots of `node`: leaves first, then inner children by increasing
/// `priority` (ties in slot order).
fn slot_order(node: &CwBvhNode, priority: &[f32; 8]) -> ([usize; 8], usize) {
    let mut slots = [0usize; 8];
    let mut used = 0;
    for s in (0..8).filter(|&s| node.child_meta[s] != 0) {
        slots[used] = s;
        used += 1;
    }
    slots[..used].sort_by(|&a, &b| {
        (is_inner(node, a), priority[a])
            .partial_cmp(&(is_inner(node, b), priority[b]))
            .unwrap_or(std::cmp::Ordering::Equal)
            .then(a.cmp(&b))
    });
    (slots, used)
}

/// `nodes` with every node's inner children moved to the slots above its leaves, in
/// increasing RTSAH priority (the highest priority in the highest slot). `triangle_area(i)`
/// is the area of the triangle at primitive position `i`.
pub fn shadow_nodes(nodes: &[CwBvhNode], triangle_area: impl Fn(usize) -> f32) -> Vec<CwBvhNode> {
    reorder(nodes, triangle_area).0
}

/// [`shadow_nodes`], and each reordered node's priorities by its new slot (0 for a leaf or
/// an empty slot).
fn reorder(
    nodes: &[CwBvhNode],
    triangle_area: impl Fn(usize) -> f32,
) -> (Vec<CwBvhNode>, Vec<[f32; 8]>) {
    let n = nodes.len();
    // Per node: the chance that a ray entering it is blocked inside, the expected work,
    // and each child's priority by slot. Children follow their parent in the array
    // (obvhs' converter appends them), so bottom up is back to front.
    let mut alpha = vec![0.0f32; n];
    let mut cost = vec![0.0f32; n];
    let mut priority = vec![[0.0f32; 8]; n];
    for i in (0..n).rev() {
        let node = &nodes[i];
        let mut child_box = [Aabb::empty(); 8];
        let mut node_box = Aabb::empty();
        for s in (0..8).filter(|&s| node.child_meta[s] != 0) {
            child_box[s] = node.child_aabb(s);
            node_box = node_box.union(&child_box[s]);
        }
        let node_area = half_area(&node_box).max(f32::MIN_POSITIVE);
        // Per slot: blocking chance inside, work, chance of entering given the node entered.
        let mut child = [(0.0f32, 0.0f32, 0.0f32); 8];
        for s in (0..8).filter(|&s| node.child_meta[s] != 0) {
            let area = half_area(&child_box[s]).max(f32::MIN_POSITIVE);
            let (a, c) = if is_inner(node, s) {
                let k = inner_child(node, s);
                (alpha[k], cost[k])
            } else {
                let meta = node.child_meta[s];
                let first = node.primitive_base_idx as usize + (meta & 0x1f) as usize;
                let count = (meta >> 5).count_ones() as usize;
                let miss = (first..first + count)
                    .map(|p| 1.0 - (triangle_area(p) / area).min(1.0))
                    .product::<f32>();
                (1.0 - miss, count as f32)
            };
            child[s] = (a, c, (area / node_area).min(1.0));
            priority[i][s] = a / c.max(f32::MIN_POSITIVE);
        }
        // The visit order: leaves, then inner children from the highest priority down.
        let (slots, used) = slot_order(node, &priority[i]);
        let leaves = slots[..used]
            .iter()
            .filter(|&&s| !is_inner(node, s))
            .count();
        let visit = slots[..leaves]
            .iter()
            .chain(slots[leaves..used].iter().rev());
        let (mut still_open, mut expected) = (1.0f32, NODE_COST);
        for &s in visit {
            let (a, c, enter) = child[s];
            expected += still_open * enter * c;
            still_open *= 1.0 - a * enter;
        }
        alpha[i] = 1.0 - still_open;
        cost[i] = expected;
    }
    // Reorder top down: a node's inner children are moved with their records, whose own
    // children stay where they are. `original[i]`: which of `nodes` the record at `out[i]`
    // is (a record moves only within its parent's children, rewritten once).
    let mut out = nodes.to_vec();
    let mut out_priority = vec![[0.0f32; 8]; n];
    let mut original: Vec<usize> = (0..n).collect();
    for i in 0..n {
        let node = out[i];
        let rank = &priority[original[i]];
        let (slots, used) = slot_order(&node, rank);
        let mut moved = node;
        moved.imask = 0;
        moved.child_meta = [0; 8];
        let mut records = [(CwBvhNode::default(), 0usize); 8];
        let mut inner = 0;
        for (new, &old) in slots[..used].iter().enumerate() {
            moved.child_min_x[new] = node.child_min_x[old];
            moved.child_max_x[new] = node.child_max_x[old];
            moved.child_min_y[new] = node.child_min_y[old];
            moved.child_max_y[new] = node.child_max_y[old];
            moved.child_min_z[new] = node.child_min_z[old];
            moved.child_max_z[new] = node.child_max_z[old];
            if is_inner(&node, old) {
                moved.imask |= 1 << new;
                moved.child_meta[new] = (24 + new as u8) | 0b0010_0000;
                let k = inner_child(&node, old);
                records[inner] = (out[k], original[k]);
                inner += 1;
                out_priority[i][new] = rank[old];
            } else {
                moved.child_meta[new] = node.child_meta[old];
            }
        }
        for new in used..8 {
            moved.child_min_x[new] = 0;
            moved.child_max_x[new] = 0;
            moved.child_min_y[new] = 0;
            moved.child_max_y[new] = 0;
            moved.child_min_z[new] = 0;
            moved.child_max_z[new] = 0;
        }
        for (k, &(record, id)) in records[..inner].iter().enumerate() {
            out[node.child_base_idx as usize + k] = record;
            original[node.child_base_idx as usize + k] = id;
        }
        out[i] = moved;
    }
    (out, out_priority)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;
    use obvhs::cwbvh::builder::build_cwbvh_from_tris;
    use obvhs::triangle::Triangle;

    /// In every reordered node the inner children sit above the leaves in increasing
    /// priority (the traversal takes the highest slot first), every priority positive and
    /// finite (a soup of 4,000 triangles of two sizes). Checked to fail with the sort
    /// reversed.
    #[test]
    fn inner_children_are_ordered_by_priority() {
        let mut state = 7u32;
        let mut uniform = || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1u32 << 24) as f32
        };
        let tris: Vec<Triangle> = (0..4000)
            .map(|i| {
                let c = Vec3A::new(uniform(), uniform(), uniform()) * 10.0;
                let size = if i % 7 == 0 { 3.0 } else { 0.2 };
                let mut p = || c + (Vec3A::new(uniform(), uniform(), uniform()) - 0.5) * size;
                Triangle {
                    v0: p(),
                    v1: p(),
                    v2: p(),
                }
            })
            .collect();
        let bvh = build_cwbvh_from_tris(
            &tris,
            obvhs::BvhBuildParams::medium_build(),
            &mut Default::default(),
        );
        let order = &bvh.primitive_indices;
        let area = |p: usize| {
            let t = &tris[order[p] as usize];
            0.5 * (t.v1 - t.v0).cross(t.v2 - t.v0).length()
        };
        let (nodes, priority) = reorder(&bvh.nodes, area);
        let mut compared = 0;
        for (i, node) in nodes.iter().enumerate() {
            let inner: Vec<usize> = (0..8).filter(|&s| is_inner(node, s)).collect();
            for w in inner.windows(2) {
                assert!(
                    priority[i][w[0]] <= priority[i][w[1]],
                    "node {i}: {:?}",
                    priority[i]
                );
                compared += (priority[i][w[0]] < priority[i][w[1]]) as usize;
            }
            for &s in &inner {
                assert!(
                    priority[i][s] > 0.0 && priority[i][s].is_finite(),
                    "node {i}"
                );
            }
        }
        assert!(compared > 50, "only {compared} strict comparisons");
    }
}
