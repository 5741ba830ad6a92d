//! Mitsuba's `blendbsdf`: a linear blend of two BSDFs at a point,
//!
//! `f = (1 - w) f₀ + w f₁`, `p = (1 - w) p₀ + w p₁`,
//!
//! `w` the blend weight there (a number, or a texture's luminance as Mitsuba's `eval_1`,
//! clamped to [0, 1]). Sampling picks component 1 with probability `w` (the lobe number
//! `u_lobe < w`, rescaled for the component's own choice of lobe), samples it, and reports
//! the blend's `f` and density of the direction, as Mitsuba 3.9's `BlendBSDF::sample` does: a
//! direction from a non-delta lobe carries `f cos / p` of the whole blend, one from a delta
//! lobe its lobe's weight with the probability of having picked that component
//! (the other component's density there is zero).
//!
//! The first component is the [`Bsdf`]'s own lobes and sidedness; the second is a
//! [`Blend`]. Both share the shading frame, the geometric normal and a bump map around the
//! blend; the adjoint correction of shading normals is the surface's, so it applies to the
//! blend as to each component. Blends of dielectrics are not read (a blend is a reflecting
//! BSDF here), which keeps thin-sheet and refraction rules out of it.

use crate::bsdf::lobes::Lobes;
use crate::bsdf::surface::{Bsdf, BsdfSample, TransportMode};
use crate::math::Rgb;
use glam::{Vec2, Vec3};

/// The second component of a blend at a point, and its weight.
#[derive(Clone, Copy, Debug)]
pub struct Blend {
    /// `w`: the share of the second component, in [0, 1].
    pub weight: f32,
    pub lobes: Lobes,
    /// The second component's sidedness (the first's is the surface's).
    pub two_sided: bool,
}

impl Bsdf {
    /// The blend's component `second` (else the first) as a BSDF of its own at this point.
    #[inline]
    pub(super) fn component(&self, blend: &Blend, second: bool) -> Bsdf {
        let mut c = *self;
        c.blend = None;
        if second {
            c.lobes = blend.lobes;
            c.two_sided = blend.two_sided;
        }
        c
    }

    /// `(1 - w) f₀ + w f₁`.
    pub(super) fn eval_blend(&self, b: &Blend, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        let f0 = self.component(b, false).eval(wo, wi, mode);
        let f1 = self.component(b, true).eval(wo, wi, mode);
        f0 * (1.0 - b.weight) + f1 * b.weight
    }

    /// `(1 - w) p₀ + w p₁`.
    pub(super) fn pdf_blend(&self, b: &Blend, wo: Vec3, wi: Vec3) -> f32 {
        let p0 = self.component(b, false).pdf(wo, wi);
        let p1 = self.component(b, true).pdf(wo, wi);
        p0 * (1.0 - b.weight) + p1 * b.weight
    }

    /// Component 1 with probability `w` (from `u_lobe`, rescaled), its direction with the
    /// blend's `f` and density.
    pub(super) fn sample_blend(
        &self,
        b: &Blend,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample> {
        let w = b.weight;
        let second = u_lobe < w;
        let (p_pick, u_rest) = if second {
            (w, u_lobe / w)
        } else {
            (1.0 - w, (u_lobe - w) / (1.0 - w))
        };
        if p_pick <= 0.0 {
            return None;
        }
        let s =
            self.component(b, second)
                .sample(wo, u_rest.clamp(0.0, 1.0 - f32::EPSILON), u, mode)?;
        if s.delta {
            // The other component has no delta lobe in this direction: the blend's weight is
            // the lobe's, its probability the lobe's times that of the pick.
            return Some(BsdfSample {
                pdf_w: s.pdf_w * p_pick,
                f: s.f * p_pick,
                ..s
            });
        }
        let pdf_w = self.pdf_blend(b, wo, s.wi);
        let f = self.eval_blend(b, wo, s.wi, mode);
        if pdf_w <= 0.0 || !pdf_w.is_finite() || f.max_element() <= 0.0 {
            return None;
        }
        // The adjoint correction is inside each component's `f`; the cosine is the surface's.
        let weight = f * (s.wi.dot(self.frame.z).abs() / pdf_w);
        if !weight.is_finite() {
            return None;
        }
        Some(BsdfSample {
            wi: s.wi,
            f,
            pdf_w,
            weight,
            delta: false,
        })
    }
}
