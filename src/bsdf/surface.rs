//! A BSDF at one surface point: the lobes in a shading frame, with the surface's sidedness
//! and the adjoint correction of shading normals; evaluation, density and sampling (the
//! conventions: [`crate::bsdf`]).

use crate::bsdf::blend::Blend;
use crate::bsdf::bump::Bump;
use crate::bsdf::fresnel::fresnel_dielectric;
use crate::bsdf::lobes::{Lobes, LocalSample, SurfaceLobes};
use crate::features::{Features, General};
use crate::math::{Frame, INV_PI, Rgb, safe_sqrt};
use crate::rng::Rng;
use crate::sampling::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use glam::{Vec2, Vec3};

/// Which quantity a path carries: radiance (paths from the camera) or importance (paths
/// from the lights).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TransportMode {
    Radiance,
    Importance,
}

/// A sampled direction.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    /// Sampled direction, world space, unit.
    pub wi: Vec3,
    /// `f(wo, wi)` (for a delta lobe, the delta's coefficient).
    pub f: Rgb,
    /// Density per steradian of `wi` (for a delta lobe, the discrete probability of the lobe).
    pub pdf_w: f32,
    /// `f · |wi·n_s| / pdf_w`, including the importance-mode shading-normal correction.
    pub weight: Rgb,
    /// True when `wi` came from a delta lobe (mirror, smooth glass, the coat of smooth
    /// plastic): a BSDF may mix delta and non-delta lobes, so this is per sample.
    pub delta: bool,
}

/// A BSDF at one surface point: lobes, shading frame and geometric normal.
#[derive(Clone, Copy, Debug)]
pub struct Bsdf {
    pub lobes: Lobes,
    /// Shading frame; `z` is the shading normal on the side of `ng`.
    pub frame: Frame,
    /// Geometric normal, unit.
    pub ng: Vec3,
    /// False: the reflecting kinds are black seen from below the shading normal.
    pub two_sided: bool,
    /// A bump map's tilted normal at this point ([`crate::bsdf::bump`]): the lobes are then
    /// evaluated about it, while `frame` stays the surface's shading frame.
    pub bump: Option<Bump>,
    /// A blend's second component ([`crate::bsdf::blend`]): the BSDF is then
    /// `(1 - w)` times the one `lobes` make plus `w` times this one.
    pub blend: Option<Blend>,
}

impl Bsdf {
    /// A BSDF with shading normal `ns` and geometric normal `ng` (both unit, same side);
    /// `lobes` is a [`SurfaceLobes`] or a bare (two-sided) [`Lobes`].
    pub fn new(lobes: impl Into<SurfaceLobes>, ns: Vec3, ng: Vec3) -> Self {
        let SurfaceLobes { lobes, two_sided } = lobes.into();
        Bsdf {
            lobes,
            frame: Frame::from_z(ns),
            ng,
            two_sided,
            bump: None,
            blend: None,
        }
    }

    /// True when every lobe (of both components of a blend) is a delta distribution.
    pub fn is_delta(&self) -> bool {
        self.lobes.is_delta() && self.blend.is_none_or(|b| b.lobes.is_delta())
    }

    /// The reflectance colour of the lobes ([`Lobes::colour`]), blended as `f` is.
    pub fn colour(&self) -> Rgb {
        match &self.blend {
            Some(b) => self.lobes.colour() * (1.0 - b.weight) + b.lobes.colour() * b.weight,
            None => self.lobes.colour(),
        }
    }

    /// `|wo·n_s| |wi·n_g| / (|wo·n_g| |wi·n_s|)` in importance mode, 1 in radiance mode.
    #[inline]
    pub(super) fn adjoint_correction(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        if mode == TransportMode::Radiance {
            return 1.0;
        }
        let ns = self.frame.z;
        let num = wo.dot(ns).abs() * wi.dot(self.ng).abs();
        let den = wo.dot(self.ng).abs() * wi.dot(ns).abs();
        if den <= 0.0 || !num.is_finite() {
            return 0.0;
        }
        num / den
    }

