//! Textures: images (`map_Kd`, Mitsuba `bitmap`, sRGB-encoded or `raw`) looked up bilinearly
//! with wrapping, and Mitsuba's procedural `checkerboard`; an image's luminance gradient, as
//! a bump map reads it (Mitsuba's `eval_1_grad`).
//!
//! Texture coordinates arrive as stored on the triangles, OBJ convention (`v` up). A lookup
//! first turns them into image convention `(u, 1 - v)` (`v` down, row 0 at the top; what
//! Mitsuba 3's OBJ loader stores), then applies the texture's optional `to_uv` transform
//! (Mitsuba's `to_uv`), then reads the image or evaluates the pattern there.

use crate::Rgb;
use crate::error::{Error, Result};
use crate::math::luminance_mitsuba;
use glam::{Affine2, Vec2};
use std::path::Path;

/// The largest texture side, in pixels: a bitmap's header that declares more is refused
/// before its pixels are decoded.
pub const MAX_TEXTURE_SIDE: u32 = 16384;
/// The most memory the decoding of one bitmap may take (the image crate's default).
pub const MAX_TEXTURE_BYTES: u64 = 512 << 20;

#[derive(Clone, Debug)]
pub enum TextureKind {
    /// An 8-bit image, row-major, top row first, sRGB-encoded as in its file. Lookups decode
    /// through a 256-entry table: 4 bytes a texel instead of 12 keeps 3 times more of a large
    /// texture in cache (the lookups are memory-bound), and gives the same linear values as
    /// decoding at load.
    Bitmap {
        width: u32,
        height: u32,
        texels: Vec<[u8; 4]>,
    },
    /// Mitsuba 3's checkerboard: `color0` where `frac(u) > 1/2` equals `frac(v) > 1/2`,
    /// `color1` elsewhere.
    Checkerboard { color0: Rgb, color1: Rgb },
}

#[derive(Clone, Debug)]
pub struct Texture {
    pub kind: TextureKind,
    /// Transform of the image-convention texture coordinates.
    pub to_uv: Option<Affine2>,
    /// The bytes are the values themselves (`v / 255`, Mitsuba's `raw`), not sRGB-encoded.
    pub raw: bool,
}

/// sRGB transfer function to linear.
#[inline]
pub fn srgb_to_linear(v: f32) -> f32 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear values of the 256 8-bit sRGB codes.
#[inline(always)]
fn srgb8_table() -> &'static [f32; 256] {
    static TABLE: std::sync::LazyLock<[f32; 256]> =
        std::sync::LazyLock::new(|| std::array::from_fn(|i| srgb_to_linear(i as f32 / 255.0)));
    &TABLE
}

/// The values of the 256 bytes read raw, `v / 255`.
#[inline(always)]
fn raw8_table() -> &'static [f32; 256] {
    static TABLE: std::sync::LazyLock<[f32; 256]> =
        std::sync::LazyLock::new(|| std::array::from_fn(|i| i as f32 / 255.0));
    &TABLE
}

/// Mitsuba 3's luminance of a linear RGB colour (`mitsuba/core/spectrum.h`), which its
/// textures' monochromatic lookups and gradients read.
#[inline]
fn mitsuba_luminance(c: Rgb) -> f32 {
    0.212671 * c.x + 0.715160 * c.y + 0.072169 * c.z
}

/// The linear colour of an 8-bit sRGB texel.
#[inline(always)]
pub fn srgb8_to_linear([r, g, b, _]: [u8; 4]) -> Rgb {
    let lut = srgb8_table();
    Rgb::new(lut[r as usize], lut[g as usize], lut[b as usize])
}

/// `i` and `i + 1` wrapped into `0..n`.
#[inline(always)]
fn wrap_pair(i: i32, n: i32) -> (usize, usize) {
    let i0 = if (0..n).contains(&i) {
        i
    } else {
        i.rem_euclid(n)
    };
    let i1 = if i0 + 1 == n { 0 } else { i0 + 1 };
    (i0 as usize, i1 as usize)
}

impl Texture {
    /// Loads an 8-bit image (PNG or JPEG) as sRGB-encoded colour.
    pub fn load(path: &Path) -> Result<Self> {
        let fail = |e: image::ImageError| Error::Texture {
            path: path.to_path_buf(),
            message: match e {
                image::ImageError::Limits(_) => format!(
                    "the image is larger than a texture may be ({MAX_TEXTURE_SIDE} pixels a side, {} MB decoded)",
                    MAX_TEXTURE_BYTES >> 20
                ),
                e => e.to_string(),
            },
        };
        let mut reader = image::ImageReader::open(path).map_err(|e| fail(e.into()))?;
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(MAX_TEXTURE_SIDE);
        limits.max_image_height = Some(MAX_TEXTURE_SIDE);
        limits.max_alloc = Some(MAX_TEXTURE_BYTES);
        reader.limits(limits);
        let img = reader.decode().map_err(fail)?;
        let rgb = img.to_rgb8();
        let (width, height) = rgb.dimensions();
        if width == 0 || height == 0 {
            return Err(Error::Texture {
                path: path.to_path_buf(),
                message: "image has zero size".into(),
            });
        }
        let texels = rgb.pixels().map(|p| [p[0], p[1], p[2], 0]).collect();
        Ok(Texture::from_srgb8(width, height, texels))
    }

