//! The guide cache: guide distributions prepared once per region of space and normal
//! direction, after the particle passes and before rendering, and shared by every
//! scattering event that falls in the region. It replaces the paper's per-event k-nearest
//! search and build (about 20 µs, the price of dozens of rays: `docs/measurements/speed.md`)
//! by a tree descent.
//!
//! **Regions.** The places where the *other* pass's paths scattered tell where this
//! direction's paths will ask: importon positions for the photon map's cache (camera paths
//! ask the photon map), photon positions and light-emission points for the importance
//! map's cache (light paths ask the importance map). A kd-tree splits those seed points at
//! the median of the longest axis until a cell holds at most `region_seeds` of them and is
//! no wider than the map's query distance; within a leaf, seeds are grouped by the
//! dominant axis of their normal (six buckets, as Open PGL and Practical Path Guiding split
//! space, here with the normal too so that both sides of a wall never share a region).
//!
//! **A region's distribution** depends only on the region: it is built at a canonical point
//! (the seed nearest the bucket's mean position) with the bucket's mean normal, from the
//! particles nearest to it: all those within the region's radius, at least `k_p`, at most
//! `region_particles` (the paper's noise in the distribution itself shrinks with more
//! particles, which a once-per-region build can afford). Particles keep their per-channel
//! weights, so the channel mixture ([`crate::guide::ChannelMix`]) reproduces per-event colour
//! steering exactly for Lambertian surfaces. Fewer than `k_p` particles: the region is
//! marked as not guiding (the fallback decision is cached too). Images do not depend on
//! the thread count: regions are built independently, without random numbers.

use crate::Rgb;
use crate::guide::distribution::{Guide, GuideDistribution, GuideParticle};
use crate::guide::grid::GridDistribution;
use crate::guide::particle_map::{ParticleMap, normal_bucket};
use crate::guide::table::DirectionTable;
use crate::math::{Frame, SIGNED_AXES};
use crate::settings::GuideParams;
use glam::Vec3;
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// A point where a path of the other pass scattered, with the side normal it arrived on.
#[derive(Clone, Copy, Debug)]
pub struct Seed {
    pub position: Vec3,
    pub normal: Vec3,
}

/// One region: where its distribution was built, and the distribution (`None`: the region
/// cannot guide and its events sample the BSDF).
pub struct Region {
    pub centre: Vec3,
    pub normal: Vec3,
    pub particles: u32,
    /// What the map says arrives per unit area in the region: the weights of the particles
    /// the distribution was built from over the disc that holds them, `Σ w_p / (π r²)`
    /// (irradiance for the photon map, importance per m² for the importance map). Guided
    /// Russian roulette reads it (`integrators/src/walk.rs`). `None` where it is not finite
    /// (particles all at one point): those vertices keep the throughput rule.
    pub density: Option<Rgb>,
    pub distribution: Option<RegionDistribution>,
    /// The distribution tabulated for the combined image's MIS weights (`None`: they read
    /// the exact density).
    pub table: Option<DirectionTable>,
}

/// A region's distribution. A raster (what footprints and the grid build for the cache) is
/// held inline in the region, so that a guided event reaches its cell arrays from the
/// region directly (no box holding the distribution, no dynamic call); any other guide's
/// distribution stays boxed.
pub enum RegionDistribution {
    Raster(GridDistribution),
    Boxed(Box<dyn GuideDistribution>),
}

impl RegionDistribution {
    /// Takes a guide's distribution, unboxing a raster.
    pub fn new(d: Box<dyn GuideDistribution>) -> Self {
        match d.as_any().downcast_ref::<GridDistribution>() {
            Some(g) => RegionDistribution::Raster(g.clone()),
            None => RegionDistribution::Boxed(d),
        }
    }

    /// The distribution behind the trait.
    pub fn get(&self) -> &dyn GuideDistribution {
        match self {
            RegionDistribution::Raster(g) => g,
            RegionDistribution::Boxed(d) => d.as_ref(),
        }
    }
}

const NONE: u32 = u32::MAX;

/// A node of the tree that finds a point's region: eight bytes, so that the upper levels
/// stay in the first-level cache (a descent is a chain of dependent loads, one per level; a
/// node large enough to hold the leaf's regions would make it a chain of cache misses).
/// `link`'s top two bits are the split axis (3: a leaf), the rest the right child's index or
/// the leaf's index in [`GuideCache::leaves`] (its region per normal bucket); the left child
/// follows its parent.
#[derive(Clone, Copy, Debug, PartialEq)]
struct PackedNode {
    split: f32,
    link: u32,
}

