//! The lights at infinity: Mitsuba 3's `directional` and `envmap` emitters.
//!
//! * The environment map's direction sampling against its own density (chi-square), and the
//!   mean of `L / pdf` against the map's integral over the sphere; a uniform map's samples
//!   fall on its rows in proportion to their solid angle, which fails without the `sin θ`
//!   weighting or the `(u, v) ↦ ω` Jacobian.
//! * Every integrator, guided or not, converges to the path tracer's image on a box on a floor
//!   lit by a directional light and on the same lit by an envmap (`tests/emitters/*.xml`).
//! * Both images' means agree with Mitsuba 3's (`tests/emitters/mitsuba-means.json`, made by
//!   `python3 scripts/emitter_means.py` with the scenes and the map).
//! * Bad input names its file and element.
//!
//! Every statistical bound is a critical value times a standard error estimated from the
//! samples themselves, at significance 0.01 Šidák-corrected over the tests of the function,
//! with fixed seeds (so each test gives the same verdict every run).

mod common;

use common::chi2::{ChiSquareTest, pearson_pooled};
use common::{chi2_sf, sidak, t_critical};
use footprint::Rgb;
use footprint::math::{PI, luminance};
use footprint::rng::Rng;
use footprint::scene::Scene;
use footprint::scene::envmap::EnvMap;
use footprint::scene::light::Light;
use footprint::scene::mitsuba::{self, ImportOptions};
use footprint_integrators::{Method, RenderOptions, render};
use glam::{Mat3, Vec2, Vec3};
use std::path::PathBuf;
use std::sync::Arc;

/// A sky brighter toward the zenith over a dim ground, with a sun of peak 60 a few texels
/// wide at `(u, v) = (0.3, 0.3)` (the map of `scripts/emitter_means.py`).
fn sky(width: usize, height: usize) -> Vec<Rgb> {
    let mut t = Vec::with_capacity(width * height);
    for j in 0..height {
        for i in 0..width {
            let v = (j as f32 + 0.5) / height as f32;
            let u = (i as f32 + 0.5) / width as f32;
            let up = (1.0 - 2.0 * v).clamp(0.0, 1.0);
            let mut c = Rgb::new(0.15 + 0.2 * up, 0.2 + 0.3 * up, 0.3 + 0.6 * up);
            if v > 0.5 {
                c *= 0.3;
            }
            let du = (u - 0.3).abs().min(1.0 - (u - 0.3).abs()) * width as f32;
            let dv = (v - 0.3) * height as f32;
            let sun = 60.0 * (-(du * du + dv * dv) / (2.0 * 1.2 * 1.2)).exp();
            t.push(c + Rgb::new(1.0, 0.9, 0.7) * sun);
        }
    }
    t
}

/// An environment light of the map, as `Scene::new` places it (unit bounding sphere).
fn env_light(map: EnvMap) -> Light {
    Light::Environment {
        le: Rgb::ONE,
        map: Some(Arc::new(map)),
        center: Vec3::ZERO,
        radius: 1.0,
    }
}

/// `∫ L dω` of the map by the midpoint rule over `(u, v)`, `dω = 2π² sin θ du dv`, on a grid
/// 64 times finer than the texels each way (the bilinear radiance is smooth within a cell).
fn integral_by_quadrature(map: &EnvMap) -> [f64; 3] {
    let (w, h) = map.size();
    let (nu, nv) = (64 * w, 64 * h);
    let mut sum = [0.0f64; 3];
    for b in 0..nv {
        let v = (b as f64 + 0.5) / nv as f64;
        let jac = 2.0 * std::f64::consts::PI.powi(2) * (std::f64::consts::PI * v).sin();
        for a in 0..nu {
            let u = (a as f64 + 0.5) / nu as f64;
            let l = map.lookup(Vec2::new(u as f32, v as f32));
            for c in 0..3 {
                sum[c] += l[c] as f64 * jac;
            }
        }
    }
    sum.map(|s| s / (nu * nv) as f64)
}

