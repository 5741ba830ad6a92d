//! The rough dielectric interface (Mitsuba 3's `roughdielectric`): microfacet reflection and
//! refraction after Walter, Marschner, Li & Torrance 2007, "Microfacet Models for
//! Refraction through Rough Surfaces", in the local shading frame, on both sides.
//!
//! `wo` (local `lo`) is on the side the path came from; `lo.z > 0` means outside (where the
//! shading normal points), so the relative index across the interface is `η = η_int/η_ext`
//! entering and `1/η` leaving (η_t/η_i of the passage from `lo`'s side). With `F` the Fresnel
//! reflectance of the microfacet, `D` and `G = G1(lo, m) G1(li, m)` from
//! [`crate::bsdf::microfacet`]:
//!
//! * reflection (`lo.z li.z > 0`), half vector `m = (lo + li)/|lo + li|` (eq. 13):
//!   `f_r = k_s F D G / (4 |cos θ_o| |cos θ_i|)` (eq. 20);
//! * refraction, generalised half vector `m ∝ lo + η li` (eq. 16), turned to the macro
//!   normal's side: `f_t = T |(lo·m)(li·m)| η² (1 - F) D G / (|cos θ_o| |cos θ_i|
//!   (lo·m + η li·m)²)` (eq. 21 divided by `η_o²`: the importance form), and in radiance
//!   mode divided by `η²` as well (the solid angle compression, Veach 1997 §5.2; what Walter
//!   et al. leave out), `T` the constant transmittance factor of one crossing;
//! * sampling: a visible normal `m` seen from `lo` (turned to the upper side), reflection
//!   with probability `F(lo·m)`, refraction otherwise, so that the density of `li` is
//!   `D_lo(m) F |∂m/∂li|` with the Jacobians `1 / (4 |li·m|)` (eq. 14) and
//!   `η² |li·m| / (lo·m + η li·m)²` (eq. 17); `1 - F` for refraction.
//!
//! Both sides of both configurations are zero where a direction sees the back of its
//! microfacet (`(v·m)(v·n) <= 0`), in the density as in `G`, as Mitsuba filters them.

use crate::bsdf::fresnel::fresnel_dielectric;
use crate::bsdf::microfacet::MicrofacetDistribution;
use crate::bsdf::surface::TransportMode;
use crate::math::{Rgb, safe_sqrt};
use glam::{Vec2, Vec3};

/// A rough dielectric interface resolved at a point.
#[derive(Clone, Copy, Debug)]
pub struct RoughGlass {
    /// Interior over exterior index of refraction.
    pub eta: f32,
    /// Factor of the reflected light (Mitsuba's `specular_reflectance`).
    pub ks: Rgb,
    /// Factor of the light refracted through one crossing (`specular_transmittance`).
    pub kt: Rgb,
    pub distr: MicrofacetDistribution,
}

/// What `f` and the density of a pair of local directions share: the microfacet normal of
/// the configuration and its terms.
struct Configuration {
    reflect: bool,
    /// `η_t/η_i` for light crossing from `lo`'s side.
    eta: f32,
    m: Vec3,
    lo_m: f32,
    li_m: f32,
    /// Fresnel reflectance at `m` seen from `lo`.
    fresnel: f32,
}

impl RoughGlass {
    /// The relative index crossing from the side of local `lo` to the other one.
    #[inline]
    fn eta_from(&self, lo: Vec3) -> f32 {
        if lo.z > 0.0 { self.eta } else { 1.0 / self.eta }
    }

