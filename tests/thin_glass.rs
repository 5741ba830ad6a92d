//! Connections through thin dielectric sheets (Mitsuba `thindielectric`): a point light
//! above a large coloured pane, a diffuse floor below it, and the camera above the pane
//! looking down through it. Every path to the camera crosses the pane twice (the light's
//! way down, the camera's way up), so next-event estimation, the light tracer's camera
//! connections and the combined image's light paths all see the floor only through it.
//!
//! At `max_depth` 4 the image is exactly the single-scattering term (the pane crossings
//! count as segments; longer paths, the floor's light reflected back by the pane, need more):
//!
//! `L(x) = T(θ_c) · (ρ / π) · I cos θ_l / r² · T(θ_l)`,
//!
//! `T(θ) = (1 - R') · T_f` the pane's straight transmission, `R' = 2R / (1 + R)` its
//! reflectance with the inner reflections summed, `R` the dielectric Fresnel term at
//! `cos θ` (IOR 1.5), `θ_c` and `θ_l` the angles of the camera ray and of the light direction
//! at the floor point `x`, `r` its distance to the light. Each pixel's expected value is that
//! radiance averaged over the pixel (box filter), by a 16 x 16 quadrature per pixel.
//!
//! Bound: over `R` renders with independent seeds, each 4 x 4 block's mean has a standard
//! error estimated from the renders' spread; the test fails when a block's |t| exceeds the
//! two-sided Student-t critical value at 0.01, Šidák-corrected over every block, channel and
//! integrator. The quadrature's own error (smooth integrand, 256 points a pixel) is below
//! 1e-4 of the value, far under the renders' standard errors.

mod common;

use common::{sidak, t_critical};
use footprint::Rgb;
use footprint::bsdf::fresnel::fresnel_dielectric;
use footprint::scene::Scene;
use footprint_integrators::{Method, RenderOptions, render};
use glam::{Vec2, Vec3};

const SIDE: u32 = 16;
const BLOCK: u32 = 4;
const RHO: f32 = 0.5;
const INTENSITY: f32 = 10.0;
const TF: [f32; 3] = [0.9, 0.7, 0.5];
/// Outside the camera's view (a point light seen directly reaches the pinhole by light tracing
/// alone, as one bright pixel).
const LIGHT: Vec3 = Vec3::new(2.0, -0.5, 2.0);

/// The scene (`common::sheet_over_floor`) with the coloured pane.
fn scene(tag: &str) -> Scene {
    let pane = format!(
        r#"<bsdf type="thindielectric"><float name="int_ior" value="1.5"/>
            <rgb name="specular_transmittance" value="{}, {}, {}"/></bsdf>"#,
        TF[0], TF[1], TF[2]
    );
    common::sheet_over_floor(&format!("pane-{tag}"), SIDE, RHO, &pane, LIGHT, INTENSITY)
}

/// The pane's straight transmission at `cos` (what a path passing it carries).
fn pane(cos: f32) -> Rgb {
    let r = fresnel_dielectric(cos.abs(), 1.5);
    let r = 2.0 * r / (1.0 + r);
    Rgb::new(TF[0], TF[1], TF[2]) * (1.0 - r)
}

/// The radiance the camera sees along `dir` from `origin` (above the pane).
fn radiance(origin: Vec3, dir: Vec3) -> Rgb {
    let t = -origin.z / dir.z;
    let x = origin + t * dir;
    let to_light = LIGHT - x;
    let r2 = to_light.length_squared();
    let cos_l = to_light.z / r2.sqrt();
    pane(dir.z) * (RHO / std::f32::consts::PI) * (INTENSITY * cos_l / r2) * pane(cos_l)
}

/// The image the renders estimate: each pixel's radiance averaged over the pixel.
fn expected(scene: &Scene) -> Vec<Rgb> {
    let cam = &scene.camera;
    let n = 16;
    let mut out = Vec::new();
    for y in 0..SIDE {
        for x in 0..SIDE {
            let mut sum = Rgb::ZERO;
            for j in 0..n {
                for i in 0..n {
                    let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                    let raster = Vec2::new(x as f32, y as f32) + u;
                    sum += radiance(cam.position, cam.ray_dir(raster));
                }
            }
            out.push(sum / (n * n) as f32);
        }
    }
    out
}

/// Block means of an image (row-major pixels) over `BLOCK` x `BLOCK` blocks.
fn blocks(pixels: &[Rgb]) -> Vec<[f64; 3]> {
    let per = SIDE / BLOCK;
    let mut out = vec![[0.0f64; 3]; (per * per) as usize];
    for y in 0..SIDE {
        for x in 0..SIDE {
            let b = ((y / BLOCK) * per + x / BLOCK) as usize;
            let p = pixels[(y * SIDE + x) as usize];
            for c in 0..3 {
                out[b][c] += p[c] as f64 / (BLOCK * BLOCK) as f64;
            }
        }
    }
    out
}

/// Path tracing (next-event estimation through the pane), light tracing (camera
/// connections through it) and the combined image (its MIS weights with the pane seen by
/// neither subpath) all find the analytic image.
#[test]
fn connections_through_a_thin_pane_carry_its_transmittance() {
    let scene = scene("analytic");
    assert!(scene.effects.thin_glass);
    let want = blocks(&expected(&scene));
    let renders = 12;
    let methods = ["pt-bsdf", "lt-bsdf", "combined-bsdf"];
    let checks = methods.len() * want.len() * 3;
    let crit = t_critical(sidak(0.01, checks), (renders - 1) as f64);
    for m in methods {
        let runs = common::runs_of(&scene, m, (renders, 16, 4, 700), |img| blocks(&img.pixels));
        let worst = common::assert_runs_match(m, &runs, &want, crit);
        eprintln!("{m}: largest |t| {worst:.2} (critical {crit:.2})");
    }
}

/// Without its transmittance the light tracer would see nothing through the pane: the
/// image is bright where the analytic one is (a check that the scene tests what it says).
#[test]
fn the_light_tracer_sees_the_floor_through_the_pane() {
    let scene = scene("lt");
    let o = RenderOptions {
        method: Method::parse("lt-bsdf").unwrap(),
        spp: 4,
        max_depth: 4,
        seed: 3,
        ..Default::default()
    };
    let out = render(&scene, &o, |_| {});
    let want: Rgb = expected(&scene).iter().copied().sum::<Rgb>() / (SIDE * SIDE) as f32;
    let got = out.image.mean();
    for c in 0..3 {
        assert!(
            got[c] > 0.5 * want[c],
            "channel {c}: {} against {}",
            got[c],
            want[c]
        );
    }
}

/// `scenes/panes`: a diffuse room lit by an area light, seen only through two coloured
/// panes. Light tracing (camera connections through the panes), the combined image and the
/// guided methods agree with unguided path tracing per region of the image and channel.
/// (Bound: `common::assert_integrators_agree`.)
#[test]
fn every_integrator_sees_the_room_through_the_panes_alike() {
    let mut scene =
        footprint::scene::load::load_scene(&common::scenes_dir().join("panes/scene.xml"))
            .expect("scenes/panes loads");
    scene.camera = scene.camera.with_resolution(32, 32).unwrap();
    scene.maps.photons = 20_000;
    scene.maps.importons = 20_000;
    assert!(scene.effects.thin_glass);
    // Guided too: particles pass them as paths do (small maps: only agreement matters).
    common::assert_integrators_agree(&scene, (10, 8, 8), 4);
}