    /// [`Bsdf::adjoint_correction`] compiled for the effects `F`. Without shading normals the
    /// frame's normal is the geometric one (bit for bit: `surface_hit_with` and the emission
    /// lobe pass `ng` as `ns`), so the general form's numerator and denominator are the same
    /// product `|wo·n_g| |wi·n_g|`, and its quotient is exactly 1 wherever it divides: the
    /// same value, without two of the four dot products and the division.
    #[inline]
    fn adjoint_correction_with<F: Features>(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        if F::SHADING_NORMALS {
            return self.adjoint_correction(wo, wi, mode);
        }
        if mode == TransportMode::Radiance {
            return 1.0;
        }
        debug_assert!(
            self.frame.z.to_array().map(f32::to_bits) == self.ng.to_array().map(f32::to_bits),
            "a shading normal in a loop compiled without them"
        );
        let den = wo.dot(self.ng).abs() * wi.dot(self.ng).abs();
        if den > 0.0 && den.is_finite() {
            1.0
        } else {
            0.0
        }
    }

    /// The side the reflecting kinds work on for `wo`: -1 when a two-sided surface is seen
    /// from below its shading normal (the local frame is flipped), else 1: Mitsuba 3's
    /// `twosided`, which flips where `cos θ_i < 0` in the shading frame.
    #[inline]
    pub(super) fn reflection_side(&self, wo: Vec3) -> f32 {
        if self.two_sided && wo.dot(self.frame.z) < 0.0 {
            -1.0
        } else {
            1.0
        }
    }

    /// Local directions of a reflection, flipped to the upper side on two-sided surfaces.
    /// Returns `None` when `wo` and `wi` are not both above the (flipped) shading horizon.
    /// The geometric normal is not consulted, as in Mitsuba 3, which evaluates every BSDF in
    /// the shading frame alone: where the shading normal is tilted, a reflection may arrive
    /// from or leave below the geometric plane.
    #[inline]
    fn reflection_local(&self, wo: Vec3, wi: Vec3) -> Option<(Vec3, Vec3)> {
        let side = self.reflection_side(wo);
        let mut lo = self.frame.to_local(wo);
        let mut li = self.frame.to_local(wi);
        lo.z *= side;
        li.z *= side;
        if lo.z <= 0.0 || li.z <= 0.0 {
            return None;
        }
        Some((lo, li))
    }

    /// The numbers [`Bsdf::sample`] reads, drawn from `rng` in a fixed order: the direction's
    /// pair first, then the lobe's number only where the BSDF has a choice of lobes (0
    /// otherwise, unread). A Lambertian vertex thus draws two numbers, and its direction keeps
    /// the same dimensions of the sequence whatever the other vertices' materials.
    #[inline]
    pub fn draw_numbers(&self, rng: &mut Rng) -> (f32, Vec2) {
        let u = rng.uniform2();
        let u_lobe = if self.lobes.chooses_a_lobe() || self.blend.is_some() {
            rng.uniform()
        } else {
            0.0
        };
        (u_lobe, u)
    }

    /// The bump at this point, compiled for the effects `F`: a bump map is a texture, so a
    /// loop compiled without textures has none (and pays nothing for them).
    #[inline(always)]
    fn bump_with<F: Features>(&self) -> Option<&Bump> {
        if F::TEXTURES {
            self.bump.as_ref()
        } else {
            None
        }
    }

    /// True when every lobe is a delta distribution, compiled for the effects `F` (false
    /// without specular surfaces).
    #[inline]
    pub fn is_delta_with<F: Features>(&self) -> bool {
        F::SPECULAR && self.is_delta()
    }

    /// The Lambertian fast path's cosines: `(lo.z, li.z)` of [`Bsdf::reflection_local`],
    /// each the same dot product the frame transform makes, without the tangential parts
    /// the Lambertian lobe does not read.
    #[inline]
    fn lambert_cosines(&self, wo: Vec3, wi: Vec3) -> Option<(f32, f32)> {
        let side = self.reflection_side(wo);
        let (lo, li) = (wo.dot(self.frame.z) * side, wi.dot(self.frame.z) * side);
        if lo <= 0.0 || li <= 0.0 {
            return None;
        }
        Some((lo, li))
    }

