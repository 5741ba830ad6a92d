//! The effect analysis and what it changes: the path loop specialised for a scene's effects
//! gives the general loop's image bit for bit (same random numbers, same floating-point
//! operations), for every integrator, guided or not.

mod common;

use common::scene_path;
use footprint::bsdf::material::MaterialKind;
use footprint::scene::Scene;
use footprint::scene::effects::Effects;
use footprint::scene::features::Specialisation;
use footprint::scene::load::load_scene;
use footprint_integrators::skips::Skip;
use footprint_integrators::{Method, RenderOptions, render};

fn small(name: &str) -> Scene {
    let mut s = load_scene(&scene_path(name)).unwrap();
    s.camera = s.camera.with_resolution(24, 24).unwrap();
    s.maps.photons = 4000;
    s.maps.importons = 4000;
    s
}

/// cornell with its tall block turned into glass: specular surfaces, no textures.
fn cornell_with_glass() -> Scene {
    let mut s = small("cornell");
    let tall = s.shading[s.shading.len() - 1].material as usize;
    s.materials[tall].kind = MaterialKind::Glass;
    s.effects = Effects::analyse(&s.materials, &s.shading, &s.lights);
    s
}

#[test]
fn specialised_loops_give_the_general_loops_image_bit_for_bit() {
    let scenes = [
        ("cornell", small("cornell"), Specialisation::LambertArea),
        ("desk", small("desk"), Specialisation::Untextured),
        (
            "cornell with glass",
            cornell_with_glass(),
            Specialisation::Untextured,
        ),
    ];
    for (name, scene, expected) in &scenes {
        assert_eq!(
            Specialisation::for_effects(&scene.effects),
            *expected,
            "{name}"
        );
        for method in ["pt-bsdf", "lt-bsdf", "combined-bsdf", "combined-footprint"] {
            let run = |specialise: bool| {
                let o = RenderOptions {
                    method: Method::parse(method).unwrap(),
                    spp: 2,
                    seed: 7,
                    specialise,
                    ..Default::default()
                };
                render(scene, &o, |_| {})
            };
            let (a, b) = (run(true), run(false));
            for ((la, ia), (_, ib)) in a.layers.iter().zip(&b.layers) {
                assert!(
                    ia.pixels == ib.pixels,
                    "{name} {method} layer {la}: the specialised loop changed the image"
                );
            }
            assert!(a.image.mean().max_element() > 0.0, "{name} {method}: black");
        }
    }
}

/// The image of `method` on `scene` (2 spp, seed 7), and what it skipped.
fn run(scene: &Scene, method: &str) -> footprint_integrators::RenderResult {
    let o = RenderOptions {
        method: Method::parse(method).unwrap(),
        spp: 2,
        seed: 7,
        ..Default::default()
    };
    render(scene, &o, |_| {})
}

fn same_image(a: &footprint_integrators::RenderResult, b: &footprint_integrators::RenderResult) {
    for ((la, ia), (_, ib)) in a.layers.iter().zip(&b.layers) {
        assert!(
            ia.pixels == ib.pixels,
            "layer {la}: the skip changed the image"
        );
    }
}

/// How often the render skipped work by the rule `rule` picks out (`None`: not at all).
fn has(r: &footprint_integrators::RenderResult, rule: fn(&Skip) -> bool) -> Option<u64> {
    r.skipped.iter().find(|s| rule(s)).map(Skip::count)
}

const EMISSION: fn(&Skip) -> bool = |s| matches!(s, Skip::EmissionLookups(_));
const ENVIRONMENT: fn(&Skip) -> bool = |s| matches!(s, Skip::EnvironmentLookups(_));
const LOOP: fn(&Skip) -> bool = |s| matches!(s, Skip::SpecialisedLoop { .. });
const PASSES: fn(&Skip) -> bool = |s| matches!(s, Skip::ParticlePasses(_));

/// The rule "no area lights" (docs/effects.md): without area lights, camera paths do no
/// emission lookups at hits; the same image as with the lookups (the scene's effects made to
/// claim an area light).
#[test]
fn no_area_lights_skips_emission_lookups_and_changes_nothing() {
    let desk = small("desk");
    let mut claims = small("desk");
    claims.effects.area_lights = true;
    for method in ["pt-bsdf", "combined-bsdf"] {
        let (a, b) = (run(&desk, method), run(&claims, method));
        same_image(&a, &b);
        let n = has(&a, EMISSION).expect("counted");
        assert!(n > 1000, "{method}: {n} lookups skipped");
        assert_eq!(has(&b, EMISSION), None);
    }
}

/// The rule "no environment" (docs/effects.md): without an environment, escaping rays look
/// nothing up.
#[test]
fn no_environment_skips_environment_lookups_and_changes_nothing() {
    let cornell = small("cornell");
    let mut claims = small("cornell");
    claims.effects.environment = true;
    assert_eq!(
        Specialisation::for_effects(&claims.effects),
        Specialisation::General
    );
    for method in ["pt-bsdf", "combined-bsdf"] {
        let (a, b) = (run(&cornell, method), run(&claims, method));
        same_image(&a, &b);
        // cornell is open at the front: camera rays escape.
        assert!(has(&a, ENVIRONMENT).expect("counted") > 0);
        assert_eq!(has(&b, ENVIRONMENT), None);
        assert!(has(&a, LOOP).expect("counted") > 0);
        assert_eq!(has(&b, LOOP), None);
    }
}