/// Next-event estimation's directions of an envmap (through `Light::sample_li`) follow the
/// light's `pdf_li`: chi-square over a `(θ, φ)` grid about the map's pole whose rows are the
/// map's and whose columns halve its cells (so every cell of the test lies within one cell of
/// the map's distribution, where `pdf sin θ` is constant and the midpoint rule exact).
/// Emission (`sample_le`) reports the density `pdf_le_dir` gives its direction.
#[test]
fn envmap_directions_follow_pdf_li() {
    let (w, h) = (64, 32);
    let light = env_light(EnvMap::new(w, h, sky(w, h), Mat3::IDENTITY).unwrap());
    let p = Vec3::new(0.1, -0.2, 0.3);
    let test = ChiSquareTest {
        axis: Vec3::Y,
        theta_max: std::f64::consts::PI,
        res_theta: h - 1,
        res_phi: 2 * w,
        samples: 2_000_000,
        integration_res: 4,
        seed: 23,
    };
    let r = test.run(
        |rng| {
            let s = light.sample_li(p, rng.uniform2())?;
            assert_eq!(s.pdf_w, light.pdf_environment(s.wi));
            assert!(s.pdf_w.is_finite() && s.pdf_w > 0.0);
            assert!(s.li.is_finite() && s.li.min_element() >= 0.0);
            Some(s.wi)
        },
        |d| light.pdf_li(p, p + d) as f64,
    );
    eprintln!("{r:?}");
    assert!((r.integral - 1.0).abs() < 1e-3, "∫ pdf = {}", r.integral);
    assert!(r.p_value > 0.01, "{r:?}");
    let mut rng = Rng::new(5, 0, 0);
    for _ in 0..10_000 {
        let e = light.sample_le(rng.uniform2(), rng.uniform2()).unwrap();
        assert_eq!(e.pdf_dir, light.pdf_le_dir(e.dir));
        // The ray starts on the unit bounding disk facing its direction, one radius back.
        assert!((e.p.dot(e.dir) + 1.0).abs() < 1e-4 && (e.p + e.dir).length() <= 1.0 + 1e-4);
    }
}

/// The mean of `L / pdf` over next-event samples of the map is `∫ L dω` (by quadrature), per
/// channel within `z` standard errors of the samples' own spread (`z` the normal quantile at
/// 0.01 over three channels, Šidák). One million samples, seed 29.
#[test]
fn envmap_estimates_its_integral() {
    let (w, h) = (64, 32);
    let map = EnvMap::new(w, h, sky(w, h), Mat3::from_rotation_y(0.7)).unwrap();
    let exact = integral_by_quadrature(&map);
    let light = env_light(map);
    let n = 1_000_000;
    let mut rng = Rng::new(29, 0, 0);
    let (mut s1, mut s2) = ([0.0f64; 3], [0.0f64; 3]);
    for _ in 0..n {
        if let Some(s) = light.sample_li(Vec3::ZERO, rng.uniform2()) {
            let x = s.li / s.pdf_w;
            assert!(x.is_finite() && x.min_element() >= 0.0);
            for c in 0..3 {
                s1[c] += x[c] as f64;
                s2[c] += (x[c] as f64).powi(2);
            }
        }
    }
    let z = common::normal_quantile(1.0 - sidak(0.01, 3) / 2.0);
    for c in 0..3 {
        let mean = s1[c] / n as f64;
        let se = ((s2[c] / n as f64 - mean * mean) / (n - 1) as f64).sqrt();
        eprintln!(
            "channel {c}: {mean:.5} ± {se:.5}, quadrature {:.5}",
            exact[c]
        );
        assert!(
            (mean - exact[c]).abs() < z * se,
            "channel {c}: mean of L/pdf {mean} ± {se}, ∫ L dω {}",
            exact[c]
        );
    }
    // The power the light is chosen by: π r² ∫ L dω, from the cells' mean radiance.
    let power = light.power_rgb();
    for c in 0..3 {
        let rel = (power[c] as f64 / (PI as f64 * exact[c]) - 1.0).abs();
        assert!(rel < 0.02, "channel {c}: power off by {rel}");
    }
}

