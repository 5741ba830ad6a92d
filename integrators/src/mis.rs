//! Multiple importance sampling weights of the combined image (Veach 1997, ch. 9 and 10).
//!
//! The combined image weighs three strategies for a path `x0 (camera) ... xk (light)` of `k`
//! segments: `p0` a camera path that hits the light, `p1` a camera path whose last vertex is
//! connected to a light sample (next-event estimation), `pk` a light path whose last vertex is
//! connected to the camera (light tracing). Each is the density of the whole path in the
//! area-product measure under that strategy, and the weight is the power heuristic
//! `w_s = p_s² / (p0² + p1² + pk²)`.
//!
//! The densities use **unguided** direction pdfs (the BSDF's, the light's emission, the
//! camera's), whichever sampler actually drew the path. The weights stay a partition of unity
//! for every path, so the combined estimate stays unbiased (Veach 1997, §9.2.2: any weights
//! that sum to one over the strategies able to make a path will do), and they cost no particle
//! query: evaluating a guided pdf for the other direction at every vertex would need the other
//! map's query there too, doubling the queries for a second-order gain.
//!
//! Both directions are counted equally: one camera path per pixel per pass and one light path
//! per pixel per pass, with the camera pdf taken over the whole image, give equal sample
//! counts. Delta (specular) steps have area density 1 in both directions, as in pbrt-v3's
//! `MISWeight`; connections at delta vertices are impossible and get density 0.

use footprint::bsdf::Bsdf;
use glam::Vec3;

/// Converts a solid-angle density at `from` into an area density at `to` (normal `n_to`, or
/// none for a point such as a delta light).
#[inline]
pub fn to_area(pdf_w: f64, from: Vec3, to: Vec3, n_to: Option<Vec3>) -> f64 {
    let d = to - from;
    let d2 = d.length_squared() as f64;
    if d2 <= 0.0 {
        return 0.0;
    }
    let cos = match n_to {
        Some(n) => (n.dot(d) as f64).abs() / d2.sqrt(),
        None => 1.0,
    };
    pdf_w * cos / d2
}

/// The unguided area density of sampling `next` from a vertex with `bsdf` at `p`, given the
/// path's other neighbour in direction `toward_other` (unit). `delta`: the path's direction
/// at this vertex came from a delta lobe (per sample, not per BSDF: smooth plastic mixes a
/// delta coat with a diffuse base); such steps give 1 (in both directions), and the BSDF's
/// `pdf`, which covers its non-delta lobes only, is used for the others.
#[inline]
pub fn step_area(
    bsdf: &Bsdf,
    delta: bool,
    p: Vec3,
    toward_other: Vec3,
    next: Vec3,
    n_next: Option<Vec3>,
) -> f64 {
    if delta || bsdf.is_delta() {
        return 1.0;
    }
    let wi = (next - p).normalize_or_zero();
    to_area(bsdf.pdf(toward_other, wi) as f64, p, next, n_next)
}

/// Power-heuristic weight of the strategy with density `own` among `all` (scaled by the
/// largest, so that neither overflow nor underflow spoils it).
#[inline]
pub fn weight(own: f64, all: [f64; 3]) -> f32 {
    let m = all.iter().copied().fold(0.0f64, f64::max);
    if !(own > 0.0) || !(m > 0.0) || !m.is_finite() {
        return 0.0;
    }
    let o = own / m;
    let sum: f64 = all.iter().map(|p| (p / m) * (p / m)).sum();
    (o * o / sum) as f32
}
