//! What the pilots predict of the candidates ([`Candidate`]): one pilot's per-pass relative
//! variance of the combined image's three layers (cross-fitted), what their own paths
//! missed, and the light a direction cannot find ([`measure`], [`can_miss_light`]); and
//! every pilot weighed with the others' images, the unguided candidates' missed paths seen
//! from the guided ones and the splitting directions' own passes ([`predict_all`] over
//! the [`GuidedPilot`]s).

use super::metric::{Metric, Pooled, fold_metrics};
use super::params::{BIAS_BLOCK_SAMPLES, FOLDS};
use super::pilot::{Moments, Pilot};
use super::split::{SplitPilot, split_ratio};
use crate::moments;
use footprint::scene::Scene;
use footprint::settings::GuideParams;

/// One candidate as the pilot measured it.
#[derive(Clone, Debug)]
pub struct Candidate {
    pub method: String,
    /// Predicted relative MSE at the time left.
    pub predicted: f64,
    /// Seconds per pass at the image's resolution (a lower-resolution pilot's scaled by the
    /// pixel counts' ratio, [`PILOT_MAX_PIXELS`](super::params::PILOT_MAX_PIXELS)).
    pub pass_seconds: f64,
    /// The relative variance of one pass (`predicted` divides it by the passes left).
    pub pass_variance: f64,
    /// Part of `pass_variance` from paths the pilot's own passes of the direction missed
    /// (estimated by MIS from the other direction's paths, [`crate::moments`]).
    pub unseen: f64,
    /// Part of `predicted` from light the method cannot find.
    pub missing: f64,
}

impl Candidate {
    /// Sets `predicted` for `time_left` seconds of rendering (infinite for a candidate that
    /// was not timed).
    pub(super) fn predict_at(&mut self, time_left: f64) {
        if !self.pass_seconds.is_finite() {
            self.predicted = f64::INFINITY;
            return;
        }
        let passes = (time_left / self.pass_seconds).max(1.0);
        self.predicted = self.pass_variance / passes + self.missing;
    }
}

/// Whether `integrator` can miss light in `scene` ("Missing light" in the module doc of
/// [`crate::auto`]).
pub(super) fn can_miss_light(scene: &Scene, integrator: &str) -> Option<&'static str> {
    let e = &scene.effects;
    let specular = e.specular_reflection || e.refraction;
    match integrator {
        "pt" if specular && (e.spot_lights || e.point_lights || e.directional_lights) => {
            Some("path tracing cannot find caustics of point, spot and directional lights")
        }
        "lt" if specular => Some("light tracing cannot see through specular surfaces"),
        "lt" if e.environment => Some("light tracing does not see the environment directly"),
        _ => None,
    }
}

