//! Mitsuba 3's `principled` BSDF: the Disney BSDF (B. Burley 2012, "Physically Based
//! Shading at Disney", SIGGRAPH course notes; B. Burley 2015, "Extending the Disney BRDF to
//! a BSDF with Integrated Subsurface Scattering", SIGGRAPH course notes), evaluated, sampled
//! and weighed as Mitsuba 3.9's `src/bsdfs/principled.cpp` and `principledhelpers.h` do, in
//! the local shading frame, on both sides.
//!
//! `lo` is footprint's `wo` (Mitsuba's `si.wi`), `li` the other direction (Mitsuba's `wo`);
//! `f` is Mitsuba's `eval` divided by `|cos θ_i|` of `li`. The lobes' weights are
//! `w_brdf = (1 - metallic)(1 - spec_trans)` and `w_bsdf = (1 - metallic) spec_trans`;
//! `h` is the half vector of the pair (`lo + li`, or `lo + η' li` across the surface, `η'`
//! the relative index of the crossing from `lo`'s side), turned to the upper side. The
//! front side is `lo.z > 0`.
//!
//! * **Main specular reflection** (Burley 2012, §5.4; Mitsuba's component 3): anisotropic
//!   GGX of `α_u = max(0.001, r²/a)`, `α_v = max(0.001, r² a)`, `a = sqrt(1 - 0.9
//!   anisotropic)` (Burley 2012, appendix B; `calc_dist_params`), `r` the roughness:
//!   `f = F_p D(h) G(lo, li) / (4 |cos θ_o| |cos θ_i|)` with Smith's separable masking. The
//!   Fresnel term `F_p` (`principled_fresnel`) mixes, on the front side,
//!   `(1 - metallic)(1 - spec_tint) F(lo·h) + metallic S(base_color) + (1 - metallic)
//!   spec_tint S(c_tint R0(η))`: `F` the dielectric Fresnel term of the index `η`,
//!   `S(R0) = R0 + (1 - R0)(1 - cos)⁵` Schlick's (of the refracted cosine where the index
//!   is below 1), `c_tint` the base colour over its luminance, `R0(η) = ((η - 1)/(η + 1))²`;
//!   on the back side it is `w_bsdf F(lo·h)`.
//! * **Main specular transmission** (Burley 2015, §4; component 2): Walter et al. 2007's
//!   refraction (eq. 21) weighted by `w_bsdf` and tinted by `sqrt(base_color)`,
//!   `f = sqrt(c) w_bsdf (1 - F) D G η'² |lo·h| |li·h| / (|cos θ_o| |cos θ_i| (lo·h + η'
//!   li·h)²)` in importance mode, divided by `η'²` in radiance mode (the solid angle's
//!   compression, Veach 1997 §5.2).
//! * **Clearcoat** (Burley 2012, §5.6; component 1), front side only: GTR1 of
//!   `α_c = lerp(0.1, 0.001, clearcoat_gloss)` (Burley 2012, appendix B: `D = (α² - 1) / (π
//!   ln(α²) (1 + (α² - 1) cos²θ_h))`), Schlick's Fresnel of `R0 = 0.04`, GGX masking of
//!   α 0.25, in Mitsuba's form `f = 0.25 clearcoat F D G` (without the `1/(4 cos θ_o cos
//!   θ_i)` of a microfacet lobe: Mitsuba's value, which this reproduces).
//! * **Diffuse** (Burley 2015, eq. 4; component 0), front side only:
//!   `f = w_brdf c/π ((1 - F_o/2)(1 - F_i/2) + R_R (F_o + F_i + F_o F_i (R_R - 1)))`,
//!   `F_x = (1 - cos θ_x)⁵`, `R_R = 2 r cos²θ_d`, `cos θ_d = li·h`; with `flatness`
//!   blended towards Hanrahan & Krueger's fake subsurface term `1.25 (F_ss (1/(cos θ_o +
//!   cos θ_i) - 0.5) + 0.5)`, `F_ss = lerp(1, R_R/2, F_o) lerp(1, R_R/2, F_i)` (Burley 2012,
//!   §5.3).
//! * **Sheen** (Burley 2012, §5.5), front side only, where the diffuse lobe is:
//!   `f = sheen (1 - metallic) (1 - cos θ_d)⁵ lerp(1, c_tint, sheen_tint)` (Mitsuba's form,
//!   without `1/π`). Mitsuba's `scalar_rgb` variant, whose images footprint is checked
//!   against, evaluates the sheen only where the diffuse lobe is active (`w_brdf > 0`); its
//!   vectorised variants also where `spec_trans = 1`.
//!
//! Sampling (Mitsuba's `sample`): a visible normal `m` of the main GGX distribution seen
//! from `lo` turned up is drawn from the pair `u` first; its Fresnel term `F = F(lo·m)`
//! sets the lobe probabilities, on the front side proportional to `s_d w_brdf` (diffuse,
//! cosine-weighted), `0.25 s_c clearcoat` (clearcoat, the GTR1 normal's density `D cos θ_h`),
//! `s_s w_bsdf (1 - F)` (transmission through `m`) and `s_s (1 - w_bsdf (1 - F))`
//! (reflection about `m`), `s_*` the `*_sampling_rate`s; on the back side `1 - F` and `F`
//! (Mitsuba samples nothing from the back where `w_bsdf = 0`). The number `u_lobe` picks
//! the lobe in that order; the diffuse and clearcoat lobes reuse `u`. On the front side the
//! sum of the probabilities does not depend on `F`, so each lobe's probability given the
//! sampled direction is the one [`Principled::pdf`] computes from the pair's half vector,
//! and the density is the mixture of the lobes' (`pdf`): the visible normals' density times
//! the Jacobians `1/(4 |li·h|)` (reflection) and `η'² |li·h| / (lo·h + η' li·h)²`
//! (refraction; Walter et al. 2007, eqs. 14 and 17).
//!
//! One departure from Mitsuba's `pdf`, which changes no image: where Mitsuba samples
//! nothing (from the back without transmission), the density here is 0, Mitsuba's the
//! reflection's (whose value is 0 there). The parameters are taken as given, as Mitsuba
//! takes them (the importer rejects constants outside [0, 1]).

