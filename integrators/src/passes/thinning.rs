//! A pass within its memory budget (`[maps] max_memory`, `--max-memory`): past its share of
//! particles a pass keeps an even sample of them, each kept particle's weight raised by
//! the inverse of the share kept, so that a map's weights still sum, in expectation, to
//! the power (or importance) arriving at its surfaces, and a guide drawn from it is the
//! same distribution in expectation. Guided estimators stay unbiased whatever a map holds
//! (the guides only choose directions, with their true densities), so thinning costs
//! noise, not correctness.
//!
//! **The rule.** At level `k` a particle is kept when the low `k` bits of a hash of its
//! position and direction are zero (a share `2^-k`), its weight multiplied by `2^k`. The
//! levels are nested (what level `k + 1` keeps, level `k` kept), so a pass thins as it
//! goes: after each batch of paths, while its particles are more than its share, the
//! level rises by one. The particles a pass ends with are those of the lowest level at
//! which all its paths' particles fit, whatever the batches were, so they do not depend on
//! the thread count. The points where photon paths leave area lights (the importance
//! cache's seeds) are thinned by the same rule.
//!
//! **The share.** Particles cost [`PEAK_BYTES_PER_PARTICLE`] at the peak of a guided render
//! (both passes' particles as drawn, their maps' trees and records, the spatial sort's copy
//! and the caches' seeds and regions; measured in `docs/measurements/memory.md`), so a
//! budget of `B` bytes allows each of the two passes `B / (2 · PEAK_BYTES_PER_PARTICLE)`.
//!
//! **Thinning by region.** A region of a guide cache builds its distribution from at most
//! `region_particles` particles, those nearest its centre (`footprint::guide::cache`), so
//! where a map is far denser than its regions most of its particles are never read, yet
//! each costs its share of the map's build: on door, whose lit room holds 99.6% of the
//! photons and few of the camera paths' questions, the photon map of 1.6M light paths took
//! 3.9 s to build. Before a cached map is built its particles (those it keeps: of depth
//! `min_depth` or more) are counted per cell of the cache's partition (a leaf of the region tree and a normal bucket: at most one region).
//! In a cell holding more than twice `PARTICLES_PER_REGION · region_particles`, the
//! `PARTICLES_PER_REGION · region_particles` nearest the cell's region's centre are kept as
//! they are, so that the region reads what it would read from the whole map, and the rest
//! are thinned by the same rule at the cell's own level, over the pass's: the least `j`
//! that brings their expected count within as many, their weights times `2^j`
//! ([`thinned_by_cell`]). Each cell's sums stay what they were in expectation, the sparse
//! cells (where guiding needs every particle) keep all of theirs, and the particles kept do
//! not depend on the thread count. Finding each particle's cell has a cost of its own, so a
//! map is thinned only where a sixteenth of its particles says that half or more would go.

use super::pass::PassOutput;
use footprint::guide::cache::Seed;
use footprint::guide::particle_map::ParticleInput;
use glam::Vec3;
use rayon::prelude::*;

/// Heap bytes per particle (of both passes together) at the peak of building the maps and
/// caches of `combined --guide footprint` (the most a render holds): 173 measured on door
/// (`docs/measurements/memory.md`), with a tenth more for what a pass holds past its
/// budget until its next check.
pub const PEAK_BYTES_PER_PARTICLE: u64 = 192;

/// The most particles each pass may keep within a budget of `bytes` (the two passes share
/// it evenly).
pub fn max_particles(bytes: u64) -> usize {
    (bytes / (2 * PEAK_BYTES_PER_PARTICLE)).max(1) as usize
}

