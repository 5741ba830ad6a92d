//! The Mitsuba 3 kinds against Mitsuba 3 itself (values printed by
//! scripts/mitsuba_bsdf_values.py), one-sidedness, and which kinds are delta and guide.

use crate::{MI_ETA, MI_K, MI_KD, MI_KS, dir, flat_bsdf, material};
use footprint::Rgb;
use footprint::bsdf::TransportMode;
use footprint::bsdf::material::{Material, MaterialKind};
use footprint::bsdf::microfacet::Microfacet;
use glam::{Vec2, Vec3};

/// The material scripts/mitsuba_bsdf_values.py gives Mitsuba under `name`.
pub fn mitsuba_material(name: &str) -> Material {
    let rough = |kind, microfacet, alpha| Material {
        microfacet,
        alpha,
        ..material(kind)
    };
    let conductor = |m: Material| Material {
        eta: MI_ETA,
        k: MI_K,
        ks: MI_KS,
        ..m
    };
    let plastic = |m: Material, ni, kd, ks, nonlinear| Material {
        ni,
        kd,
        ks,
        nonlinear,
        ..m
    };
    use MaterialKind::*;
    use Microfacet::*;
    match name {
        "roughconductor_ggx_a0.1" => conductor(rough(RoughConductor, Ggx, 0.1)),
        "roughconductor_ggx_a0.4" => conductor(rough(RoughConductor, Ggx, 0.4)),
        "roughconductor_beckmann_a0.1" => conductor(rough(RoughConductor, Beckmann, 0.1)),
        "roughconductor_beckmann_a0.4" => conductor(rough(RoughConductor, Beckmann, 0.4)),
        // Anisotropic: α_u along the local x axis, α_v along y.
        "roughconductor_ggx_u0.1_v0.4" => Material {
            alpha_v: Some(0.4),
            ..conductor(rough(RoughConductor, Ggx, 0.1))
        },
        "roughconductor_beckmann_u0.5_v0.15" => Material {
            alpha_v: Some(0.15),
            ..conductor(rough(RoughConductor, Beckmann, 0.5))
        },
        "roughplastic_ggx_a0.2" => plastic(rough(RoughPlastic, Ggx, 0.2), 1.5, MI_KD, MI_KS, false),
        "roughplastic_beckmann_a0.3" => plastic(
            rough(RoughPlastic, Beckmann, 0.3),
            1.6,
            MI_KD,
            Rgb::ONE,
            false,
        ),
        "roughplastic_ggx_a0.05_nonlinear" => {
            plastic(rough(RoughPlastic, Ggx, 0.05), 1.45, MI_KD, Rgb::ONE, true)
        }
        "plastic" => plastic(material(Plastic), 1.5, MI_KD, MI_KS, false),
        "plastic_nonlinear" => plastic(material(Plastic), 1.7, MI_KD, Rgb::ONE, true),
        "conductor" => conductor(material(Conductor)),
        "thindielectric" => Material {
            ni: 1.5,
            ks: Rgb::ONE,
            tf: Rgb::ONE,
            ..material(ThinGlass)
        },
        _ => panic!("unknown Mitsuba material {name}"),
    }
    .prepared()
}

pub fn close(a: f32, b: f32, rel: f32) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-30) || (a == 0.0 && b == 0.0)
}

/// `eval` and `pdf` of the rough kinds and smooth plastic's base, and the delta lobes'
/// weights and probabilities, agree with Mitsuba 3's to 1e-3 — roughplastic's too: its tables
/// are computed with the same quadrature over the same visible-normal sample mapping.
#[test]
fn matches_mitsuba_3() {
    check_eval_rows(MITSUBA_EVAL, mitsuba_material);
    for &(name, cos, u_lobe, w_ref, p_ref) in MITSUBA_DELTA {
        let b = flat_bsdf(&mitsuba_material(name));
        let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
        let s = b
            .sample(wo, u_lobe, Vec2::new(0.5, 0.5), TransportMode::Radiance)
            .unwrap();
        let w_ref = Rgb::from(w_ref);
        eprintln!(
            "{name} cos {cos}: weight {} vs {w_ref}, p {} vs {p_ref}",
            s.weight, s.pdf_w
        );
        assert!(s.delta, "{name}: not a delta sample");
        assert!((s.wi - Vec3::new(-wo.x, -wo.y, wo.z)).length() < 1e-5);
        for c in 0..3 {
            assert!(
                close(s.weight[c], w_ref[c], 1e-3),
                "{name} cos {cos}: weight {} vs {w_ref}",
                s.weight
            );
        }
        assert!(
            close(s.pdf_w, p_ref, 1e-3),
            "{name} cos {cos}: probability {} vs {p_ref}",
            s.pdf_w
        );
    }
}