    /// A texture from 8-bit sRGB-encoded texels (the fourth byte unused), row-major, top row
    /// first.
    pub fn from_srgb8(width: u32, height: u32, texels: Vec<[u8; 4]>) -> Self {
        assert_eq!(texels.len(), (width * height) as usize);
        Texture {
            kind: TextureKind::Bitmap {
                width,
                height,
                texels,
            },
            to_uv: None,
            raw: false,
        }
    }

    /// Mitsuba's checkerboard.
    pub fn checkerboard(color0: Rgb, color1: Rgb) -> Self {
        Texture {
            kind: TextureKind::Checkerboard { color0, color1 },
            to_uv: None,
            raw: false,
        }
    }

    /// Size in texels (a procedural texture has none: 0 x 0).
    pub fn size(&self) -> (u32, u32) {
        match &self.kind {
            TextureKind::Bitmap { width, height, .. } => (*width, *height),
            TextureKind::Checkerboard { .. } => (0, 0),
        }
    }

    /// The decoding table of the texel bytes: sRGB, or the bytes' values when `raw`.
    #[inline(always)]
    fn table(&self) -> &'static [f32; 256] {
        if self.raw {
            raw8_table()
        } else {
            srgb8_table()
        }
    }

    /// The texture coordinates a lookup at `uv` (`v` up, as stored on triangles) reads:
    /// image convention `(u, 1 - v)`, then `to_uv`.
    #[inline]
    fn st(&self, uv: Vec2) -> Vec2 {
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        let st = Vec2::new(uv.x, 1.0 - uv.y);
        match &self.to_uv {
            Some(t) => t.transform_point2(st),
            None => st,
        }
    }

    /// The gradient of the texture's luminance with respect to Mitsuba's texture coordinates
    /// `(u, 1 - v)` at `uv` (`v` up), as Mitsuba 3's `bitmap` computes it (`eval_1_grad`,
    /// `src/textures/bitmap.cpp`): the bilinear interpolant's partials in texel units, `(1 -
    /// f_y)(f₁₀ - f₀₀) + f_y (f₁₁ - f₀₁)` and `(1 - f_x)(f₀₁ - f₀₀) + f_x (f₁₁ - f₁₀)`, taken
    /// through the transpose of `to_uv`'s linear part and then scaled by the resolution
    /// `(width, height)` component by component (Mitsuba's order). A procedural texture has
    /// none: `None`.
    pub fn luminance_gradient(&self, uv: Vec2) -> Option<Vec2> {
        let TextureKind::Bitmap {
            width,
            height,
            texels,
        } = &self.kind
        else {
            return None;
        };
        let st = self.st(uv);
        let (w, h) = (*width as i32, *height as i32);
        let x = st.x * w as f32 - 0.5;
        let y = st.y * h as f32 - 0.5;
        if !(x.is_finite() && y.is_finite()) {
            return Some(Vec2::ZERO);
        }
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, x1) = wrap_pair(x0 as i32, w);
        let (y0, y1) = wrap_pair(y0 as i32, h);
        let (row0, row1) = (y0 * *width as usize, y1 * *width as usize);
        let lut = self.table();
        let f = |i: usize| {
            let [r, g, b, _] = texels[i];
            mitsuba_luminance(Rgb::new(lut[r as usize], lut[g as usize], lut[b as usize]))
        };
        let (f00, f10, f01, f11) = (f(row0 + x0), f(row0 + x1), f(row1 + x0), f(row1 + x1));
        let df_xy = Vec2::new(
            (1.0 - fy) * (f10 - f00) + fy * (f11 - f01),
            (1.0 - fx) * (f01 - f00) + fx * (f11 - f10),
        );
        let df_st = match &self.to_uv {
            Some(t) => Vec2::new(t.matrix2.x_axis.dot(df_xy), t.matrix2.y_axis.dot(df_xy)),
            None => df_xy,
        };
        Some(df_st * Vec2::new(*width as f32, *height as f32))
    }

    /// The scalar value at `uv` (`v` up) of a texture given for a scalar property, as
    /// Mitsuba 3.9's `eval_1`: a bitmap's luminance ([`luminance_mitsuba`]; the grey value of a
    /// grey one); for a checkerboard, `color1` where [`Texture::lookup`] (Mitsuba's `eval`)
    /// gives `color0` and `color0` where it gives `color1`: Mitsuba's `eval_1` takes the
    /// opposite cells (`src/textures/checkerboard.cpp`), and footprint renders what Mitsuba
    /// renders.
    pub fn lookup_1(&self, uv: Vec2) -> f32 {
        match &self.kind {
            TextureKind::Checkerboard { color0, color1 } => {
                let cell0 = color0_cell(self.st(uv));
                luminance_mitsuba(if cell0 { *color1 } else { *color0 })
            }
            TextureKind::Bitmap { .. } => luminance_mitsuba(self.lookup(uv)),
        }
    }

    /// Lookup at `uv` (`v` up, as stored on triangles); bilinear and wrapping for images.
    pub fn lookup(&self, uv: Vec2) -> Rgb {
        let st = self.st(uv);
        match &self.kind {
            TextureKind::Bitmap {
                width,
                height,
                texels,
            } => {
                let (w, h) = (*width as i32, *height as i32);
                let x = st.x * w as f32 - 0.5;
                let y = st.y * h as f32 - 0.5;
                if !(x.is_finite() && y.is_finite()) {
                    return srgb8_to_linear(texels[0]);
                }
                let x0 = x.floor();
                let y0 = y.floor();
                let fx = x - x0;
                let fy = y - y0;
                // Wrapped texel columns and rows: one remainder each (the `as` casts saturate
                // far outside the image; any wrapped index is then still in range).
                let (x0, x1) = wrap_pair(x0 as i32, w);
                let (y0, y1) = wrap_pair(y0 as i32, h);
                let row0 = y0 * *width as usize;
                let row1 = y1 * *width as usize;
                let lut = self.table();
                let texel = |i: usize| {
                    let [r, g, b, _] = texels[i];
                    Rgb::new(lut[r as usize], lut[g as usize], lut[b as usize])
                };
                let a = texel(row0 + x0).lerp(texel(row0 + x1), fx);
                let b = texel(row1 + x0).lerp(texel(row1 + x1), fx);
                a.lerp(b, fy)
            }
            TextureKind::Checkerboard { color0, color1 } => {
                if color0_cell(st) {
                    *color0
                } else {
                    *color1
                }
            }
        }
    }
}

