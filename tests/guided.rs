//! Guided integrators: every integrator x guide pair converges to the same image, stays
//! numerically stable on hard scenes, and is reproducible whatever the thread count.
//!
//! Agreement: each pair renders `R` images (different seeds, given one set of maps built per
//! pair: a guided estimate is unbiased given any maps) at low resolution; so does an
//! unguided path-traced reference. Per region and
//! channel, the difference of the two means is compared with its standard error from the
//! replicates' spread (Welch), against Student's t with `R - 1` degrees of freedom at
//! significance 0.01, Šidák-corrected over every pair x region x channel of the scene.

mod common;

use common::{PAIRS, mean_stderr, scene_path, sidak, t_critical};
use footprint::scene::Scene;
use footprint::scene::load::load_scene;
use footprint::settings::GuideParams;
use footprint_integrators::render::{guidance, render_guided};
use footprint_integrators::{Method, RenderOptions, render};
use std::time::Instant;

fn small(name: &str, w: u32, h: u32, particles: usize) -> Scene {
    let mut s = load_scene(&scene_path(name)).unwrap();
    s.camera = s.camera.with_resolution(w, h).unwrap();
    s.maps.photons = particles;
    s.maps.importons = particles;
    s
}

fn opts(method: &str, spp: u32, max_depth: u32, seed: u64) -> RenderOptions {
    RenderOptions {
        method: Method::parse(method).unwrap(),
        spp,
        time: None,
        max_depth,
        seed,
        ..Default::default()
    }
}

/// The guide parameters of the paper's per-event method (no guide cache).
fn per_event() -> GuideParams {
    GuideParams {
        cache: false,
        ..Default::default()
    }
}

/// Regions whose `p_BSDF` a render learned.
fn learned_regions(r: &footprint_integrators::RenderResult) -> usize {
    r.learned_p_bsdf
        .expect("the run reports the learned regions")
        .0
}

#[allow(clippy::too_many_arguments)]
fn agreement(
    scene: &Scene,
    side: u32,
    renders: usize,
    spp: u32,
    max_depth: u32,
    methods: &[&str],
    params: &GuideParams,
) {
    // The maps and caches are built once per method (from the first replicate's seed) and
    // shared by its replicates: a guided estimate is unbiased given any maps, so the
    // replicates' mean must match the reference given these ones.
    let replicate = |m: &str, seed: u64| -> Vec<Vec<[f64; 3]>> {
        let with_seed = |seed: u64| RenderOptions {
            guide_params: params.clone(),
            ..opts(m, spp, max_depth, seed)
        };
        let maps = guidance(scene, &with_seed(seed), &|| None);
        (0..renders)
            .map(|r| {
                let o = with_seed(seed + r as u64);
                let out = render_guided(scene, &o, &maps, Instant::now(), |_| {});
                assert!(out.image.all_valid(), "{m}: invalid pixel");
                common::region_means(&out.image, side)
            })
            .collect()
    };
    let reference = replicate("pt-bsdf", 5000);
    let n_regions = (side * side) as usize;
    let crit = t_critical(
        sidak(0.01, methods.len() * n_regions * 3),
        (renders - 1) as f64,
    );
    let stat = |reps: &Vec<Vec<[f64; 3]>>, i: usize, c: usize| {
        mean_stderr(&reps.iter().map(|r| r[i][c]).collect::<Vec<_>>())
    };
    let mut failures = Vec::new();
    for &m in methods {
        // Other seeds than the reference's: the unguided path tracer is compared with an
        // independent replicate set of itself.
        let reps = replicate(m, 1000);
        let mut worst = 0.0f64;
        for i in 0..n_regions {
            for c in 0..3 {
                let (ma, sa) = stat(&reps, i, c);
                let (mb, sb) = stat(&reference, i, c);
                let se = (sa * sa + sb * sb).sqrt();
                if se == 0.0 && ma == mb {
                    continue;
                }
                let t = (ma - mb).abs() / se.max(1e-30);
                worst = worst.max(t);
                if t > crit {
                    failures.push(format!("{m} region {i} channel {c}: {ma:.5} ± {sa:.5} vs reference {mb:.5} ± {sb:.5} (|t| {t:.2})"));
                }
            }
        }
        eprintln!("{m}: largest |t| {worst:.2} (critical {crit:.2})");
    }
    assert!(
        failures.is_empty(),
        "disagreements:\n{}",
        failures.join("\n")
    );
}

