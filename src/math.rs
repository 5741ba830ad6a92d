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
