//! Second moments of the three estimates (path tracing, light tracing, the combined image),
//! for `auto`'s pilot (`crate::auto`). A short pilot misses a method's rare, bright paths:
//! on door, a few passes of unguided path tracing predict a small part of its rendered
//! error, because the camera paths that find the light through the gap are too rare to be
//! drawn.
//! But the combined image knows every strategy's density at every contribution
//! ([`Strategies`]), so each estimate's second moment can be estimated from *every* path of
//! the pilot by MIS, including the paths only another strategy finds often, and, where a
//! guided pilot tracks the unguided densities beside its own ([`crate::mis::PilotMis`]),
//! the unguided methods' second moments from the guided paths.
//!
//! With `g = Σ_{s∈E} (w^E_s)² f² / q_s` the second moment of estimate `E` (strategies `s ∈ E`
//! of densities `q_s`, weighted against each other by the power heuristic `w^E_s`; cross
//! terms between the contributions of one sample left out), `∫ g = Σ_t E_t[w_t g / p_t]`
//! over the pilot's strategies `t` (densities `p_t`, weights `w_t`): a contribution of
//! unweighted value `V = f / p_t` adds `w_t V² Σ_{s∈E} (w^E_s)² p_t / q_s`
//! ([`moment_factor`]). A strategy of density 0 cannot make the path: light an estimate
//! misses altogether is bias, measured apart (`crate::auto`), and adds nothing here. The
//! same layers keep each estimate's own second moment, the squares of what it added itself:
//! the difference is what its own pilot paths did not show.
//!
//! The layers are written by the combined image when a render asks for them
//! (`RenderOptions::moments`), deposited with the filter's squared weights
//! (`SplatList::splat_second_moment`), averaged per pass like every layer. Environment
//! paths add nothing (the path tracer alone makes them).
//!
//! **Russian roulette.** A path that survived roulette with probability `S` (the product of
//! its survival probabilities, [`crate::walk::Vertex::survival`]) was drawn with density
//! `p_t S`, and its value carries `1 / S`. For the strategies of the path's own direction the
//! estimate's roulette on that path is the same, and the term above is its second moment
//! with roulette (as the own layer's squares are). For the other direction's strategies the
//! estimate's roulette on the path is unknown: their terms are taken without it, which is
//! `S` times the term above (`g / (p_t S)` with `V = f / (p_t S)`). Without that factor a
//! light path's own roulette would inflate path tracing's MIS second moment by `1 / S`: on
//! Veach Ajar, whose guided light paths can survive with small probabilities, guided path
//! tracing would show an excess over its own paths that its renders do not have.
//!
//! **What the render will not draw.** A term of strategy `s` from a path made by `t` stands
//! for the paths near it that `s` would draw: `N q_s / (K p_t)` of them over a render of `N`
//! passes of the estimate, against the one the pilot's `K` passes drew. Where that count is
//! below one the render mostly does not draw such a path at all: its typical error holds the
//! path's missing share of the pixel, squared, and not its second moment `f² / q_s`, which
//! only the rare render that draws it shows (paths the light tracer finds easily and path
//! tracing rarely: read by MIS from the light paths, they predicted path tracing's error
//! on Veach Ajar about a hundred times, and on a room behind window panes up to orders of
//! magnitude above what its renders measure). So the ratio `p_t / q_s` is taken at most
//! `N / K` ([`Horizon`]): past it the term is `w_t (w^E_s)² V² N / K`, which adds
//! `w_t (w^E_s)² (V / K)²` to the render's error (the layer's mean over `K` passes, divided
//! by `N`): about the path's own share of the pixel as the pilot saw it, squared. The
//! predicted error is then the typical render's (the median over seeds, which the
//! comparisons report), not the mean over renders, which the rare paths dominate.
//!
//! Approximations, each the same for a method's MIS and own layers where it matters: the
//! cross terms of one sample's contributions are left out; the densities are those the
//! weights read (with the guide cache the guided mixture in white light, while path
//! tracing's own weight reads it in the path's colour); the other direction's roulette is
//! left out (above). `auto` uses the layers only with guided MIS weights and the guide
//! cache, where the weights' densities are the samplers'.

