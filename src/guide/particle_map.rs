//! Particle maps (Hey & Purgathofer 2001, §2.1): the photon map that guides view paths and the
//! importance map that guides light paths are one data structure with two fillings. A photon
//! carries flux `Φ_p`, an importon importance `W_p` (RGB, per channel, §2.1 last paragraph);
//! both carry their incoming direction `Ψ_p` (pointing away from the surface, toward where
//! the particle came from) and the normal of the surface they landed on, oriented toward the
//! side they arrived from.
//!
//! Storage: a kiddo `ImmutableKdTree` over positions (12 bytes of coordinates and a 4-byte
//! index per particle) and a compact 14-byte record per particle: `Ψ_p` octahedral-encoded in
//! 2 x 16 bits, the normal in 2 x 8 bits, the weight as three IEEE half floats relative to a
//! per-map scale, and the offset of the particle's tangent plane (half float) for the plane
//! rule below. About 31 bytes per particle in all, tree included; the paper used 96.
//!
//! Query (§2.1): the `k` nearest particles within a maximum distance whose contribution
//! `c_p = Φ_p f_r(x, Ψ_p, Ψ_i)` (computed by the caller) is non-zero. Particles on a surface
//! facing elsewhere (stored normal more than ~45° from the query normal, which excludes the
//! back of a thin wall) or on another parallel surface (the query point lies farther from the
//! particle's tangent plane than a fraction of the maximum distance: a floor under a table)
//! do not count. Fewer than `k` found is
//! reported, so the caller can fall back to the BSDF.

use crate::Rgb;
use crate::math::bounds;
use glam::{Vec2, Vec3};
use kiddo::SquaredEuclidean;
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// The 30-bit Morton code of a point in the unit cube (10 bits per axis, interleaved).
fn morton3(unit: [f32; 3]) -> u64 {
    let spread = |x: f32| {
        let mut v = ((x.clamp(0.0, 1.0) * 1023.0) as u64) & 0x3ff;
        v = (v | v << 16) & 0x0300_00ff;
        v = (v | v << 8) & 0x0300_f00f;
        v = (v | v << 4) & 0x030c_30c3;
        (v | v << 2) & 0x0924_9249
    };
    spread(unit[0]) | spread(unit[1]) << 1 | spread(unit[2]) << 2
}

/// The particles in Morton order over the bounds `lo`..`hi` (ties in input order). A map
/// keeps its particles so: a query's candidates then lie in a few runs of the records
/// instead of all over them (a pass stores particles in path order), and its tests of
/// their normals and planes wait less on memory. A query breaks ties of distance by this
/// order's index, so where two candidates lie at exactly the same distance at the `k`-th
/// place another one may be kept than in input order.
fn in_spatial_order(particles: &[&ParticleInput], lo: Vec3, hi: Vec3) -> Vec<ParticleInput> {
    let ext = (hi - lo).max(Vec3::splat(f32::MIN_POSITIVE));
    let mut keys: Vec<u64> = particles
        .par_iter()
        .enumerate()
        .map(|(i, p)| morton3(((p.position - lo) / ext).to_array()) << 32 | i as u64)
        .collect();
    keys.par_sort_unstable();
    keys.par_iter()
        .map(|k| *particles[(k & 0xffff_ffff) as usize])
        .collect()
}

/// What a map holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapKind {
    /// Photons from the light pass; weight = flux `Φ_p`.
    Photons,
    /// Importons from the view pass; weight = importance `W_p`.
    Importons,
}

impl MapKind {
    pub fn name(self) -> &'static str {
        match self {
            MapKind::Photons => "photon map",
            MapKind::Importons => "importance map",
        }
    }
}