/// `eval` and `pdf` of the materials `material(name)` at each row's directions agree with
/// the row's (Mitsuba 3's) to 1e-3 (4e-3 for Beckmann densities, below).
pub fn check_eval_rows(rows: &[EvalRow], material: impl Fn(&str) -> Material) {
    for &(name, wo, wi, f_ref, pdf_ref) in rows {
        let b = flat_bsdf(&material(name));
        let (wo, wi) = (dir(wo[0], wo[1]), dir(wi[0], wi[1]));
        let f = b.eval(wo, wi, TransportMode::Radiance);
        let pdf = b.pdf(wo, wi);
        let f_ref = Rgb::from(f_ref);
        for c in 0..3 {
            assert!(
                close(f[c], f_ref[c], 1e-3),
                "{name} {wo} {wi}: f {f} vs Mitsuba {f_ref}"
            );
        }
        // Beckmann densities use the exact Smith masking the visible-normal sampler follows,
        // Mitsuba's the 0.35%-accurate rational approximation its `eval` uses (as ours).
        let tol = if name.contains("beckmann") {
            4e-3
        } else {
            1e-3
        };
        assert!(
            close(pdf, pdf_ref, tol),
            "{name} {wo} {wi}: pdf {pdf} vs Mitsuba {pdf_ref}"
        );
    }
}