    /// The microfacet normal of `(lo, li)` and the terms `f` and the density read; `None`
    /// where neither can be positive (grazing `lo`, a degenerate half vector, a direction
    /// seeing its facet from behind).
    #[inline]
    fn configuration(&self, lo: Vec3, li: Vec3) -> Option<Configuration> {
        if lo.z == 0.0 || li.z == 0.0 {
            return None;
        }
        let reflect = lo.z * li.z > 0.0;
        let eta = self.eta_from(lo);
        let h = if reflect { lo + li } else { lo + eta * li };
        let len = h.length();
        if !(len > 0.0 && len.is_finite()) {
            return None;
        }
        // Walter et al. eq. 16's half vector, turned to the macro normal's side.
        let m = if h.z < 0.0 { -h / len } else { h / len };
        let (lo_m, li_m) = (lo.dot(m), li.dot(m));
        if lo_m * lo.z <= 0.0 || li_m * li.z <= 0.0 {
            return None;
        }
        Some(Configuration {
            reflect,
            eta,
            m,
            lo_m,
            li_m,
            fresnel: fresnel_dielectric(lo_m.abs(), eta),
        })
    }

    /// `f(lo, li)` (no cosine) in the local frame, `lo` and `li` on either side.
    pub fn eval(&self, lo: Vec3, li: Vec3, mode: TransportMode) -> Rgb {
        let Some(c) = self.configuration(lo, li) else {
            return Rgb::ZERO;
        };
        let d = self.distr.d(c.m);
        if d == 0.0 {
            return Rgb::ZERO;
        }
        let g = self.distr.g1_front(lo) * self.distr.g1_front(li);
        let cos_cos = (lo.z * li.z).abs();
        if c.reflect {
            return self.ks * (c.fresnel * d * g / (4.0 * cos_cos));
        }
        let denom = c.lo_m + c.eta * c.li_m;
        // Radiance is compressed into the narrower solid angle of the denser side.
        let scale = match mode {
            TransportMode::Radiance => 1.0,
            TransportMode::Importance => c.eta * c.eta,
        };
        let t =
            scale * (1.0 - c.fresnel) * d * g * (c.lo_m * c.li_m).abs() / (cos_cos * denom * denom);
        self.kt * t
    }

    /// Density per steradian of [`RoughGlass::sample`] returning `li`.
    pub fn pdf(&self, lo: Vec3, li: Vec3) -> f32 {
        let Some(c) = self.configuration(lo, li) else {
            return 0.0;
        };
        let up = lo * lo.z.signum();
        let pdf_m = self.distr.pdf_visible(up, c.m);
        if c.reflect {
            // Eq. 14.
            c.fresnel * pdf_m / (4.0 * c.li_m.abs())
        } else {
            // Eq. 17.
            let denom = c.lo_m + c.eta * c.li_m;
            (1.0 - c.fresnel) * pdf_m * c.eta * c.eta * c.li_m.abs() / (denom * denom)
        }
    }

    /// Draws `li` given `lo` (either side): a visible microfacet normal from `u`, then
    /// reflection when `u_lobe < F`, refraction otherwise. `None` where the drawn direction
    /// leaves the side its lobe scatters to (it carries no light: `G` is zero there).
    pub fn sample(&self, lo: Vec3, u_lobe: f32, u: Vec2) -> Option<Vec3> {
        if lo.z == 0.0 {
            return None;
        }
        // The configuration turned to the upper side (a point reflection, which maps the
        // mirror and the refraction about m onto their negatives).
        let side = lo.z.signum();
        let up = lo * side;
        let eta = self.eta_from(lo);
        let m = self.distr.sample_visible(up, u);
        let cos_i = up.dot(m);
        if cos_i <= 0.0 {
            return None;
        }
        let reflect = u_lobe < fresnel_dielectric(cos_i, eta);
        let li_up = if reflect {
            2.0 * cos_i * m - up
        } else {
            let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
            if sin2_t >= 1.0 {
                return None; // F = 1 here: unreachable in exact arithmetic
            }
            let cos_t = safe_sqrt(1.0 - sin2_t);
            // Snell's law about m (Walter et al. eq. 40).
            (m * (cos_i / eta - cos_t) - up / eta).normalize()
        };
        let li = li_up * side;
        let same_side = li.z * lo.z;
        let on_its_side = if reflect {
            same_side > 0.0
        } else {
            same_side < 0.0
        };
        (on_its_side && li.is_finite()).then_some(li)
    }
}
