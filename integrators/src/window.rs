//! A noisy image's local means, each over the smallest window around its pixel whose mean
//! is known well enough: `auto`'s metric reads the pilot's image through it
//! ([`crate::auto`]), and the relative importance target the short pre-render's
//! ([`crate::passes::target`]). A pixel's own mean from a few passes is heavy-tailed, usually
//! below its expectation where rare bright paths carry the light; a fixed blur either
//! keeps that noise or smears edges that are known well.

/// Window radii (pixels) tried, smallest first.
pub const RADII: [usize; 6] = [1, 2, 4, 8, 16, 32];
/// A window is used when the standard error of its luminance mean is at most this share of
/// that mean (or of `floor`).
pub const RELATIVE_ERROR: f64 = 0.2;

/// Rec. 709 luminance weights (`footprint::math::luminance`'s), in double precision.
pub const LUMINANCE: [f64; 3] = [0.2126, 0.7152, 0.0722];

/// Per pixel of a `width`-wide image, the mean colour over the smallest window of
/// [`RADII`] whose luminance mean has a standard error of at most [`RELATIVE_ERROR`] of
/// `max(mean, floor)` (else the largest). `mean(i, c)` is pixel `i`'s mean in channel
/// `c`, `var_of_mean(i, c)` that mean's variance; the channels are taken as fully
/// correlated (an upper bound of the luminance's variance).
pub fn window_means(
    width: usize,
    npix: usize,
    mean: &dyn Fn(usize, usize) -> f64,
    var_of_mean: &dyn Fn(usize, usize) -> f64,
    floor: f64,
) -> Vec<[f64; 3]> {
    let width = width.max(1);
    let height = npix / width;
    // Summed-area tables.
    let sat = |value: &dyn Fn(usize) -> f64| {
        let mut t = vec![0.0f64; (width + 1) * (height + 1)];
        for y in 0..height {
            let mut row = 0.0;
            for x in 0..width {
                row += value(y * width + x);
                t[(y + 1) * (width + 1) + x + 1] = t[y * (width + 1) + x + 1] + row;
            }
        }
        t
    };
    let means: [Vec<f64>; 3] = std::array::from_fn(|c| sat(&|i| mean(i, c)));
    let var_lum = sat(&|i| {
        let sd: f64 = (0..3)
            .map(|c| LUMINANCE[c] * var_of_mean(i, c).max(0.0).sqrt())
            .sum();
        sd * sd
    });
    let window = |t: &[f64], x0: usize, y0: usize, x1: usize, y1: usize| {
        let w = width + 1;
        t[y1 * w + x1] - t[y0 * w + x1] - t[y1 * w + x0] + t[y0 * w + x0]
    };
    (0..width * height)
        .map(|i| {
            let (x, y) = (i % width, i / width);
            let mut acc = [0.0f64; 3];
            for &rad in &RADII {
                let (x0, y0) = (x.saturating_sub(rad), y.saturating_sub(rad));
                let (x1, y1) = ((x + rad + 1).min(width), (y + rad + 1).min(height));
                let count = ((x1 - x0) * (y1 - y0)) as f64;
                acc = std::array::from_fn(|c| window(&means[c], x0, y0, x1, y1) / count);
                let mean_lum: f64 = (0..3).map(|c| LUMINANCE[c] * acc[c]).sum();
                let se = window(&var_lum, x0, y0, x1, y1).max(0.0).sqrt() / count;
                if se <= RELATIVE_ERROR * mean_lum.max(floor) {
                    break;
                }
            }
            acc
        })
        .collect()
}