const LEAF: u32 = 3;
const INDEX_BITS: u32 = 30;

impl PackedNode {
    fn inner(axis: usize, split: f32, right: usize) -> Self {
        assert!(right < 1 << INDEX_BITS, "guide cache tree too large");
        PackedNode {
            split,
            link: (axis as u32) << INDEX_BITS | right as u32,
        }
    }

    /// The split axis (`LEAF` for a leaf) and the right child's or the leaf's index.
    #[inline]
    fn decode(self) -> (u32, u32) {
        (self.link >> INDEX_BITS, self.link & ((1 << INDEX_BITS) - 1))
    }

    fn leaf(index: usize) -> Self {
        assert!(index < 1 << INDEX_BITS, "guide cache tree too large");
        PackedNode {
            split: 0.0,
            link: LEAF << INDEX_BITS | index as u32,
        }
    }
}

/// What the cache cost and holds (printed by `render` and `maps`).
#[derive(Clone, Debug, Default)]
pub struct CacheStats {
    pub seeds: usize,
    pub regions: usize,
    /// Regions with a distribution.
    pub guiding: usize,
    /// Particles over all guiding regions.
    pub particles: u64,
    pub heap_bytes: usize,
    pub build_time: Duration,
}

impl CacheStats {
    pub fn summary(&self) -> String {
        format!(
            "{} regions from {} seeds, {} guide ({:.0} particles each), {:.1} MB ({:.0} bytes/region), built in {:.3} s",
            self.regions,
            self.seeds,
            self.guiding,
            self.particles as f64 / self.guiding.max(1) as f64,
            self.heap_bytes as f64 / 1e6,
            self.heap_bytes as f64 / self.regions.max(1) as f64,
            self.build_time.as_secs_f64()
        )
    }
}

/// The regions and the tree that finds them.
pub struct GuideCache {
    nodes: Vec<PackedNode>,
    /// Where a lookup's descent may start, by a coarse grid over the seeds' box.
    entry: EntryGrid,
    leaves: Vec<[u32; 6]>,
    regions: Vec<Region>,
    /// What every vertex in a region reads, packed apart from the regions (20 bytes each
    /// against a [`Region`]'s 224): a vertex in a region that does not guide, or that
    /// learned BSDF sampling alone, touches no [`Region`] (`docs/measurements/speed.md`,
    /// "Where a guided vertex's time goes").
    summaries: Vec<RegionSummary>,
    pub stats: CacheStats,
}

/// A region's [`Region::density`] and whether it has a distribution.
#[derive(Clone, Copy, Debug)]
pub struct RegionSummary {
    pub density: Option<Rgb>,
    pub guides: bool,
}

impl RegionSummary {
    fn of(r: &Region) -> Self {
        RegionSummary {
            density: r.density,
            guides: r.distribution.is_some(),
        }
    }
}

/// A region to build: its seeds' bucket in one leaf.
#[derive(Debug, PartialEq)]
struct Job {
    centre: Vec3,
    normal: Vec3,
    radius: f32,
}

/// The regions' tree before their distributions: where each region is, from the seeds
/// alone. A render builds it first, so that the map's particles can be counted per region
/// before the map is built (`integrators/src/passes/thinning.rs`, "Thinning by region").
pub struct Partition {
    nodes: Vec<PackedNode>,
    entry: EntryGrid,
    leaves: Vec<[u32; 6]>,
    jobs: Vec<Job>,
    seeds: usize,
    build_time: Duration,
}

impl Partition {
    /// Splits the other pass's scattering points `seeds` into regions (`max_dist`: the
    /// map's query distance, the widest a leaf may be).
    pub fn new(seeds: &[Seed], params: &GuideParams, max_dist: f32) -> Self {
        let start = Instant::now();
        let mut seeds: Vec<Seed> = seeds
            .iter()
            .filter(|s| s.position.is_finite() && s.normal.is_finite())
            .copied()
            .collect();
        let n_seeds = seeds.len();
        let (lo, hi) = crate::math::bounds(seeds.iter().map(|s| s.position));
        let Subtree {
            nodes,
            leaves,
            jobs,
        } = if seeds.is_empty() {
            Subtree::default()
        } else {
            split(&mut seeds, params.region_seeds, max_dist, PARALLEL_SEEDS)
        };
        let entry = EntryGrid::build(&nodes, lo, hi, leaves.len());
        Partition {
            nodes,
            entry,
            leaves,
            jobs,
            seeds: n_seeds,
            build_time: start.elapsed(),
        }
    }