    /// `f(wo, wi)`; zero for delta lobes.
    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        self.eval_with::<General>(wo, wi, mode)
    }

    /// [`Bsdf::eval`] compiled for the effects `F`.
    #[inline]
    pub fn eval_with<F: Features>(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        if let Some(b) = &self.blend {
            return self.eval_blend(b, wo, wi, mode);
        }
        if let Some(bump) = self.bump_with::<F>() {
            return self.eval_bumped(bump, wo, wi, mode);
        }
        if F::LAMBERTIAN {
            if let Lobes::Diffuse { kd } = self.lobes {
                return match self.lambert_cosines(wo, wi) {
                    Some(_) => kd * INV_PI * self.adjoint_correction_with::<F>(wo, wi, mode),
                    None => Rgb::ZERO,
                };
            }
        }
        if self.is_delta_with::<F>() {
            return Rgb::ZERO;
        }
        if self.lobes.scatters_both_sides() {
            let (lo, li) = (self.frame.to_local(wo), self.frame.to_local(wi));
            return self.lobes.eval_both_sides(lo, li, mode)
                * self.adjoint_correction_with::<F>(wo, wi, mode);
        }
        let f = match self.reflection_local(wo, wi) {
            Some((lo, li)) => self.lobes.eval_local(lo, li),
            None => return Rgb::ZERO,
        };
        f * self.adjoint_correction_with::<F>(wo, wi, mode)
    }

    /// `f(wo, wi)` ([`Bsdf::eval_with`]) and, where it comes at no extra cost, the density
    /// [`Bsdf::pdf_with`] of `wi`: the Lambertian fast path reads both from one set of
    /// cosines (the very values the two calls compute); elsewhere the density is left to be
    /// computed where it is needed (`None`). Always inlined: without the fast path it is
    /// [`Bsdf::eval_with`] itself.
    #[inline(always)]
    pub fn eval_and_lambert_pdf_with<F: Features>(
        &self,
        wo: Vec3,
        wi: Vec3,
        mode: TransportMode,
    ) -> (Rgb, Option<f32>) {
        if F::LAMBERTIAN && self.bump_with::<F>().is_none() && self.blend.is_none() {
            if let Lobes::Diffuse { kd } = self.lobes {
                return match self.lambert_cosines(wo, wi) {
                    Some((_, li)) => (
                        kd * INV_PI * self.adjoint_correction_with::<F>(wo, wi, mode),
                        Some(cosine_hemisphere_pdf(li)),
                    ),
                    None => (Rgb::ZERO, Some(0.0)),
                };
            }
        }
        (self.eval_with::<F>(wo, wi, mode), None)
    }

    /// Density per steradian with which [`Bsdf::sample`] returns `wi` from its non-delta
    /// lobes (times their probability); zero for delta lobes.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.pdf_with::<General>(wo, wi)
    }

    /// [`Bsdf::pdf`] compiled for the effects `F`.
    #[inline]
    pub fn pdf_with<F: Features>(&self, wo: Vec3, wi: Vec3) -> f32 {
        if let Some(b) = &self.blend {
            return self.pdf_blend(b, wo, wi);
        }
        if let Some(bump) = self.bump_with::<F>() {
            return self.pdf_bumped(bump, wo, wi);
        }
        if F::LAMBERTIAN {
            if let Lobes::Diffuse { .. } = self.lobes {
                return match self.lambert_cosines(wo, wi) {
                    Some((_, li)) => cosine_hemisphere_pdf(li),
                    None => 0.0,
                };
            }
        }
        if self.is_delta_with::<F>() {
            return 0.0;
        }
        if self.lobes.scatters_both_sides() {
            return self
                .lobes
                .pdf_both_sides(self.frame.to_local(wo), self.frame.to_local(wi));
        }
        match self.reflection_local(wo, wi) {
            Some((lo, li)) => self.lobes.pdf_local(lo, li),
            None => 0.0,
        }
    }

    /// A delta sample in local direction `li` (already flipped by `side`) of coefficient
    /// `weight` (`f · cos / prob`) and discrete probability `prob`.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn delta_sample(
        &self,
        wo: Vec3,
        li: Vec3,
        side: f32,
        weight: Rgb,
        prob: f32,
        mode: TransportMode,
        transmitted: bool,
    ) -> Option<BsdfSample> {
        let wi = self.frame.to_world(Vec3::new(li.x, li.y, li.z * side));
        // The shading frame alone decides, as in Mitsuba 3: a reflection may leave below the
        // geometric plane where the shading normal is tilted, and glass keeps the direction
        // its shading frame gives on either side (near a smooth mesh's silhouette). Only a
        // thin sheet's straight transmission must cross the surface.
        let crosses = wi.dot(self.ng) * wo.dot(self.ng);
        let glass = matches!(self.lobes, Lobes::Glass { .. });
        if !glass && transmitted && crosses >= 0.0 {
            return None;
        }
        let corr = self.adjoint_correction(wo, wi, mode);
        Some(BsdfSample {
            wi,
            f: weight * (prob * corr / li.z.abs()),
            pdf_w: prob,
            weight: weight * corr,
            delta: true,
        })
    }

    /// True for a thin dielectric sheet: light passes it in a straight line, so a
    /// connection may cross it ([`Bsdf::pass_through`]).
    #[inline]
    pub fn is_thin(&self) -> bool {
        matches!(self.lobes, Lobes::ThinGlass { .. })
    }

    /// What a thin dielectric sheet lets through along `-wo` (arriving from `wo`): the
    /// straight transmission's weight times the probability [`Bsdf::sample`] gives it,
    /// `(1 - R') · Tf` with `R' = 2R / (1 + R)` the sheet's reflectance (its inner
    /// reflections summed). The expectation of sampling at the sheet, taken exactly: a
    /// connection through the sheet multiplies by it. Zero where the sampling would refuse
    /// (the shading normal on the other side), and for every other kind of surface.
    #[inline]
    pub fn pass_through(&self, wo: Vec3) -> Rgb {
        let Lobes::ThinGlass { eta, tf, .. } = self.lobes else {
            return Rgb::ZERO;
        };
        let side = if wo.dot(self.ng) >= 0.0 { 1.0 } else { -1.0 };
        let cos = self.frame.to_local(wo).z * side;
        if cos <= 0.0 {
            return Rgb::ZERO;
        }
        let r = fresnel_dielectric(cos, eta);
        let r = if r < 1.0 { 2.0 * r / (1.0 + r) } else { 1.0 };
        tf * (1.0 - r)
    }

    /// Samples `wi` given `wo`, with one number to choose a lobe and two for the direction.
    pub fn sample(
        &self,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample> {
        self.sample_with::<General>(wo, u_lobe, u, mode)
    }

    /// [`Bsdf::sample`] compiled for the effects `F`: the Lambertian fast path evaluates
    /// `f` and the pdf from one set of cosines (the same operations as the general path).
    #[inline]
    pub fn sample_with<F: Features>(
        &self,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample> {
        if let Some(b) = &self.blend {
            return self.sample_blend(b, wo, u_lobe, u, mode);
        }
        if let Some(bump) = self.bump_with::<F>() {
            return self.sample_bumped(bump, wo, u_lobe, u, mode);
        }
        if F::LAMBERTIAN {
            if let Lobes::Diffuse { kd } = self.lobes {
                let side = self.reflection_side(wo);
                if wo.dot(self.frame.z) * side <= 0.0 {
                    return None;
                }
                let li = sample_cosine_hemisphere(u);
                if li.z <= 0.0 {
                    return None;
                }
                let wi = self.frame.to_world(Vec3::new(li.x, li.y, li.z * side));
                let (_, cos_i) = self.lambert_cosines(wo, wi)?;
                let pdf_w = cosine_hemisphere_pdf(cos_i);
                let f = kd * INV_PI * self.adjoint_correction_with::<F>(wo, wi, mode);
                if pdf_w <= 0.0 || !pdf_w.is_finite() || f.max_element() <= 0.0 {
                    return None;
                }
                let weight = f * (wi.dot(self.frame.z).abs() / pdf_w);
                return Some(BsdfSample {
                    wi,
                    f,
                    pdf_w,
                    weight,
                    delta: false,
                });
            }
        }
        self.sample_general(wo, u_lobe, u, mode)
    }

    fn sample_general(
        &self,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample> {
        if self.lobes.scatters_both_sides() {
            // Both sides in the shading frame, as Mitsuba's `roughdielectric` and
            // `principled` (their cos θ_i): no flip, and the direction stands on either side
            // of the geometric normal.
            let li = self
                .lobes
                .sample_both_sides(self.frame.to_local(wo), u_lobe, u)?;
            return self.non_delta_sample(wo, self.frame.to_world(li), mode);
        }
        // The frame is flipped to wo's side for the transmitting kinds and for two-sided
        // reflection; a one-sided surface seen from below scatters nothing.
        let side = if let Lobes::Glass { .. } = self.lobes {
            // Mitsuba's `dielectric`: wo's side of the shading normal (its cos θ_i) says
            // whether the path enters or leaves, whichever side of the geometric normal wo
            // is on.
            if wo.dot(self.frame.z) >= 0.0 {
                1.0
            } else {
                -1.0
            }
        } else if self.lobes.transmits() {
            if wo.dot(self.ng) >= 0.0 { 1.0 } else { -1.0 }
        } else {
            self.reflection_side(wo)
        };
        let mut lo = self.frame.to_local(wo);
        lo.z *= side;
        if lo.z <= 0.0 {
            return None;
        }
        let li = match self.lobes {
            Lobes::ThinGlass { eta, ks, tf } => {
                // Reflectance with the sheet's inner reflections summed: R + T²R/(1 - R²).
                let mirror = Vec3::new(-lo.x, -lo.y, lo.z);
                let r = fresnel_dielectric(lo.z, eta);
                let r = if r < 1.0 { 2.0 * r / (1.0 + r) } else { 1.0 };
                return if u_lobe < r {
                    self.delta_sample(wo, mirror, side, ks, r, mode, false)
                } else {
                    self.delta_sample(wo, -lo, side, tf, 1.0 - r, mode, true)
                };
            }
            Lobes::Glass { eta, tf_sqrt } => {
                return self.sample_glass(wo, lo, side, eta, tf_sqrt, u_lobe, mode);
            }
            _ => match self.lobes.sample_reflection_local(lo, u_lobe, u)? {
                LocalSample::Smooth(li) => li,
                LocalSample::Delta { li, weight, prob } => {
                    return self.delta_sample(wo, li, side, weight, prob, mode, false);
                }
            },
        };
        if li.z <= 0.0 {
            return None;
        }
        let wi = self.frame.to_world(Vec3::new(li.x, li.y, li.z * side));
        self.non_delta_sample(wo, wi, mode)
    }

    /// The sample of a non-delta lobe in direction `wi`: `f` and the density from `eval` and
    /// `pdf` (so that the three agree exactly); `None` where either is not positive.
    #[inline]
    fn non_delta_sample(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Option<BsdfSample> {
        let pdf_w = self.pdf(wo, wi);
        let f = self.eval(wo, wi, mode);
        if pdf_w <= 0.0 || !pdf_w.is_finite() || f.max_element() <= 0.0 {
            return None;
        }
        let weight = f * (wi.dot(self.frame.z).abs() / pdf_w);
        if !weight.is_finite() {
            return None;
        }
        Some(BsdfSample {
            wi,
            f,
            pdf_w,
            weight,
            delta: false,
        })
    }

    /// The smooth dielectric: Fresnel reflection or refraction, `lo` on the incident side.
    #[allow(clippy::too_many_arguments)]
    fn sample_glass(
        &self,
        wo: Vec3,
        lo: Vec3,
        side: f32,
        eta: f32,
        tf_sqrt: Rgb,
        u_lobe: f32,
        mode: TransportMode,
    ) -> Option<BsdfSample> {
        // Entering when wo is on the side the shading normal points to.
        let entering = side > 0.0;
        let eta_rel = if entering { eta } else { 1.0 / eta };
        let fr = fresnel_dielectric(lo.z, eta_rel);
        if u_lobe < fr {
            let li = Vec3::new(-lo.x, -lo.y, lo.z);
            return self.delta_sample(wo, li, side, Rgb::ONE, fr, mode, false);
        }
        // Refraction about the local normal (+z), incident direction -lo.
        let cos_i = lo.z;
        let sin2_t = (1.0 - cos_i * cos_i) / (eta_rel * eta_rel);
        if sin2_t >= 1.0 {
            return None; // fr = 1 here; unreachable in exact arithmetic
        }
        let cos_t = safe_sqrt(1.0 - sin2_t);
        let li = (-lo / eta_rel + Vec3::new(0.0, 0.0, cos_i / eta_rel - cos_t)).normalize();
        let radiance_scale = if mode == TransportMode::Radiance {
            1.0 / (eta_rel * eta_rel)
        } else {
            1.0
        };
        self.delta_sample(wo, li, side, tf_sqrt * radiance_scale, 1.0 - fr, mode, true)
    }
}
