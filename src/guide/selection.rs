//! The BSDF selection probability `p_BSDF`, learned per region of the guide cache from the
//! render's own samples (Müller et al. 2019, "Practical Path Guiding for Efficient
//! Light-Transport Simulation", §5 learn theirs by gradient descent on the same objective;
//! here a small grid of candidates is searched exactly instead).
//!
//! **Objective.** At a guided vertex the direction is drawn from the one-sample mixture
//! `p_α(ω) = α p_bsdf(ω) + (1 - α) p_guide(ω)`, and the vertex's estimate of its reflected
//! radiance is `g(ω) / p_α(ω)` with `g = f · |cos| · L_i`. Its second moment
//! `M(α) = ∫ g² / p_α dω` is what the region's `α` should minimise. A sample drawn with
//! `α_0` estimates `M(α)` for *every* `α` by importance sampling:
//! `M̂(α) = g² / (p_α · p_α0) = X² · p_α0 / p_α`, where `X = g / p_α0` is what the path
//! brought back through that vertex per unit throughput arriving there (the sum of the
//! path's later contributions divided by its throughput `β` at the vertex; luminance).
//!
//! **Weighed by what the vertex is worth to the image.** A pixel's variance gathers each
//! of its paths' vertices' as `β² Var[X]` (the law of total variance over the path's
//! choices), so a region's vertices count by their `β²`: every guided vertex whose path
//! found light adds `(β X)² p_α0 / p_α` to each candidate's sum, `β X` being simply what
//! came back through the vertex in the path's estimate. Counted unweighted, a vertex deep
//! in a dim path would weigh as much as a first bounce seen by the camera, and the region
//! would choose for the vertices that matter least. The region takes the candidate with
//! the smallest sum once it has [`MIN_RECORDS`] such vertices.
//!
//! **Before a region has learned**, it takes the cache's pooled choice: the same sums over
//! every region's records (the choice of the vertices the image weighs most, wherever they
//! fell), at most [`MAX_POOLED_P_BSDF`], once the cache holds [`MIN_RECORDS`] records; the
//! configured default before that. Most regions are visited too rarely to learn within a
//! short budget (Modern Hall at 8 s: 483 of 1,751), and where the guide does not pay, as in
//! a sky-lit room whose sparse photon map guides from 50 particles a region, the default
//! even mixture cost 1.3-1.5x BSDF sampling at equal time where the pooled choice
//! (`p_BSDF = 0.9` there) costs nothing (`docs/measurements/guided-vs-bsdf.md`,
//! "Pooled selection"). Capped below 1, a region still reads its distribution and gathers
//! the records that give it its own choice. The pool counts every record alike, so the
//! busiest regions weigh most, and regions that learned BSDF sampling alone add no more
//! records: over a long render the pool leans toward the regions where guiding pays.
//!
//! **Guiding where it pays for its time.** A guided vertex costs more than an unguided one
//! (the region's distribution read at the sampled direction and at the light sample's,
//! or drawn from), so the sums of the guided candidates are weighed by
//! [`GUIDED_VERTEX_COST`] against the last candidate, `α = 1`: BSDF sampling alone, which
//! reads nothing of the region. A region whose vertices the guide does not help by more
//! than its cost takes `α = 1` and is no longer guided (its vertices cost what unguided
//! ones do, and teach nothing more: the choice is final). Efficiency is the inverse of
//! variance times time; with the time of a region's vertices `c(α)` and the second moment
//! `M(α)` standing for the variance, the region minimises `M(α) c(α)`.
//!
//! **Unbiased and reproducible.** The probabilities change only between passes, from
//! records gathered in earlier passes: every pass samples with fixed, valid mixtures, so
//! its estimate is unbiased whatever the learned values. The render hands the records over
//! in row order ([`SelectionLearner::absorb`]), so the sums, and the image, do not depend on
//! the thread count.

#[allow(unused_imports)] // the doc links
use crate::guide::cache::GuideCache;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU32, Ordering};

/// The candidate probabilities. Never 0: the BSDF keeps a share wherever the guide could
/// miss a direction the BSDF favours (a defensive mixture). The last, 1, is BSDF sampling
/// alone: a region takes it where guiding does not pay for its time
/// ([`GUIDED_VERTEX_COST`]).
pub const CANDIDATES: [f32; 10] = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0];

/// The time of a guided vertex over an unguided one's, by which the guided candidates'
/// second moments are weighed against BSDF sampling alone. Guided path tracing draws
/// 0.62-0.75 of the unguided paths per second (`docs/measurements/speed.md`: about 0.34 µs
/// per guided event against 0.7-1.2 µs of an unguided vertex, its rays included); 1.25 is
/// the low end, so that a region leaves guiding only where it measurably does not pay.
pub const GUIDED_VERTEX_COST: f64 = 1.25;