/// True where a checkerboard's colour lookup (Mitsuba's `eval`) gives `color0` at texture
/// coordinates `st`: the fractional parts of both on the same side of 1/2.
#[inline]
fn color0_cell(st: Vec2) -> bool {
    (st.x - st.x.floor() > 0.5) == (st.y - st.y.floor() > 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3x2 image with distinct bytes per texel and channel.
    fn image() -> Texture {
        let texels = (0..6u8)
            .map(|i| [10 + 40 * i, 200 - 30 * i, 7 * i * i, 0])
            .collect();
        Texture::from_srgb8(3, 2, texels)
    }

    /// The linear value of texel (x, y) decoded by the transfer function itself (not the table).
    fn decoded(t: &Texture, x: usize, y: usize) -> Rgb {
        let TextureKind::Bitmap { texels, width, .. } = &t.kind else {
            unreachable!()
        };
        let [r, g, b, _] = texels[y * *width as usize + x];
        let f = |v: u8| srgb_to_linear(v as f32 / 255.0);
        Rgb::new(f(r), f(g), f(b))
    }

    /// `uv` (v up) of the centre of texel (x, y) (row 0 at the top).
    fn centre(x: f32, y: f32) -> Vec2 {
        Vec2::new((x + 0.5) / 3.0, 1.0 - (y + 0.5) / 2.0)
    }

    #[test]
    fn texel_centres_decode_their_bytes() {
        let t = image();
        for y in 0..2 {
            for x in 0..3 {
                let got = t.lookup(centre(x as f32, y as f32));
                assert!(got.abs_diff_eq(decoded(&t, x, y), 1e-6), "texel ({x}, {y})");
            }
        }
    }

    #[test]
    fn bilinear_between_texels_and_wrapping_across_edges() {
        let t = image();
        // Halfway between texels (0, 0) and (1, 0).
        let mid = t.lookup(centre(0.5, 0.0));
        let want = 0.5 * (decoded(&t, 0, 0) + decoded(&t, 1, 0));
        assert!(mid.abs_diff_eq(want, 1e-6));
        // Halfway between the last column and the first (wrapping), and the same a whole
        // period away in both directions (negative coordinates included).
        let edge = t.lookup(centre(2.5, 1.0));
        let want = 0.5 * (decoded(&t, 2, 1) + decoded(&t, 0, 1));
        assert!(edge.abs_diff_eq(want, 1e-6));
        for shift in [-3.0f32, -1.0, 2.0, 5.0] {
            let uv = centre(2.5, 1.0) + Vec2::splat(shift);
            assert!(t.lookup(uv).abs_diff_eq(edge, 1e-5), "shift {shift}");
        }
        // Non-finite coordinates read texel 0 instead of a NaN.
        assert!(t.lookup(Vec2::NAN).is_finite());
    }
}