/// A uniform map of radiance 1: its samples fall on the map's rows in proportion to their
/// solid angle `(cos θ_j - cos θ_{j+1}) / 2` (chi-square), and the mean of `L / pdf` is `4π`
/// (within `z` standard errors, `z` at 0.01). Both fail if the `sin θ` weighting of the
/// distribution or the `1 / (2π² sin θ)` Jacobian of its density is dropped: the same samples
/// are checked against what each omission would give, and must reject it.
#[test]
fn envmap_sampling_needs_sin_theta_and_the_jacobian() {
    let (w, h) = (16, 32);
    let map = EnvMap::new(w, h, vec![Rgb::ONE; w * h], Mat3::IDENTITY).unwrap();
    let rows = h - 1;
    let d_theta = std::f64::consts::PI / rows as f64;
    let n = 400_000;
    let mut counts = vec![0.0f64; rows];
    let (mut s1, mut s2, mut s_nojac) = (0.0f64, 0.0f64, 0.0f64);
    let mut poles = 0usize;
    let mut rng = Rng::new(31, 0, 0);
    for _ in 0..n {
        // A direction on a pole (f32 numbers can make one) has no density: it is not made,
        // and counts as an estimate of 0. Near a pole `L / pdf` goes to 0 with `sin θ`, so
        // this loses nothing measurable.
        let Some((toward, pdf_w, l)) = map.sample(rng.uniform2()) else {
            poles += 1;
            continue;
        };
        let theta = (toward.y as f64).clamp(-1.0, 1.0).acos();
        counts[((theta / d_theta) as usize).min(rows - 1)] += 1.0;
        let x = luminance(l) as f64 / pdf_w as f64;
        s1 += x;
        s2 += x * x;
        // The density without the Jacobian: the (u, v) density itself.
        let pdf_uv = pdf_w as f64 * 2.0 * std::f64::consts::PI.powi(2) * theta.sin();
        s_nojac += luminance(l) as f64 / pdf_uv;
    }
    let solid_angle =
        |j: usize| ((j as f64 * d_theta).cos() - ((j + 1) as f64 * d_theta).cos()) / 2.0;
    let chi2_against = |mass: &dyn Fn(usize) -> f64| {
        let (chi2, bins) = pearson_pooled((0..rows).map(|j| (counts[j], mass(j) * n as f64)));
        chi2_sf(chi2, (bins - 1) as f64)
    };
    let p_rows = chi2_against(&solid_angle);
    let p_without_sin = chi2_against(&|_| 1.0 / rows as f64);
    let mean = s1 / n as f64;
    let se = ((s2 / n as f64 - mean * mean) / (n - 1) as f64).sqrt();
    let z = common::normal_quantile(1.0 - 0.01 / 2.0);
    let four_pi = 4.0 * std::f64::consts::PI;
    assert!(poles * 1_000 < n, "{poles} samples on a pole");
    eprintln!(
        "{poles} samples on a pole; rows: p = {p_rows:.3} (without sin θ: {p_without_sin:e}); mean L/pdf {mean:.5} ± {se:.5} (without the Jacobian {:.5}), 4π = {four_pi:.5}",
        s_nojac / n as f64
    );
    assert!(
        p_rows > 0.01,
        "rows not sampled by solid angle: p = {p_rows}"
    );
    assert!((mean - four_pi).abs() < z * se, "{mean} ± {se}");
    // The checks have the power to see either omission.
    assert!(p_without_sin < 1e-9);
    assert!((s_nojac / n as f64 - four_pi).abs() > 100.0 * se);
}

fn scene_file(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/emitters")
        .join(format!("{name}.xml"))
}