    /// The cells a point may fall in: six normal buckets per leaf of the tree (a cell holds
    /// at most one region, and every point of space falls in one cell).
    pub fn cells(&self) -> usize {
        6 * self.leaves.len().max(1)
    }

    /// The cell of a point `x` on a surface of side normal `n`, in `0..self.cells()`.
    #[inline]
    pub fn cell(&self, x: Vec3, n: Vec3) -> usize {
        6 * leaf_of(&self.nodes, &self.entry, x).unwrap_or(0) + normal_bucket(n)
    }

    /// The centre of the region in `cell` (where its distribution is built, from the
    /// particles nearest it), if the cell holds one.
    pub fn centre(&self, cell: usize) -> Option<Vec3> {
        let r = *self.leaves.get(cell / 6)?.get(cell % 6)?;
        (r != NONE).then(|| self.jobs[r as usize].centre)
    }
}

/// The leaf of the region tree `nodes` holding `x` (a descent from the node `entry` gives).
#[inline(always)]
fn leaf_of(nodes: &[PackedNode], entry: &EntryGrid, x: Vec3) -> Option<usize> {
    // The coordinate of a split's axis read by index from an array rather than by glam's
    // `Index`, whose match becomes a jump table that mispredicts at every node.
    let xs = [x.x, x.y, x.z, 0.0];
    let mut i = entry.start_node(x);
    loop {
        let node = *nodes.get(i)?;
        let (axis, index) = node.decode();
        if axis == LEAF {
            return Some(index as usize);
        }
        i = if xs[(axis & 3) as usize] < node.split {
            i + 1
        } else {
            index as usize
        };
    }
}

impl GuideCache {
    /// Builds the cache of `map` for `guide` over the other pass's scattering points
    /// `seeds`; `max_dist` is the map's query distance.
    pub fn build(
        map: &ParticleMap,
        guide: &dyn Guide,
        seeds: &[Seed],
        params: &GuideParams,
        max_dist: f32,
    ) -> Self {
        Self::from_partition(
            map,
            guide,
            Partition::new(seeds, params, max_dist),
            params,
            max_dist,
        )
    }

    /// Builds the regions of `partition` from `map` (the cache [`GuideCache::build`]
    /// builds, its partition made beforehand; its time counts in the cache's).
    pub fn from_partition(
        map: &ParticleMap,
        guide: &dyn Guide,
        partition: Partition,
        params: &GuideParams,
        max_dist: f32,
    ) -> Self {
        let start = Instant::now();
        let Partition {
            nodes,
            entry,
            leaves,
            jobs,
            seeds: n_seeds,
            build_time: partition_time,
        } = partition;
        let regions: Vec<Region> = jobs
            .par_iter()
            .map(|job| build_region(map, guide, params, max_dist, job))
            .collect();
        let guiding: Vec<&Region> = regions
            .iter()
            .filter(|r| r.distribution.is_some())
            .collect();
        let heap_bytes = nodes.capacity() * std::mem::size_of::<PackedNode>()
            + entry.start.capacity() * 4
            + regions.len() * std::mem::size_of::<RegionSummary>()
            + leaves.capacity() * std::mem::size_of::<[u32; 6]>()
            + regions.capacity() * std::mem::size_of::<Region>()
            + guiding
                .iter()
                .filter_map(|r| r.distribution.as_ref())
                .map(|d| match d {
                    RegionDistribution::Raster(g) => g.heap_bytes(),
                    RegionDistribution::Boxed(b) => b.heap_bytes() + std::mem::size_of_val(&**b),
                })
                .sum::<usize>()
            + guiding
                .iter()
                .filter_map(|r| r.table.as_ref())
                .map(|t| t.heap_bytes())
                .sum::<usize>();
        let stats = CacheStats {
            seeds: n_seeds,
            regions: regions.len(),
            guiding: guiding.len(),
            particles: guiding.iter().map(|r| r.particles as u64).sum(),
            heap_bytes,
            build_time: partition_time + start.elapsed(),
        };
        GuideCache {
            nodes,
            entry,
            leaves,
            summaries: regions.iter().map(RegionSummary::of).collect(),
            regions,
            stats,
        }
    }

