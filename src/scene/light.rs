//! Lights: emissive triangles (area lights), spot lights with inner/outer cone angles, point
//! lights, a directional light (Mitsuba's `directional`), and an environment, uniform
//! (Mitsuba's `constant`) or from an image (Mitsuba's `envmap`, [`EnvMap`]). Each light
//! offers what the two kinds of paths need:
//!
//! * `sample_li`: a point on the light seen from a shading point (next-event estimation),
//!   with its density per steradian at the shading point;
//! * `sample_le`: an emitted ray (light tracing and the photon pass), with its positional
//!   density per area and directional density per steradian (`pdf_le_dir`); spot lights emit
//!   in proportion to their falloff, so every photon of a light carries the same flux;
//! * `power`: the emitted flux, by which lights are chosen.
//!
//! The directional light and the environment are at infinity: they are seen along
//! directions, not at points, and a shadow ray of twice the scene's bounding radius stands
//! for "to infinity". Their emitted rays start on the disk of the scene's bounding sphere
//! (radius `r`) perpendicular to the emitted direction, so `pdf_pos = 1 / (π r²)` is per unit
//! area of that disk (pbrt-v4's `DistantLight::SampleLe`, `UniformInfiniteLight::SampleLe`
//! and `ImageInfiniteLight::SampleLe`; pbrt-v4 §12.3, "Distant Lights", and §12.5, "Infinite
//! Area Lights"):
//!
//! * the directional light is a delta in direction: next-event estimation reaches it along
//!   one direction with `pdf_w = 1` (as point lights), an emitted ray has `pdf_dir = 1`, and
//!   its flux is `E π r²` for irradiance `E`; nothing hits it, and the camera does not see it;
//! * the environment's directions are sampled uniformly (uniform radiance) or in proportion to
//!   the map's radiance times `sin θ` ([`EnvMap`]), for next-event estimation and emission
//!   alike; rays that leave the scene see it, and its flux is `π r² ∫ L dω` (`π r² · 4π · L`
//!   when uniform).

use crate::math::{Frame, PI, Rgb, luminance};
use crate::sampling::{
    cosine_hemisphere_pdf, sample_cosine_hemisphere, sample_uniform_sphere,
    sample_uniform_triangle, uniform_sphere_pdf,
};
use crate::scene::envmap::EnvMap;
use crate::scene::geometry::TriangleGeom;
use glam::{Vec2, Vec3};
use std::sync::Arc;

#[derive(Clone, Debug)]
pub enum Light {
    /// One emissive triangle, emitting radiance `le` from the side its winding normal faces.
    Area {
        triangle: u32,
        geom: TriangleGeom,
        /// Unit normal of the emitting side.
        n: Vec3,
        area: f32,
        le: Rgb,
    },
    /// Isotropic point light of intensity `intensity` (W/sr).
    Point { position: Vec3, intensity: Rgb },
    /// Spot light: intensity `intensity` on its axis, full inside `cos_inner`, falling off
    /// to zero at `cos_outer` along `profile`.
    Spot {
        position: Vec3,
        frame: Frame,
        intensity: Rgb,
        cos_inner: f32,
        cos_outer: f32,
        profile: SpotProfile,
    },
    /// Parallel light travelling along the unit `dir`, of irradiance `irradiance` (W/m²) on
    /// a surface facing it. `center` and `radius` bound the scene (set by `Scene::new`).
    Directional {
        dir: Vec3,
        irradiance: Rgb,
        center: Vec3,
        radius: f32,
    },
    /// Radiance arriving from every direction: `le` uniformly, or `le` times the map's value
    /// where there is a `map`. `center` and `radius` bound the scene (set by `Scene::new`).
    Environment {
        le: Rgb,
        map: Option<Arc<EnvMap>>,
        center: Vec3,
        radius: f32,
    },
}

