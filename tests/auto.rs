//! `auto`: the pilot chooses light tracing where light tracing is the only way (a caustic
//! of a point light cast through glass) and path tracing where the camera sees mostly the
//! light's direct glow; `compare` and `render` accept it.

mod common;

use footprint::scene::Scene;
use footprint::scene::load::load_scene;
use footprint_integrators::auto::{
    AutoSpec, Decision, Note, Request, Run, choose, particle_pass_seconds, render_request,
};
use footprint_integrators::maps::run_passes;
use footprint_integrators::render::pass_settings;
use footprint_integrators::{Method, RenderOptions};
use std::path::PathBuf;
use std::time::Instant;

/// A folder of its own for a test's scene files.
fn dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A point light inside a glass cube above a white floor: every path from the light to
/// what the camera sees passes through glass, so only light tracing finds the light.
fn caustic_scene() -> Scene {
    let d = dir("auto-caustic");
    let mut obj = String::from("mtllib scene.mtl\no floor\nusemtl white\n");
    obj += "v -3 0 -3\nv 3 0 -3\nv 3 0 3\nv -3 0 3\nf 1 4 3\nf 1 3 2\n";
    obj += "o glass\n";
    obj += &common::box_obj([-0.4, 0.8, -0.4], [0.4, 1.6, 0.4], 5, "glass");
    std::fs::write(d.join("scene.obj"), obj).unwrap();
    std::fs::write(
        d.join("scene.mtl"),
        "newmtl white\nKd 0.8 0.8 0.8\nKs 0 0 0\nillum 1\nnewmtl glass\nKd 0 0 0\nNi 1.5\nTf 1 1 1\nillum 7\n",
    )
    .unwrap();
    std::fs::write(
        d.join("scene.toml"),
        "[camera]\nposition = [0.0, 2.5, -3.5]\nlook_at = [0.0, 0.0, 0.5]\nfov_y = 45.0\nresolution = [40, 40]\n\n[[mesh]]\nfile = \"scene.obj\"\n\n[[light]]\ntype = \"point\"\nposition = [0.0, 1.2, 0.0]\nintensity = [20.0, 20.0, 20.0]\n",
    )
    .unwrap();
    load_scene(&d.join("scene.toml")).unwrap()
}

/// cornell seen from below its ceiling light, which fills most of the picture.
fn glow_scene() -> Scene {
    let d = dir("auto-glow");
    let cornell = common::scenes_dir().join("cornell/cornell.obj");
    std::fs::write(
        d.join("scene.toml"),
        format!(
            "[camera]\nposition = [2.78, 4.6, 2.795]\nlook_at = [2.78, 5.5, 2.795]\nup = [0.0, 0.0, 1.0]\nfov_y = 70.0\nresolution = [40, 40]\n\n[[mesh]]\nfile = \"{}\"\n",
            cornell.display()
        ),
    )
    .unwrap();
    load_scene(&d.join("scene.toml")).unwrap()
}

/// The spec of `auto` with `guide` fixed (`auto-GUIDE`): the integrator chosen.
fn integrator_chosen(guide: &str) -> AutoSpec {
    AutoSpec::new(None, Some(Method::guide(guide).unwrap()))
}

/// Renders `request` as `footprint render` does, and returns the result and the choice.
fn rendered(
    scene: &Scene,
    o: &RenderOptions,
    request: &Request,
) -> footprint_integrators::auto::Rendered {
    render_request(scene, o, request, &Run::default(), &mut |_| {}, |_| {}).unwrap()
}

fn opts() -> RenderOptions {
    RenderOptions {
        spp: 32,
        seed: 3,
        max_depth: 8,
        ..Default::default()
    }
}

#[test]
fn auto_picks_light_tracing_for_a_point_light_caustic_through_glass() {
    let scene = caustic_scene();
    let spec = integrator_chosen("bsdf");
    assert_eq!(spec.label, "auto-bsdf");
    // Compared at the time of 256 path-tracing passes: at a few milliseconds (32 passes of
    // this 40x40 image) light tracing's own noise is as large as the whole missing caustic,
    // and the choice would turn on the machine's pass-time ratio.
    let o = RenderOptions { spp: 256, ..opts() };
    let c = choose(&scene, &o, &spec);
    eprintln!("{c:?}");
    assert_eq!(c.method.name(), "lt-bsdf", "{c:?}");
    assert!(
        c.noted(|n| matches!(n, Note::MissesLight { method, .. } if method == "pt-bsdf")),
        "{c:?}"
    );
}

#[test]
fn auto_picks_path_tracing_where_the_camera_sees_the_lights_glow() {
    let scene = glow_scene();
    let c = choose(&scene, &opts(), &integrator_chosen("bsdf"));
    eprintln!("{c:?}");
    assert_eq!(c.method.name(), "pt-bsdf", "{c:?}");
}