use crate::mis::Strategies;
use footprint::Rgb;

/// The layers' names, after the integrator's own layers.
pub const LAYERS: [&str; 9] = [
    "m2-pt-own",
    "m2-lt-own",
    "m2-combined-own",
    "m2-pt",
    "m2-lt",
    "m2-combined",
    "m2-pt-unguided",
    "m2-lt-unguided",
    "m2-combined-unguided",
];

/// The three estimates, in the order of their layers (and of the combined image's layers
/// `pt`, `lt` less one: `OWN + e`, `MIS + e`, `UNGUIDED + e`).
pub const PT: usize = 0;
pub const LT: usize = 1;
pub const COMBINED: usize = 2;
/// Each estimate's own second moment: the squares of its own contributions.
pub const OWN: usize = 0;
/// Estimated by MIS from every path, with the pilot's densities.
pub const MIS: usize = 3;
/// Estimated by MIS from every path for the unguided form of the estimate.
pub const UNGUIDED: usize = 6;

/// How many passes of each estimate ([`PT`], [`LT`], [`COMBINED`]) the render is expected
/// to draw per pass of the pilot that writes the layers, at the same density over the image
/// (a pilot at a lower resolution draws as many paths per pilot pixel as the render per
/// pixel, so the ratio is the render's time left over the pilot's passes' time, each pass
/// timed at its own resolution): the largest `p_t / q_s` a term counts (the module doc,
/// "What the render will not draw").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Horizon(pub [f64; 3]);

impl Horizon {
    /// No bound: every term's full second moment (the mean over renders).
    pub const UNBOUNDED: Horizon = Horizon([f64::INFINITY; 3]);

    /// `render_s` seconds of rendering left, over `pilot_passes` passes of the pilot of
    /// `pass_s` seconds each for the three estimates (pt, lt, combined) at the pilot's
    /// resolution; at least one pass (the render draws at least what the pilot drew).
    pub fn new(render_s: f64, pilot_passes: f64, pass_s: [f64; 3]) -> Horizon {
        Horizon(pass_s.map(|t| {
            let h = render_s / (pilot_passes.max(1.0) * t);
            if h.is_nan() { 1.0 } else { h.max(1.0) }
        }))
    }
}

/// The strategies each estimate weighs against each other.
const SETS: [&[usize]; 3] = [&[0, 1], &[2], &[0, 1, 2]];

/// Whether strategy `s` traces camera paths (hitting the light, next-event estimation) or
/// light paths (light tracing).
const CAMERA_SIDE: [bool; 3] = [true, true, false];

/// `w_t Σ_{s∈set} (w^E_s)² min(p_t / q_s, horizon)` for a path made by `st.own` with
/// densities `st.p`, of an estimate over `set` with densities `q`, each term of a strategy
/// of the other direction times `survival`, the path's roulette survival (see the module
/// doc); 0 when no strategy of `set` can make the path.
pub fn moment_factor(
    st: &Strategies,
    q: &[f64; 3],
    set: &[usize],
    survival: f64,
    horizon: f64,
) -> f64 {
    let p_t = st.p[st.own];
    if !(p_t > 0.0) || !p_t.is_finite() {
        return 0.0;
    }
    // The weight as `mis::weight` computes it, scaled by the largest density (products
    // of area densities of long paths under- and overflow).
    let w_t = st.weight() as f64;
    let m = set.iter().map(|&s| q[s]).fold(0.0f64, f64::max);
    if !(m > 0.0) || !m.is_finite() {
        return 0.0;
    }
    let sum_q2: f64 = set.iter().map(|&s| (q[s] / m) * (q[s] / m)).sum();
    let mut f = 0.0;
    for &s in set {
        if q[s] > 0.0 {
            let w = (q[s] / m) * (q[s] / m) / sum_q2;
            let rr = if CAMERA_SIDE[s] == CAMERA_SIDE[st.own] {
                1.0
            } else {
                survival
            };
            f += w * w * (p_t / q[s]).min(horizon) * rr;
        }
    }
    let f = w_t * f;
    if f.is_finite() { f } else { 0.0 }
}