/// Vertices with a non-zero return a region needs before its probability is learned. The
/// second-moment estimates are heavy-tailed: with a few dozen records the choice follows the
/// noise to the grid's ends (the learning: `docs/guiding.md`, "`p_BSDF` learned per
/// region").
pub const MIN_RECORDS: u64 = 512;

/// The most a region short of its own [`MIN_RECORDS`] takes of the cache's pooled choice:
/// a region at 1 would read nothing of its distribution and gather no records of its own.
pub const MAX_POOLED_P_BSDF: f32 = 0.9;

/// What one guided vertex of a finished path teaches its region.
#[derive(Clone, Copy, Debug)]
pub struct SelectionRecord {
    pub region: u32,
    /// `(β X)²`: the square of what came back through the vertex in the path's estimate
    /// (luminance; see the module doc).
    pub returned2: f32,
    /// Densities per steradian of the sampled direction: the BSDF's, the guide's and the
    /// mixture's the direction was drawn with.
    pub pdf_bsdf_w: f32,
    pub pdf_guide_w: f32,
    pub pdf_w: f32,
}

/// A region's sums: `Σ (β X)² p_α0 / p_α` per candidate, and how many records made them.
#[derive(Clone, Copy, Debug, Default)]
struct RegionSums {
    moments: [f64; CANDIDATES.len()],
    records: u64,
}

impl RegionSums {
    /// Adds a valid record.
    fn add(&mut self, r: &SelectionRecord) {
        for (m, &a) in self.moments.iter_mut().zip(&CANDIDATES) {
            let p_a = a * r.pdf_bsdf_w + (1.0 - a) * r.pdf_guide_w;
            // For a < 1, p_a >= min(a, 1 - a) · (p_bsdf + p_guide) > 0 wherever pdf_w > 0;
            // BSDF sampling alone cannot draw a direction of BSDF density 0 that brought
            // light back: its second moment is unbounded.
            *m += if p_a > 0.0 {
                r.returned2 as f64 * r.pdf_w as f64 / p_a as f64
            } else {
                f64::INFINITY
            };
        }
        self.records += 1;
    }

    /// The candidate of least second moment times cost, once [`MIN_RECORDS`] records made
    /// the sums.
    fn best(&self) -> Option<f32> {
        if self.records < MIN_RECORDS {
            return None;
        }
        let cost = |j: usize| {
            let c = if CANDIDATES[j] < 1.0 {
                GUIDED_VERTEX_COST
            } else {
                1.0
            };
            self.moments[j] * c
        };
        (0..CANDIDATES.len())
            .min_by(|&a, &b| cost(a).total_cmp(&cost(b)))
            .map(|j| CANDIDATES[j])
    }
}

/// The learned probabilities of one guide cache's regions, for one render.
pub struct SelectionLearner {
    /// `p_BSDF` per region, as `f32` bits: read by every guided vertex, written between
    /// passes.
    p_bsdf: Vec<AtomicU32>,
    sums: Mutex<Learned>,
    default: f32,
}

/// The sums per region, and pooled over the cache.
struct Learned {
    regions: Vec<RegionSums>,
    pooled: RegionSums,
}

impl SelectionLearner {
    /// A learner for the `n` regions of a guide cache ([`GuideCache::regions`]), every one
    /// starting at `default`.
    pub fn new(n: usize, default: f32) -> Self {
        SelectionLearner {
            p_bsdf: (0..n).map(|_| AtomicU32::new(default.to_bits())).collect(),
            sums: Mutex::new(Learned {
                regions: vec![RegionSums::default(); n],
                pooled: RegionSums::default(),
            }),
            default,
        }
    }

    /// The probability of sampling the BSDF in region `region`.
    #[inline]
    pub fn p_bsdf(&self, region: u32) -> f32 {
        self.p_bsdf
            .get(region as usize)
            .map_or(self.default, |p| f32::from_bits(p.load(Ordering::Relaxed)))
    }

    /// Adds `records` (in a fixed order) to the sums and sets every region's probability:
    /// its own choice where it has enough records, else the cache's pooled choice (at most
    /// [`MAX_POOLED_P_BSDF`]), else the default. Call between passes only.
    pub fn absorb(&self, records: &[SelectionRecord]) {
        let mut learned = self.sums.lock().unwrap_or_else(|e| e.into_inner());
        let Learned { regions, pooled } = &mut *learned;
        for r in records {
            let Some(s) = regions.get_mut(r.region as usize) else {
                continue;
            };
            let valid = r.returned2.is_finite()
                && r.returned2 > 0.0
                && r.pdf_w.is_finite()
                && r.pdf_w > 0.0
                && r.pdf_bsdf_w.is_finite()
                && r.pdf_bsdf_w >= 0.0
                && r.pdf_guide_w.is_finite()
                && r.pdf_guide_w >= 0.0;
            if !valid {
                continue;
            }
            s.add(r);
            pooled.add(r);
        }
        // Regions short of their own records take the cache's pooled choice, at most
        // `MAX_POOLED_P_BSDF` so that they keep guiding a share of their vertices and
        // gathering the records of their own choice.
        let prior = self.p_bsdf_before_learning(pooled);
        for (i, s) in regions.iter().enumerate() {
            let p = s.best().unwrap_or(prior);
            self.p_bsdf[i].store(p.to_bits(), Ordering::Relaxed);
        }
    }