/// `render` with `auto`: the pilot counts in a time budget, the result says what was chosen.
#[test]
fn render_with_auto_keeps_the_budget_and_reports_the_choice() {
    let mut scene = load_scene(&common::scene_path("desk")).unwrap();
    scene.camera = scene.camera.with_resolution(48, 48).unwrap();
    let o = RenderOptions {
        time: Some(1.5),
        ..opts()
    };
    let request = Request::default()
        .with_names(Some("auto"), Some("auto"))
        .unwrap();
    assert_eq!(request.label(), "auto");
    let out = rendered(&scene, &o, &request);
    let c = out.choice.expect("auto reports its choice");
    let r = out.result;
    eprintln!("desk: {c:?}");
    assert_eq!(r.method, c.method, "the chosen method renders");
    // The pilot counts in the budget (25% slack: a loaded machine slows the last pass).
    assert!(r.elapsed.as_secs_f64() < 1.5 * 1.25, "took {:?}", r.elapsed);
    assert!(r.image.all_valid() && r.image.mean().max_element() > 0.0);
    // A fixed part stays fixed.
    let Request::Auto(spec) = request.with_names(Some("lt"), None).unwrap() else {
        panic!("the guide is still chosen")
    };
    assert_eq!(spec.label, "lt-auto");
    assert!(spec.candidates.iter().all(|m| m.integrator.name() == "lt"));
    // Naming the other part fixes the method; naming auto again chooses it.
    let fixed = request.with_names(Some("lt"), Some("grid")).unwrap();
    assert_eq!(fixed, Request::Fixed(Method::parse("lt-grid").unwrap()));
    assert_eq!(
        fixed.with_names(None, Some("auto")).unwrap().label(),
        "lt-auto"
    );
    assert_eq!(Request::parse("pt-auto").unwrap().label(), "pt-auto");
    assert_eq!(
        Request::parse("auto").unwrap(),
        Request::Auto(AutoSpec::all())
    );
    assert!(Request::parse("pt-bsdf").unwrap().fixed().is_some());
    assert!(Request::parse("pt-nothing").is_err());
}

/// An image of more than `PILOT_MAX_PIXELS` pixels is piloted at a lower resolution (both
/// sides halved here), and the maps the pilot built there guide the render at the image's
/// own resolution: the run names the pilot's resolution, the image has the requested size,
/// and every pixel is valid and lit.
#[test]
fn a_large_image_is_piloted_at_a_lower_resolution_and_its_maps_guide_the_render() {
    let mut scene = load_scene(&common::scene_path("cornell")).unwrap();
    let (w, h) = (192, 160);
    assert!((w * h) as usize > footprint_integrators::auto::PILOT_MAX_PIXELS);
    scene.camera = scene.camera.with_resolution(w, h).unwrap();
    scene.maps.photons = 20_000;
    scene.maps.importons = 20_000;
    let spec = integrator_chosen("footprint");
    let o = RenderOptions { spp: 2, ..opts() };
    let c = choose(&scene, &o, &spec);
    eprintln!("{c:?}");
    let piloted_at = |c: &footprint_integrators::auto::Choice| {
        c.noted(|n| matches!(n, Note::PilotResolution { pilot: (96, 80), image, .. } if *image == (w, h)))
    };
    assert!(piloted_at(&c), "{c:?}");
    assert!(c.guidance.is_some(), "the piloted maps are handed on");
    // Two passes leave no room for the light tracer's importance target at the image's
    // resolution: the pilot builds it at its own (FULL_TARGET_SHARE).
    assert!(
        !c.noted(|n| matches!(n, Note::TargetAtImageResolution { .. })),
        "{c:?}"
    );
    assert!(
        c.candidates
            .iter()
            .all(|k| k.pass_seconds > 0.0 && k.predicted >= 0.0),
        "{:?}",
        c.candidates
    );
    let out = rendered(&scene, &o, &Request::Auto(spec));
    assert!(piloted_at(out.choice.as_ref().unwrap()));
    let out = out.result;
    assert_eq!((out.image.width, out.image.height), (w, h));
    assert!(out.image.all_valid() && out.image.mean().min_element() > 0.0);
}

