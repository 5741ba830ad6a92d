//! Small math helpers: the RGB colour type, orthonormal frames, luminance.

use glam::Vec3;

/// Linear RGB radiometric quantity (radiance, flux, importance, throughput).
pub type Rgb = Vec3;

pub const PI: f32 = std::f32::consts::PI;
pub const INV_PI: f32 = 1.0 / PI;
pub const INV_4PI: f32 = 1.0 / (4.0 * PI);

/// Rec. 709 luminance of a linear RGB value.
#[inline]
pub fn luminance(c: Rgb) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// Mitsuba 3's `luminance` of a linear sRGB colour (its coefficients, to six digits), which
/// its principled BSDF and its textures' scalar values (`eval_1`) read.
#[inline]
pub fn luminance_mitsuba(c: Rgb) -> f32 {
    0.212671 * c.x + 0.715160 * c.y + 0.072169 * c.z
}

/// True when every channel is finite and non-negative.
#[inline]
pub fn is_valid_rgb(c: Rgb) -> bool {
    c.is_finite() && c.min_element() >= 0.0
}

/// True when every channel is exactly zero.
#[inline]
pub fn is_black(c: Rgb) -> bool {
    c.max_element() <= 0.0
}

/// The six signed coordinate axes: +x, -x, +y, -y, +z, -z.
pub const SIGNED_AXES: [Vec3; 6] = [
    Vec3::X,
    Vec3::NEG_X,
    Vec3::Y,
    Vec3::NEG_Y,
    Vec3::Z,
    Vec3::NEG_Z,
];

/// An orthonormal frame; `z` is the normal. Converts between world and local directions.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub x: Vec3,
    pub y: Vec3,
    pub z: Vec3,
}

impl Frame {
    /// A frame around the unit vector `n` (Duff et al. 2017 via glam's `any_orthonormal_pair`).
    #[inline]
    pub fn from_z(n: Vec3) -> Self {
        let (x, y) = n.any_orthonormal_pair();
        Frame { x, y, z: n }
    }

    /// The frame about the unit normal `n` whose `x` axis is `tangent` made orthogonal to
    /// it, `y = n × x` (Mitsuba 3's `SurfaceInteraction::initialize_sh_frame`, which orients
    /// anisotropic BSDFs by `∂p/∂u`); `None` where `tangent` has no part orthogonal to `n`.
    #[inline]
    pub fn from_z_and_tangent(n: Vec3, tangent: Vec3) -> Option<Self> {
        let x = (tangent - n * n.dot(tangent)).try_normalize()?;
        Some(Frame {
            x,
            y: n.cross(x),
            z: n,
        })
    }

    #[inline]
    pub fn to_local(&self, v_world: Vec3) -> Vec3 {
        Vec3::new(
            v_world.dot(self.x),
            v_world.dot(self.y),
            v_world.dot(self.z),
        )
    }

    #[inline]
    pub fn to_world(&self, v_local: Vec3) -> Vec3 {
        self.x * v_local.x + self.y * v_local.y + self.z * v_local.z
    }
}

/// Power heuristic (beta = 2) weight of strategy `a` against strategy `b` (Veach 1997, eq. 9.13).
#[inline]
pub fn power_heuristic(pdf_a: f32, pdf_b: f32) -> f32 {
    let a2 = pdf_a * pdf_a;
    let b2 = pdf_b * pdf_b;
    if a2 == 0.0 {
        return 0.0;
    }
    if !(b2.is_finite()) {
        return 0.0;
    }
    if !(a2.is_finite()) {
        return 1.0;
    }
    a2 / (a2 + b2)
}

/// `sqrt(max(0, x))`: robust against tiny negative rounding.
#[inline]
pub fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}

/// `atan2(y, x)` in `[-π, π]`, inlined: an odd minimax polynomial of degree 15 for the
/// arctangent on `[0, 1]` and the octant identities. Largest error 1.4e-7 rad (libm's
/// `atan2f`, an out-of-line call, is within 1 ulp, 2.4e-7 near π): what the guide grids'
/// cell index needs at every guided event and for every rasterised footprint. `(0, 0)`
/// gives 0, like `atan2`.
#[inline(always)]
pub fn atan2_fast(y: f32, x: f32) -> f32 {
    const C: [f32; 8] = [
        0.999_999_34,
        -0.333_298_6,
        0.199_465_66,
        -0.139_086_29,
        0.096_421_95,
        -0.055_912_29,
        0.021_862_93,
        -0.004_054_559,
    ];
    let (ax, ay) = (x.abs(), y.abs());
    if x.is_nan() || y.is_nan() {
        return f32::NAN;
    }
    let (lo, hi) = (ax.min(ay), ax.max(ay));
    if hi == 0.0 {
        return 0.0;
    }
    let a = lo / hi;
    let t = a * a;
    // Horner with a multiply and an add: `f32::mul_add` is a call to `fmaf` where the
    // build does not assume FMA (x86-64-v2).
    let mut p = C[7];
    for &c in C[..7].iter().rev() {
        p = p * t + c;
    }
    let mut r = a * p;
    if ay > ax {
        r = std::f32::consts::FRAC_PI_2 - r;
    }
    if x < 0.0 {
        r = std::f32::consts::PI - r;
    }
    if y.is_sign_negative() { -r } else { r }
}

