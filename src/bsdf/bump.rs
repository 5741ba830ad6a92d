//! Bump mapping as Mitsuba 3's `bumpmap` BSDF adapter does it (`src/bsdfs/bumpmap.cpp`): a
//! height field tilts the shading normal (Blinn 1978, "Simulation of wrinkled surfaces"), the
//! nested BSDF is evaluated and sampled about the tilted normal, and a shadowing term smooths
//! the terminator (Estevez et al. 2019, "A Microfacet-Based Shadowing Function to Solve the
//! Bump Terminator Problem", Ray Tracing Gems ch. 12; Mitsuba's `eval_shadow_terminator`).
//!
//! **The tilted normal.** With `h` the height texture's luminance and `(u, v)` Mitsuba's
//! texture coordinates, the gradient `∇h = scale · (∂h/∂u, ∂h/∂v)` replaces the normal
//! components of the surface's partials `∂p/∂u`, `∂p/∂v` (the derivative of the normal itself
//! neglected, as Mitsuba does):
//! `∂p/∂u' = ∂p/∂u + n_s (∂h/∂u - n_s·∂p/∂u)` (likewise for `v`), and the bumped normal is
//! `n_b = normalize(∂p/∂u' × ∂p/∂v')`, turned to the geometric normal's side. Mitsuba then
//! expresses `n_b` in the unbumped shading frame ("a small rotation from the original shading
//! frame"), and, with `flip_invalid_normals`, mirrors it about the shading normal (`(x, y, z)`
//! → `(-x, -y, z)`) where it puts `wo` (Mitsuba's `si.wi`) on the other side from the shading
//! normal: the bumped frame depends on the side the path arrives from, so every evaluation
//! derives it from its own `wo` ([`Bump::normal_for`]). The frame's rotation about `n_b` is left
//! free: every lobe here is isotropic.
//!
//! **What the BSDF returns.** Mitsuba's value, cosine included, is
//! `f_nested(wo_b, wi_b) cos θ_i,b · G(wi)`, zero unless `wi` lies on the same side of the
//! shading and the bumped normal; `G(wi) = 2 / (1 + sqrt(1 + α² tan² θ_i))` with
//! `α² = min(tan² θ_b / 8, 1)`, `θ_i` measured from the unbumped shading normal and `θ_b` the
//! bumped normal's tilt from it. The density is the nested one in the bumped frame (no `G`).
//! Integrators here multiply `f` by `|wi·n_s|` with the unbumped shading normal `n_s` (that of
//! the hit), so the BSDF's `f` is Mitsuba's value divided by that cosine; the estimator's
//! product, the sample weight `f |cos θ_i| / pdf`, and the importance-mode correction (the
//! unbumped shading normal's, as Mitsuba's `ptracer` applies it) are then Mitsuba's. The hit's
//! shading normal stays the surface's: the bump lives in the BSDF alone, as in Mitsuba, where
//! the integrators see `si.sh_frame` unchanged.

use crate::bsdf::lobes::LocalSample;
use crate::bsdf::surface::{Bsdf, BsdfSample, TransportMode};
use crate::math::{Frame, Rgb};
use glam::{Vec2, Vec3};

/// A material's bump or normal map: the texture, what it holds, and the parameters Mitsuba's
/// `bumpmap` and `normalmap` share.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BumpMap {
    /// Index into the scene's textures.
    pub texture: u32,
    /// What the texture holds: heights or normals.
    pub source: NormalSource,
    /// Mitsuba's `flip_invalid_normals` (default true).
    pub flip_invalid_normals: bool,
    /// Mitsuba's `use_shadowing_function` (default true): the terminator term `G`.
    pub shadowing: bool,
    /// The nested BSDF is two-sided (`bumpmap` around `twosided`): it reflects on whichever
    /// side of the bumped normal `wo` lies. A `twosided` around the `bumpmap` is the
    /// material's own `two_sided` and acts on the unbumped frame.
    pub nested_two_sided: bool,
}