use crate::Rgb;
use crate::bsdf::fresnel::fresnel_dielectric;
use crate::bsdf::microfacet::{Microfacet, MicrofacetDistribution};
use crate::bsdf::surface::TransportMode;
use crate::math::{INV_PI, PI, luminance_mitsuba, safe_sqrt};
use crate::sampling::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use glam::{Vec2, Vec3};

/// A scalar parameter of the principled material: a constant, or a texture whose scalar
/// value (Mitsuba's `eval_1`, `Texture::lookup_1`) is the parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scalar {
    /// The constant; for a textured parameter, what the lobes take where textures are not
    /// looked up (Mitsuba's default of the parameter).
    pub value: f32,
    /// Index into the scene's textures.
    pub texture: Option<u32>,
}

impl Scalar {
    pub const fn constant(value: f32) -> Self {
        Scalar {
            value,
            texture: None,
        }
    }

    /// The value at a point where `lookup` gives a texture's value (`None`: not looked up).
    #[inline]
    fn at(&self, lookup: &impl Fn(u32) -> Option<f32>) -> f32 {
        self.texture.and_then(lookup).unwrap_or(self.value)
    }
}

/// Mitsuba's `diffuse_reflectance_sampling_rate`, `main_specular_sampling_rate` and
/// `clearcoat_sampling_rate`: the lobes' relative sampling weights (all 1 by default).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SamplingRates {
    pub diffuse: f32,
    pub specular: f32,
    pub clearcoat: f32,
}

impl Default for SamplingRates {
    fn default() -> Self {
        SamplingRates {
            diffuse: 1.0,
            specular: 1.0,
            clearcoat: 1.0,
        }
    }
}

/// The parameters of a principled material (the base colour is the material's `kd`), with
/// their textures; Mitsuba's defaults.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipledParams {
    pub roughness: Scalar,
    pub anisotropic: Scalar,
    pub metallic: Scalar,
    pub spec_trans: Scalar,
    pub spec_tint: Scalar,
    pub sheen: Scalar,
    pub sheen_tint: Scalar,
    pub flatness: Scalar,
    pub clearcoat: Scalar,
    pub clearcoat_gloss: Scalar,
    /// Interior over exterior index, `eta` or from `specular` (`2 / (1 - sqrt(0.08
    /// specular)) - 1`).
    pub eta: f32,
    pub rates: SamplingRates,
}