    /// The region holding `x` for a surface with side normal `n`, if any seed of the other
    /// pass landed there.
    #[inline]
    pub fn lookup(&self, x: Vec3, n: Vec3) -> Option<&Region> {
        self.lookup_index(x, n).map(|i| &self.regions[i as usize])
    }

    /// The index in [`GuideCache::regions`] of the region [`GuideCache::lookup`] finds.
    #[inline]
    pub fn lookup_index(&self, x: Vec3, n: Vec3) -> Option<u32> {
        let leaf = leaf_of(&self.nodes, &self.entry, x)?;
        let r = self.leaves[leaf][normal_bucket(n)];
        (r != NONE).then_some(r)
    }

    pub fn regions(&self) -> &[Region] {
        &self.regions
    }

    /// Region `i`'s [`RegionSummary`].
    #[inline]
    pub fn summary(&self, i: u32) -> &RegionSummary {
        &self.summaries[i as usize]
    }
}

/// A coarse grid over the seeds' bounding box that tells a lookup where in the region tree
/// its descent may start: for each cell, the deepest node every point of the cell reaches
/// (the descent from the root takes the same side of every split above it for all of the
/// cell's points). The lookup then skips the tree's top levels, a chain of dependent loads
/// and comparisons at every scattering event, and finds the same region
/// (`tests::the_entry_grid_finds_what_the_root_finds`). Points outside the box start at the
/// root.
#[derive(Default)]
struct EntryGrid {
    lo: Vec3,
    /// Cells per unit length along each axis (of the grid's box: the seeds' box, each side at
    /// least [`ENTRY_MIN_THICKNESS`] of the longest).
    scale: Vec3,
    dims: [u32; 3],
    start: Vec<u32>,
}

/// About this many grid cells per leaf of the tree (the cells are cheap, 4 bytes each, and a
/// cell that holds many leaves stops its descent early).
const ENTRY_CELLS_PER_LEAF: usize = 4;

/// At most this many cells (1 MB).
const ENTRY_MAX_CELLS: usize = 1 << 18;

/// The grid's box is at least this thick along every axis, as a share of its longest side:
/// seeds all on one plane (or one line) still get a box of normal floats around them.
const ENTRY_MIN_THICKNESS: f32 = 1e-3;

impl EntryGrid {
    fn build(nodes: &[PackedNode], lo: Vec3, hi: Vec3, leaves: usize) -> Self {
        let longest = (hi - lo).max_element();
        // A single leaf needs no grid; a box too small (or too large) for its cells' sizes
        // to be normal floats gets none either: every lookup then starts at the root.
        if nodes.len() < 2 || !(1e-30..=1e30).contains(&longest) || !lo.is_finite() {
            return EntryGrid::default();
        }
        // The box the grid covers: the seeds' box, each side at least
        // `ENTRY_MIN_THICKNESS` of the longest (a flat axis gets a thin slab of cells).
        let extent = (hi - lo).max(Vec3::splat(longest * ENTRY_MIN_THICKNESS));
        // Cells as near to cubes as the box allows, about `ENTRY_CELLS_PER_LEAF` per leaf,
        // at most `ENTRY_MAX_CELLS` (an axis cut in half until they fit, after rounding).
        let cells = (leaves * ENTRY_CELLS_PER_LEAF).clamp(1, ENTRY_MAX_CELLS) as f32;
        let side = ((extent.x / longest) * (extent.y / longest) * (extent.z / longest) / cells)
            .cbrt()
            * longest;
        if !(side > 0.0) || !side.is_finite() {
            return EntryGrid::default();
        }
        let mut dims = extent
            .to_array()
            .map(|e| ((e / side).round() as u32).clamp(1, 256));
        while dims.iter().map(|&d| d as usize).product::<usize>() > ENTRY_MAX_CELLS {
            let widest = (0..3).max_by_key(|&a| dims[a]).unwrap_or(0);
            dims[widest] = dims[widest].div_ceil(2);
        }
        let dims_f = Vec3::new(dims[0] as f32, dims[1] as f32, dims[2] as f32);
        // The cells' size and its inverse from the same box, so that `start_node`'s cell of
        // a point and the cell boxes below agree to rounding.
        let cell_size = extent / dims_f;
        let scale = dims_f / extent;
        let mut start = Vec::with_capacity((dims[0] * dims[1] * dims[2]) as usize);
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    // The cell's box, widened by a hundredth of a cell: a point that rounding
                    // puts in this cell (`start_node`) lies within it.
                    let c = Vec3::new(i as f32, j as f32, k as f32);
                    let min = lo + (c - 0.01) * cell_size;
                    let max = lo + (c + 1.01) * cell_size;
                    start.push(deepest_common_node(nodes, min, max));
                }
            }
        }
        EntryGrid {
            lo,
            scale,
            dims,
            start,
        }
    }

    /// The node a lookup at `x` may start its descent from (the root outside the grid).
    #[inline]
    fn start_node(&self, x: Vec3) -> usize {
        if self.start.is_empty() {
            return 0;
        }
        let c = (x - self.lo) * self.scale;
        let d = self.dims;
        // `as u32` takes a negative or NaN coordinate to 0: the bounds checks below are
        // against the unconverted values.
        let inside = c.x >= 0.0
            && c.y >= 0.0
            && c.z >= 0.0
            && c.x < d[0] as f32
            && c.y < d[1] as f32
            && c.z < d[2] as f32;
        if !inside {
            return 0;
        }
        let (i, j, k) = (
            (c.x as u32).min(d[0] - 1),
            (c.y as u32).min(d[1] - 1),
            (c.z as u32).min(d[2] - 1),
        );
        self.start[((k * d[1] + j) * d[0] + i) as usize] as usize
    }
}

