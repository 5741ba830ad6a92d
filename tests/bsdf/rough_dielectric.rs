//! The rough dielectric (Mitsuba 3's `roughdielectric`): its values against Mitsuba 3's on
//! both sides and in both transport modes, importance mode as the adjoint of radiance mode,
//! radiance's generalised reciprocity, and the white furnace against an independent
//! quadrature of the interface's albedo.

use crate::common::{mean_stderr, normal_quantile, sidak};
use crate::configs::{ROUGH_GLASS_ETA, rough_glass, rough_glass_configs};
use crate::reciprocity::check_adjoint_and_reciprocity;
use crate::{MitsubaRow, check_mitsuba_row, dir, flat_bsdf};
use footprint::Rgb;
use footprint::bsdf::material::Material;
use footprint::bsdf::microfacet::{Microfacet, MicrofacetDistribution, gauss_legendre_01};
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use footprint::rng::Rng;
use glam::Vec3;

/// The factors scripts/mitsuba_bsdf_values.py gives Mitsuba's `roughdielectric`.
const MI_KS: Rgb = Rgb::new(0.9, 0.8, 1.0);
const MI_KT: Rgb = Rgb::new(0.7, 0.9, 0.8);

/// The BSDF the script names `roughdielectric_{distribution}_a{alpha}`.
fn mitsuba_rough_glass(name: &str) -> Bsdf {
    let rest = name.strip_prefix("roughdielectric_").unwrap();
    let (dist, roughness) = rest.split_once('_').unwrap();
    let kind = match dist {
        "ggx" => Microfacet::Ggx,
        "beckmann" => Microfacet::Beckmann,
        _ => panic!("{name}"),
    };
    // `a<alpha>`, or `u<alpha_u>_v<alpha_v>` (anisotropic).
    let (alpha, alpha_v) = match roughness.strip_prefix('a') {
        Some(a) => (a.parse().unwrap(), None),
        None => {
            let (u, v) = roughness.split_once("_v").unwrap();
            (u[1..].parse().unwrap(), Some(v.parse().unwrap()))
        }
    };
    flat_bsdf(&Material {
        alpha_v,
        ..rough_glass(kind, alpha, MI_KS, MI_KT)
    })
}

/// `eval` and `pdf` agree with Mitsuba 3's to 1e-3 on both sides, reflection and refraction,
/// in both modes, about the lobes' peaks and in their tails; Beckmann densities to 4e-3
/// (they use the exact Smith masking the sampler follows, Mitsuba the 0.35%-accurate rational
/// approximation its `eval` also uses, as ours does).
#[test]
fn rough_dielectric_matches_mitsuba_3() {
    let mut worst = (0.0f32, 0.0f32);
    for row in MITSUBA_ROUGH_DIELECTRIC {
        let pdf_tol = if row.0.contains("beckmann") {
            4e-3
        } else {
            1e-3
        };
        let (f_err, pdf_err) = check_mitsuba_row(&mitsuba_rough_glass(row.0), row, pdf_tol);
        worst = (worst.0.max(f_err), worst.1.max(pdf_err));
    }
    eprintln!(
        "{} rows; largest relative difference: f {:.2e}, pdf {:.2e}",
        MITSUBA_ROUGH_DIELECTRIC.len(),
        worst.0,
        worst.1
    );
}

/// `f*(wo, wi) = f(wi, wo) |wo·n_s| |wi·n_g| / (|wo·n_g| |wi·n_s|)` (Veach 1997, eq. 5.19):
/// importance mode is the adjoint of radiance mode, refraction included (which is what the
/// `1/η²` of radiance mode makes it), flat and under a tilted shading normal; and radiance
/// is reciprocal in the generalised sense `f(a, b) / η_a² = f(b, a) / η_b²` (Veach 1997,
/// eq. 5.14), `η_x` the index on `x`'s side. Pairs come from the BSDF's own sampling, so
/// that they lie where narrow lobes are non-zero.
#[test]
fn rough_dielectric_adjoint_and_reciprocity() {
    let configs = rough_glass_configs();
    let checked = check_adjoint_and_reciprocity(&configs, 31, |c, v| {
        if v.dot(c.bsdf.frame.z) > 0.0 {
            1.0
        } else {
            ROUGH_GLASS_ETA
        }
    });
    assert!(checked > configs.len() * 1000, "only {checked} pairs");
}

/// White furnace: a rough dielectric with white factors. In importance mode `∫ f cos` is the
/// fraction of the light reflected or refracted, `R + T <= 1`, short of 1 by the microfacet
/// model's single-scattering loss; in radiance mode the refracted part is `T/η²`, `η` the
/// relative index of the crossing. `R` and `T` come independently of `eval`, `pdf` and
/// `sample`: by Gauss-Legendre quadrature over the visible-normal sample space of
/// `∫ D_wo(m) F G1(wi, m) dm` and `∫ D_wo(m) (1 - F) G1(wt, m) dm`
/// ([`MicrofacetDistribution::dielectric_reflectance`], `_transmittance`), times
/// `G1(wo)/G1_sampled(wo)`: the visible normals drawn follow the exact Smith masking, `f`'s
/// `G1(wo)` the rational approximation for Beckmann (1 for GGX).
///
/// Bound: the sampled mean of `f cos / pdf` (200,000 samples of bounded weights, a mean close
/// to normal; fixed seed) against the quadrature, two-sided z-test at 1% Šidák-corrected over
/// all cases, plus twice the quadrature's own error (n against n/2 nodes; the integrand's
/// slope is infinite at the critical angle, so from inside it converges slowly) and the
/// weights' f32 rounding.
#[test]
fn rough_dielectric_white_furnace() {
    let thetas_in = [0.0f32, 30.0, 60.0, 85.0];
    // From inside: normal, oblique, beyond the smooth critical angle (41.8°), grazing.
    let thetas_out = [180.0f32, 150.0, 120.0, 95.0];
    let kinds = [Microfacet::Ggx, Microfacet::Beckmann];
    let alphas = [0.01f32, 0.1, 0.5];
    let cases = kinds.len() * alphas.len() * (thetas_in.len() + thetas_out.len()) * 2;
    let z = normal_quantile(1.0 - 0.5 * sidak(0.01, cases));
    // Rules of n and n/2 nodes per side: GGX's visible normals are cheap to draw, and its
    // quadrature from inside needs more nodes than Beckmann's (the concentric disc mapping
    // folds the critical angle's circle along its diagonals).
    let rules = |kind| {
        let n = if kind == Microfacet::Ggx { 256 } else { 128 };
        (gauss_legendre_01(n), gauss_legendre_01(n / 2))
    };
    let mut rng = Rng::new(37, 0, 0);
    let n = 200_000;
    let mut largest_loss = 0.0f64;
    for kind in kinds {
        for alpha in alphas {
            let b = flat_bsdf(&rough_glass(kind, alpha, Rgb::ONE, Rgb::ONE));
            let distr = MicrofacetDistribution::new(kind, alpha);
            let (nodes, nodes_coarse) = rules(kind);
            for theta in thetas_in.iter().chain(&thetas_out) {
                let wo = dir(*theta, 10.0);
                let up = wo * wo.z.signum();
                let eta = if wo.z > 0.0 {
                    ROUGH_GLASS_ETA
                } else {
                    1.0 / ROUGH_GLASS_ETA
                };
                let quad = |nodes: &[(f64, f64)]| {
                    (
                        distr.dielectric_reflectance(up.z, eta, nodes),
                        distr.dielectric_transmittance(up.z, eta, nodes),
                    )
                };
                let (r, t) = quad(&nodes);
                let (r2, t2) = quad(&nodes_coarse);
                let masking = (distr.g1_front(up) / distr.g1_sampled_front(up)) as f64;
                for mode in [TransportMode::Importance, TransportMode::Radiance] {
                    let t_scale = match mode {
                        TransportMode::Importance => 1.0,
                        TransportMode::Radiance => 1.0 / (eta * eta) as f64,
                    };
                    let expect = (r + t * t_scale) * masking;
                    // The quadrature's error, and the f32 rounding of the weights (about 1e-7
                    // each, 1e-5 allowed: it does not average out where every weight is 1).
                    let quad_err =
                        2.0 * ((r - r2).abs() + (t - t2).abs() * t_scale) * masking + 1e-5 * expect;
                    let xs: Vec<f64> = (0..n)
                        .map(|_| {
                            b.sample(wo, rng.uniform(), rng.uniform2(), mode)
                                .map(|s| s.weight.x as f64)
                                .unwrap_or(0.0)
                        })
                        .collect();
                    let (m, se) = mean_stderr(&xs);
                    eprintln!(
                        "{kind:?} α={alpha} θ={theta} {mode:?}: {m:.5} ± {se:.5}, quadrature {expect:.5} ± {quad_err:.5} (R {r:.4}, T {t:.4})"
                    );
                    assert!(
                        (m - expect).abs() <= z * se + quad_err,
                        "{kind:?} α={alpha} θ={theta} {mode:?}: sampled {m} ± {se} vs quadrature {expect} (z {z:.2})"
                    );
                    if mode == TransportMode::Importance {
                        assert!(
                            m <= 1.0 + 1e-5 + z * se,
                            "{kind:?} α={alpha} θ={theta}: albedo {m} ± {se} exceeds 1"
                        );
                        largest_loss = largest_loss.max(1.0 - m);
                    }
                }
            }
        }
    }
    eprintln!("largest single-scattering loss: {largest_loss:.4}");
}

/// Both sides are read from the shading frame, whatever the surface's sidedness flag and
/// whichever side of the geometric normal the directions are on: seen from inside, the
/// surface refracts out as the flat interface does.
#[test]
fn rough_dielectric_reads_its_side_from_the_shading_frame() {
    let m = rough_glass(Microfacet::Ggx, 0.2, MI_KS, MI_KT);
    let one_sided = flat_bsdf(&m);
    let two_sided = flat_bsdf(&footprint::bsdf::material::Material {
        two_sided: true,
        ..m.clone()
    });
    let (wo, wi) = (dir(150.0, 0.0), dir(30.0, 180.0));
    let f = one_sided.eval(wo, wi, TransportMode::Radiance);
    assert!(f.max_element() > 0.0, "no refraction out of the inside");
    assert_eq!(f, two_sided.eval(wo, wi, TransportMode::Radiance));
    // A shading normal tilted 30° about x: wo is above the geometric normal but below the
    // shading normal, so the path arrives from inside.
    let ns = dir(30.0, 90.0);
    let tilted = Bsdf::new(Lobes::new(&m, Rgb::ZERO, MI_KS), ns, Vec3::Z);
    let wo = dir(75.0, 270.0);
    assert!(wo.dot(Vec3::Z) > 0.0 && wo.dot(ns) < 0.0);
    let mut rng = Rng::new(41, 0, 0);
    let mut out = 0;
    for _ in 0..1000 {
        if let Some(s) = tilted.sample(wo, rng.uniform(), rng.uniform2(), TransportMode::Radiance) {
            out += usize::from(s.wi.dot(ns) > 0.0);
            assert!(s.weight.is_finite() && s.weight.min_element() >= 0.0);
        }
    }
    assert!(out > 0, "nothing refracted out through the shading frame");
}

