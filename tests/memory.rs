//! The memory budget of the particle maps and guide caches (`[maps] max_memory`,
//! `--max-memory`; `integrators/src/passes/thinning.rs`): a guided render whose passes draw
//! far more particles than the budget holds stays within it (the heap's peak, measured by
//! the counting allocator), thins its passes the same way on any thread count, and says
//! so on its terminal and in its EXR header.
//!
//! The heap is counted for the whole test process, so the tests that measure it take a
//! lock and no other test of this file allocates while they run.

mod common;

use footprint::scene::Scene;
use footprint_integrators::passes::thinning::max_particles;
use footprint_integrators::passes::{PassSettings, light_pass};
use footprint_integrators::{Method, RenderOptions};
use std::process::Command;
use std::sync::Mutex;

#[global_allocator]
static HEAP: footprint::heap::CountingAlloc = footprint::heap::CountingAlloc;

/// Held by every test of this file: the heap's peak is the process's.
static ALONE: Mutex<()> = Mutex::new(());

fn door(photons: usize) -> Scene {
    let mut s = footprint::scene::load::load_scene(&common::scene_path("door")).unwrap();
    s.camera = s.camera.with_resolution(32, 32).unwrap();
    s.maps.photons = photons;
    s.maps.importons = photons;
    s
}

/// The peak heap bytes above the start while building the maps and caches of
/// `combined-footprint` (both passes, both maps, both caches: the most a render holds) on
/// door with `photons` paths per pass and `max_memory`; and the particles each pass kept,
/// with its thinning level.
fn build_peak(photons: usize, max_memory: Option<u64>) -> (usize, Vec<(usize, u32)>) {
    let mut scene = door(photons);
    scene.maps.max_memory = max_memory;
    let opts = RenderOptions {
        method: Method::parse("combined-footprint").unwrap(),
        seed: 3,
        ..Default::default()
    };
    let start = footprint::heap::heap_bytes();
    footprint::heap::reset_peak();
    let g = footprint_integrators::render::guidance(&scene, &opts, &|| None);
    let peak = footprint::heap::heap_peak() - start;
    let kept = [&g.photons, &g.importons]
        .into_iter()
        .map(|m| {
            let p = &m.as_ref().expect("both maps").pass;
            (p.particles.len(), p.stats.thinning)
        })
        .collect();
    (peak, kept)
}

/// Door's passes of 300,000 paths each draw about 2.4 million particles each (about 800 MB
/// at the peak of the build without a budget). With a budget of 64 MB the peak stays under
/// it and each pass keeps at most its share; without the thinning (the default budget,
/// half the machine's memory) the same build takes more than six times the 64 MB, so the
/// first check fails when the protection is removed.
#[test]
fn a_guided_build_stays_within_its_memory_budget() {
    let _alone = ALONE.lock().unwrap();
    let budget: u64 = 64 << 20;
    let (peak, kept) = build_peak(300_000, Some(budget));
    eprintln!(
        "peak {:.1} MB within 64 MiB, kept {kept:?}",
        peak as f64 / 1e6
    );
    assert!(
        peak as u64 <= budget,
        "peak {:.1} MB over the {:.0} MB budget",
        peak as f64 / 1e6,
        budget as f64 / 1e6
    );
    for (n, level) in kept {
        assert!(level > 0, "not thinned");
        assert!(n <= max_particles(budget), "{n} particles kept");
    }
    let (unbounded, kept) = build_peak(300_000, None);
    eprintln!(
        "peak {:.1} MB without a budget, kept {kept:?}",
        unbounded as f64 / 1e6
    );
    assert!(kept.iter().all(|(_, level)| *level == 0));
    assert!(
        unbounded as u64 > 6 * budget,
        "without the budget the build peaked at only {:.1} MB",
        unbounded as f64 / 1e6
    );
}

/// A thinned pass keeps the same particles with the same weights, bit for bit, on one
/// thread and on eight (that they do not depend on the batches between the budget checks
/// either is the unit test `the_particles_kept_do_not_depend_on_the_batches`).
#[test]
fn a_thinned_pass_is_the_same_on_any_thread_count() {
    let _alone = ALONE.lock().unwrap();
    let scene = door(100_000);
    let s = PassSettings {
        paths: 100_000,
        max_depth: 8,
        rr_depth: footprint::settings::DEFAULT_RR_DEPTH,
        seed: 9,
        soft_glossy_max: scene.maps.soft_glossy_max,
        specialise: true,
        target: None,
        max_particles: 100_000,
    };
    let bsdf = footprint::guide::sampler::GuidedSampler::bsdf();
    let pass = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| light_pass(&scene, &s, &bsdf))
    };
    let (one, eight) = (pass(1), pass(8));
    assert!(one.stats.thinning > 0, "not thinned");
    assert!(one.particles.len() <= s.max_particles);
    assert_eq!(one.stats.thinning, eight.stats.thinning);
    assert_eq!(one.particles.len(), eight.particles.len());
    let bits = |p: &footprint::guide::particle_map::ParticleInput| {
        let (a, b) = (p.position.to_array(), p.weight.to_array());
        [a[0], a[1], a[2], b[0], b[1], b[2]].map(f32::to_bits)
    };
    assert!(
        one.particles
            .iter()
            .zip(&eight.particles)
            .all(|(a, b)| bits(a) == bits(b))
    );
    assert_eq!(one.emission_points.len(), eight.emission_points.len());
}

/// `footprint render` with a budget its passes exceed warns on standard error and records
/// the thinning in its EXR header; a bad budget is an error naming the flag.
#[test]
fn a_render_says_when_it_thinned_its_maps() {
    let _alone = ALONE.lock().unwrap();
    let dir = std::env::temp_dir().join(format!("footprint-memory-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("door.exr");
    let run = |budget: &str| {
        Command::new(env!("CARGO_BIN_EXE_footprint"))
            .arg("render")
            .arg(common::scene_path("door"))
            .args(["--integrator", "pt", "--guide", "footprint", "--spp", "1"])
            .args(["--resolution", "32x32", "--photons", "100000"])
            .args(["--max-memory", budget, "-o"])
            .arg(&out)
            .output()
            .expect("the binary runs")
    };
    let o = run("20M");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: light pass thinned to keep the maps within max_memory 20M"),
        "{stderr}"
    );
    let exr = footprint::film::image_io::read_exr_layers(&out).unwrap();
    let thinned = exr
        .attributes
        .iter()
        .find(|(k, _)| k == "footprint/maps_thinned")
        .map(|(_, v)| v.clone())
        .expect("footprint/maps_thinned in the header");
    assert!(thinned.contains("light pass"), "{thinned}");
    let o = run("8G");
    assert!(o.status.success());
    assert!(!String::from_utf8_lossy(&o.stderr).contains("thinned"));
    let o = run("lots");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(stderr.contains("--max-memory"), "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}