/// `(sin x, cos x)` for `|x| <= π/4`, inlined: the Taylor polynomials of degree 9 (sine)
/// and 10 (cosine), whose truncation errors there (2e-9, 1e-10) are below the rounding of
/// `f32`. The concentric disk mapping needs exactly this range, at every diffuse bounce;
/// libm's `sincosf` is an out-of-line call with its own range reduction.
#[inline(always)]
pub fn sin_cos_quarter(x: f32) -> (f32, f32) {
    let x2 = x * x;
    let sin =
        x + x * x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0 + x2 / 362_880.0)));
    let cos = 1.0
        + x2 * (-0.5
            + x2 * (1.0 / 24.0 + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40_320.0 - x2 / 3_628_800.0))));
    (sin, cos)
}

/// `(sin 2πu, cos 2πu)` for `u` in `[0, 1]` (an azimuth drawn as a fraction of a turn): the
/// turn is split into quarters exactly (`u - q/4` rounds nothing), the remainder of at most an
/// eighth of a turn goes through [`sin_cos_quarter`], and the quarter rotates the pair.
#[inline(always)]
pub fn sin_cos_turns(u: f32) -> (f32, f32) {
    let q = (4.0 * u).round();
    let x = (u - 0.25 * q) * std::f32::consts::TAU;
    let (s, c) = sin_cos_quarter(x);
    match (q as i32) & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

#[cfg(test)]
mod atan2_tests {
    use super::{atan2_fast, sin_cos_quarter, sin_cos_turns};

    /// Against double precision over the whole range of each: the bound is a few ulp of 1
    /// (the polynomials' truncation is below 2e-9; what remains is the rounding of `x` and
    /// of the sums).
    #[test]
    fn sin_cos_match_libm() {
        let mut worst = 0.0f64;
        for k in 0..=100_000 {
            let x = (k as f32 / 100_000.0 - 0.5) * std::f32::consts::FRAC_PI_2;
            let (s, c) = sin_cos_quarter(x);
            let (ws, wc) = (x as f64).sin_cos();
            worst = worst.max((s as f64 - ws).abs()).max((c as f64 - wc).abs());
        }
        assert!(worst < 3e-7, "quarter: largest error {worst}");
        let mut worst = 0.0f64;
        for k in 0..=100_000 {
            let u = k as f32 / 100_000.0;
            let (s, c) = sin_cos_turns(u);
            let (ws, wc) = (u as f64 * std::f64::consts::TAU).sin_cos();
            worst = worst.max((s as f64 - ws).abs()).max((c as f64 - wc).abs());
        }
        assert!(worst < 5e-7, "turns: largest error {worst}");
        assert_eq!(sin_cos_turns(0.0), (0.0, 1.0));
        assert_eq!(sin_cos_turns(0.25).0, 1.0);
    }

    /// Against the double-precision arctangent on a dense circle, the axes and the
    /// diagonals: the bound is the polynomial's fitted error (1.4e-7) plus the rounding of
    /// the inputs and of the octant identities (a few ulp of π).
    #[test]
    fn atan2_fast_matches_atan2() {
        let mut worst = 0.0f64;
        for k in 0..200_000 {
            let phi = (k as f64 / 200_000.0) * std::f64::consts::TAU - std::f64::consts::PI;
            for r in [1e-3f64, 1.0, 7.5] {
                let (y, x) = ((r * phi.sin()) as f32, (r * phi.cos()) as f32);
                let want = (y as f64).atan2(x as f64);
                worst = worst.max((atan2_fast(y, x) as f64 - want).abs());
            }
        }
        assert!(worst < 6e-7, "largest error {worst}");
        for (y, x) in [
            (0.0f32, 1.0f32),
            (1.0, 0.0),
            (0.0, -1.0),
            (-1.0, 0.0),
            (1.0, 1.0),
            (-2.0, -2.0),
        ] {
            let want = (y as f64).atan2(x as f64);
            assert!((atan2_fast(y, x) as f64 - want).abs() < 6e-7, "({y}, {x})");
        }
        assert_eq!(atan2_fast(0.0, 0.0), 0.0);
        assert!(atan2_fast(f32::NAN, 1.0).is_nan());
    }
}

/// The smallest box holding `points`: `(lo, hi)`; `(+inf, -inf)` for none.
pub fn bounds(points: impl Iterator<Item = Vec3>) -> (Vec3, Vec3) {
    points.fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    )
}
