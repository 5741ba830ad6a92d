//! Scenes far from the origin, and much smaller or larger than the bundled ones, render the
//! image of the same scene at its own place and size: the Cornell box translated by 10⁵,
//! scaled by 10⁻³, 10⁻⁵ and 10³, with every integrator x guide pair (particle maps, the
//! guide cache's regions and the footprints' radii included); the translated box on each
//! acceleration structure.
//!
//! The box's vertices and the camera are first rounded to multiples of 2⁻⁷, which f32 holds
//! exactly at 10⁵ (its spacing there is 2⁻⁷): translated, the scene is the same scene, not
//! one moved by the rounding, and the images must agree in expectation.
//!
//! Bound: each pair renders `R` independent images (seeds `0..R`) of the near scene and `R`
//! of the moved one (other seeds). Per 4x4-pixel block and channel, and for the whole
//! image's mean per channel, the difference of the two means is compared with its standard
//! error from the replicates' spread (Welch), against Student's t with `R - 1` degrees of
//! freedom (conservative for Welch's test) at significance 0.01, Šidák-corrected over every
//! pair x (block or whole image) x channel of the test.

mod common;

use common::{PAIRS, mean_stderr, scenes_dir, sidak, t_critical};
use footprint::scene::Scene;
use footprint::scene::load::load_scene;
use footprint_integrators::{Method, RenderOptions, render};

/// Image side in pixels, block side, renders per scene and pair, samples per render.
const SIDE: u32 = 16;
const BLOCK: u32 = 4;
const RENDERS: usize = 10;
const SPP: u32 = 2;

/// A coordinate rounded to a multiple of 2⁻⁷.
fn snap(x: f64) -> f64 {
    (x * 128.0).round() / 128.0
}