/// A particle as a pass produces it (full precision, before compaction).
#[derive(Clone, Copy, Debug)]
pub struct ParticleInput {
    pub position: Vec3,
    /// `Ψ_p`: unit direction toward where the particle came from.
    pub dir: Vec3,
    /// Unit normal of the surface, on the side the particle arrived from.
    pub normal: Vec3,
    /// `Φ_p` or `W_p`.
    pub weight: Rgb,
    /// Path segments from the light (photons) or camera (importons) to this point.
    pub depth: u16,
    /// True when every earlier scattering vertex of the path was specular.
    pub specular_chain: bool,
}

/// The compact record: 14 bytes, 2-byte aligned.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
struct Record {
    dir: [u16; 2],
    normal: [u8; 2],
    weight: [u16; 3],
    /// `n_p · (p - centre)` as a half float: the particle's tangent plane.
    plane: u16,
}

/// A particle found by a query, decoded.
#[derive(Clone, Copy, Debug)]
pub struct Neighbor {
    pub index: u32,
    pub dist2: f32,
    pub dir: Vec3,
    pub normal: Vec3,
    pub weight: Rgb,
    /// `c_p` as the caller's contribution function gave it.
    pub contribution: f32,
}

/// Minimum cosine between a particle's stored normal and the query normal.
pub const NORMAL_COS_MIN: f32 = 0.7;
/// Largest distance of the query point from a particle's tangent plane, as a fraction of the
/// maximum query distance.
pub const PLANE_FRACTION: f32 = 0.25;

pub struct ParticleMap {
    pub kind: MapKind,
    tree: Option<kiddo::ImmutableKdTree<f32, 3>>,
    records: Vec<Record>,
    /// Stored weights are `weight / scale` in half precision.
    scale: f32,
    /// Plane offsets are relative to this point (the particles' bounding-box centre), so
    /// their magnitude stays within the scene's size.
    centre: Vec3,
    density: DensityGrid,
    pub build_time: Duration,
}

/// A coarse grid of particle counts over the map's bounds, split by the particles' normal into
/// six buckets (the dominant axis and its sign): at most one cell per 64 particles, six 16-bit
/// saturating counts each (under 0.2 bytes per particle). It gives each query a first radius
/// expected to hold about `2k` admissible particles, and an upper bound on the admissible
/// particles within the maximum distance, so that a query that cannot find `k` (the dark
/// side of a wall) returns at once instead of searching.
#[derive(Clone, Debug, Default)]
struct DensityGrid {
    lo: Vec3,
    cell: f32,
    dims: [usize; 3],
    counts: Vec<[u16; 6]>,
}

/// The axis of each normal bucket.
const BUCKET_AXES: [Vec3; 6] = crate::math::SIGNED_AXES;

/// The bucket of a normal: its dominant axis and sign, as an index into
/// [`crate::math::SIGNED_AXES`] (the count grid's buckets and the guide cache's regions).
#[inline]
pub fn normal_bucket(n: Vec3) -> usize {
    let a = n.abs();
    if a.x >= a.y && a.x >= a.z {
        if n.x >= 0.0 { 0 } else { 1 }
    } else if a.y >= a.z {
        if n.y >= 0.0 { 2 } else { 3 }
    } else if n.z >= 0.0 {
        4
    } else {
        5
    }
}

impl DensityGrid {
    fn build(particles: &[(Vec3, Vec3)], lo: Vec3, hi: Vec3) -> Self {
        let extent = (hi - lo).max(Vec3::splat(1e-6));
        let target = (particles.len() / 64).clamp(1, 1 << 18) as f32;
        // Cubic cells, about `target` of them: cell³ · cells = volume, grown until flat or
        // thin particle sets (a single wall) do not get more cells than that either.
        let dims_for = |cell: f32| {
            [
                ((extent.x / cell).ceil() as usize).max(1),
                ((extent.y / cell).ceil() as usize).max(1),
                ((extent.z / cell).ceil() as usize).max(1),
            ]
        };
        let mut cell = (extent.x * extent.y * extent.z / target)
            .cbrt()
            .max(extent.max_element() / 1024.0);
        while dims_for(cell).iter().product::<usize>() as f32 > 2.0 * target {
            cell *= 1.25;
        }
        let dims = dims_for(cell);
        let mut g = DensityGrid {
            lo,
            cell,
            dims,
            counts: vec![[0; 6]; dims[0] * dims[1] * dims[2]],
        };
        for (p, n) in particles {
            let i = g.index(g.cell_of(*p));
            let b = normal_bucket(*n);
            g.counts[i][b] = g.counts[i][b].saturating_add(1);
        }
        g
    }