fn load(name: &str) -> Scene {
    let mut scene = mitsuba::load(&scene_file(name), &ImportOptions::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    scene.maps.photons = 50_000;
    scene.maps.importons = 50_000;
    scene
}

/// `R` renders of `method` with seeds from `seed`: every image valid, every sample accepted.
fn renders(
    scene: &Scene,
    method: &str,
    r: usize,
    spp: u32,
    seed: u64,
) -> Vec<footprint::film::Image> {
    (0..r)
        .map(|k| {
            let opts = RenderOptions {
                method: Method::parse(method).unwrap(),
                spp,
                time: None,
                max_depth: 4,
                seed: seed + k as u64,
                ..Default::default()
            };
            let out = render(scene, &opts, |_| {});
            assert!(
                out.image.all_valid() && out.stats.rejected == 0,
                "{method}: {} samples rejected",
                out.stats.rejected
            );
            out.image
        })
        .collect()
}

/// Every integrator with BSDF sampling and with the footprint guide, path tracing first.
fn methods() -> Vec<&'static str> {
    let m: Vec<&str> = common::PAIRS
        .into_iter()
        .filter(|m| !m.ends_with("grid"))
        .collect();
    assert_eq!(m[0], "pt-bsdf");
    m
}

/// Every method's image of `name` against path tracing's (BSDF sampling), per region of a 4 x 4
/// grid and channel: Welch's t of the two means over `R` renders each, against Student's t
/// with `R - 1` degrees of freedom at 0.01, Šidák-corrected over every region, channel and
/// method. Light tracing does not see the environment: its regions where a camera ray
/// escapes are left out (a 4 x 4 grid of rays per pixel finds them).
fn every_method_agrees(name: &str) {
    let scene = load(name);
    let side = 4;
    let (rw, rh) = (scene.camera.width / side, scene.camera.height / side);
    let r = 12;
    let spp = 16;
    let cam = &scene.camera;
    let sees_environment: Vec<bool> = (0..side * side)
        .map(|i| {
            let (x0, y0) = ((i % side) * rw, (i / side) * rh);
            (0..rw * rh * 16).any(|k| {
                let (px, sub) = (k / 16, k % 16);
                let raster = Vec2::new(
                    (x0 + px % rw) as f32 + ((sub % 4) as f32 + 0.5) / 4.0,
                    (y0 + px / rw) as f32 + ((sub / 4) as f32 + 0.5) / 4.0,
                );
                scene
                    .intersect(cam.position, cam.ray_dir(raster), f32::INFINITY)
                    .is_none()
            })
        })
        .collect();
    let stats = |images: &[footprint::film::Image]| -> Vec<[(f64, f64); 3]> {
        let means: Vec<Vec<[f64; 3]>> = images
            .iter()
            .map(|img| common::region_means(img, side))
            .collect();
        (0..(side * side) as usize)
            .map(|i| {
                std::array::from_fn(|c| {
                    let xs: Vec<f64> = means.iter().map(|m| m[i][c]).collect();
                    common::mean_stderr(&xs)
                })
            })
            .collect()
    };
    let methods = methods();
    let reference = stats(&renders(&scene, methods[0], r, spp, 1000));
    let crit = t_critical(
        sidak(0.01, (side * side) as usize * 3 * (methods.len() - 1)),
        (r - 1) as f64,
    );
    let mut failures = Vec::new();
    for (m, method) in methods.iter().enumerate().skip(1) {
        let got = stats(&renders(&scene, method, r, spp, 1000 + 100 * m as u64));
        let mut worst = 0.0f64;
        for (i, (a, b)) in got.iter().zip(&reference).enumerate() {
            if method.starts_with("lt") && sees_environment[i] && scene.effects.environment {
                continue;
            }
            for c in 0..3 {
                let ((ma, sa), (mb, sb)) = (a[c], b[c]);
                let t = (ma - mb).abs() / (sa * sa + sb * sb).sqrt().max(1e-12);
                worst = worst.max(t);
                if t > crit {
                    failures.push(format!(
                        "{method}: region {i} channel {c}: {ma:.5} ± {sa:.5} against pt-bsdf {mb:.5} ± {sb:.5}, |t| = {t:.2}"
                    ));
                }
            }
        }
        eprintln!("{name}, {method}: largest |t| {worst:.2} (critical {crit:.2})");
    }
    assert!(failures.is_empty(), "{name}:\n{}", failures.join("\n"));
}