/// The Cornell box with its vertices and camera on the 2⁻⁷ grid, moved by `x -> s x + t`
/// (the mesh through its transform, the camera here), in a fresh folder; loaded at
/// `SIDE` x `SIDE` with small maps.
fn cornell(tag: &str, scale: f64, translate: [f64; 3]) -> Scene {
    let d = std::env::temp_dir().join(format!("footprint-far-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    let src = scenes_dir().join("cornell");
    std::fs::copy(src.join("cornell.mtl"), d.join("cornell.mtl")).unwrap();
    // The light hangs 1 mm below the ceiling, which the grid would merge with it: it goes one
    // step lower (coincident surfaces are another test's, `tests/degenerate.rs`).
    let mut light = false;
    let obj: String = std::fs::read_to_string(src.join("cornell.obj"))
        .unwrap()
        .lines()
        .map(|l| {
            if let Some(name) = l.strip_prefix("o ") {
                light = name.trim() == "light";
            }
            match l.strip_prefix("v ") {
                Some(v) => {
                    let c: Vec<f64> = v.split_whitespace().map(|x| x.parse().unwrap()).collect();
                    let y = snap(c[1]) - if light { 1.0 / 128.0 } else { 0.0 };
                    format!("v {} {y} {}\n", snap(c[0]), snap(c[2]))
                }
                None => format!("{l}\n"),
            }
        })
        .collect();
    std::fs::write(d.join("cornell.obj"), obj).unwrap();
    let place = |p: [f64; 3]| -> String {
        let q: Vec<String> = (0..3)
            .map(|i| format!("{:?}", (snap(p[i]) * scale + translate[i]) as f32))
            .collect();
        format!("[{}]", q.join(", "))
    };
    let toml = format!(
        "[camera]\nposition = {}\nlook_at = {}\nfov_y = 39.3\nresolution = [{SIDE}, {SIDE}]\n\
         [[mesh]]\nfile = \"cornell.obj\"\n\
         transform = {{ translate = [{:?}, {:?}, {:?}], scale = {:?} }}\n",
        place([2.78, 2.73, -8.0]),
        place([2.78, 2.73, 0.0]),
        translate[0] as f32,
        translate[1] as f32,
        translate[2] as f32,
        scale as f32,
    );
    std::fs::write(d.join("cornell.toml"), toml).unwrap();
    let mut s = load_scene(&d.join("cornell.toml")).unwrap();
    s.maps.photons = 5_000;
    s.maps.importons = 5_000;
    s
}

/// Per render of `scene` with `method` (`RENDERS` of them, seeds from `seed`): the block
/// means, then the whole image's mean.
fn replicates(scene: &Scene, method: &str, seed: u64) -> Vec<Vec<[f64; 3]>> {
    (0..RENDERS)
        .map(|r| {
            let o = RenderOptions {
                method: Method::parse(method).unwrap(),
                spp: SPP,
                time: None,
                max_depth: 6,
                seed: seed + r as u64,
                ..Default::default()
            };
            let out = render(scene, &o, |_| {});
            assert!(out.image.all_valid(), "{method}: invalid pixel");
            let mut means = common::region_means(&out.image, SIDE / BLOCK);
            let m = out.image.mean();
            means.push([m.x as f64, m.y as f64, m.z as f64]);
            means
        })
        .collect()
}

/// The near scene's replicates, per pair, rendered once for every test of the file.
fn near() -> &'static Vec<Vec<Vec<[f64; 3]>>> {
    static NEAR: std::sync::OnceLock<Vec<Vec<Vec<[f64; 3]>>>> = std::sync::OnceLock::new();
    NEAR.get_or_init(|| {
        let scene = cornell("near", 1.0, [0.0; 3]);
        PAIRS.iter().map(|m| replicates(&scene, m, 0)).collect()
    })
}

/// Every pair renders `far` as it renders the near scene, per block and channel and over the
/// whole image (Welch's t, see the file's comment).
fn same_images(far: &Scene, what: &str) {
    let blocks = ((SIDE / BLOCK) * (SIDE / BLOCK)) as usize;
    let crit = t_critical(
        sidak(0.01, PAIRS.len() * (blocks + 1) * 3),
        (RENDERS - 1) as f64,
    );
    let stat = |reps: &Vec<Vec<[f64; 3]>>, i: usize, c: usize| {
        mean_stderr(&reps.iter().map(|r| r[i][c]).collect::<Vec<_>>())
    };
    let mut failures = Vec::new();
    for (m, a) in PAIRS.iter().zip(near()) {
        let b = replicates(far, m, 1000);
        let mut worst = 0.0f64;
        for i in 0..=blocks {
            for c in 0..3 {
                let (ma, sa) = stat(a, i, c);
                let (mb, sb) = stat(&b, i, c);
                let t = (mb - ma).abs() / (sa * sa + sb * sb).sqrt().max(1e-30);
                worst = worst.max(t);
                if t > crit {
                    let place = if i == blocks {
                        "whole image".to_string()
                    } else {
                        format!("block {i}")
                    };
                    failures.push(format!(
                        "{what} {m} {place} channel {c}: {mb:.5} ± {sb:.5}, near {ma:.5} ± {sa:.5} (|t| {t:.2})"
                    ));
                }
            }
        }
        let ((ma, sa), (mb, sb)) = (stat(a, blocks, 1), stat(&b, blocks, 1));
        eprintln!(
            "{what} {m}: image mean (green) {:.4} of the near one's (|t| {:.2}), largest |t| {worst:.2} (critical {crit:.2})",
            mb / ma,
            (mb - ma).abs() / (sa * sa + sb * sb).sqrt()
        );
    }
    assert!(
        failures.is_empty(),
        "{} disagreements:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn far_from_the_origin_translated_by_1e5_renders_the_same_image() {
    let test = "far_from_the_origin_translated_by_1e5_renders_the_same_image";
    for far in common::each_accel(test, &cornell("far", 1.0, [1e5, -1e5, 1e5])) {
        let what = format!("translated by 1e5 ({})", far.bvh.name());
        same_images(&far, &what);
    }
}

#[test]
fn far_from_the_origin_scale_1e_minus_3_renders_the_same_image() {
    same_images(&cornell("small", 1e-3, [0.0; 3]), "scaled by 1e-3");
}

/// A box of 55 µm: the ray offset's fixed steps near the origin shrink with the scene
/// ([`footprint::scene::Scene::offset_scale`]); at their unit size they were a quarter of it.
#[test]
fn far_from_the_origin_scale_1e_minus_5_renders_the_same_image() {
    same_images(&cornell("tiny", 1e-5, [0.0; 3]), "scaled by 1e-5");
}

#[test]
fn far_from_the_origin_scale_1e3_renders_the_same_image() {
    same_images(&cornell("large", 1e3, [0.0; 3]), "scaled by 1e3");
}

/// A scene far from the origin is centred when loaded, and what leaves the renderer puts it
/// back where its file did: the translated box's origin is the centre of its bounds, its
/// camera sits where the scene file put it, and `footprint export` writes the file's
/// coordinates (read back, the export gives the same centred scene).
#[test]
fn far_from_the_origin_scenes_are_centred_and_exported_where_they_were() {
    use footprint::scene::mitsuba::{self, ImportOptions, export::export};
    let far = cornell("export", 1.0, [1e5, -1e5, 1e5]);
    let near = cornell("export-near", 1.0, [0.0; 3]);
    assert_eq!(near.origin, glam::Vec3::ZERO, "a scene at the origin stays");
    let centre = 0.5 * (far.bounds.0 + far.bounds.1);
    assert!(
        centre.abs().max_element() < 1e-3 && (far.origin.x - 1e5).abs() < 10.0,
        "origin {} bounds {:?}",
        far.origin,
        far.bounds
    );
    let camera = far.camera.position + far.origin;
    let want = glam::Vec3::new(1e5 + snap(2.78) as f32, -1e5 + snap(2.73) as f32, 1e5 - 8.0);
    assert!(
        (camera - want).abs().max_element() <= 0.0,
        "camera at {camera}, not {want}"
    );
    let out = std::env::temp_dir().join(format!("footprint-far-export-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    export(&far, std::path::Path::new("cornell.toml"), &out).unwrap();
    let back = mitsuba::load(&out.join("scene.xml"), &ImportOptions::default()).unwrap();
    assert_eq!(back.origin, far.origin);
    assert_eq!(back.camera.position, far.camera.position);
    assert!((back.camera.frame.z - far.camera.frame.z).length() < 1e-6);
    let (mut a, mut b) = (
        far.triangles
            .iter()
            .map(|t| t.p0.to_array())
            .collect::<Vec<_>>(),
        back.triangles
            .iter()
            .map(|t| t.p0.to_array())
            .collect::<Vec<_>>(),
    );
    a.sort_by(|x, y| x.partial_cmp(y).unwrap());
    b.sort_by(|x, y| x.partial_cmp(y).unwrap());
    assert_eq!(a.len(), b.len());
    let worst = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (0..3).map(|i| (x[i] - y[i]).abs()).fold(0.0, f32::max))
        .fold(0.0, f32::max);
    assert!(worst <= 0.0, "exported vertices moved by {worst}");
}