    /// Buckets that can hold a particle whose normal is within the query cone of `n`
    /// (`n_p · n >= NORMAL_COS_MIN`): a bucket spans up to 54.8° around its axis and the cone
    /// 45.6° around `n`, so the bucket counts when its axis is within 100.4° of `n`.
    fn buckets_for(n: Vec3) -> [bool; 6] {
        let mut b = [false; 6];
        for (i, a) in BUCKET_AXES.iter().enumerate() {
            b[i] = a.dot(n) > -0.18;
        }
        b
    }

    fn cell_of(&self, x: Vec3) -> [isize; 3] {
        let c = (x - self.lo) / self.cell;
        [
            c.x.floor() as isize,
            c.y.floor() as isize,
            c.z.floor() as isize,
        ]
    }

    fn index(&self, c: [isize; 3]) -> usize {
        let cl = |v: isize, d: usize| v.clamp(0, d as isize - 1) as usize;
        (cl(c[2], self.dims[2]) * self.dims[1] + cl(c[1], self.dims[1])) * self.dims[0]
            + cl(c[0], self.dims[0])
    }

    /// Admissible-bucket particles in the cells from `c - reach` to `c + reach` (clipped to
    /// the grid); `None` when a count saturated (the sum would not be a bound).
    fn sum_around(&self, c: [isize; 3], reach: [isize; 3], buckets: &[bool; 6]) -> Option<u64> {
        let range =
            |a: usize| (c[a] - reach[a]).max(0)..=(c[a] + reach[a]).min(self.dims[a] as isize - 1);
        let mut sum = 0u64;
        for z in range(2) {
            for y in range(1) {
                for x in range(0) {
                    let counts = &self.counts[self.index([x, y, z])];
                    for (b, &on) in buckets.iter().enumerate() {
                        if on {
                            if counts[b] == u16::MAX {
                                return None;
                            }
                            sum += counts[b] as u64;
                        }
                    }
                }
            }
        }
        Some(sum)
    }

    /// A radius around `x` expected to hold about `m` admissible particles, assuming they
    /// lie on surfaces: the 3 x 3 x 3 block around `x` holds `S` of them on about `9 cell²`
    /// of surface, so `r = cell · sqrt(9 m / (π S))`.
    fn radius_for(&self, x: Vec3, n: Vec3, m: usize) -> Option<f32> {
        if self.counts.is_empty() {
            return None;
        }
        let sum = self
            .sum_around(self.cell_of(x), [1, 1, 1], &Self::buckets_for(n))
            .unwrap_or(u64::MAX);
        if sum == 0 || sum == u64::MAX {
            return None;
        }
        Some(self.cell * (9.0 * m as f32 / (PI_F32 * sum as f32)).sqrt())
    }

    /// An upper bound on the admissible particles within `max_dist` of `x` (every cell the
    /// ball touches, the buckets that can face `n`); `None` when not cheaply known.
    fn bound_within(&self, x: Vec3, n: Vec3, max_dist: f32) -> Option<u64> {
        if self.counts.is_empty() {
            return Some(0);
        }
        let lo = self.cell_of(x - Vec3::splat(max_dist));
        let hi = self.cell_of(x + Vec3::splat(max_dist));
        let cells: i64 = (0..3).map(|a| (hi[a] - lo[a] + 1) as i64).product();
        if cells > 4096 {
            return None;
        }
        let c = [
            (lo[0] + hi[0]) / 2,
            (lo[1] + hi[1]) / 2,
            (lo[2] + hi[2]) / 2,
        ];
        let reach = [
            (hi[0] - lo[0] + 1) / 2 + 1,
            (hi[1] - lo[1] + 1) / 2 + 1,
            (hi[2] - lo[2] + 1) / 2 + 1,
        ];
        self.sum_around(c, reach, &Self::buckets_for(n))
    }
}

