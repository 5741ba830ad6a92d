//! BSDFs at a surface point, evaluated in the local shading frame.
//!
//! Conventions (as pbrt-v4): `wo` points from the surface toward where the path came from
//! (the camera side in radiance mode, the light side in importance mode), `wi` is the other
//! direction, the one being sampled. `eval` returns `f(wo, wi)` without any cosine; the
//! estimator multiplies by `|wi · n_s|`. Every call takes a [`TransportMode`]:
//!
//! * refraction scales radiance by `1/η²` but not importance (Veach 1997, §5.2);
//! * shading normals make the BSDF non-symmetric; in importance mode the adjoint BSDF carries
//!   the correction `|wo·n_s| |wi·n_g| / (|wo·n_g| |wi·n_s|)` (Veach 1997, eq. 5.19).
//!
//! Lobes: Lambertian; a normalised Blinn lobe layered over it; a perfect mirror; a smooth
//! dielectric with coloured transmittance. The Blinn lobe is
//! `f = k_s (n+1)/(8π) · cos^n θ_h / ((h·wi) · max(cos θ_i, cos θ_o))`
//! (Ashikhmin & Shirley 2000 without the Fresnel factor): reciprocal, its albedo is at most
//! `k_s` for every exponent, and sampling the half vector with density
//! `(n+1)/(2π) cos^n θ_h` gives a sample weight of at most `k_s`.
//!
//! The Mitsuba 3 kinds evaluate to what Mitsuba's plugins of the same names evaluate to
//! (`eval` there includes the cosine, here it does not):
//!
//! * `conductor`: a mirror of weight `k_s F_c(cos θ)`, `F_c` the conductor Fresnel term of
//!   `η + i k` ([`crate::bsdf::fresnel`]);
//! * `roughconductor`: `k_s F_c(wo·h) D(h) G(wo, wi) / (4 cos θ_o cos θ_i)` with the
//!   distributions of [`crate::bsdf::microfacet`], sampled by visible normals;
//! * `plastic`: a mirror of weight `k_s F(cos θ_o)` over a Lambertian base seen through the
//!   interface, `f = k_d' (1 - F(cos θ_o)) (1 - F(cos θ_i)) / (π η²)` with
//!   `k_d' = k_d / (1 - F_dr)` (`k_d / (1 - k_d F_dr)` when `nonlinear`), `F_dr` the diffuse
//!   reflectance of the interface seen from inside; the lobe is chosen with probability
//!   ∝ `F w_s` for the mirror and `(1 - F)(1 - w_s)` for the base, `w_s` = mean(k_s) /
//!   (mean(k_d) + mean(k_s));
//! * `roughplastic`: the microfacet reflection of a dielectric, `k_s F(wo·h) D G / (4 cos
//!   cos)`, plus the base `k_d' t(cos θ_o) t(cos θ_i) / (π η²)`, `t` the coating's tabled
//!   transmittance and `k_d'` divided by its tabled internal reflectance
//!   ([`crate::bsdf::rough_plastic`]); lobe probabilities as plastic with `1 - t` for `F`;
//! * `roughdielectric`: microfacet reflection `k_s F(wo·h) D G / (4 |cos θ_o| |cos θ_i|)`
//!   and refraction `T |(wo·m)(wi·m)| (1 - F) D G / (|cos θ_o| |cos θ_i| (wo·m + η wi·m)²)`
//!   in radiance mode, times `η²` in importance mode (`m ∝ wo + η wi`, `η` the relative
//!   index of the crossing, `T` the constant transmittance of one crossing; Walter et al.
//!   2007, eqs. 20-21), sampled by visible normals with reflection chosen with probability
//!   `F` ([`crate::bsdf::rough_glass`]); entering or leaving read from `cos θ_o` in the
//!   shading frame, as smooth glass;
//! * `thindielectric`: reflection `R' = 2R/(1 + R)` (the sheet's inner reflections summed),
//!   straight transmission `1 - R'` (`wi = -wo`), with `k_s` and `T_f` as factors and no
//!   `1/η²` (the ray leaves into the medium it came from);
//! * `principled`: the Disney BSDF (Burley 2012, 2015) as Mitsuba 3.9 evaluates and samples
//!   it: anisotropic GGX reflection and refraction, a GTR1 clearcoat, a retro-reflective
//!   diffuse lobe with sheen and fake subsurface ([`crate::bsdf::principled`]); reflection
//!   only, from the front, unless it transmits (`spec_trans > 0`), then on both sides in
//!   the shading frame, as the rough dielectric. Its anisotropic lobe's tangent is the
//!   surface's `∂p/∂u`, as Mitsuba's shading frame.
//!
//! Sidedness: two-sided surfaces reflect on whichever side of the shading normal `wo` is (the
//! frame is flipped to it, as Mitsuba's `twosided` flips where `cos θ_i < 0`); a one-sided
//! surface (Mitsuba's BSDFs unless wrapped in `twosided`) is black unless both directions are
//! above the shading normal, as Mitsuba evaluates it. Glass, rough glass and thin glass
//! scatter on both sides regardless. The front is the side the shading normal faces,
//! also where a mesh is wound against its vertex normals (`SurfaceHit::facing_ng`). Glass
//! reads wo's side in the shading frame, as Mitsuba's `dielectric` (`cos θ_i`): near a smooth
//! mesh's silhouette, where wo is above the geometric normal and below the shading normal,
//! the path arrives from inside, and the direction the shading frame gives stands even across
//! the geometric plane. The geometric normal decides nothing here, as in Mitsuba, which
//! evaluates every BSDF in the shading frame alone: where shading normals are tilted against
//! the faces, a reflection may arrive from or leave below the geometric plane (`scenes/ltcheck`,
//! whose panel is seen from its back through tilted normals, agrees with Mitsuba block by
//! block only so; a rule that also asked both directions to lie on one side of the geometric
//! normal left it 10-30% darker there).
//!
//! Blends (Mitsuba's `blendbsdf`, [`crate::bsdf::blend`]): `(1 - w) f₀ + w f₁` with the
//! densities mixed alike; the second component's lobes ride along in [`Bsdf::blend`].
//!
//! Bump maps (Mitsuba's `bumpmap`, [`crate::bsdf::bump`]): the lobes are evaluated and
//! sampled about a normal tilted by a height field's gradient, mirrored per call to the side
//! `wo` arrives from (`flip_invalid_normals`), with the terminator's shadowing term on `f`.
//! The frame of the cosine and of the adjoint correction stays the surface's shading frame:
//! `f` is Mitsuba's cosine-weighted value divided by `|wi·n_s|` of that frame, so that every
//! integrator's `f |wi·n_s|`, every sample weight and the importance-mode correction are
//! Mitsuba's.
//!
//! The lobes a material resolves to at a point, with their `f` and densities in the local
//! frame, are in `lobes.rs` (the Blinn lobe in `blinn.rs`); the BSDF at a point, which adds
//! the shading frame, the sidedness and the adjoint correction and samples the lobes, in
//! `surface.rs`.

pub mod blend;
mod blinn;
pub mod bump;
pub mod fresnel;
mod lobes;
pub mod material;
pub mod microfacet;
pub mod principled;
pub mod rough_glass;
pub mod rough_plastic;
mod surface;

pub use crate::bsdf::fresnel::{fresnel_conductor, fresnel_dielectric};
pub use crate::bsdf::lobes::{Lobes, SurfaceLobes};
pub use crate::bsdf::surface::{Bsdf, BsdfSample, TransportMode};