    /// Regions that have learned their own probability so far, and all regions.
    pub fn learned_regions(&self) -> (usize, usize) {
        let sums = self.sums.lock().unwrap_or_else(|e| e.into_inner());
        let learned = sums
            .regions
            .iter()
            .filter(|s| s.records >= MIN_RECORDS)
            .count();
        (learned, sums.regions.len())
    }

    /// Regions learned so far, and the mean and range of their probabilities.
    pub fn summary(&self) -> String {
        let sums = self.sums.lock().unwrap_or_else(|e| e.into_inner());
        let others = format!("others {}", self.p_bsdf_before_learning(&sums.pooled));
        let learned: Vec<f32> = sums
            .regions
            .iter()
            .enumerate()
            .filter(|(_, s)| s.records >= MIN_RECORDS)
            .map(|(i, _)| self.p_bsdf(i as u32))
            .collect();
        if learned.is_empty() {
            return format!(
                "p_BSDF learned in 0 of {} regions ({others})",
                sums.regions.len(),
            );
        }
        let mean = learned.iter().sum::<f32>() / learned.len() as f32;
        let (lo, hi) = learned
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        let counts: Vec<String> = CANDIDATES
            .iter()
            .map(|&c| format!("{c}: {}", learned.iter().filter(|&&p| p == c).count()))
            .collect();
        format!(
            "p_BSDF learned in {} of {} regions (mean {mean:.2}, {lo}..{hi}; {}; {others})",
            learned.len(),
            sums.regions.len(),
            counts.join(", "),
        )
    }