#[test]
fn every_pair_agrees_with_the_reference_on_cornell() {
    let scene = small("cornell", 24, 24, 20_000);
    agreement(&scene, 3, 20, 2, 6, &PAIRS, &GuideParams::default());
}

#[test]
fn every_pair_agrees_with_the_reference_on_door() {
    let scene = small("door", 24, 24, 40_000);
    agreement(&scene, 2, 20, 4, 8, &PAIRS, &GuideParams::default());
}

/// desk: a spot light, glossy surfaces (the Blinn lobes of the desk and the lamp) and a
/// small lampshade; 64 samples per replicate because its light-tracing replicates are
/// heavy-tailed (see `tests/mitsuba.rs`).
#[test]
fn every_pair_agrees_with_the_reference_on_desk() {
    let scene = small("desk", 16, 16, 30_000);
    agreement(&scene, 2, 16, 16, 8, &PAIRS, &GuideParams::default());
}

/// The slit room (`scenes/slit`): a closed room lit only through a narrow slit from a bright
/// room behind it, the light reaching the camera's room after bouncing in the lit one; 16
/// samples per replicate, as its replicates are heavy-tailed as desk's are.
#[test]
fn every_pair_agrees_with_the_reference_in_the_slit_room() {
    let mut scene = load_scene(&common::scenes_dir().join("slit/scene.xml")).unwrap();
    scene.camera = scene.camera.with_resolution(16, 12).unwrap();
    scene.maps.photons = 30_000;
    scene.maps.importons = 30_000;
    agreement(&scene, 2, 16, 16, 10, &PAIRS, &GuideParams::default());
}

/// Maps that refine each other (two rounds: the second round's light pass guided by the
/// first importance map, its view pass by the first photon map) with guided MIS weights:
/// every guided pair still agrees with unguided path tracing, on cornell and door.
#[test]
fn guided_passes_agree_with_the_reference() {
    let mut cornell = small("cornell", 24, 24, 20_000);
    cornell.maps.rounds = 2;
    let guided = [
        "pt-footprint",
        "lt-footprint",
        "combined-footprint",
        "combined-grid",
    ];
    agreement(&cornell, 3, 20, 2, 6, &guided, &GuideParams::default());
    let mut door = small("door", 24, 24, 40_000);
    door.maps.rounds = 2;
    agreement(&door, 2, 20, 4, 8, &guided, &GuideParams::default());
}

/// The probability of sampling the BSDF learned per region (`learn_p_bsdf`) changes only
/// between passes, so the guided images stay unbiased: pt, lt and combined with learning
/// (camera paths over the photon map's cache, light paths over the importance map's) agree
/// with unguided path tracing on cornell. 64 passes per replicate, so that regions gather
/// the records learning waits for (checked: the runs report learned regions).
#[test]
fn learned_selection_agrees_with_the_reference_on_cornell() {
    let scene = small("cornell", 32, 32, 20_000);
    // The default parameters learn `p_BSDF` per region.
    let params = GuideParams::default();
    assert!(params.learn_p_bsdf);
    for m in ["pt-footprint", "lt-footprint"] {
        let probe = render(
            &scene,
            &RenderOptions {
                guide_params: params.clone(),
                ..opts(m, 64, 6, 1)
            },
            |_| {},
        );
        let learned = learned_regions(&probe);
        eprintln!("{m}: learned regions at 64 spp: {learned}");
        assert!(
            learned > 0,
            "{m}: nothing was learned: the test would not test it"
        );
    }
    agreement(
        &scene,
        2,
        12,
        64,
        6,
        &["pt-footprint", "lt-footprint", "combined-footprint"],
        &params,
    );
}

