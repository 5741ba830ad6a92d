//! How maps are built: a grown pass, sparse maps grown within a budget, and a second guide
//! built from the first guide's particles.

use crate::common::scene_path;
use crate::pass_settings;
use footprint::guide::sampler::GuidedSampler;
use footprint::scene::load::load_scene;
use footprint_integrators::passes::light_pass;

/// A light pass grown from N to 2N paths (`grow_light_pass`: the first N kept with their
/// weights rescaled, the next N traced) is the pass of 2N paths: the same particles in the
/// same order, weights equal to f32 rounding, the same escaped flux.
#[test]
fn a_grown_pass_is_the_pass_of_all_its_paths() {
    use footprint_integrators::passes::grow_light_pass;
    let scene = load_scene(&scene_path("cornell")).unwrap();
    let bsdf = GuidedSampler::bsdf();
    {
        let run = |n: usize| light_pass(&scene, &pass_settings(n, 5), &bsdf);
        // An odd count: the chunks of the grown part start mid-chunk of the whole.
        let half = run(3001);
        let grown = grow_light_pass(&scene, &pass_settings(6002, 5), &bsdf, half);
        let whole = run(6002);
        assert_eq!(grown.stats.paths, 6002);
        assert_eq!(grown.particles.len(), whole.particles.len());
        assert_eq!(grown.emission_points.len(), whole.emission_points.len());
        for (a, b) in grown.particles.iter().zip(&whole.particles) {
            assert_eq!((a.position, a.dir, a.depth), (b.position, b.dir, b.depth));
            assert!(
                (a.weight - b.weight).abs().max_element() <= 1e-6 * b.weight.max_element(),
                "{} vs {}",
                a.weight,
                b.weight
            );
        }
        assert_eq!(grown.stats.escaped.len(), whole.stats.escaped.len());
        for (a, b) in grown.stats.escaped.iter().zip(&whole.stats.escaped) {
            assert!((*a - *b).abs().max_element() <= 1e-5 * b.max_element().max(1e-12));
        }
    }
}