/// Where a bump map's normal comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NormalSource {
    /// Mitsuba's `bumpmap`: a height field (the texture's luminance), whose gradient times
    /// `scale` (default 1; any sign) tilts the normal ([`bumped_normal`]).
    Height { scale: f32 },
    /// Mitsuba's `normalmap` (`src/bsdfs/normalmap.cpp`): the texture's colour `c` holds the
    /// normal `2c - 1` in the shading frame whose tangent follows `∂p/∂u` ([`mapped_normal`]).
    Normals,
}

/// The bump at one surface point: the bumped normal in the unbumped shading frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bump {
    /// The bumped normal `n_b` in the local unbumped shading frame, before the per-`wo` flip.
    pub normal_local: Vec3,
    /// `α²` of the shadowing term, or `None` without it.
    pub shadow_alpha2: Option<f32>,
    pub flip_invalid_normals: bool,
    pub nested_two_sided: bool,
}

/// `∂p/∂u` and `∂p/∂v` of a triangle with edges `e1`, `e2` and texture coordinates `uv`
/// (Mitsuba's convention, `v` down), as Mitsuba's mesh computes them
/// (`Mesh::compute_surface_interaction`): the edges taken to the texture basis through the
/// inverse of the coordinates' 2x2 matrix, both zero where its determinant is zero.
pub fn uv_partials(e1: Vec3, e2: Vec3, uv: [Vec2; 3]) -> (Vec3, Vec3) {
    let duv0 = uv[1] - uv[0];
    let duv1 = uv[2] - uv[0];
    let det = duv0.x * duv1.y - duv0.y * duv1.x;
    let inv_det = if det != 0.0 { 1.0 / det } else { 0.0 };
    (
        (duv1.y * e1 - duv0.y * e2) * inv_det,
        (-duv1.x * e1 + duv0.x * e2) * inv_det,
    )
}

/// The bumped normal in world space (Mitsuba's `BumpMap::frame` up to the change of frame):
/// `ns` the shading normal, `ng` the geometric normal (the surface's front), `dp_du`,
/// `dp_dv` the surface's partials and `grad_uv` the scaled height gradient. `None` where the
/// partials give no normal (a degenerate texture parametrisation: Mitsuba's normal is then
/// NaN).
pub fn bumped_normal(ns: Vec3, ng: Vec3, dp_du: Vec3, dp_dv: Vec3, grad_uv: Vec2) -> Option<Vec3> {
    let du = ns * (grad_uv.x - ns.dot(dp_du)) + dp_du;
    let dv = ns * (grad_uv.y - ns.dot(dp_dv)) + dp_dv;
    let n = du.cross(dv).try_normalize()?;
    Some(if ng.dot(n) < 0.0 { -n } else { n })
}

/// The normal of a normal map in world space (Mitsuba's `NormalMap::frame`): the colour `c`
/// read as `n = 2c - 1` in the shading frame of the hit as Mitsuba builds it
/// (`SurfaceInteraction::initialize_sh_frame`): `z` the shading normal `ns`, `x` the
/// partial `∂p/∂u` made orthogonal to it, `y = z × x`. Neither turned to a side nor
/// flipped here: the flip of `flip_invalid_normals` depends on the arriving direction
/// ([`Bump::normal_for`]). `None` where the partial gives no tangent (Mitsuba's frame is
/// then NaN) or the colour no direction.
pub fn mapped_normal(ns: Vec3, dp_du: Vec3, c: Rgb) -> Option<Vec3> {
    let s = (dp_du - ns * ns.dot(dp_du)).try_normalize()?;
    let t = ns.cross(s);
    let n = c * 2.0 - Vec3::ONE;
    (s * n.x + t * n.y + ns * n.z).try_normalize()
}

