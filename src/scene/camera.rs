//! The perspective camera, a pinhole or a thin lens: primary rays for path tracing, and the
//! camera importance `W_e` that light tracing needs to splat a connection onto the film.
//!
//! Conventions: the image plane sits at distance 1 along `forward`; raster `(0, 0)` is the
//! top-left corner, `x` right, `y` down, in pixels. `W_e` is normalised over the whole image:
//! `W_e(ω) = 1 / (A · cos⁴θ)` with `A` the image plane's area at distance 1 (Veach 1997,
//! §10.3.3; pbrt-v4 `PerspectiveCamera::We`), so a pixel's box-filter importance is
//! `W_e · pixel_count` inside that pixel.
//!
//! **Thin lens** (pbrt-v4 §5.2.3; Mitsuba 3's `thinlens`): a disk of radius `lens_radius`
//! (world units) about `position`, perpendicular to the view axis, focused on the plane at
//! `focus_distance` along that axis. A camera ray starts at a point sampled uniformly on the
//! disk (concentric mapping) and passes through the point of the focal plane that the
//! raster position's pinhole ray reaches, as Mitsuba's `ThinLensCamera::sample_ray` does.
//! The importance of a lens point `x` is `W_e(x, ω) = 1 / (A · A_lens · cos⁴θ)` (pbrt-v4
//! `PerspectiveCamera::We`): the pinhole's spread over the lens area. A connection samples
//! the lens uniformly (density `1 / A_lens` per unit area, pbrt-v4
//! `PerspectiveCamera::SampleWi`), so its `W_e · cos θ / (d² p_A)` is the pinhole's value at
//! the lens point, on the raster position the focused ray from that lens point reaches.
//! The direction density of a ray from a lens point is the pinhole's `1 / (A cos³θ)`: the
//! focal plane's image rectangle of area `f² A` seen from the lens point. A lens radius of
//! 0 is the pinhole, computed as before.

use crate::film::filter::PixelFilter;
use crate::math::{Frame, PI};
use crate::rng::Rng;
use crate::sampling::sample_concentric_disk;
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
    /// Thin lens: radius of the aperture disk in world units (0: a pinhole).
    lens_radius: f32,
    /// Thin lens: distance of the plane in focus along the view axis, in world units.
    focus_distance: f32,
}