/// What one pilot measured of the candidates of `guide` (the combined image, pt and lt: its
/// three layers): the relative variance per pass and the missing light. `predicted` is set
/// later, for every candidate at the same time left ([`Candidate::predict_at`]).
/// `same_paths`: `reference` is this pilot's own combined layer (so the layers' differences
/// to it are measured per pass), not an independent pilot's.
#[allow(clippy::too_many_arguments)]
pub(super) fn measure(
    scene: &Scene,
    pilot: &Pilot,
    reference: &Moments,
    metric: &Metric,
    folds: &[Metric; FOLDS],
    same_paths: bool,
    seconds: [f64; 3],
    guide: &str,
) -> Vec<Candidate> {
    let npix = reference.sum.len();
    let scale = metric.scale;
    let k = pilot.layers[0].n as f64;
    let k_ref = reference.n as f64;
    let width = (scene.camera.width as usize).max(1);
    let height = npix / width;
    // Missing light is measured on square blocks of pixels holding at least
    // BIAS_BLOCK_SAMPLES pilot samples: with a handful of passes a pixel's reference mean is
    // mostly noise, and the metric's weight 1 / (R^2 + 0.01) of a noisy R undercounts the
    // light a method misses (measured pixel by pixel from 4 passes, a point-light caustic
    // reads a small part of what the block estimate reads).
    let side = ((BIAS_BLOCK_SAMPLES / k_ref).sqrt().ceil() as usize).max(1);
    ["combined", "pt", "lt"]
        .iter()
        .enumerate()
        .map(|(l, name)| {
            let layer = &pilot.layers[l];
            // The per-pass variance, each fold's squared deviations from the mean weighed
            // with its own weights (from `R` without the fold's passes).
            let mut var = 0.0f64;
            for (fold, w) in pilot.folds.iter().zip(folds) {
                let f = &fold[l];
                if f.n == 0 {
                    continue;
                }
                for i in 0..npix {
                    for c in 0..3 {
                        let m = layer.mean(i, c);
                        let dev2 = f.sum2[i][c] - 2.0 * m * f.sum[i][c] + f.n as f64 * m * m;
                        var += dev2.max(0.0) * w.weight[i][c];
                    }
                }
            }
            var /= (k - 1.0).max(1.0) * scale * scale;
            // What the estimate's own pilot paths missed of its second moment: the MIS
            // estimate from every path less its own (crate::moments).
            let e = estimate_index(l);
            let unseen = metric.excess(&pilot.m2[moments::MIS + e], &pilot.m2[moments::OWN + e]);
            let mut bias = 0.0f64;
            if can_miss_light(scene, name).is_some() {
                for y0 in (0..height).step_by(side) {
                    for x0 in (0..width).step_by(side) {
                        let (mut m, mut sl, mut sr, mut noise) =
                            (0.0, [0.0; 3], [0.0; 3], [0.0; 3]);
                        for y in y0..(y0 + side).min(height) {
                            for x in x0..(x0 + side).min(width) {
                                let i = y * width + x;
                                m += 1.0;
                                for c in 0..3 {
                                    sl[c] += layer.mean(i, c);
                                    sr[c] += reference.mean(i, c);
                                    noise[c] += if same_paths {
                                        pilot.diffs[l].var(i, c) / k
                                    } else {
                                        layer.var(i, c) / k + reference.var(i, c) / k_ref
                                    };
                                }
                            }
                        }
                        for c in 0..3 {
                            // The squared difference of the block means, less what their
                            // noise explains in expectation; summed signed over the image
                            // and clamped once, so that noise alone adds no bias.
                            let r = sr[c] / m / scale;
                            let diff = (sl[c] - sr[c]) / m / scale;
                            let noise = noise[c] / (m * m) / (scale * scale);
                            bias += m * (diff * diff - noise) / (r * r + 0.01);
                        }
                    }
                }
            }
            let n = (3 * npix) as f64;
            let (var, bias) = (var / n, (bias / n).max(0.0));
            Candidate {
                method: format!("{name}-{guide}"),
                predicted: f64::INFINITY,
                pass_seconds: seconds[l],
                pass_variance: var + unseen,
                unseen,
                missing: bias,
            }
        })
        .collect()
}

/// The second-moment layers' estimate for the image layer `l` (combined, pt, lt).
pub(super) fn estimate_index(l: usize) -> usize {
    [moments::COMBINED, moments::PT, moments::LT][l]
}

/// What one guided pilot measured: the guide's combined image ([`Pilot`]), its pass times
/// at the image's resolution (combined, pt, lt) and its splitting directions' own passes
/// (pt, lt; [`SplitPilot`]).
pub(super) struct GuidedPilot {
    pub(super) guide: &'static str,
    pub(super) pilot: Pilot,
    pub(super) secs: [f64; 3],
    pub(super) split: [Option<SplitPilot>; 2],
}