/// The deepest node of the tree that the descent of every point in the box `[min, max]`
/// passes through.
fn deepest_common_node(nodes: &[PackedNode], min: Vec3, max: Vec3) -> u32 {
    let mut i = 0usize;
    loop {
        let (axis, index) = nodes[i].decode();
        if axis == LEAF {
            return i as u32;
        }
        let split = nodes[i].split;
        i = if max[axis as usize] < split {
            i + 1
        } else if min[axis as usize] >= split {
            index as usize
        } else {
            return i as u32;
        };
    }
}

/// Part of the region tree, its node, leaf and job indices counted from its own start
/// ([`Subtree::append`] moves them to where it lands).
#[derive(Default)]
struct Subtree {
    nodes: Vec<PackedNode>,
    leaves: Vec<[u32; 6]>,
    jobs: Vec<Job>,
}

impl Subtree {
    /// Appends `other` after this subtree's nodes, leaves and jobs.
    fn append(&mut self, other: Subtree) {
        let (n0, l0, j0) = (self.nodes.len(), self.leaves.len(), self.jobs.len() as u32);
        self.nodes.extend(other.nodes.into_iter().map(|node| {
            let (axis, index) = node.decode();
            if axis == LEAF {
                PackedNode::leaf(l0 + index as usize)
            } else {
                PackedNode::inner(axis as usize, node.split, n0 + index as usize)
            }
        }));
        self.leaves.extend(
            other
                .leaves
                .into_iter()
                .map(|leaf| leaf.map(|r| if r == NONE { NONE } else { r + j0 })),
        );
        self.jobs.extend(other.jobs);
    }
}

/// Seeds above which the two halves of a split are built in parallel (the median
/// selection is linear in the seeds: the root's alone is sequential).
const PARALLEL_SEEDS: usize = 1 << 15;