    /// What a region short of its own records takes: the pooled choice, at most
    /// [`MAX_POOLED_P_BSDF`]; the default until the cache has pooled enough records.
    fn p_bsdf_before_learning(&self, pooled: &RegionSums) -> f32 {
        pooled
            .best()
            .map_or(self.default, |p| p.min(MAX_POOLED_P_BSDF))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` records of region 0 drawn with the even mixture, all with the same densities.
    fn records(n: u64, pdf_bsdf_w: f32, pdf_guide_w: f32) -> Vec<SelectionRecord> {
        (0..n)
            .map(|_| SelectionRecord {
                region: 0,
                returned2: 1.0,
                pdf_bsdf_w,
                pdf_guide_w,
                pdf_w: 0.5 * pdf_bsdf_w + 0.5 * pdf_guide_w,
            })
            .collect()
    }

    #[test]
    fn learns_the_candidate_of_least_second_moment() {
        // Light only where the guide is dense and the BSDF is not: M(α) ∝ 1/(0.01 α + 1 - α),
        // smallest at the least BSDF share.
        let l = SelectionLearner::new(2, 0.5);
        l.absorb(&records(MIN_RECORDS, 0.01, 1.0));
        assert_eq!(l.p_bsdf(0), 0.1);
        assert_eq!(
            l.p_bsdf(1),
            0.1,
            "a region without records takes the pooled choice"
        );
        // The reverse: light only where the BSDF is dense; BSDF sampling alone, whose
        // second moment 1 is below 0.9's 1/0.901 weighed by the guide's cost.
        let l = SelectionLearner::new(1, 0.5);
        l.absorb(&records(MIN_RECORDS, 1.0, 0.01));
        assert_eq!(l.p_bsdf(0), 1.0);
        // Half of each kind with p = 1 and 0: M(α) ∝ 1/α + 1/(1 - α), smallest at 1/2; a
        // skew of 4 to 1 toward the guide's directions moves the optimum to
        // argmin 4/(1 - α) + 1/α = 1/3, so the grid's 0.3.
        let l = SelectionLearner::new(1, 0.9);
        let mut r = records(MIN_RECORDS, 1.0, 0.0);
        r.extend(records(MIN_RECORDS, 0.0, 1.0));
        l.absorb(&r);
        assert_eq!(l.p_bsdf(0), 0.5);
        let l = SelectionLearner::new(1, 0.9);
        let mut r = records(MIN_RECORDS, 1.0, 0.0);
        r.extend(records(4 * MIN_RECORDS, 0.0, 1.0));
        l.absorb(&r);
        assert_eq!(l.p_bsdf(0), 0.3);
    }

    /// A guide whose density at the directions that bring light back is `g` times the
    /// BSDF's: `M(α) ∝ 1/(α + (1 - α) g)`, smallest at the least BSDF share for `g > 1`.
    /// Guiding is kept only where that beats BSDF sampling alone by more than its cost:
    /// at `g = 1.1`, `M(0.1) = 0.917` weighed by 1.25 is 1.147 against `M(1) = 1`; at
    /// `g = 2`, 0.658 against 1.
    #[test]
    fn guides_only_where_the_guide_pays_for_its_cost() {
        for (g, expected) in [(1.0, 1.0), (1.1, 1.0), (2.0, 0.1)] {
            let l = SelectionLearner::new(1, 0.5);
            l.absorb(&records(MIN_RECORDS, 1.0, g));
            assert_eq!(l.p_bsdf(0), expected, "guide density {g} x the BSDF's");
        }
        // Light found in a direction the BSDF never draws: BSDF sampling alone cannot
        // estimate it, whatever the cost.
        let l = SelectionLearner::new(1, 0.5);
        let mut r = records(MIN_RECORDS, 1.0, 1.0);
        r.push(records(1, 0.0, 1.0)[0]);
        l.absorb(&r);
        assert!(l.p_bsdf(0) < 1.0, "{}", l.p_bsdf(0));
    }

    /// `n` records of the even mixture dealt in turn to regions `0..regions`.
    fn spread(n: u64, regions: u32, pdf_bsdf_w: f32, pdf_guide_w: f32) -> Vec<SelectionRecord> {
        (0..n)
            .map(|i| SelectionRecord {
                region: (i % regions as u64) as u32,
                ..records(1, pdf_bsdf_w, pdf_guide_w)[0]
            })
            .collect()
    }

    /// Regions short of their own records take the cache's pooled choice once the cache
    /// holds `MIN_RECORDS`, the default before; BSDF sampling alone only up to
    /// `MAX_POOLED_P_BSDF`, so that they go on gathering records. A region with its own
    /// records keeps its own choice whatever the pool says.
    #[test]
    fn regions_without_their_own_records_take_the_pooled_choice() {
        let l = SelectionLearner::new(9, 0.5);
        let bsdf_dense = spread(MIN_RECORDS, 8, 1.0, 0.01);
        l.absorb(&bsdf_dense[..MIN_RECORDS as usize - 1]);
        for i in 0..9 {
            assert_eq!(
                l.p_bsdf(i),
                0.5,
                "one record short in the cache: the default"
            );
        }
        l.absorb(&bsdf_dense[MIN_RECORDS as usize - 1..]);
        for i in 0..9 {
            assert_eq!(l.p_bsdf(i), MAX_POOLED_P_BSDF, "region {i}");
        }
        assert_eq!(l.learned_regions(), (0, 9));

        // Regions 1-8 learn the most guiding, region 0 BSDF sampling alone: each keeps its
        // own choice, whatever the pool (0.3 here) says.
        let l = SelectionLearner::new(9, 0.5);
        let mut r = spread(8 * MIN_RECORDS, 8, 0.01, 1.0);
        for x in &mut r {
            x.region += 1;
        }
        r.extend(records(MIN_RECORDS, 1.0, 0.01));
        l.absorb(&r);
        assert_eq!(l.p_bsdf(0), 1.0, "region 0 learned BSDF sampling alone");
        for i in 1..9 {
            assert_eq!(l.p_bsdf(i), 0.1, "region {i}: its own choice");
        }
        // The reverse pool (light where the guide is dense) for a region without records.
        let l = SelectionLearner::new(3, 0.5);
        l.absorb(&spread(MIN_RECORDS, 2, 0.01, 1.0));
        assert_eq!(l.p_bsdf(2), 0.1, "a region without records: the pool's");
        assert!(l.summary().contains("others 0.1"), "{}", l.summary());
    }

    #[test]
    fn waits_for_enough_records_and_ignores_invalid_ones() {
        let l = SelectionLearner::new(1, 0.5);
        l.absorb(&records(MIN_RECORDS - 1, 0.01, 1.0));
        assert_eq!(l.p_bsdf(0), 0.5, "one record short");
        let mut bad = records(4, 0.01, 1.0);
        bad[0].returned2 = f32::NAN;
        bad[1].pdf_w = 0.0;
        bad[2].pdf_guide_w = f32::INFINITY;
        bad[3].region = 7;
        l.absorb(&bad);
        assert_eq!(l.p_bsdf(0), 0.5, "invalid records do not count");
        l.absorb(&records(1, 0.01, 1.0));
        assert_eq!(l.p_bsdf(0), 0.1);
    }
}