/// Every candidate's per-pass noise, missing light and pass time from the unguided
/// `pilot` (whose combined layer is `reference`; `unguided_alone` its candidates measured
/// with its own image as `R`, what they are without guided pilots) and the guided
/// `pilots`, each weighed as the comments below say; not yet predicted at a time
/// ([`Candidate::predict_at`]).
pub(super) fn predict_all(
    scene: &Scene,
    params: &GuideParams,
    reference: &Moments,
    pilot: &Pilot,
    unguided_alone: Vec<Candidate>,
    secs: [f64; 3],
    pilots: &[GuidedPilot],
) -> Vec<Candidate> {
    // The metric's weights `1 / (R² + 0.01)` for each pilot's candidates read `R` from the
    // other pilots' combined images pooled with the pilot's own passes but those of the
    // fold being weighed ([`fold_metrics`]); what exceeds a candidate's own second moment
    // and its missing light are weighed with the other pilots' images alone. A pilot's own
    // image is correlated with its candidates' noise (a bright sample raises both `R` and
    // the variance at its pixel, and the noisiest pixels get the least weight): with a
    // guided pilot's own `R` its candidates come out several times too low. With the other
    // pilots' `R` alone the guided candidates, weighed with the noisy unguided image, come
    // out too high (door `lt-footprint`, Veach Ajar `pt-footprint`).
    // The pilots are pooled by inverse variance ([`Pooled`]).
    let others = |skip: Option<usize>| -> Vec<&Moments> {
        let unguided = skip.map(|_| reference);
        let guided = pilots.iter().enumerate().filter(|(j, _)| Some(*j) != skip);
        unguided
            .into_iter()
            .chain(guided.map(|(_, g)| &g.pilot.layers[0]))
            .collect()
    };
    // One scale for every candidate: the image's mean luminance from every pilot pooled
    // (an image-wide mean, barely correlated with any pilot's per-pixel noise); only the
    // per-pixel weights leave a pilot's own image out.
    let every: Vec<&Moments> = std::iter::once(reference)
        .chain(pilots.iter().map(|g| &g.pilot.layers[0]))
        .collect();
    let scale = Metric::mean_luminance(&every);
    // Without guided pilots the weights are the unguided pilot's own, as `choose` measured
    // them (`unguided_alone`).
    let mut all = if pilots.is_empty() {
        unguided_alone
    } else {
        let base = others(None);
        let metric = Metric::with_scale(scene.camera.width, &Pooled::new(&base), scale);
        let folds = fold_metrics(scene.camera.width, &base, pilot, scale);
        measure(scene, pilot, reference, &metric, &folds, true, secs, "bsdf")
    };
    for (j, g) in pilots.iter().enumerate() {
        let (gname, p, secs, split) = (g.guide, &g.pilot, &g.secs, &g.split);
        let rest = others(Some(j));
        let own = Metric::with_scale(scene.camera.width, &Pooled::new(&rest), scale);
        let folds = fold_metrics(scene.camera.width, &rest, p, scale);
        all.extend(measure(
            scene, p, reference, &own, &folds, false, *secs, gname,
        ));
        // What the unguided candidates' own pilot paths missed, seen from the guided paths
        // (crate::moments): the guided pilot's MIS estimate of each unguided estimate's
        // second moment less the unguided pilot's own, weighed without that guided pilot's
        // image (its rare bright paths raise both).
        for (l, c) in all.iter_mut().take(3).enumerate() {
            let e = estimate_index(l);
            let seen = own.excess(&p.m2[moments::UNGUIDED + e], &pilot.m2[moments::OWN + e]);
            if seen > c.unseen {
                c.pass_variance += seen - c.unseen;
                c.unseen = seen;
            }
        }
        // A split direction's per-pass noise: its unsplit layer's as measured (cross-fitted,
        // with what its paths missed), times the ratio of its own passes' noise to the
        // layer's under the same weights ([`split_ratio`]); its time is theirs.
        for (d, sp) in split.iter().enumerate() {
            let name = format!("{}-{gname}", ["pt", "lt"][d]);
            let Some(v) = sp.as_ref().and_then(|sp| sp.pass_variance(&folds)) else {
                continue;
            };
            if let Some(c) = all.iter_mut().find(|c| c.method == name) {
                let ratio = split_ratio(c.pass_variance - c.unseen, v, params.guided_split);
                c.unseen *= ratio;
                c.pass_variance *= ratio;
            }
        }
    }
    all
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A candidate that was not timed (its direction not wanted) is predicted infinite, not
    /// at one pass's error, and so never ranks ahead of a timed one.
    #[test]
    fn a_candidate_not_timed_is_predicted_infinite() {
        let mut timed = Candidate {
            method: "pt-bsdf".into(),
            predicted: 0.0,
            pass_seconds: 0.01,
            pass_variance: 100.0,
            unseen: 0.0,
            missing: 0.0,
        };
        let mut untimed = Candidate {
            method: "lt-footprint".into(),
            pass_seconds: f64::INFINITY,
            pass_variance: 1e-6,
            ..timed.clone()
        };
        timed.predict_at(10.0);
        untimed.predict_at(10.0);
        assert!((timed.predicted - 0.1).abs() < 1e-12, "{}", timed.predicted);
        assert!(untimed.predicted.is_infinite(), "{}", untimed.predicted);
    }
}