/// The rule "no surface stores particles" (docs/effects.md): a scene with no surface that
/// stores particles (every surface a mirror) runs no particle pass for a guided method, and
/// gives the image of a run that built the (empty) maps.
#[test]
fn no_particle_surfaces_skips_the_passes_and_changes_nothing() {
    let mut mirrors = small("cornell");
    for m in &mut mirrors.materials {
        m.kind = MaterialKind::Mirror;
        m.ks = footprint::Rgb::splat(0.8);
    }
    mirrors.effects = Effects::analyse(&mirrors.materials, &mirrors.shading, &mirrors.lights);
    assert!(!footprint_integrators::skips::particles_stored(&mirrors));
    for method in ["pt-footprint", "lt-footprint", "combined-footprint"] {
        let skipping = run(&mirrors, method);
        let o = RenderOptions {
            method: Method::parse(method).unwrap(),
            spp: 2,
            seed: 7,
            ..Default::default()
        };
        let pass = footprint_integrators::passes::PassSettings {
            paths: 0,
            max_depth: o.max_depth,
            rr_depth: o.rr_depth,
            seed: o.seed,
            soft_glossy_max: mirrors.maps.soft_glossy_max,
            specialise: false,
            target: None,
            max_particles: usize::MAX,
        };
        let g = footprint_integrators::maps::Guidance::build(
            &mirrors,
            &o.method,
            &o.guide_params,
            &pass,
            &|| None,
        );
        assert!(
            g.photons.is_some() || g.importons.is_some(),
            "{method}: no maps"
        );
        let built = footprint_integrators::render_prepared(
            &mirrors,
            &o,
            &g,
            std::time::Duration::ZERO,
            footprint_integrators::StopRule::WithinBudget,
            |_| {},
        );
        same_image(&skipping, &built);
        assert_eq!(has(&skipping, PASSES), Some(2), "{method}");
        assert!(skipping.maps.is_empty());
        assert!(skipping.image.mean().max_element() > 0.0, "{method}: black");
    }
}

/// Every bundled and imported scene lists what its effects let the renderer skip, and a
/// render of it reports the counters.
#[test]
fn every_scene_lists_its_skips() {
    let mut scenes: Vec<(String, Scene)> = ["cornell", "door", "desk", "furnace"]
        .iter()
        .map(|n| (n.to_string(), small(n)))
        .collect();
    let features = common::scenes_dir().join("features/scene.xml");
    scenes.push(("features".into(), load_scene(&features).unwrap()));
    let ext = common::scenes_dir().join("../../shared/scenes-ext");
    let imported = [
        ("veach-ajar/scene.xml", vec![("resx", "32"), ("resy", "18")]),
        (
            "cornell-box-bitterli/scene.xml",
            vec![("resx", "16"), ("resy", "16")],
        ),
        ("cornell-box-mcguire/mitsuba/scene.xml", vec![("res", "16")]),
    ];
    if ext.is_dir() {
        for (name, defines) in imported {
            let opts = footprint::scene::mitsuba::ImportOptions {
                defines: defines
                    .iter()
                    .map(|(k, v)| (k.to_string(), v.to_string()))
                    .collect(),
                lenient: false,
            };
            scenes.push((
                name.into(),
                footprint::scene::mitsuba::load(&ext.join(name), &opts).unwrap(),
            ));
        }
    } else {
        common::skip(
            "every_scene_lists_its_skips",
            "../shared/scenes-ext is absent: only the bundled scenes checked",
        );
    }
    for (name, mut scene) in scenes {
        if scene.camera.width > 32 {
            scene.camera = scene.camera.with_resolution(32, 24).unwrap();
        }
        let e = &scene.effects;
        let listed = e.skipped();
        let r = run(&scene, "pt-bsdf");
        eprintln!(
            "{name}: {:?}; loop {:?}; skips {listed:?}; counted {:?}",
            e.list()
                .iter()
                .filter(|x| x.1)
                .map(|x| x.0)
                .collect::<Vec<_>>(),
            Specialisation::for_effects(e),
            r.skipped
        );
        assert_eq!(
            listed.iter().any(|s| s.contains("area lights")),
            !e.area_lights,
            "{name}"
        );
        assert_eq!(has(&r, EMISSION).is_some(), !e.area_lights, "{name}");
        assert_eq!(has(&r, ENVIRONMENT).is_some(), !e.environment, "{name}");
        assert_eq!(
            has(&r, LOOP).is_some(),
            Specialisation::for_effects(e) != Specialisation::General,
            "{name}"
        );
        // "No surface stores particles" on a guided method: the passes are skipped exactly where nothing stores
        // particles (small maps: only whether they are built matters here).
        scene.maps.photons = 2000;
        scene.maps.importons = 2000;
        let g = run(&scene, "combined-footprint");
        assert_eq!(
            has(&g, PASSES).is_some(),
            !footprint_integrators::skips::particles_stored(&scene),
            "{name}"
        );
    }
}
