//! An environment map: radiance arriving from infinitely far, stored as a latitude-longitude
//! image, with Mitsuba 3's conventions (its `envmap` emitter):
//!
//! * **Directions.** In the map's own frame, texture coordinates `(u, v)` name the direction
//!   `(sin φ sin θ, cos θ, -cos φ sin θ)` with `φ = 2π u` and `θ = π v`: `+y` is up (the top
//!   row, `v = 0`), `u = 0` looks along `-z` and `u = 1/4` along `+x`. A `to_world` rotation
//!   turns the map's frame into the world's.
//! * **Lookup.** Bilinear between texel values placed at `u_i = (i + 1/2) / W` (periodic in
//!   `u`) and `v_j = j / (H - 1)` (the first and last rows lie on the poles).
//! * **Sampling** (pbrt-v3 §14.2.4, "Infinite Area Lights"). A piecewise-constant density
//!   over the cells between texel centres ([`Distribution2D`]), each weighted by the mean of
//!   its four corners' luminance times its solid angle over `Δφ`, `cos θ_j - cos θ_{j+1}`
//!   (the integral of `sin θ` over the row: a cell on a pole is not zero). A point of density
//!   `p(u, v)` on the square is a direction of density `p(u, v) / (2π² sin θ)` per steradian,
//!   the Jacobian of `(u, v) ↦ ω`. Sampling and [`EnvMap::pdf`] read the same cells, so they
//!   agree, and every direction of non-zero radiance has a non-zero density.

use crate::distribution_2d::Distribution2D;
use crate::math::{PI, Rgb, luminance};
use glam::{Mat3, Vec2, Vec3};
use std::path::{Path, PathBuf};

#[derive(Clone, Debug)]
pub struct EnvMap {
    width: usize,
    height: usize,
    /// Row-major, top row (`θ = 0`) first.
    texels: Vec<Rgb>,
    /// World from the map's frame (a rotation), and back.
    to_world: Mat3,
    to_local: Mat3,
    /// Over the `W x (H - 1)` cells between texel centres, in `(s, v)` with `s = u - 1/(2W)`.
    distribution: Distribution2D,
    /// `∫ L dω` over the sphere (RGB).
    integral: Rgb,
    /// The file the map was read from, if any.
    pub source: Option<PathBuf>,
}

/// Why a map cannot be made: the message names what is wrong (the caller names the file).
pub type EnvMapError = String;

impl EnvMap {
    /// The map of `width x height` texels (row-major, top row first) turned by `to_world`
    /// (a rotation). Every texel must be finite and non-negative, the image at least 2 x 3
    /// texels (as Mitsuba 3 requires) and not black.
    pub fn new(
        width: usize,
        height: usize,
        texels: Vec<Rgb>,
        to_world: Mat3,
    ) -> Result<Self, EnvMapError> {
        if width < 2 || height < 3 {
            return Err(format!(
                "the image is {width} x {height} texels: an environment map needs at least 2 x 3"
            ));
        }
        if texels.len() != width * height {
            return Err(format!(
                "{} texels for a {width} x {height} image",
                texels.len()
            ));
        }
        if let Some(k) = texels
            .iter()
            .position(|t| !(t.is_finite() && t.min_element() >= 0.0))
        {
            return Err(format!(
                "texel ({}, {}) is {} (radiance must be finite and not negative)",
                k % width,
                k / width,
                texels[k]
            ));
        }
        let rotation = to_world.transpose() * to_world;
        if !(rotation.abs_diff_eq(Mat3::IDENTITY, 1e-4) && to_world.determinant() > 0.0) {
            return Err("to_world must be a rotation (no scale, shear or mirror)".into());
        }
        let (w, h) = (width, height);
        let d_theta = PI / (h - 1) as f32;
        let mut weights = Vec::with_capacity(w * (h - 1));
        let mut integral = Rgb::ZERO;
        for j in 0..h - 1 {
            let band = (j as f32 * d_theta).cos() - ((j + 1) as f32 * d_theta).cos();
            for i in 0..w {
                let i1 = (i + 1) % w;
                let corners = texels[j * w + i]
                    + texels[j * w + i1]
                    + texels[(j + 1) * w + i]
                    + texels[(j + 1) * w + i1];
                let mean = corners * 0.25;
                weights.push(luminance(mean) * band.max(0.0));
                integral += mean * (band * 2.0 * PI / w as f32);
            }
        }
        let distribution = Distribution2D::new(&weights, w, h - 1)
            .ok_or("the map is black: it emits nothing".to_string())?;
        Ok(EnvMap {
            width,
            height,
            texels,
            to_world,
            to_local: to_world.transpose(),
            distribution,
            integral,
            source: None,
        })
    }