/// Russian roulette with and without the guide cache's estimate (`guided_rr`; the tests
/// above run the default): the rule really acts (the same seed gives another image with it
/// switched off), and the guided pairs agree with unguided path tracing under the
/// non-default rule too, on cornell and door.
#[test]
fn guided_russian_roulette_acts_and_either_rule_agrees() {
    let scene = small("cornell", 24, 24, 20_000);
    let image = |guided_rr: bool| {
        let o = RenderOptions {
            guide_params: GuideParams {
                guided_rr,
                ..Default::default()
            },
            ..opts("pt-footprint", 4, 6, 3)
        };
        render(&scene, &o, |_| {}).image
    };
    let (on, off) = (image(true), image(false));
    let changed = on
        .pixels
        .iter()
        .zip(&off.pixels)
        .filter(|(a, b)| a != b)
        .count();
    eprintln!("{changed} of {} pixels differ", on.pixels.len());
    assert!(
        changed * 2 > on.pixels.len(),
        "guided Russian roulette changed only {changed} pixels"
    );
    let guided = ["pt-footprint", "lt-footprint", "combined-footprint"];
    // The default rule is what the tests above run; here the other one.
    let params = GuideParams {
        guided_rr: !GuideParams::default().guided_rr,
        ..Default::default()
    };
    agreement(&scene, 3, 20, 2, 6, &guided, &params);
    agreement(
        &small("door", 24, 24, 40_000),
        2,
        20,
        4,
        8,
        &guided,
        &params,
    );
}

/// Guided splitting (`guided_split`; the tests above run the default, 4 branches at most):
/// it really acts (the same seed gives another image, and more vertices, than without it),
/// and the guided pairs that split agree with unguided path tracing without it too, on
/// cornell and door.
#[test]
fn guided_splitting_acts_and_either_setting_agrees() {
    let scene = small("cornell", 24, 24, 20_000);
    let split = |n: u32| GuideParams {
        guided_split: n,
        ..Default::default()
    };
    let default = GuideParams::default().guided_split;
    assert!(
        default > 1,
        "the default splits: the test below compares it with 1"
    );
    let image = |n: u32| {
        let o = RenderOptions {
            guide_params: split(n),
            ..opts("pt-footprint", 4, 6, 3)
        };
        render(&scene, &o, |_| {})
    };
    let (on, off) = (image(default), image(1));
    let changed = on
        .image
        .pixels
        .iter()
        .zip(&off.image.pixels)
        .filter(|(a, b)| a != b)
        .count();
    let (v_on, v_off) = (on.camera_guide.vertices, off.camera_guide.vertices);
    eprintln!(
        "{changed} of {} pixels differ; vertices {v_off} without splitting, {v_on} with",
        on.image.pixels.len()
    );
    assert!(
        changed * 4 > on.image.pixels.len(),
        "splitting changed only {changed} pixels"
    );
    assert!(v_on > v_off, "splitting traced no more vertices");
    let guided = ["pt-footprint", "lt-footprint"];
    agreement(&scene, 3, 20, 2, 6, &guided, &split(1));
    agreement(
        &small("door", 24, 24, 40_000),
        2,
        20,
        4,
        8,
        &guided,
        &split(1),
    );
}

/// The paper's per-event preparation (no guide cache) stays correct.
#[test]
fn per_event_guiding_agrees_with_the_reference_on_cornell() {
    let scene = small("cornell", 16, 16, 20_000);
    let methods = ["pt-footprint", "lt-grid", "combined-footprint"];
    agreement(&scene, 2, 16, 2, 6, &methods, &per_event());
}