impl Default for PrincipledParams {
    fn default() -> Self {
        PrincipledParams {
            roughness: Scalar::constant(0.5),
            anisotropic: Scalar::constant(0.0),
            metallic: Scalar::constant(0.0),
            spec_trans: Scalar::constant(0.0),
            spec_tint: Scalar::constant(0.0),
            sheen: Scalar::constant(0.0),
            sheen_tint: Scalar::constant(0.0),
            flatness: Scalar::constant(0.0),
            clearcoat: Scalar::constant(0.0),
            clearcoat_gloss: Scalar::constant(0.0),
            eta: 1.5,
            rates: SamplingRates::default(),
        }
    }
}

impl PrincipledParams {
    /// The scalar parameters with Mitsuba's names.
    pub fn scalars(&self) -> [(&'static str, Scalar); 10] {
        [
            ("roughness", self.roughness),
            ("anisotropic", self.anisotropic),
            ("metallic", self.metallic),
            ("spec_trans", self.spec_trans),
            ("spec_tint", self.spec_tint),
            ("sheen", self.sheen),
            ("sheen_tint", self.sheen_tint),
            ("flatness", self.flatness),
            ("clearcoat", self.clearcoat),
            ("clearcoat_gloss", self.clearcoat_gloss),
        ]
    }

    /// True when `spec_trans` is a texture or a constant other than 0 (Mitsuba's
    /// `m_has_spec_trans`): the material may transmit.
    pub fn may_transmit(&self) -> bool {
        self.spec_trans.texture.is_some() || self.spec_trans.value != 0.0
    }

    /// True when `anisotropic` is a texture or a constant other than 0.
    pub fn may_be_anisotropic(&self) -> bool {
        self.anisotropic.texture.is_some() || self.anisotropic.value != 0.0
    }

    /// True when some scalar parameter is a texture.
    pub fn textured(&self) -> bool {
        self.scalars().iter().any(|(_, s)| s.texture.is_some())
    }

    /// Mitsuba's `specular` → `eta`: `2 / (1 - sqrt(0.08 specular)) - 1` (the index whose
    /// normal-incidence reflectance is `0.08 specular`, Burley 2012 §5.4).
    pub fn eta_of_specular(specular: f32) -> f32 {
        2.0 / (1.0 - (0.08 * specular).sqrt()) - 1.0
    }

    /// The lobes with base colour `base_color` (already textured) and the textured scalars'
    /// values from `lookup` (a texture index to the texture's scalar value at the point,
    /// `Texture::lookup_1`; `None` where textures are not looked up: the scalar's `value`).
    pub fn at(&self, base_color: Rgb, lookup: impl Fn(u32) -> Option<f32>) -> Principled {
        let roughness = self.roughness.at(&lookup);
        let (alpha_u, alpha_v) = alphas(roughness, self.anisotropic.at(&lookup));
        let gloss = self.clearcoat_gloss.at(&lookup);
        Principled {
            base_color,
            roughness,
            alpha_u,
            alpha_v,
            eta: self.eta,
            metallic: self.metallic.at(&lookup),
            spec_trans: self.spec_trans.at(&lookup),
            spec_tint: self.spec_tint.at(&lookup),
            sheen: self.sheen.at(&lookup),
            sheen_tint: self.sheen_tint.at(&lookup),
            flatness: self.flatness.at(&lookup),
            clearcoat: self.clearcoat.at(&lookup),
            // lerp(0.1, 0.001, gloss).
            clearcoat_alpha: 0.1 * (1.0 - gloss) + 0.001 * gloss,
            rates: self.rates,
        }
    }
}

/// The main lobe's GGX roughness along the tangent and the bitangent (Mitsuba's
/// `calc_dist_params`; Burley 2012, appendix B): `r²/a` and `r² a`, `a = sqrt(1 - 0.9
/// anisotropic)`, each at least 0.001.
fn alphas(roughness: f32, anisotropic: f32) -> (f32, f32) {
    let r2 = roughness * roughness;
    if anisotropic == 0.0 {
        let a = r2.max(0.001);
        return (a, a);
    }
    let aspect = (1.0 - 0.9 * anisotropic).sqrt();
    ((r2 / aspect).max(0.001), (r2 * aspect).max(0.001))
}

/// The principled lobes resolved at a point (textures looked up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Principled {
    pub base_color: Rgb,
    /// The roughness parameter `r` itself (the diffuse lobe's retro-reflection reads it).
    pub roughness: f32,
    /// The main lobe's GGX roughness along the tangent and the bitangent.
    pub alpha_u: f32,
    pub alpha_v: f32,
    /// Interior over exterior index.
    pub eta: f32,
    pub metallic: f32,
    pub spec_trans: f32,
    pub spec_tint: f32,
    pub sheen: f32,
    pub sheen_tint: f32,
    pub flatness: f32,
    pub clearcoat: f32,
    /// GTR1's `α_c = lerp(0.1, 0.001, clearcoat_gloss)`.
    pub clearcoat_alpha: f32,
    pub rates: SamplingRates,
}

