//! Mitsuba 3's `bumpmap` (`footprint::bsdf::bump`): the BSDF against Mitsuba 3's own values at
//! points of `scenes/bumpmap` (printed by scripts/mitsuba_bumpmap_values.py), sampling
//! against the density (chi-square) and the sample weight against `f cos / pdf` under a
//! diffuse and a rough conductor, a constant height field that leaves the BSDF exactly as it
//! was, a linear ramp that tilts the normal by its analytic angle, and the importer's errors.
//! The scene's image against Mitsuba's is in tests/mitsuba.rs (`bumpmap_matches_mitsuba`).

mod common;

use common::chi2::ChiSquareTest;
use common::sidak;
use footprint::Rgb;
use footprint::bsdf::bump::{Bump, BumpMap, NormalSource};
use footprint::bsdf::material::{Material, MaterialKind};
use footprint::bsdf::microfacet::Microfacet;
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use footprint::scene::Scene;
use footprint::scene::mitsuba::{self, ImportOptions};
use glam::Vec3;
use std::path::{Path, PathBuf};

include!("bumpmap_values.rs");

fn scene_xml() -> PathBuf {
    common::scenes_dir().join("bumpmap").join("scene.xml")
}

fn load(path: &Path) -> Scene {
    mitsuba::load(path, &ImportOptions::default()).expect("the scene imports")
}

/// Relative agreement of `a` with `b` within `rel`, or both under `abs`.
fn close(a: f32, b: f32, rel: f32, abs: f32) -> bool {
    (a - b).abs() <= rel * b.abs().max(a.abs()) || (a - b).abs() <= abs
}

/// At every point and direction Mitsuba's `eval` (cosine included) and `pdf`, in both modes:
/// footprint's `f · |wi·n_s|` (the integrators' product) and its density. The tolerance is
/// float rounding (Mitsuba's frames and footprint's are built in other orders).
#[test]
fn matches_mitsuba_3_pointwise() {
    let scene = load(&scene_xml());
    let mut checked = 0;
    for &(o, t, wi, rad, imp, pdf) in MITSUBA_POINTS {
        let (o, t, wi) = (Vec3::from(o), Vec3::from(t), Vec3::from(wi));
        let dir = (t - o).normalize();
        let hit = scene
            .intersect(o, dir, f32::INFINITY)
            .expect("the ray hits");
        let bsdf = scene.bsdf(&hit);
        let wo = -dir;
        let cos = wi.dot(hit.ns).abs();
        for (mode, want) in [
            (TransportMode::Radiance, rad),
            (TransportMode::Importance, imp),
        ] {
            // Mitsuba's BSDF carries no adjoint correction (its ptracer applies it): take it
            // out of footprint's, which the flat planes make 1 anyway.
            let got = bsdf.eval(wo, wi, mode) * cos;
            let want = Rgb::from(want);
            for c in 0..3 {
                assert!(
                    close(got[c], want[c], 2e-3, 1e-6),
                    "{mode:?} eval at {t} from {o}, wi {wi}: footprint {got}, Mitsuba {want}"
                );
            }
        }
        let got = bsdf.pdf(wo, wi);
        assert!(
            close(got, pdf, 2e-3, 1e-6),
            "pdf at {t} from {o}, wi {wi}: footprint {got}, Mitsuba {pdf}"
        );
        checked += 1;
    }
    assert!(checked >= 90, "{checked} points");
}

/// A BSDF of `kind` on the plane `z = 0` (shading normal +z) bumped to the normal of tilt
/// `tilt_deg` toward +x (azimuth `phi_deg`), nested two-sided or not.
fn bumped(kind: MaterialKind, tilt_deg: f32, phi_deg: f32, nested_two_sided: bool) -> Bsdf {
    let m = Material {
        kind,
        kd: Rgb::new(0.7, 0.5, 0.3),
        ks: Rgb::ONE,
        eta: Rgb::new(0.2, 0.92, 1.1),
        k: Rgb::new(3.9, 2.45, 2.14),
        alpha: 0.3,
        microfacet: Microfacet::Ggx,
        two_sided: false,
        ..Material::default()
    }
    .prepared();
    let mut bsdf = Bsdf::new(Lobes::new(&m, m.kd, m.ks), Vec3::Z, Vec3::Z);
    let map = BumpMap {
        texture: 0,
        source: NormalSource::Height { scale: 1.0 },
        flip_invalid_normals: true,
        shadowing: true,
        nested_two_sided,
    };
    let (t, p) = (tilt_deg.to_radians(), phi_deg.to_radians());
    let n = Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
    bsdf.bump = Some(Bump::new(&map, &bsdf.frame, n));
    bsdf
}