/// The analytic scene (radiance 1 everywhere): every pair within its error bound (t-test on
/// the image means of independent renders, Šidák over pairs x channels).
#[test]
fn every_pair_finds_radiance_one_in_the_furnace() {
    let scene = small("furnace", 16, 16, 20_000);
    let renders = 20;
    let crit = t_critical(sidak(0.01, PAIRS.len() * 3), (renders - 1) as f64);
    for m in PAIRS {
        let mut means = [Vec::new(), Vec::new(), Vec::new()];
        for r in 0..renders {
            let out = render(&scene, &opts(m, 2, 64, 50 + r as u64), |_| {});
            let image_mean = out.image.mean();
            for c in 0..3 {
                means[c].push(image_mean[c] as f64);
            }
        }
        for (c, channel) in means.iter().enumerate() {
            let (mean, se) = mean_stderr(channel);
            let t = (mean - 1.0).abs() / se.max(1e-9);
            eprintln!("{m} channel {c}: {mean:.4} ± {se:.4}");
            assert!(t <= crit, "{m} channel {c}: {mean} ± {se}, not 1");
        }
    }
}

/// Equal seeds give equal images whatever the thread count, guided pairs included, with the
/// guide cache and without.
#[test]
fn guided_images_do_not_depend_on_the_thread_count() {
    let scene = small("cornell", 20, 16, 10_000);
    // Learning (the default) needs passes before it acts: the cases of 128 passes are
    // checked to have learned.
    for (m, params, spp) in [
        ("combined-footprint", GuideParams::default(), 2),
        // Light paths split (the default): each branch draws its own stream.
        ("lt-footprint", GuideParams::default(), 2),
        ("combined-grid", GuideParams::default(), 2),
        ("combined-footprint", per_event(), 2),
        // 128 passes: guided Russian roulette (the default) ends paths sooner, so regions
        // gather the records learning waits for more slowly (48 passes sufficed without it).
        ("pt-footprint", GuideParams::default(), 128),
        ("lt-footprint", GuideParams::default(), 128),
    ] {
        let o = RenderOptions {
            guide_params: params,
            ..opts(m, spp, 6, 9)
        };
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| render(&scene, &o, |_| {}))
        };
        let (a, b) = (run(1), run(3));
        if spp >= 128 {
            assert!(learned_regions(&a) > 0, "{m}: nothing learned");
        }
        for ((na, ia), (_, ib)) in a.layers.iter().zip(&b.layers) {
            assert!(
                ia.pixels == ib.pixels,
                "{m} layer {na}: depends on the thread count"
            );
        }
    }
}

