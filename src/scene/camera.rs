//! The pinhole camera: primary rays for path tracing, and the camera importance `W_e` that
//! light tracing needs to splat a connection onto the film.
//!
//! Conventions: the image plane sits at distance 1 along `forward`; raster `(0, 0)` is the
//! top-left corner, `x` right, `y` down, in pixels. `W_e` is normalised over the whole image:
//! `W_e(ω) = 1 / (A · cos⁴θ)` with `A` the image plane's area at distance 1 (Veach 1997,
//! §10.3.3; pbrt-v4 `PerspectiveCamera::We`), so a pixel's box-filter importance is
//! `W_e · pixel_count` inside that pixel.

use crate::film::filter::PixelFilter;
use crate::math::Frame;
use glam::{Vec2, Vec3};

#[derive(Clone, Debug)]
pub struct Camera {
    pub position: Vec3,
    pub frame: Frame,
    pub width: u32,
    pub height: u32,
    /// Vertical field of view in degrees.
    pub fov_y_deg: f32,
    tan_half_y: f32,
    tan_half_x: f32,
    /// Image plane area at distance 1.
    plane_area: f32,
    /// Pixel reconstruction filter (box unless the scene asks for another).
    pub filter: PixelFilter,
}

/// A light-tracing connection from a surface point to the camera.
#[derive(Clone, Copy, Debug)]
pub struct CameraConnection {
    /// Where the point lands on the film, in pixels.
    pub raster: Vec2,
    /// Unit direction from the point to the camera.
    pub dir_to_camera: Vec3,
    pub distance: f32,
    /// `W_e(ω) · cos θ_cam / d²`: the importance arriving at the point, per unit projected
    /// area there, normalised over the whole image (multiply by the pixel count for a pixel).
    pub we_geom: f32,
}

impl Camera {
    /// Builds a camera; `Err` names what is wrong (zero look direction, look direction
    /// parallel to up, field of view out of range, zero resolution).
    pub fn new(
        position: Vec3,
        look_at: Vec3,
        up: Vec3,
        fov_y_deg: f32,
        width: u32,
        height: u32,
    ) -> Result<Self, String> {
        if !position.is_finite() || !look_at.is_finite() || !up.is_finite() {
            return Err("camera position, look_at and up must be finite".into());
        }
        let forward = (look_at - position)
            .try_normalize()
            .ok_or("camera look_at equals position: the look direction is zero")?;
        let up_n = up.try_normalize().ok_or("camera up vector is zero")?;
        let right = forward
            .cross(up_n)
            .try_normalize()
            .filter(|r| forward.cross(up_n).length() > 1e-6 && r.is_finite())
            .ok_or("camera look direction is parallel to up")?;
        let true_up = right.cross(forward);
        // Frame: x right, y up, z forward.
        let frame = Frame {
            x: right,
            y: true_up,
            z: forward,
        };
        Camera::from_frame(position, frame, fov_y_deg, width, height)
    }

    /// Builds a camera from its frame: `x` points right on the image, `y` up, `z` along the
    /// view (orthonormal; a mirrored, left-handed frame is allowed, as Mitsuba's sensor
    /// transforms may mirror the image).
    pub fn from_frame(
        position: Vec3,
        frame: Frame,
        fov_y_deg: f32,
        width: u32,
        height: u32,
    ) -> Result<Self, String> {
        if !position.is_finite()
            || !frame.x.is_finite()
            || !frame.y.is_finite()
            || !frame.z.is_finite()
        {
            return Err("camera position and orientation must be finite".into());
        }
        if width == 0 || height == 0 {
            return Err(format!(
                "camera resolution must be at least 1x1, got {width}x{height}"
            ));
        }
        if width > 32768 || height > 32768 {
            return Err(format!(
                "camera resolution {width}x{height} is larger than 32768 on a side"
            ));
        }
        if !(fov_y_deg > 0.0 && fov_y_deg < 179.0) {
            return Err(format!(
                "camera fov_y must be in (0, 179) degrees, got {fov_y_deg}"
            ));
        }
        let tan_half_y = (fov_y_deg.to_radians() * 0.5).tan();
        let tan_half_x = tan_half_y * width as f32 / height as f32;
        Ok(Camera {
            position,
            frame,
            width,
            height,
            fov_y_deg,
            tan_half_y,
            tan_half_x,
            plane_area: 4.0 * tan_half_x * tan_half_y,
            filter: PixelFilter::default(),
        })
    }

    /// The same camera with another resolution (the field of view stays vertical).
    pub fn with_resolution(&self, width: u32, height: u32) -> Result<Self, String> {
        let mut c = Camera::from_frame(self.position, self.frame, self.fov_y_deg, width, height)?;
        c.filter = self.filter.clone();
        Ok(c)
    }

    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Unit world direction of the ray through raster position `raster` (pixels).
    #[inline]
    pub fn ray_dir(&self, raster: Vec2) -> Vec3 {
        let sx = (2.0 * raster.x / self.width as f32 - 1.0) * self.tan_half_x;
        let sy = (1.0 - 2.0 * raster.y / self.height as f32) * self.tan_half_y;
        self.frame.to_world(Vec3::new(sx, sy, 1.0)).normalize()
    }

    /// Raster position of world direction `dir` (unit) from the camera, if on the film.
    #[inline]
    pub fn raster_of(&self, dir: Vec3) -> Option<Vec2> {
        let l = self.frame.to_local(dir);
        if l.z <= 0.0 {
            return None;
        }
        let sx = l.x / l.z / self.tan_half_x;
        let sy = l.y / l.z / self.tan_half_y;
        let x = (sx + 1.0) * 0.5 * self.width as f32;
        let y = (1.0 - sy) * 0.5 * self.height as f32;
        if x >= 0.0 && x < self.width as f32 && y >= 0.0 && y < self.height as f32 {
            Some(Vec2::new(x, y))
        } else {
            None
        }
    }

    /// `W_e` for a direction leaving the camera with cosine `cos_theta` to the view axis.
    #[inline]
    pub fn we(&self, cos_theta: f32) -> f32 {
        if cos_theta <= 0.0 {
            return 0.0;
        }
        let c2 = cos_theta * cos_theta;
        1.0 / (self.plane_area * c2 * c2)
    }

    /// Solid-angle density with which [`Camera::ray_dir`] directions are generated when the
    /// raster position is uniform over the whole image: `1 / (A cos³θ)`.
    #[inline]
    pub fn pdf_dir(&self, cos_theta: f32) -> f32 {
        if cos_theta <= 0.0 {
            return 0.0;
        }
        1.0 / (self.plane_area * cos_theta * cos_theta * cos_theta)
    }

    /// Connects surface point `p` to the camera (visibility not tested).
    #[inline]
    pub fn connect(&self, p: Vec3) -> Option<CameraConnection> {
        let to_cam = self.position - p;
        let d2 = to_cam.length_squared();
        if d2 <= 0.0 || !d2.is_finite() {
            return None;
        }
        let distance = d2.sqrt();
        let dir_to_camera = to_cam / distance;
        let raster = self.raster_of(-dir_to_camera)?;
        let cos_cam = (-dir_to_camera).dot(self.frame.z);
        let we_geom = self.we(cos_cam) * cos_cam / d2;
        Some(CameraConnection {
            raster,
            dir_to_camera,
            distance,
            we_geom,
        })
    }
}