/// Splits `seeds` into leaves (nodes in depth-first order, the left child right after its
/// parent) and queues one job per (leaf, normal bucket). The halves of a split of at least
/// `parallel_from` seeds are built in parallel and joined in the same order: the tree does
/// not depend on the threads.
fn split(seeds: &mut [Seed], max_seeds: usize, max_extent: f32, parallel_from: usize) -> Subtree {
    let (lo, hi) = crate::math::bounds(seeds.iter().map(|s| s.position));
    let ext = hi - lo;
    let axis = if ext.x >= ext.y && ext.x >= ext.z {
        0
    } else if ext.y >= ext.z {
        1
    } else {
        2
    };
    let small = seeds.len() <= max_seeds && ext[axis] <= max_extent;
    if small || seeds.len() < 2 || !(ext[axis] > 0.0) {
        let mut t = Subtree {
            nodes: vec![PackedNode::leaf(0)],
            ..Default::default()
        };
        let leaf = leaf_jobs(seeds, &mut t.jobs);
        t.leaves.push(leaf);
        return t;
    }
    let mid = seeds.len() / 2;
    seeds.select_nth_unstable_by(mid, |a, b| a.position[axis].total_cmp(&b.position[axis]));
    let split_at = seeds[mid].position[axis];
    // Lookups send points below the split value left; the median seed starts the right half.
    let parallel = seeds.len() >= parallel_from;
    let (left, right) = seeds.split_at_mut(mid);
    let (left, right) = if parallel {
        rayon::join(
            || split(left, max_seeds, max_extent, parallel_from),
            || split(right, max_seeds, max_extent, parallel_from),
        )
    } else {
        (
            split(left, max_seeds, max_extent, parallel_from),
            split(right, max_seeds, max_extent, parallel_from),
        )
    };
    let mut t = Subtree {
        nodes: vec![PackedNode::inner(axis, split_at, 1 + left.nodes.len())],
        ..Default::default()
    };
    t.append(left);
    t.append(right);
    t
}

/// One job per normal bucket present in a leaf: the seed nearest the bucket's mean position
/// as the centre, the mean normal, and the bucket's radius around the centre.
fn leaf_jobs(seeds: &[Seed], jobs: &mut Vec<Job>) -> [u32; 6] {
    let mut regions = [NONE; 6];
    for (b, axis) in SIGNED_AXES.iter().enumerate() {
        let members: Vec<&Seed> = seeds
            .iter()
            .filter(|s| normal_bucket(s.normal) == b)
            .collect();
        if members.is_empty() {
            continue;
        }
        let mean = members.iter().map(|s| s.position).sum::<Vec3>() / members.len() as f32;
        let centre = members
            .iter()
            .map(|s| s.position)
            .min_by(|a, b| {
                a.distance_squared(mean)
                    .total_cmp(&b.distance_squared(mean))
            })
            .unwrap_or(mean);
        let normal = members
            .iter()
            .map(|s| s.normal)
            .sum::<Vec3>()
            .try_normalize()
            .unwrap_or(*axis);
        let radius = members
            .iter()
            .map(|s| s.position.distance(centre))
            .fold(0.0f32, f32::max);
        regions[b] = jobs.len() as u32;
        jobs.push(Job {
            centre,
            normal,
            radius,
        });
    }
    regions
}

