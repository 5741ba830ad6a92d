//! The combined image's MIS weights are a partition of unity: for random paths in every
//! bundled scene, the three strategies' weights (camera path hitting the light, next-event
//! connection, light path connected to the camera), each computed by the running trackers
//! of its own subpath, sum to one, with the unguided densities and with the guided ones
//! (guide cache built from the scene's maps: footprints rasterised for sampling, the default,
//! and footprints sampled from their caps with the weights read from each region's table or
//! from the caps). A density that one side computed differently
//! from the other (a throughput-dependent channel mixture, a missed emission term, a
//! forward/reverse mix-up) breaks the sum by far more than the tolerance. Deterministic
//! paths from fixed seeds. Tolerance 1e-3: the two sides evaluate the same densities in f32
//! from directions obtained differently (a sampled direction, a normalised difference of
//! positions), about 1e-7 apart, and a Blinn lobe of exponent n (desk has up to 1e4)
//! amplifies a direction error δ into a relative pdf error of about n·δ.

mod common;

use common::scene_path;
use footprint::bsdf::TransportMode;
use footprint::rng::Rng;
use footprint::scene::Scene;
use footprint::scene::geometry::SurfaceHit;
use footprint::scene::load::load_scene;
use footprint::settings::GuideParams;
use footprint_integrators::Method;
use footprint_integrators::maps::Guidance;
use footprint_integrators::mis::{CameraMis, Densities, LightMis};
use footprint_integrators::passes::PassSettings;
use glam::{Vec2, Vec3};

/// A path x0 (camera) .. x_{k-1} (surfaces), and the light point x_k with its light.
struct Path {
    /// The camera vertex x0: the lens point (the position for a pinhole).
    lens: Vec3,
    hits: Vec<(SurfaceHit, Vec3)>, // hit and the direction of travel into it
    delta: Vec<bool>,
}

fn random_path(scene: &Scene, rng: &mut Rng, len: usize) -> Option<Path> {
    let cam = &scene.camera;
    let raster = rng.uniform2() * Vec2::new(cam.width as f32, cam.height as f32);
    let (lens, first_dir) = cam.ray(raster, cam.draw_lens_sample(rng));
    let (mut origin, mut dir) = (lens, first_dir);
    let mut hits = Vec::new();
    let mut delta = Vec::new();
    for _ in 0..len {
        let hit = scene.intersect(origin, dir, f32::INFINITY)?;
        if hit.light.is_some() {
            return None;
        }
        let bsdf = scene.bsdf(&hit);
        let s = bsdf.sample(-dir, rng.uniform(), rng.uniform2(), TransportMode::Radiance)?;
        hits.push((hit, dir));
        delta.push(s.delta);
        origin = scene.spawn_origin(hit.p, hit.ng, s.wi);
        dir = s.wi;
    }
    Some(Path { lens, hits, delta })
}

/// The three weights of every checked path, with the densities `guided` or not, under the
/// guide settings `params` (what the regions sample from and what the weights read).
fn check_scene(name: &str, guided: bool, params: &GuideParams) -> Vec<[f32; 3]> {
    check(load_scene(&scene_path(name)).unwrap(), name, guided, params)
}

/// [`check_scene`] on a loaded scene.
fn check(mut scene: Scene, name: &str, guided: bool, params: &GuideParams) -> Vec<[f32; 3]> {
    scene.camera = scene.camera.with_resolution(32, 32).unwrap();
    scene.maps.photons = 30_000;
    scene.maps.importons = 30_000;
    let method = Method::parse("combined-footprint").unwrap();
    let pass = PassSettings {
        paths: 0,
        max_depth: 8,
        rr_depth: footprint::settings::DEFAULT_RR_DEPTH,
        seed: 3,
        soft_glossy_max: scene.maps.soft_glossy_max,
        specialise: true,
        target: None,
        max_particles: usize::MAX,
    };
    let g = Guidance::build(&scene, &method, params, &pass, &|| None);
    let camera = g.camera_sampler(&scene, &method, params);
    let light = g.light_sampler(&scene, &method, params);
    let d = Densities {
        camera: &camera,
        light: &light,
        guided,
    };
    let mut rng = Rng::new(41, 0, 0);
    let (mut checked, mut worst) = (0, 0.0f64);
    let mut weights = Vec::new();
    for trial in 0..4000 {
        let len = 1 + trial % 4;
        let Some(path) = random_path(&scene, &mut rng, len) else {
            continue;
        };
        // The light point: a next-event sample from the last surface vertex.
        let (last, last_dir) = path.hits[len - 1];
        let bsdf_last = scene.bsdf(&last);
        if bsdf_last.is_delta() {
            continue;
        }
        let (li, _) = scene.light_distribution.sample(rng.uniform());
        let lgt = &scene.lights[li];
        if lgt.is_environment() {
            continue;
        }
        let Some(ls) = lgt.sample_li(last.p, rng.uniform2()) else {
            continue;
        };
        let k = len as u32 + 1; // segments
        // ---- The camera subpath: x1 .. x_{k-1}, then the next-event weight and the
        // light hit at x_k ----
        let mut cm = CameraMis::new(path.lens, &d);
        for (j, (hit, dir)) in path.hits.iter().enumerate() {
            let depth = j as u32 + 1;
            cm.arrive(&scene, depth, *dir, hit.p, hit.ng);
            if j + 1 < len {
                cm.scattered(depth, hit.p, hit.ng, &scene.bsdf(hit), path.delta[j]);
            }
        }
        let w1 = cm
            .nee(
                &scene,
                li as u32,
                k - 1,
                &bsdf_last,
                last.p,
                last.ng,
                -last_dir,
                &ls,
            )
            .weight();
        cm.scattered(k - 1, last.p, last.ng, &bsdf_last, false);
        let w0 = match ls.n {
            Some(n) => {
                cm.arrive(&scene, k, ls.wi, ls.p, n);
                cm.light_hit(&scene, li as u32, k, -ls.wi, ls.p).weight()
            }
            None => 0.0, // a camera path cannot hit a point, spot or directional light
        };
        // ---- The light subpath: y0 = x_k, y1 = x_{k-1}, ..., y_{k-1} = x1 ----
        let mut lm = LightMis::new(&scene, &d, li as u32, ls.p, ls.n);
        let mut prev = ls.p;
        let mut wk = 0.0;
        for j in (0..len).rev() {
            let (hit, _) = path.hits[j];
            let depth = (len - j) as u32;
            let into = (hit.p - prev).normalize();
            lm.arrive(lgt, depth, into, hit.p, hit.ng);
            let bsdf = scene.bsdf(&hit);
            if j == 0 {
                if bsdf.is_delta() {
                    break;
                }
                // The light path's connection reaches the camera path's lens point.
                let to_cam = (path.lens - hit.p).normalize();
                wk = lm
                    .camera_connection(&scene, depth, &bsdf, hit.p, hit.ng, path.lens, to_cam)
                    .weight();
            } else {
                // The light path leaves y_depth toward x_{j-1}: delta as the camera path's
                // step there (a delta step is delta both ways).
                lm.scattered(depth, hit.p, hit.ng, &bsdf, path.delta[j - 1]);
            }
            prev = hit.p;
        }
        let sum = (w0 + w1 + wk) as f64;
        if sum == 0.0 {
            continue; // no strategy can make this path (delta steps at both ends)
        }
        worst = worst.max((sum - 1.0).abs());
        assert!(
            (sum - 1.0).abs() < 1e-3,
            "{name} (guided {guided}) path {trial} of {k} segments: weights {w0} + {w1} + {wk} = {sum}"
        );
        checked += 1;
        weights.push([w0, w1, wk]);
    }
    eprintln!(
        "{name}, guided {guided}, raster {}, table {}: {checked} paths, largest |sum - 1| {worst:.2e}",
        params.raster, params.mis_table
    );
    assert!(checked > 500, "{name}: only {checked} paths checked");
    weights
}