/// A scene built to be hard: the only light shines through a slit a few pixels wide, a
/// floor lit at grazing angles, a Blinn panel of exponent 10^4, a coloured glass block.
fn hard_scene() -> Scene {
    let d = std::env::temp_dir().join(format!("footprint-hard-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    let mtl = "newmtl white\nKd 0.7 0.7 0.7\nillum 1\nnewmtl light\nKd 0 0 0\nKe 60 55 50\nillum 1\n\
               newmtl shiny\nKd 0.05 0.05 0.05\nKs 0.9 0.9 0.9\nNs 10000\nillum 2\nnewmtl glass\nNi 1.5\nTf 0.9 0.3 0.2\nillum 7\n";
    let mut obj = "mtllib m.mtl\n".to_string();
    let mut n = 1;
    let mut add = |lo: [f32; 3], hi: [f32; 3], m: &str| {
        obj += &common::box_obj(lo, hi, n, m);
        n += 8;
    };
    // Room 4 x 2.5 x 4 of thick walls.
    add([-0.1, -0.1, -0.1], [4.1, 0.0, 4.1], "white"); // floor
    add([-0.1, 2.5, -0.1], [4.1, 2.6, 4.1], "white"); // ceiling
    add([-0.1, 0.0, -0.1], [0.0, 2.5, 4.1], "white");
    add([4.0, 0.0, -0.1], [4.1, 2.5, 4.1], "white");
    add([-0.1, 0.0, 4.0], [4.1, 2.5, 4.1], "white");
    add([-0.1, 0.0, -0.1], [4.1, 2.5, 0.0], "white");
    // A dividing wall at x = 3 with a 2 cm slit, the light behind it, low, so that the floor
    // beyond the slit is lit at grazing angles.
    add([3.0, 0.0, 0.0], [3.05, 2.5, 1.99], "white");
    add([3.0, 0.0, 2.01], [3.05, 2.5, 4.0], "white");
    add([3.5, 0.05, 1.8], [3.52, 0.45, 2.2], "light");
    // A mirror-like glossy panel and a coloured glass block in the lit room.
    add([1.0, 0.0, 3.0], [2.0, 1.0, 3.05], "shiny");
    add([1.2, 0.0, 1.0], [1.6, 0.6, 1.4], "glass");
    std::fs::write(d.join("m.mtl"), mtl).unwrap();
    std::fs::write(d.join("h.obj"), obj).unwrap();
    std::fs::write(
        d.join("h.toml"),
        "[camera]\nposition = [0.3, 1.5, 0.3]\nlook_at = [3.0, 0.3, 2.0]\nfov_y = 60.0\nresolution = [48, 48]\n[[mesh]]\nfile = \"h.obj\"\n",
    )
    .unwrap();
    let mut s = load_scene(&d.join("h.toml")).unwrap();
    s.maps.photons = 30_000;
    s.maps.importons = 30_000;
    s
}

/// Hard cases stay numerically stable: no NaN, infinite or negative pixel and no rejected
/// sample for any pair on door, desk and the hard scene; the largest single-sample
/// contribution is reported (and must be finite).
#[test]
fn hard_cases_stay_stable() {
    let scenes = [
        ("door", small("door", 32, 32, 30_000)),
        ("desk", small("desk", 32, 32, 30_000)),
        ("hard", hard_scene()),
    ];
    for (name, scene) in &scenes {
        for m in PAIRS {
            let out = render(scene, &opts(m, 2, 10, 3), |_| {});
            for (layer, img) in &out.layers {
                assert!(img.all_valid(), "{name} {m} {layer}: invalid pixel");
            }
            assert_eq!(out.stats.rejected, 0, "{name} {m}: rejected samples");
            assert!(out.stats.max_luminance.is_finite());
            eprintln!(
                "{name} {m}: mean {:.5}, largest single-sample contribution {:.3}, fallbacks {}/{} + {}/{}",
                out.image.mean().y,
                out.stats.max_luminance,
                out.camera_guide.fallbacks,
                out.camera_guide.prepared,
                out.light_guide.fallbacks,
                out.light_guide.prepared
            );
        }
    }
}

/// Light tracing, guided and not, loses no light where it could: on `scenes/ltcheck` (shading
/// normals on a coarse sphere, a two-sided rough conductor seen from its back with tilted
/// normals, a glass sphere, a one-sided rectangle light; none of the other bundled scenes has
/// them all) `lt-bsdf` and `lt-footprint` agree with path tracing per
/// 4x4 block and channel, leaving out the blocks where the camera sees the glass directly
/// (light tracing cannot connect through a smooth surface to the camera). Welch's t on 16
/// independent renders each against Student's quantile at 0.01, Šidák over every method,
/// block and channel.
#[test]
fn light_tracing_agrees_with_path_tracing_on_the_lt_check_scene() {
    use footprint::scene::mitsuba::{self, ImportOptions};
    let xml = common::scenes_dir().join("ltcheck/scene.xml");
    let mut scene = mitsuba::load(&xml, &ImportOptions::default()).unwrap();
    scene.maps.photons = 30_000;
    scene.maps.importons = 30_000;
    let cam = scene.camera.clone();
    let block = 4u32;
    let (bw, bh) = (cam.width / block, cam.height / block);
    // Blocks where some pixel sees the glass directly (corners and centre of each pixel).
    let glass = |x: u32, y: u32| {
        [
            (0.01, 0.01),
            (0.99, 0.01),
            (0.01, 0.99),
            (0.99, 0.99),
            (0.5, 0.5),
        ]
        .iter()
        .any(|(u, v)| {
            let r = glam::Vec2::new(x as f32 + u, y as f32 + v);
            scene
                .intersect(cam.position, cam.ray_dir(r), f32::INFINITY)
                .is_some_and(|h| scene.bsdf(&h).is_delta())
        })
    };
    let keep: Vec<bool> = (0..bh)
        .flat_map(|by| (0..bw).map(move |bx| (bx, by)))
        .map(|(bx, by)| {
            !(by * block..(by + 1) * block)
                .any(|y| (bx * block..(bx + 1) * block).any(|x| glass(x, y)))
        })
        .collect();
    let kept = keep.iter().filter(|k| **k).count();
    assert!(kept * 2 > keep.len(), "most blocks see no glass");
    let renders = 16;
    let replicate = |m: &str, params: GuideParams, spp: u32, seed: u64| -> Vec<Vec<[f64; 3]>> {
        (0..renders)
            .map(|r| {
                let o = RenderOptions {
                    guide_params: params.clone(),
                    ..opts(m, spp, 8, seed + r as u64)
                };
                let out = render(&scene, &o, |_| {});
                assert!(out.image.all_valid(), "{m}: invalid pixel");
                common::region_means(&out.image, bw)
            })
            .collect()
    };
    let reference = replicate("pt-bsdf", GuideParams::default(), 64, 9000);
    let methods = [
        ("lt-bsdf", GuideParams::default()),
        ("lt-footprint", GuideParams::default()),
    ];
    let crit = t_critical(sidak(0.01, methods.len() * kept * 3), (renders - 1) as f64);
    let stat = |reps: &Vec<Vec<[f64; 3]>>, i: usize, c: usize| {
        mean_stderr(&reps.iter().map(|r| r[i][c]).collect::<Vec<_>>())
    };
    for (m, params) in methods {
        let cached = params.cache;
        let reps = replicate(m, params, 64, 100);
        let mut worst = 0.0f64;
        for (i, _) in keep.iter().enumerate().filter(|(_, k)| **k) {
            for c in 0..3 {
                let (ma, sa) = stat(&reps, i, c);
                let (mb, sb) = stat(&reference, i, c);
                let t = (ma - mb).abs() / (sa * sa + sb * sb).sqrt().max(1e-30);
                worst = worst.max(t);
                assert!(
                    t <= crit,
                    "{m} (cache {cached}) block {i} channel {c}: {ma:.5} ± {sa:.5} vs path tracing {mb:.5} ± {sb:.5}"
                );
            }
        }
        eprintln!(
            "{m} (cache {cached}): largest |t| {worst:.2} over {kept} blocks (critical {crit:.2})"
        );
    }
}

/// A guide's particles arrived by `min_depth` segments or more, so a camera path's last
/// scattering vertex (depth `max_depth - 1`, whose next vertex counts only a light it hits)
/// gains nothing from the photon map without its direct light (`min_depth` 2): it samples
/// its BSDF alone and looks up no region (`walk::Start::max_segments`). At `max_depth` 2 no
/// camera vertex is prepared; one segment more, or the map with its depth-1 photons
/// (`min_depth` 1), and vertices are.
#[test]
fn guiding_stops_where_no_particle_could_lead_to_a_counted_path() {
    let scene = small("cornell", 16, 16, 20_000);
    let prepared = |max_depth: u32, min_depth: u16| {
        let o = RenderOptions {
            guide_params: GuideParams {
                min_depth,
                ..Default::default()
            },
            ..opts("pt-footprint", 2, max_depth, 1)
        };
        render(&scene, &o, |_| {}).camera_guide.prepared
    };
    assert_eq!(prepared(2, 2), 0, "the last scattering vertex was prepared");
    assert!(
        prepared(3, 2) > 0,
        "the first vertex of depth-3 paths was not prepared"
    );
    assert!(
        prepared(2, 1) > 0,
        "depth-1 photons did not guide the last vertex"
    );
}