/// Gathers a region's particles and builds its distribution.
fn build_region(
    map: &ParticleMap,
    guide: &dyn Guide,
    params: &GuideParams,
    max_dist: f32,
    job: &Job,
) -> Region {
    let mut out = Region {
        centre: job.centre,
        normal: job.normal,
        particles: 0,
        density: None,
        distribution: None,
        table: None,
    };
    let mut neighbors = Vec::new();
    let found = map.query(
        job.centre,
        job.normal,
        params.region_particles,
        max_dist,
        |nb| nb.weight.max_element(),
        &mut neighbors,
    );
    if found < params.k_p {
        return out;
    }
    // All particles within the region's radius, at least k_p (nearest first).
    let r2 = job.radius * job.radius;
    let keep = neighbors
        .iter()
        .position(|nb| nb.dist2 > r2)
        .unwrap_or(neighbors.len())
        .max(params.k_p);
    let particles: Vec<GuideParticle> = neighbors[..keep]
        .iter()
        .map(|nb| GuideParticle {
            dir: nb.dir,
            weight: nb.weight,
        })
        .filter(|p| p.admissible(job.normal, params))
        .collect();
    if particles.is_empty() {
        return out;
    }
    out.particles = particles.len() as u32;
    let disc = std::f32::consts::PI * neighbors[keep - 1].dist2;
    let density = particles.iter().map(|p| p.weight).sum::<Rgb>() / disc;
    out.density = crate::math::is_valid_rgb(density).then_some(density);
    let frame = Frame::from_z(job.normal);
    out.distribution = guide
        .build(&frame, &particles, params)
        .map(RegionDistribution::new);
    if params.guided_mis && params.mis_table > 0 {
        out.table = out
            .distribution
            .as_ref()
            .and_then(|d| d.get().tabulate(&frame, params.mis_table));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    /// Building the halves of large splits in parallel gives the tree, leaves and jobs of
    /// the sequential build (its indices moved by `Subtree::append`), and the tree finds
    /// every seed's own region.
    #[test]
    fn the_parallel_split_builds_the_sequential_tree() {
        let mut rng = Rng::new(5, 0, 0);
        let seeds: Vec<Seed> = (0..60_000)
            .map(|i| Seed {
                position: Vec3::new(
                    rng.uniform() * 4.0,
                    rng.uniform() * 2.0,
                    rng.uniform() * 3.0,
                ),
                normal: SIGNED_AXES[i % 6],
            })
            .collect();
        let build = |parallel_from: usize| {
            let mut s = seeds.clone();
            split(&mut s, 500, 0.5, parallel_from)
        };
        let (sequential, parallel) = (build(usize::MAX), build(1000));
        assert!(sequential.leaves.len() > 100, "{}", sequential.leaves.len());
        assert_eq!(sequential.nodes, parallel.nodes);
        assert_eq!(sequential.leaves, parallel.leaves);
        assert_eq!(sequential.jobs, parallel.jobs);
        let cache = GuideCache {
            nodes: parallel.nodes,
            entry: EntryGrid::default(),
            leaves: parallel.leaves,
            regions: Vec::new(),
            summaries: Vec::new(),
            stats: CacheStats::default(),
        };
        for s in seeds.iter().step_by(97) {
            let r = cache
                .lookup_index(s.position, s.normal)
                .expect("a seed's region");
            let job = &parallel.jobs[r as usize];
            assert!(
                job.normal.dot(s.normal) > 0.5,
                "the region of a seed's own normal bucket"
            );
            assert!(job.centre.distance(s.position) <= job.radius + 1e-5);
        }
    }

    /// Builds the tree over `seeds` twice, with and without the entry grid, and checks that
    /// both find the same region at the seeds, at `points`, on every cell boundary of the
    /// grid along each axis (and one float either side), at NaN and at infinity. Returns the
    /// grid.
    fn entry_grid_agrees(
        seeds: &[Seed],
        max_seeds: usize,
        max_extent: f32,
        points: &[Vec3],
    ) -> EntryGrid {
        let tree = || {
            let mut s = seeds.to_vec();
            split(&mut s, max_seeds, max_extent, usize::MAX)
        };
        let cache = |t: Subtree, entry: bool| {
            let (lo, hi) = crate::math::bounds(seeds.iter().map(|s| s.position));
            GuideCache {
                entry: if entry {
                    EntryGrid::build(&t.nodes, lo, hi, t.leaves.len())
                } else {
                    EntryGrid::default()
                },
                nodes: t.nodes,
                leaves: t.leaves,
                regions: Vec::new(),
                summaries: Vec::new(),
                stats: CacheStats::default(),
            }
        };
        let (from_root, mut from_grid) = (cache(tree(), false), cache(tree(), true));
        let grid = std::mem::take(&mut from_grid.entry);
        assert!(
            grid.start.len() <= ENTRY_MAX_CELLS,
            "{} cells",
            grid.start.len()
        );
        let mut at: Vec<Vec3> = seeds.iter().map(|s| s.position).collect();
        at.extend_from_slice(points);
        if !grid.start.is_empty() {
            let (centre, first) = (at[0], grid.lo);
            for axis in 0..3 {
                for k in 0..=grid.dims[axis] {
                    let edge = first[axis] + k as f32 / grid.scale[axis];
                    for v in [edge, edge.next_down(), edge.next_up()] {
                        let mut p = centre;
                        p[axis] = v;
                        at.push(p);
                    }
                }
            }
        }
        at.push(Vec3::NAN);
        at.push(Vec3::splat(f32::INFINITY));
        from_grid.entry = grid;
        for p in at {
            for n in SIGNED_AXES {
                assert_eq!(
                    from_grid.lookup_index(p, n),
                    from_root.lookup_index(p, n),
                    "at {p} facing {n}"
                );
            }
        }
        from_grid.entry
    }

    /// A lookup that starts where the entry grid says finds the region the descent from
    /// the root finds, at random points inside and around clustered seeds, and the grid
    /// skips the tree's top for most cells.
    #[test]
    fn the_entry_grid_finds_what_the_root_finds() {
        let mut rng = Rng::new(9, 0, 0);
        // Two dense blobs and a sparse background, so that the tree's leaves differ in
        // size, as a scene's do.
        let seeds: Vec<Seed> = (0..40_000)
            .map(|i| {
                let u = Vec3::new(rng.uniform(), rng.uniform(), rng.uniform());
                let position = match i % 3 {
                    0 => Vec3::new(0.5, 0.2, 0.1) + 0.1 * u,
                    1 => Vec3::new(3.0, 1.5, 2.0) + 0.3 * u,
                    _ => Vec3::new(-1.0, 0.0, -2.0) + Vec3::new(5.0, 2.0, 5.0) * u,
                };
                Seed {
                    position,
                    normal: SIGNED_AXES[i % 6],
                }
            })
            .collect();
        let points: Vec<Vec3> = (0..20_000)
            .map(|_| {
                let u = Vec3::new(rng.uniform(), rng.uniform(), rng.uniform());
                Vec3::new(-1.5, -0.5, -2.5) + Vec3::new(6.0, 3.0, 6.0) * u
            })
            .collect();
        let grid = entry_grid_agrees(&seeds, 64, 0.25, &points);
        assert!(grid.start.len() > 1000, "{} cells", grid.start.len());
        let skipped = grid.start.iter().filter(|&&n| n > 0).count();
        assert!(
            skipped * 2 > grid.start.len(),
            "most cells start below the root"
        );
    }

    /// Seeds on a plane, on a line, in a box of 1e-25, in one too small for its cells to
    /// be normal floats, and a set whose extent along one axis is subnormal: the grid stays
    /// within its cell budget and finds what the root finds (or is left out and every
    /// lookup starts at the root).
    #[test]
    fn the_entry_grid_of_flat_and_tiny_seed_sets() {
        let mut rng = Rng::new(10, 0, 0);
        let mut u = || rng.uniform();
        let seed = |position: Vec3, i: usize| Seed {
            position,
            normal: SIGNED_AXES[i % 6],
        };
        let plane: Vec<Seed> = (0..20_000)
            .map(|i| seed(Vec3::new(u(), u(), 0.0), i))
            .collect();
        let line: Vec<Seed> = (0..20_000)
            .map(|i| seed(Vec3::new(3.0 * u(), 0.0, 0.0), i))
            .collect();
        let small: Vec<Seed> = (0..2_000)
            .map(|i| seed(Vec3::splat(1e-20) + 1e-25 * Vec3::new(u(), u(), u()), i))
            .collect();
        let tiny: Vec<Seed> = (0..2_000)
            .map(|i| seed(1e-35 * Vec3::new(u(), u(), u()), i))
            .collect();
        let mut subnormal: Vec<Seed> = (0..1_500)
            .map(|i| seed(Vec3::new(0.01 + 0.99 * i as f32 / 1500.0, 0.0, 0.0), i))
            .collect();
        subnormal.push(seed(Vec3::ZERO, 0));
        subnormal.push(seed(Vec3::new(0.0, 1e-39, 0.0), 0));
        let near = |set: &[Seed], spread: f32| -> Vec<Vec3> {
            let mut rng = Rng::new(11, 0, 0);
            set.iter()
                .step_by(7)
                .map(|s| {
                    let d = Vec3::new(rng.uniform(), rng.uniform(), rng.uniform()) - 0.5;
                    s.position + spread * d
                })
                .collect()
        };
        let g = entry_grid_agrees(&plane, 16, 0.05, &near(&plane, 0.01));
        assert!(
            g.start.len() > 100,
            "a plane's grid: {} cells",
            g.start.len()
        );
        let g = entry_grid_agrees(&line, 16, 0.05, &near(&line, 0.01));
        assert!(
            g.start.len() > 100,
            "a line's grid: {} cells",
            g.start.len()
        );
        let g = entry_grid_agrees(&small, 16, 1e-27, &near(&small, 1e-26));
        assert!(
            g.start.len() > 10,
            "a box of 1e-25: {} cells",
            g.start.len()
        );
        let g = entry_grid_agrees(&tiny, 16, 1e-37, &near(&tiny, 1e-36));
        assert!(g.start.is_empty(), "no grid over a box of 1e-35");
        entry_grid_agrees(&subnormal, 1, 0.05, &near(&subnormal, 1e-39));
    }
}