#[test]
fn every_method_agrees_under_a_directional_light() {
    let scene = load("directional");
    assert!(scene.effects.directional_lights && !scene.effects.environment);
    every_method_agrees("directional");
}

#[test]
fn every_method_agrees_under_an_envmap() {
    let scene = load("envmap");
    assert!(scene.effects.environment);
    every_method_agrees("envmap");
}

/// The image mean of `name` by `method` against Mitsuba 3's `path` (the JSON's mean and
/// standard error over its seeds): Welch's t per channel against Student's t with
/// `min(R, seeds) - 1` degrees of freedom at 0.01, Šidák-corrected over the three channels
/// and the two scenes.
fn matches_mitsuba(name: &str, method: &str, r: usize, spp: u32) {
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(scene_file("mitsuba-means").with_extension("json")).unwrap(),
    )
    .unwrap();
    let entry = &json["scenes"][name];
    let seeds = entry["seeds"].as_u64().unwrap() as usize;
    let num = |k: &str, c: usize| entry[k][c].as_f64().unwrap();
    let scene = load(name);
    let images = renders(&scene, method, r, spp, 4000);
    let crit = t_critical(sidak(0.01, 6), (r.min(seeds) - 1) as f64);
    for c in 0..3 {
        let xs: Vec<f64> = images.iter().map(|i| i.mean()[c] as f64).collect();
        let (m, s) = common::mean_stderr(&xs);
        let (rm, rs) = (num("mean", c), num("stderr", c));
        let t = (m - rm).abs() / (s * s + rs * rs).sqrt();
        eprintln!(
            "{name} ({method}) channel {c}: footprint {m:.5} ± {s:.5}, Mitsuba {rm:.5} ± {rs:.5}, |t| = {t:.2} (critical {crit:.2}), ratio {:.4}",
            m / rm
        );
        assert!(t < crit, "{name} channel {c}: |t| = {t:.2} > {crit:.2}");
    }
}

#[test]
fn directional_light_matches_mitsuba() {
    matches_mitsuba("directional", "pt-bsdf", 16, 256);
}

#[test]
fn envmap_matches_mitsuba() {
    matches_mitsuba("envmap", "pt-bsdf", 16, 256);
}