    /// Reads a map from an OpenEXR (`.exr`) or Radiance RGBE (`.hdr`) file, linear RGB.
    pub fn load(path: &Path, to_world: Mat3) -> Result<Self, EnvMapError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase();
        let (width, height, texels) = match ext.as_str() {
            "exr" => {
                let img = crate::film::image_io::read_exr(path)
                    .map_err(|e| format!("not a readable EXR image ({e})"))?;
                (img.width as usize, img.height as usize, img.pixels)
            }
            "hdr" => {
                let mut bytes =
                    std::fs::read(path).map_err(|e| format!("cannot read the file ({e})"))?;
                // Radiance files open with `#?RADIANCE` or, as Mitsuba and others write them,
                // `#?RGBE`; the decoder knows the first.
                if bytes.starts_with(b"#?RGBE\n") {
                    bytes.splice(..6, b"#?RADIANCE".iter().copied());
                }
                let mut reader = image::ImageReader::with_format(
                    std::io::Cursor::new(bytes),
                    image::ImageFormat::Hdr,
                );
                let mut limits = image::Limits::default();
                limits.max_image_width = Some(crate::scene::texture::MAX_TEXTURE_SIDE);
                limits.max_image_height = Some(crate::scene::texture::MAX_TEXTURE_SIDE);
                reader.limits(limits);
                let img = reader
                    .decode()
                    .map_err(|e| format!("not a readable Radiance HDR image ({e})"))?
                    .to_rgb32f();
                let (w, h) = img.dimensions();
                let texels = img.pixels().map(|p| Rgb::new(p[0], p[1], p[2])).collect();
                (w as usize, h as usize, texels)
            }
            _ => {
                return Err(
                    "an environment map must be an OpenEXR (.exr) or Radiance HDR (.hdr) image"
                        .into(),
                );
            }
        };
        let mut map = EnvMap::new(width, height, texels, to_world)?;
        map.source = Some(path.to_path_buf());
        Ok(map)
    }

    /// Size in texels.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// The texel in column `x` of row `y` (row 0 at the top).
    pub fn texel(&self, x: usize, y: usize) -> Rgb {
        self.texels[y * self.width + x]
    }

    /// World from the map's frame.
    pub fn to_world(&self) -> Mat3 {
        self.to_world
    }

    /// `∫ L dω` over the sphere, by the cells' mean radiance (RGB).
    pub fn integral(&self) -> Rgb {
        self.integral
    }

    /// The texture coordinates of a unit direction of the map's frame.
    #[inline]
    pub fn direction_to_uv(d: Vec3) -> Vec2 {
        let u = d.x.atan2(-d.z) * (0.5 / PI);
        let v = d.y.clamp(-1.0, 1.0).acos() * (1.0 / PI);
        Vec2::new(u - u.floor(), v)
    }

    /// The unit direction of the map's frame at texture coordinates `uv`, and `sin θ`.
    #[inline]
    pub fn uv_to_direction(uv: Vec2) -> (Vec3, f32) {
        let (sin_t, cos_t) = (uv.y * PI).sin_cos();
        let (sin_p, cos_p) = (uv.x * 2.0 * PI).sin_cos();
        (
            Vec3::new(sin_p * sin_t, cos_t, -cos_p * sin_t),
            sin_t.max(0.0),
        )
    }

    /// The bilinear lookup at texture coordinates `uv` (`u` periodic, `v` clamped).
    #[inline]
    pub fn lookup(&self, uv: Vec2) -> Rgb {
        let (w, h) = (self.width, self.height);
        let s = uv.x - 0.5 / w as f32;
        let x = (s - s.floor()) * w as f32;
        let y = uv.y.clamp(0.0, 1.0) * (h - 1) as f32;
        let i = (x as usize).min(w - 1);
        let j = (y as usize).min(h - 2);
        let (fx, fy) = (x - i as f32, y - j as f32);
        let i1 = if i + 1 == w { 0 } else { i + 1 };
        let t = |i: usize, j: usize| self.texels[j * w + i];
        let top = t(i, j) * (1.0 - fx) + t(i1, j) * fx;
        let bottom = t(i, j + 1) * (1.0 - fx) + t(i1, j + 1) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// Radiance arriving from the world direction `toward` (unit, pointing at the map).
    #[inline]
    pub fn eval(&self, toward: Vec3) -> Rgb {
        self.lookup(Self::direction_to_uv(self.to_local * toward))
    }

    /// A world direction toward the map with its density per steradian and its radiance, as
    /// [`EnvMap::pdf`] and [`EnvMap::eval`] give them for that direction (so that they agree
    /// exactly, also where a direction on the border of two cells comes back from its
    /// coordinates in the other); `None` where that density is zero or cannot be expressed
    /// (`sin θ = 0`, on a pole).
    #[inline]
    pub fn sample(&self, u: Vec2) -> Option<(Vec3, f32, Rgb)> {
        let (st, _) = self.distribution.sample(u);
        let su = st.x + 0.5 / self.width as f32;
        let uv = Vec2::new(if su >= 1.0 { su - 1.0 } else { su }, st.y);
        let (local, _) = Self::uv_to_direction(uv);
        let toward = (self.to_world * local).normalize();
        let (pdf_w, uv) = self.pdf_and_uv(toward);
        if !(pdf_w > 0.0) {
            return None;
        }
        Some((toward, pdf_w, self.lookup(uv)))
    }

    /// Density per steradian with which [`EnvMap::sample`] returns the world direction
    /// `toward` (unit).
    #[inline]
    pub fn pdf(&self, toward: Vec3) -> f32 {
        self.pdf_and_uv(toward).0
    }

    /// [`EnvMap::pdf`] and the direction's texture coordinates: the density of its cell over
    /// the Jacobian `2π² sin θ`; 0 on the poles.
    #[inline]
    fn pdf_and_uv(&self, toward: Vec3) -> (f32, Vec2) {
        let uv = Self::direction_to_uv(self.to_local * toward);
        let (_, sin_t) = Self::uv_to_direction(uv);
        if !(sin_t > 0.0) {
            return (0.0, uv);
        }
        let s = uv.x - 0.5 / self.width as f32;
        let st = Vec2::new(if s < 0.0 { s + 1.0 } else { s }, uv.y);
        let pdf_w = self.distribution.pdf(st) / (2.0 * PI * PI * sin_t);
        (if pdf_w.is_finite() { pdf_w } else { 0.0 }, uv)
    }
}