/// The hash that decides a particle's fate (a SplitMix64 finaliser over its bits).
fn hash(a: Vec3, b: Vec3) -> u64 {
    let mut h = 0x9e37_79b9_7f4a_7c15u64;
    for x in a.to_array().into_iter().chain(b.to_array()) {
        h ^= x.to_bits() as u64;
        h = (h ^ (h >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        h = (h ^ (h >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        h ^= h >> 31;
    }
    h
}

/// Whether a particle at `(a, b)` is kept at `level`.
fn kept(a: Vec3, b: Vec3, level: u32) -> bool {
    level == 0 || hash(a, b).trailing_zeros() >= level
}

/// Brings particles and seeds kept at level `from` to level `to >= from`.
pub(super) fn thin(particles: &mut Vec<ParticleInput>, seeds: &mut Vec<Seed>, from: u32, to: u32) {
    if to <= from {
        return;
    }
    let scale = (1u64 << (to - from).min(63)) as f32;
    particles.retain_mut(|p| {
        let keep = kept(p.position, p.dir, to);
        p.weight *= scale;
        keep
    });
    seeds.retain(|s| kept(s.position, s.normal, to));
}

/// What a pass has kept so far, at its thinning level: the batches of a pass are appended
/// in order (`ChunkOut::append`, each thinned to the level) and the level raised after each
/// while the particles are more than the pass's share ([`Kept::within`]). The particles kept
/// in the end do not depend on the batches.
pub(super) struct Kept<'a> {
    pub(super) particles: &'a mut Vec<ParticleInput>,
    pub(super) seeds: &'a mut Vec<Seed>,
    pub(super) level: &'a mut u32,
}

impl Kept<'_> {
    /// Raises the level while the particles are more than `max`.
    pub(super) fn within(self, max: usize) {
        while self.particles.len() > max && *self.level < 63 {
            let from = *self.level;
            *self.level += 1;
            thin(self.particles, self.seeds, from, *self.level);
        }
    }
}

/// The particles nearest a region's centre kept as they are, in multiples of
/// `region_particles` (what the region reads at most): a cell holding more than twice as
/// many keeps those and about as many again of the rest, thinned.
pub const PARTICLES_PER_REGION: usize = 2;

/// Thinning by region is done only where it is estimated to drop at least this share of
/// the particles: finding the particles' cells costs a fifth to more than all of what the
/// dropped particles save the map's and cache's builds (door, 12.8M particles, 95%
/// dropped: 0.79 s against about 4 s saved; desk, 29% dropped by an even sample of each
/// dense cell: 0.13 s against 0.08 s saved).
pub const MIN_DROPPED_SHARE: f64 = 0.5;

/// The estimate of [`MIN_DROPPED_SHARE`] reads every this-many-th particle.
const ESTIMATE_STRIDE: usize = 16;

/// The cells of a cache's partition as thinning reads them.
pub struct Cells<C, R> {
    /// How many cells there are.
    pub count: usize,
    /// The cell of a particle, in `0..count`.
    pub of: C,
    /// The centre of the region in a cell, where the cell holds one.
    pub centre: R,
}

/// `particles` (kept at the pass's thinning `level`) thinned where a cell holds more than
/// `2 per_cell` of them. In such a cell, the `per_cell` particles nearest its region's
/// centre are kept as they are (what the region reads: its distribution and density are
/// those of the unthinned map), and the rest at the least `j` with `rest / 2^j <=
/// per_cell`, on top of `level`, their weights times `2^j` (a cell without a region thins
/// all of its particles so). `None` when no cell holds more, or when every
/// [`ESTIMATE_STRIDE`]-th particle says that less than [`MIN_DROPPED_SHARE`] of them
/// would go. Particles below `min_depth`, which the map leaves out, count in no cell and
/// are dropped.
pub fn thinned_by_cell<C, R>(
    particles: &[ParticleInput],
    level: u32,
    min_depth: u16,
    cells: Cells<C, R>,
    per_cell: usize,
) -> Option<Vec<ParticleInput>>
where
    C: Fn(&ParticleInput) -> usize + Sync,
    R: Fn(usize) -> Option<Vec3> + Sync,
{
    let per_cell = per_cell.max(1);
    let n_cells = cells.count.max(1);
    // Particles the map leaves out (below `min_depth`) are in no cell, and dropped.
    const OUT: u32 = u32::MAX;
    let cell = |p: &ParticleInput| {
        if p.depth < min_depth {
            OUT
        } else {
            (cells.of)(p).min(n_cells - 1) as u32
        }
    };
    // A cell's particles kept as they are, and the level of the rest, for its count.
    let plan = |c: usize, n: usize| -> (usize, u32) {
        if n <= 2 * per_cell {
            return (n, 0);
        }
        let exact = if (cells.centre)(c).is_some() {
            per_cell
        } else {
            0
        };
        let mut j = 0u32;
        while (n - exact) >> j > per_cell && level + j < 63 {
            j += 1;
        }
        (exact, j)
    };
    let kept_of = |c: usize, n: usize| {
        let (exact, j) = plan(c, n);
        exact as f64 + (n - exact) as f64 / (1u64 << j) as f64
    };
    // The estimate: the counts of every ESTIMATE_STRIDE-th particle, scaled.
    let mut counts = vec![0usize; n_cells];
    for c in particles.iter().step_by(ESTIMATE_STRIDE).map(cell) {
        if c != OUT {
            counts[c as usize] += ESTIMATE_STRIDE;
        }
    }
    let kept_estimate: f64 = counts.iter().enumerate().map(|(c, &n)| kept_of(c, n)).sum();
    let in_cells: usize = counts.iter().sum();
    if kept_estimate > (1.0 - MIN_DROPPED_SHARE) * in_cells as f64 {
        return None;
    }
    let of: Vec<u32> = particles.par_iter().map(cell).collect();
    counts.iter_mut().for_each(|n| *n = 0);
    for &c in of.iter().filter(|&&c| c != OUT) {
        counts[c as usize] += 1;
    }
    let plans: Vec<(usize, u32)> = counts
        .iter()
        .enumerate()
        .map(|(c, &n)| plan(c, n))
        .collect();
    if plans.iter().all(|&(_, j)| j == 0) {
        return None;
    }
    // The particles of each cell that keeps some as they are, by a counting sort of their
    // indices; then each such cell's nearest to its centre (ties by index), in parallel.
    let mut start = vec![0usize; n_cells + 1];
    for c in 0..n_cells {
        let exact = plans[c].1 > 0 && plans[c].0 > 0;
        start[c + 1] = start[c] + if exact { counts[c] } else { 0 };
    }
    let mut members = vec![0u32; start[n_cells]];
    let mut fill = start.clone();
    for (i, &c) in of.iter().enumerate().filter(|&(_, &c)| c != OUT) {
        let c = c as usize;
        if start[c + 1] > start[c] {
            members[fill[c]] = i as u32;
            fill[c] += 1;
        }
    }
    let mut exact = vec![false; particles.len()];
    let nearest: Vec<Vec<u32>> = (0..n_cells)
        .into_par_iter()
        .filter(|&c| start[c + 1] > start[c])
        .map(|c| {
            let centre = (cells.centre)(c).unwrap_or(Vec3::ZERO);
            let mut by_distance: Vec<(f32, u32)> = members[start[c]..start[c + 1]]
                .iter()
                .map(|&i| (particles[i as usize].position.distance_squared(centre), i))
                .collect();
            let k = plans[c].0;
            by_distance
                .select_nth_unstable_by(k - 1, |a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            by_distance[..k].iter().map(|&(_, i)| i).collect()
        })
        .collect();
    for i in nearest.into_iter().flatten() {
        exact[i as usize] = true;
    }
    Some(
        particles
            .par_iter()
            .zip(of.par_iter())
            .zip(exact.par_iter())
            .filter_map(|((p, &c), &exact)| {
                if c == OUT {
                    return None;
                }
                let j = plans[c as usize].1;
                if exact || j == 0 {
                    return Some(*p);
                }
                kept(p.position, p.dir, level + j).then(|| {
                    let mut q = *p;
                    q.weight *= (1u64 << j) as f32;
                    q
                })
            })
            .collect(),
    )
}

impl PassOutput {
    /// Thins this pass (kept at `self.stats.thinning`) to `level`.
    pub fn thin_to(&mut self, level: u32) {
        let from = self.stats.thinning;
        thin(&mut self.particles, &mut self.emission_points, from, level);
        self.stats.thinning = self.stats.thinning.max(level);
        self.forget_seed_count(from);
    }

    /// A view pass thinned past `from` no longer knows which of its particles its seeding
    /// paths stored (`PassStats::seed_particles`): its cache then reads them all.
    fn forget_seed_count(&mut self, from: u32) {
        if self.stats.thinning > from {
            self.stats.seed_particles = None;
        }
    }

    /// Thins this pass until it holds at most `max` particles.
    pub fn within(&mut self, max: usize) {
        let from = self.stats.thinning;
        let kept = Kept {
            particles: &mut self.particles,
            seeds: &mut self.emission_points,
            level: &mut self.stats.thinning,
        };
        kept.within(max);
        self.forget_seed_count(from);
    }

    /// The share of the drawn particles this pass kept: `2^-thinning`.
    pub fn kept_share(&self) -> f64 {
        0.5f64.powi(self.stats.thinning as i32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use footprint::Rgb;

    fn particles(n: usize) -> Vec<ParticleInput> {
        (0..n)
            .map(|i| ParticleInput {
                position: Vec3::new(i as f32 * 0.37, (i % 17) as f32, 1.0),
                dir: Vec3::Z,
                normal: Vec3::Z,
                weight: Rgb::splat(1.0),
                depth: 1,
                specular_chain: false,
            })
            .collect()
    }

    /// Each particle's position and weight, bit for bit.
    fn bits(p: &[ParticleInput]) -> Vec<[u32; 4]> {
        p.iter()
            .map(|q| {
                let (a, w) = (q.position.to_array(), q.weight.x);
                [a[0], a[1], a[2], w].map(f32::to_bits)
            })
            .collect()
    }

    /// The levels nest, each keeps about half of the one before (a binomial count within
    /// 5 standard deviations), and the kept weights sum to the drawn ones within the same
    /// bound.
    #[test]
    fn each_level_keeps_half_of_the_one_before_and_the_weights_sum_stays() {
        let n = 100_000;
        let all = particles(n);
        let mut last = all.clone();
        for level in 1..=6 {
            let mut p = all.clone();
            thin(&mut p, &mut Vec::new(), 0, level);
            let expect = n as f64 / (1u64 << level) as f64;
            let sd = (expect * (1.0 - 0.5f64.powi(level as i32))).sqrt();
            assert!(
                (p.len() as f64 - expect).abs() < 5.0 * sd,
                "level {level}: {} of {n}",
                p.len()
            );
            let sum: f64 = p.iter().map(|q| q.weight.x as f64).sum();
            assert!((sum - n as f64).abs() < 5.0 * sd * (1u64 << level) as f64);
            // Thinning the level before (a superset) gives the same particles and weights.
            thin(&mut last, &mut Vec::new(), level - 1, level);
            assert_eq!(last.len(), p.len());
            let same = |a: &ParticleInput, b: &ParticleInput| {
                a.position == b.position && a.weight == b.weight
            };
            assert!(last.iter().zip(&p).all(|(a, b)| same(a, b)));
            last = p;
        }
    }

    /// The particles a pass keeps do not depend on its batches (so neither on its thread
    /// count): the same 100,000 particles appended in batches of 1,000, 7,000 and all at
    /// once, each followed by the budget check, end at the same level with the same
    /// particles and weights, bit for bit, and within the budget.
    #[test]
    fn the_particles_kept_do_not_depend_on_the_batches() {
        let all = particles(100_000);
        let max = 9_000;
        let run = |batch: usize| {
            let (mut kept, mut seeds, mut level) = (Vec::new(), Vec::new(), 0u32);
            for chunk in all.chunks(batch) {
                // A batch drawn at level 0, thinned to the level kept so far, appended.
                let mut drawn = chunk.to_vec();
                thin(&mut drawn, &mut Vec::new(), 0, level);
                kept.append(&mut drawn);
                let k = Kept {
                    particles: &mut kept,
                    seeds: &mut seeds,
                    level: &mut level,
                };
                k.within(max);
            }
            (kept, level)
        };
        let (once, level) = run(all.len());
        assert!(
            level >= 4 && once.len() <= max,
            "level {level}, {} kept",
            once.len()
        );
        for batch in [1_000, 7_000] {
            let (kept, l) = run(batch);
            assert_eq!(l, level, "batches of {batch}");
            assert_eq!(bits(&kept), bits(&once), "batches of {batch}");
        }
    }

    /// Thinning by region: a cell within twice `per_cell` keeps every particle, bit for
    /// bit; a dense cell with a region keeps the `per_cell` particles nearest the region's
    /// centre bit for bit (found here by a full sort) and about `rest / 2^j` of the rest (a
    /// binomial count within 5 standard deviations) at the least `j` that brings them within
    /// `per_cell`, their weights summing to the rest's drawn sum within the same bound; a
    /// dense cell without a region thins all of its particles so; on a pass already thinned
    /// to level 2 such a cell keeps exactly what thinning the whole pass to level `2 + j`
    /// keeps.
    #[test]
    fn thinning_by_cell_keeps_each_regions_nearest_and_each_cells_sum() {
        // Cells by index: 100 particles, then 50,000 (with a region), then 20,000 (without).
        let all = particles(70_100);
        let bound = [100.0 * 0.37, 50_100.0 * 0.37];
        let cell_of = |p: &ParticleInput| {
            let x = p.position.x;
            if x < bound[0] - 0.1 {
                0
            } else if x < bound[1] - 0.1 {
                1
            } else {
                2
            }
        };
        let centre = Vec3::new(10_000.0 * 0.37, 8.0, 1.0);
        let cells = |level_centre: Option<Vec3>| Cells {
            count: 3,
            of: cell_of,
            centre: move |c| if c == 1 { level_centre } else { None },
        };
        let per_cell = 1_000;
        let thinned =
            thinned_by_cell(&all, 0, 1, cells(Some(centre)), per_cell).expect("dense cells thin");
        let in_cell = |ps: &[ParticleInput], c: usize| -> Vec<ParticleInput> {
            ps.iter().filter(|p| cell_of(p) == c).copied().collect()
        };
        assert_eq!(bits(&in_cell(&thinned, 0)), bits(&in_cell(&all, 0)));
        // Cell 1's nearest to the centre, by a full sort (ties by index).
        let mut order: Vec<usize> = (0..all.len()).filter(|&i| cell_of(&all[i]) == 1).collect();
        order.sort_by(|&a, &b| {
            let d = |i: usize| all[i].position.distance_squared(centre);
            d(a).total_cmp(&d(b)).then(a.cmp(&b))
        });
        let nearest: Vec<ParticleInput> = {
            let mut idx = order[..per_cell].to_vec();
            idx.sort();
            idx.iter().map(|&i| all[i]).collect()
        };
        let kept1 = in_cell(&thinned, 1);
        let is_near = |q: &ParticleInput| nearest.iter().any(|n| n.position == q.position);
        let (near, rest): (Vec<ParticleInput>, Vec<ParticleInput>) =
            kept1.iter().partition(|q| is_near(q));
        assert_eq!(bits(&near), bits(&nearest));
        // 49,000 / 2^6 = 766 and 20,000 / 2^5 = 625 are the first within 1,000.
        for (what, kept, n, j) in [
            ("cell 1's rest", rest, 49_000usize, 6u32),
            ("cell 2", in_cell(&thinned, 2), 20_000, 5),
        ] {
            let share = 0.5f64.powi(j as i32);
            let expect = n as f64 * share;
            let sd = (n as f64 * share * (1.0 - share)).sqrt();
            assert!(
                (kept.len() as f64 - expect).abs() < 5.0 * sd,
                "{what}: {} kept",
                kept.len()
            );
            let sum: f64 = kept.iter().map(|q| q.weight.x as f64).sum();
            assert!(
                (sum - n as f64).abs() < 5.0 * sd / share,
                "{what}: weights sum to {sum}"
            );
        }
        // On a pass at level 2: cell 2 (about 5,000 left) goes to level 2 + 3.
        let mut pass = all.clone();
        thin(&mut pass, &mut Vec::new(), 0, 2);
        let thinned =
            thinned_by_cell(&pass, 2, 1, cells(Some(centre)), per_cell).expect("dense cells thin");
        let mut whole = all.clone();
        thin(&mut whole, &mut Vec::new(), 0, 5);
        assert_eq!(bits(&in_cell(&thinned, 2)), bits(&in_cell(&whole, 2)));
    }

    /// Particles below `min_depth`, which the map leaves out, count in no cell and are
    /// dropped: of 70,100 particles every second one at depth 1, with `min_depth` 2, a sparse
    /// cell keeps its 50 of depth 2 bit for bit and a dense cell of 35,000 of depth 2 keeps
    /// about 35,000 / 2^6 (within 5 binomial standard deviations; counted with its depth-1
    /// particles, it would go to 2^7).
    #[test]
    fn thinning_by_cell_counts_only_what_the_map_keeps() {
        let mut all = particles(70_100);
        for (i, p) in all.iter_mut().enumerate() {
            p.depth = 1 + (i % 2) as u16;
        }
        let cells = Cells {
            count: 2,
            of: |p: &ParticleInput| usize::from(p.position.x > 100.0 * 0.37 - 0.1),
            centre: |_| None,
        };
        let thinned = thinned_by_cell(&all, 0, 2, cells, 1_000).expect("the dense cell thins");
        assert!(thinned.iter().all(|p| p.depth >= 2));
        let deep = |ps: &[ParticleInput], sparse: bool| -> Vec<ParticleInput> {
            ps.iter()
                .filter(|p| p.depth >= 2 && (p.position.x < 100.0 * 0.37 - 0.1) == sparse)
                .copied()
                .collect()
        };
        assert_eq!(bits(&deep(&thinned, true)), bits(&deep(&all, true)));
        let (n, share) = (35_000.0, 0.5f64.powi(6));
        let sd = (n * share * (1.0 - share)).sqrt();
        let kept = deep(&thinned, false).len() as f64;
        assert!((kept - n * share).abs() < 5.0 * sd, "{kept} kept");
    }

    /// Thinning by region is skipped where it would drop less than half of the particles:
    /// every cell within twice `per_cell`, or one dense cell among many sparse ones.
    #[test]
    fn thinning_by_cell_is_skipped_where_it_drops_little() {
        let all = particles(40_000);
        let by = |size: f32, from: f32| Cells {
            count: 40,
            of: move |p: &ParticleInput| ((p.position.x / (size * 0.37)).max(from) - from) as usize,
            centre: |_| None,
        };
        // 40 cells of 1,000.
        assert!(thinned_by_cell(&all, 0, 1, by(1_000.0, 0.0), 600).is_none());
        // A cell of 10,000 (the first) among 30 of 1,000: a fifth would go.
        assert!(thinned_by_cell(&all, 0, 1, by(1_000.0, 9.0), 600).is_none());
        // With every cell of 10,000, the thinning is done.
        assert!(thinned_by_cell(&all, 0, 1, by(10_000.0, 0.0), 600).is_some());
    }
}