const PI_F32: f32 = std::f32::consts::PI;

// ---- Encodings ----

/// A weight (non-negative, finite) as half-float bits; negative and NaN become 0, values
/// beyond the half range saturate at its largest finite value.
pub fn weight_to_f16(x: f32) -> u16 {
    if !(x > 0.0) {
        return 0;
    }
    half::f16::from_f32(x.min(65504.0)).to_bits()
}

/// Half-float bits to f32.
#[inline]
pub fn f16_to_f32(h: u16) -> f32 {
    half::f16::from_bits(h).to_f32()
}

/// Octahedral mapping of a unit vector to `[-1, 1]²` (Cigolle et al. 2014).
fn oct_encode(v: Vec3) -> Vec2 {
    let l1 = v.x.abs() + v.y.abs() + v.z.abs();
    let p = Vec2::new(v.x, v.y) / l1;
    if v.z < 0.0 {
        Vec2::new(
            (1.0 - p.y.abs()) * p.x.signum(),
            (1.0 - p.x.abs()) * p.y.signum(),
        )
    } else {
        p
    }
}

fn oct_decode(p: Vec2) -> Vec3 {
    let z = 1.0 - p.x.abs() - p.y.abs();
    let (x, y) = if z < 0.0 {
        (
            (1.0 - p.y.abs()) * p.x.signum(),
            (1.0 - p.x.abs()) * p.y.signum(),
        )
    } else {
        (p.x, p.y)
    };
    Vec3::new(x, y, z).normalize()
}

fn quantize(x: f32, levels: f32) -> f32 {
    ((x.clamp(-1.0, 1.0) * 0.5 + 0.5) * levels).round()
}

fn dequantize(q: f32, levels: f32) -> f32 {
    q / levels * 2.0 - 1.0
}

/// A unit direction in 2 x 16 bits (angular error below 0.01°).
pub fn encode_dir16(v: Vec3) -> [u16; 2] {
    let p = oct_encode(v);
    [quantize(p.x, 65535.0) as u16, quantize(p.y, 65535.0) as u16]
}

pub fn decode_dir16(e: [u16; 2]) -> Vec3 {
    oct_decode(Vec2::new(
        dequantize(e[0] as f32, 65535.0),
        dequantize(e[1] as f32, 65535.0),
    ))
}

/// A unit direction in 2 x 8 bits (angular error about 1°): enough for the normal test.
fn encode_dir8(v: Vec3) -> [u8; 2] {
    let p = oct_encode(v);
    [quantize(p.x, 255.0) as u8, quantize(p.y, 255.0) as u8]
}

fn decode_dir8(e: [u8; 2]) -> Vec3 {
    oct_decode(Vec2::new(
        dequantize(e[0] as f32, 255.0),
        dequantize(e[1] as f32, 255.0),
    ))
}

impl ParticleMap {
    /// `particles` (all valid: finite positions, positive weights) in the order a map
    /// built from them keeps them: particle `i` of the result is the map's particle `i`
    /// ([`ParticleMap::get`]).
    pub fn spatial_order(particles: &[ParticleInput]) -> Vec<ParticleInput> {
        let (lo, hi) = bounds(particles.iter().map(|p| p.position));
        in_spatial_order(&particles.iter().collect::<Vec<_>>(), lo, hi)
    }

    /// Builds a map; particles with a non-finite or non-positive weight are dropped.
    pub fn build(kind: MapKind, particles: &[ParticleInput]) -> Self {
        Self::build_from_depth(kind, particles, 0)
    }