/// How a spot light falls off between its inner and outer cone.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpotProfile {
    /// Smoothstep in cos θ, as pbrt-v4's `SpotLight` (footprint's own scenes).
    Smoothstep,
    /// Linear in the angle θ, as Mitsuba 3's `spot` (`beam_width` to `cutoff_angle`).
    LinearAngle,
}

/// A point on a light sampled from a shading point.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Point on the light.
    pub p: Vec3,
    /// Unit direction from the shading point to the light.
    pub wi: Vec3,
    pub distance: f32,
    /// Radiance arriving along `-wi` (area) or intensity / d² (delta lights).
    pub li: Rgb,
    /// Density per steradian at the shading point (1 for delta lights), excluding the
    /// choice of the light.
    pub pdf_w: f32,
    /// Normal of the light surface (area lights), for offsetting the shadow ray's end.
    pub n: Option<Vec3>,
    pub delta: bool,
}

/// An emitted ray.
#[derive(Clone, Copy, Debug)]
pub struct LightEmission {
    pub p: Vec3,
    pub n: Option<Vec3>,
    pub dir: Vec3,
    /// Emitted radiance (area) or intensity (delta) along `dir`.
    pub le: Rgb,
    /// Density of `p` per unit area (1 for delta positions).
    pub pdf_pos: f32,
    /// Density of `dir` per steradian.
    pub pdf_dir: f32,
    /// Cosine at the emitting surface (1 for point and spot lights).
    pub cos_light: f32,
}