/// With a time budget, a sparse photon map grows and says why; a dense one, or no budget,
/// or `maps.grow = false`, does not, and the importance map never does. door with 20,000
/// photons is sparse (light reaches the camera's room only through the door gap); the
/// budget is generous so that time never stops the growth here.
#[test]
fn sparse_photon_maps_grow_within_a_budget() {
    use footprint_integrators::maps::{Guidance, sparse};
    use std::time::Duration;
    let mut door = load_scene(&scene_path("door")).unwrap();
    door.maps.photons = 20_000;
    door.maps.importons = 20_000;
    let method = footprint_integrators::Method::parse("pt-footprint").unwrap();
    let params = footprint::settings::GuideParams::default();
    let pass = pass_settings(0, 3);
    let budget = Some(Duration::from_secs(10_000));
    let plain = Guidance::build_within(&door, &method, &params, &pass, None, &|| None);
    let cache = plain.photon_cache.as_ref().unwrap();
    assert!(
        sparse(&cache.stats, &params).is_some(),
        "door at 20k photons should be sparse"
    );
    assert_eq!(plain.grown, None);
    let grown = Guidance::build_within(&door, &method, &params, &pass, budget, &|| None);
    eprintln!("{:?}", grown.summaries);
    let paths = grown.photons.as_ref().unwrap().pass.stats.paths;
    assert_eq!(grown.grown, Some((20_000, paths)), "the growth is reported");
    // Neither the generous budget nor the path limit stops it: every doubling is taken.
    assert_eq!(paths, 20_000 << footprint_integrators::maps::MAX_GROWTHS);
    // Most of the grown map's photons land in the lit room, where few regions are: the map
    // holds a share of them (`passes::thinning`, "Thinning by region").
    let (kept, all, _) = grown
        .photons
        .as_ref()
        .unwrap()
        .thinned
        .expect("thinned by region");
    assert!(2 * kept <= all, "{kept} of {all} kept");
    let after = grown.photon_cache.as_ref().unwrap();
    assert!(
        after.stats.guiding > cache.stats.guiding,
        "more regions guide after growing ({} -> {})",
        cache.stats.guiding,
        after.stats.guiding
    );
    // The importance map keeps its count, also where the photon map grows beside it.
    let both = footprint_integrators::Method::parse("combined-footprint").unwrap();
    let g = Guidance::build_within(&door, &both, &params, &pass, budget, &|| None);
    assert!(g.photons.as_ref().unwrap().pass.stats.paths > 20_000);
    assert_eq!(g.importons.as_ref().unwrap().pass.stats.paths, 20_000);
    // Only the photon side is built again: the importance cache is the one built without a
    // budget (its seeds are the first light pass's points), and the first photon map's
    // summary lines give way to the grown one's.
    let plain_both = Guidance::build_within(&door, &both, &params, &pass, None, &|| None);
    let regions = |g: &Guidance| g.importon_cache.as_ref().unwrap().stats.regions;
    assert_eq!(regions(&g), regions(&plain_both));
    let photon_lines = |g: &Guidance| {
        let n = g.summaries.iter().filter(|s| s.starts_with("photon map:"));
        n.count()
    };
    assert_eq!(photon_lines(&g), 1, "{:?}", g.summaries);
    // auto's winner grows the pilot's maps (built for the combined image) with the time
    // left, for the method it chose.
    let chosen = footprint_integrators::RenderOptions {
        method,
        time: Some(10_000.0),
        ..Default::default()
    };
    // A light tracer that wins keeps the pilot's photon map as it is: it never reads it.
    let lt = footprint_integrators::RenderOptions {
        method: footprint_integrators::Method::parse("lt-footprint").unwrap(),
        time: Some(10_000.0),
        ..Default::default()
    };
    let piloted = Guidance::build_within(&door, &both, &params, &pass, None, &|| None);
    let kept =
        footprint_integrators::auto::chosen_guidance(&door, &lt, piloted, Some(10_000.0), &|| None);
    assert_eq!(kept.photons.as_ref().unwrap().pass.stats.paths, 20_000);
    assert_eq!(kept.grown, None);
    let left = Some(10_000.0);
    let g =
        footprint_integrators::auto::chosen_guidance(&door, &chosen, plain_both, left, &|| None);
    assert_eq!(
        g.photons.as_ref().unwrap().pass.stats.paths,
        20_000 << footprint_integrators::maps::MAX_GROWTHS
    );
    assert_eq!(g.grown.map(|(from, _)| from), Some(20_000));
    // Switched off in the scene.
    let mut off = door;
    off.maps.grow = false;
    let opts = footprint_integrators::RenderOptions {
        method,
        time: Some(10_000.0),
        ..Default::default()
    };
    let g = footprint_integrators::render::guidance(&off, &opts, &|| None);
    assert_eq!(g.photons.as_ref().unwrap().pass.stats.paths, 20_000);
    // A dense map keeps its count: desk at its 200,000 photons (99% of its regions guide,
    // their particles fill 72% of region_particles).
    let desk = load_scene(&scene_path("desk")).unwrap();
    let g = Guidance::build_within(&desk, &method, &params, &pass, budget, &|| None);
    let c = g.photon_cache.as_ref().unwrap();
    assert_eq!(
        sparse(&c.stats, &params),
        None,
        "desk: {}",
        c.stats.summary()
    );
    assert_eq!(g.grown, None);
    assert_eq!(
        g.photons.as_ref().unwrap().pass.stats.paths,
        desk.maps.photons
    );
}

/// A second guide builds its maps from the first's particles (`auto` pilots every guide on
/// one pair of passes): `Guidance::passes` hands back the very passes the first guide's
/// maps were built from, so the grid's maps and caches built from them equal those built
/// from the passes themselves.
#[test]
fn a_second_guide_builds_from_the_first_guides_particles() {
    use footprint_integrators::maps::{Guidance, run_passes};
    let mut door = load_scene(&scene_path("door")).unwrap();
    door.maps.photons = 20_000;
    door.maps.importons = 20_000;
    let params = footprint::settings::GuideParams::default();
    let pass = pass_settings(0, 5);
    let footprint = footprint_integrators::Method::parse("combined-footprint").unwrap();
    let grid = footprint_integrators::Method::parse("combined-grid").unwrap();
    let passes = run_passes(&door, &footprint, &params, &pass);
    let first = Guidance::from_passes(&door, &footprint, &params, passes.clone(), &|| None);
    let handed = first.passes();
    assert_eq!(handed.light_time, passes.light_time);
    assert_eq!(handed.view_time, passes.view_time);
    let direct = Guidance::from_passes(&door, &grid, &params, passes, &|| None);
    let second = Guidance::from_passes(&door, &grid, &params, handed, &|| None);
    for (a, b) in [
        (&direct.photons, &second.photons),
        (&direct.importons, &second.importons),
    ] {
        let (a, b) = (a.as_ref().unwrap(), b.as_ref().unwrap());
        assert!(a.map.len() > 1000, "{} particles", a.map.len());
        assert_eq!(a.map.len(), b.map.len());
        assert_eq!(a.pass.particles.len(), b.pass.particles.len());
        for (p, q) in a.pass.particles.iter().zip(&b.pass.particles) {
            assert_eq!((p.position, p.dir, p.weight), (q.position, q.dir, q.weight));
        }
    }
    for (a, b) in [
        (&direct.photon_cache, &second.photon_cache),
        (&direct.importon_cache, &second.importon_cache),
    ] {
        let (a, b) = (&a.as_ref().unwrap().stats, &b.as_ref().unwrap().stats);
        assert_eq!(
            (a.seeds, a.regions, a.guiding, a.particles),
            (b.seeds, b.regions, b.guiding, b.particles)
        );
    }
}