/// A row of `MITSUBA_EVAL`: Mitsuba material, `wo` and `wi` as (θ, φ) in degrees, `f`, pdf.
pub type EvalRow = (&'static str, [f32; 2], [f32; 2], [f32; 3], f32);
/// A row of `MITSUBA_DELTA`: Mitsuba material, cos θ_o, lobe number, weight, probability.
type DeltaRow = (&'static str, f32, f32, [f32; 3], f32);

// Generated by scripts/mitsuba_bsdf_values.py with Mitsuba 3.9.1 (variant scalar_rgb).
// (name, wo (theta, phi deg), wi (theta, phi deg), f = eval / cos(wi), pdf)
#[rustfmt::skip]
#[allow(clippy::excessive_precision)]
const MITSUBA_EVAL: &[EvalRow] = &[
    ("roughconductor_ggx_a0.1", [30.0, 0.0], [35.0, 180.0], [6.6413985e+00, 4.9708177e+00, 3.2030876e+00], 6.5012989e+00),
    ("roughconductor_ggx_a0.1", [0.0, 0.0], [10.0, 40.0], [2.2067703e+00, 1.6519962e+00, 1.0590866e+00], 2.5924711e+00),
    ("roughconductor_ggx_a0.1", [60.0, 0.0], [20.0, 120.0], [2.8115294e-02, 2.1042605e-02, 1.3591695e-02], 3.1552680e-02),
    ("roughconductor_ggx_a0.1", [80.0, 10.0], [75.0, 200.0], [6.4534933e-01, 5.1072908e-01, 4.2880967e-01], 2.0582137e-01),
    ("roughconductor_ggx_a0.1", [45.0, 0.0], [50.0, 170.0], [3.3918585e+00, 2.5399979e+00, 1.6700549e+00], 2.6168845e+00),
    ("roughconductor_ggx_a0.1", [87.0, 0.0], [40.0, 90.0], [2.2648026e-02, 1.6954005e-02, 1.1068601e-02], 2.0773118e-02),
    ("roughconductor_ggx_a0.4", [30.0, 0.0], [35.0, 180.0], [5.5762459e-01, 4.1735946e-01, 2.6893742e-01], 5.5568445e-01),
    ("roughconductor_ggx_a0.4", [0.0, 0.0], [10.0, 40.0], [3.9105863e-01, 2.9274790e-01, 1.8767923e-01], 4.5994306e-01),
    ("roughconductor_ggx_a0.4", [60.0, 0.0], [20.0, 120.0], [1.7482526e-01, 1.3084618e-01, 8.4515263e-02], 1.9716837e-01),
    ("roughconductor_ggx_a0.4", [80.0, 10.0], [75.0, 200.0], [1.3046960e+00, 1.0325356e+00, 8.6691997e-01], 5.6292272e-01),
    ("roughconductor_ggx_a0.4", [45.0, 0.0], [50.0, 170.0], [7.4845749e-01, 5.6048342e-01, 3.6851923e-01], 6.0643137e-01),
    ("roughconductor_ggx_a0.4", [87.0, 0.0], [40.0, 90.0], [1.1173092e-01, 8.3640248e-02, 5.4605420e-02], 1.0510588e-01),
    ("roughconductor_beckmann_a0.1", [30.0, 0.0], [35.0, 180.0], [7.7967892e+00, 5.8355815e+00, 3.7603226e+00], 7.6229849e+00),
    ("roughconductor_beckmann_a0.1", [0.0, 0.0], [10.0, 40.0], [3.1994087e+00, 2.3950888e+00, 1.5354795e+00], 3.7583113e+00),
    ("roughconductor_beckmann_a0.1", [60.0, 0.0], [20.0, 120.0], [2.5330474e-11, 1.8958334e-11, 1.2245437e-11], 2.8417975e-11),
    ("roughconductor_beckmann_a0.1", [80.0, 10.0], [75.0, 200.0], [3.1892585e-05, 2.5239773e-05, 2.1191389e-05], 9.8400378e-06),
    ("roughconductor_beckmann_a0.1", [45.0, 0.0], [50.0, 170.0], [5.0106205e+00, 3.7522098e+00, 2.4670872e+00], 3.8521614e+00),
    ("roughconductor_beckmann_a0.1", [87.0, 0.0], [40.0, 90.0], [0.0000000e+00, 0.0000000e+00, 0.0000000e+00], 0.0000000e+00),
    ("roughconductor_beckmann_a0.4", [30.0, 0.0], [35.0, 180.0], [5.8265320e-01, 4.3609236e-01, 2.8100851e-01], 5.6966484e-01),
    ("roughconductor_beckmann_a0.4", [0.0, 0.0], [10.0, 40.0], [4.0982078e-01, 3.0679328e-01, 1.9668366e-01], 4.8141211e-01),
    ("roughconductor_beckmann_a0.4", [60.0, 0.0], [20.0, 120.0], [2.5775575e-01, 1.9291467e-01, 1.2460612e-01], 2.8917331e-01),
    ("roughconductor_beckmann_a0.4", [80.0, 10.0], [75.0, 200.0], [3.3606534e+00, 2.6596192e+00, 2.2330243e+00], 1.1404682e+00),
    ("roughconductor_beckmann_a0.4", [45.0, 0.0], [50.0, 170.0], [8.7323476e-01, 6.5392301e-01, 4.2995601e-01], 6.7134225e-01),
    ("roughconductor_beckmann_a0.4", [87.0, 0.0], [40.0, 90.0], [7.1768409e-05, 5.3724858e-05, 3.5074839e-05], 6.5711632e-05),
    ("roughplastic_ggx_a0.2", [30.0, 0.0], [35.0, 180.0], [2.4591522e-01, 1.6051280e-01, 1.4463672e-01], 4.7041780e-01),
    ("roughplastic_ggx_a0.2", [0.0, 0.0], [10.0, 40.0], [2.0336114e-01, 1.2190711e-01, 9.5627625e-02], 4.2783606e-01),
    ("roughplastic_ggx_a0.2", [60.0, 0.0], [20.0, 120.0], [1.4610826e-01, 7.4684027e-02, 4.0136126e-02], 2.5468817e-01),
    ("roughplastic_ggx_a0.2", [80.0, 10.0], [75.0, 200.0], [5.4947656e-01, 4.4994379e-01, 5.2532412e-01], 2.7785730e-01),
    ("roughplastic_ggx_a0.2", [45.0, 0.0], [50.0, 170.0], [2.7303718e-01, 1.8663026e-01, 1.7922085e-01], 4.2790532e-01),
    ("roughplastic_ggx_a0.2", [87.0, 0.0], [40.0, 90.0], [1.0960725e-01, 5.5949117e-02, 2.9938249e-02], 1.3923891e-01),
    ("roughplastic_beckmann_a0.3", [30.0, 0.0], [35.0, 180.0], [2.2781709e-01, 1.4800973e-01, 1.0810604e-01], 3.7122658e-01),
    ("roughplastic_beckmann_a0.3", [0.0, 0.0], [10.0, 40.0], [2.0605272e-01, 1.2532192e-01, 8.4956515e-02], 3.8455057e-01),
    ("roughplastic_beckmann_a0.3", [60.0, 0.0], [20.0, 120.0], [1.5913850e-01, 8.3655462e-02, 4.5913951e-02], 2.5494662e-01),
    ("roughplastic_beckmann_a0.3", [80.0, 10.0], [75.0, 200.0], [1.2947315e+00, 1.2407269e+00, 1.2137245e+00], 5.4923469e-01),
    ("roughplastic_beckmann_a0.3", [45.0, 0.0], [50.0, 170.0], [2.7275575e-01, 1.9584675e-01, 1.5739224e-01], 3.7164199e-01),
    ("roughplastic_beckmann_a0.3", [87.0, 0.0], [40.0, 90.0], [1.1649252e-01, 5.8246262e-02, 2.9123131e-02], 1.0704992e-01),
    ("roughplastic_ggx_a0.05_nonlinear", [30.0, 0.0], [35.0, 180.0], [6.4342650e-01, 5.6855321e-01, 5.4110527e-01], 1.3672374e+00),
    ("roughplastic_ggx_a0.05_nonlinear", [0.0, 0.0], [10.0, 40.0], [1.9305913e-01, 1.1779053e-01, 9.0197649e-02], 4.6291482e-01),
    ("roughplastic_ggx_a0.05_nonlinear", [60.0, 0.0], [20.0, 120.0], [1.1990461e-01, 4.8442966e-02, 2.2245682e-02], 2.3979598e-01),
    ("roughplastic_ggx_a0.05_nonlinear", [80.0, 10.0], [75.0, 200.0], [1.3050597e-01, 9.0355485e-02, 7.5636634e-02], 6.8518609e-02),
    ("roughplastic_ggx_a0.05_nonlinear", [45.0, 0.0], [50.0, 170.0], [2.3624938e-01, 1.6317723e-01, 1.3638956e-01], 3.6689180e-01),
    ("roughplastic_ggx_a0.05_nonlinear", [87.0, 0.0], [40.0, 90.0], [5.7236242e-02, 2.3258289e-02, 1.0802237e-02], 5.7847179e-02),
    ("plastic", [30.0, 0.0], [35.0, 180.0], [1.9309799e-01, 9.6548995e-02, 4.8274498e-02], 2.3460920e-01),
    ("plastic", [0.0, 0.0], [10.0, 40.0], [1.9401965e-01, 9.7009823e-02, 4.8504911e-02], 2.8313783e-01),
    ("plastic", [60.0, 0.0], [20.0, 120.0], [1.8403076e-01, 9.2015378e-02, 4.6007689e-02], 2.3894784e-01),
    ("plastic", [80.0, 10.0], [75.0, 200.0], [9.6284587e-02, 4.8142294e-02, 2.4071147e-02], 3.1346135e-02),
    ("plastic", [45.0, 0.0], [50.0, 170.0], [1.8842149e-01, 9.4210747e-02, 4.7105373e-02], 1.8010710e-01),
    ("plastic", [87.0, 0.0], [40.0, 90.0], [5.1754659e-02, 2.5877329e-02, 1.2938665e-02], 2.8993027e-02),
    ("plastic_nonlinear", [30.0, 0.0], [35.0, 180.0], [9.8115009e-02, 3.6121127e-02, 1.5956686e-02], 2.1516542e-01),
    ("plastic_nonlinear", [0.0, 0.0], [10.0, 40.0], [9.8683633e-02, 3.6330465e-02, 1.6049163e-02], 2.5995407e-01),
    ("plastic_nonlinear", [60.0, 0.0], [20.0, 120.0], [9.3033682e-02, 3.4250430e-02, 1.5130297e-02], 2.1505849e-01),
    ("plastic_nonlinear", [80.0, 10.0], [75.0, 200.0], [4.7876753e-02, 1.7625868e-02, 7.7863148e-03], 2.7465338e-02),
    ("plastic_nonlinear", [45.0, 0.0], [50.0, 170.0], [9.5374158e-02, 3.5112078e-02, 1.5510934e-02], 1.6436857e-01),
    ("plastic_nonlinear", [87.0, 0.0], [40.0, 90.0], [2.6164622e-02, 9.6325282e-03, 4.2552168e-03], 2.5364641e-02),
    ("roughconductor_ggx_u0.1_v0.4", [30.0, 0.0], [35.0, 180.0], [1.6603496e+00, 1.2427044e+00, 8.0077189e-01], 1.6253247e+00),
    ("roughconductor_ggx_u0.1_v0.4", [0.0, 0.0], [10.0, 40.0], [7.9649174e-01, 5.9625657e-01, 3.8225715e-01], 9.3615353e-01),
    ("roughconductor_ggx_u0.1_v0.4", [60.0, 0.0], [20.0, 120.0], [9.4475870e-03, 7.0709510e-03, 4.5672197e-03], 1.0641971e-02),
    ("roughconductor_ggx_u0.1_v0.4", [80.0, 10.0], [75.0, 200.0], [2.6924990e+00, 2.1308421e+00, 1.7890615e+00], 9.0396333e-01),
    ("roughconductor_ggx_u0.1_v0.4", [45.0, 0.0], [50.0, 170.0], [2.6501096e+00, 1.9845383e+00, 1.3048387e+00], 2.0478551e+00),
    ("roughconductor_ggx_u0.1_v0.4", [87.0, 0.0], [40.0, 90.0], [1.0454895e-02, 7.8263924e-03, 5.1095429e-03], 9.8349769e-03),
    ("roughconductor_ggx_u0.1_v0.4", [40.0, 90.0], [45.0, 270.0], [2.8238738e+00, 2.1137442e+00, 1.3767996e+00], 2.4779825e+00),
    ("roughconductor_ggx_u0.1_v0.4", [50.0, 60.0], [30.0, 250.0], [3.2185551e-01, 2.4089580e-01, 1.5630440e-01], 3.3685109e-01),
    ("roughconductor_ggx_u0.1_v0.4", [20.0, 135.0], [60.0, 300.0], [3.3894011e-01, 2.5368223e-01, 1.6457461e-01], 2.1957140e-01),
    ("roughconductor_ggx_u0.1_v0.4", [70.0, 300.0], [65.0, 110.0], [3.1667421e-01, 2.4127860e-01, 1.7655396e-01], 1.8379673e-01),
    ("roughconductor_beckmann_u0.5_v0.15", [30.0, 0.0], [35.0, 180.0], [1.2483362e+00, 9.3432918e-01, 6.0206154e-01], 1.2205086e+00),
    ("roughconductor_beckmann_u0.5_v0.15", [0.0, 0.0], [10.0, 40.0], [7.8267674e-01, 5.8591463e-01, 3.7562697e-01], 9.1940206e-01),
    ("roughconductor_beckmann_u0.5_v0.15", [60.0, 0.0], [20.0, 120.0], [1.8265870e-01, 1.3670904e-01, 8.8302165e-02], 2.0492277e-01),
    ("roughconductor_beckmann_u0.5_v0.15", [80.0, 10.0], [75.0, 200.0], [3.6457340e-02, 2.8852318e-02, 2.4224494e-02], 1.2967983e-02),
    ("roughconductor_beckmann_u0.5_v0.15", [45.0, 0.0], [50.0, 170.0], [1.2891770e+00, 9.6540203e-01, 6.3475415e-01], 9.9111837e-01),
    ("roughconductor_beckmann_u0.5_v0.15", [87.0, 0.0], [40.0, 90.0], [2.1309049e-13, 1.5951666e-13, 1.0414212e-13], 1.9510707e-13),
    ("roughconductor_beckmann_u0.5_v0.15", [40.0, 90.0], [45.0, 270.0], [1.5118009e+00, 1.1316231e+00, 7.3708922e-01], 1.2774214e+00),
    ("roughconductor_beckmann_u0.5_v0.15", [50.0, 60.0], [30.0, 250.0], [7.6182572e-01, 5.7019566e-01, 3.6996947e-01], 7.8807312e-01),
    ("roughconductor_beckmann_u0.5_v0.15", [20.0, 135.0], [60.0, 300.0], [9.0531232e-03, 6.7758765e-03, 4.3958039e-03], 5.4068114e-03),
    ("roughconductor_beckmann_u0.5_v0.15", [70.0, 300.0], [65.0, 110.0], [5.0145964e+00, 3.8206923e+00, 2.7957655e+00], 2.5457535e+00),
];
// (name, cos(wo), lobe sample number, sample weight, discrete probability)
#[rustfmt::skip]
#[allow(clippy::excessive_precision)]
const MITSUBA_DELTA: &[DeltaRow] = &[
    ("conductor", 1.00, 0.0, [8.3835614e-01, 6.2759650e-01, 4.0234789e-01], 1.0000000e+00),
    ("conductor", 0.80, 0.0, [8.3748847e-01, 6.2680799e-01, 4.0533906e-01], 1.0000000e+00),
    ("conductor", 0.50, 0.0, [8.3333111e-01, 6.2781328e-01, 4.3436444e-01], 1.0000000e+00),
    ("conductor", 0.20, 0.0, [8.4271866e-01, 6.7502826e-01, 5.8949691e-01], 1.0000000e+00),
    ("conductor", 0.05, 0.0, [8.8056409e-01, 7.5969189e-01, 8.4997147e-01], 1.0000000e+00),
    ("plastic", 1.00, 0.0, [3.7199992e-01, 3.3066663e-01, 4.1333327e-01], 9.6774213e-02),
    ("plastic", 0.80, 0.0, [3.7414202e-01, 3.3257070e-01, 4.1571337e-01], 1.0558893e-01),
    ("plastic", 0.50, 0.0, [3.9905265e-01, 3.5471347e-01, 4.4339183e-01], 2.0114647e-01),
    ("plastic", 0.20, 0.0, [5.3639191e-01, 4.7679281e-01, 5.9599102e-01], 5.6862330e-01),
    ("plastic", 0.05, 0.0, [7.6367176e-01, 6.7881936e-01, 8.4852421e-01], 8.8639843e-01),
    ("thindielectric", 1.00, 0.0, [1.0000000e+00, 1.0000000e+00, 1.0000000e+00], 7.6923087e-02),
    ("thindielectric", 0.80, 0.0, [1.0000000e+00, 1.0000000e+00, 1.0000000e+00], 8.4097996e-02),
    ("thindielectric", 0.50, 0.0, [1.0000000e+00, 1.0000000e+00, 1.0000000e+00], 1.6376752e-01),
    ("thindielectric", 0.20, 0.0, [1.0000000e+00, 1.0000000e+00, 1.0000000e+00], 5.0623018e-01),
    ("thindielectric", 0.05, 0.0, [1.0000000e+00, 1.0000000e+00, 1.0000000e+00], 8.5853249e-01),
];

/// A one-sided surface is black from below its shading normal (Mitsuba's BSDFs outside a
/// `twosided`), a two-sided one reflects there as from above; glass ignores the flag.
#[test]
fn one_sided_is_black_from_the_back() {
    let kinds = [
        MaterialKind::Diffuse,
        MaterialKind::Glossy,
        MaterialKind::Mirror,
        MaterialKind::Conductor,
        MaterialKind::RoughConductor,
        MaterialKind::Plastic,
        MaterialKind::RoughPlastic,
    ];
    let (wo, wi) = (dir(40.0, 0.0), dir(45.0, 180.0));
    let back = |v: Vec3| Vec3::new(v.x, v.y, -v.z);
    for kind in kinds {
        for two_sided in [true, false] {
            let m = Material {
                alpha: 0.3,
                kd: Rgb::splat(0.5),
                ks: Rgb::splat(0.5),
                ns: 10.0,
                eta: MI_ETA,
                k: MI_K,
                two_sided,
                ..material(kind)
            };
            let b = flat_bsdf(&m);
            let front = b.eval(wo, wi, TransportMode::Radiance);
            let from_back = b.eval(back(wo), back(wi), TransportMode::Radiance);
            let pdf_back = b.pdf(back(wo), back(wi));
            let s_back = b.sample(back(wo), 0.3, Vec2::new(0.4, 0.6), TransportMode::Radiance);
            if b.is_delta() {
                assert_eq!(
                    s_back.is_some(),
                    two_sided,
                    "{kind:?} two_sided {two_sided}"
                );
                continue;
            }
            assert!(front.max_element() > 0.0, "{kind:?}: black from the front");
            if two_sided {
                assert_eq!(
                    from_back, front,
                    "{kind:?}: two-sided differs from the back"
                );
                assert!(pdf_back > 0.0 && s_back.is_some());
            } else {
                assert_eq!(
                    from_back,
                    Rgb::ZERO,
                    "{kind:?}: one-sided not black from the back"
                );
                assert_eq!(pdf_back, 0.0);
                assert!(
                    s_back.is_none(),
                    "{kind:?}: one-sided sampled from the back"
                );
            }
        }
    }
    // Glass, rough glass and thin glass scatter from both sides whatever the flag.
    for kind in [
        MaterialKind::Glass,
        MaterialKind::RoughGlass,
        MaterialKind::ThinGlass,
    ] {
        let b = flat_bsdf(&Material {
            ks: Rgb::ONE,
            ..material(kind)
        });
        assert!(
            b.sample(back(wo), 0.5, Vec2::splat(0.5), TransportMode::Radiance)
                .is_some()
        );
    }
}

/// Delta-ness and guiding of the Mitsuba kinds: the smooth ones are delta (but smooth plastic,
/// whose base is diffuse); the rough ones (rough dielectric too) guide while their
/// Blinn-equivalent exponent `2/α² - 2` is soft.
#[test]
fn mitsuba_kinds_delta_and_guiding() {
    use footprint::guide::guides_at;
    let lobes = |kind, alpha| {
        let m = Material {
            alpha,
            ..material(kind)
        };
        flat_bsdf(&m).lobes
    };
    for (kind, delta) in [
        (MaterialKind::Conductor, true),
        (MaterialKind::ThinGlass, true),
        (MaterialKind::Plastic, false),
        (MaterialKind::RoughConductor, false),
        (MaterialKind::RoughPlastic, false),
        (MaterialKind::RoughGlass, false),
    ] {
        let l = lobes(kind, 0.3);
        assert_eq!(l.is_delta(), delta, "{kind:?}");
        if delta || kind == MaterialKind::Plastic {
            assert!(!guides_at(&l, 1e9), "{kind:?} guides");
        }
    }
    for kind in [
        MaterialKind::RoughConductor,
        MaterialKind::RoughPlastic,
        MaterialKind::RoughGlass,
    ] {
        // α = 0.3: exponent 2/0.09 - 2 = 20.2.
        assert!(guides_at(&lobes(kind, 0.3), 21.0));
        assert!(!guides_at(&lobes(kind, 0.3), 20.0));
        assert!(!guides_at(&lobes(kind, 0.01), 100.0));
    }
}