/// `(1 - cos)⁵` with the cosine clamped to [0, 1] (Mitsuba's `schlick_weight`).
#[inline]
fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// The crossing of an interface of index `eta` (interior over exterior) at signed cosine
/// `cos_i` of the incident direction with the normal (negative: from inside): the relative
/// index `η_it` of the crossing, its reciprocal `η_ti`, and the refracted direction's
/// `|cos θ_t|` (0 beyond the critical angle).
#[inline]
fn crossing(cos_i: f32, eta: f32) -> (f32, f32, f32) {
    let (eta_it, eta_ti) = if cos_i >= 0.0 {
        (eta, 1.0 / eta)
    } else {
        (1.0 / eta, eta)
    };
    let cos_t = safe_sqrt(1.0 - (1.0 - cos_i * cos_i) * eta_ti * eta_ti);
    (eta_it, eta_ti, cos_t)
}

/// The dielectric Fresnel term of index `eta` at signed cosine `cos_i` ([`crossing`]), the
/// crossing's `η_ti` and the signed cosine of the refracted direction (Mitsuba's `fresnel`,
/// whose index-matched interface reflects nothing at any angle).
#[inline]
fn fresnel(cos_i: f32, eta: f32) -> (f32, f32, f32) {
    let (eta_it, eta_ti, cos_t) = crossing(cos_i, eta);
    let r = if eta == 1.0 {
        0.0
    } else {
        fresnel_dielectric(cos_i.abs(), eta_it)
    };
    (r, eta_ti, if cos_i >= 0.0 { -cos_t } else { cos_t })
}

/// Schlick's Fresnel term of normal-incidence reflectance `r0` at signed cosine `cos_i`
/// across an interface of index `eta`, of the refracted cosine where the index of the
/// crossing is below 1 (Mitsuba's `calc_schlick`).
#[inline]
fn schlick(r0: Rgb, cos_i: f32, eta: f32) -> Rgb {
    let (eta_it, _, cos_t) = crossing(cos_i, eta);
    let w = schlick_weight(if eta_it > 1.0 { cos_i.abs() } else { cos_t });
    r0 + (Rgb::ONE - r0) * w
}

/// `((η - 1)/(η + 1))²`, the normal-incidence reflectance of index `η`.
#[inline]
fn schlick_r0(eta: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    r * r
}

/// Smith's GGX masking of isotropic roughness `alpha` for direction `v` and normal `h`
/// (Mitsuba's `smith_ggx1`, the clearcoat's).
#[inline]
fn smith_ggx1(v: Vec3, h: Vec3, alpha: f32) -> f32 {
    if v.dot(h) * v.z <= 0.0 {
        return 0.0;
    }
    if v.z == 1.0 {
        return 1.0;
    }
    let cos2 = v.z * v.z;
    let tan2 = (1.0 - cos2) / cos2;
    2.0 / (1.0 + (1.0 + alpha * alpha * tan2).sqrt())
}

/// GTR1 (Burley 2012, appendix B; the clearcoat's distribution): `D(h)` per solid angle,
/// flushed to zero where `D cos θ <= 1e-20`, as Mitsuba's `GTR1Isotropic::eval`.
#[inline]
fn gtr1_d(alpha: f32, h: Vec3) -> f32 {
    let a2 = alpha * alpha;
    let d = (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * h.z * h.z));
    if d * h.z > 1e-20 { d } else { 0.0 }
}

/// A GTR1 normal drawn with density `D(h) cos θ_h` (Burley 2012, appendix B:
/// `cos²θ = (1 - α^(2(1 - u)))/(1 - α²)`; Mitsuba's `GTR1Isotropic::sample`).
#[inline]
fn gtr1_sample(alpha: f32, u: Vec2) -> Vec3 {
    let a2 = alpha * alpha;
    let cos2 = (1.0 - a2.powf(1.0 - u.y)) / (1.0 - a2);
    let sin_t = (1.0 - cos2).max(0.0).sqrt();
    let (sin_p, cos_p) = (2.0 * PI * u.x).sin_cos();
    Vec3::new(cos_p * sin_t, sin_p * sin_t, cos2.max(0.0).sqrt())
}