/// A light-tracing connection from a surface point to the camera.
#[derive(Clone, Copy, Debug)]
pub struct CameraConnection {
    /// Where the point lands on the film, in pixels.
    pub raster: Vec2,
    /// The camera vertex: the sampled lens point (the position for a pinhole), world space.
    pub lens: Vec3,
    /// Unit direction from the point to the camera vertex.
    pub dir_to_camera: Vec3,
    pub distance: f32,
    /// `W_e(x, ω) · cos θ_cam / (d² p_A(x))`: the importance arriving at the point, per unit
    /// projected area there, normalised over the whole image (multiply by the pixel count for
    /// a pixel), divided by the lens point's density per unit area (1 for a pinhole).
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
            lens_radius: 0.0,
            focus_distance: 1.0,
        })
    }

    /// The same camera with a thin lens of aperture radius `lens_radius` focused at
    /// `focus_distance` along the view axis (both world units); radius 0 is the pinhole.
    pub fn with_lens(mut self, lens_radius: f32, focus_distance: f32) -> Result<Self, String> {
        if !(lens_radius >= 0.0 && lens_radius.is_finite()) {
            return Err(format!(
                "the aperture radius must be finite and at least 0, got {lens_radius}"
            ));
        }
        if !(focus_distance > 0.0 && focus_distance.is_finite()) {
            return Err(format!(
                "the focus distance must be finite and greater than 0, got {focus_distance}"
            ));
        }
        self.lens_radius = lens_radius;
        self.focus_distance = focus_distance;
        Ok(self)
    }

    /// The same camera with another resolution (the field of view stays vertical; the lens
    /// and the filter stay).
    pub fn with_resolution(&self, width: u32, height: u32) -> Result<Self, String> {
        let mut c = Camera::from_frame(self.position, self.frame, self.fov_y_deg, width, height)?
            .with_lens(self.lens_radius, self.focus_distance)?;
        c.filter = self.filter.clone();
        Ok(c)
    }

    /// Radius of the lens's aperture in world units (0: a pinhole).
    #[inline]
    pub fn lens_radius(&self) -> f32 {
        self.lens_radius
    }

    /// Distance of the plane in focus along the view axis, in world units.
    #[inline]
    pub fn focus_distance(&self) -> f32 {
        self.focus_distance
    }

    /// The camera has a lens (its rays and connections start on a disk, not at a point).
    #[inline]
    pub fn has_lens(&self) -> bool {
        self.lens_radius > 0.0
    }

    /// Area of the lens's aperture disk (world units²; 0 for a pinhole).
    #[inline]
    pub fn lens_area(&self) -> f32 {
        PI * self.lens_radius * self.lens_radius
    }

    /// The two numbers that choose a lens point, drawn from `rng` where there is a lens: a
    /// pinhole draws none, so that its paths read the same numbers as without this call.
    #[inline]
    pub fn draw_lens_sample(&self, rng: &mut Rng) -> Vec2 {
        if self.has_lens() {
            rng.uniform2()
        } else {
            Vec2::splat(0.5)
        }
    }

    /// The lens point that `u_lens` in [0, 1)² chooses (uniform over the disk by the
    /// concentric mapping, as Mitsuba's `square_to_uniform_disk_concentric`), in the camera's
    /// local frame (`z = 0`).
    #[inline]
    fn lens_point_local(&self, u_lens: Vec2) -> Vec3 {
        (self.lens_radius * sample_concentric_disk(u_lens)).extend(0.0)
    }

    /// The lens point `u_lens` chooses, in world space (the position for a pinhole).
    #[inline]
    pub fn lens_point(&self, u_lens: Vec2) -> Vec3 {
        if !self.has_lens() {
            return self.position;
        }
        self.position + self.frame.to_world(self.lens_point_local(u_lens))
    }

    /// The camera ray through raster position `raster` (pixels) from the lens point `u_lens`
    /// chooses: its origin and unit direction. The ray aims at the point of the focal plane
    /// that the pinhole ray through `raster` reaches (Mitsuba's `ThinLensCamera::sample_ray`);
    /// a pinhole's is `(position, ray_dir(raster))`.
    #[inline]
    pub fn ray(&self, raster: Vec2, u_lens: Vec2) -> (Vec3, Vec3) {
        if !self.has_lens() {
            return (self.position, self.ray_dir(raster));
        }
        let lens = self.lens_point_local(u_lens);
        let focus = self.image_plane_point(raster) * self.focus_distance;
        let dir = self.frame.to_world(focus - lens).normalize();
        (self.position + self.frame.to_world(lens), dir)
    }

    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// The point of the image plane at distance 1 that raster position `raster` (pixels)
    /// names, in the camera's local frame.
    #[inline]
    fn image_plane_point(&self, raster: Vec2) -> Vec3 {
        let sx = (2.0 * raster.x / self.width as f32 - 1.0) * self.tan_half_x;
        let sy = (1.0 - 2.0 * raster.y / self.height as f32) * self.tan_half_y;
        Vec3::new(sx, sy, 1.0)
    }

    /// Unit world direction of the pinhole ray through raster position `raster` (pixels):
    /// the ray from the lens centre.
    #[inline]
    pub fn ray_dir(&self, raster: Vec2) -> Vec3 {
        self.frame
            .to_world(self.image_plane_point(raster))
            .normalize()
    }

    /// Raster position of world direction `dir` (unit) from the lens centre, if on the film.
    #[inline]
    pub fn raster_of(&self, dir: Vec3) -> Option<Vec2> {
        let l = self.frame.to_local(dir);
        if l.z <= 0.0 {
            return None;
        }
        self.raster_at(Vec2::new(l.x / l.z, l.y / l.z))
    }

    /// Raster position of the image-plane point `(x, y, 1)` (camera frame), if on the film.
    #[inline]
    fn raster_at(&self, plane: Vec2) -> Option<Vec2> {
        let sx = plane.x / self.tan_half_x;
        let sy = plane.y / self.tan_half_y;
        let x = (sx + 1.0) * 0.5 * self.width as f32;
        let y = (1.0 - sy) * 0.5 * self.height as f32;
        if x >= 0.0 && x < self.width as f32 && y >= 0.0 && y < self.height as f32 {
            Some(Vec2::new(x, y))
        } else {
            None
        }
    }

    /// `W_e` for a direction leaving the camera with cosine `cos_theta` to the view axis (a
    /// pinhole's; a thin lens's at a lens point is this divided by the lens area, module
    /// doc).
    #[inline]
    pub fn we(&self, cos_theta: f32) -> f32 {
        if cos_theta <= 0.0 {
            return 0.0;
        }
        let c2 = cos_theta * cos_theta;
        1.0 / (self.plane_area * c2 * c2)
    }

    /// Solid-angle density with which [`Camera::ray`] directions from one lens point (or
    /// the pinhole) are generated when the raster position is uniform over the whole image:
    /// `1 / (A cos³θ)`.
    #[inline]
    pub fn pdf_dir(&self, cos_theta: f32) -> f32 {
        if cos_theta <= 0.0 {
            return 0.0;
        }
        1.0 / (self.plane_area * cos_theta * cos_theta * cos_theta)
    }

    /// Connects surface point `p` to the lens point `u_lens` chooses (visibility not tested):
    /// pbrt-v4's `PerspectiveCamera::SampleWi`. The point lands where the ray from that lens
    /// point through `p` crosses the focal plane, seen from the lens centre (the raster
    /// position whose camera ray from that lens point passes through `p`). `None` off the
    /// film or behind the lens.
    #[inline]
    pub fn connect(&self, p: Vec3, u_lens: Vec2) -> Option<CameraConnection> {
        if !self.has_lens() {
            return self.connect_pinhole(p);
        }
        let lens_local = self.lens_point_local(u_lens);
        let lens = self.position + self.frame.to_world(lens_local);
        let to_cam = lens - p;
        let d2 = to_cam.length_squared();
        if d2 <= 0.0 || !d2.is_finite() {
            return None;
        }
        let distance = d2.sqrt();
        let dir_to_camera = to_cam / distance;
        // The direction from the lens point toward p, in the camera frame: it crosses the
        // focal plane at lens + l f / l.z, which the lens centre sees at (that / f).
        let l = self.frame.to_local(-dir_to_camera);
        if l.z <= 0.0 {
            return None;
        }
        let plane = lens_local.truncate() / self.focus_distance + l.truncate() / l.z;
        let raster = self.raster_at(plane)?;
        let cos_cam = l.z;
        // W_e(x, ω) cos / (d² p_A(x)) with W_e(x, ω) = 1 / (A A_lens cos⁴) and p_A = 1 / A_lens.
        let we_geom = self.we(cos_cam) * cos_cam / d2;
        if !we_geom.is_finite() {
            return None;
        }
        Some(CameraConnection {
            raster,
            lens,
            dir_to_camera,
            distance,
            we_geom,
        })
    }

    /// [`Camera::connect`] for the pinhole.
    #[inline]
    fn connect_pinhole(&self, p: Vec3) -> Option<CameraConnection> {
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
            lens: self.position,
            dir_to_camera,
            distance,
            we_geom,
        })
    }
}