fn unit(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// The bumped configurations the sampling tests run: (name, BSDF, wo). `wo` at 70° toward -x
/// lies below a normal tilted 30° toward -x... and is flipped; the others are not.
fn configs() -> Vec<(String, Bsdf, Vec3)> {
    let mut out = Vec::new();
    for (kind, name) in [
        (MaterialKind::Diffuse, "diffuse"),
        (MaterialKind::RoughConductor, "roughconductor"),
    ] {
        for (tilt, phi, two) in [
            (25.0, 0.0, false),
            (50.0, 120.0, true),
            (35.0, 180.0, false),
        ] {
            for wo in [unit(20.0, 10.0), unit(70.0, 0.0), unit(85.0, 200.0)] {
                out.push((
                    format!("{name} tilt {tilt} phi {phi} nested two-sided {two}, wo {wo}"),
                    bumped(kind, tilt, phi, two),
                    wo,
                ));
            }
        }
    }
    out
}

/// Sampling draws directions with the density `pdf` reports (chi-square over the sphere,
/// Šidák-corrected over the configurations).
#[test]
fn sampling_matches_pdf_chi_square() {
    let configs = configs();
    let alpha = sidak(0.01, configs.len());
    for (name, bsdf, wo) in &configs {
        let test = ChiSquareTest::sphere(300_000);
        let r = test.run(
            |rng| {
                bsdf.sample(*wo, rng.uniform(), rng.uniform2(), TransportMode::Radiance)
                    .map(|s| s.wi)
            },
            |wi| bsdf.pdf(*wo, wi) as f64,
        );
        eprintln!(
            "{name}: chi2 {:.1} dof {} p {:.3e} integral {:.4}",
            r.chi2, r.dof, r.p_value, r.integral
        );
        assert!(r.p_value > alpha, "{name}: p = {:.3e}", r.p_value);
    }
}

/// Every sample reports the density and `f` that `pdf` and `eval` give for its direction, and
/// its weight is `f |wi·n_s| / pdf` (radiance and importance mode); the weights' mean is the
/// albedo, which the terminator's shadowing keeps at most 1.
#[test]
fn sample_weight_is_eval_cos_over_pdf() {
    for (name, bsdf, wo) in configs() {
        for mode in [TransportMode::Radiance, TransportMode::Importance] {
            let mut rng = footprint::rng::Rng::new(5, 0xB0, 0);
            let (mut sum, n) = (Rgb::ZERO, 20_000);
            for _ in 0..n {
                let Some(s) = bsdf.sample(wo, rng.uniform(), rng.uniform2(), mode) else {
                    continue;
                };
                let f = bsdf.eval(wo, s.wi, mode);
                let pdf = bsdf.pdf(wo, s.wi);
                let want = f * (s.wi.dot(Vec3::Z).abs() / pdf);
                assert!(
                    close(s.pdf_w, pdf, 1e-5, 0.0)
                        && (s.f - f).abs().max_element() <= 1e-5 * f.max_element(),
                    "{name}: sample reports pdf {} f {}, eval gives {pdf} {f}",
                    s.pdf_w,
                    s.f
                );
                assert!(
                    (s.weight - want).abs().max_element() <= 1e-4 * want.max_element(),
                    "{name} {mode:?}: weight {} against f cos / pdf {want}",
                    s.weight
                );
                sum += s.weight;
            }
            let albedo = sum / n as f32;
            assert!(albedo.max_element() <= 1.02, "{name}: albedo {albedo}");
        }
    }
}

/// A one-rectangle scene (`[-1, 1]²` at `z = 0`, facing +z; the light above) with the BSDF
/// `bsdf`, written to a temporary folder; texture file names are absolute.
fn plane_scene(tag: &str, bsdf: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("footprint-bumpmap-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.xml");
    let xml = format!(
        r#"<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="0.2"/><rotate x="1" angle="180"/><translate z="3"/></transform>
    <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
  {bsdf}
</scene>"#
    );
    std::fs::write(&path, xml).unwrap();
    path
}

fn height(name: &str) -> String {
    common::scenes_dir()
        .join("bumpmap")
        .join(name)
        .display()
        .to_string()
}

/// Points of the plane `(x, y)` in the interior of its texture's cells, each seen straight
/// down from above.
fn plane_hits(scene: &Scene) -> Vec<(footprint::scene::geometry::SurfaceHit, Vec3)> {
    let mut out = Vec::new();
    for i in 0..9 {
        for j in 0..5 {
            let (x, y) = (-0.75 + 0.17 * i as f32, -0.7 + 0.31 * j as f32);
            let o = Vec3::new(x + 0.3, y - 0.2, 2.0);
            let dir = (Vec3::new(x, y, 0.0) - o).normalize();
            let hit = scene.intersect(o, dir, f32::INFINITY).expect("the plane");
            out.push((hit, -dir));
        }
    }
    out
}

/// A constant height field has no gradient: the BSDF is the nested one exactly (the same
/// frame and values, bit for bit), for a diffuse and a rough conductor.
#[test]
fn a_constant_height_field_leaves_the_bsdf_unchanged() {
    let nested = [
        r#"<bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.5, 0.4"/></bsdf>"#,
        r#"<bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha" value="0.2"/></bsdf>"#,
    ];
    for (k, inner) in nested.iter().enumerate() {
        let bumped = format!(
            r#"<shape type="rectangle"><bsdf type="bumpmap"><texture type="bitmap"><string name="filename" value="{}"/></texture><float name="scale" value="3"/>{inner}</bsdf></shape>"#,
            height("flat.png")
        );
        let plain = format!(r#"<shape type="rectangle">{inner}</shape>"#);
        let a = load(&plane_scene(&format!("flat{k}"), &bumped));
        let b = load(&plane_scene(&format!("plain{k}"), &plain));
        assert!(a.materials.iter().any(|m| m.bump.is_some()));
        for ((ha, wo), (hb, _)) in plane_hits(&a).into_iter().zip(plane_hits(&b)) {
            let (ba, bb) = (a.bsdf(&ha), b.bsdf(&hb));
            assert!(ba.bump.is_none(), "no gradient, no bump");
            assert_eq!(format!("{:?}", ba.frame), format!("{:?}", bb.frame));
            for wi in [unit(10.0, 20.0), unit(60.0, 250.0), unit(85.0, 100.0)] {
                let (fa, fb) = (
                    ba.eval(wo, wi, TransportMode::Radiance),
                    bb.eval(wo, wi, TransportMode::Radiance),
                );
                assert_eq!(
                    fa.to_array().map(f32::to_bits),
                    fb.to_array().map(f32::to_bits)
                );
                assert_eq!(ba.pdf(wo, wi).to_bits(), bb.pdf(wo, wi).to_bits());
            }
        }
    }
}

/// A linear ramp `h = (10 + 8 x) / 255` over the 16 columns of `ramp.png` (raw) has
/// `∂h/∂u = 16 · 8 / 255` inside the image (bilinear interpolation of a line is the line);
/// on the rectangle (`∂p/∂u = (2, 0, 0)`, `∂p/∂v = (0, 2, 0)`) scaled by `s` it tilts the
/// normal to `(-2 s ∂h/∂u, 0, 4)`: by `atan(s ∂h/∂u / 2)` toward -x, for either sign of `s`.
#[test]
fn a_linear_ramp_tilts_the_normal_by_the_analytic_angle() {
    for scale in [0.5f32, 2.0, -1.5] {
        let xml = format!(
            r#"<shape type="rectangle"><bsdf type="bumpmap"><texture type="bitmap"><boolean name="raw" value="true"/><string name="filename" value="{}"/></texture><float name="scale" value="{scale}"/><bsdf type="diffuse"/></bsdf></shape>"#,
            height("ramp.png")
        );
        let scene = load(&plane_scene("ramp", &xml));
        let dh_du = 16.0 * 8.0 / 255.0;
        let want = (scale * dh_du / 2.0).atan();
        for (hit, wo) in plane_hits(&scene) {
            let bsdf = scene.bsdf(&hit);
            let bump = bsdf.bump.expect("a gradient");
            let n = bsdf.frame.to_world(bump.normal_local);
            let tilt = (-n.x).atan2(n.z);
            assert!(
                (tilt - want).abs() < 1e-5 && n.y.abs() < 1e-6,
                "scale {scale}: normal {n} tilted {tilt}, want {want}"
            );
            // Seen from above the tilted plane, the flip leaves it as it is.
            assert_eq!(bump.normal_for(bsdf.frame.to_local(wo)), bump.normal_local);
        }
    }
}

/// What the importer refuses, naming the element's line (all on line 8 here); and an `id` on the nested BSDF
/// names the nested BSDF alone, as Mitsuba 3 resolves it (a `<ref>` to it gets no bump).
#[test]
fn the_importer_reads_mitsubas_structure_and_refuses_the_rest() {
    let tex = format!(
        r#"<texture name="map" type="bitmap"><string name="filename" value="{}"/></texture>"#,
        height("bumps.png")
    );
    let diffuse = r#"<bsdf type="diffuse"/>"#;
    let cases = [
        (
            format!(r#"<bsdf type="bumpmap">{tex}</bsdf>"#),
            "needs a nested <bsdf>",
        ),
        (
            format!(r#"<bsdf type="bumpmap">{tex}{diffuse}{diffuse}</bsdf>"#),
            "one nested <bsdf>",
        ),
        (
            format!(r#"<bsdf type="bumpmap">{diffuse}</bsdf>"#),
            "needs a nested <texture>",
        ),
        (
            format!(r#"<bsdf type="bumpmap">{tex}{tex}{diffuse}</bsdf>"#),
            "property 'map' is given twice",
        ),
        (
            format!(r#"<bsdf type="bumpmap"><texture type="checkerboard"/>{diffuse}</bsdf>"#),
            "must be a 'bitmap'",
        ),
        (
            format!(r#"<bsdf type="bumpmap">{tex}<bsdf type="dielectric"/></bsdf>"#),
            "a dielectric inside a bumpmap",
        ),
        (
            format!(r#"<bsdf type="bumpmap">{tex}<emitter type="point"/>{diffuse}</bsdf>"#),
            "not <emitter>",
        ),
        (
            format!(r#"<bsdf type="bumpmap">{tex}<float name="scael" value="2"/>{diffuse}</bsdf>"#),
            "scael",
        ),
        (
            format!(r#"<bsdf type="normalmap">{diffuse}</bsdf>"#),
            "normalmap needs a nested <texture> (the normal map)",
        ),
        (
            format!(r#"<bsdf type="normalmap">{tex}<bsdf type="dielectric"/></bsdf>"#),
            "a dielectric inside a normalmap",
        ),
        (
            // A normal map has no scale.
            format!(
                r#"<bsdf type="normalmap">{tex}<float name="scale" value="2"/>{diffuse}</bsdf>"#
            ),
            "scale",
        ),
    ];
    for (i, (bsdf, want)) in cases.iter().enumerate() {
        let path = plane_scene(
            &format!("bad{i}"),
            &format!("<shape type=\"rectangle\">{bsdf}</shape>"),
        );
        let err = match mitsuba::load(&path, &ImportOptions::default()) {
            Ok(_) => panic!("{bsdf}: imported"),
            Err(e) => e.to_string(),
        };
        assert!(
            err.contains(want) && err.contains("scene.xml:8:"),
            "{bsdf}: {err}"
        );
    }
    // Bitterli's exports: the id on the nested twosided.
    let xml = format!(
        r#"<bsdf type="bumpmap">{tex}<bsdf type="twosided" id="Alu">{diffuse}</bsdf></bsdf>
  <bsdf type="bumpmap" id="Bumped">{tex}<bsdf type="twosided">{diffuse}</bsdf></bsdf>
  <shape type="rectangle"><ref id="Alu"/></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-1"/></transform><ref id="Bumped"/></shape>"#
    );
    let scene = load(&plane_scene("ids", &xml));
    let hit = scene
        .intersect(Vec3::new(0.1, 0.1, 2.0), -Vec3::Z, f32::INFINITY)
        .expect("the plane at z = 0");
    let alu = &scene.materials[hit.material as usize];
    assert!(alu.bump.is_none() && alu.two_sided, "{alu:?}");
    let bumped = scene
        .materials
        .iter()
        .find(|m| m.name == "Bumped")
        .expect("the bumped material");
    let b = bumped.bump.expect("a bump");
    assert!(
        b.nested_two_sided && !bumped.two_sided && b.source == NormalSource::Height { scale: 1.0 }
    );
    assert!(b.flip_invalid_normals && b.shadowing);
    // A normal map: the same adapter with the texture's colours as normals, its options read.
    let xml = format!(
        r#"<bsdf type="normalmap" id="Mapped">{tex}<boolean name="use_shadowing_function" value="false"/>{diffuse}</bsdf>
  <shape type="rectangle"><ref id="Mapped"/></shape>"#
    );
    let scene = load(&plane_scene("normals", &xml));
    let mapped = scene.materials.iter().find(|m| m.name == "Mapped");
    let b = mapped
        .expect("the mapped material")
        .bump
        .expect("a normal map");
    assert_eq!(b.source, NormalSource::Normals);
    assert!(b.flip_invalid_normals && !b.shadowing && !b.nested_two_sided);
}