/// Mitsuba's `mac_mic_compatibility`: both directions on the sides of the microfacet normal
/// `h` (turned to `lo`'s side) that a reflection (both on `lo`'s) or a refraction (`li` on
/// the other) puts them.
#[inline]
fn compatible(h: Vec3, lo: Vec3, li: Vec3, reflection: bool) -> bool {
    let hs = if lo.z < 0.0 { -h } else { h };
    lo.dot(hs) > 0.0
        && if reflection {
            li.dot(hs) > 0.0
        } else {
            li.dot(hs) < 0.0
        }
}

/// The lobes' probabilities, in the order `u_lobe` picks them.
#[derive(Clone, Copy, Debug)]
struct LobeProbabilities {
    diffuse: f32,
    clearcoat: f32,
    transmission: f32,
    reflection: f32,
}

/// What `f` and the density of a pair of local directions share.
struct Pair {
    reflect: bool,
    front: bool,
    /// `η'`, the relative index of the crossing from `lo`'s side.
    eta_path: f32,
    /// The half vector, on the upper side.
    h: Vec3,
    /// The dielectric Fresnel term at `h` seen from `lo`.
    fresnel: f32,
}

impl Principled {
    #[inline]
    fn w_brdf(&self) -> f32 {
        (1.0 - self.metallic) * (1.0 - self.spec_trans)
    }

    #[inline]
    fn w_bsdf(&self) -> f32 {
        (1.0 - self.metallic) * self.spec_trans
    }

    /// True where the main lobe transmits (`w_bsdf > 0`): the lobes then scatter to both
    /// sides and from both; otherwise they reflect only, from the front.
    #[inline]
    pub fn transmits(&self) -> bool {
        self.w_bsdf() > 0.0
    }

    /// True where the main lobe is anisotropic: its tangent must be the surface's `∂p/∂u`.
    #[inline]
    pub fn is_anisotropic(&self) -> bool {
        self.alpha_u != self.alpha_v
    }

    /// The main lobe's GGX distribution.
    #[inline]
    pub fn distribution(&self) -> MicrofacetDistribution {
        MicrofacetDistribution::anisotropic(Microfacet::Ggx, self.alpha_u, self.alpha_v)
    }

    /// The lobe probabilities with `fresnel` the dielectric Fresnel term at the main lobe's
    /// normal; `None` where none is positive.
    #[inline]
    fn probabilities(&self, front: bool, fresnel: f32) -> Option<LobeProbabilities> {
        let w_bsdf = self.w_bsdf();
        let p = if front {
            let s = self.rates.specular;
            LobeProbabilities {
                diffuse: self.w_brdf() * self.rates.diffuse,
                clearcoat: 0.25 * self.clearcoat * self.rates.clearcoat,
                transmission: s * w_bsdf * (1.0 - fresnel),
                reflection: s * (1.0 - w_bsdf * (1.0 - fresnel)),
            }
        } else {
            LobeProbabilities {
                diffuse: 0.0,
                clearcoat: 0.0,
                transmission: 1.0 - fresnel,
                reflection: fresnel,
            }
        };
        let total = p.diffuse + p.clearcoat + p.transmission + p.reflection;
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        let inv = 1.0 / total;
        Some(LobeProbabilities {
            diffuse: p.diffuse * inv,
            clearcoat: p.clearcoat * inv,
            transmission: p.transmission * inv,
            reflection: p.reflection * inv,
        })
    }

    /// The half vector of `(lo, li)` and its terms; `None` where no lobe can be positive
    /// (grazing `lo` or `li`, a degenerate half vector, from the back without transmission).
    #[inline]
    fn pair(&self, lo: Vec3, li: Vec3) -> Option<Pair> {
        if lo.z == 0.0 || li.z == 0.0 {
            return None;
        }
        let front = lo.z > 0.0;
        if !front && !self.transmits() {
            return None;
        }
        let reflect = lo.z * li.z > 0.0;
        let eta_path = if front { self.eta } else { 1.0 / self.eta };
        let h = (lo + li * if reflect { 1.0 } else { eta_path }).try_normalize()?;
        let h = if h.z < 0.0 { -h } else { h };
        let (fresnel, _, _) = fresnel(lo.dot(h), self.eta);
        Some(Pair {
            reflect,
            front,
            eta_path,
            h,
            fresnel,
        })
    }

