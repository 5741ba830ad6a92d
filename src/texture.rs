//! Image textures (`map_Kd`): decoded once to linear RGB, looked up bilinearly with wrapping.

use crate::Rgb;
use crate::error::{Error, Result};
use glam::Vec2;
use std::path::Path;

#[derive(Clone, Debug)]
pub struct Texture {
    pub width: u32,
    pub height: u32,
    texels: Vec<Rgb>,
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
        Ok(Texture {
            width,
            height,
            texels,
        })
    }

    /// A texture from linear texels, row-major, top row first.
    pub fn from_texels(width: u32, height: u32, texels: Vec<Rgb>) -> Self {
        assert_eq!(texels.len(), (width * height) as usize);
        Texture {
            width,
            height,
            texels,
        }
    }

    #[inline]
    fn texel(&self, x: i64, y: i64) -> Rgb {
        let x = x.rem_euclid(self.width as i64) as usize;
        let y = y.rem_euclid(self.height as i64) as usize;
        self.texels[y * self.width as usize + x]
    }

    /// Bilinear lookup at `uv` (`v` up, as in OBJ), wrapping.
    pub fn lookup(&self, uv: Vec2) -> Rgb {
        if !uv.is_finite() {
            return self.texel(0, 0);
        }
        let x = uv.x * self.width as f32 - 0.5;
        let y = (1.0 - uv.y) * self.height as f32 - 0.5;
        let x0 = x.floor();
        let y0 = y.floor();
        let fx = x - x0;
        let fy = y - y0;
        let (x0, y0) = (x0 as i64, y0 as i64);
        let a = self.texel(x0, y0).lerp(self.texel(x0 + 1, y0), fx);
        let b = self.texel(x0, y0 + 1).lerp(self.texel(x0 + 1, y0 + 1), fx);
        a.lerp(b, fy)
    }
}
