//! The error of an image against a reference, and of a method against time: relative MSE,
//! mean absolute error, spots, the largest sample's share, the budget rule, and the log-log
//! slope of error against time.

use footprint::film::Image;
use footprint::math::luminance;

/// A run missed its budget when it took more than this fraction longer than the budget, or
/// when its map passes alone took longer than the budget (a guided method at a small rung).
pub const BUDGET_TOLERANCE: f64 = 0.1;
/// A pixel is a spot when its luminance error exceeds this multiple of the reference
/// luminance (plus 1% of the reference mean).
pub const SPOT_FACTOR: f32 = 4.0;
/// Whether a run of `seconds`, `map_seconds` of them building maps, missed budget `t`: it
/// took more than [`BUDGET_TOLERANCE`] longer, or its maps alone took longer than `t`.
pub fn missed(seconds: f64, map_seconds: f64, t: f64) -> bool {
    seconds > t * (1.0 + BUDGET_TOLERANCE) || map_seconds > t
}
/// Relative MSE (see the module doc).
pub fn rel_mse(x: &Image, r: &Image) -> f64 {
    relative_mean(x, r, |a, b| (a - b) * (a - b) / (b * b + 0.01))
}

/// The mean over pixels and channels of `term(a, b)`, `a` from `x` and `b` from the
/// reference `r`, both divided by the reference's mean luminance.
fn relative_mean(x: &Image, r: &Image, term: impl Fn(f64, f64) -> f64) -> f64 {
    let m = luminance(r.mean()).max(1e-20) as f64;
    let mut sum = 0.0f64;
    for (a, b) in x.pixels.iter().zip(&r.pixels) {
        for c in 0..3 {
            sum += term(a[c] as f64 / m, b[c] as f64 / m);
        }
    }
    sum / (3 * r.pixels.len()) as f64
}
/// What a reference's own noise adds, in expectation, to the relative MSE of any image
/// rendered independently of it: [`rel_mse`]'s mean with `(X - R)²` replaced by the
/// reference's variance, `stderr` its per-pixel standard error (as Mitsuba references carry
/// beside their mean: `tests/mitsuba-references/NAME-stderr.exr`). `E[(X - R)²] = Var X +
/// Var R` for independent images, so `rel_mse - reference_noise` estimates the image's own
/// error (to first order in the noise of the denominator's `R`).
pub fn reference_noise(r: &Image, stderr: &Image) -> f64 {
    relative_mean(stderr, r, |s, b| s * s / (b * b + 0.01))
}
/// Mean absolute error over pixels and channels.
pub fn mae(x: &Image, r: &Image) -> f64 {
    let sum: f64 = x
        .pixels
        .iter()
        .zip(&r.pixels)
        .map(|(a, b)| (*a - *b).abs().element_sum() as f64)
        .sum();
    sum / (3 * r.pixels.len()) as f64
}
/// Number of spots (see the module doc).
pub fn spots(x: &Image, r: &Image) -> usize {
    let floor = 0.01 * luminance(r.mean());
    x.pixels
        .iter()
        .zip(&r.pixels)
        .filter(|(a, b)| {
            let (la, lb) = (luminance(**a), luminance(**b));
            (la - lb).abs() > SPOT_FACTOR * lb + floor
        })
        .count()
}
/// The largest single-sample contribution's share of the image (see [`Row::largest_share`]):
/// a sample's value is averaged over the passes, so its share of the summed image is
/// `value / (passes · Σ pixels)`.
pub fn largest_share(r: &footprint_integrators::RenderResult) -> f64 {
    let total = luminance(r.image.mean()) as f64 * r.image.pixels.len() as f64;
    if !(total > 0.0) || r.passes == 0 {
        return 0.0;
    }
    r.stats.max_luminance as f64 / (r.passes as f64 * total)
}
/// Least-squares slope of log(error) against log(time).
pub fn log_log_slope(points: &[(f64, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(t, e)| *t > 0.0 && *e > 0.0)
        .map(|(t, e)| (t.ln(), e.ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}
/// Time a method needs to reach `target` error, on its log-log line through the last point
/// with the fitted slope (extrapolated when the ladder did not reach it).
pub fn time_to_reach(points: &[(f64, f64)], target: f64) -> Option<f64> {
    let slope = log_log_slope(points)?;
    if slope >= 0.0 {
        return None;
    }
    let (t, e) = *points.last()?;
    Some(t * (target / e).powf(1.0 / slope))
}
/// False-colour error image: |X - R| / (R + 1% mean) in luminance, through a blue-red ramp.
pub fn error_image(x: &Image, r: &Image) -> Image {
    let floor = 0.01 * luminance(r.mean()).max(1e-20);
    let mut out = Image::new(r.width, r.height);
    for ((o, a), b) in out.pixels.iter_mut().zip(&x.pixels).zip(&r.pixels) {
        let e = ((luminance(*a) - luminance(*b)).abs() / (luminance(*b) + floor)).min(1.0);
        *o = footprint::Rgb::new(e, 0.2 * (1.0 - e), 1.0 - e) * 0.8;
    }
    out
}
/// An exposure that maps the reference's mean to mid-grey in the previews.
pub fn preview_exposure(r: &Image) -> f32 {
    let m = luminance(r.mean()).max(1e-12);
    (0.18 / m).log2()
}

#[cfg(test)]
mod tests {
    use super::*;
    use footprint::Rgb;
    use footprint::rng::Rng;

    /// A perfect image's relative MSE against a noisy reference is the reference's own noise:
    /// a reference of 40,000 pixels drawn as the truth plus Gaussian noise of a known standard
    /// error (5% of each value; fixed seed), the truth's `rel_mse` against it and
    /// `reference_noise` agree within 5 standard errors of the mean of their per-term
    /// differences `(e² - s²) / (R² + 0.01)`.
    #[test]
    fn a_perfect_image_measures_the_references_own_noise() {
        let (w, h) = (200u32, 200u32);
        let mut rng = Rng::new(3, 0, 0);
        let mut truth = Image::new(w, h);
        let mut reference = Image::new(w, h);
        let mut stderr = Image::new(w, h);
        for i in 0..(w * h) as usize {
            let t = Rgb::new(
                0.2 + rng.uniform(),
                0.1 + 2.0 * rng.uniform(),
                0.5 + rng.uniform(),
            );
            let s = 0.05 * t;
            let mut gauss = || {
                let (u1, u2) = (rng.uniform().max(1e-12), rng.uniform());
                (-2.0 * u1.ln()).sqrt() * (std::f32::consts::TAU * u2).cos()
            };
            let e = Rgb::new(gauss(), gauss(), gauss()) * s;
            truth.pixels[i] = t;
            reference.pixels[i] = t + e;
            stderr.pixels[i] = s;
        }
        let measured = rel_mse(&truth, &reference);
        let noise = reference_noise(&reference, &stderr);
        let m = luminance(reference.mean()) as f64;
        let diffs: Vec<f64> = truth
            .pixels
            .iter()
            .zip(&reference.pixels)
            .zip(&stderr.pixels)
            .flat_map(|((t, r), s)| {
                (0..3).map(move |c| {
                    let (t, r, s) = (t[c] as f64 / m, r[c] as f64 / m, s[c] as f64 / m);
                    ((t - r).powi(2) - s * s) / (r * r + 0.01)
                })
            })
            .collect();
        let n = diffs.len() as f64;
        let mean = diffs.iter().sum::<f64>() / n;
        let sd = (diffs.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let se = sd / n.sqrt();
        assert!(noise > 0.0);
        assert!(
            (measured - noise).abs() < 5.0 * se,
            "rel_mse {measured:.6e} against the reference's noise {noise:.6e} (se {se:.2e})"
        );
        // Against a reference without noise of its own, the image's error is all its own.
        let zero = Image::new(w, h);
        assert_eq!(reference_noise(&truth, &zero), 0.0);
    }
}
