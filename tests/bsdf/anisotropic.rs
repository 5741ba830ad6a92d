//! Anisotropic microfacet distributions (`MicrofacetDistribution::anisotropic`, the
//! principled BSDF's main lobe): visible normals drawn by stretching the configuration to
//! roughness 1 follow the density `D(m) G1(wi) max(0, wi·m) / cos θ_i`. The normalisation of
//! `D` and of that density (which checks Smith's masking of the projected roughness) are
//! `bsdf/microfacet.rs`.

use crate::common::chi2::ChiSquareTest;
use crate::common::sidak;
use crate::dir;
use footprint::bsdf::microfacet::{Microfacet, MicrofacetDistribution};
use glam::Vec3;

/// Chi-square of the sampled normals against the density over the upper hemisphere, GGX and
/// Beckmann, rough along either axis, from normal, oblique and grazing incidence at azimuths
/// between the axes: one test at 1% Šidák-corrected over the cases (fixed seed).
#[test]
fn anisotropic_visible_normals_chi_square() {
    let mut cases = Vec::new();
    for kind in [Microfacet::Ggx, Microfacet::Beckmann] {
        for (au, av) in [(0.1f32, 0.5f32), (0.7, 0.2)] {
            for wi in [dir(0.0, 0.0), dir(50.0, 20.0), dir(80.0, 110.0)] {
                cases.push((MicrofacetDistribution::anisotropic(kind, au, av), wi));
            }
        }
    }
    let alpha = sidak(0.01, cases.len());
    for (distr, wi) in &cases {
        let test = ChiSquareTest {
            axis: Vec3::Z,
            theta_max: std::f64::consts::FRAC_PI_2,
            res_theta: 40,
            res_phi: 80,
            samples: 1_000_000,
            integration_res: 12,
            seed: 11,
        };
        let r = test.run(
            |rng| Some(distr.sample_visible(*wi, rng.uniform2())),
            |m| distr.pdf_visible(*wi, m) as f64,
        );
        eprintln!(
            "{distr:?} wi {wi}: chi2 {:.1} dof {} p {:.3e} integral {:.4}",
            r.chi2, r.dof, r.p_value, r.integral
        );
        assert!(
            r.p_value > alpha,
            "{distr:?} wi {wi}: sampling disagrees with the density (p = {:.3e} < {alpha:.3e})",
            r.p_value
        );
    }
}