// Generated by scripts/mitsuba_bsdf_values.py with Mitsuba 3.9.1 (variant scalar_rgb).
// (name, importance mode, wo (theta, phi deg), wi (theta, phi deg), f = eval / |cos(wi)|,
// pdf); int_ior 1.5, ext_ior 1, specular_reflectance and _transmittance as in the test.
#[rustfmt::skip]
#[allow(clippy::excessive_precision)]
const MITSUBA_ROUGH_DIELECTRIC: &[MitsubaRow] = &[
    ("roughdielectric_ggx_a0.01", false, [5.0000, 20.0000], [5.0000, 200.0000], [2.8867840e+01, 2.5660303e+01, 3.2075379e+01], 3.1953331e+01),
    ("roughdielectric_ggx_a0.01", true, [5.0000, 20.0000], [5.0000, 200.0000], [2.8867840e+01, 2.5660303e+01, 3.2075379e+01], 3.1953331e+01),
    ("roughdielectric_ggx_a0.01", false, [5.0000, 20.0000], [5.1960, 200.5384], [2.7165829e+01, 2.4147406e+01, 3.0184256e+01], 3.0060228e+01),
    ("roughdielectric_ggx_a0.01", true, [5.0000, 20.0000], [5.1960, 200.5384], [2.7165829e+01, 2.4147406e+01, 3.0184256e+01], 3.0060228e+01),
    ("roughdielectric_ggx_a0.01", false, [5.0000, 20.0000], [3.6540, 199.5101], [5.0850381e+00, 4.5200339e+00, 5.6500423e+00], 5.6385565e+00),
    ("roughdielectric_ggx_a0.01", true, [5.0000, 20.0000], [3.6540, 199.5101], [5.0850381e+00, 4.5200339e+00, 5.6500423e+00], 5.6385565e+00),
    ("roughdielectric_ggx_a0.01", false, [5.0000, 20.0000], [176.6690, 200.0000], [8.5128257e+03, 1.0945062e+04, 9.7289438e+03], 2.7316422e+04),
    ("roughdielectric_ggx_a0.01", true, [5.0000, 20.0000], [176.6690, 200.0000], [1.9153856e+04, 2.4626387e+04, 2.1890122e+04], 2.7316422e+04),
    ("roughdielectric_ggx_a0.01", false, [5.0000, 20.0000], [176.8650, 200.5384], [1.9849619e+03, 2.5520940e+03, 2.2685280e+03], 6.3706860e+03),
    ("roughdielectric_ggx_a0.01", true, [5.0000, 20.0000], [176.8650, 200.5384], [4.4661638e+03, 5.7422102e+03, 5.1041870e+03], 6.3706860e+03),
    ("roughdielectric_ggx_a0.01", false, [5.0000, 20.0000], [175.3230, 199.5101], [3.3853865e+00, 4.3526397e+00, 3.8690135e+00], 1.0845367e+01),
    ("roughdielectric_ggx_a0.01", true, [5.0000, 20.0000], [175.3230, 199.5101], [7.6171195e+00, 9.7934393e+00, 8.7052794e+00], 1.0845367e+01),
    ("roughdielectric_ggx_a0.01", false, [35.0000, 0.0000], [35.0000, 180.0000], [4.5956450e+01, 4.0850180e+01, 5.1062725e+01], 4.1828640e+01),
    ("roughdielectric_ggx_a0.01", true, [35.0000, 0.0000], [35.0000, 180.0000], [4.5956450e+01, 4.0850180e+01, 5.1062725e+01], 4.1828640e+01),
    ("roughdielectric_ggx_a0.01", false, [35.0000, 0.0000], [35.1960, 180.5384], [3.5588154e+01, 3.1633916e+01, 3.9542394e+01], 3.2313858e+01),
    ("roughdielectric_ggx_a0.01", true, [35.0000, 0.0000], [35.1960, 180.5384], [3.5588154e+01, 3.1633916e+01, 3.9542394e+01], 3.2313858e+01),
    ("roughdielectric_ggx_a0.01", false, [35.0000, 0.0000], [33.6540, 179.5101], [7.3997919e+00, 6.5775931e+00, 8.2219913e+00], 6.8440552e+00),
    ("roughdielectric_ggx_a0.01", true, [35.0000, 0.0000], [33.6540, 179.5101], [7.3997919e+00, 6.5775931e+00, 8.2219913e+00], 6.8440552e+00),
    ("roughdielectric_ggx_a0.01", false, [35.0000, 0.0000], [157.5186, 180.0000], [6.6356584e+03, 8.5315607e+03, 7.5836098e+03], 1.9708070e+04),
    ("roughdielectric_ggx_a0.01", true, [35.0000, 0.0000], [157.5186, 180.0000], [1.4930230e+04, 1.9196009e+04, 1.7063119e+04], 1.9708070e+04),
    ("roughdielectric_ggx_a0.01", false, [35.0000, 0.0000], [157.7146, 180.5384], [9.7569265e+02, 1.2544620e+03, 1.1150774e+03], 2.9019163e+03),
    ("roughdielectric_ggx_a0.01", true, [35.0000, 0.0000], [157.7146, 180.5384], [2.1953086e+03, 2.8225396e+03, 2.5089241e+03], 2.9019163e+03),
    ("roughdielectric_ggx_a0.01", false, [35.0000, 0.0000], [156.1726, 179.5101], [5.7033603e+00, 7.3328915e+00, 6.5181264e+00], 1.6769793e+01),
    ("roughdielectric_ggx_a0.01", true, [35.0000, 0.0000], [156.1726, 179.5101], [1.2832561e+01, 1.6499006e+01, 1.4665784e+01], 1.6769793e+01),
    ("roughdielectric_ggx_a0.01", false, [70.0000, 130.0000], [70.0000, 310.0000], [1.0468142e+03, 9.3050161e+02, 1.1631270e+03], 3.9788779e+02),
    ("roughdielectric_ggx_a0.01", true, [70.0000, 130.0000], [70.0000, 310.0000], [1.0468142e+03, 9.3050161e+02, 1.1631270e+03], 3.9788779e+02),
    ("roughdielectric_ggx_a0.01", false, [70.0000, 130.0000], [70.1960, 310.5384], [1.4460453e+02, 1.2853736e+02, 1.6067170e+02], 5.4446632e+01),
    ("roughdielectric_ggx_a0.01", true, [70.0000, 130.0000], [70.1960, 310.5384], [1.4460453e+02, 1.2853736e+02, 1.6067170e+02], 5.4446632e+01),
    ("roughdielectric_ggx_a0.01", false, [70.0000, 130.0000], [68.6540, 309.5101], [6.9763466e+01, 6.2011972e+01, 7.7514965e+01], 2.8220007e+01),
    ("roughdielectric_ggx_a0.01", true, [70.0000, 130.0000], [68.6540, 309.5101], [6.9763466e+01, 6.2011972e+01, 7.7514965e+01], 2.8220007e+01),
    ("roughdielectric_ggx_a0.01", false, [70.0000, 130.0000], [141.2104, 310.0000], [2.6990901e+03, 3.4702587e+03, 3.0846746e+03], 6.7623564e+03),
    ("roughdielectric_ggx_a0.01", true, [70.0000, 130.0000], [141.2104, 310.0000], [6.0729522e+03, 7.8080813e+03, 6.9405168e+03], 6.7623564e+03),
    ("roughdielectric_ggx_a0.01", false, [70.0000, 130.0000], [141.4064, 310.5384], [4.7114763e+02, 6.0576121e+02, 5.3845442e+02], 1.1836614e+03),
    ("roughdielectric_ggx_a0.01", true, [70.0000, 130.0000], [141.4064, 310.5384], [1.0600820e+03, 1.3629626e+03, 1.2115224e+03], 1.1836614e+03),
    ("roughdielectric_ggx_a0.01", false, [70.0000, 130.0000], [139.8644, 309.5101], [1.8184803e+01, 2.3380461e+01, 2.0782633e+01], 4.4687931e+01),
    ("roughdielectric_ggx_a0.01", true, [70.0000, 130.0000], [139.8644, 309.5101], [4.0915810e+01, 5.2606040e+01, 4.6760927e+01], 4.4687931e+01),
    ("roughdielectric_ggx_a0.01", false, [160.0000, 30.0000], [160.0000, 210.0000], [3.3844723e+01, 3.0084201e+01, 3.7605250e+01], 3.5337494e+01),
    ("roughdielectric_ggx_a0.01", true, [160.0000, 30.0000], [160.0000, 210.0000], [3.3844723e+01, 3.0084201e+01, 3.7605250e+01], 3.5337494e+01),
    ("roughdielectric_ggx_a0.01", false, [160.0000, 30.0000], [160.1960, 210.5384], [3.0158920e+01, 2.6807932e+01, 3.3509913e+01], 3.1528139e+01),
    ("roughdielectric_ggx_a0.01", true, [160.0000, 30.0000], [160.1960, 210.5384], [3.0158920e+01, 2.6807932e+01, 3.3509913e+01], 3.1528139e+01),
    ("roughdielectric_ggx_a0.01", false, [160.0000, 30.0000], [158.6540, 209.5101], [5.9430876e+00, 5.2827449e+00, 6.6034307e+00], 6.1504545e+00),
    ("roughdielectric_ggx_a0.01", true, [160.0000, 30.0000], [158.6540, 209.5101], [5.9430876e+00, 5.2827449e+00, 6.6034307e+00], 6.1504545e+00),
    ("roughdielectric_ggx_a0.01", false, [160.0000, 30.0000], [30.8659, 210.0000], [1.5814120e+04, 2.0332440e+04, 1.8073282e+04], 8.6187266e+03),
    ("roughdielectric_ggx_a0.01", true, [160.0000, 30.0000], [30.8659, 210.0000], [7.0284989e+03, 9.0366414e+03, 8.0325704e+03], 8.6187266e+03),
    ("roughdielectric_ggx_a0.01", false, [160.0000, 30.0000], [31.0619, 210.5384], [3.7339489e+03, 4.8007915e+03, 4.2673701e+03], 2.0308367e+03),
    ("roughdielectric_ggx_a0.01", true, [160.0000, 30.0000], [31.0619, 210.5384], [1.6595327e+03, 2.1336849e+03, 1.8966088e+03], 2.0308367e+03),
    ("roughdielectric_ggx_a0.01", false, [160.0000, 30.0000], [29.5199, 209.5101], [6.8476461e+01, 8.8041168e+01, 7.8258817e+01], 3.7833424e+01),
    ("roughdielectric_ggx_a0.01", true, [160.0000, 30.0000], [29.5199, 209.5101], [3.0433978e+01, 3.9129400e+01, 3.4781692e+01], 3.7833424e+01),
    ("roughdielectric_ggx_a0.01", false, [135.0000, 250.0000], [135.0000, 70.0000], [1.4323232e+03, 1.2731762e+03, 1.5914702e+03], 1.1253676e+03),
    ("roughdielectric_ggx_a0.01", true, [135.0000, 250.0000], [135.0000, 70.0000], [1.4323232e+03, 1.2731762e+03, 1.5914702e+03], 1.1253676e+03),
    ("roughdielectric_ggx_a0.01", false, [135.0000, 250.0000], [135.1960, 70.5384], [9.1581010e+02, 8.1405343e+02, 1.0175668e+03], 7.2200336e+02),
    ("roughdielectric_ggx_a0.01", true, [135.0000, 250.0000], [135.1960, 70.5384], [9.1581010e+02, 8.1405343e+02, 1.0175668e+03], 7.2200336e+02),
    ("roughdielectric_ggx_a0.01", false, [135.0000, 250.0000], [133.6540, 69.5101], [2.2197053e+02, 1.9730715e+02, 2.4663394e+02], 1.7025655e+02),
    ("roughdielectric_ggx_a0.01", true, [135.0000, 250.0000], [133.6540, 69.5101], [2.2197053e+02, 1.9730715e+02, 2.4663394e+02], 1.7025655e+02),
    ("roughdielectric_ggx_a0.01", false, [135.0000, 250.0000], [12.2473, 70.0000], [1.9263505e-05, 2.4767364e-05, 2.2015435e-05], 1.1952453e-05),
    ("roughdielectric_ggx_a0.01", true, [135.0000, 250.0000], [12.2473, 70.0000], [8.5615590e-06, 1.1007719e-05, 9.7846393e-06], 1.1952453e-05),
    ("roughdielectric_ggx_a0.01", false, [135.0000, 250.0000], [12.4433, 70.5384], [1.9836630e-05, 2.5504240e-05, 2.2670435e-05], 1.2298848e-05),
    ("roughdielectric_ggx_a0.01", true, [135.0000, 250.0000], [12.4433, 70.5384], [8.8162803e-06, 1.1335218e-05, 1.0075749e-05], 1.2298848e-05),
    ("roughdielectric_ggx_a0.01", false, [135.0000, 250.0000], [10.9013, 69.5101], [1.5630324e-05, 2.0096130e-05, 1.7863228e-05], 9.7449392e-06),
    ("roughdielectric_ggx_a0.01", true, [135.0000, 250.0000], [10.9013, 69.5101], [6.9468097e-06, 8.9316120e-06, 7.9392118e-06], 9.7449392e-06),
    ("roughdielectric_ggx_a0.01", false, [115.0000, 60.0000], [115.0000, 240.0000], [4.0090019e+03, 3.5635573e+03, 4.4544466e+03], 1.8827471e+03),
    ("roughdielectric_ggx_a0.01", true, [115.0000, 60.0000], [115.0000, 240.0000], [4.0090019e+03, 3.5635573e+03, 4.4544466e+03], 1.8827471e+03),
    ("roughdielectric_ggx_a0.01", false, [115.0000, 60.0000], [115.1960, 240.5384], [9.6080068e+02, 8.5404511e+02, 1.0675563e+03], 4.5452740e+02),
    ("roughdielectric_ggx_a0.01", true, [115.0000, 60.0000], [115.1960, 240.5384], [9.6080068e+02, 8.5404511e+02, 1.0675563e+03], 4.5452740e+02),
    ("roughdielectric_ggx_a0.01", false, [115.0000, 60.0000], [113.6540, 239.5101], [3.9411938e+02, 3.5032836e+02, 4.3791043e+02], 1.7571806e+02),
    ("roughdielectric_ggx_a0.01", true, [115.0000, 60.0000], [113.6540, 239.5101], [3.9411938e+02, 3.5032836e+02, 4.3791043e+02], 1.7571806e+02),
    ("roughdielectric_ggx_a0.01", false, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.01", true, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.01", false, [115.0000, 60.0000], [15.9729, 240.5384], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.01", true, [115.0000, 60.0000], [15.9729, 240.5384], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.01", false, [115.0000, 60.0000], [14.4309, 239.5101], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.01", true, [115.0000, 60.0000], [14.4309, 239.5101], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.1", false, [5.0000, 20.0000], [5.0000, 200.0000], [2.8866754e-01, 2.5659340e-01, 3.2074173e-01], 3.1952730e-01),
    ("roughdielectric_ggx_a0.1", true, [5.0000, 20.0000], [5.0000, 200.0000], [2.8866754e-01, 2.5659340e-01, 3.2074173e-01], 3.1952730e-01),
    ("roughdielectric_ggx_a0.1", false, [5.0000, 20.0000], [6.9596, 205.3840], [2.7239824e-01, 2.4213179e-01, 3.0266473e-01], 3.0044582e-01),
    ("roughdielectric_ggx_a0.1", true, [5.0000, 20.0000], [6.9596, 205.3840], [2.7239824e-01, 2.4213179e-01, 3.0266473e-01], 3.0044582e-01),
    ("roughdielectric_ggx_a0.1", false, [5.0000, 20.0000], [0.1000, 195.1009], [2.0620026e-01, 1.8328914e-01, 2.2911142e-01], 2.2911106e-01),
    ("roughdielectric_ggx_a0.1", true, [5.0000, 20.0000], [0.1000, 195.1009], [2.0620026e-01, 1.8328914e-01, 2.2911142e-01], 2.2911106e-01),
    ("roughdielectric_ggx_a0.1", false, [5.0000, 20.0000], [176.6690, 200.0000], [8.5125936e+01, 1.0944763e+02, 9.7286787e+01], 2.7315909e+02),
    ("roughdielectric_ggx_a0.1", true, [5.0000, 20.0000], [176.6690, 200.0000], [1.9153333e+02, 2.4625713e+02, 2.1889524e+02], 2.7315909e+02),
    ("roughdielectric_ggx_a0.1", false, [5.0000, 20.0000], [178.6286, 205.3840], [1.9903298e+01, 2.5589955e+01, 2.2746626e+01], 6.3956646e+01),
    ("roughdielectric_ggx_a0.1", true, [5.0000, 20.0000], [178.6286, 205.3840], [4.4782417e+01, 5.7577391e+01, 5.1179906e+01], 6.3956646e+01),
    ("roughdielectric_ggx_a0.1", false, [5.0000, 20.0000], [163.2089, 195.1009], [3.6644037e-02, 4.7113761e-02, 4.1878903e-02], 1.1278823e-01),
    ("roughdielectric_ggx_a0.1", true, [5.0000, 20.0000], [163.2089, 195.1009], [8.2449073e-02, 1.0600595e-01, 9.4227514e-02], 1.1278823e-01),
    ("roughdielectric_ggx_a0.1", false, [35.0000, 0.0000], [35.0000, 180.0000], [4.5845236e-01, 4.0751324e-01, 5.0939152e-01], 4.1777995e-01),
    ("roughdielectric_ggx_a0.1", true, [35.0000, 0.0000], [35.0000, 180.0000], [4.5845236e-01, 4.0751324e-01, 5.0939152e-01], 4.1777995e-01),
    ("roughdielectric_ggx_a0.1", false, [35.0000, 0.0000], [36.9596, 185.3840], [3.6248165e-01, 3.2220594e-01, 4.0275739e-01], 3.2228208e-01),
    ("roughdielectric_ggx_a0.1", true, [35.0000, 0.0000], [36.9596, 185.3840], [3.6248165e-01, 3.2220594e-01, 4.0275739e-01], 3.2228208e-01),
    ("roughdielectric_ggx_a0.1", false, [35.0000, 0.0000], [21.5399, 175.1009], [6.6622393e-02, 5.9219909e-02, 7.4024884e-02], 6.8881951e-02),
    ("roughdielectric_ggx_a0.1", true, [35.0000, 0.0000], [21.5399, 175.1009], [6.6622393e-02, 5.9219909e-02, 7.4024884e-02], 6.8881951e-02),
    ("roughdielectric_ggx_a0.1", false, [35.0000, 0.0000], [157.5186, 180.0000], [6.6248181e+01, 8.5176232e+01, 7.5712213e+01], 1.9684207e+02),
    ("roughdielectric_ggx_a0.1", true, [35.0000, 0.0000], [157.5186, 180.0000], [1.4905840e+02, 1.9164650e+02, 1.7035245e+02], 1.9684207e+02),
    ("roughdielectric_ggx_a0.1", false, [35.0000, 0.0000], [159.4782, 185.3840], [9.4897439e+00, 1.2201099e+01, 1.0845423e+01], 2.8577021e+01),
    ("roughdielectric_ggx_a0.1", true, [35.0000, 0.0000], [159.4782, 185.3840], [2.1351925e+01, 2.7452475e+01, 2.4402202e+01], 2.8577021e+01),
    ("roughdielectric_ggx_a0.1", false, [35.0000, 0.0000], [144.0585, 175.1009], [8.1263380e-02, 1.0448149e-01, 9.2872435e-02], 2.1175237e-01),
    ("roughdielectric_ggx_a0.1", true, [35.0000, 0.0000], [144.0585, 175.1009], [1.8284257e-01, 2.3508332e-01, 2.0896296e-01], 2.1175237e-01),
    ("roughdielectric_ggx_a0.1", false, [70.0000, 130.0000], [70.0000, 310.0000], [1.0094557e+01, 8.9729393e+00, 1.1216174e+01], 3.9072344e+00),
    ("roughdielectric_ggx_a0.1", true, [70.0000, 130.0000], [70.0000, 310.0000], [1.0094557e+01, 8.9729393e+00, 1.1216174e+01], 3.9072344e+00),
    ("roughdielectric_ggx_a0.1", false, [70.0000, 130.0000], [71.9596, 315.3840], [1.4692232e+00, 1.3059762e+00, 1.6324703e+00], 5.1720190e-01),
    ("roughdielectric_ggx_a0.1", true, [70.0000, 130.0000], [71.9596, 315.3840], [1.4692232e+00, 1.3059762e+00, 1.6324703e+00], 5.1720190e-01),
    ("roughdielectric_ggx_a0.1", false, [70.0000, 130.0000], [56.5399, 305.1009], [4.2870792e-01, 3.8107371e-01, 4.7634213e-01], 2.6412895e-01),
    ("roughdielectric_ggx_a0.1", true, [70.0000, 130.0000], [56.5399, 305.1009], [4.2870792e-01, 3.8107371e-01, 4.7634213e-01], 2.6412895e-01),
    ("roughdielectric_ggx_a0.1", false, [70.0000, 130.0000], [141.2104, 310.0000], [2.6462666e+01, 3.4023430e+01, 3.0243050e+01], 6.6405930e+01),
    ("roughdielectric_ggx_a0.1", true, [70.0000, 130.0000], [141.2104, 310.0000], [5.9540996e+01, 7.6552708e+01, 6.8046854e+01], 6.6405930e+01),
    ("roughdielectric_ggx_a0.1", false, [70.0000, 130.0000], [143.1700, 315.3840], [3.8639936e+00, 4.9679915e+00, 4.4159925e+00], 9.9550886e+00),
    ("roughdielectric_ggx_a0.1", true, [70.0000, 130.0000], [143.1700, 315.3840], [8.6939842e+00, 1.1177980e+01, 9.9359824e+00], 9.9550886e+00),
    ("roughdielectric_ggx_a0.1", false, [70.0000, 130.0000], [127.7503, 305.1009], [4.4171572e-01, 5.6792019e-01, 5.0481795e-01], 8.7284189e-01),
    ("roughdielectric_ggx_a0.1", true, [70.0000, 130.0000], [127.7503, 305.1009], [9.9386012e-01, 1.2778202e+00, 1.1358402e+00], 8.7284189e-01),
    ("roughdielectric_ggx_a0.1", false, [160.0000, 30.0000], [160.0000, 210.0000], [3.3822543e-01, 3.0064484e-01, 3.7580605e-01], 3.5325915e-01),
    ("roughdielectric_ggx_a0.1", true, [160.0000, 30.0000], [160.0000, 210.0000], [3.3822543e-01, 3.0064484e-01, 3.7580605e-01], 3.5325915e-01),
    ("roughdielectric_ggx_a0.1", false, [160.0000, 30.0000], [161.9596, 215.3840], [2.9776734e-01, 2.6468208e-01, 3.3085260e-01], 3.1467077e-01),
    ("roughdielectric_ggx_a0.1", true, [160.0000, 30.0000], [161.9596, 215.3840], [2.9776734e-01, 2.6468208e-01, 3.3085260e-01], 3.1467077e-01),
    ("roughdielectric_ggx_a0.1", false, [160.0000, 30.0000], [146.5399, 205.1009], [7.5275048e-02, 6.6911160e-02, 8.3638949e-02], 6.9853581e-02),
    ("roughdielectric_ggx_a0.1", true, [160.0000, 30.0000], [146.5399, 205.1009], [7.5275048e-02, 6.6911160e-02, 8.3638949e-02], 6.9853581e-02),
    ("roughdielectric_ggx_a0.1", false, [160.0000, 30.0000], [30.8659, 210.0000], [1.5794985e+02, 2.0307837e+02, 1.8051412e+02], 8.6159004e+01),
    ("roughdielectric_ggx_a0.1", true, [160.0000, 30.0000], [30.8659, 210.0000], [7.0199937e+01, 9.0257058e+01, 8.0228502e+01], 8.6159004e+01),
    ("roughdielectric_ggx_a0.1", false, [160.0000, 30.0000], [32.8255, 215.3840], [3.4409919e+01, 4.4241324e+01, 3.9325625e+01], 1.8378149e+01),
    ("roughdielectric_ggx_a0.1", true, [160.0000, 30.0000], [32.8255, 215.3840], [1.5293298e+01, 1.9662812e+01, 1.7478056e+01], 1.8378149e+01),
    ("roughdielectric_ggx_a0.1", false, [160.0000, 30.0000], [17.4058, 205.1009], [5.5902628e-01, 7.1874806e-01, 6.3888717e-01], 3.3876792e-01),
    ("roughdielectric_ggx_a0.1", true, [160.0000, 30.0000], [17.4058, 205.1009], [2.4845610e-01, 3.1944355e-01, 2.8394983e-01], 3.3876792e-01),
    ("roughdielectric_ggx_a0.1", false, [135.0000, 250.0000], [135.0000, 70.0000], [1.4252770e+01, 1.2669128e+01, 1.5836411e+01], 1.1225959e+01),
    ("roughdielectric_ggx_a0.1", true, [135.0000, 250.0000], [135.0000, 70.0000], [1.4252770e+01, 1.2669128e+01, 1.5836411e+01], 1.1225959e+01),
    ("roughdielectric_ggx_a0.1", false, [135.0000, 250.0000], [136.9596, 75.3840], [9.0835452e+00, 8.0742632e+00, 1.0092829e+01], 7.3926182e+00),
    ("roughdielectric_ggx_a0.1", true, [135.0000, 250.0000], [136.9596, 75.3840], [9.0835452e+00, 8.0742632e+00, 1.0092829e+01], 7.3926182e+00),
    ("roughdielectric_ggx_a0.1", false, [135.0000, 250.0000], [121.5399, 65.1009], [2.7551140e+00, 2.4489902e+00, 3.0612378e+00], 1.6118671e+00),
    ("roughdielectric_ggx_a0.1", true, [135.0000, 250.0000], [121.5399, 65.1009], [2.7551140e+00, 2.4489902e+00, 3.0612378e+00], 1.6118671e+00),
    ("roughdielectric_ggx_a0.1", false, [135.0000, 250.0000], [12.2473, 70.0000], [1.9210152e-03, 2.4698766e-03, 2.1954461e-03], 1.1920739e-03),
    ("roughdielectric_ggx_a0.1", true, [135.0000, 250.0000], [12.2473, 70.0000], [8.5378476e-04, 1.0977233e-03, 9.7575399e-04], 1.1920739e-03),
    ("roughdielectric_ggx_a0.1", false, [135.0000, 250.0000], [14.2069, 75.3840], [2.5244250e-03, 3.2456892e-03, 2.8850573e-03], 1.5540378e-03),
    ("roughdielectric_ggx_a0.1", true, [135.0000, 250.0000], [14.2069, 75.3840], [1.1219666e-03, 1.4425284e-03, 1.2822475e-03], 1.5540378e-03),
    ("roughdielectric_ggx_a0.1", false, [135.0000, 250.0000], [0.1000, 65.1009], [7.9137097e-05, 1.0174769e-04, 9.0442403e-05], 5.0245704e-05),
    ("roughdielectric_ggx_a0.1", true, [135.0000, 250.0000], [0.1000, 65.1009], [3.5172045e-05, 4.5221198e-05, 4.0196625e-05], 5.0245704e-05),
    ("roughdielectric_ggx_a0.1", false, [115.0000, 60.0000], [115.0000, 240.0000], [3.9202854e+01, 3.4846983e+01, 4.3558728e+01], 1.8617985e+01),
    ("roughdielectric_ggx_a0.1", true, [115.0000, 60.0000], [115.0000, 240.0000], [3.9202854e+01, 3.4846983e+01, 4.3558728e+01], 1.8617985e+01),
    ("roughdielectric_ggx_a0.1", false, [115.0000, 60.0000], [116.9596, 245.3840], [9.7315867e+00, 8.6502997e+00, 1.0812874e+01], 4.9490695e+00),
    ("roughdielectric_ggx_a0.1", true, [115.0000, 60.0000], [116.9596, 245.3840], [9.7315867e+00, 8.6502997e+00, 1.0812874e+01], 4.9490695e+00),
    ("roughdielectric_ggx_a0.1", false, [115.0000, 60.0000], [101.5399, 235.1009], [5.0929161e+00, 4.5270366e+00, 5.6587956e+00], 1.1962854e+00),
    ("roughdielectric_ggx_a0.1", true, [115.0000, 60.0000], [101.5399, 235.1009], [5.0929161e+00, 4.5270366e+00, 5.6587956e+00], 1.1962854e+00),
    ("roughdielectric_ggx_a0.1", false, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.1", true, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.1", false, [115.0000, 60.0000], [17.7365, 245.3840], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.1", true, [115.0000, 60.0000], [17.7365, 245.3840], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.1", false, [115.0000, 60.0000], [2.3168, 235.1009], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.1", true, [115.0000, 60.0000], [2.3168, 235.1009], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.5", false, [5.0000, 20.0000], [5.0000, 200.0000], [1.1536108e-02, 1.0254318e-02, 1.2817897e-02], 1.2775226e-02),
    ("roughdielectric_ggx_a0.5", true, [5.0000, 20.0000], [5.0000, 200.0000], [1.1536108e-02, 1.0254318e-02, 1.2817897e-02], 1.2775226e-02),
    ("roughdielectric_ggx_a0.5", false, [5.0000, 20.0000], [14.7982, 226.9202], [1.1261072e-02, 1.0009843e-02, 1.2512303e-02], 1.2149828e-02),
    ("roughdielectric_ggx_a0.5", true, [5.0000, 20.0000], [14.7982, 226.9202], [1.1261072e-02, 1.0009843e-02, 1.2512303e-02], 1.2149828e-02),
    ("roughdielectric_ggx_a0.5", false, [5.0000, 20.0000], [0.1000, 175.5046], [1.1371971e-02, 1.0108419e-02, 1.2635523e-02], 1.2635510e-02),
    ("roughdielectric_ggx_a0.5", true, [5.0000, 20.0000], [0.1000, 175.5046], [1.1371971e-02, 1.0108419e-02, 1.2635523e-02], 1.2635510e-02),
    ("roughdielectric_ggx_a0.5", false, [5.0000, 20.0000], [176.6690, 200.0000], [3.4027836e+00, 4.3750072e+00, 3.8888957e+00], 1.0921350e+01),
    ("roughdielectric_ggx_a0.5", true, [5.0000, 20.0000], [176.6690, 200.0000], [7.6562615e+00, 9.8437651e+00, 8.7500135e+00], 1.0921350e+01),
    ("roughdielectric_ggx_a0.5", false, [5.0000, 20.0000], [179.9000, 226.9202], [2.6770311e+00, 3.4418972e+00, 3.0594642e+00], 8.6047306e+00),
    ("roughdielectric_ggx_a0.5", true, [5.0000, 20.0000], [179.9000, 226.9202], [6.0233186e+00, 7.7442666e+00, 6.8837931e+00], 8.6047306e+00),
    ("roughdielectric_ggx_a0.5", false, [5.0000, 20.0000], [109.3685, 175.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.5", true, [5.0000, 20.0000], [109.3685, 175.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.5", false, [35.0000, 0.0000], [35.0000, 180.0000], [1.7335920e-02, 1.5409707e-02, 1.9262133e-02], 1.6248152e-02),
    ("roughdielectric_ggx_a0.5", true, [35.0000, 0.0000], [35.0000, 180.0000], [1.7335920e-02, 1.5409707e-02, 1.9262133e-02], 1.6248152e-02),
    ("roughdielectric_ggx_a0.5", false, [35.0000, 0.0000], [44.7982, 206.9202], [1.5920985e-02, 1.4151988e-02, 1.7689984e-02], 1.3283685e-02),
    ("roughdielectric_ggx_a0.5", true, [35.0000, 0.0000], [44.7982, 206.9202], [1.5920985e-02, 1.4151988e-02, 1.7689984e-02], 1.3283685e-02),
    ("roughdielectric_ggx_a0.5", false, [35.0000, 0.0000], [0.1000, 155.5046], [8.4563075e-03, 7.5167175e-03, 9.3958970e-03], 9.3958853e-03),
    ("roughdielectric_ggx_a0.5", true, [35.0000, 0.0000], [0.1000, 155.5046], [8.4563075e-03, 7.5167175e-03, 9.3958970e-03], 9.3958853e-03),
    ("roughdielectric_ggx_a0.5", false, [35.0000, 0.0000], [157.5186, 180.0000], [2.5505891e+00, 3.2793288e+00, 2.9149591e+00], 7.6555133e+00),
    ("roughdielectric_ggx_a0.5", true, [35.0000, 0.0000], [157.5186, 180.0000], [5.7388241e+00, 7.3784881e+00, 6.5586561e+00], 7.6555133e+00),
    ("roughdielectric_ggx_a0.5", false, [35.0000, 0.0000], [167.3168, 206.9202], [3.1927146e-01, 4.1049189e-01, 3.6488170e-01], 1.0043476e+00),
    ("roughdielectric_ggx_a0.5", true, [35.0000, 0.0000], [167.3168, 206.9202], [7.1836068e-01, 9.2360657e-01, 8.2098365e-01], 1.0043476e+00),
    ("roughdielectric_ggx_a0.5", false, [35.0000, 0.0000], [90.5000, 155.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.5", true, [35.0000, 0.0000], [90.5000, 155.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.5", false, [70.0000, 130.0000], [70.0000, 310.0000], [2.2998249e-01, 2.0442890e-01, 2.5553611e-01], 1.1795145e-01),
    ("roughdielectric_ggx_a0.5", true, [70.0000, 130.0000], [70.0000, 310.0000], [2.2998249e-01, 2.0442890e-01, 2.5553611e-01], 1.1795145e-01),
    ("roughdielectric_ggx_a0.5", false, [70.0000, 130.0000], [79.7982, 336.9202], [5.7608744e-02, 5.1207774e-02, 6.4009719e-02], 2.2407064e-02),
    ("roughdielectric_ggx_a0.5", true, [70.0000, 130.0000], [79.7982, 336.9202], [5.7608744e-02, 5.1207774e-02, 6.4009719e-02], 2.2407064e-02),
    ("roughdielectric_ggx_a0.5", false, [70.0000, 130.0000], [2.6995, 285.5046], [7.2885959e-03, 6.4787523e-03, 8.0984400e-03], 8.0905790e-03),
    ("roughdielectric_ggx_a0.5", true, [70.0000, 130.0000], [2.6995, 285.5046], [7.2885959e-03, 6.4787523e-03, 8.0984400e-03], 8.0905790e-03),
    ("roughdielectric_ggx_a0.5", false, [70.0000, 130.0000], [141.2104, 310.0000], [7.7020958e-01, 9.9026943e-01, 8.8023954e-01], 2.0046599e+00),
    ("roughdielectric_ggx_a0.5", true, [70.0000, 130.0000], [141.2104, 310.0000], [1.7329712e+00, 2.2281058e+00, 1.9805385e+00], 2.0046599e+00),
    ("roughdielectric_ggx_a0.5", false, [70.0000, 130.0000], [151.0086, 336.9202], [9.0214155e-03, 1.1598962e-02, 1.0310190e-02], 2.5841547e-02),
    ("roughdielectric_ggx_a0.5", true, [70.0000, 130.0000], [151.0086, 336.9202], [2.0298182e-02, 2.6097662e-02, 2.3197924e-02], 2.5841547e-02),
    ("roughdielectric_ggx_a0.5", false, [70.0000, 130.0000], [73.9099, 285.5046], [6.2838880e-02, 5.5856786e-02, 6.9820981e-02], 2.9037619e-02),
    ("roughdielectric_ggx_a0.5", true, [70.0000, 130.0000], [73.9099, 285.5046], [6.2838880e-02, 5.5856786e-02, 6.9820981e-02], 2.9037619e-02),
    ("roughdielectric_ggx_a0.5", false, [160.0000, 30.0000], [160.0000, 210.0000], [1.3318335e-02, 1.1838520e-02, 1.4798150e-02], 1.4019910e-02),
    ("roughdielectric_ggx_a0.5", true, [160.0000, 30.0000], [160.0000, 210.0000], [1.3318335e-02, 1.1838520e-02, 1.4798150e-02], 1.4019910e-02),
    ("roughdielectric_ggx_a0.5", false, [160.0000, 30.0000], [169.7982, 236.9202], [1.1632338e-02, 1.0339856e-02, 1.2924819e-02], 1.2746177e-02),
    ("roughdielectric_ggx_a0.5", true, [160.0000, 30.0000], [169.7982, 236.9202], [1.1632338e-02, 1.0339856e-02, 1.2924819e-02], 1.2746177e-02),
    ("roughdielectric_ggx_a0.5", false, [160.0000, 30.0000], [92.6995, 185.5046], [2.7323639e-01, 2.4287680e-01, 3.0359600e-01], 8.3300456e-02),
    ("roughdielectric_ggx_a0.5", true, [160.0000, 30.0000], [92.6995, 185.5046], [2.7323639e-01, 2.4287680e-01, 3.0359600e-01], 8.3300456e-02),
    ("roughdielectric_ggx_a0.5", false, [160.0000, 30.0000], [30.8659, 210.0000], [6.1400470e+00, 7.8943461e+00, 7.0171966e+00], 3.4194207e+00),
    ("roughdielectric_ggx_a0.5", true, [160.0000, 30.0000], [30.8659, 210.0000], [2.7289098e+00, 3.5085983e+00, 3.1187543e+00], 3.4194207e+00),
    ("roughdielectric_ggx_a0.5", false, [160.0000, 30.0000], [40.6641, 236.9202], [8.4536873e-01, 1.0869027e+00, 9.6613571e-01], 4.2512587e-01),
    ("roughdielectric_ggx_a0.5", true, [160.0000, 30.0000], [40.6641, 236.9202], [3.7571942e-01, 4.8306781e-01, 4.2939366e-01], 4.2512587e-01),
    ("roughdielectric_ggx_a0.5", false, [160.0000, 30.0000], [0.1000, 185.5046], [3.1006140e-01, 3.9865037e-01, 3.5435588e-01], 1.9686414e-01),
    ("roughdielectric_ggx_a0.5", true, [160.0000, 30.0000], [0.1000, 185.5046], [1.3780506e-01, 1.7717794e-01, 1.5749151e-01], 1.9686414e-01),
    ("roughdielectric_ggx_a0.5", false, [135.0000, 250.0000], [135.0000, 70.0000], [5.1087772e-01, 4.5411355e-01, 5.6764194e-01], 4.2507187e-01),
    ("roughdielectric_ggx_a0.5", true, [135.0000, 250.0000], [135.0000, 70.0000], [5.1087772e-01, 4.5411355e-01, 5.6764194e-01], 4.2507187e-01),
    ("roughdielectric_ggx_a0.5", false, [135.0000, 250.0000], [144.7982, 96.9202], [6.1192612e-02, 5.4393435e-02, 6.7991794e-02], 5.7235423e-02),
    ("roughdielectric_ggx_a0.5", true, [135.0000, 250.0000], [144.7982, 96.9202], [6.1192612e-02, 5.4393435e-02, 6.7991794e-02], 5.7235423e-02),
    ("roughdielectric_ggx_a0.5", false, [135.0000, 250.0000], [67.6995, 45.5046], [5.6237947e-01, 7.2305928e-01, 6.4271938e-01], 1.7456809e-01),
    ("roughdielectric_ggx_a0.5", true, [135.0000, 250.0000], [67.6995, 45.5046], [2.4994640e-01, 3.2135965e-01, 2.8565304e-01], 1.7456809e-01),
    ("roughdielectric_ggx_a0.5", false, [135.0000, 250.0000], [12.2473, 70.0000], [4.5124790e-02, 5.8017588e-02, 5.1571189e-02], 2.8080817e-02),
    ("roughdielectric_ggx_a0.5", true, [135.0000, 250.0000], [12.2473, 70.0000], [2.0055463e-02, 2.5785595e-02, 2.2920530e-02], 2.8080817e-02),
    ("roughdielectric_ggx_a0.5", false, [135.0000, 250.0000], [22.0455, 96.9202], [1.0418236e-01, 1.3394875e-01, 1.1906555e-01], 6.1933301e-02),
    ("roughdielectric_ggx_a0.5", true, [135.0000, 250.0000], [22.0455, 96.9202], [4.6303272e-02, 5.9532781e-02, 5.2918031e-02], 6.1933301e-02),
    ("roughdielectric_ggx_a0.5", false, [135.0000, 250.0000], [0.1000, 45.5046], [1.8601654e-03, 2.3916412e-03, 2.1259033e-03], 1.1810559e-03),
    ("roughdielectric_ggx_a0.5", true, [135.0000, 250.0000], [0.1000, 45.5046], [8.2674017e-04, 1.0629517e-03, 9.4484591e-04], 1.1810559e-03),
    ("roughdielectric_ggx_a0.5", false, [115.0000, 60.0000], [115.0000, 240.0000], [1.0548755e+00, 9.3766711e-01, 1.1720839e+00], 6.1080754e-01),
    ("roughdielectric_ggx_a0.5", true, [115.0000, 60.0000], [115.0000, 240.0000], [1.0548755e+00, 9.3766711e-01, 1.1720839e+00], 6.1080754e-01),
    ("roughdielectric_ggx_a0.5", false, [115.0000, 60.0000], [124.7982, 266.9202], [4.1760641e-01, 3.7120572e-01, 4.6400714e-01], 2.9550916e-01),
    ("roughdielectric_ggx_a0.5", true, [115.0000, 60.0000], [124.7982, 266.9202], [4.1760641e-01, 3.7120572e-01, 4.6400714e-01], 2.9550916e-01),
    ("roughdielectric_ggx_a0.5", false, [115.0000, 60.0000], [47.6995, 215.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.5", true, [115.0000, 60.0000], [47.6995, 215.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.5", false, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.5", true, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.5", false, [115.0000, 60.0000], [25.5751, 266.9202], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.5", true, [115.0000, 60.0000], [25.5751, 266.9202], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.5", false, [115.0000, 60.0000], [0.1000, 215.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_a0.5", true, [115.0000, 60.0000], [0.1000, 215.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.01", false, [5.0000, 20.0000], [5.0000, 200.0000], [2.8867853e+01, 2.5660316e+01, 3.2075394e+01], 3.1953339e+01),
    ("roughdielectric_beckmann_a0.01", true, [5.0000, 20.0000], [5.0000, 200.0000], [2.8867853e+01, 2.5660316e+01, 3.2075394e+01], 3.1953339e+01),
    ("roughdielectric_beckmann_a0.01", false, [5.0000, 20.0000], [5.1960, 200.5384], [2.7995117e+01, 2.4884550e+01, 3.1105687e+01], 3.0977865e+01),
    ("roughdielectric_beckmann_a0.01", true, [5.0000, 20.0000], [5.1960, 200.5384], [2.7995117e+01, 2.4884550e+01, 3.1105687e+01], 3.0977865e+01),
    ("roughdielectric_beckmann_a0.01", false, [5.0000, 20.0000], [3.6540, 199.5101], [7.2454109e+00, 6.4403653e+00, 8.0504566e+00], 8.0340919e+00),
    ("roughdielectric_beckmann_a0.01", true, [5.0000, 20.0000], [3.6540, 199.5101], [7.2454109e+00, 6.4403653e+00, 8.0504566e+00], 8.0340919e+00),
    ("roughdielectric_beckmann_a0.01", false, [5.0000, 20.0000], [176.6690, 200.0000], [8.5128287e+03, 1.0945065e+04, 9.7289477e+03], 2.7316432e+04),
    ("roughdielectric_beckmann_a0.01", true, [5.0000, 20.0000], [176.6690, 200.0000], [1.9153862e+04, 2.4626393e+04, 2.1890130e+04], 2.7316432e+04),
    ("roughdielectric_beckmann_a0.01", false, [5.0000, 20.0000], [176.8650, 200.5384], [2.9175873e+03, 3.7511834e+03, 3.3343853e+03], 9.3639248e+03),
    ("roughdielectric_beckmann_a0.01", true, [5.0000, 20.0000], [176.8650, 200.5384], [6.5645713e+03, 8.4401634e+03, 7.5023678e+03], 9.3639248e+03),
    ("roughdielectric_beckmann_a0.01", false, [5.0000, 20.0000], [175.3230, 199.5101], [2.2796834e-18, 2.9310215e-18, 2.6053524e-18], 7.3031536e-18),
    ("roughdielectric_beckmann_a0.01", true, [5.0000, 20.0000], [175.3230, 199.5101], [5.1292870e-18, 6.5947974e-18, 5.8620426e-18], 7.3031536e-18),
    ("roughdielectric_beckmann_a0.01", false, [35.0000, 0.0000], [35.0000, 180.0000], [4.5957568e+01, 4.0851172e+01, 5.1063964e+01], 4.1829147e+01),
    ("roughdielectric_beckmann_a0.01", true, [35.0000, 0.0000], [35.0000, 180.0000], [4.5957568e+01, 4.0851172e+01, 5.1063964e+01], 4.1829147e+01),
    ("roughdielectric_beckmann_a0.01", false, [35.0000, 0.0000], [35.1960, 180.5384], [4.0156776e+01, 3.5694916e+01, 4.4618643e+01], 3.6461700e+01),
    ("roughdielectric_beckmann_a0.01", true, [35.0000, 0.0000], [35.1960, 180.5384], [4.0156776e+01, 3.5694916e+01, 4.4618643e+01], 3.6461700e+01),
    ("roughdielectric_beckmann_a0.01", false, [35.0000, 0.0000], [33.6540, 179.5101], [1.0390108e+01, 9.2356520e+00, 1.1544565e+01], 9.6096878e+00),
    ("roughdielectric_beckmann_a0.01", true, [35.0000, 0.0000], [33.6540, 179.5101], [1.0390108e+01, 9.2356520e+00, 1.1544565e+01], 9.6096878e+00),
    ("roughdielectric_beckmann_a0.01", false, [35.0000, 0.0000], [157.5186, 180.0000], [6.6357673e+03, 8.5317008e+03, 7.5837340e+03], 1.9708307e+04),
    ("roughdielectric_beckmann_a0.01", true, [35.0000, 0.0000], [157.5186, 180.0000], [1.4930474e+04, 1.9196324e+04, 1.7063398e+04], 1.9708307e+04),
    ("roughdielectric_beckmann_a0.01", false, [35.0000, 0.0000], [157.7146, 180.5384], [1.3357597e+03, 1.7174053e+03, 1.5265825e+03], 3.9728154e+03),
    ("roughdielectric_beckmann_a0.01", true, [35.0000, 0.0000], [157.7146, 180.5384], [3.0054591e+03, 3.8641617e+03, 3.4348104e+03], 3.9728154e+03),
    ("roughdielectric_beckmann_a0.01", false, [35.0000, 0.0000], [156.1726, 179.5101], [4.0305241e-12, 5.1821027e-12, 4.6063139e-12], 1.1851035e-11),
    ("roughdielectric_beckmann_a0.01", true, [35.0000, 0.0000], [156.1726, 179.5101], [9.0686801e-12, 1.1659731e-11, 1.0364205e-11], 1.1851035e-11),
    ("roughdielectric_beckmann_a0.01", false, [70.0000, 130.0000], [70.0000, 310.0000], [1.0472090e+03, 9.3085255e+02, 1.1635656e+03], 3.9796289e+02),
    ("roughdielectric_beckmann_a0.01", true, [70.0000, 130.0000], [70.0000, 310.0000], [1.0472090e+03, 9.3085255e+02, 1.1635656e+03], 3.9796289e+02),
    ("roughdielectric_beckmann_a0.01", false, [70.0000, 130.0000], [70.1960, 310.5384], [1.9197543e+02, 1.7064484e+02, 2.1330604e+02], 7.2268845e+01),
    ("roughdielectric_beckmann_a0.01", true, [70.0000, 130.0000], [70.1960, 310.5384], [1.9197543e+02, 1.7064484e+02, 2.1330604e+02], 7.2268845e+01),
    ("roughdielectric_beckmann_a0.01", false, [70.0000, 130.0000], [68.6540, 309.5101], [6.5286850e+01, 5.8032756e+01, 7.2540944e+01], 2.6404846e+01),
    ("roughdielectric_beckmann_a0.01", true, [70.0000, 130.0000], [68.6540, 309.5101], [6.5286850e+01, 5.8032756e+01, 7.2540944e+01], 2.6404846e+01),
    ("roughdielectric_beckmann_a0.01", false, [70.0000, 130.0000], [141.2104, 310.0000], [2.6996426e+03, 3.4709691e+03, 3.0853060e+03], 6.7636318e+03),
    ("roughdielectric_beckmann_a0.01", true, [70.0000, 130.0000], [141.2104, 310.0000], [6.0741957e+03, 7.8096806e+03, 6.9419388e+03], 6.7636318e+03),
    ("roughdielectric_beckmann_a0.01", false, [70.0000, 130.0000], [141.4064, 310.5384], [6.7379170e+02, 8.6630358e+02, 7.7004768e+02], 1.6927360e+03),
    ("roughdielectric_beckmann_a0.01", true, [70.0000, 130.0000], [141.4064, 310.5384], [1.5160313e+03, 1.9491830e+03, 1.7326073e+03], 1.6927360e+03),
    ("roughdielectric_beckmann_a0.01", false, [70.0000, 130.0000], [139.8644, 309.5101], [1.2847938e-02, 1.6518778e-02, 1.4683358e-02], 3.1572379e-02),
    ("roughdielectric_beckmann_a0.01", true, [70.0000, 130.0000], [139.8644, 309.5101], [2.8907856e-02, 3.7167243e-02, 3.3037552e-02], 3.1572379e-02),
    ("roughdielectric_beckmann_a0.01", false, [160.0000, 30.0000], [160.0000, 210.0000], [3.3844951e+01, 3.0084402e+01, 3.7605502e+01], 3.5337612e+01),
    ("roughdielectric_beckmann_a0.01", true, [160.0000, 30.0000], [160.0000, 210.0000], [3.3844951e+01, 3.0084402e+01, 3.7605502e+01], 3.5337612e+01),
    ("roughdielectric_beckmann_a0.01", false, [160.0000, 30.0000], [160.1960, 210.5384], [3.1862054e+01, 2.8321828e+01, 3.5402284e+01], 3.3308487e+01),
    ("roughdielectric_beckmann_a0.01", true, [160.0000, 30.0000], [160.1960, 210.5384], [3.1862054e+01, 2.8321828e+01, 3.5402284e+01], 3.3308487e+01),
    ("roughdielectric_beckmann_a0.01", false, [160.0000, 30.0000], [158.6540, 209.5101], [8.4333728e+00, 7.4963318e+00, 9.3704144e+00], 8.7275963e+00),
    ("roughdielectric_beckmann_a0.01", true, [160.0000, 30.0000], [158.6540, 209.5101], [8.4333728e+00, 7.4963318e+00, 9.3704144e+00], 8.7275963e+00),
    ("roughdielectric_beckmann_a0.01", false, [160.0000, 30.0000], [30.8659, 210.0000], [1.5814317e+04, 2.0332692e+04, 1.8073505e+04], 8.6187559e+03),
    ("roughdielectric_beckmann_a0.01", true, [160.0000, 30.0000], [30.8659, 210.0000], [7.0285848e+03, 9.0367517e+03, 8.0326689e+03], 8.6187559e+03),
    ("roughdielectric_beckmann_a0.01", false, [160.0000, 30.0000], [31.0619, 210.5384], [5.4917775e+03, 7.0608571e+03, 6.2763179e+03], 2.9868657e+03),
    ("roughdielectric_beckmann_a0.01", true, [160.0000, 30.0000], [31.0619, 210.5384], [2.4407902e+03, 3.1381586e+03, 2.7894747e+03], 2.9868657e+03),
    ("roughdielectric_beckmann_a0.01", false, [160.0000, 30.0000], [29.5199, 209.5101], [6.3465411e-03, 8.1598385e-03, 7.2531898e-03], 3.5064518e-03),
    ("roughdielectric_beckmann_a0.01", true, [160.0000, 30.0000], [29.5199, 209.5101], [2.8206848e-03, 3.6265949e-03, 3.2236401e-03], 3.5064518e-03),
    ("roughdielectric_beckmann_a0.01", false, [135.0000, 250.0000], [135.0000, 70.0000], [1.4323949e+03, 1.2732400e+03, 1.5915500e+03], 1.1253958e+03),
    ("roughdielectric_beckmann_a0.01", true, [135.0000, 250.0000], [135.0000, 70.0000], [1.4323949e+03, 1.2732400e+03, 1.5915500e+03], 1.1253958e+03),
    ("roughdielectric_beckmann_a0.01", false, [135.0000, 250.0000], [135.1960, 70.5384], [1.1134783e+03, 9.8975855e+02, 1.2371981e+03], 8.7781873e+02),
    ("roughdielectric_beckmann_a0.01", true, [135.0000, 250.0000], [135.1960, 70.5384], [1.1134783e+03, 9.8975855e+02, 1.2371981e+03], 8.7781873e+02),
    ("roughdielectric_beckmann_a0.01", false, [135.0000, 250.0000], [133.6540, 69.5101], [3.0493731e+02, 2.7105541e+02, 3.3881925e+02], 2.3388753e+02),
    ("roughdielectric_beckmann_a0.01", true, [135.0000, 250.0000], [133.6540, 69.5101], [3.0493731e+02, 2.7105541e+02, 3.3881925e+02], 2.3388753e+02),
    ("roughdielectric_beckmann_a0.01", false, [135.0000, 250.0000], [12.2473, 70.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.01", true, [135.0000, 250.0000], [12.2473, 70.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.01", false, [135.0000, 250.0000], [12.4433, 70.5384], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.01", true, [135.0000, 250.0000], [12.4433, 70.5384], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.01", false, [135.0000, 250.0000], [10.9013, 69.5101], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.01", true, [135.0000, 250.0000], [10.9013, 69.5101], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.01", false, [115.0000, 60.0000], [115.0000, 240.0000], [4.0099236e+03, 3.5643767e+03, 4.4554708e+03], 1.8829635e+03),
    ("roughdielectric_beckmann_a0.01", true, [115.0000, 60.0000], [115.0000, 240.0000], [4.0099236e+03, 3.5643767e+03, 4.4554708e+03], 1.8829635e+03),
    ("roughdielectric_beckmann_a0.01", false, [115.0000, 60.0000], [115.1960, 240.5384], [1.4137185e+03, 1.2566387e+03, 1.5707984e+03], 6.6871436e+02),
    ("roughdielectric_beckmann_a0.01", true, [115.0000, 60.0000], [115.1960, 240.5384], [1.4137185e+03, 1.2566387e+03, 1.5707984e+03], 6.6871436e+02),
    ("roughdielectric_beckmann_a0.01", false, [115.0000, 60.0000], [113.6540, 239.5101], [4.3480655e+02, 3.8649471e+02, 4.8311839e+02], 1.9383319e+02),
    ("roughdielectric_beckmann_a0.01", true, [115.0000, 60.0000], [113.6540, 239.5101], [4.3480655e+02, 3.8649471e+02, 4.8311839e+02], 1.9383319e+02),
    ("roughdielectric_beckmann_a0.01", false, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.01", true, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.01", false, [115.0000, 60.0000], [15.9729, 240.5384], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.01", true, [115.0000, 60.0000], [15.9729, 240.5384], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.01", false, [115.0000, 60.0000], [14.4309, 239.5101], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.01", true, [115.0000, 60.0000], [14.4309, 239.5101], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", false, [5.0000, 20.0000], [5.0000, 200.0000], [2.8867855e-01, 2.5660316e-01, 3.2075394e-01], 3.1953338e-01),
    ("roughdielectric_beckmann_a0.1", true, [5.0000, 20.0000], [5.0000, 200.0000], [2.8867855e-01, 2.5660316e-01, 3.2075394e-01], 3.1953338e-01),
    ("roughdielectric_beckmann_a0.1", false, [5.0000, 20.0000], [6.9596, 205.3840], [2.8088583e-01, 2.4967629e-01, 3.1209536e-01], 3.0979577e-01),
    ("roughdielectric_beckmann_a0.1", true, [5.0000, 20.0000], [6.9596, 205.3840], [2.8088583e-01, 2.4967629e-01, 3.1209536e-01], 3.0979577e-01),
    ("roughdielectric_beckmann_a0.1", false, [5.0000, 20.0000], [0.1000, 195.1009], [2.4033689e-01, 2.1363280e-01, 2.6704099e-01], 2.6704058e-01),
    ("roughdielectric_beckmann_a0.1", true, [5.0000, 20.0000], [0.1000, 195.1009], [2.4033689e-01, 2.1363280e-01, 2.6704099e-01], 2.6704058e-01),
    ("roughdielectric_beckmann_a0.1", false, [5.0000, 20.0000], [176.6690, 200.0000], [8.5128275e+01, 1.0945064e+02, 9.7289461e+01], 2.7316431e+02),
    ("roughdielectric_beckmann_a0.1", true, [5.0000, 20.0000], [176.6690, 200.0000], [1.9153863e+02, 2.4626396e+02, 2.1890131e+02], 2.7316431e+02),
    ("roughdielectric_beckmann_a0.1", false, [5.0000, 20.0000], [178.6286, 205.3840], [2.9272248e+01, 3.7635747e+01, 3.3453999e+01], 9.4062401e+01),
    ("roughdielectric_beckmann_a0.1", true, [5.0000, 20.0000], [178.6286, 205.3840], [6.5862548e+01, 8.4680416e+01, 7.5271486e+01], 9.4062401e+01),
    ("roughdielectric_beckmann_a0.1", false, [5.0000, 20.0000], [163.2089, 195.1009], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", true, [5.0000, 20.0000], [163.2089, 195.1009], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", false, [35.0000, 0.0000], [35.0000, 180.0000], [4.5957558e-01, 4.0851167e-01, 5.1063956e-01], 4.1829145e-01),
    ("roughdielectric_beckmann_a0.1", true, [35.0000, 0.0000], [35.0000, 180.0000], [4.5957558e-01, 4.0851167e-01, 5.1063956e-01], 4.1829145e-01),
    ("roughdielectric_beckmann_a0.1", false, [35.0000, 0.0000], [36.9596, 185.3840], [4.1230264e-01, 3.6649123e-01, 4.5811404e-01], 3.6606044e-01),
    ("roughdielectric_beckmann_a0.1", true, [35.0000, 0.0000], [36.9596, 185.3840], [4.1230264e-01, 3.6649123e-01, 4.5811404e-01], 3.6606044e-01),
    ("roughdielectric_beckmann_a0.1", false, [35.0000, 0.0000], [21.5399, 175.1009], [9.4079897e-02, 8.3626584e-02, 1.0453323e-01], 9.7232848e-02),
    ("roughdielectric_beckmann_a0.1", true, [35.0000, 0.0000], [21.5399, 175.1009], [9.4079897e-02, 8.3626584e-02, 1.0453323e-01], 9.7232848e-02),
    ("roughdielectric_beckmann_a0.1", false, [35.0000, 0.0000], [157.5186, 180.0000], [6.6357676e+01, 8.5317012e+01, 7.5837346e+01], 1.9708307e+02),
    ("roughdielectric_beckmann_a0.1", true, [35.0000, 0.0000], [157.5186, 180.0000], [1.4930473e+02, 1.9196323e+02, 1.7063399e+02], 1.9708307e+02),
    ("roughdielectric_beckmann_a0.1", false, [35.0000, 0.0000], [159.4782, 185.3840], [1.3406756e+01, 1.7237258e+01, 1.5322007e+01], 4.0358406e+01),
    ("roughdielectric_beckmann_a0.1", true, [35.0000, 0.0000], [159.4782, 185.3840], [3.0165201e+01, 3.8783829e+01, 3.4474516e+01], 4.0358406e+01),
    ("roughdielectric_beckmann_a0.1", false, [35.0000, 0.0000], [144.0585, 175.1009], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", true, [35.0000, 0.0000], [144.0585, 175.1009], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", false, [70.0000, 130.0000], [70.0000, 310.0000], [1.0472089e+01, 9.3085244e+00, 1.1635655e+01], 3.9796286e+00),
    ("roughdielectric_beckmann_a0.1", true, [70.0000, 130.0000], [70.0000, 310.0000], [1.0472089e+01, 9.3085244e+00, 1.1635655e+01], 3.9796286e+00),
    ("roughdielectric_beckmann_a0.1", false, [70.0000, 130.0000], [71.9596, 315.3840], [1.9343481e+00, 1.7194206e+00, 2.1492757e+00], 6.6560382e-01),
    ("roughdielectric_beckmann_a0.1", true, [70.0000, 130.0000], [71.9596, 315.3840], [1.9343481e+00, 1.7194206e+00, 2.1492757e+00], 6.6560382e-01),
    ("roughdielectric_beckmann_a0.1", false, [70.0000, 130.0000], [56.5399, 305.1009], [5.1490245e-01, 4.5769106e-01, 5.7211384e-01], 3.1543851e-01),
    ("roughdielectric_beckmann_a0.1", true, [70.0000, 130.0000], [56.5399, 305.1009], [5.1490245e-01, 4.5769106e-01, 5.7211384e-01], 3.1543851e-01),
    ("roughdielectric_beckmann_a0.1", false, [70.0000, 130.0000], [141.2104, 310.0000], [2.6996429e+01, 3.4709694e+01, 3.0853063e+01], 6.7636322e+01),
    ("roughdielectric_beckmann_a0.1", true, [70.0000, 130.0000], [141.2104, 310.0000], [6.0741958e+01, 7.8096800e+01, 6.9419379e+01], 6.7636322e+01),
    ("roughdielectric_beckmann_a0.1", false, [70.0000, 130.0000], [143.1700, 315.3840], [5.7260997e+00, 7.3621282e+00, 6.5441142e+00], 1.4731939e+01),
    ("roughdielectric_beckmann_a0.1", true, [70.0000, 130.0000], [143.1700, 315.3840], [1.2883723e+01, 1.6564787e+01, 1.4724255e+01], 1.4731939e+01),
    ("roughdielectric_beckmann_a0.1", false, [70.0000, 130.0000], [127.7503, 305.1009], [2.1342806e-07, 2.7440748e-07, 2.4391777e-07], 4.1999530e-07),
    ("roughdielectric_beckmann_a0.1", true, [70.0000, 130.0000], [127.7503, 305.1009], [4.8021301e-07, 6.1741673e-07, 5.4881487e-07], 4.1999530e-07),
    ("roughdielectric_beckmann_a0.1", false, [160.0000, 30.0000], [160.0000, 210.0000], [3.3844950e-01, 3.0084401e-01, 3.7605501e-01], 3.5337612e-01),
    ("roughdielectric_beckmann_a0.1", true, [160.0000, 30.0000], [160.0000, 210.0000], [3.3844950e-01, 3.0084401e-01, 3.7605501e-01], 3.5337612e-01),
    ("roughdielectric_beckmann_a0.1", false, [160.0000, 30.0000], [161.9596, 215.3840], [3.1398548e-01, 2.7909820e-01, 3.4887275e-01], 3.3172163e-01),
    ("roughdielectric_beckmann_a0.1", true, [160.0000, 30.0000], [161.9596, 215.3840], [3.1398548e-01, 2.7909820e-01, 3.4887275e-01], 3.3172163e-01),
    ("roughdielectric_beckmann_a0.1", false, [160.0000, 30.0000], [146.5399, 205.1009], [1.0640279e-01, 9.4580257e-02, 1.1822532e-01], 9.8631836e-02),
    ("roughdielectric_beckmann_a0.1", true, [160.0000, 30.0000], [146.5399, 205.1009], [1.0640279e-01, 9.4580257e-02, 1.1822532e-01], 9.8631836e-02),
    ("roughdielectric_beckmann_a0.1", false, [160.0000, 30.0000], [30.8659, 210.0000], [1.5814315e+02, 2.0332690e+02, 1.8073502e+02], 8.6187546e+01),
    ("roughdielectric_beckmann_a0.1", true, [160.0000, 30.0000], [30.8659, 210.0000], [7.0285833e+01, 9.0367494e+01, 8.0326673e+01], 8.6187546e+01),
    ("roughdielectric_beckmann_a0.1", false, [160.0000, 30.0000], [32.8255, 215.3840], [5.0700206e+01, 6.5185975e+01, 5.7943090e+01], 2.7050587e+01),
    ("roughdielectric_beckmann_a0.1", true, [160.0000, 30.0000], [32.8255, 215.3840], [2.2533425e+01, 2.8971547e+01, 2.5752488e+01], 2.7050587e+01),
    ("roughdielectric_beckmann_a0.1", false, [160.0000, 30.0000], [17.4058, 205.1009], [4.7353474e-08, 6.0883035e-08, 5.4118254e-08], 2.8688991e-08),
    ("roughdielectric_beckmann_a0.1", true, [160.0000, 30.0000], [17.4058, 205.1009], [2.1045990e-08, 2.7059129e-08, 2.4052560e-08], 2.8688991e-08),
    ("roughdielectric_beckmann_a0.1", false, [135.0000, 250.0000], [135.0000, 70.0000], [1.4323947e+01, 1.2732399e+01, 1.5915497e+01], 1.1253956e+01),
    ("roughdielectric_beckmann_a0.1", true, [135.0000, 250.0000], [135.0000, 70.0000], [1.4323947e+01, 1.2732399e+01, 1.5915497e+01], 1.1253956e+01),
    ("roughdielectric_beckmann_a0.1", false, [135.0000, 250.0000], [136.9596, 75.3840], [1.1005400e+01, 9.7825779e+00, 1.2228222e+01], 8.9372730e+00),
    ("roughdielectric_beckmann_a0.1", true, [135.0000, 250.0000], [136.9596, 75.3840], [1.1005400e+01, 9.7825779e+00, 1.2228222e+01], 8.9372730e+00),
    ("roughdielectric_beckmann_a0.1", false, [135.0000, 250.0000], [121.5399, 65.1009], [3.7183175e+00, 3.3051713e+00, 4.1314640e+00], 2.1611364e+00),
    ("roughdielectric_beckmann_a0.1", true, [135.0000, 250.0000], [121.5399, 65.1009], [3.7183175e+00, 3.3051713e+00, 4.1314640e+00], 2.1611364e+00),
    ("roughdielectric_beckmann_a0.1", false, [135.0000, 250.0000], [12.2473, 70.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", true, [135.0000, 250.0000], [12.2473, 70.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", false, [135.0000, 250.0000], [14.2069, 75.3840], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", true, [135.0000, 250.0000], [14.2069, 75.3840], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", false, [135.0000, 250.0000], [0.1000, 65.1009], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", true, [135.0000, 250.0000], [0.1000, 65.1009], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", false, [115.0000, 60.0000], [115.0000, 240.0000], [4.0099238e+01, 3.5643767e+01, 4.4554708e+01], 1.8829634e+01),
    ("roughdielectric_beckmann_a0.1", true, [115.0000, 60.0000], [115.0000, 240.0000], [4.0099238e+01, 3.5643767e+01, 4.4554708e+01], 1.8829634e+01),
    ("roughdielectric_beckmann_a0.1", false, [115.0000, 60.0000], [116.9596, 245.3840], [1.4615131e+01, 1.2991228e+01, 1.6239035e+01], 7.3621635e+00),
    ("roughdielectric_beckmann_a0.1", true, [115.0000, 60.0000], [116.9596, 245.3840], [1.4615131e+01, 1.2991228e+01, 1.6239035e+01], 7.3621635e+00),
    ("roughdielectric_beckmann_a0.1", false, [115.0000, 60.0000], [101.5399, 235.1009], [4.1941237e+00, 3.7281100e+00, 4.6601375e+00], 9.3226206e-01),
    ("roughdielectric_beckmann_a0.1", true, [115.0000, 60.0000], [101.5399, 235.1009], [4.1941237e+00, 3.7281100e+00, 4.6601375e+00], 9.3226206e-01),
    ("roughdielectric_beckmann_a0.1", false, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", true, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", false, [115.0000, 60.0000], [17.7365, 245.3840], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", true, [115.0000, 60.0000], [17.7365, 245.3840], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", false, [115.0000, 60.0000], [2.3168, 235.1009], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.1", true, [115.0000, 60.0000], [2.3168, 235.1009], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", false, [5.0000, 20.0000], [5.0000, 200.0000], [1.1547141e-02, 1.0264126e-02, 1.2830157e-02], 1.2781335e-02),
    ("roughdielectric_beckmann_a0.5", true, [5.0000, 20.0000], [5.0000, 200.0000], [1.1547141e-02, 1.0264126e-02, 1.2830157e-02], 1.2781335e-02),
    ("roughdielectric_beckmann_a0.5", false, [5.0000, 20.0000], [14.7982, 226.9202], [1.1697822e-02, 1.0398065e-02, 1.2997580e-02], 1.2566471e-02),
    ("roughdielectric_beckmann_a0.5", true, [5.0000, 20.0000], [14.7982, 226.9202], [1.1697822e-02, 1.0398065e-02, 1.2997580e-02], 1.2566471e-02),
    ("roughdielectric_beckmann_a0.5", false, [5.0000, 20.0000], [0.1000, 175.5046], [1.1460729e-02, 1.0187315e-02, 1.2734143e-02], 1.2734125e-02),
    ("roughdielectric_beckmann_a0.5", true, [5.0000, 20.0000], [0.1000, 175.5046], [1.1460729e-02, 1.0187315e-02, 1.2734143e-02], 1.2734125e-02),
    ("roughdielectric_beckmann_a0.5", false, [5.0000, 20.0000], [176.6690, 200.0000], [3.4051310e+00, 4.3780255e+00, 3.8915786e+00], 1.0926571e+01),
    ("roughdielectric_beckmann_a0.5", true, [5.0000, 20.0000], [176.6690, 200.0000], [7.6615442e+00, 9.8505572e+00, 8.7560510e+00], 1.0926571e+01),
    ("roughdielectric_beckmann_a0.5", false, [5.0000, 20.0000], [179.9000, 226.9202], [2.9642614e+00, 3.8111932e+00, 3.3877273e+00], 9.5279665e+00),
    ("roughdielectric_beckmann_a0.5", true, [5.0000, 20.0000], [179.9000, 226.9202], [6.6695879e+00, 8.5751848e+00, 7.6223868e+00], 9.5279665e+00),
    ("roughdielectric_beckmann_a0.5", false, [5.0000, 20.0000], [109.3685, 175.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", true, [5.0000, 20.0000], [109.3685, 175.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", false, [35.0000, 0.0000], [35.0000, 180.0000], [1.8383024e-02, 1.6340467e-02, 2.0425584e-02], 1.6731659e-02),
    ("roughdielectric_beckmann_a0.5", true, [35.0000, 0.0000], [35.0000, 180.0000], [1.8383024e-02, 1.6340467e-02, 2.0425584e-02], 1.6731659e-02),
    ("roughdielectric_beckmann_a0.5", false, [35.0000, 0.0000], [44.7982, 206.9202], [2.0168171e-02, 1.7927264e-02, 2.2409080e-02], 1.5901323e-02),
    ("roughdielectric_beckmann_a0.5", true, [35.0000, 0.0000], [44.7982, 206.9202], [2.0168171e-02, 1.7927264e-02, 2.2409080e-02], 1.5901323e-02),
    ("roughdielectric_beckmann_a0.5", false, [35.0000, 0.0000], [0.1000, 155.5046], [1.1418360e-02, 1.0149654e-02, 1.2687068e-02], 1.2687047e-02),
    ("roughdielectric_beckmann_a0.5", true, [35.0000, 0.0000], [0.1000, 155.5046], [1.1418360e-02, 1.0149654e-02, 1.2687068e-02], 1.2687047e-02),
    ("roughdielectric_beckmann_a0.5", false, [35.0000, 0.0000], [157.5186, 180.0000], [2.6543070e+00, 3.4126804e+00, 3.0334937e+00], 7.8833232e+00),
    ("roughdielectric_beckmann_a0.5", true, [35.0000, 0.0000], [157.5186, 180.0000], [5.9721905e+00, 7.6785310e+00, 6.8253613e+00], 7.8833232e+00),
    ("roughdielectric_beckmann_a0.5", false, [35.0000, 0.0000], [167.3168, 206.9202], [4.8520617e-01, 6.2383651e-01, 5.5452135e-01], 1.5215354e+00),
    ("roughdielectric_beckmann_a0.5", true, [35.0000, 0.0000], [167.3168, 206.9202], [1.0917137e+00, 1.4036319e+00, 1.2476729e+00], 1.5215354e+00),
    ("roughdielectric_beckmann_a0.5", false, [35.0000, 0.0000], [90.5000, 155.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", true, [35.0000, 0.0000], [90.5000, 155.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", false, [70.0000, 130.0000], [70.0000, 310.0000], [3.6001060e-01, 3.2000944e-01, 4.0001178e-01], 1.4757524e-01),
    ("roughdielectric_beckmann_a0.5", true, [70.0000, 130.0000], [70.0000, 310.0000], [3.6001060e-01, 3.2000944e-01, 4.0001178e-01], 1.4757524e-01),
    ("roughdielectric_beckmann_a0.5", false, [70.0000, 130.0000], [79.7982, 336.9202], [8.1777298e-02, 7.2690933e-02, 9.0863668e-02], 2.2284549e-02),
    ("roughdielectric_beckmann_a0.5", true, [70.0000, 130.0000], [79.7982, 336.9202], [8.1777298e-02, 7.2690933e-02, 9.0863668e-02], 2.2284549e-02),
    ("roughdielectric_beckmann_a0.5", false, [70.0000, 130.0000], [2.6995, 285.5046], [1.1852688e-02, 1.0535723e-02, 1.3169654e-02], 1.3155039e-02),
    ("roughdielectric_beckmann_a0.5", true, [70.0000, 130.0000], [2.6995, 285.5046], [1.1852688e-02, 1.0535723e-02, 1.3169654e-02], 1.3155039e-02),
    ("roughdielectric_beckmann_a0.5", false, [70.0000, 130.0000], [141.2104, 310.0000], [1.0010995e+00, 1.2871278e+00, 1.1441137e+00], 2.5081346e+00),
    ("roughdielectric_beckmann_a0.5", true, [70.0000, 130.0000], [141.2104, 310.0000], [2.2524737e+00, 2.8960376e+00, 2.5742557e+00], 2.5081346e+00),
    ("roughdielectric_beckmann_a0.5", false, [70.0000, 130.0000], [151.0086, 336.9202], [1.6779641e-02, 2.1573825e-02, 1.9176733e-02], 4.7176152e-02),
    ("roughdielectric_beckmann_a0.5", true, [70.0000, 130.0000], [151.0086, 336.9202], [3.7754191e-02, 4.8541101e-02, 4.3147650e-02], 4.7176152e-02),
    ("roughdielectric_beckmann_a0.5", false, [70.0000, 130.0000], [73.9099, 285.5046], [1.3700958e-01, 1.2178630e-01, 1.5223287e-01], 4.8377950e-02),
    ("roughdielectric_beckmann_a0.5", true, [70.0000, 130.0000], [73.9099, 285.5046], [1.3700958e-01, 1.2178630e-01, 1.5223287e-01], 4.8377950e-02),
    ("roughdielectric_beckmann_a0.5", false, [160.0000, 30.0000], [160.0000, 210.0000], [1.3537981e-02, 1.2033760e-02, 1.5042201e-02], 1.4135044e-02),
    ("roughdielectric_beckmann_a0.5", true, [160.0000, 30.0000], [160.0000, 210.0000], [1.3537981e-02, 1.2033760e-02, 1.5042201e-02], 1.4135044e-02),
    ("roughdielectric_beckmann_a0.5", false, [160.0000, 30.0000], [169.7982, 236.9202], [1.2252330e-02, 1.0890961e-02, 1.3613700e-02], 1.3398469e-02),
    ("roughdielectric_beckmann_a0.5", true, [160.0000, 30.0000], [169.7982, 236.9202], [1.2252330e-02, 1.0890961e-02, 1.3613700e-02], 1.3398469e-02),
    ("roughdielectric_beckmann_a0.5", false, [160.0000, 30.0000], [92.6995, 185.5046], [5.5250859e-01, 4.9111875e-01, 6.1389844e-01], 1.0143676e-01),
    ("roughdielectric_beckmann_a0.5", true, [160.0000, 30.0000], [92.6995, 185.5046], [5.5250859e-01, 4.9111875e-01, 6.1389844e-01], 1.0143676e-01),
    ("roughdielectric_beckmann_a0.5", false, [160.0000, 30.0000], [30.8659, 210.0000], [6.3257255e+00, 8.1330757e+00, 7.2294009e+00], 3.4475017e+00),
    ("roughdielectric_beckmann_a0.5", true, [160.0000, 30.0000], [30.8659, 210.0000], [2.8114340e+00, 3.6147007e+00, 3.2130676e+00], 3.4475017e+00),
    ("roughdielectric_beckmann_a0.5", false, [160.0000, 30.0000], [40.6641, 236.9202], [1.3033673e+00, 1.6757580e+00, 1.4895627e+00], 6.2772071e-01),
    ("roughdielectric_beckmann_a0.5", true, [160.0000, 30.0000], [40.6641, 236.9202], [5.7927438e-01, 7.4478133e-01, 6.6202788e-01], 6.2772071e-01),
    ("roughdielectric_beckmann_a0.5", false, [160.0000, 30.0000], [0.1000, 185.5046], [3.1992053e-02, 4.1132641e-02, 3.6562347e-02], 2.0312386e-02),
    ("roughdielectric_beckmann_a0.5", true, [160.0000, 30.0000], [0.1000, 185.5046], [1.4218690e-02, 1.8281173e-02, 1.6249933e-02], 2.0312386e-02),
    ("roughdielectric_beckmann_a0.5", false, [135.0000, 250.0000], [135.0000, 70.0000], [5.7295792e-01, 5.0929595e-01, 6.3661994e-01], 4.5015827e-01),
    ("roughdielectric_beckmann_a0.5", true, [135.0000, 250.0000], [135.0000, 70.0000], [5.7295792e-01, 5.0929595e-01, 6.3661994e-01], 4.5015827e-01),
    ("roughdielectric_beckmann_a0.5", false, [135.0000, 250.0000], [144.7982, 96.9202], [7.7724677e-02, 6.9088606e-02, 8.6360757e-02], 7.0567682e-02),
    ("roughdielectric_beckmann_a0.5", true, [135.0000, 250.0000], [144.7982, 96.9202], [7.7724677e-02, 6.9088606e-02, 8.6360757e-02], 7.0567682e-02),
    ("roughdielectric_beckmann_a0.5", false, [135.0000, 250.0000], [67.6995, 45.5046], [9.7474261e-01, 1.2532405e+00, 1.1139915e+00], 2.4741258e-01),
    ("roughdielectric_beckmann_a0.5", true, [135.0000, 250.0000], [67.6995, 45.5046], [4.3321891e-01, 5.5699574e-01, 4.9510736e-01], 2.4741258e-01),
    ("roughdielectric_beckmann_a0.5", false, [135.0000, 250.0000], [12.2473, 70.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", true, [135.0000, 250.0000], [12.2473, 70.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", false, [135.0000, 250.0000], [22.0455, 96.9202], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", true, [135.0000, 250.0000], [22.0455, 96.9202], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", false, [135.0000, 250.0000], [0.1000, 45.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", true, [135.0000, 250.0000], [0.1000, 45.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", false, [115.0000, 60.0000], [115.0000, 240.0000], [1.5037583e+00, 1.3366741e+00, 1.6708426e+00], 7.2927755e-01),
    ("roughdielectric_beckmann_a0.5", true, [115.0000, 60.0000], [115.0000, 240.0000], [1.5037583e+00, 1.3366741e+00, 1.6708426e+00], 7.2927755e-01),
    ("roughdielectric_beckmann_a0.5", false, [115.0000, 60.0000], [124.7982, 266.9202], [7.9479113e-01, 7.0648104e-01, 8.8310127e-01], 5.0480956e-01),
    ("roughdielectric_beckmann_a0.5", true, [115.0000, 60.0000], [124.7982, 266.9202], [7.9479113e-01, 7.0648104e-01, 8.8310127e-01], 5.0480956e-01),
    ("roughdielectric_beckmann_a0.5", false, [115.0000, 60.0000], [47.6995, 215.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", true, [115.0000, 60.0000], [47.6995, 215.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", false, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", true, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", false, [115.0000, 60.0000], [25.5751, 266.9202], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", true, [115.0000, 60.0000], [25.5751, 266.9202], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", false, [115.0000, 60.0000], [0.1000, 215.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_a0.5", true, [115.0000, 60.0000], [0.1000, 215.5046], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_u0.1_v0.3", false, [5.0000, 20.0000], [5.0000, 200.0000], [9.6219052e-02, 8.5528055e-02, 1.0691006e-01], 1.0650718e-01),
    ("roughdielectric_ggx_u0.1_v0.3", true, [5.0000, 20.0000], [5.0000, 200.0000], [9.6219052e-02, 8.5528055e-02, 1.0691006e-01], 1.0650718e-01),
    ("roughdielectric_ggx_u0.1_v0.3", false, [5.0000, 20.0000], [10.8789, 216.1521], [7.4767168e-02, 6.6459706e-02, 8.3074629e-02], 8.1610128e-02),
    ("roughdielectric_ggx_u0.1_v0.3", true, [5.0000, 20.0000], [10.8789, 216.1521], [7.4767168e-02, 6.6459706e-02, 8.3074629e-02], 8.1610128e-02),
    ("roughdielectric_ggx_u0.1_v0.3", false, [5.0000, 20.0000], [0.1000, 185.3028], [7.1041545e-02, 6.3148045e-02, 7.8935053e-02], 7.8934930e-02),
    ("roughdielectric_ggx_u0.1_v0.3", true, [5.0000, 20.0000], [0.1000, 185.3028], [7.1041545e-02, 6.3148045e-02, 7.8935053e-02], 7.8934930e-02),
    ("roughdielectric_ggx_u0.1_v0.3", false, [5.0000, 20.0000], [176.6690, 200.0000], [2.8374574e+01, 3.6481595e+01, 3.2428086e+01], 9.1051392e+01),
    ("roughdielectric_ggx_u0.1_v0.3", true, [5.0000, 20.0000], [176.6690, 200.0000], [6.3842794e+01, 8.2083588e+01, 7.2963199e+01], 9.1051392e+01),
    ("roughdielectric_ggx_u0.1_v0.3", false, [5.0000, 20.0000], [179.9000, 216.1521], [2.2041367e+00, 2.8338898e+00, 2.5190133e+00], 7.0847139e+00),
    ("roughdielectric_ggx_u0.1_v0.3", true, [5.0000, 20.0000], [179.9000, 216.1521], [4.9593072e+00, 6.3762520e+00, 5.6677796e+00], 7.0847139e+00),
    ("roughdielectric_ggx_u0.1_v0.3", false, [5.0000, 20.0000], [136.2887, 185.3028], [9.3746335e-05, 1.2053100e-04, 1.0713867e-04], 2.1833916e-04),
    ("roughdielectric_ggx_u0.1_v0.3", true, [5.0000, 20.0000], [136.2887, 185.3028], [2.1092925e-04, 2.7119476e-04, 2.4106200e-04], 2.1833916e-04),
    ("roughdielectric_ggx_u0.1_v0.3", false, [35.0000, 0.0000], [35.0000, 180.0000], [1.5281746e-01, 1.3583774e-01, 1.6979717e-01], 1.3925999e-01),
    ("roughdielectric_ggx_u0.1_v0.3", true, [35.0000, 0.0000], [35.0000, 180.0000], [1.5281746e-01, 1.3583774e-01, 1.6979717e-01], 1.3925999e-01),
    ("roughdielectric_ggx_u0.1_v0.3", false, [35.0000, 0.0000], [40.8789, 196.1521], [1.0821937e-01, 9.6194995e-02, 1.2024374e-01], 9.1190547e-02),
    ("roughdielectric_ggx_u0.1_v0.3", true, [35.0000, 0.0000], [40.8789, 196.1521], [1.0821937e-01, 9.6194995e-02, 1.2024374e-01], 9.1190547e-02),
    ("roughdielectric_ggx_u0.1_v0.3", false, [35.0000, 0.0000], [0.1000, 165.3028], [1.1915670e-03, 1.0591707e-03, 1.3239634e-03], 1.3239612e-03),
    ("roughdielectric_ggx_u0.1_v0.3", true, [35.0000, 0.0000], [0.1000, 165.3028], [1.1915670e-03, 1.0591707e-03, 1.3239634e-03], 1.3239612e-03),
    ("roughdielectric_ggx_u0.1_v0.3", false, [35.0000, 0.0000], [157.5186, 180.0000], [2.2082725e+01, 2.8392075e+01, 2.5237401e+01], 6.5614021e+01),
    ("roughdielectric_ggx_u0.1_v0.3", true, [35.0000, 0.0000], [157.5186, 180.0000], [4.9686133e+01, 6.3882170e+01, 5.6784153e+01], 6.5614021e+01),
    ("roughdielectric_ggx_u0.1_v0.3", false, [35.0000, 0.0000], [163.3975, 196.1521], [2.0520974e-01, 2.6384109e-01, 2.3452543e-01], 6.3233143e-01),
    ("roughdielectric_ggx_u0.1_v0.3", true, [35.0000, 0.0000], [163.3975, 196.1521], [4.6172191e-01, 5.9364243e-01, 5.2768219e-01], 6.3233143e-01),
    ("roughdielectric_ggx_u0.1_v0.3", false, [35.0000, 0.0000], [117.1383, 165.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_u0.1_v0.3", true, [35.0000, 0.0000], [117.1383, 165.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_u0.1_v0.3", false, [70.0000, 130.0000], [70.0000, 310.0000], [2.8960011e+00, 2.5742233e+00, 3.2177791e+00], 1.2082717e+00),
    ("roughdielectric_ggx_u0.1_v0.3", true, [70.0000, 130.0000], [70.0000, 310.0000], [2.8960011e+00, 2.5742233e+00, 3.2177791e+00], 1.2082717e+00),
    ("roughdielectric_ggx_u0.1_v0.3", false, [70.0000, 130.0000], [75.8789, 326.1521], [3.3213381e-02, 2.9523009e-02, 3.6903760e-02], 1.0106655e-02),
    ("roughdielectric_ggx_u0.1_v0.3", true, [70.0000, 130.0000], [75.8789, 326.1521], [3.3213381e-02, 2.9523009e-02, 3.6903760e-02], 1.0106655e-02),
    ("roughdielectric_ggx_u0.1_v0.3", false, [70.0000, 130.0000], [29.6197, 295.3028], [3.7626874e-03, 3.3446113e-03, 4.1807640e-03], 3.6564502e-03),
    ("roughdielectric_ggx_u0.1_v0.3", true, [70.0000, 130.0000], [29.6197, 295.3028], [3.7626874e-03, 3.3446113e-03, 4.1807640e-03], 3.6564502e-03),
    ("roughdielectric_ggx_u0.1_v0.3", false, [70.0000, 130.0000], [141.2104, 310.0000], [8.1224761e+00, 1.0443183e+01, 9.2828296e+00], 2.0535345e+01),
    ("roughdielectric_ggx_u0.1_v0.3", true, [70.0000, 130.0000], [141.2104, 310.0000], [1.8275569e+01, 2.3497159e+01, 2.0886366e+01], 2.0535345e+01),
    ("roughdielectric_ggx_u0.1_v0.3", false, [70.0000, 130.0000], [147.0893, 326.1521], [3.7098263e-01, 4.7697767e-01, 4.2398015e-01], 1.0047156e+00),
    ("roughdielectric_ggx_u0.1_v0.3", true, [70.0000, 130.0000], [147.0893, 326.1521], [8.3471068e-01, 1.0731994e+00, 9.5395513e-01], 1.0047156e+00),
    ("roughdielectric_ggx_u0.1_v0.3", false, [70.0000, 130.0000], [100.8301, 295.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_u0.1_v0.3", true, [70.0000, 130.0000], [100.8301, 295.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_u0.1_v0.3", false, [160.0000, 30.0000], [160.0000, 210.0000], [1.1259288e-01, 1.0008257e-01, 1.2510321e-01], 1.1767524e-01),
    ("roughdielectric_ggx_u0.1_v0.3", true, [160.0000, 30.0000], [160.0000, 210.0000], [1.1259288e-01, 1.0008257e-01, 1.2510321e-01], 1.1767524e-01),
    ("roughdielectric_ggx_u0.1_v0.3", false, [160.0000, 30.0000], [165.8789, 226.1521], [5.1630500e-02, 4.5893782e-02, 5.7367226e-02], 5.5679101e-02),
    ("roughdielectric_ggx_u0.1_v0.3", true, [160.0000, 30.0000], [165.8789, 226.1521], [5.1630500e-02, 4.5893782e-02, 5.7367226e-02], 5.5679101e-02),
    ("roughdielectric_ggx_u0.1_v0.3", false, [160.0000, 30.0000], [119.6197, 195.3028], [6.7277316e-03, 5.9802062e-03, 7.4752574e-03], 3.7385516e-03),
    ("roughdielectric_ggx_u0.1_v0.3", true, [160.0000, 30.0000], [119.6197, 195.3028], [6.7277316e-03, 5.9802062e-03, 7.4752574e-03], 3.7385516e-03),
    ("roughdielectric_ggx_u0.1_v0.3", false, [160.0000, 30.0000], [30.8659, 210.0000], [5.2521769e+01, 6.7527988e+01, 6.0024881e+01], 2.8700695e+01),
    ("roughdielectric_ggx_u0.1_v0.3", true, [160.0000, 30.0000], [30.8659, 210.0000], [2.3343011e+01, 3.0012443e+01, 2.6677729e+01], 2.8700695e+01),
    ("roughdielectric_ggx_u0.1_v0.3", false, [160.0000, 30.0000], [36.7448, 226.1521], [7.6150119e+00, 9.7907295e+00, 8.7028710e+00], 3.9019320e+00),
    ("roughdielectric_ggx_u0.1_v0.3", true, [160.0000, 30.0000], [36.7448, 226.1521], [3.3844498e+00, 4.3514352e+00, 3.8679425e+00], 3.9019320e+00),
    ("roughdielectric_ggx_u0.1_v0.3", false, [160.0000, 30.0000], [0.1000, 195.3028], [9.1395212e-03, 1.1750812e-02, 1.0445167e-02], 5.8028614e-03),
    ("roughdielectric_ggx_u0.1_v0.3", true, [160.0000, 30.0000], [0.1000, 195.3028], [4.0620088e-03, 5.2225829e-03, 4.6422959e-03], 5.8028614e-03),
    ("roughdielectric_ggx_u0.1_v0.3", false, [135.0000, 250.0000], [135.0000, 70.0000], [4.5913169e+00, 4.0811708e+00, 5.1014634e+00], 3.6785941e+00),
    ("roughdielectric_ggx_u0.1_v0.3", true, [135.0000, 250.0000], [135.0000, 70.0000], [4.5913169e+00, 4.0811708e+00, 5.1014634e+00], 3.6785941e+00),
    ("roughdielectric_ggx_u0.1_v0.3", false, [135.0000, 250.0000], [140.8789, 86.1521], [3.1421225e-01, 2.7929980e-01, 3.4912474e-01], 2.7481291e-01),
    ("roughdielectric_ggx_u0.1_v0.3", true, [135.0000, 250.0000], [140.8789, 86.1521], [3.1421225e-01, 2.7929980e-01, 3.4912474e-01], 2.7481291e-01),
    ("roughdielectric_ggx_u0.1_v0.3", false, [135.0000, 250.0000], [94.6197, 55.3028], [8.1833928e-02, 7.2741270e-02, 9.0926586e-02], 1.5702911e-02),
    ("roughdielectric_ggx_u0.1_v0.3", true, [135.0000, 250.0000], [94.6197, 55.3028], [8.1833928e-02, 7.2741270e-02, 9.0926586e-02], 1.5702911e-02),
    ("roughdielectric_ggx_u0.1_v0.3", false, [135.0000, 250.0000], [12.2473, 70.0000], [1.3585513e-02, 1.7467088e-02, 1.5526300e-02], 8.4374128e-03),
    ("roughdielectric_ggx_u0.1_v0.3", true, [135.0000, 250.0000], [12.2473, 70.0000], [6.0380058e-03, 7.7631502e-03, 6.9005785e-03], 8.4374128e-03),
    ("roughdielectric_ggx_u0.1_v0.3", false, [135.0000, 250.0000], [18.1262, 86.1521], [1.4925965e-02, 1.9190527e-02, 1.7058247e-02], 9.0280818e-03),
    ("roughdielectric_ggx_u0.1_v0.3", true, [135.0000, 250.0000], [18.1262, 86.1521], [6.6337616e-03, 8.5291224e-03, 7.5814425e-03], 9.0280818e-03),
    ("roughdielectric_ggx_u0.1_v0.3", false, [135.0000, 250.0000], [0.1000, 55.3028], [5.6065764e-04, 7.2084549e-04, 6.4075156e-04], 3.5597256e-04),
    ("roughdielectric_ggx_u0.1_v0.3", true, [135.0000, 250.0000], [0.1000, 55.3028], [2.4918118e-04, 3.2037578e-04, 2.8477848e-04], 3.5597256e-04),
    ("roughdielectric_ggx_u0.1_v0.3", false, [115.0000, 60.0000], [115.0000, 240.0000], [1.1569089e+01, 1.0283635e+01, 1.2854544e+01], 5.8393264e+00),
    ("roughdielectric_ggx_u0.1_v0.3", true, [115.0000, 60.0000], [115.0000, 240.0000], [1.1569089e+01, 1.0283635e+01, 1.2854544e+01], 5.8393264e+00),
    ("roughdielectric_ggx_u0.1_v0.3", false, [115.0000, 60.0000], [120.8789, 256.1521], [1.7266128e-01, 1.5347670e-01, 1.9184588e-01], 1.0402538e-01),
    ("roughdielectric_ggx_u0.1_v0.3", true, [115.0000, 60.0000], [120.8789, 256.1521], [1.7266128e-01, 1.5347670e-01, 1.9184588e-01], 1.0402538e-01),
    ("roughdielectric_ggx_u0.1_v0.3", false, [115.0000, 60.0000], [74.6197, 225.3028], [3.4098256e+00, 4.3840615e+00, 3.8969439e+00], 6.5771610e-01),
    ("roughdielectric_ggx_u0.1_v0.3", true, [115.0000, 60.0000], [74.6197, 225.3028], [1.5154782e+00, 1.9484719e+00, 1.7319751e+00], 6.5771610e-01),
    ("roughdielectric_ggx_u0.1_v0.3", false, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_u0.1_v0.3", true, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_u0.1_v0.3", false, [115.0000, 60.0000], [21.6558, 256.1521], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_u0.1_v0.3", true, [115.0000, 60.0000], [21.6558, 256.1521], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_u0.1_v0.3", false, [115.0000, 60.0000], [0.1000, 225.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_ggx_u0.1_v0.3", true, [115.0000, 60.0000], [0.1000, 225.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [5.0000, 20.0000], [5.0000, 200.0000], [9.6226172e-02, 8.5534375e-02, 1.0691797e-01], 1.0651112e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [5.0000, 20.0000], [5.0000, 200.0000], [9.6226172e-02, 8.5534375e-02, 1.0691797e-01], 1.0651112e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [5.0000, 20.0000], [10.8789, 216.1521], [8.1704134e-02, 7.2625901e-02, 9.0782374e-02], 8.9150853e-02),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [5.0000, 20.0000], [10.8789, 216.1521], [8.1704134e-02, 7.2625901e-02, 9.0782374e-02], 8.9150853e-02),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [5.0000, 20.0000], [0.1000, 185.3028], [9.2439549e-02, 8.2168490e-02, 1.0271061e-01], 1.0271045e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [5.0000, 20.0000], [0.1000, 185.3028], [9.2439549e-02, 8.2168490e-02, 1.0271061e-01], 1.0271045e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [5.0000, 20.0000], [176.6690, 200.0000], [2.8376089e+01, 3.6483544e+01, 3.2429817e+01], 9.1054764e+01),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [5.0000, 20.0000], [176.6690, 200.0000], [6.3846202e+01, 8.2087975e+01, 7.2967088e+01], 9.1054764e+01),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [5.0000, 20.0000], [179.9000, 216.1521], [1.5285312e+01, 1.9652544e+01, 1.7468928e+01], 4.9131287e+01),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [5.0000, 20.0000], [179.9000, 216.1521], [3.4391952e+01, 4.4218223e+01, 3.9305088e+01], 4.9131287e+01),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [5.0000, 20.0000], [136.2887, 185.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [5.0000, 20.0000], [136.2887, 185.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [35.0000, 0.0000], [35.0000, 180.0000], [1.5319188e-01, 1.3617056e-01, 1.7021320e-01], 1.3943048e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [35.0000, 0.0000], [35.0000, 180.0000], [1.5319188e-01, 1.3617056e-01, 1.7021320e-01], 1.3943048e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [35.0000, 0.0000], [40.8789, 196.1521], [4.5509764e-02, 4.0453125e-02, 5.0566406e-02], 3.8232986e-02),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [35.0000, 0.0000], [40.8789, 196.1521], [4.5509764e-02, 4.0453125e-02, 5.0566406e-02], 3.8232986e-02),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [35.0000, 0.0000], [0.1000, 165.3028], [4.7123576e-02, 4.1887628e-02, 5.2359532e-02], 5.2359454e-02),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [35.0000, 0.0000], [0.1000, 165.3028], [4.7123576e-02, 4.1887628e-02, 5.2359532e-02], 5.2359454e-02),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [35.0000, 0.0000], [157.5186, 180.0000], [2.2119222e+01, 2.8438999e+01, 2.5279111e+01], 6.5694359e+01),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [35.0000, 0.0000], [157.5186, 180.0000], [4.9768247e+01, 6.3987747e+01, 5.6877997e+01], 6.5694359e+01),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [35.0000, 0.0000], [163.3975, 196.1521], [1.5925621e-01, 2.0475800e-01, 1.8200712e-01], 4.9055415e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [35.0000, 0.0000], [163.3975, 196.1521], [3.5832649e-01, 4.6070548e-01, 4.0951600e-01], 4.9055415e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [35.0000, 0.0000], [117.1383, 165.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [35.0000, 0.0000], [117.1383, 165.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [70.0000, 130.0000], [70.0000, 310.0000], [3.4906961e+00, 3.1028412e+00, 3.8785514e+00], 1.3265427e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [70.0000, 130.0000], [70.0000, 310.0000], [3.4906961e+00, 3.1028412e+00, 3.8785514e+00], 1.3265427e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [70.0000, 130.0000], [75.8789, 326.1521], [1.7016492e-04, 1.5125772e-04, 1.8907215e-04], 4.7313548e-05),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [70.0000, 130.0000], [75.8789, 326.1521], [1.7016492e-04, 1.5125772e-04, 1.8907215e-04], 4.7313548e-05),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [70.0000, 130.0000], [29.6197, 295.3028], [1.1726008e-03, 1.0423118e-03, 1.3028898e-03], 1.1326347e-03),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [70.0000, 130.0000], [29.6197, 295.3028], [1.1726008e-03, 1.0423118e-03, 1.3028898e-03], 1.1326347e-03),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [70.0000, 130.0000], [141.2104, 310.0000], [8.9988085e+00, 1.1569896e+01, 1.0284353e+01], 2.2545437e+01),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [70.0000, 130.0000], [141.2104, 310.0000], [2.0247318e+01, 2.6032267e+01, 2.3139793e+01], 2.2545437e+01),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [70.0000, 130.0000], [147.0893, 326.1521], [5.6164955e-04, 7.2212087e-04, 6.4188523e-04], 1.5155844e-03),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [70.0000, 130.0000], [147.0893, 326.1521], [1.2637115e-03, 1.6247719e-03, 1.4442417e-03], 1.5155844e-03),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [70.0000, 130.0000], [100.8301, 295.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [70.0000, 130.0000], [100.8301, 295.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [160.0000, 30.0000], [160.0000, 210.0000], [1.1281650e-01, 1.0028133e-01, 1.2535166e-01], 1.1779203e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [160.0000, 30.0000], [160.0000, 210.0000], [1.1281650e-01, 1.0028133e-01, 1.2535166e-01], 1.1779203e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [160.0000, 30.0000], [165.8789, 226.1521], [1.0255859e-01, 9.1163196e-02, 1.1395399e-01], 1.1051055e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [160.0000, 30.0000], [165.8789, 226.1521], [1.0255859e-01, 9.1163196e-02, 1.1395399e-01], 1.1051055e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [160.0000, 30.0000], [119.6197, 195.3028], [2.7653875e-01, 2.4581224e-01, 3.0726529e-01], 1.5186302e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [160.0000, 30.0000], [119.6197, 195.3028], [2.7653875e-01, 2.4581224e-01, 3.0726529e-01], 1.5186302e-01),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [160.0000, 30.0000], [30.8659, 210.0000], [5.2714381e+01, 6.7775632e+01, 6.0245011e+01], 2.8729181e+01),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [160.0000, 30.0000], [30.8659, 210.0000], [2.3428616e+01, 3.0122506e+01, 2.6775562e+01], 2.8729181e+01),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [160.0000, 30.0000], [36.7448, 226.1521], [8.9138728e-03, 1.1460694e-02, 1.0187284e-02], 4.5350851e-03),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [160.0000, 30.0000], [36.7448, 226.1521], [3.9617214e-03, 5.0936420e-03, 4.5276819e-03], 4.5350851e-03),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [160.0000, 30.0000], [0.1000, 195.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [160.0000, 30.0000], [0.1000, 195.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [135.0000, 250.0000], [135.0000, 70.0000], [4.7746493e+00, 4.2441328e+00, 5.3051659e+00], 3.7513187e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [135.0000, 250.0000], [135.0000, 70.0000], [4.7746493e+00, 4.2441328e+00, 5.3051659e+00], 3.7513187e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [135.0000, 250.0000], [140.8789, 86.1521], [1.9947551e+00, 1.7731157e+00, 2.2163946e+00], 1.7195101e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [135.0000, 250.0000], [140.8789, 86.1521], [1.9947551e+00, 1.7731157e+00, 2.2163946e+00], 1.7195101e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [135.0000, 250.0000], [94.6197, 55.3028], [1.4896371e-01, 1.3241220e-01, 1.6551525e-01], 1.7079210e-02),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [135.0000, 250.0000], [94.6197, 55.3028], [1.4896371e-01, 1.3241220e-01, 1.6551525e-01], 1.7079210e-02),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [135.0000, 250.0000], [12.2473, 70.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [135.0000, 250.0000], [12.2473, 70.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [135.0000, 250.0000], [18.1262, 86.1521], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [135.0000, 250.0000], [18.1262, 86.1521], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [135.0000, 250.0000], [0.1000, 55.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [135.0000, 250.0000], [0.1000, 55.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [115.0000, 60.0000], [115.0000, 240.0000], [1.3366411e+01, 1.1881255e+01, 1.4851568e+01], 6.2765441e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [115.0000, 60.0000], [115.0000, 240.0000], [1.3366411e+01, 1.1881255e+01, 1.4851568e+01], 6.2765441e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [115.0000, 60.0000], [120.8789, 256.1521], [4.4486853e+00, 3.9543873e+00, 4.9429837e+00], 2.5368640e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [115.0000, 60.0000], [120.8789, 256.1521], [4.4486853e+00, 3.9543873e+00, 4.9429837e+00], 2.5368640e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [115.0000, 60.0000], [74.6197, 225.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [115.0000, 60.0000], [74.6197, 225.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [115.0000, 60.0000], [15.7769, 240.0000], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [115.0000, 60.0000], [21.6558, 256.1521], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [115.0000, 60.0000], [21.6558, 256.1521], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", false, [115.0000, 60.0000], [0.1000, 225.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughdielectric_beckmann_u0.3_v0.1", true, [115.0000, 60.0000], [0.1000, 225.3028], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
];