/// What one contribution of the combined image adds to the layers: `value` is its
/// unweighted value `V` (per channel), `st` the strategies that made it, `own` what the
/// direction that made it added to its own estimate (a camera path: path tracing's weighted
/// value; a light path: `value`), `by_camera` which direction that was, `survival` the
/// path's Russian roulette survival probability, `horizon` the render's passes per pilot
/// pass.
#[inline]
pub fn terms(
    value: Rgb,
    st: &Strategies,
    own: Rgb,
    by_camera: bool,
    survival: f32,
    horizon: &Horizon,
) -> [Rgb; LAYERS.len()] {
    let survival = survival as f64;
    let v2 = value * value;
    let combined = value * st.weight();
    let mut t = [Rgb::ZERO; LAYERS.len()];
    t[OWN + if by_camera { PT } else { LT }] = own * own;
    t[OWN + COMBINED] = combined * combined;
    for (e, set) in SETS.iter().enumerate() {
        // Squared values of rare paths can pass f32's range: such a term is kept at its
        // largest finite value rather than dropped by the film as invalid.
        let clamp = |f: f64| v2 * (f.min(1e30) as f32);
        let h = horizon.0[e];
        t[MIS + e] = clamp(moment_factor(st, &st.p, set, survival, h));
        t[UNGUIDED + e] = clamp(moment_factor(st, &st.unguided, set, survival, h));
    }
    t.map(|x| x.min(Rgb::splat(f32::MAX)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A toy path space [0, 1) with integrand f(x) = 1 + 8x³ and three "strategies" of
    /// known densities, the first two on the camera side, the third on the light side, each
    /// side with its own Russian roulette (survival 0.3 + 0.6x and 0.9 - 0.7x): the MIS
    /// estimate of each estimate's second moment, from samples of all three weighted by the
    /// power heuristic, matches its integral (midpoint rule), for the samplers' own
    /// densities and for another set (the "unguided" ones). A term of strategy `s` counts
    /// the roulette of its side from the paths of that side and none from the other side's
    /// (the module doc), so the integral weighs `1 / S_s` by the pilot's weights of `s`'s
    /// side. Seeded; the bound is 5 standard errors of the estimate, measured from the
    /// samples themselves.
    #[test]
    fn mis_second_moments_match_their_integrals() {
        use footprint::rng::Rng;
        let f = |x: f64| 1.0 + 8.0 * x * x * x;
        // Densities on [0, 1): uniform, 2x, 4x³ (sampled by inversion).
        let pdf = |k: usize, x: f64| match k {
            0 => 1.0,
            1 => 2.0 * x,
            _ => 4.0 * x * x * x,
        };
        let sample = |k: usize, u: f64| match k {
            0 => u,
            1 => u.sqrt(),
            _ => u.powf(0.25),
        };
        let survival = |k: usize, x: f64| {
            if CAMERA_SIDE[k] {
                0.3 + 0.6 * x
            } else {
                0.9 - 0.7 * x
            }
        };
        // The estimates' densities: the samplers' own, and "unguided" ones 1, 3x², 2(1-x).
        let q_other = |x: f64| [1.0, 3.0 * x * x, 2.0 * (1.0 - x)];
        let own = |x: f64| [pdf(0, x), pdf(1, x), pdf(2, x)];
        let exact = |set: &[usize], q: &dyn Fn(f64) -> [f64; 3]| {
            let n = 200_000;
            (0..n)
                .map(|i| {
                    let x = (i as f64 + 0.5) / n as f64;
                    let (qs, ps) = (q(x), own(x));
                    let sum: f64 = set.iter().map(|&s| qs[s] * qs[s]).sum();
                    let sum_p: f64 = ps.iter().map(|p| p * p).sum();
                    set.iter()
                        .filter(|&&s| qs[s] > 0.0)
                        .map(|&s| {
                            // The pilot's weights of s's side and of the other side.
                            let (same, other): (f64, f64) = (0..3)
                                .map(|t| ps[t] * ps[t] / sum_p)
                                .enumerate()
                                .fold((0.0, 0.0), |(a, b), (t, w)| {
                                    if CAMERA_SIDE[t] == CAMERA_SIDE[s] {
                                        (a + w, b)
                                    } else {
                                        (a, b + w)
                                    }
                                });
                            let rr = same / survival(s, x) + other;
                            (qs[s] * qs[s] / sum).powi(2) * f(x) * f(x) / qs[s] * rr
                        })
                        .sum::<f64>()
                })
                .sum::<f64>()
                / n as f64
        };
        let mut rng = Rng::new(11, 0, 0);
        let n = 400_000;
        for (e, set) in SETS.iter().enumerate() {
            for (name, q) in [
                ("own", &own as &dyn Fn(f64) -> [f64; 3]),
                ("other", &q_other),
            ] {
                // One sample of each strategy per round: the estimate is the round's sum.
                let rounds: Vec<f64> = (0..n)
                    .map(|_| {
                        (0..3)
                            .map(|t| {
                                let x = sample(t, rng.uniform() as f64);
                                let s = survival(t, x);
                                if rng.uniform() as f64 >= s {
                                    return 0.0;
                                }
                                let st = Strategies {
                                    p: own(x),
                                    own: t,
                                    unguided: q(x),
                                };
                                let v = f(x) / (pdf(t, x) * s);
                                v * v * moment_factor(&st, &st.unguided, set, s, f64::INFINITY)
                            })
                            .sum()
                    })
                    .collect();
                let mean = rounds.iter().sum::<f64>() / n as f64;
                let var = rounds.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
                let se = (var / n as f64).sqrt();
                let want = exact(set, q);
                assert!(
                    (mean - want).abs() < 5.0 * se,
                    "estimate {e} ({name}): {mean} ± {se}, integral {want}"
                );
            }
        }
    }

    /// The horizon bounds each term's density ratio `p_t / q_s`: a light path a thousand
    /// times likelier for the light tracer than for either of path tracing's strategies
    /// counts in path tracing's second moment as if ten times likelier under a horizon of
    /// ten (a hundredth of its full term), and in the light tracer's own (`q = p`) in full.
    #[test]
    fn the_horizon_bounds_each_terms_density_ratio() {
        let st = Strategies {
            p: [1e-3, 1e-3, 1.0],
            own: 2,
            unguided: [1e-3, 1e-3, 1.0],
        };
        let pt = |h| moment_factor(&st, &st.p, SETS[PT], 1.0, h);
        let lt = |h| moment_factor(&st, &st.p, SETS[LT], 1.0, h);
        assert!((pt(f64::INFINITY) / pt(10.0) - 100.0).abs() < 1e-9);
        assert_eq!(lt(f64::INFINITY), lt(10.0));
        // 30 s left over 10 pilot passes of 0.01 s (pt), 0.02 s (lt), 0.03 s (combined):
        // 300, 150 and 100 render passes per pilot pass; never under one.
        let h = Horizon::new(30.0, 10.0, [0.01, 0.02, 0.03]);
        for (got, want) in h.0.iter().zip([300.0, 150.0, 100.0]) {
            assert!((got - want).abs() < 1e-9, "{got} against {want}");
        }
        assert_eq!(Horizon::new(0.0, 10.0, [0.01; 3]).0, [1.0; 3]);
    }
}