    /// The main lobe's Fresnel term `F_p` (Mitsuba's `principled_fresnel`) at signed cosine
    /// `cos` for the dielectric term `fresnel`.
    #[inline]
    fn principled_fresnel(&self, fresnel: f32, cos: f32, front: bool) -> Rgb {
        if !front {
            return Rgb::splat(self.w_bsdf() * fresnel);
        }
        let eta_it = if cos >= 0.0 { self.eta } else { 1.0 / self.eta };
        let mut f_schlick = Rgb::ZERO;
        if self.metallic != 0.0 {
            f_schlick += self.metallic * schlick(self.base_color, cos, self.eta);
        }
        if self.spec_tint != 0.0 {
            let r0 = self.tint() * schlick_r0(eta_it);
            f_schlick += (1.0 - self.metallic) * self.spec_tint * schlick(r0, cos, self.eta);
        }
        Rgb::splat((1.0 - self.metallic) * (1.0 - self.spec_tint) * fresnel) + f_schlick
    }

    /// The base colour over its luminance (white where it is black).
    #[inline]
    fn tint(&self) -> Rgb {
        let lum = luminance_mitsuba(self.base_color);
        if lum > 0.0 {
            self.base_color / lum
        } else {
            Rgb::ONE
        }
    }

    /// `f(lo, li)` (no cosine) in the local frame, `lo` and `li` on either side.
    pub fn eval(&self, lo: Vec3, li: Vec3, mode: TransportMode) -> Rgb {
        let Some(pair) = self.pair(lo, li) else {
            return Rgb::ZERO;
        };
        let Pair {
            reflect,
            front,
            eta_path,
            h,
            fresnel,
        } = pair;
        let (cos_o, cos_i) = (lo.z.abs(), li.z.abs());
        let distr = self.distribution();
        let (lo_h, li_h) = (lo.dot(h), li.dot(h));
        let mut f = Rgb::ZERO;
        let compatible_reflection = reflect && compatible(h, lo, li, true);
        if compatible_reflection && fresnel > 0.0 {
            let d = distr.d(h);
            let g = distr.g1(lo, h) * distr.g1(li, h);
            f += self.principled_fresnel(fresnel, lo_h, front) * (d * g / (4.0 * cos_o * cos_i));
        }
        if !reflect && self.transmits() && fresnel < 1.0 && compatible(h, lo, li, false) {
            let d = distr.d(h);
            let g = distr.g1(lo, h) * distr.g1(li, h);
            // Importance carries η'² more than radiance (the solid angle's compression).
            let eta2 = match mode {
                TransportMode::Radiance => 1.0,
                TransportMode::Importance => eta_path * eta_path,
            };
            let denom = lo_h + eta_path * li_h;
            let t = eta2 * (1.0 - fresnel) * d * g * (lo_h * li_h).abs()
                / (cos_o * cos_i * denom * denom);
            f += self.base_color.map(f32::sqrt) * (self.w_bsdf() * t);
        }
        if !(reflect && front) {
            return f;
        }
        if self.clearcoat > 0.0 && compatible_reflection {
            let f_cc = schlick(Rgb::splat(0.04), lo_h, self.eta).x;
            let d_cc = gtr1_d(self.clearcoat_alpha, h);
            let g_cc = smith_ggx1(lo, h, 0.25) * smith_ggx1(li, h, 0.25);
            f += Rgb::splat(0.25 * self.clearcoat * f_cc * d_cc * g_cc);
        }
        let w_brdf = self.w_brdf();
        if w_brdf > 0.0 {
            f += self.diffuse(cos_o, cos_i, li_h) * w_brdf;
            if self.sheen > 0.0 && self.metallic < 1.0 {
                let tint = Rgb::ONE + (self.tint() - Rgb::ONE) * self.sheen_tint;
                f += tint * (self.sheen * (1.0 - self.metallic) * schlick_weight(li_h.abs()));
            }
        }
        f
    }