impl Bump {
    /// The bump of normal `n_world` (from [`bumped_normal`]) in the shading frame `frame`.
    pub fn new(map: &BumpMap, frame: &Frame, n_world: Vec3) -> Self {
        let normal_local = frame.to_local(n_world);
        let shadow_alpha2 = map
            .shadowing
            .then(|| (0.125 * tan2_theta(normal_local)).min(1.0));
        Bump {
            normal_local,
            shadow_alpha2,
            flip_invalid_normals: map.flip_invalid_normals,
            nested_two_sided: map.nested_two_sided,
        }
    }

    /// The bumped normal for a path arriving from local direction `lo`: mirrored about the
    /// shading normal where it and the shading normal put `lo` on different sides (with
    /// `flip_invalid_normals`).
    #[inline]
    pub fn normal_for(&self, lo: Vec3) -> Vec3 {
        let n = self.normal_local;
        if self.flip_invalid_normals && lo.z * lo.dot(n) <= 0.0 {
            Vec3::new(-n.x, -n.y, n.z)
        } else {
            n
        }
    }

    /// The shadowing term `G` for local direction `li` (1 without it).
    #[inline]
    pub fn shadowing(&self, li: Vec3) -> f32 {
        match self.shadow_alpha2 {
            Some(alpha2) => 2.0 / (1.0 + (1.0 + alpha2 * tan2_theta(li)).sqrt()),
            None => 1.0,
        }
    }
}

/// `tan² θ` of a local unit direction (Mitsuba's `Frame::tan_theta_2`, `max(0, 1 - cos²) / cos²`).
#[inline]
fn tan2_theta(v: Vec3) -> f32 {
    let c2 = v.z * v.z;
    (1.0 - c2).max(0.0) / c2
}

/// A reflection about the bumped normal: the local directions in the bumped frame (both
/// above it) and `wi` in the shading frame, turned to the side the surface reflects on.
struct BumpedPair {
    lo_b: Vec3,
    li_b: Vec3,
    li: Vec3,
}

impl Bsdf {
    /// The shading-frame direction of `wo` turned to the side the surface reflects on (the
    /// side a `twosided` around the bump map flips to), and that side.
    #[inline]
    fn bumped_wo(&self, wo: Vec3) -> (Vec3, f32) {
        let side = self.reflection_side(wo);
        let mut lo = self.frame.to_local(wo);
        lo.z *= side;
        (lo, side)
    }

    /// The frame about the bumped normal for a path arriving from `lo`, `lo` in it, and the
    /// side a two-sided nested BSDF flips to (1 otherwise).
    #[inline]
    fn bumped_frame(&self, bump: &Bump, lo: Vec3) -> (Frame, Vec3, f32) {
        let frame_b = Frame::from_z(bump.normal_for(lo));
        let mut lo_b = frame_b.to_local(lo);
        let inner = if bump.nested_two_sided && lo_b.z < 0.0 {
            -1.0
        } else {
            1.0
        };
        lo_b.z *= inner;
        (frame_b, lo_b, inner)
    }

    /// The local directions of a reflection from `wo` to `wi` about the bumped normal;
    /// `None` where the surface does not reflect between them: across the geometric surface
    /// (as without a bump map), `wi` on different sides of the shading and the bumped normal
    /// (Mitsuba's test), or either below the bumped normal (after a two-sided nested BSDF's
    /// flip).
    #[inline]
    fn bumped_pair(&self, bump: &Bump, wo: Vec3, wi: Vec3) -> Option<BumpedPair> {
        if wo.dot(self.ng) * wi.dot(self.ng) <= 0.0 {
            return None;
        }
        let (lo, side) = self.bumped_wo(wo);
        let mut li = self.frame.to_local(wi);
        li.z *= side;
        let (frame_b, lo_b, inner) = self.bumped_frame(bump, lo);
        let mut li_b = frame_b.to_local(li);
        if li.z * li_b.z <= 0.0 {
            return None;
        }
        li_b.z *= inner;
        if lo_b.z <= 0.0 || li_b.z <= 0.0 {
            return None;
        }
        Some(BumpedPair { lo_b, li_b, li })
    }