#[inline]
fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    if a == b {
        return if x < a { 0.0 } else { 1.0 };
    }
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl Light {
    /// Point and spot lights (a single position) and the directional light (a single
    /// direction): reachable only by connection.
    pub fn is_delta(&self) -> bool {
        matches!(
            self,
            Light::Point { .. } | Light::Spot { .. } | Light::Directional { .. }
        )
    }

    pub fn is_environment(&self) -> bool {
        matches!(self, Light::Environment { .. })
    }

    /// The directional light and the environment: at infinity, their emitted rays start on
    /// the scene's bounding disk, which no camera sees.
    pub fn is_infinite(&self) -> bool {
        matches!(self, Light::Directional { .. } | Light::Environment { .. })
    }

    /// A uniform environment of radiance `le` (Mitsuba's `constant`).
    pub fn uniform_environment(le: Rgb) -> Self {
        Light::Environment {
            le,
            map: None,
            center: Vec3::ZERO,
            radius: 1.0,
        }
    }

    /// A directional light travelling along `dir` (normalised here) with irradiance
    /// `irradiance`; `None` for a zero or non-finite direction.
    pub fn directional(dir: Vec3, irradiance: Rgb) -> Option<Self> {
        Some(Light::Directional {
            dir: dir.try_normalize()?,
            irradiance,
            center: Vec3::ZERO,
            radius: 1.0,
        })
    }

    /// Density per steradian with which the environment's next-event estimation and emission
    /// sample the direction `toward` (unit, pointing at the environment); 0 for other lights.
    #[inline]
    pub fn pdf_environment(&self, toward: Vec3) -> f32 {
        match self {
            Light::Environment { map: None, .. } => uniform_sphere_pdf(),
            Light::Environment { map: Some(m), .. } => m.pdf(toward),
            _ => 0.0,
        }
    }

    /// Density per unit area of the emitted rays' origins on the bounding disk (lights at
    /// infinity), or `None` for lights at finite positions.
    #[inline]
    pub fn disk_pdf(&self) -> Option<f32> {
        match self {
            Light::Directional { radius, .. } | Light::Environment { radius, .. } => {
                Some(1.0 / (PI * radius * radius))
            }
            _ => None,
        }
    }

    /// Emitted flux (RGB, W).
    pub fn power_rgb(&self) -> Rgb {
        match self {
            Light::Area { area, le, .. } => *le * (PI * *area),
            Light::Point { intensity, .. } => *intensity * (4.0 * PI),
            Light::Environment {
                le,
                map: None,
                radius,
                ..
            } => *le * (4.0 * PI * PI * radius * radius),
            Light::Environment {
                le,
                map: Some(m),
                radius,
                ..
            } => *le * m.integral() * (PI * radius * radius),
            Light::Directional {
                irradiance, radius, ..
            } => *irradiance * (PI * radius * radius),
            Light::Spot {
                intensity,
                cos_inner,
                cos_outer,
                profile,
                ..
            } => *intensity * (2.0 * PI * Self::spot_mass(*cos_inner, *cos_outer, *profile)),
        }
    }

    /// A spot light with Mitsuba 3's profile: full within `beam` radians of the axis `dir`,
    /// falling linearly in angle to zero at `cutoff`.
    pub fn spot_linear_angle(
        position: Vec3,
        dir: Vec3,
        intensity: Rgb,
        beam: f32,
        cutoff: f32,
    ) -> Self {
        Light::Spot {
            position,
            frame: Frame::from_z(dir),
            intensity,
            cos_inner: beam.cos(),
            cos_outer: cutoff.cos(),
            profile: SpotProfile::LinearAngle,
        }
    }

    /// Luminance of the emitted flux: what lights are chosen by.
    pub fn power(&self) -> f32 {
        luminance(self.power_rgb())
    }

    /// Spot falloff for a direction with cosine `cos_t` to the axis.
    #[inline]
    fn spot_falloff(cos_t: f32, cos_inner: f32, cos_outer: f32, profile: SpotProfile) -> f32 {
        match profile {
            SpotProfile::Smoothstep => smoothstep(cos_outer, cos_inner, cos_t),
            SpotProfile::LinearAngle => {
                if cos_t >= cos_inner {
                    1.0
                } else if cos_t <= cos_outer {
                    0.0
                } else {
                    let (ti, to) = (cos_inner.acos(), cos_outer.acos());
                    ((to - cos_t.clamp(-1.0, 1.0).acos()) / (to - ti)).clamp(0.0, 1.0)
                }
            }
        }
    }

    /// `∫ falloff d(cos θ)` over `[-1, 1]`: the cap `1 - cos_inner` plus the ring's share.
    fn spot_mass(cos_inner: f32, cos_outer: f32, profile: SpotProfile) -> f32 {
        (1.0 - cos_inner) + Self::spot_ring_mass(cos_inner, cos_outer, profile)
    }

    /// `∫ falloff d(cos θ)` over the ring between the cones. Smoothstep: half the ring (exact
    /// for a smoothstep in cos θ). Linear in angle, with `t_i`, `t_o` the cone angles:
    /// `∫_{t_i}^{t_o} (t_o - t)/(t_o - t_i) sin t dt
    ///   = ((t_o - t_i) cos t_i + sin t_i - sin t_o) / (t_o - t_i)`.
    fn spot_ring_mass(cos_inner: f32, cos_outer: f32, profile: SpotProfile) -> f32 {
        match profile {
            SpotProfile::Smoothstep => 0.5 * (cos_inner - cos_outer),
            SpotProfile::LinearAngle => {
                let (ti, to) = (cos_inner.acos() as f64, cos_outer.acos() as f64);
                if to - ti <= 1e-9 {
                    return 0.0;
                }
                (((to - ti) * ti.cos() + ti.sin() - to.sin()) / (to - ti)) as f32
            }
        }
    }

    /// Radiance (area, environment) or intensity (point, spot) leaving the light toward unit
    /// `dir`; the directional light's irradiance. The environment's light toward `dir` comes
    /// from the direction `-dir`.
    #[inline]
    pub fn emitted(&self, dir: Vec3) -> Rgb {
        match self {
            Light::Area { n, le, .. } => {
                if dir.dot(*n) > 0.0 {
                    *le
                } else {
                    Rgb::ZERO
                }
            }
            Light::Point { intensity, .. } => *intensity,
            Light::Environment { le, map: None, .. } => *le,
            Light::Environment {
                le, map: Some(m), ..
            } => *le * m.eval(-dir),
            Light::Directional { irradiance, .. } => *irradiance,
            Light::Spot {
                frame,
                intensity,
                cos_inner,
                cos_outer,
                profile,
                ..
            } => {
                *intensity * Self::spot_falloff(dir.dot(frame.z), *cos_inner, *cos_outer, *profile)
            }
        }
    }

    /// Samples a point on the light as seen from `p_ref`.
    pub fn sample_li(&self, p_ref: Vec3, u: Vec2) -> Option<LightSample> {
        match self {
            Light::Area {
                geom, n, area, le, ..
            } => {
                let (b1, b2) = sample_uniform_triangle(u);
                let p = geom.point(b1, b2);
                let d = p - p_ref;
                let dist2 = d.length_squared();
                if dist2 <= 0.0 {
                    return None;
                }
                let distance = dist2.sqrt();
                let wi = d / distance;
                let cos_l = -wi.dot(*n);
                if cos_l <= 0.0 {
                    return None;
                }
                let pdf_w = dist2 / (cos_l * *area);
                if !pdf_w.is_finite() {
                    return None;
                }
                Some(LightSample {
                    p,
                    wi,
                    distance,
                    li: *le,
                    pdf_w,
                    n: Some(*n),
                    delta: false,
                })
            }
            Light::Point {
                position,
                intensity,
            } => {
                let d = *position - p_ref;
                let dist2 = d.length_squared();
                if dist2 <= 0.0 {
                    return None;
                }
                let distance = dist2.sqrt();
                Some(LightSample {
                    p: *position,
                    wi: d / distance,
                    distance,
                    li: *intensity / dist2,
                    pdf_w: 1.0,
                    n: None,
                    delta: true,
                })
            }
            Light::Environment {
                le,
                map: Some(m),
                radius,
                ..
            } => {
                let (wi, pdf_w, l) = m.sample(u)?;
                let distance = 2.0 * *radius;
                Some(LightSample {
                    p: p_ref + wi * distance,
                    wi,
                    distance,
                    li: *le * l,
                    pdf_w,
                    n: None,
                    delta: false,
                })
            }
            Light::Directional {
                dir,
                irradiance,
                radius,
                ..
            } => {
                let distance = 2.0 * *radius;
                Some(LightSample {
                    p: p_ref - *dir * distance,
                    wi: -*dir,
                    distance,
                    li: *irradiance,
                    pdf_w: 1.0,
                    n: None,
                    delta: true,
                })
            }
            Light::Environment {
                le,
                map: None,
                radius,
                ..
            } => {
                let wi = sample_uniform_sphere(u);
                let distance = 2.0 * *radius;
                Some(LightSample {
                    p: p_ref + wi * distance,
                    wi,
                    distance,
                    li: *le,
                    pdf_w: uniform_sphere_pdf(),
                    n: None,
                    delta: false,
                })
            }
            Light::Spot { position, .. } => {
                let d = *position - p_ref;
                let dist2 = d.length_squared();
                if dist2 <= 0.0 {
                    return None;
                }
                let distance = dist2.sqrt();
                let wi = d / distance;
                let i = self.emitted(-wi);
                if i.max_element() <= 0.0 {
                    return None;
                }
                Some(LightSample {
                    p: *position,
                    wi,
                    distance,
                    li: i / dist2,
                    pdf_w: 1.0,
                    n: None,
                    delta: true,
                })
            }
        }
    }

    /// Density per steradian at `p_ref` with which [`Light::sample_li`] returns the point
    /// `p_light` (area lights and the environment; zero for delta lights).
    pub fn pdf_li(&self, p_ref: Vec3, p_light: Vec3) -> f32 {
        match self {
            Light::Area { n, area, .. } => {
                let d = p_light - p_ref;
                let dist2 = d.length_squared();
                let cos_l = (-d).dot(*n) / dist2.sqrt();
                if cos_l <= 0.0 || dist2 <= 0.0 {
                    return 0.0;
                }
                dist2 / (cos_l * *area)
            }
            Light::Environment { map: None, .. } => uniform_sphere_pdf(),
            Light::Environment { .. } => self.pdf_environment((p_light - p_ref).normalize()),
            _ => 0.0,
        }
    }

    /// Samples an emitted ray: area lights uniformly in area and cosine-weighted in
    /// direction; point lights uniformly on the sphere; spot lights in proportion to their
    /// falloff; the environment in direction as its next-event estimation samples it, the
    /// directional light along its direction, both from the bounding disk facing the
    /// direction.
    pub fn sample_le(&self, u_pos: Vec2, u_dir: Vec2) -> Option<LightEmission> {
        match self {
            Light::Environment {
                le,
                map: Some(m),
                center,
                radius,
            } => {
                let (toward, pdf_dir, l) = m.sample(u_dir)?;
                let dir = -toward;
                Some(LightEmission {
                    p: Self::disk_point(dir, *center, *radius, u_pos),
                    n: None,
                    dir,
                    le: *le * l,
                    pdf_pos: 1.0 / (PI * radius * radius),
                    pdf_dir,
                    cos_light: 1.0,
                })
            }
            Light::Directional {
                dir,
                irradiance,
                center,
                radius,
            } => Some(LightEmission {
                p: Self::disk_point(*dir, *center, *radius, u_pos),
                n: None,
                dir: *dir,
                le: *irradiance,
                pdf_pos: 1.0 / (PI * radius * radius),
                pdf_dir: 1.0,
                cos_light: 1.0,
            }),
            Light::Environment {
                le,
                map: None,
                center,
                radius,
            } => {
                let dir = sample_uniform_sphere(u_dir);
                Some(LightEmission {
                    p: Self::disk_point(dir, *center, *radius, u_pos),
                    n: None,
                    dir,
                    le: *le,
                    pdf_pos: 1.0 / (PI * radius * radius),
                    pdf_dir: uniform_sphere_pdf(),
                    cos_light: 1.0,
                })
            }
            Light::Area {
                geom, n, area, le, ..
            } => {
                let (b1, b2) = sample_uniform_triangle(u_pos);
                let p = geom.point(b1, b2);
                let local = sample_cosine_hemisphere(u_dir);
                if local.z <= 0.0 {
                    return None;
                }
                let dir = Frame::from_z(*n).to_world(local).normalize();
                Some(LightEmission {
                    p,
                    n: Some(*n),
                    dir,
                    le: *le,
                    pdf_pos: 1.0 / *area,
                    pdf_dir: cosine_hemisphere_pdf(local.z),
                    cos_light: local.z,
                })
            }
            Light::Point {
                position,
                intensity,
            } => Some(LightEmission {
                p: *position,
                n: None,
                dir: sample_uniform_sphere(u_dir),
                le: *intensity,
                pdf_pos: 1.0,
                pdf_dir: uniform_sphere_pdf(),
                cos_light: 1.0,
            }),
            Light::Spot {
                position,
                frame,
                cos_inner,
                cos_outer,
                profile,
                ..
            } => {
                let cos_t = Self::sample_spot_cos(u_dir.x, *cos_inner, *cos_outer, *profile);
                let sin_t = crate::math::safe_sqrt(1.0 - cos_t * cos_t);
                let (sin_phi, cos_phi) = crate::math::sin_cos_turns(u_dir.y);
                let dir = frame
                    .to_world(Vec3::new(sin_t * cos_phi, sin_t * sin_phi, cos_t))
                    .normalize();
                let le = self.emitted(dir);
                let pdf_dir = self.pdf_le_dir(dir);
                if le.max_element() <= 0.0 || pdf_dir <= 0.0 {
                    return None;
                }
                Some(LightEmission {
                    p: *position,
                    n: None,
                    dir,
                    le,
                    pdf_pos: 1.0,
                    pdf_dir,
                    cos_light: 1.0,
                })
            }
        }
    }

    /// A point of the disk of radius `radius` about `center` perpendicular to `dir`, on the
    /// side `dir` leaves from: where rays from infinity along `dir` start.
    #[inline]
    fn disk_point(dir: Vec3, center: Vec3, radius: f32, u: Vec2) -> Vec3 {
        let frame = Frame::from_z(dir);
        let d = crate::sampling::sample_concentric_disk(u) * radius;
        center - dir * radius + frame.x * d.x + frame.y * d.y
    }

    /// Density per steradian with which [`Light::sample_le`] emits `dir` (unit, world); 0 for
    /// the directional light (a delta in direction).
    pub fn pdf_le_dir(&self, dir: Vec3) -> f32 {
        match self {
            Light::Area { n, .. } => cosine_hemisphere_pdf(dir.dot(*n)),
            Light::Point { .. } => uniform_sphere_pdf(),
            Light::Environment { .. } => self.pdf_environment(-dir),
            Light::Directional { .. } => 0.0,
            Light::Spot {
                frame,
                cos_inner,
                cos_outer,
                profile,
                ..
            } => {
                // Proportional to the falloff: falloff / (2π ∫ falloff d(cos θ)).
                let norm = Self::spot_mass(*cos_inner, *cos_outer, *profile);
                Self::spot_falloff(dir.dot(frame.z), *cos_inner, *cos_outer, *profile)
                    / (2.0 * PI * norm)
            }
        }
    }

    /// `cos θ` with density proportional to the spot falloff on `[cos_outer, 1]`: the full
    /// cap `[cos_inner, 1]` with probability equal to its share, else the ring. The
    /// smoothstep ring's normalised cdf in `t = (cos θ - cos_outer)/(cos_inner - cos_outer)`
    /// is `2t³ - t⁴` (inverted by Newton's method); the linear-in-angle ring's cdf in θ (see
    /// [`Light::spot_ring_mass`]) is inverted by bisection. Every photon of a spot light then
    /// carries the same flux.
    fn sample_spot_cos(u: f32, cos_inner: f32, cos_outer: f32, profile: SpotProfile) -> f32 {
        let cap = 1.0 - cos_inner;
        let ring = Self::spot_ring_mass(cos_inner, cos_outer, profile);
        let p_cap = cap / (cap + ring);
        if u < p_cap || ring <= 0.0 {
            let v = if p_cap > 0.0 { (u / p_cap).min(1.0) } else { u };
            return 1.0 - v * cap;
        }
        let v = ((u - p_cap) / (1.0 - p_cap)).clamp(0.0, 1.0);
        if profile == SpotProfile::LinearAngle {
            let (ti, to) = (cos_inner.acos() as f64, cos_outer.acos() as f64);
            // Unnormalised cdf from t_i: [-(t_o - t) cos t - sin t] between t_i and θ.
            let g = |t: f64| -(to - t) * t.cos() - t.sin();
            let total = g(to) - g(ti);
            let target = v as f64 * total + g(ti);
            let (mut lo, mut hi) = (ti, to);
            for _ in 0..40 {
                let mid = 0.5 * (lo + hi);
                if g(mid) < target {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return (0.5 * (lo + hi)).cos() as f32;
        }
        // Solve 2t³ - t⁴ = v on [0, 1]; monotone, derivative 6t² - 4t³ = 2t²(3 - 2t).
        let mut t = v.sqrt().max(1e-3);
        for _ in 0..12 {
            let f = 2.0 * t * t * t - t * t * t * t - v;
            let d = 2.0 * t * t * (3.0 - 2.0 * t);
            if d <= 0.0 {
                break;
            }
            t = (t - f / d).clamp(0.0, 1.0);
        }
        cos_outer + t * (cos_inner - cos_outer)
    }
}