    /// Builds a map of the particles that reached their surface in at least `min_depth`
    /// segments (see `GuideParams::min_depth`); particles with a non-finite or non-positive
    /// weight are dropped.
    pub fn build_from_depth(kind: MapKind, particles: &[ParticleInput], min_depth: u16) -> Self {
        let start = Instant::now();
        let valid: Vec<&ParticleInput> = particles
            .iter()
            .filter(|p| {
                p.depth >= min_depth
                    && p.position.is_finite()
                    && p.weight.is_finite()
                    && p.weight.max_element() > 0.0
                    && p.weight.min_element() >= 0.0
            })
            .collect();
        let max_w = valid
            .iter()
            .map(|p| p.weight.max_element())
            .fold(0.0f32, f32::max);
        let (lo, hi) = bounds(valid.iter().map(|p| p.position));
        let valid = in_spatial_order(&valid, lo, hi);
        let centre = if valid.is_empty() {
            Vec3::ZERO
        } else {
            0.5 * (lo + hi)
        };
        // The largest weight maps to 2^15, far below the half range's 65504.
        let scale = if max_w > 0.0 { max_w / 32768.0 } else { 1.0 };
        let records: Vec<Record> = valid
            .par_iter()
            .map(|p| Record {
                dir: encode_dir16(p.dir),
                normal: encode_dir8(p.normal),
                weight: [
                    weight_to_f16(p.weight.x / scale),
                    weight_to_f16(p.weight.y / scale),
                    weight_to_f16(p.weight.z / scale),
                ],
                plane: half::f16::from_f32(
                    p.normal.dot(p.position - centre).clamp(-65504.0, 65504.0),
                )
                .to_bits(),
            })
            .collect();
        let points: Vec<[f32; 3]> = valid.iter().map(|p| p.position.to_array()).collect();
        let with_normals: Vec<(Vec3, Vec3)> =
            valid.iter().map(|p| (p.position, p.normal)).collect();
        let density = DensityGrid::build(&with_normals, lo, hi);
        drop(with_normals);
        let tree = if points.is_empty() {
            None
        } else {
            kiddo::ImmutableKdTree::<f32, 3>::new_from_slice_parallel(&points).ok()
        };
        ParticleMap {
            kind,
            tree,
            records,
            scale,
            centre,
            density,
            build_time: start.elapsed(),
        }
    }

    pub fn len(&self) -> usize {
        self.records.len()
    }

    pub fn is_empty(&self) -> bool {
        self.records.is_empty()
    }

    /// Bytes per particle of the compact record (the tree adds its own; see
    /// `tests/maps.rs` and `footprint maps`, which measure the whole map).
    pub const RECORD_BYTES: usize = std::mem::size_of::<Record>();

    /// The decoded particle `i` (weight back at full scale): the `i`-th of the map's
    /// particles in their spatial order ([`ParticleMap::spatial_order`]).
    pub fn get(&self, i: u32) -> (Vec3, Vec3, Rgb) {
        let r = &self.records[i as usize];
        let w = Rgb::new(
            f16_to_f32(r.weight[0]),
            f16_to_f32(r.weight[1]),
            f16_to_f32(r.weight[2]),
        ) * self.scale;
        (decode_dir16(r.dir), decode_dir8(r.normal), w)
    }

    /// False when fewer than `k` particles that could face `n` lie within `max_dist` of `x`
    /// (a cheap bound from the density grid, no search): a [`ParticleMap::query`] for `k`
    /// would then report fewer than `k`. True means "maybe".
    pub fn may_hold(&self, x: Vec3, n: Vec3, k: usize, max_dist: f32) -> bool {
        match self.density.bound_within(x, n, max_dist) {
            Some(bound) => bound >= k as u64,
            None => true,
        }
    }