/// An envmap scene around `emitter` (the element's text), in a fresh folder with `files`
/// written next to it; the import's error message.
fn import_error(tag: &str, emitter: &str, files: &[(&str, &[u8])]) -> String {
    let dir = std::env::temp_dir().join(format!("footprint-emitters-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (f, bytes) in files {
        std::fs::write(dir.join(f), bytes).unwrap();
    }
    let xml = dir.join("scene.xml");
    std::fs::write(
        &xml,
        format!(
            r#"<scene version="3.0.0">
  <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film></sensor>
  <shape type="rectangle"><bsdf type="diffuse"/></shape>
  {emitter}
</scene>"#
        ),
    )
    .unwrap();
    match mitsuba::load(&xml, &ImportOptions::default()) {
        Ok(_) => panic!("{tag}: the scene loaded"),
        Err(e) => e.to_string(),
    }
}

/// An EXR of `w x h` texels, every one `c`.
fn exr_bytes(w: u32, h: u32, c: f32) -> Vec<u8> {
    let path = std::env::temp_dir().join(format!(
        "footprint-emitters-{w}x{h}-{c}-{}.exr",
        std::process::id()
    ));
    let img = footprint::film::Image {
        width: w,
        height: h,
        pixels: vec![Rgb::splat(c); (w * h) as usize],
    };
    footprint::film::image_io::write_exr(&path, &[("", &img)], &[]).unwrap();
    std::fs::read(&path).unwrap()
}

#[test]
fn bad_envmaps_and_directional_lights_name_their_file_and_element() {
    let env = |f: &str| {
        format!(r#"<emitter type="envmap"><string name="filename" value="{f}"/></emitter>"#)
    };
    let cases: Vec<(&str, String, Vec<(&str, Vec<u8>)>, &str)> = vec![
        ("missing", env("nowhere.exr"), vec![], "nowhere.exr"),
        ("garbage", env("sky.exr"), vec![("sky.exr", b"not an image".to_vec())], "not a readable EXR"),
        ("garbage-hdr", env("sky.hdr"), vec![("sky.hdr", b"#?RADIANCE\nnonsense".to_vec())], "not a readable Radiance HDR"),
        ("png", env("sky.png"), vec![("sky.png", vec![0u8; 8])], "OpenEXR (.exr) or Radiance HDR (.hdr)"),
        ("tiny", env("sky.exr"), vec![("sky.exr", exr_bytes(1, 1, 1.0))], "at least 2 x 3"),
        ("negative", env("sky.exr"), vec![("sky.exr", exr_bytes(4, 4, -1.0))], "texel (0, 0)"),
        ("nan", env("sky.exr"), vec![("sky.exr", exr_bytes(4, 4, f32::NAN))], "texel (0, 0)"),
        ("black", env("sky.exr"), vec![("sky.exr", exr_bytes(4, 4, 0.0))], "black"),
        (
            "scaled",
            r#"<emitter type="envmap"><string name="filename" value="sky.exr"/><transform name="to_world"><scale value="2"/></transform></emitter>"#.into(),
            vec![("sky.exr", exr_bytes(4, 4, 1.0))],
            "rotation",
        ),
        (
            "both",
            r#"<emitter type="directional"><vector name="direction" value="0, -1, 0"/><transform name="to_world"><rotate x="1" angle="90"/></transform></emitter>"#.into(),
            vec![],
            "not both",
        ),
        (
            "zero",
            r#"<emitter type="directional"><vector name="direction" value="0, 0, 0"/></emitter>"#.into(),
            vec![],
            "zero",
        ),
        (
            "negative-irradiance",
            r#"<emitter type="directional"><rgb name="irradiance" value="1, -1, 1"/></emitter>"#.into(),
            vec![],
            "must not be negative",
        ),
    ];
    for (tag, emitter, files, expect) in &cases {
        let files: Vec<(&str, &[u8])> = files.iter().map(|(f, b)| (*f, b.as_slice())).collect();
        let e = import_error(tag, emitter, &files);
        assert!(e.contains(expect), "{tag}: {e}");
        assert!(
            e.contains("scene.xml:4"),
            "{tag}: the element's line in {e}"
        );
        if tag.contains("hdr") || emitter.contains("envmap") {
            assert!(
                e.contains("sky.") || e.contains("nowhere.exr"),
                "{tag}: the file in {e}"
            );
        }
    }
}

/// The map read from Radiance RGBE (`sky.hdr`) is the one read from OpenEXR (`sky.exr`), both
/// written by `scripts/emitter_means.py` from the same texels: equal within RGBE's shared
/// exponent (8 bits of mantissa for the largest channel of a texel).
#[test]
fn hdr_and_exr_maps_read_alike() {
    let dir = scene_file("sky").parent().unwrap().to_path_buf();
    let exr = EnvMap::load(&dir.join("sky.exr"), Mat3::IDENTITY).unwrap();
    let hdr = EnvMap::load(&dir.join("sky.hdr"), Mat3::IDENTITY).unwrap();
    assert_eq!(exr.size(), (64, 32));
    assert_eq!(hdr.size(), exr.size());
    for y in 0..32 {
        for x in 0..64 {
            let (a, b) = (exr.texel(x, y), hdr.texel(x, y));
            assert!(
                (a - b).abs().max_element() <= a.max_element() / 128.0,
                "texel ({x}, {y}): {a} from the EXR, {b} from the HDR"
            );
        }
    }
}

/// `footprint export` writes both lights back as Mitsuba emitters that import to the same
/// lights: the directional light's direction and irradiance, the map's texels, scale and
/// rotation.
#[test]
fn export_round_trip_keeps_both_lights() {
    for name in ["directional", "envmap"] {
        let scene = load(name);
        let out = std::env::temp_dir().join(format!(
            "footprint-emitters-export-{name}-{}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&out);
        std::fs::create_dir_all(&out).unwrap();
        mitsuba::export::export(&scene, &scene_file(name), &out).unwrap();
        let back = mitsuba::load(&out.join("scene.xml"), &ImportOptions::default()).unwrap();
        let (a, b) = (&scene.lights[0], &back.lights[0]);
        match (a, b) {
            (
                Light::Directional {
                    dir: d0,
                    irradiance: e0,
                    ..
                },
                Light::Directional {
                    dir: d1,
                    irradiance: e1,
                    ..
                },
            ) => assert!(d0.abs_diff_eq(*d1, 1e-6) && e0 == e1, "{a:?} against {b:?}"),
            (
                Light::Environment {
                    le: l0,
                    map: Some(m0),
                    ..
                },
                Light::Environment {
                    le: l1,
                    map: Some(m1),
                    ..
                },
            ) => {
                assert_eq!(l0, l1);
                assert!(m0.to_world().abs_diff_eq(m1.to_world(), 1e-6));
                assert_eq!(m0.size(), m1.size());
                let (w, h) = m0.size();
                for k in 0..w * h {
                    assert_eq!(m0.texel(k % w, k / w), m1.texel(k % w, k / w));
                }
            }
            _ => panic!("{name}: {a:?} came back as {b:?}"),
        }
    }
}

/// TOML scenes take both lights: `type = "directional"` (`direction`, `irradiance`) and
/// `type = "envmap"` (`file` relative to the scene, `scale`); a bad map names its field.
#[test]
fn toml_scenes_read_both_lights() {
    let dir = std::env::temp_dir().join(format!("footprint-emitters-toml-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("floor.obj"),
        common::box_obj([-2.0, -0.1, -2.0], [2.0, 0.0, 2.0], 1, "white"),
    )
    .unwrap();
    std::fs::write(dir.join("floor.mtl"), "newmtl white\nKd 0.5 0.5 0.5\n").unwrap();
    let sky = scene_file("sky").with_extension("exr");
    let toml = |map: &str| {
        format!(
            r#"[camera]
position = [0.0, 2.0, 5.0]
look_at = [0.0, 0.0, 0.0]
fov_y = 40.0
resolution = [8, 8]

[[mesh]]
file = "floor.obj"

[[light]]
type = "directional"
direction = [0.0, -2.0, 0.0]
irradiance = [1.0, 2.0, 3.0]

[[light]]
type = "envmap"
file = "{}"
scale = 2.0
"#,
            map.replace('\\', "/")
        )
    };
    let path = dir.join("scene.toml");
    std::fs::write(&path, toml(&sky.display().to_string())).unwrap();
    let scene = footprint::scene::load::load_scene(&path).unwrap();
    assert!(scene.effects.directional_lights && scene.effects.environment);
    match &scene.lights[..2] {
        [
            Light::Directional {
                dir, irradiance, ..
            },
            Light::Environment {
                le, map: Some(m), ..
            },
        ] => {
            assert_eq!((*dir, *irradiance), (Vec3::NEG_Y, Rgb::new(1.0, 2.0, 3.0)));
            assert_eq!((*le, m.size()), (Rgb::splat(2.0), (64, 32)));
        }
        other => panic!("{other:?}"),
    }
    std::fs::write(&path, toml("missing.exr")).unwrap();
    let Err(e) = footprint::scene::load::load_scene(&path) else {
        panic!("a missing map loaded");
    };
    let e = e.to_string();
    assert!(
        e.contains("light[1].file") && e.contains("missing.exr"),
        "{e}"
    );
}