/// How many paths' weights differ by more than 1e-3 in some strategy.
fn differing(a: &[[f32; 3]], b: &[[f32; 3]]) -> usize {
    a.iter()
        .zip(b)
        .filter(|(x, y)| (0..3).any(|s| (x[s] - y[s]).abs() > 1e-3))
        .count()
}

#[test]
fn weights_sum_to_one_on_random_paths_in_every_bundled_scene() {
    for name in ["cornell", "door", "desk"] {
        // The defaults (footprints rasterised for sampling, whose grid the weights read
        // exactly), and footprints sampled from their caps with the weights read from each
        // region's table or from the caps.
        let defaults = GuideParams::default();
        let caps = |mis_table| GuideParams {
            raster: 0,
            mis_table,
            ..GuideParams::default()
        };
        let unguided = check_scene(name, false, &defaults);
        let guided = check_scene(name, true, &defaults);
        let tabulated = check_scene(name, true, &caps(16));
        let exact = check_scene(name, true, &caps(0));
        // The tables stand in for the exact densities: the weights differ from those.
        let from_exact = differing(&exact, &tabulated);
        eprintln!(
            "{name}: tabulated densities change the weights of {from_exact} of {} paths",
            tabulated.len()
        );
        assert!(from_exact > 0, "{name}: the tables are not read");
        // The guided densities are really used: they change the weights of many paths.
        let changed = differing(&unguided, &guided);
        eprintln!(
            "{name}: guided densities change the weights of {changed} of {} paths",
            guided.len()
        );
        assert!(
            changed * 10 > guided.len(),
            "{name}: guided weights barely differ"
        );
    }
}

/// The same under a directional light (`tests/emitters/directional.xml`): next-event estimation
/// and light tracing are the strategies that make its paths, the light path's first vertex
/// of area density `pdf_pos |cos θ|` from the bounding disk.
#[test]
fn weights_sum_to_one_under_a_directional_light() {
    let xml = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/emitters/directional.xml");
    let scene = footprint::scene::mitsuba::load(&xml, &Default::default()).unwrap();
    assert!(scene.lights.iter().all(|l| l.is_delta() && l.is_infinite()));
    let defaults = GuideParams::default();
    for guided in [false, true] {
        let w = check(scene.clone(), "directional", guided, &defaults);
        // Both strategies carry weight.
        assert!(w.iter().any(|w| w[1] > 0.1) && w.iter().any(|w| w[2] > 0.1));
    }
}

/// The same through a thin lens (cornell's camera with an aperture of radius 0.3 focused on
/// the back wall): the camera vertex is a lens point, its area density `1 / A_lens` shared
/// by all three strategies, the direction from it of the pinhole's density at that point.
#[test]
fn weights_sum_to_one_through_a_thin_lens() {
    let mut scene = load_scene(&scene_path("cornell")).unwrap();
    scene.camera = scene.camera.clone().with_lens(0.3, 13.6).unwrap();
    let defaults = GuideParams::default();
    for guided in [false, true] {
        let w = check(scene.clone(), "cornell through a lens", guided, &defaults);
        // Next-event estimation and light tracing both carry weight; hitting the small
        // light carries some.
        assert!(w.iter().any(|w| w[1] > 0.1) && w.iter().any(|w| w[2] > 0.1));
        assert!(w.iter().any(|w| w[0] > 0.0));
    }
}