/// Compared at the time of many passes, the target's four passes at the image's resolution
/// are a small share of what is left, and the pilot's view pass reads the target at the
/// image's resolution (the extra time against the horizon: four unguided combined passes
/// at four times the pixels against 0.08 of 100000 path-tracing passes, a margin of
/// thousands).
#[test]
fn a_long_horizon_builds_the_importance_target_at_the_images_resolution() {
    let mut scene = load_scene(&common::scene_path("cornell")).unwrap();
    let (w, h) = (192, 160);
    scene.camera = scene.camera.with_resolution(w, h).unwrap();
    scene.maps.photons = 20_000;
    scene.maps.importons = 20_000;
    let o = RenderOptions {
        spp: 100_000,
        ..opts()
    };
    let c = choose(&scene, &o, &integrator_chosen("footprint"));
    eprintln!("{c:?}");
    assert!(
        c.noted(|n| matches!(
            n,
            Note::PilotResolution {
                pilot: (96, 80),
                ..
            }
        )),
        "{c:?}"
    );
    assert!(
        c.noted(|n| matches!(
            n,
            Note::TargetAtImageResolution {
                image: (192, 160),
                ..
            }
        )),
        "{c:?}"
    );
    let g = c.guidance.expect("the piloted maps are handed on");
    assert!(g.importons.as_ref().is_some_and(|m| m.map.len() > 0));
}

/// Every candidate guided (`--integrator auto --guide footprint`) with a sample budget whose
/// maps would not fit the guided-maps share: the maps are piloted anyway, and a footprint
/// method is chosen (the candidate list is not empty).
#[test]
fn auto_with_a_fixed_guide_chooses_among_guided_methods() {
    let mut scene = load_scene(&common::scene_path("cornell")).unwrap();
    scene.camera = scene.camera.with_resolution(32, 32).unwrap();
    scene.maps.photons = 20_000;
    scene.maps.importons = 20_000;
    let spec = integrator_chosen("footprint");
    assert_eq!(spec.label, "auto-footprint");
    let o = RenderOptions { spp: 2, ..opts() };
    let c = choose(&scene, &o, &spec);
    eprintln!("{c:?}");
    assert_eq!(c.method.guide.name(), "footprint", "{c:?}");
    assert!(c.guidance.is_some(), "the piloted maps are handed on");
}

/// A budget too short for a pilot renders the first unguided candidate without one.
#[test]
fn auto_without_room_for_a_pilot_renders_unguided() {
    let scene = glow_scene();
    let o = RenderOptions {
        time: Some(1e-4),
        ..opts()
    };
    let c = choose(&scene, &o, &AutoSpec::all());
    eprintln!("{c:?}");
    assert_eq!(c.method.name(), "pt-bsdf");
    assert!(
        matches!(c.decision, Decision::NoRoomForPilot { budget_s, .. } if budget_s == 1e-4),
        "{c:?}"
    );
}

