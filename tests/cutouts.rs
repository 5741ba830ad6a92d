//! Cut-outs (Mitsuba `mask`): surfaces that light passes straight through where their
//! opacity `α` is under 1. Walks pass them with probability `1 - α` without a vertex;
//! next-event estimation, the light tracer's camera connections and the combined image's
//! connections multiply by `1 - α` for each one crossed (`Scene::transmittance`).
//!
//! The analytic case: a point light above a large cut-out sheet of constant opacity `α`
//! whose own BSDF is black, a diffuse floor below it, the camera above the sheet looking
//! down through it. Every path to the camera crosses the sheet twice, and the floor (an
//! infinite plane that cannot see itself) is the only surface that reflects, so at any depth
//! of 2 or more the image is exactly
//!
//! `L(x) = (1 - α) · (ρ / π) · I cos θ_l / r² · (1 - α)`,
//!
//! `θ_l` the angle of the light direction at the floor point `x`, `r` its distance to the
//! light; each pixel's expected value is that radiance averaged over the pixel (box filter),
//! by a 16 x 16 quadrature per pixel.
//!
//! Bounds: over `R` renders with independent seeds, each block's (or region's) mean has a
//! standard error estimated from the renders' spread; a test fails when a |t| exceeds the
//! two-sided Student-t critical value at 0.01, Šidák-corrected over every block, channel and
//! compared integrator. The quadrature's own error (a smooth integrand, 256 points a pixel) is
//! below 1e-4 of the value, far under the renders' standard errors.

mod common;

use common::{sidak, t_critical};
use footprint::Rgb;
use footprint::film::Image;
use footprint::scene::Scene;
use glam::{Vec2, Vec3};

const SIDE: u32 = 16;
const BLOCK: u32 = 4;
const RHO: f32 = 0.5;
const INTENSITY: f32 = 10.0;
const OPACITY: f32 = 0.35;
/// Outside the camera's view (a point light seen directly reaches the pinhole by light
/// tracing alone, as one bright pixel).
const LIGHT: Vec3 = Vec3::new(2.0, -0.5, 2.0);

/// The scene (`common::sheet_over_floor`) with the black cut-out sheet.
fn scene(tag: &str) -> Scene {
    let sheet = format!(
        r#"<bsdf type="mask"><float name="opacity" value="{OPACITY}"/>
            <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf></bsdf></bsdf>"#
    );
    common::sheet_over_floor(
        &format!("cutout-{tag}"),
        SIDE,
        RHO,
        &sheet,
        LIGHT,
        INTENSITY,
    )
}

/// The radiance the camera sees along `dir` from `origin` (above the sheet).
fn radiance(origin: Vec3, dir: Vec3) -> f32 {
    let t = -origin.z / dir.z;
    let x = origin + t * dir;
    let to_light = LIGHT - x;
    let r2 = to_light.length_squared();
    let cos_l = to_light.z / r2.sqrt();
    let through = 1.0 - OPACITY;
    through * (RHO / std::f32::consts::PI) * (INTENSITY * cos_l / r2) * through
}

/// Block means of the image the renders estimate: each pixel's radiance averaged over it.
fn expected(scene: &Scene) -> Vec<[f64; 3]> {
    let cam = &scene.camera;
    let n = 16;
    let mut img = Image::new(SIDE, SIDE);
    for y in 0..SIDE {
        for x in 0..SIDE {
            let mut sum = 0.0;
            for j in 0..n {
                for i in 0..n {
                    let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                    sum += radiance(cam.position, cam.ray_dir(Vec2::new(x as f32, y as f32) + u));
                }
            }
            img.pixels[(y * SIDE + x) as usize] = Rgb::splat(sum / (n * n) as f32);
        }
    }
    common::region_means(&img, SIDE / BLOCK)
}

/// Path tracing (light samples through the sheet), light tracing (camera connections through
/// it) and the combined image all find the analytic image, at two depths: the sheet is no
/// segment of a path, so depth 2 (camera, floor, light) already holds the whole image.
#[test]
fn connections_through_a_cutout_carry_its_transparency() {
    let scene = scene("analytic");
    assert!(scene.effects.masks);
    let want = expected(&scene);
    let renders = 12;
    let methods = ["pt-bsdf", "lt-bsdf", "combined-bsdf"];
    let depths = [2, 5];
    let checks = depths.len() * methods.len() * want.len() * 3;
    let crit = t_critical(sidak(0.01, checks), (renders - 1) as f64);
    for max_depth in depths {
        for m in methods {
            let runs = common::runs_of(&scene, m, (renders, 16, max_depth, 700), |img| {
                common::region_means(img, SIDE / BLOCK)
            });
            let label = format!("{m}, depth {max_depth}");
            let worst = common::assert_runs_match(&label, &runs, &want, crit);
            eprintln!("{label}: largest |t| {worst:.2} (critical {crit:.2})");
        }
    }
}

/// A cut-out that blocked connections (as an opaque surface) would leave only the light
/// that paths carry through it by sampling; one that let them pass without its `1 - α`
/// would brighten the floor by `1 / (1 - α)²` = 2.4 here. The light tracer's image mean
/// lies within 10% of the analytic one, far from either (a check that the scene tests what it
/// says, on one render).
#[test]
fn the_light_tracer_sees_the_floor_through_the_cutout() {
    let scene = scene("lt");
    let whole = |img: &Image| {
        let m = img.mean();
        vec![[m.x as f64, m.y as f64, m.z as f64]]
    };
    let got = common::runs_of(&scene, "lt-bsdf", (1, 8, 4, 3), whole)[0][0][0];
    let want = expected(&scene).iter().map(|b| b[0]).sum::<f64>() / (SIDE / BLOCK).pow(2) as f64;
    assert!((got / want - 1.0).abs() < 0.1, "{got} against {want}");
}

/// `scenes/cutout`: a lattice screen of holes (a bitmap opacity) under a small ceiling light,
/// casting a shadow of holes that the camera sees through it, and a curtain of constant
/// opacity. Light tracing, the combined image and the guided methods agree with unguided
/// path tracing per region of the image and channel (the image against Mitsuba 3:
/// `tests/mitsuba.rs`).
/// (Bound: `common::assert_integrators_agree`.)
#[test]
fn every_integrator_sees_through_the_cutouts_alike() {
    let mut scene =
        footprint::scene::load::load_scene(&common::scenes_dir().join("cutout/scene.xml"))
            .expect("scenes/cutout loads");
    scene.camera = scene.camera.with_resolution(32, 32).unwrap();
    scene.maps.photons = 20_000;
    scene.maps.importons = 20_000;
    assert!(scene.effects.masks && scene.effects.textures);
    // Guided too: particles pass them as paths do (small maps: only agreement matters).
    common::assert_integrators_agree(&scene, (10, 8, 6), 4);
}