    /// Distance of `x` from particle `i`'s tangent plane (as stored, in half precision).
    pub fn plane_distance(&self, i: u32, x: Vec3) -> f32 {
        let (_, normal, _) = self.get(i);
        (normal.dot(x - self.centre) - f16_to_f32(self.records[i as usize].plane)).abs()
    }

    /// The `k` nearest particles to `x` within `max_dist` that face the query normal `n`
    /// (oriented toward the side the query comes from), lie near its tangent plane and have
    /// a positive `contribution`. Writes them to `out` (nearest first) and returns how many.
    pub fn query(
        &self,
        x: Vec3,
        n: Vec3,
        k: usize,
        max_dist: f32,
        mut contribution: impl FnMut(&Neighbor) -> f32,
        out: &mut Vec<Neighbor>,
    ) -> usize {
        out.clear();
        let Some(tree) = &self.tree else { return 0 };
        if k == 0 || !(max_dist > 0.0) {
            return 0;
        }
        let plane = PLANE_FRACTION * max_dist;
        let r2 = max_dist * max_dist;
        let q = x.to_array();
        let xc = x - self.centre;
        // Rules that need no caller, cheapest first: facing the same way, on the same plane.
        let geometric = |i: u32| -> bool {
            let rec = &self.records[i as usize];
            let normal = decode_dir8(rec.normal);
            normal.dot(n) >= NORMAL_COS_MIN
                && (normal.dot(xc) - f16_to_f32(rec.plane)).abs() <= plane
        };
        // Unsorted radius searches, from a radius expected to hold about 2k particles
        // (the density grid), growing until k admissible ones are found or the maximum
        // distance is reached. Once k admissible particles lie within r, the k nearest
        // admissible ones within the maximum distance are among them. Only the nearest
        // geometric candidates are decoded and given to `contribution`.
        let mut r = self
            .density
            .radius_for(x, n, 2 * k)
            .unwrap_or(max_dist)
            .clamp(1e-3 * max_dist, max_dist);
        let mut cands: Vec<(f32, u32)> = Vec::new();
        loop {
            out.clear();
            cands.clear();
            let found = tree
                .query(&q)
                .within::<SquaredEuclidean<f32>>((r * r).min(r2))
                .unsorted()
                .execute();
            cands.extend(
                found
                    .iter()
                    .filter(|nb| geometric(nb.item))
                    .map(|nb| (nb.distance, nb.item)),
            );
            if cands.len() >= k || r >= max_dist {
                // Nearest first (index breaking ties), sorted only as far as needed: each
                // round brings the next `k - found` nearest to the front and sorts them.
                let order =
                    |a: &(f32, u32), b: &(f32, u32)| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1));
                let mut done = 0;
                while done < cands.len() {
                    let end = (done + k - out.len()).min(cands.len());
                    let partial = end < cands.len();
                    let rest = &mut cands[done..];
                    if partial {
                        rest.select_nth_unstable_by(end - done - 1, order);
                    }
                    rest[..end - done].sort_unstable_by(order);
                    for &(dist2, i) in &cands[done..end] {
                        let (dir, normal, weight) = self.get(i);
                        let mut cand = Neighbor {
                            index: i,
                            dist2,
                            dir,
                            normal,
                            weight,
                            contribution: 0.0,
                        };
                        let c = contribution(&cand);
                        if c > 0.0 && c.is_finite() {
                            cand.contribution = c;
                            out.push(cand);
                            if out.len() == k {
                                return k;
                            }
                        }
                    }
                    done = end;
                }
                if r >= max_dist {
                    return out.len();
                }
            }
            // Grow by the shortfall (particles lie on surfaces: count ~ r²), at least 1.5x.
            let have = out.len().max(cands.len().min(k / 2)).max(1);
            let grow = ((k as f32 / have as f32).sqrt() * 1.2).clamp(1.5, 8.0);
            r = (r * grow).min(max_dist);
        }
    }
}
