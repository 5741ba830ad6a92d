//! The bundled scenes: every one renders with both integrators without a NaN, infinite or
//! negative pixel; the effect analysis finds what each scene contains; equal seeds give
//! equal images whatever the number of threads.

mod common;

use common::scene_path;
use footprint::scene::effects::Effects;
use footprint::scene::load::load_scene;
use footprint_integrators::{Method, RenderOptions, render};

fn opts(integrator: &str, spp: u32, seed: u64) -> RenderOptions {
    RenderOptions {
        method: Method::from_names(integrator, "bsdf").unwrap(),
        spp,
        time: None,
        max_depth: 12,
        seed,
        ..Default::default()
    }
}

#[test]
fn no_invalid_pixel_in_any_bundled_scene() {
    for name in ["cornell", "door", "desk", "furnace"] {
        let mut scene = load_scene(&scene_path(name)).unwrap();
        scene.camera = scene.camera.with_resolution(64, 64).unwrap();
        for integrator in ["pt", "lt"] {
            let r = render(&scene, &opts(integrator, 16, 3), |_| {});
            assert!(r.image.all_valid(), "{name} {integrator:?}: invalid pixel");
            assert_eq!(
                r.stats.rejected, 0,
                "{name} {integrator:?}: rejected samples"
            );
            // door is lit only through a 4 cm gap: at 64x64 and 16 samples neither unguided
            // integrator is sure to find a lit pixel (that is what guiding is for).
            if name != "door" {
                assert!(
                    r.image.mean().max_element() > 0.0,
                    "{name} {integrator:?}: black image"
                );
            }
            eprintln!(
                "{name} {integrator:?}: mean {:?}, largest sample {:.3}",
                r.image.mean(),
                r.stats.max_luminance
            );
        }
    }
}

#[test]
fn effect_analysis_is_right_for_each_scene() {
    let e = |name: &str| load_scene(&scene_path(name)).unwrap().effects;
    let diffuse_area = Effects {
        diffuse: true,
        area_lights: true,
        ..Default::default()
    };
    assert_eq!(e("cornell"), diffuse_area);
    assert_eq!(e("door"), diffuse_area);
    assert_eq!(e("furnace"), diffuse_area);
    assert_eq!(
        e("desk"),
        Effects {
            diffuse: true,
            glossy: true,
            non_lambertian: true,
            spot_lights: true,
            ..Default::default()
        }
    );
    // The skips follow from the effects.
    let desk = load_scene(&scene_path("desk")).unwrap();
    assert!(
        desk.effects
            .skipped()
            .iter()
            .any(|s| s.contains("no area lights"))
    );
    let cornell = load_scene(&scene_path("cornell")).unwrap();
    assert!(
        cornell
            .effects
            .skipped()
            .iter()
            .any(|s| s.contains("no textures"))
    );
    assert!(
        !cornell
            .effects
            .skipped()
            .iter()
            .any(|s| s.contains("no area lights"))
    );
}

#[test]
fn equal_seeds_give_equal_images_whatever_the_thread_count() {
    let mut scene = load_scene(&scene_path("cornell")).unwrap();
    scene.camera = scene.camera.with_resolution(48, 40).unwrap();
    // A tent filter: camera samples are splatted into neighbouring rows too.
    let mut tent = scene.camera.clone();
    tent.filter =
        footprint::film::filter::PixelFilter::new(footprint::film::filter::FilterKind::Tent {
            radius: 1.0,
        });
    for (integrator, filtered) in [("pt", false), ("lt", false), ("combined", true)] {
        let mut scene = load_scene(&scene_path("cornell")).unwrap();
        scene.camera = if filtered {
            tent.clone()
        } else {
            scene.camera.with_resolution(48, 40).unwrap()
        };
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| render(&scene, &opts(integrator, 3, 42), |_| {}).image)
        };
        let (a, b, c) = (run(1), run(2), run(5));
        assert!(
            a.pixels == b.pixels && b.pixels == c.pixels,
            "{integrator:?} (filtered {filtered}): image depends on the thread count"
        );
        let other = {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(2)
                .build()
                .unwrap();
            pool.install(|| render(&scene, &opts(integrator, 3, 43), |_| {}).image)
        };
        assert!(
            other.pixels != a.pixels,
            "{integrator:?}: the seed changes nothing"
        );
    }
}