    /// The diffuse lobe with its retro-reflection (and fake subsurface, by `flatness`),
    /// before the weight `w_brdf`; `cos_d` is `li·h`.
    #[inline]
    fn diffuse(&self, cos_o: f32, cos_i: f32, cos_d: f32) -> Rgb {
        let (f_o, f_i) = (schlick_weight(cos_o), schlick_weight(cos_i));
        let lambert = (1.0 - 0.5 * f_i) * (1.0 - 0.5 * f_o);
        let rr = 2.0 * self.roughness * cos_d * cos_d;
        let retro = rr * (f_o + f_i + f_o * f_i * (rr - 1.0));
        let mut shape = lambert + retro;
        if self.flatness != 0.0 {
            let fss90 = 0.5 * rr;
            let fss = (1.0 + (fss90 - 1.0) * f_o) * (1.0 + (fss90 - 1.0) * f_i);
            let ss = 1.25 * (fss * (1.0 / (cos_o + cos_i) - 0.5) + 0.5);
            shape += (ss - shape) * self.flatness;
        }
        self.base_color * (INV_PI * shape)
    }

    /// Density per steradian of [`Principled::sample`] returning `li`.
    pub fn pdf(&self, lo: Vec3, li: Vec3) -> f32 {
        let Some(pair) = self.pair(lo, li) else {
            return 0.0;
        };
        let Some(p) = self.probabilities(pair.front, pair.fresnel) else {
            return 0.0;
        };
        let h = pair.h;
        let (lo_h, li_h) = (lo.dot(h), li.dot(h));
        let up = if lo.z < 0.0 { -lo } else { lo };
        let mut pdf = 0.0;
        if pair.reflect {
            if pair.front {
                pdf += p.diffuse * cosine_hemisphere_pdf(li.z);
            }
            if compatible(h, lo, li, true) {
                let jacobian = 1.0 / (4.0 * li_h.abs());
                pdf += p.reflection * self.distribution().pdf_visible(up, h) * jacobian;
                if p.clearcoat > 0.0 {
                    pdf += p.clearcoat * gtr1_d(self.clearcoat_alpha, h) * h.z * jacobian;
                }
            }
        } else if p.transmission > 0.0 && compatible(h, lo, li, false) {
            let denom = lo_h + pair.eta_path * li_h;
            let jacobian = (pair.eta_path * pair.eta_path * li_h / (denom * denom)).abs();
            pdf += p.transmission * self.distribution().pdf_visible(up, h) * jacobian;
        }
        if pdf.is_finite() { pdf } else { 0.0 }
    }

    /// Draws `li` given `lo` (either side) with the lobe number `u_lobe` and the pair `u`;
    /// `None` where the drawn direction leaves the side its lobe scatters to.
    pub fn sample(&self, lo: Vec3, u_lobe: f32, u: Vec2) -> Option<Vec3> {
        if lo.z == 0.0 {
            return None;
        }
        let front = lo.z > 0.0;
        if !front && !self.transmits() {
            return None;
        }
        let up = if front { lo } else { -lo };
        let m = self.distribution().sample_visible(up, u);
        let cos = lo.dot(m);
        let (fresnel, eta_ti, cos_t) = fresnel(cos, self.eta);
        let p = self.probabilities(front, fresnel)?;
        let (li, reflection) = if u_lobe < p.diffuse {
            (sample_cosine_hemisphere(u), true)
        } else if u_lobe < p.diffuse + p.clearcoat {
            let h = gtr1_sample(self.clearcoat_alpha, u);
            let li = reflect(lo, h);
            if !compatible(h, lo, li, true) {
                return None;
            }
            (li, true)
        } else if u_lobe < p.diffuse + p.clearcoat + p.transmission {
            // Snell's law about m (Mitsuba's `refract`).
            let li = (m * (cos * eta_ti + cos_t) - lo * eta_ti).normalize();
            if !compatible(m, lo, li, false) {
                return None;
            }
            (li, false)
        } else {
            let li = reflect(lo, m);
            if !compatible(m, lo, li, true) {
                return None;
            }
            (li, true)
        };
        let on_its_side = if reflection {
            li.z * lo.z > 0.0
        } else {
            li.z * lo.z < 0.0
        };
        (on_its_side && li.is_finite()).then_some(li)
    }
}

/// Mirror of `v` about `m`.
#[inline]
fn reflect(v: Vec3, m: Vec3) -> Vec3 {
    2.0 * v.dot(m) * m - v
}
