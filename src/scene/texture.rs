//! Textures: images (`map_Kd`, Mitsuba `bitmap`) decoded once to linear RGB and looked up
//! bilinearly with wrapping, and Mitsuba's procedural `checkerboard`.
//!
//! Texture coordinates arrive as stored on the triangles, OBJ convention (`v` up). A lookup
//! first turns them into image convention `(u, 1 - v)` (`v` down, row 0 at the top; what
//! Mitsuba 3's OBJ loader stores), then applies the texture's optional `to_uv` transform
//! (Mitsuba's `to_uv`), then reads the image or evaluates the pattern there.

use crate::Rgb;
use crate::error::{Error, Result};
use glam::{Affine2, Vec2};
use std::path::Path;

#[derive(Clone, Debug)]
pub enum TextureKind {
    /// An image, row-major, top row first, linear RGB.
    Bitmap {
        width: u32,
        height: u32,
        texels: Vec<Rgb>,
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

impl Texture {
    /// Loads an 8-bit image (PNG or JPEG) as sRGB-encoded colour.
    pub fn load(path: &Path) -> Result<Self> {
        let img = image::open(path).map_err(|e| Error::Texture {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        let rgb = img.to_rgb8();
        let (width, height) = rgb.dimensions();
        if width == 0 || height == 0 {
            return Err(Error::Texture {
                path: path.to_path_buf(),
                message: "image has zero size".into(),
            });
        }
        // A lookup table for the 256 possible values.
        let lut: Vec<f32> = (0..256).map(|i| srgb_to_linear(i as f32 / 255.0)).collect();
        let texels = rgb
            .pixels()
            .map(|p| Rgb::new(lut[p[0] as usize], lut[p[1] as usize], lut[p[2] as usize]))
            .collect();
        Ok(Texture::from_texels(width, height, texels))
    }

    /// A texture from linear texels, row-major, top row first.
    pub fn from_texels(width: u32, height: u32, texels: Vec<Rgb>) -> Self {
        assert_eq!(texels.len(), (width * height) as usize);
        Texture {
            kind: TextureKind::Bitmap {
                width,
                height,
                texels,
            },
            to_uv: None,
        }
    }

    /// Mitsuba's checkerboard.
    pub fn checkerboard(color0: Rgb, color1: Rgb) -> Self {
        Texture {
            kind: TextureKind::Checkerboard { color0, color1 },
            to_uv: None,
        }
    }

    /// Size in texels (a procedural texture has none: 0 x 0).
    pub fn size(&self) -> (u32, u32) {
        match &self.kind {
            TextureKind::Bitmap { width, height, .. } => (*width, *height),
            TextureKind::Checkerboard { .. } => (0, 0),
        }
    }

    /// Lookup at `uv` (`v` up, as stored on triangles); bilinear and wrapping for images.
    pub fn lookup(&self, uv: Vec2) -> Rgb {
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        let mut st = Vec2::new(uv.x, 1.0 - uv.y);
        if let Some(t) = &self.to_uv {
            st = t.transform_point2(st);
        }
        match &self.kind {
            TextureKind::Bitmap {
                width,
                height,
                texels,
            } => {
                let texel = |x: i64, y: i64| {
                    let x = x.rem_euclid(*width as i64) as usize;
                    let y = y.rem_euclid(*height as i64) as usize;
                    texels[y * *width as usize + x]
                };
                let x = st.x * *width as f32 - 0.5;
                let y = st.y * *height as f32 - 0.5;
                if !(x.is_finite() && y.is_finite()) {
                    return texel(0, 0);
                }
                let x0 = x.floor();
                let y0 = y.floor();
                let fx = x - x0;
                let fy = y - y0;
                let (x0, y0) = (x0 as i64, y0 as i64);
                let a = texel(x0, y0).lerp(texel(x0 + 1, y0), fx);
                let b = texel(x0, y0 + 1).lerp(texel(x0 + 1, y0 + 1), fx);
                a.lerp(b, fy)
            }
            TextureKind::Checkerboard { color0, color1 } => {
                let mx = st.x - st.x.floor() > 0.5;
                let my = st.y - st.y.floor() > 0.5;
                if mx == my { *color0 } else { *color1 }
            }
        }
    }
}
