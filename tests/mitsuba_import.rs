//! Mitsuba 3 XML import: what is read (parameters, references, transforms, sensor, shapes,
//! materials, emitters), the errors for what is not (element, line, what is supported), the
//! `--lenient` stand-ins, the export round trip, and the pixel filters the import brings.
//! Image agreement with Mitsuba 3 itself is `tests/mitsuba.rs`.

mod common;

use footprint::bsdf::Lobes;
use footprint::bsdf::material::MaterialKind;
use footprint::bsdf::microfacet::Microfacet;
use footprint::bsdf::principled::PrincipledParams;
use footprint::film::filter::{FilterKind, PixelFilter};
use footprint::scene::Scene;
use footprint::scene::light::Light;
use footprint::scene::mitsuba::{self, ImportOptions};
use glam::{Vec2, Vec3};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh folder with the given files.
fn dir_with(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let d = std::env::temp_dir().join(format!("footprint-mitsuba-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join("meshes")).unwrap();
    for (f, text) in files {
        std::fs::write(d.join(f), text).unwrap();
    }
    d
}

const SENSOR: &str = r#"<sensor type="perspective">
    <float name="fov" value="$fov"/>
    <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
    <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
    <film type="hdrfilm"><integer name="width" value="$resx"/><integer name="height" value="16"/><rfilter type="tent"/></film>
  </sensor>"#;

const LIGHT: &str = r#"<shape type="rectangle">
    <transform name="to_world"><rotate x="1" angle="90"/><translate y="2"/></transform>
    <emitter type="area"><rgb name="radiance" value="2, 3, 4"/></emitter>
  </shape>"#;

fn scene_xml(body: &str) -> String {
    format!(
        "<scene version=\"3.0.0\">\n  <default name=\"fov\" value=\"40\"/>\n  <default name=\"resx\" value=\"32\"/>\n  {SENSOR}\n  {LIGHT}\n  {body}\n</scene>\n"
    )
}

fn load(dir: &Path, defines: &[(&str, &str)], lenient: bool) -> footprint::Result<Scene> {
    mitsuba::load(
        &dir.join("scene.xml"),
        &ImportOptions {
            defines: defines
                .iter()
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect(),
            lenient,
        },
    )
}

fn load_err(name: &str, body: &str) -> String {
    let d = dir_with(name, &[("scene.xml", &scene_xml(body))]);
    match load(&d, &[], false) {
        Ok(_) => panic!("{name}: expected an error"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn sensor_film_parameters_and_defines() {
    let d = dir_with("sensor", &[("scene.xml", &scene_xml(""))]);
    let s = load(&d, &[], false).unwrap();
    let c = &s.camera;
    assert_eq!((c.width, c.height), (32, 16));
    assert_eq!(s.settings.spp, 4);
    assert_eq!(c.filter.kind, FilterKind::Tent { radius: 1.0 });
    // fov_axis x (Mitsuba's default): the 40 degrees span the width.
    let tan_x = (20.0f32).to_radians().tan();
    let want_fov_y = 2.0 * (tan_x * 16.0 / 32.0).atan().to_degrees();
    assert!(
        (c.fov_y_deg - want_fov_y).abs() < 1e-3,
        "{} vs {want_fov_y}",
        c.fov_y_deg
    );
    // Looking down -z from z = 5 with y up: image right is world +x (Mitsuba's lookat).
    assert!((c.position - Vec3::new(0.0, 0.0, 5.0)).length() < 1e-6);
    assert!((c.frame.z - Vec3::NEG_Z).length() < 1e-6);
    assert!(
        (c.frame.x - Vec3::X).length() < 1e-6,
        "right = {:?}",
        c.frame.x
    );
    // -D overrides a default, as on Mitsuba's command line.
    let s = load(&d, &[("resx", "64"), ("fov", "30")], false).unwrap();
    assert_eq!(s.camera.width, 64);
    let want = 2.0
        * ((15.0f32).to_radians().tan() * 16.0 / 64.0)
            .atan()
            .to_degrees();
    assert!((s.camera.fov_y_deg - want).abs() < 1e-3);
    // -D of a parameter the scene does not have is an error (whole names: `$resx` is not
    // `$res`).
    let e = load(&d, &[("nope", "1")], false).err().unwrap().to_string();
    assert!(e.contains("nope"), "{e}");
    let e = load(&d, &[("res", "8")], false).err().unwrap().to_string();
    assert!(e.contains("'$res'"), "{e}");
}

#[test]
fn shapes_transforms_and_area_lights() {
    let body = r#"<shape type="cube"><transform name="to_world"><scale value="0.5"/><translate x="3"/></transform></shape>
  <shape type="sphere"><point name="center" x="-3" y="0" z="0"/><float name="radius" value="0.5"/></shape>
  <shape type="rectangle" id="flipped"><boolean name="flip_normals" value="true"/>
    <transform name="to_world"><matrix value="1 0 0 0  0 1 0 0  0 0 1 -2  0 0 0 1"/></transform>
    <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>"#;
    let d = dir_with("shapes", &[("scene.xml", &scene_xml(body))]);
    let s = load(&d, &[], false).unwrap();
    let mut area_by_material = std::collections::HashMap::<u32, f32>::new();
    for (t, sh) in s.triangles.iter().zip(s.shading.iter()) {
        *area_by_material.entry(sh.material).or_default() += t.area();
    }
    // Light rectangle: [-1,1]^2 rotated +90 deg about x (its +z normal becomes -y), at y = 2.
    let lights: Vec<_> = s
        .lights
        .iter()
        .filter_map(|l| match l {
            Light::Area { n, le, geom, .. } => Some((*n, *le, *geom)),
            _ => None,
        })
        .collect();
    assert_eq!(
        lights.len(),
        4,
        "two area-light rectangles of two triangles"
    );
    let top: Vec<_> = lights.iter().filter(|l| l.1.y == 3.0).collect();
    assert_eq!(top.len(), 2);
    for (n, _, g) in &top {
        assert!((*n - Vec3::NEG_Y).length() < 1e-5, "normal {n:?}");
        assert!((g.p0.y - 2.0).abs() < 1e-5);
    }
    // flip_normals: the rectangle at z = -2 emits toward -z instead of +z.
    for (n, le, g) in lights.iter().filter(|l| l.1 == footprint::Rgb::ONE) {
        assert!(
            (*n - Vec3::NEG_Z).length() < 1e-5,
            "flipped normal {n:?} {le:?}"
        );
        assert!((g.p0.z + 2.0).abs() < 1e-5);
    }
    // Cube of half-size 0.5: area 6; the sphere of radius 0.5: area pi within the
    // tessellation's deficit (< 0.1%). Both use the default material (one-sided diffuse 0.5).
    let default_mats: Vec<u32> = s
        .materials
        .iter()
        .enumerate()
        .filter(|(_, m)| m.name == "default" && !m.emits())
        .map(|(i, _)| i as u32)
        .collect();
    assert_eq!(default_mats.len(), 1);
    let m = &s.materials[default_mats[0] as usize];
    assert!(!m.two_sided && m.kind == MaterialKind::Diffuse && m.kd == footprint::Rgb::splat(0.5));
    let (mut cube_area, mut sphere_area) = (0.0, 0.0);
    for (t, sh) in s.triangles.iter().zip(s.shading.iter()) {
        if sh.material != default_mats[0] {
            continue;
        }
        let c = (t.p0 + t.e1 / 3.0 + t.e2 / 3.0).x;
        let outward = if c > 0.0 {
            Vec3::new(3.0, 0.0, 0.0)
        } else {
            Vec3::new(-3.0, 0.0, 0.0)
        };
        let centroid = t.p0 + (t.e1 + t.e2) / 3.0;
        assert!(
            t.cross().dot(centroid - outward) > 0.0,
            "faces point outward"
        );
        if c > 0.0 {
            cube_area += t.area();
        } else {
            sphere_area += t.area();
        }
    }
    assert!((cube_area - 6.0).abs() < 1e-4, "cube area {cube_area}");
    let pi = std::f32::consts::PI;
    assert!(
        sphere_area < pi && sphere_area > pi * 0.999,
        "sphere area {sphere_area}"
    );
}

/// Nested objects may carry a `name` (`<ref name="bsdf" id="m"/>`, `<rfilter name="rfilter">`),
/// and a mirroring transform does not turn Mitsuba's rectangle around (its front follows the
/// transformed normal, not the winding).
#[test]
fn named_objects_and_mirrored_primitives() {
    let body = r#"<bsdf type="twosided" id="m"><bsdf type="diffuse" name="bsdf"><rgb name="reflectance" value="0.3"/></bsdf></bsdf>
  <shape type="cube"><ref name="bsdf" id="m"/></shape>
  <shape type="rectangle" id="mirror_x">
    <transform name="to_world"><scale x="-1"/><translate z="-4"/></transform>
    <emitter type="area" name="emitter"><rgb name="radiance" value="5"/></emitter></shape>
  <shape type="rectangle" id="mirror_z">
    <transform name="to_world"><scale z="-1"/><translate z="-6"/></transform>
    <emitter type="area"><rgb name="radiance" value="7"/></emitter></shape>"#;
    let xml = scene_xml(body).replace(
        "<rfilter type=\"tent\"/>",
        "<rfilter type=\"box\" name=\"rfilter\"/>",
    );
    let d = dir_with("named", &[("scene.xml", &xml)]);
    let s = load(&d, &[], false).unwrap();
    assert_eq!(s.camera.filter.kind, FilterKind::Box);
    assert!(
        s.materials
            .iter()
            .any(|m| m.kd == footprint::Rgb::splat(0.3) && m.two_sided),
        "the referenced BSDF is used"
    );
    for (le, want) in [(5.0, Vec3::Z), (7.0, Vec3::NEG_Z)] {
        for l in &s.lights {
            if let Light::Area { n, le: e, .. } = l {
                if e.x == le {
                    assert!(
                        (*n - want).length() < 1e-5,
                        "radiance {le}: normal {n:?}, want {want:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn materials_references_and_textures() {
    let body = r#"<bsdf type="twosided" id="gold"><bsdf type="roughconductor">
      <string name="distribution" value="ggx"/><float name="alpha" value="0.2"/>
      <rgb name="eta" value="0.2, 0.4, 1.4"/><rgb name="k" value="3.9, 2.4, 1.8"/></bsdf></bsdf>
  <bsdf type="plastic" id="red"><rgb name="diffuse_reflectance" value="0.5, 0.1, 0.1"/><string name="int_ior" value="bk7"/></bsdf>
  <texture type="checkerboard" id="check"><rgb name="color0" value="0.9"/><rgb name="color1" value="0.1"/>
    <transform name="to_uv"><scale x="4" y="2"/></transform></texture>
  <shape type="rectangle"><ref id="gold"/></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-1"/></transform><ref id="red"/></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-2"/></transform>
    <bsdf type="diffuse"><ref name="reflectance" id="check"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-3"/></transform>
    <bsdf type="dielectric"><float name="int_ior" value="1.33"/><rgb name="specular_transmittance" value="0.5"/></bsdf></shape>"#;
    let d = dir_with("materials", &[("scene.xml", &scene_xml(body))]);
    let s = load(&d, &[], false).unwrap();
    let by_kind = |k: MaterialKind| s.materials.iter().find(|m| m.kind == k).unwrap();
    let gold = by_kind(MaterialKind::RoughConductor);
    assert!(gold.two_sided && gold.microfacet == Microfacet::Ggx && gold.alpha == 0.2);
    assert_eq!(gold.k, footprint::Rgb::new(3.9, 2.4, 1.8));
    let red = by_kind(MaterialKind::Plastic);
    assert!(!red.two_sided);
    assert!(
        (red.ni - 1.5046 / 1.000277).abs() < 1e-5,
        "named IOR bk7 over air: {}",
        red.ni
    );
    let glass = by_kind(MaterialKind::Glass);
    // specular_transmittance applies at each interface: 0.25 per passage in and out.
    assert!((glass.tf.x - 0.25).abs() < 1e-6 && (glass.ni - 1.33 / 1.000277).abs() < 1e-5);
    // The checkerboard with to_uv (4, 2): Mitsuba's uv (u, v) -> (4u, 2v); colour0 where the
    // fractional parts are both below or both above 1/2. Stored uv are OBJ-style (v up).
    let diffuse = s
        .materials
        .iter()
        .find(|m| m.kind == MaterialKind::Diffuse && m.kd_texture.is_some())
        .unwrap();
    let tex = &s.textures[diffuse.kd_texture.unwrap() as usize];
    let at = |u: f32, v_mitsuba: f32| tex.lookup(Vec2::new(u, 1.0 - v_mitsuba)).x;
    assert_eq!(at(0.05, 0.1), 0.9);
    assert_eq!(at(0.2, 0.1), 0.1);
    assert_eq!(at(0.2, 0.3), 0.9);
    assert_eq!(at(0.3, 0.6), 0.9);
    assert_eq!(at(0.3, 0.8), 0.1);
}

/// `roughdielectric`: the Practical Path Guiding torus scene's BSDF (named indices, the
/// default Beckmann distribution), a GGX one with constant factors; its errors name the
/// element's line; and it survives the export round trip.
#[test]
fn rough_dielectric_is_read_and_written() {
    let body = r#"<shape type="rectangle"><bsdf type="roughdielectric"><string name="int_ior" value="acrylic glass"/>
      <string name="ext_ior" value="air"/><float name="alpha" value="0.01"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-1"/></transform>
    <bsdf type="roughdielectric"><string name="distribution" value="ggx"/><float name="alpha" value="0.3"/>
      <float name="int_ior" value="1.33"/><float name="ext_ior" value="1.0"/>
      <rgb name="specular_reflectance" value="0.9, 0.8, 0.7"/><rgb name="specular_transmittance" value="0.5"/></bsdf></shape>"#;
    let d = dir_with("roughdielectric", &[("scene.xml", &scene_xml(body))]);
    let s = load(&d, &[], false).unwrap();
    let rough: Vec<_> = s
        .materials
        .iter()
        .filter(|m| m.kind == MaterialKind::RoughGlass)
        .collect();
    assert_eq!(rough.len(), 2);
    let torus = rough.iter().find(|m| m.alpha == 0.01).unwrap();
    assert_eq!(torus.microfacet, Microfacet::Beckmann);
    assert!((torus.ni - 1.49 / 1.000277).abs() < 1e-6, "{}", torus.ni);
    assert_eq!(
        (torus.ks, torus.tf),
        (footprint::Rgb::ONE, footprint::Rgb::ONE)
    );
    let ggx = rough.iter().find(|m| m.alpha == 0.3).unwrap();
    assert_eq!(ggx.microfacet, Microfacet::Ggx);
    assert!((ggx.ni - 1.33).abs() < 1e-6);
    assert_eq!(ggx.ks, footprint::Rgb::new(0.9, 0.8, 0.7));
    // specular_transmittance applies at each crossing: 0.25 per passage in and out.
    assert!((ggx.tf - footprint::Rgb::splat(0.25)).abs().max_element() < 1e-6);
    assert!(s.effects.glossy && !s.effects.refraction);

    // Written back and read again: the same parameters.
    let out = dir_with("roughdielectric-export", &[]);
    footprint::scene::mitsuba::export::export(&s, &d.join("scene.xml"), &out).unwrap();
    let back = load(&out, &[], false).unwrap();
    for m in &rough {
        let b = back
            .materials
            .iter()
            .find(|b| b.kind == MaterialKind::RoughGlass && b.alpha == m.alpha)
            .unwrap();
        assert_eq!((b.microfacet, b.ks), (m.microfacet, m.ks));
        assert!((b.ni - m.ni).abs() < 1e-6 && (b.tf - m.tf).abs().max_element() < 1e-6);
    }

    // Bad input: the element's line and what is wrong.
    let bad = |name: &str, props: &str| {
        load_err(
            name,
            &format!(
                "<shape type=\"cube\">\n<bsdf type=\"roughdielectric\">{props}</bsdf></shape>"
            ),
        )
    };
    let e = bad("rd-alpha", r#"<float name="alpha" value="-0.1"/>"#);
    assert!(
        e.contains("scene.xml:15:") && e.contains("alpha must be in"),
        "{e}"
    );
    let e = bad("rd-distr", r#"<string name="distribution" value="phong"/>"#);
    assert!(e.contains("scene.xml:15:") && e.contains("phong"), "{e}");
    let e = bad(
        "rd-ior",
        r#"<float name="int_ior" value="1.2"/><float name="ext_ior" value="1.2"/>"#,
    );
    assert!(
        e.contains("scene.xml:15:") && e.contains("must differ"),
        "{e}"
    );
    let e = bad("rd-tex", r#"<texture name="alpha" type="checkerboard"/>"#);
    assert!(
        e.contains("scene.xml:15:") && e.contains("'alpha' is a <texture>"),
        "{e}"
    );
}

/// `principled`: Mitsuba's defaults; every parameter, constant and as a texture (a
/// checkerboard roughness, read at the hits); `eta` and `specular` with Mitsuba's adjustments
/// where the material transmits; an anisotropic material's tangent along `∂p/∂u`; errors
/// naming the element's line; and the export round trip.
#[test]
fn principled_is_read_and_written() {
    let body = r#"<shape type="rectangle"><bsdf type="principled"/></shape>
  <shape type="rectangle"><transform name="to_world"><translate x="3"/></transform>
    <bsdf type="twosided"><bsdf type="principled"><rgb name="base_color" value="0.8, 0.2, 0.1"/>
      <float name="metallic" value="0.3"/><float name="specular" value="0.7"/><float name="spec_tint" value="0.2"/>
      <float name="anisotropic" value="0.5"/><float name="sheen" value="0.4"/><float name="sheen_tint" value="0.6"/>
      <float name="clearcoat" value="0.7"/><float name="clearcoat_gloss" value="0.9"/><float name="flatness" value="0.1"/>
      <float name="main_specular_sampling_rate" value="2"/><float name="clearcoat_sampling_rate" value="0.5"/>
      <float name="diffuse_reflectance_sampling_rate" value="0.25"/>
      <texture name="roughness" type="checkerboard"><float name="color0" value="0.9"/><float name="color1" value="0.1"/></texture>
    </bsdf></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><translate x="6"/></transform>
    <bsdf type="principled"><float name="spec_trans" value="0.5"/><float name="eta" value="1"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><translate x="9"/></transform>
    <bsdf type="principled"><float name="spec_trans" value="1"/><float name="specular" value="0"/>
      <texture name="base_color" type="checkerboard"><rgb name="color0" value="0.9, 0.5, 0.1"/></texture></bsdf></shape>"#;
    let d = dir_with("principled", &[("scene.xml", &scene_xml(body))]);
    let s = load(&d, &[], false).unwrap();
    let at_x = |x: f32| {
        let hit = s
            .intersect(Vec3::new(x, 0.3, 5.0), Vec3::NEG_Z, 10.0)
            .expect("the rectangle is hit");
        (s.materials[hit.material as usize].clone(), hit)
    };
    let (m, _) = at_x(0.2);
    assert_eq!(m.kind, MaterialKind::Principled);
    assert!(!m.two_sided && m.kd == footprint::Rgb::splat(0.5) && m.kd_texture.is_none());
    assert_eq!(m.principled, PrincipledParams::default());
    assert!((m.principled.eta - 1.5).abs() < 1e-6, "specular 0.5: η 1.5");

    let (m, _) = at_x(3.2);
    let p = m.principled;
    assert!(m.two_sided && m.kd == footprint::Rgb::new(0.8, 0.2, 0.1));
    let constants = [
        p.metallic,
        p.spec_tint,
        p.anisotropic,
        p.sheen,
        p.sheen_tint,
    ];
    assert_eq!(constants.map(|c| c.value), [0.3, 0.2, 0.5, 0.4, 0.6]);
    assert_eq!(
        [p.clearcoat.value, p.clearcoat_gloss.value, p.flatness.value],
        [0.7, 0.9, 0.1]
    );
    assert_eq!(
        (p.rates.diffuse, p.rates.specular, p.rates.clearcoat),
        (0.25, 2.0, 0.5)
    );
    assert_eq!(p.eta, PrincipledParams::eta_of_specular(0.7));
    assert!(p.roughness.texture.is_some() && !p.may_transmit());
    // The checkerboard's scalar value at the hits (Mitsuba's uv of the rectangle: ((x + 1)/2,
    // (y + 1)/2) of its local point), Mitsuba's `eval_1`: color1 (0.1) where both coordinates
    // are below 1/2, where its colour (`eval`) is color0, and color0 (0.9) where one is above
    // (checked with Mitsuba 3.9.1); and the anisotropic lobe's tangent is ∂p/∂u, +x.
    for (x, y, want) in [(2.5f32, -0.5f32, 0.1f32), (3.5, -0.5, 0.9)] {
        let hit = s
            .intersect(Vec3::new(x, y, 5.0), Vec3::NEG_Z, 10.0)
            .unwrap();
        let b = s.bsdf(&hit);
        let Lobes::Principled(l) = b.lobes else {
            panic!("not principled")
        };
        assert!(
            (l.roughness - want).abs() < 1e-6,
            "({x}, {y}): {}",
            l.roughness
        );
        assert!(l.is_anisotropic());
        assert!(
            (b.frame.x - Vec3::X).length() < 1e-5,
            "tangent {}",
            b.frame.x
        );
    }
    // Transmitting: η 1 becomes 1.001, specular 0 becomes 1e-3, as Mitsuba makes them.
    assert_eq!(at_x(6.2).0.principled.eta, 1.001);
    let (m, _) = at_x(9.2);
    assert_eq!(m.principled.eta, PrincipledParams::eta_of_specular(1e-3));
    assert!(m.kd_texture.is_some() && m.principled.may_transmit());
    assert!(s.effects.glossy && s.effects.diffuse && s.effects.textures);
    assert!(s.effects.coloured_filtering);

    // Written back and read again: the same parameters, the roughness still a texture.
    let out = dir_with("principled-export", &[]);
    footprint::scene::mitsuba::export::export(&s, &d.join("scene.xml"), &out).unwrap();
    let back = load(&out, &[], false).unwrap();
    let written: Vec<_> = s
        .materials
        .iter()
        .filter(|m| m.kind == MaterialKind::Principled)
        .collect();
    for m in written {
        let b = back
            .materials
            .iter()
            .find(|b| {
                b.kind == MaterialKind::Principled
                    && b.kd == m.kd
                    && b.two_sided == m.two_sided
                    && b.principled.eta == m.principled.eta
            })
            .unwrap_or_else(|| panic!("{} not written back", m.name));
        let texture = |p: &PrincipledParams| p.scalars().map(|(_, s)| s.texture.is_some());
        let values = |p: &PrincipledParams| {
            p.scalars()
                .map(|(_, s)| s.texture.map_or(s.value, |_| -1.0))
        };
        assert_eq!(texture(&b.principled), texture(&m.principled), "{}", m.name);
        assert_eq!(values(&b.principled), values(&m.principled), "{}", m.name);
        assert_eq!(b.principled.rates, m.principled.rates);
        assert_eq!(b.kd_texture.is_some(), m.kd_texture.is_some());
    }

    // Bad input: the element's line and what is wrong.
    let bad =
        |name: &str, bsdf: &str| load_err(name, &format!("<shape type=\"cube\">\n{bsdf}</shape>"));
    let principled = |props: &str| format!("<bsdf type=\"principled\">{props}</bsdf>");
    for (name, props, what) in [
        (
            "pr-rough",
            r#"<float name="roughness" value="1.5"/>"#,
            "'roughness' must lie in [0, 1]",
        ),
        (
            "pr-base",
            r#"<rgb name="base_color" value="1.2, 0.5, 0.5"/>"#,
            "'base_color' must lie in [0, 1]",
        ),
        (
            "pr-both",
            r#"<float name="eta" value="1.5"/><float name="specular" value="0.5"/>"#,
            "not both",
        ),
        (
            "pr-eta",
            r#"<float name="eta" value="-1"/>"#,
            "'eta' must be positive",
        ),
        (
            "pr-rate",
            r#"<float name="clearcoat_sampling_rate" value="-1"/>"#,
            "must not be negative",
        ),
        (
            "pr-etatex",
            r#"<texture name="eta" type="checkerboard"/>"#,
            "'eta' must be a <float>",
        ),
        (
            "pr-unknown",
            r#"<float name="subsurface" value="0.5"/>"#,
            "'subsurface'",
        ),
    ] {
        let e = bad(name, &principled(props));
        assert!(
            e.contains("scene.xml:15:") && e.contains(what),
            "{name}: {e}"
        );
    }
    let e = bad(
        "pr-twosided",
        &format!(
            "<bsdf type=\"twosided\">{}</bsdf>",
            principled(r#"<float name="spec_trans" value="0.2"/>"#)
        ),
    );
    assert!(
        e.contains("scene.xml:15:") && e.contains("transmits"),
        "{e}"
    );
}

/// An OBJ without texture coordinates: Mitsuba's uv is the face's barycentrics `(b1, b2)`
/// (checked with Mitsuba 3.9.1: the triangle (0,0,0), (1,0,0), (0,1,0) hit at (0.2, 0.3) has
/// uv (0.2, 0.3)), which a checkerboard then sees; also with flip_normals.
#[test]
fn meshes_without_uvs_use_mitsubas_barycentrics() {
    for flip in ["false", "true"] {
        let body = format!(
            r#"<shape type="obj"><string name="filename" value="tri.obj"/><boolean name="flip_normals" value="{flip}"/>
    <bsdf type="twosided"><bsdf type="diffuse"><texture name="reflectance" type="checkerboard">
      <rgb name="color0" value="0.9"/><rgb name="color1" value="0.1"/></texture></bsdf></bsdf></shape>"#
        );
        let d = dir_with(
            &format!("nouv{flip}"),
            &[
                ("scene.xml", &scene_xml(&body)),
                ("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
            ],
        );
        let s = load(&d, &[], false).unwrap();
        // Hit points (x, y) on the triangle: uv = (x, y); colour0 where both coordinates are on
        // the same side of 1/2.
        for (x, y, want) in [(0.2f32, 0.3f32, 0.9f32), (0.6, 0.3, 0.1), (0.2, 0.6, 0.1)] {
            let hit = s
                .intersect(Vec3::new(x, y, 1.0), Vec3::NEG_Z, 10.0)
                .expect("the triangle is hit");
            let m = &s.materials[hit.material as usize];
            let kd = m.kd * s.textures[m.kd_texture.unwrap() as usize].lookup(hit.uv);
            assert!(
                (kd.x - want).abs() < 1e-6,
                "flip {flip}: ({x}, {y}) -> {kd:?}, want {want}"
            );
        }
    }
}

#[test]
fn errors_name_the_element_line_and_what_is_supported() {
    // Unknown BSDF type: line of the element, the supported list, the --lenient hint.
    let e = load_err(
        "bsdf",
        "<shape type=\"cube\">\n<bsdf type=\"hair\"/></shape>",
    );
    assert!(
        e.contains("scene.xml:15:")
            && e.contains("bsdf 'hair'")
            && e.contains("roughplastic")
            && e.contains("--lenient"),
        "{e}"
    );
    // Unknown shape, unknown property, undefined parameter, dangling reference.
    let e = load_err(
        "shape",
        "<shape type=\"bsplinecurve\"><string name=\"filename\" value=\"x.txt\"/></shape>",
    );
    assert!(
        e.contains("shape 'bsplinecurve'") && e.contains("obj, ply, serialized, rectangle"),
        "{e}"
    );
    let e = load_err(
        "prop",
        "<shape type=\"cube\"><float name=\"radiuss\" value=\"1\"/></shape>",
    );
    assert!(e.contains("radiuss"), "{e}");
    let e = load_err(
        "param",
        "<shape type=\"sphere\"><float name=\"radius\" value=\"$r\"/></shape>",
    );
    assert!(e.contains("$r") && e.contains("-D r="), "{e}");
    let e = load_err("ref", "<shape type=\"cube\"><ref id=\"missing\"/></shape>");
    assert!(e.contains("missing"), "{e}");
    let e = load_err(
        "number",
        "<shape type=\"sphere\"><float name=\"radius\" value=\"big\"/></shape>",
    );
    assert!(e.contains("'big' is not a finite number"), "{e}");
    // A BSDF that contains itself.
    let e = load_err(
        "cycle",
        "<bsdf type=\"twosided\" id=\"a\"><ref id=\"a\"/></bsdf><shape type=\"cube\"><ref id=\"a\"/></shape>",
    );
    assert!(e.contains("cycle"), "{e}");
    // XML syntax: line and column from the parser.
    let d = dir_with(
        "syntax",
        &[("scene.xml", "<scene>\n  <shape type=\"cube\">\n</scene>\n")],
    );
    let e = load(&d, &[], false).err().unwrap().to_string();
    assert!(e.contains("scene.xml:3:"), "{e}");
    // The version is required, as in Mitsuba 3, and must be a version number.
    for (name, root, expect) in [
        ("noversion", "<scene>", "needs a 'version'"),
        (
            "badversion",
            "<scene version=\"three\">",
            "not a version number",
        ),
    ] {
        let d = dir_with(name, &[("scene.xml", &format!("{root}\n</scene>\n"))]);
        let e = load(&d, &[], false).err().unwrap().to_string();
        assert!(e.contains(expect) && e.contains("scene.xml:1:"), "{e}");
    }
    // A missing mesh file names the file.
    for (kind, file) in [
        ("obj", "nothere.obj"),
        ("ply", "nothere.ply"),
        ("serialized", "nothere.serialized"),
    ] {
        let e = load_err(
            kind,
            &format!("<shape type=\"{kind}\"><string name=\"filename\" value=\"{file}\"/></shape>"),
        );
        assert!(e.contains(file), "{e}");
    }
    // A negative shape_index, as Mitsuba.
    let e = load_err(
        "index",
        "<shape type=\"serialized\"><string name=\"filename\" value=\"m.serialized\"/><integer name=\"shape_index\" value=\"-1\"/></shape>",
    );
    assert!(e.contains("'shape_index' must be a non-negative"), "{e}");
    // No light: the scene's own error.
    let d = dir_with(
        "dark",
        &[(
            "scene.xml",
            &format!(
                "<scene version=\"3.0.0\"><default name=\"fov\" value=\"40\"/><default name=\"resx\" value=\"8\"/>{SENSOR}<shape type=\"cube\"/></scene>"
            ),
        )],
    );
    let e = load(&d, &[], false).err().unwrap().to_string();
    assert!(e.contains("no lights"), "{e}");
}

#[test]
fn lenient_replaces_and_says_so() {
    let body = "<shape type=\"cube\"><bsdf type=\"hair\"/></shape>\n<medium type=\"homogeneous\"/>";
    let d = dir_with("lenient", &[("scene.xml", &scene_xml(body))]);
    assert!(load(&d, &[], false).is_err());
    let s = load(&d, &[], true).unwrap();
    assert_eq!(s.import_notes.len(), 2, "{:?}", s.import_notes);
    assert!(
        s.import_notes[0].contains("bsdf 'hair'") && s.import_notes[0].contains("grey diffuse")
    );
    assert!(s.import_notes[1].contains("<medium>"));
    // The command line: a non-zero exit without --lenient; notes on stderr with it.
    let run = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_footprint"))
            .arg("render")
            .arg(d.join("scene.xml"))
            .args(["--out", d.join("o.exr").to_str().unwrap(), "--spp", "1"])
            .args(extra)
            .output()
            .unwrap()
    };
    let o = run(&[]);
    assert!(!o.status.success() && !d.join("o.exr").exists());
    let o = run(&["--lenient", "-D", "resx=8"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("note:") && err.contains("bsdf 'hair'"),
        "{err}"
    );
}

/// Exporting a bundled scene and reading it back gives the same triangles, materials,
/// lights and camera.
#[test]
fn export_round_trip() {
    let src = common::scene_path("cornell");
    let scene = footprint::scene::load::load_scene(&src).unwrap();
    let d = dir_with("export", &[]);
    footprint::scene::mitsuba::export::export(&scene, &src, &d).unwrap();
    let back = load(&d, &[], false).unwrap();
    assert_eq!(back.triangles.len(), scene.triangles.len());
    assert_eq!(back.lights.len(), scene.lights.len());
    let area = |s: &Scene| s.triangles.iter().map(|t| t.area() as f64).sum::<f64>();
    assert!((area(&back) / area(&scene) - 1.0).abs() < 1e-6);
    let power = |s: &Scene| s.lights.iter().map(|l| l.power() as f64).sum::<f64>();
    assert!((power(&back) / power(&scene) - 1.0).abs() < 1e-5);
    let (a, b) = (&scene.camera, &back.camera);
    assert_eq!((a.width, a.height), (b.width, b.height));
    assert!((a.fov_y_deg - b.fov_y_deg).abs() < 1e-4);
    assert!((a.frame.x - b.frame.x).length() < 1e-5 && (a.frame.z - b.frame.z).length() < 1e-5);
    // The same rays hit the same triangles with the same albedo.
    for i in 0..200 {
        let r = Vec2::new((i % 20) as f32 * 0.05 + 0.025, (i / 20) as f32 * 0.1 + 0.05)
            * Vec2::new(a.width as f32, a.height as f32);
        let (ha, hb) = (
            scene.intersect(a.position, a.ray_dir(r), f32::INFINITY),
            back.intersect(b.position, b.ray_dir(r), f32::INFINITY),
        );
        match (ha, hb) {
            (Some(x), Some(y)) => {
                assert!((x.t - y.t).abs() < 1e-4 * x.t.max(1.0));
                let (ma, mb) = (
                    &scene.materials[x.material as usize],
                    &back.materials[y.material as usize],
                );
                assert_eq!(ma.kd, mb.kd);
                assert_eq!(ma.ke, mb.ke);
            }
            (None, None) => {}
            _ => panic!("ray {i} hits in one scene only"),
        }
    }
}

/// Filter importance sampling and the light tracer's splat weights describe the same
/// filter: sampled raster positions of a pixel follow the tabulated profile cut off at the
/// film's edges (chi-square over the covered area), and the splat weights of every pixel sum
/// to one over the film.
#[test]
fn pixel_filters_sample_what_they_splat() {
    for kind in [
        FilterKind::Box,
        FilterKind::Tent { radius: 1.0 },
        FilterKind::Gaussian { stddev: 0.5 },
        FilterKind::Tent { radius: 2.5 },
    ] {
        let f = PixelFilter::new(kind);
        let (w, h) = (6u32, 5u32);
        // Splat weights at raster x, as a density for pixel p: it integrates to 1 over the film.
        for (px, py) in [(0u32, 0u32), (2, 2), (5, 4)] {
            let cells = 60usize;
            let (x0, x1) = (0.0f32, w as f32);
            let (y0, y1) = (0.0f32, h as f32);
            let weight_at = |x: f32, y: f32| {
                let mut wgt = 0.0;
                f.splat_weights(Vec2::new(x, y), w, h, |i, v| {
                    if i == py * w + px {
                        wgt += v;
                    }
                });
                wgt
            };
            // Midpoint integral of the splat density over the film.
            let n = 600;
            let mut total = 0.0f64;
            for i in 0..n {
                for j in 0..n {
                    let x = x0 + (i as f32 + 0.5) * (x1 - x0) / n as f32;
                    let y = y0 + (j as f32 + 0.5) * (y1 - y0) / n as f32;
                    total += weight_at(x, y) as f64;
                }
            }
            total *= ((x1 - x0) * (y1 - y0)) as f64 / (n * n) as f64;
            assert!(
                (total - 1.0).abs() < 0.01,
                "{kind:?} pixel ({px},{py}): splat weights integrate to {total}"
            );
            // Chi-square: samples of the pixel against the splat density, cells over the film.
            let cell_of = |p: Vec2| {
                let cx = ((p.x / w as f32) * cells as f32) as usize;
                let cy = ((p.y / h as f32) * cells as f32) as usize;
                cx.min(cells - 1) * cells + cy.min(cells - 1)
            };
            let mut masses = vec![0.0f64; cells * cells];
            let sub = 4;
            for cx in 0..cells {
                for cy in 0..cells {
                    let mut m = 0.0f64;
                    for a in 0..sub {
                        for b in 0..sub {
                            let x = (cx as f32 + (a as f32 + 0.5) / sub as f32) * w as f32
                                / cells as f32;
                            let y = (cy as f32 + (b as f32 + 0.5) / sub as f32) * h as f32
                                / cells as f32;
                            m += weight_at(x, y) as f64;
                        }
                    }
                    masses[cx * cells + cy] = m / (sub * sub) as f64
                        * (w as f64 / cells as f64)
                        * (h as f64 / cells as f64);
                }
            }
            let mut rng = footprint::rng::Rng::new(5, 9, (px * 10 + py) as u64);
            let samples: Vec<usize> = (0..200_000)
                .map(|_| cell_of(f.sample_raster(px, py, w, h, rng.uniform2())))
                .collect();
            // Pearson's chi-square (cells expecting fewer than 5 samples pooled); fixed seed,
            // significance 1% Šidák-corrected over the 12 cases.
            let mut observed = vec![0.0f64; cells * cells];
            for c in &samples {
                observed[*c] += 1.0;
            }
            let n = samples.len() as f64;
            let (chi2, bins) = common::chi2::pearson_pooled(
                observed.iter().zip(&masses).map(|(o, m)| (*o, m * n)),
            );
            let p = common::chi2_sf(chi2, (bins - 1) as f64);
            assert!(
                p > common::sidak(0.01, 12),
                "{kind:?} pixel ({px},{py}): chi2 {chi2:.1} over {bins} bins, p = {p:.2e}"
            );
        }
    }
}

/// The triangles of the shapes whose default-material diffuse reflectance is `kd` (each shape
/// of a test scene gets its own), with their shading.
fn shape_triangles(
    s: &Scene,
    kd: f32,
) -> Vec<(
    footprint::scene::geometry::TriangleGeom,
    footprint::scene::geometry::TriangleShading,
)> {
    s.triangles
        .iter()
        .zip(s.shading.iter())
        .filter(|(_, sh)| s.materials[sh.material as usize].kd.x == kd)
        .map(|(t, sh)| (*t, *sh))
        .collect()
}

/// The torus of `scenes/meshes` from its OBJ, from its PLY (which Mitsuba 3 wrote from the
/// OBJ, texture coordinates flipped as Mitsuba reads OBJ's) and from mesh 1 of
/// `meshes.serialized` (double precision) gives the same triangles, shading normals and
/// texture coordinates, under the same transform. The OBJ's six decimals bound the
/// differences.
#[test]
fn the_same_mesh_from_obj_ply_and_serialized_gives_the_same_triangles() {
    let dir = common::scenes_dir().join("meshes");
    let load_shape = |kind: &str, file: &str, extra: &str| {
        let body = format!(
            r#"<shape type="{kind}"><string name="filename" value="{}"/>{extra}
    <transform name="to_world"><rotate x="1" angle="30"/><translate y="0.5" z="-1"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.25"/></bsdf></shape>"#,
            dir.join(file).display()
        );
        let d = dir_with(&format!("same-{kind}"), &[("scene.xml", &scene_xml(&body))]);
        shape_triangles(&load(&d, &[], false).unwrap(), 0.25)
    };
    let obj = load_shape("obj", "torus.obj", "");
    assert_eq!(obj.len(), 576);
    for (kind, file, extra) in [
        ("ply", "torus.ply", ""),
        (
            "serialized",
            "meshes.serialized",
            r#"<integer name="shape_index" value="1"/>"#,
        ),
    ] {
        let other = load_shape(kind, file, extra);
        assert_eq!(other.len(), obj.len(), "{kind}");
        let centroid = |t: &footprint::scene::geometry::TriangleGeom| t.p0 + (t.e1 + t.e2) / 3.0;
        for (t, sh) in &obj {
            // The same triangle: the one whose centroid is nearest (the BVH orders them).
            let (u, ush) = other
                .iter()
                .min_by(|a, b| {
                    let da = (centroid(&a.0) - centroid(t)).length();
                    let db = (centroid(&b.0) - centroid(t)).length();
                    da.total_cmp(&db)
                })
                .unwrap();
            let close = |a: Vec3, b: Vec3, tol: f32| (a - b).length() < tol;
            assert!(
                close(t.p0, u.p0, 1e-5) && close(t.e1, u.e1, 1e-5) && close(t.e2, u.e2, 1e-5),
                "{kind}: triangle {t:?} against {u:?}"
            );
            let (n, un) = (sh.normals.unwrap(), ush.normals.unwrap());
            let (uv, uuv) = (sh.uvs.unwrap(), ush.uvs.unwrap());
            for k in 0..3 {
                assert!(
                    close(n[k], un[k], 1e-4),
                    "{kind}: normal {:?} against {:?}",
                    n[k],
                    un[k]
                );
                assert!(
                    (uv[k] - uuv[k]).length() < 1e-5,
                    "{kind}: uv {:?} against {:?}",
                    uv[k],
                    uuv[k]
                );
            }
        }
    }
}

/// A PLY shape's options: `flip_tex_coords` flips v, `face_normals` drops the shading
/// normals, `flip_normals` turns the normals and the winding around; and mesh 0 of
/// `meshes.serialized`, which has no normals, gets Mitsuba's angle-weighted ones.
#[test]
fn ply_options_and_computed_normals() {
    let dir = common::scenes_dir().join("meshes");
    let ply = dir.join("torus.ply");
    let body = format!(
        r#"<shape type="ply"><string name="filename" value="{0}"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.1"/></bsdf></shape>
  <shape type="ply"><string name="filename" value="{0}"/><boolean name="flip_tex_coords" value="true"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.2"/></bsdf></shape>
  <shape type="ply"><string name="filename" value="{0}"/><boolean name="face_normals" value="true"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.3"/></bsdf></shape>
  <shape type="ply"><string name="filename" value="{0}"/><boolean name="flip_normals" value="true"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.4"/></bsdf></shape>
  <shape type="serialized"><string name="filename" value="{1}"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.6"/></bsdf></shape>"#,
        ply.display(),
        dir.join("meshes.serialized").display()
    );
    let d = dir_with("ply-options", &[("scene.xml", &scene_xml(&body))]);
    let s = load(&d, &[], false).unwrap();
    let key = |t: &footprint::scene::geometry::TriangleGeom| {
        let c = t.p0 + (t.e1 + t.e2) / 3.0;
        [c.x, c.y, c.z].map(|x| (x * 1e4).round() as i64)
    };
    let by_centroid = |kd: f32| {
        let mut v = shape_triangles(&s, kd);
        v.sort_by_key(|(t, _)| key(t));
        v
    };
    let plain = by_centroid(0.1);
    assert_eq!(plain.len(), 576);
    for ((t, sh), (_, flipped_uv)) in plain.iter().zip(&by_centroid(0.2)) {
        let (a, b) = (sh.uvs.unwrap(), flipped_uv.uvs.unwrap());
        for k in 0..3 {
            assert!((a[k].x - b[k].x).abs() < 1e-6 && (a[k].y - (1.0 - b[k].y)).abs() < 1e-6);
        }
        // The torus is smooth: the shading normals lie on the winding's side.
        let ng = t.cross();
        assert!(sh.normals.unwrap().iter().all(|n| n.dot(ng) > 0.0));
    }
    assert!(by_centroid(0.3).iter().all(|(_, sh)| sh.normals.is_none()));
    for ((t, sh), (u, flipped)) in plain.iter().zip(&by_centroid(0.4)) {
        assert!(
            t.cross().dot(u.cross()) < 0.0,
            "flip_normals turns the winding"
        );
        let (a, b) = (sh.normals.unwrap(), flipped.normals.unwrap());
        // The winding's reversal swaps the first and last vertex.
        for (k, j) in [(0, 2), (1, 1), (2, 0)] {
            assert!(
                (a[k] + b[j]).length() < 1e-6,
                "{:?} against {:?}",
                a[k],
                b[j]
            );
        }
    }
    // The octahedron: each vertex's normal is its own direction (four faces, equal angles).
    let octahedron = shape_triangles(&s, 0.6);
    assert_eq!(octahedron.len(), 8);
    for (t, sh) in &octahedron {
        let p = [t.p0, t.p0 + t.e1, t.p0 + t.e2];
        for (p, n) in p.iter().zip(sh.normals.unwrap()) {
            assert!((p.normalize() - n).length() < 1e-5, "{p:?}: {n:?}");
        }
    }
}

/// `disk` and `cylinder`: areas within 0.1% of the exact shapes', normals out of the cylinder
/// (its axis from `p0` to `p1`) and along the disk's transformed +z; `flip_normals` turns the
/// cylinder's normals in and a mirroring transform does not (as in Mitsuba 3.9.1); a
/// cylinder of no radius or no length is an error.
#[test]
fn disk_and_cylinder_shapes() {
    let cylinder = |kd: f32, extra: &str| {
        format!(
            r#"<shape type="cylinder"><point name="p0" x="1" y="-1" z="0"/><point name="p1" x="1" y="1" z="0"/>
    <float name="radius" value="0.5"/>{extra}<bsdf type="diffuse"><rgb name="reflectance" value="{kd}"/></bsdf></shape>"#
        )
    };
    let body = [
        cylinder(0.1, ""),
        cylinder(0.2, r#"<boolean name="flip_normals" value="true"/>"#),
        // Mirrored in x about the origin: the axis at x = -1.
        cylinder(0.3, r#"<transform name="to_world"><scale x="-1"/></transform>"#),
        r#"<shape type="disk"><transform name="to_world"><scale value="2"/><rotate y="1" angle="90"/><translate z="-3"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.4"/></bsdf></shape>"#
            .to_string(),
    ]
    .join("\n");
    let d = dir_with("disk-cylinder", &[("scene.xml", &scene_xml(&body))]);
    let s = load(&d, &[], false).unwrap();
    let pi = std::f32::consts::PI;
    for (kd, axis_x, outward) in [(0.1, 1.0, 1.0), (0.2, 1.0, -1.0), (0.3, -1.0, 1.0)] {
        let tris = shape_triangles(&s, kd);
        let area: f32 = tris.iter().map(|(t, _)| t.area()).sum();
        let exact = 2.0 * pi * 0.5 * 2.0;
        assert!((area / exact - 1.0).abs() < 1e-3, "{kd}: area {area}");
        for (t, sh) in &tris {
            let c = t.p0 + (t.e1 + t.e2) / 3.0;
            let radial = Vec3::new(c.x - axis_x, 0.0, c.z).normalize();
            assert!(
                t.cross().normalize().dot(radial) * outward > 0.99,
                "{kd}: winding"
            );
            for (k, n) in sh.normals.unwrap().iter().enumerate() {
                let p = [t.p0, t.p0 + t.e1, t.p0 + t.e2][k];
                let r = Vec3::new(p.x - axis_x, 0.0, p.z);
                assert!((r.length() - 0.5).abs() < 1e-5);
                assert!(
                    (*n - r.normalize() * outward).length() < 1e-5,
                    "{kd}: {n:?}"
                );
            }
        }
    }
    // The disk of radius 2 turned to face +x.
    let disk = shape_triangles(&s, 0.4);
    let area: f32 = disk.iter().map(|(t, _)| t.area()).sum();
    assert!((area / (4.0 * pi) - 1.0).abs() < 1e-3, "disk area {area}");
    assert!(disk.iter().all(|(t, sh)| {
        t.cross().normalize().dot(Vec3::X) > 0.9999
            && sh
                .normals
                .unwrap()
                .iter()
                .all(|n| (*n - Vec3::X).length() < 1e-5)
    }));
    for (what, shape) in [
        (
            "radius",
            r#"<shape type="cylinder"><float name="radius" value="0"/></shape>"#,
        ),
        (
            "length",
            r#"<shape type="cylinder"><point name="p1" x="0" y="0" z="0"/></shape>"#,
        ),
    ] {
        let e = load_err(&format!("cylinder-{what}"), shape);
        assert!(
            e.contains("cylinder needs a positive radius and p0 != p1"),
            "{e}"
        );
    }
}

/// Where a ray meets a disk and a cylinder, footprint's tessellation gives Mitsuba's normal and
/// texture coordinates (values printed by Mitsuba 3.9.1 `scalar_rgb` for these rays: the
/// cylinder's `u = φ / 2π` with φ from Mitsuba's frame about the axis, `v` along it; the
/// disk's `(r, φ / 2π)`), also under a mirroring transform, to the tessellation's accuracy.
#[test]
fn disk_and_cylinder_hits_match_mitsuba() {
    // (to_world, ray origin and direction, Mitsuba's normal and uv) for the cylinder from
    // (1, -1, 0) to (1, 1, 0.3) of radius 0.5 and for the unit disk moved to z = -2.
    let cylinder = [
        (
            "",
            Vec3::new(3.0, 0.1, 0.2),
            Vec3::NEG_X,
            Vec3::new(0.997601, -0.010269, 0.0684598),
            Vec2::new(0.988974, 0.552567),
        ),
        (
            r#"<scale x="-1"/>"#,
            Vec3::new(-3.0, 0.1, 0.2),
            Vec3::X,
            Vec3::new(-0.997601, -0.010269, 0.0684598),
            Vec2::new(0.988974, 0.552567),
        ),
    ];
    for (transform, o, dir, n, uv) in cylinder {
        let body = format!(
            r#"<shape type="cylinder"><point name="p0" x="1" y="-1" z="0"/><point name="p1" x="1" y="1" z="0.3"/>
    <float name="radius" value="0.5"/><transform name="to_world">{transform}</transform></shape>"#
        );
        let d = dir_with("cylinder-hit", &[("scene.xml", &scene_xml(&body))]);
        let s = load(&d, &[], false).unwrap();
        let hit = s.intersect(o, dir, 10.0).expect("the cylinder is hit");
        assert!(
            (hit.ns - n).length() < 2e-3,
            "{transform}: normal {:?}",
            hit.ns
        );
        assert!(hit.ng.dot(n) > 0.99, "{transform}: the winding faces out");
        let mitsuba_uv = Vec2::new(hit.uv.x, 1.0 - hit.uv.y);
        assert!(
            (mitsuba_uv - uv).length() < 2e-3,
            "{transform}: uv {mitsuba_uv:?}"
        );
    }
    for (transform, uv) in [
        ("", Vec2::new(0.5, 0.147584)),
        (r#"<scale x="-1"/>"#, Vec2::new(0.5, 0.352416)),
    ] {
        let body = format!(
            r#"<shape type="disk"><transform name="to_world"><translate z="-2"/>{transform}</transform></shape>"#
        );
        let d = dir_with("disk-hit", &[("scene.xml", &scene_xml(&body))]);
        let s = load(&d, &[], false).unwrap();
        let hit = s
            .intersect(Vec3::new(0.3, 0.4, 0.0), Vec3::NEG_Z, 10.0)
            .expect("the disk is hit");
        assert!((hit.ns - Vec3::Z).length() < 1e-5 && hit.ng.dot(Vec3::Z) > 0.9999);
        let mitsuba_uv = Vec2::new(hit.uv.x, 1.0 - hit.uv.y);
        assert!(
            (mitsuba_uv - uv).length() < 2e-3,
            "{transform}: uv {mitsuba_uv:?}"
        );
    }
}

/// A Mitsuba 0.5 file (Bitterli's collection is published so) reads as Mitsuba 3 upgrades
/// it: camelCase property names, a `diffuse` BSDF's `diffuseReflectance`, and a texture's
/// `uscale`/`vscale`/`uoffset` as its `to_uv`; the same scene written for version 3 gives the
/// same materials and textures. In a version 3 file the old names are errors, as in Mitsuba 3.
#[test]
fn version_0_5_files_upgrade_as_mitsuba_3() {
    let old = r#"<bsdf type="plastic" id="red"><rgb name="diffuseReflectance" value="0.5, 0.1, 0.1"/><float name="intIOR" value="1.4"/></bsdf>
  <shape type="rectangle"><transform name="toWorld"><translate z="-1"/></transform><ref id="red"/></shape>
  <shape type="rectangle"><transform name="toWorld"><translate z="-2"/></transform>
    <bsdf type="diffuse"><texture name="diffuseReflectance" type="checkerboard"><rgb name="color0" value="0.9"/>
      <rgb name="color1" value="0.1"/><float name="uscale" value="4"/><float name="vscale" value="2"/>
      <float name="uoffset" value="0.25"/></texture></bsdf></shape>"#;
    let new = r#"<bsdf type="plastic" id="red"><rgb name="diffuse_reflectance" value="0.5, 0.1, 0.1"/><float name="int_ior" value="1.4"/></bsdf>
  <shape type="rectangle"><transform name="to_world"><translate z="-1"/></transform><ref id="red"/></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-2"/></transform>
    <bsdf type="diffuse"><texture name="reflectance" type="checkerboard"><rgb name="color0" value="0.9"/>
      <rgb name="color1" value="0.1"/><transform name="to_uv"><translate x="0.25"/><scale x="4" y="2"/></transform></texture></bsdf></shape>"#;
    let legacy = scene_xml(old).replace("version=\"3.0.0\"", "version=\"0.5.0\"");
    let a = load(&dir_with("legacy", &[("scene.xml", &legacy)]), &[], false).unwrap();
    let b = load(
        &dir_with("upgraded", &[("scene.xml", &scene_xml(new))]),
        &[],
        false,
    )
    .unwrap();
    assert_eq!(a.materials.len(), b.materials.len());
    for (m, n) in a.materials.iter().zip(&b.materials) {
        assert_eq!(
            (m.kind, m.kd, m.ni, m.kd_texture),
            (n.kind, n.kd, n.ni, n.kd_texture)
        );
    }
    assert_eq!(a.textures.len(), 1);
    let (ta, tb) = (&a.textures[0], &b.textures[0]);
    assert!(
        tb.to_uv.is_some() && ta.to_uv == tb.to_uv,
        "{:?} {:?}",
        ta.to_uv,
        tb.to_uv
    );
    for (u, v) in [(0.05, 0.1), (0.2, 0.3), (0.3, 0.8), (0.7, 0.45)] {
        let uv = Vec2::new(u, v);
        assert_eq!(ta.lookup(uv), tb.lookup(uv));
    }
    // The old names in a version 3 file are properties nobody reads.
    let e = load(
        &dir_with("oldnames", &[("scene.xml", &scene_xml(old))]),
        &[],
        false,
    )
    .err()
    .unwrap()
    .to_string();
    assert!(e.contains("'diffuseReflectance'"), "{e}");
}

/// Mitsuba's `mask`: the nested BSDF with its opacity (a number, a colour's or spectrum's
/// luminance, a texture; default 0.5), through `twosided` and references; written back as a
/// mask; bad opacities and nestings name their line.
#[test]
fn masks_are_read_and_written() {
    let body = r#"<bsdf type="mask" id="leaf">
    <texture name="opacity" type="checkerboard"><rgb name="color0" value="1"/><rgb name="color1" value="0"/></texture>
    <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.1"/></bsdf></bsdf>
  </bsdf>
  <shape type="rectangle"><ref id="leaf"/></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-1"/></transform>
    <bsdf type="mask"><spectrum name="opacity" value="0.612066"/><bsdf type="diffuse"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-2"/></transform>
    <bsdf type="mask"><bsdf type="roughconductor"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-3"/></transform>
    <bsdf type="diffuse"/></shape>"#;
    let d = dir_with("mask", &[("scene.xml", &scene_xml(body))]);
    let s = load(&d, &[], false).unwrap();
    let leaf = s.materials.iter().find(|m| m.name == "leaf").unwrap();
    assert!(leaf.two_sided && leaf.kind == MaterialKind::Diffuse);
    assert_eq!((leaf.opacity, leaf.opacity_texture.is_some()), (1.0, true));
    let blinds = s
        .materials
        .iter()
        .find(|m| m.opacity_texture.is_none() && m.opacity < 0.7)
        .unwrap();
    assert!((blinds.opacity - 0.612066).abs() < 1e-5 && !blinds.two_sided);
    let metal = s
        .materials
        .iter()
        .find(|m| m.kind == MaterialKind::RoughConductor)
        .unwrap();
    assert_eq!(metal.opacity, 0.5, "Mitsuba's default opacity");
    assert!(s.materials.iter().any(|m| !m.is_masked()));
    assert!(s.effects.masks && s.effects.textures);

    // Written back and read again: the same opacities.
    let out = dir_with("mask-export", &[]);
    footprint::scene::mitsuba::export::export(&s, &d.join("scene.xml"), &out).unwrap();
    let back = load(&out, &[], false).unwrap();
    let opacities = |s: &Scene| {
        let mut o: Vec<_> = s
            .materials
            .iter()
            .filter(|m| !m.emits())
            .map(|m| (m.opacity.to_bits(), m.opacity_texture.is_some()))
            .collect();
        o.sort();
        o
    };
    assert_eq!(opacities(&back), opacities(&s));

    // Bad input: the element's line and what is wrong.
    let bad = |name: &str, props: &str| {
        load_err(
            name,
            &format!("<shape type=\"cube\">\n<bsdf type=\"mask\">{props}</bsdf></shape>"),
        )
    };
    let e = bad(
        "mask-range",
        r#"<float name="opacity" value="1.5"/><bsdf type="diffuse"/>"#,
    );
    assert!(
        e.contains("scene.xml:15:") && e.contains("opacity must be in [0, 1]"),
        "{e}"
    );
    let e = bad("mask-none", r#"<float name="opacity" value="0.5"/>"#);
    assert!(
        e.contains("scene.xml:15:") && e.contains("exactly one nested <bsdf>, found 0"),
        "{e}"
    );
    let e = bad("mask-glass", r#"<bsdf type="dielectric"/>"#);
    assert!(
        e.contains("scene.xml:15:") && e.contains("a mask around a dielectric"),
        "{e}"
    );
    // A mask on a light is refused (Mitsuba's emitter ignores it; footprint's walks would not).
    let e = load_err(
        "mask-light",
        r#"<shape type="cube"><bsdf type="mask"><bsdf type="diffuse"/></bsdf>
        <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>"#,
    );
    assert!(
        e.contains("scene.xml:14:") && e.contains("a mask on an emitting shape"),
        "{e}"
    );
}

/// Mitsuba's `blendbsdf`: two nested BSDFs (by reference too) and `weight` (a number, clamped
/// as Mitsuba clamps it, or a texture), `twosided` around it reaching both components; written
/// back as a blend; a missing weight, a wrong count and a dielectric inside name their line.
#[test]
fn blends_are_read_and_written() {
    let body = r#"<bsdf type="roughconductor" id="metal"><float name="alpha" value="0.2"/></bsdf>
  <bsdf type="twosided" id="mix"><bsdf type="blendbsdf">
    <float name="weight" value="0.3"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.1"/></bsdf>
    <ref id="metal"/>
  </bsdf></bsdf>
  <shape type="rectangle"><ref id="mix"/></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-1"/></transform>
    <bsdf type="blendbsdf"><texture name="weight" type="checkerboard"/><float name="unused" value="1"/>
      <bsdf type="plastic"/><bsdf type="diffuse"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-2"/></transform>
    <bsdf type="blendbsdf"><float name="weight" value="1.7"/><bsdf type="diffuse"/><bsdf type="plastic"/></bsdf></shape>"#;
    let d = dir_with("blend", &[("scene.xml", &scene_xml(body))]);
    let e = match load(&d, &[], false) {
        Ok(_) => panic!("an unread property is an error"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains("unused"), "{e}");
    let d = dir_with(
        "blend",
        &[(
            "scene.xml",
            &scene_xml(&body.replace(r#"<float name="unused" value="1"/>"#, "")),
        )],
    );
    let s = load(&d, &[], false).unwrap();
    let mix = s.materials.iter().find(|m| m.name == "mix").unwrap();
    let b = mix.blend.as_ref().expect("a blend");
    assert_eq!(
        (mix.kind, b.other.kind),
        (MaterialKind::Diffuse, MaterialKind::RoughConductor)
    );
    assert!(mix.two_sided && b.other.two_sided, "twosided reaches both");
    assert_eq!((b.weight, b.weight_texture), (0.3, None));
    assert_eq!(b.other.alpha, 0.2);
    let textured = s
        .materials
        .iter()
        .find(|m| m.kind == MaterialKind::Plastic)
        .unwrap();
    let tb = textured.blend.as_ref().unwrap();
    assert!(tb.weight_texture.is_some() && tb.other.kind == MaterialKind::Diffuse);
    let clamped = s
        .materials
        .iter()
        .find(|m| {
            m.blend
                .as_ref()
                .is_some_and(|b| b.other.kind == MaterialKind::Plastic)
        })
        .unwrap();
    assert_eq!(clamped.blend.as_ref().unwrap().weight, 1.0);
    assert!(s.effects.non_lambertian && s.effects.glossy && s.effects.specular_reflection);

    // Written back and read again: the same components and weights.
    let out = dir_with("blend-export", &[]);
    footprint::scene::mitsuba::export::export(&s, &d.join("scene.xml"), &out).unwrap();
    let back = load(&out, &[], false).unwrap();
    let blends = |s: &Scene| {
        let mut v: Vec<_> = s
            .materials
            .iter()
            .filter_map(|m| {
                let b = m.blend.as_ref()?;
                Some((
                    format!("{:?}/{:?}", m.kind, b.other.kind),
                    b.weight.to_bits(),
                    b.weight_texture.is_some(),
                    (m.two_sided, b.other.two_sided),
                ))
            })
            .collect();
        v.sort();
        v
    };
    assert_eq!(blends(&back), blends(&s));

    // Bad input: the element's line and what is wrong.
    let bad = |name: &str, props: &str| {
        load_err(
            name,
            &format!("<shape type=\"cube\">\n<bsdf type=\"blendbsdf\">{props}</bsdf></shape>"),
        )
    };
    let e = bad(
        "blend-weight",
        r#"<bsdf type="diffuse"/><bsdf type="diffuse"/>"#,
    );
    assert!(
        e.contains("scene.xml:15:") && e.contains("needs a 'weight'"),
        "{e}"
    );
    let e = bad(
        "blend-one",
        r#"<float name="weight" value="0.5"/><bsdf type="diffuse"/>"#,
    );
    assert!(
        e.contains("scene.xml:15:") && e.contains("two nested <bsdf>, found 1"),
        "{e}"
    );
    let e = bad(
        "blend-glass",
        "<float name=\"weight\" value=\"0.5\"/><bsdf type=\"diffuse\"/>\n<bsdf type=\"dielectric\"/>",
    );
    assert!(
        e.contains("scene.xml:16:") && e.contains("a dielectric in a blendbsdf"),
        "{e}"
    );
}

/// Mitsuba's `thinlens` sensor: `aperture_radius` (required) and `focus_distance` (default
/// `far_clip`, itself 1e4 by default) are read with perspective's other parameters; an
/// aperture of 0 is the pinhole; a scaled `to_world` is refused, as Mitsuba refuses it; a TOML
/// camera takes the same lens and exports it as a `thinlens` that reads back the same.
#[test]
fn thinlens_sensor_reads_its_aperture_and_focus() {
    let thin = |props: &str, transform: &str| {
        scene_xml("")
            .replace(
                "<sensor type=\"perspective\">",
                &format!("<sensor type=\"thinlens\">{props}"),
            )
            .replace(
                "<lookat origin=\"0, 0, 5\"",
                &format!("{transform}<lookat origin=\"0, 0, 5\""),
            )
    };
    let load_thin = |name: &str, props: &str, transform: &str| {
        let d = dir_with(name, &[("scene.xml", &thin(props, transform))]);
        load(&d, &[], false)
    };
    let r#ref = load(
        &dir_with("pinhole-ref", &[("scene.xml", &scene_xml(""))]),
        &[],
        false,
    )
    .unwrap()
    .camera;
    let lens =
        r#"<float name="aperture_radius" value="0.1"/><float name="focus_distance" value="3"/>"#;
    let c = load_thin("thinlens", lens, "").unwrap().camera;
    assert!(c.has_lens());
    assert_eq!((c.lens_radius(), c.focus_distance()), (0.1, 3.0));
    // The rest as perspective reads it.
    assert_eq!((c.width, c.height), (r#ref.width, r#ref.height));
    assert!((c.fov_y_deg - r#ref.fov_y_deg).abs() < 1e-6);
    assert!((c.position - r#ref.position).length() < 1e-6);
    assert!((c.frame.x - r#ref.frame.x).length() < 1e-6);
    // focus_distance defaults to far_clip, and that to 1e4.
    let radius = r#"<float name="aperture_radius" value="0.2"/>"#;
    let c = load_thin("thin-default", radius, "").unwrap().camera;
    assert_eq!(c.focus_distance(), 1e4);
    let far = r#"<float name="aperture_radius" value="0.2"/><float name="far_clip" value="50"/>"#;
    assert_eq!(
        load_thin("thin-far", far, "")
            .unwrap()
            .camera
            .focus_distance(),
        50.0
    );
    // An aperture of 0 is the pinhole.
    let zero = r#"<float name="aperture_radius" value="0"/>"#;
    assert!(!load_thin("thin-zero", zero, "").unwrap().camera.has_lens());
    // Errors: no aperture, a negative one, a scaled to_world.
    let e = load_thin("thin-none", "", "").err().unwrap().to_string();
    assert!(e.contains("aperture_radius"), "{e}");
    let neg = r#"<float name="aperture_radius" value="-0.1"/>"#;
    let e = load_thin("thin-neg", neg, "").err().unwrap().to_string();
    assert!(e.contains("aperture radius"), "{e}");
    let e = load_thin("thin-scaled", lens, "<scale value=\"2\"/>")
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("scale"), "{e}");
    // A TOML camera with a lens (focus defaulting to the distance to look_at), exported and
    // read back.
    let d = dir_with(
        "toml-lens",
        &[
            (
                "s.toml",
                "[camera]\nposition = [0.0, 0.0, -3.0]\nlook_at = [0.0, 0.0, 1.0]\nfov_y = 40.0\n\
             resolution = [16, 16]\naperture_radius = 0.05\n[[mesh]]\nfile = \"m.obj\"\n\
             [[light]]\ntype = \"point\"\nposition = [0.0, 1.0, -1.0]\nintensity = [1.0, 1.0, 1.0]\n",
            ),
            ("m.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n"),
        ],
    );
    let scene = footprint::scene::load::load_scene(&d.join("s.toml")).unwrap();
    assert_eq!(
        (scene.camera.lens_radius(), scene.camera.focus_distance()),
        (0.05, 4.0)
    );
    let out = dir_with("toml-lens-export", &[]);
    footprint::scene::mitsuba::export::export(&scene, &d.join("s.toml"), &out).unwrap();
    assert!(
        std::fs::read_to_string(out.join("scene.xml"))
            .unwrap()
            .contains("thinlens")
    );
    let back = load(&out, &[], false).unwrap().camera;
    assert_eq!((back.lens_radius(), back.focus_distance()), (0.05, 4.0));
}

/// Anisotropic roughness: `alpha_u` and `alpha_v` of a `roughconductor` and a
/// `roughdielectric` are read as they are (equal ones are the isotropic `alpha`); a
/// `roughplastic`'s, or one inside a `bumpmap`, is unsupported, lenient: `sqrt(α_u α_v)`;
/// `export` writes them back.
#[test]
fn anisotropic_roughness_is_read() {
    let rough = |kind: &str, u: f32, v: f32| {
        format!(
            r#"<shape type="rectangle"><bsdf type="{kind}"><string name="distribution" value="ggx"/>
    <float name="alpha_u" value="{u}"/><float name="alpha_v" value="{v}"/></bsdf></shape>"#
        )
    };
    let body = format!(
        "{}\n{}\n{}",
        rough("roughconductor", 0.1, 0.4),
        rough("roughdielectric", 0.3, 0.05),
        rough("roughconductor", 0.2, 0.2)
    );
    let d = dir_with("anisotropic", &[("scene.xml", &scene_xml(&body))]);
    let s = load(&d, &[], false).unwrap();
    let find = |k: MaterialKind, a: f32| {
        s.materials
            .iter()
            .find(|m| m.kind == k && m.alpha == a)
            .unwrap_or_else(|| panic!("{k:?} α {a}"))
    };
    let c = find(MaterialKind::RoughConductor, 0.1);
    assert!(c.is_anisotropic() && c.alpha_v == Some(0.4));
    let g = find(MaterialKind::RoughGlass, 0.3);
    assert_eq!(g.alpha_v, Some(0.05));
    assert!(!find(MaterialKind::RoughConductor, 0.2).is_anisotropic());
    // Exported and read back.
    let out = dir_with("anisotropic-export", &[]);
    footprint::scene::mitsuba::export::export(&s, &d.join("scene.xml"), &out).unwrap();
    let back = load(&out, &[], false).unwrap();
    assert!(
        back.materials
            .iter()
            .any(|m| m.alpha == 0.1 && m.alpha_v == Some(0.4))
    );
    // Unsupported: a rough plastic's anisotropy, and anisotropy inside a bump map.
    let plastic = rough("roughplastic", 0.1, 0.4);
    let heights = common::scenes_dir().join("bumpmap").join("bumps.png");
    let bumped = format!(
        r#"<shape type="rectangle"><bsdf type="bumpmap"><texture type="bitmap"><string name="filename" value="{}"/></texture>{}</bsdf></shape>"#,
        heights.display(),
        rough("roughconductor", 0.1, 0.4)
            .trim_start_matches(r#"<shape type="rectangle">"#)
            .trim_end_matches("</shape>")
    );
    for (name, body) in [("aniso-plastic", plastic), ("aniso-bump", bumped)] {
        let d = dir_with(name, &[("scene.xml", &scene_xml(&body))]);
        let e = load(&d, &[], false).err().unwrap().to_string();
        assert!(e.contains("anisotropic"), "{name}: {e}");
        let s = load(&d, &[], true).unwrap();
        assert!(
            s.import_notes
                .iter()
                .any(|n| n.contains("sqrt(alpha_u alpha_v) = 0.2"))
        );
        assert!(s.materials.iter().all(|m| !m.is_anisotropic()));
    }
}