    /// `f(wo, wi)` with a bump map: Mitsuba's value (the nested `f cos θ_i` in the bumped
    /// frame, times the shadowing term) over `|cos θ_i|` in the shading frame, with the
    /// shading frame's importance-mode correction.
    pub(super) fn eval_bumped(&self, bump: &Bump, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        let Some(BumpedPair { lo_b, li_b, li }) = self.bumped_pair(bump, wo, wi) else {
            return Rgb::ZERO;
        };
        let f = self.lobes.eval_local(lo_b, li_b);
        f * (li_b.z * bump.shadowing(li) / li.z.abs() * self.adjoint_correction(wo, wi, mode))
    }

    /// The density of `wi` with a bump map: the nested lobes' in the bumped frame.
    pub(super) fn pdf_bumped(&self, bump: &Bump, wo: Vec3, wi: Vec3) -> f32 {
        match self.bumped_pair(bump, wo, wi) {
            Some(BumpedPair { lo_b, li_b, .. }) => self.lobes.pdf_local(lo_b, li_b),
            None => 0.0,
        }
    }

    /// Samples the nested lobes in the bumped frame; the weight is Mitsuba's (the nested
    /// weight times the shadowing term), with the shading frame's importance-mode correction.
    pub(super) fn sample_bumped(
        &self,
        bump: &Bump,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample> {
        let (lo, side) = self.bumped_wo(wo);
        let (frame_b, lo_b, inner) = self.bumped_frame(bump, lo);
        if lo_b.z <= 0.0 {
            return None;
        }
        let sampled = self.lobes.sample_reflection_local(lo_b, u_lobe, u)?;
        let li_b = match sampled {
            LocalSample::Smooth(li_b) | LocalSample::Delta { li: li_b, .. } => li_b,
        };
        if li_b.z <= 0.0 {
            return None;
        }
        let li = frame_b.to_world(Vec3::new(li_b.x, li_b.y, li_b.z * inner));
        let wi = self.frame.to_world(Vec3::new(li.x, li.y, li.z * side));
        match sampled {
            LocalSample::Smooth(_) => {
                let pdf_w = self.pdf_bumped(bump, wo, wi);
                let f = self.eval_bumped(bump, wo, wi, mode);
                if pdf_w <= 0.0 || !pdf_w.is_finite() || f.max_element() <= 0.0 {
                    return None;
                }
                Some(BsdfSample {
                    wi,
                    f,
                    pdf_w,
                    weight: f * (wi.dot(self.frame.z).abs() / pdf_w),
                    delta: false,
                })
            }
            LocalSample::Delta { weight, prob, .. } => {
                if li.z * li_b.z * inner <= 0.0 || wi.dot(self.ng) * wo.dot(self.ng) <= 0.0 {
                    return None;
                }
                let weight = weight * (bump.shadowing(li) * self.adjoint_correction(wo, wi, mode));
                Some(BsdfSample {
                    wi,
                    f: weight * (prob / li.z.abs()),
                    pdf_w: prob,
                    weight,
                    delta: true,
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Barycentric texture coordinates give the edges themselves; a scaled, swapped
    /// parametrisation gives the scaled, swapped edges; a degenerate one gives zero partials
    /// and no normal (Mitsuba's would be NaN), so the bump leaves the frame alone.
    #[test]
    fn uv_partials_as_mitsubas_mesh_and_the_degenerate_case() {
        let (e1, e2) = (Vec3::new(2.0, 0.0, 0.5), Vec3::new(0.3, 1.5, 0.0));
        let bary = [Vec2::ZERO, Vec2::X, Vec2::Y];
        assert_eq!(uv_partials(e1, e2, bary), (e1, e2));
        let swapped = [Vec2::ZERO, Vec2::new(0.0, 0.5), Vec2::new(2.0, 0.0)];
        let (du, dv) = uv_partials(e1, e2, swapped);
        assert!(du.abs_diff_eq(0.5 * e2, 1e-6) && dv.abs_diff_eq(2.0 * e1, 1e-6));
        let line = [Vec2::ZERO, Vec2::X, Vec2::new(2.0, 0.0)];
        let (du, dv) = uv_partials(e1, e2, line);
        assert_eq!((du, dv), (Vec3::ZERO, Vec3::ZERO));
        assert_eq!(
            bumped_normal(Vec3::Z, Vec3::Z, du, dv, Vec2::new(0.3, -0.2)),
            None
        );
    }

    /// A normal map's colour is a normal in the frame of `ns` and `∂p/∂u`: the flat colour
    /// (0.5, 0.5, 1) gives `ns`; red tilts toward `∂p/∂u` (made orthogonal to `ns`), green
    /// toward `ns × ∂p/∂u`; a length-free colour is normalised; a partial along `ns` gives no
    /// tangent and no normal.
    #[test]
    fn normal_map_colours_in_the_tangent_frame() {
        let ns = Vec3::new(0.0, 0.6, 0.8);
        let dp_du = Vec3::new(2.0, 0.3, 0.0); // not orthogonal to ns
        let s = (dp_du - ns * ns.dot(dp_du)).normalize();
        let t = ns.cross(s);
        let flat = mapped_normal(ns, dp_du, Rgb::new(0.5, 0.5, 1.0)).unwrap();
        assert!(flat.abs_diff_eq(ns, 1e-6), "{flat}");
        let red = mapped_normal(ns, dp_du, Rgb::new(1.0, 0.5, 0.5)).unwrap();
        assert!(red.abs_diff_eq(s, 1e-6), "{red}");
        let green = mapped_normal(ns, dp_du, Rgb::new(0.5, 1.0, 0.5)).unwrap();
        assert!(green.abs_diff_eq(t, 1e-6), "{green}");
        let tilted = mapped_normal(ns, dp_du, Rgb::new(0.75, 0.5, 0.75)).unwrap();
        assert!(tilted.abs_diff_eq((s + ns).normalize(), 1e-6), "{tilted}");
        assert_eq!(mapped_normal(ns, ns * 3.0, Rgb::new(0.6, 0.5, 1.0)), None);
        assert_eq!(mapped_normal(ns, dp_du, Rgb::splat(0.5)), None);
    }

    /// The flip mirrors the bumped normal about the shading normal exactly where `wo` lies on
    /// different sides of the two, and the shadowing term is 1 at normal incidence and falls
    /// toward grazing.
    #[test]
    fn flip_and_shadowing() {
        let n = Vec3::new(0.5, 0.0, 0.75f32.sqrt());
        let map = BumpMap {
            texture: 0,
            source: NormalSource::Height { scale: 1.0 },
            flip_invalid_normals: true,
            shadowing: true,
            nested_two_sided: false,
        };
        let bump = Bump::new(&map, &Frame::from_z(Vec3::Z), n);
        let n = bump.normal_local;
        let below_bumped = Vec3::new(-0.9, 0.0, 0.1f32).normalize();
        assert!(below_bumped.dot(n) < 0.0);
        assert_eq!(bump.normal_for(below_bumped), Vec3::new(-n.x, -n.y, n.z));
        assert_eq!(bump.normal_for(Vec3::new(0.2, 0.1, 0.9).normalize()), n);
        assert_eq!(bump.shadowing(Vec3::Z), 1.0);
        let (g45, g85) = (
            bump.shadowing(Vec3::new(1.0, 0.0, 1.0).normalize()),
            bump.shadowing(Vec3::new(
                85f32.to_radians().sin(),
                0.0,
                85f32.to_radians().cos(),
            )),
        );
        assert!(1.0 > g45 && g45 > g85 && g85 > 0.0, "{g45} {g85}");
    }
}