/// A sparse photon map grows where most of the light arriving in its cache's regions is
/// indirect, what a guide of `min_depth` particles leads to (`maps::indirect_share`), or where
/// most of its regions cannot guide at all. The slit room's camera room is lit through the
/// slit (60% indirect); the features scene mostly straight from its lights and sky (10%),
/// with 89% of its regions guiding; the meshes scene at 20,000 photons as directly, but with
/// few regions guiding. Where a sparse map does not grow the run summary says why.
#[test]
fn a_sparse_map_grows_where_the_light_arriving_is_mostly_indirect() {
    use footprint_integrators::maps::{
        Growth, Guidance, MAX_GUIDING_TO_WEIGH_LIGHT, MIN_INDIRECT_SHARE, growth, indirect_share,
    };
    use std::time::Duration;
    let method = footprint_integrators::Method::parse("pt-footprint").unwrap();
    let params = footprint::settings::GuideParams::default();
    let pass = pass_settings(0, 3);
    let xml = |name: &str| {
        let path = crate::common::scenes_dir().join(name).join("scene.xml");
        load_scene(&path).unwrap()
    };
    let mut meshes = xml("meshes");
    meshes.maps.photons = 20_000;
    // (scene, mostly indirect, most regions guide)
    for (name, scene, indirect, guiding) in [
        ("slit", xml("slit"), true, true),
        ("features", xml("features"), false, true),
        ("meshes", meshes, false, false),
    ] {
        let plain = Guidance::build_within(&scene, &method, &params, &pass, None, &|| None);
        let cache = plain.photon_cache.as_ref().unwrap();
        let particles = &plain.photons.as_ref().unwrap().pass.particles;
        let share = indirect_share(cache, particles, params.min_depth).unwrap();
        // Every particle arrived in at least one segment, none in more than the walk's depth.
        assert_eq!(indirect_share(cache, particles, 1), Some(1.0), "{name}");
        assert_eq!(
            indirect_share(cache, particles, u16::MAX),
            Some(0.0),
            "{name}"
        );
        assert_eq!(share >= MIN_INDIRECT_SHARE, indirect, "{name}: {share}");
        let guiding_share = cache.stats.guiding as f64 / cache.stats.regions as f64;
        assert_eq!(
            guiding_share >= MAX_GUIDING_TO_WEIGH_LIGHT,
            guiding,
            "{name}"
        );
        match growth(cache, particles, &params) {
            Growth::Grows(why) => {
                assert!(indirect || !guiding, "{name}: {why}");
                assert_eq!(why.contains("indirect"), guiding, "{name}: {why}");
            }
            Growth::MostlyDirect(line) => {
                assert!(!indirect && guiding, "{name}: {line}");
                // With a budget that would fit every doubling, the map keeps its count, and
                // the run summary says why.
                let budget = Some(Duration::from_secs(10_000));
                let g = Guidance::build_within(&scene, &method, &params, &pass, budget, &|| None);
                assert_eq!(g.grown, None, "{name}");
                let paths = g.photons.as_ref().unwrap().pass.stats.paths;
                assert_eq!(paths, scene.maps.photons, "{name}");
                assert!(g.summaries.contains(&line), "{name}: {:?}", g.summaries);
            }
            Growth::Dense => panic!("{name} should be sparse: {}", cache.stats.summary()),
        }
    }
}