/// The glow scene (easy per sample) and door at 128x128 (hard), each with `paths` photon and
/// importon paths, named and marked hard.
fn easy_and_hard(paths: usize) -> [(&'static str, Scene, bool); 2] {
    let mut door = load_scene(&common::scene_path("door")).unwrap();
    door.camera = door.camera.with_resolution(128, 128).unwrap();
    [("glow", glow_scene(), false), ("door", door, true)].map(|(name, mut scene, hard)| {
        scene.maps.photons = paths;
        scene.maps.importons = paths;
        (name, scene, hard)
    })
}

/// Guides are piloted only where the scene is hard per sample: where the camera sees mostly
/// the light's glow one unguided pass has a small relative variance and no guide is piloted
/// (its maps would fit: small maps, a long sample budget); on door, whose light reaches the
/// camera's room through a gap, the footprints are piloted. Door at 128x128 (one unguided
/// pass: 196-419 here, the glow 0.01-0.8, the gate 4): at 32x32 each pixel averages 16
/// times the area and the pilot measures 7-12, near enough the gate that which candidate
/// the timings make best could decide the test.
#[test]
fn only_scenes_hard_per_sample_pilot_guides() {
    for (name, scene, guided) in easy_and_hard(20_000) {
        let o = RenderOptions {
            spp: 4000,
            ..opts()
        };
        let c = choose(&scene, &o, &AutoSpec::all());
        eprintln!("{name}: {c:?}");
        let gated = c.noted(|n| {
            matches!(
                n,
                Note::EasyScene {
                    guide: "footprint",
                    ..
                }
            )
        });
        assert_eq!(gated, !guided, "{name}: {c:?}");
        let piloted = c
            .candidates
            .iter()
            .any(|c| c.method.ends_with("-footprint"));
        assert_eq!(piloted, guided, "{name}: {c:?}");
    }
}

/// Where no guide's maps fit a short budget, a scene hard per sample bets on guided path
/// tracing unpiloted, and an easy one renders unguided. Door at 128x128 (one unguided pass:
/// 196-419, far above `HARD_PASS_VARIANCE`, 10) and the glow scene (0.01-0.8), with
/// particle passes of two million paths each (estimated at about 20 s, far over 30% of the
/// 12-s budget) and room for the unguided pilot (40 pairs of door's passes take about 5 s).
#[test]
fn a_hard_scene_whose_maps_do_not_fit_renders_guided_path_tracing() {
    for (name, scene, bet) in easy_and_hard(2_000_000) {
        let o = RenderOptions {
            time: Some(12.0),
            ..opts()
        };
        let c = choose(&scene, &o, &AutoSpec::all());
        eprintln!("{name}: {}", c.reason());
        let unpiloted = matches!(c.decision, Decision::HardSceneUnpiloted { .. });
        assert_eq!(unpiloted, bet, "{name}: {c:?}");
        if bet {
            assert_eq!(c.method.name(), "pt-footprint", "{c:?}");
            assert!(c.guidance.is_none(), "the render builds the maps");
            assert!(
                c.noted(|n| matches!(n, Note::MapsTooCostly { .. })),
                "{c:?}"
            );
        } else {
            assert!(!c.method.guided(), "{name}: {c:?}");
        }
    }
}

/// The command line: a part named nowhere (flag or scene file) is chosen when the other is
/// (`--integrator auto` alone chooses the guide too); a part named anywhere stays fixed;
/// nothing named chooses both. Read back from the label the EXR header records.
#[test]
fn integrator_auto_alone_chooses_the_guide_too() {
    let d = dir("auto-cli");
    let cornell = common::scenes_dir().join("cornell/cornell.obj");
    let scene = |render: &str| {
        format!(
            "[camera]\nposition = [2.78, 2.73, -8.0]\nlook_at = [2.78, 2.73, 0.0]\nfov_y = 39.0\nresolution = [16, 16]\n\n[render]\nspp = 2\n{render}\n[[mesh]]\nfile = \"{}\"\n",
            cornell.display()
        )
    };
    let label = |file: &str, render: &str, flags: &[&str]| -> String {
        let path = d.join(file);
        std::fs::write(&path, scene(render)).unwrap();
        let out = d.join(format!("{file}.exr"));
        let run = std::process::Command::new(env!("CARGO_BIN_EXE_footprint"))
            .arg("render")
            .arg(&path)
            .args(flags)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        footprint::film::image_io::read_exr_text_attribute(&out, "footprint/auto")
            .map(|a| a.split(':').next().unwrap().to_string())
            .unwrap_or_else(|| "fixed".into())
    };
    assert_eq!(label("none.toml", "", &[]), "auto");
    assert_eq!(label("i.toml", "", &["--integrator", "auto"]), "auto");
    assert_eq!(label("g.toml", "", &["--guide", "auto"]), "auto");
    let fixed_guide = ["--integrator", "auto", "--guide", "bsdf"];
    assert_eq!(label("ig.toml", "", &fixed_guide), "auto-bsdf");
    // A guide the scene names stays fixed.
    let named = "guide = \"grid\"\n";
    assert_eq!(
        label("s.toml", named, &["--integrator", "auto"]),
        "auto-grid"
    );
    assert_eq!(label("f.toml", named, &["--integrator", "lt"]), "fixed");
}

/// `auto` judges whether a guide's maps fit its budget by their particle passes, timed on a
/// sixteenth of their paths (at least four chunks of paths per worker) and scaled up
/// (`particle_pass_seconds`). On the slit room that estimate of `combined-footprint`'s passes
/// lies within 1.5x of the passes run in full (`run_passes`), the fastest of three runs of
/// each, alternated (other jobs only ever slow a run down; a part of the paths keeps the
/// workers less evenly busy, about 10% here). Unscaled, the estimate reads 0.05 s against
/// 0.68 s (checked), and the test fails.
#[test]
fn the_maps_particle_passes_are_estimated_from_a_part_of_their_paths() {
    let scene = load_scene(&common::scenes_dir().join("slit/scene.xml")).unwrap();
    let o = RenderOptions {
        max_depth: 10,
        ..opts()
    };
    let method = Method::from_names("combined", "footprint").unwrap();
    let pass = pass_settings(&scene, &o);
    let (mut estimate, mut full) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..3 {
        estimate = estimate.min(particle_pass_seconds(&scene, &o, &method));
        let t = Instant::now();
        let passes = run_passes(&scene, &method, &o.guide_params, &pass);
        full = full.min(t.elapsed().as_secs_f64());
        drop(passes);
    }
    eprintln!("particle passes estimated {estimate:.3} s, took {full:.3} s");
    assert!(
        estimate < 1.5 * full && estimate > full / 1.5,
        "particle passes estimated at {estimate:.3} s, took {full:.3} s"
    );
}
