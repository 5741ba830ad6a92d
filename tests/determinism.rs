//! Reproducibility through the command line: a fixed seed gives the same EXR, every layer bit
//! for bit, on 1, 2 and 4 threads (`--threads`), guided methods and `auto` included, on each
//! ray tracer this machine has; and what a render's EXR header records renders it again, bit
//! for bit: the method `auto` chose, the seed and the passes it drew (a time budget's
//! passes, and the photon paths of a photon map grown with the budget, included).
//!
//! `auto`'s choice is not part of the promise: the pilot predicts each candidate's error at
//! equal time from pass times it measures, so two runs may choose differently. Given its
//! choice, an `auto` render is the chosen method's render: the header names it.
//!
//! The library's own thread-count tests are in `tests/scenes.rs` (unguided, filtered) and
//! `tests/guided.rs` (guided, cached and per event, learned `p_BSDF`).

mod common;

use footprint::film::image_io::{ExrLayers, read_exr_layers};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh output folder for a test.
fn workdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("footprint-det-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `footprint render SCENE ARGS -o OUT` and returns the EXR's layers and header.
fn render(scene: &str, out: &Path, args: &[&str]) -> ExrLayers {
    let scene = common::scene_path(scene);
    let o = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .arg("render")
        .arg(&scene)
        .args(args)
        .arg("-o")
        .arg(out)
        .output()
        .expect("the binary runs");
    assert!(
        o.status.success(),
        "footprint render {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&o.stderr)
    );
    read_exr_layers(out).unwrap()
}

/// The header attribute `name`.
fn attr<'a>(e: &'a ExrLayers, name: &str) -> &'a str {
    e.attributes
        .iter()
        .find(|(k, _)| k == name)
        .map(|(_, v)| v.as_str())
        .unwrap_or_else(|| panic!("no {name} in the header"))
}

/// Every layer of `a` equals `b`'s bit for bit, and they are not black.
fn assert_identical(a: &ExrLayers, b: &ExrLayers, what: &str) {
    let names = |e: &ExrLayers| e.layers.iter().map(|l| l.0.clone()).collect::<Vec<_>>();
    assert_eq!(names(a), names(b), "{what}: layers");
    for ((name, x), (_, y)) in a.layers.iter().zip(&b.layers) {
        assert!(x.mean().max_element() > 0.0, "{what}: {name} is black");
        let differ = x
            .pixels
            .iter()
            .zip(&y.pixels)
            .filter(|(p, q)| p.to_array().map(f32::to_bits) != q.to_array().map(f32::to_bits))
            .count();
        assert_eq!(differ, 0, "{what}: {differ} pixels of {name} differ");
    }
}

/// Small, quick maps and image for every render of these tests.
const SMALL: [&str; 6] = [
    "--resolution",
    "24x20",
    "--photons",
    "10000",
    "--importons",
    "10000",
];

/// The flags of a small render of `method` (`integrator-guide`): 3 passes of depth 6 with
/// `seed` on `threads` threads.
fn small_run<'a>(method: &'a str, seed: &'a str, threads: &'a str) -> Vec<&'a str> {
    let (integrator, guide) = method.split_once('-').unwrap();
    let mut args = vec![
        "--integrator",
        integrator,
        "--guide",
        guide,
        "--spp",
        "3",
        "--seed",
        seed,
        "--threads",
        threads,
        "--max-depth",
        "6",
    ];
    args.extend(SMALL);
    args
}

/// The acceleration structures to run: the CWBVH, and Embree where the system has it (else
/// a visible skip).
fn accels(test: &str) -> Vec<&'static str> {
    let mut a = vec!["cwbvh"];
    if footprint::scene::embree::available().is_ok() {
        a.push("embree");
    } else {
        common::skip(test, "Embree (libembree3) is not installed: the CWBVH only");
    }
    a
}

#[test]
fn a_seed_gives_the_same_exr_on_1_2_and_4_threads() {
    let d = workdir("threads");
    for accel in accels("a_seed_gives_the_same_exr_on_1_2_and_4_threads") {
        for method in [
            "combined-footprint",
            "pt-footprint",
            "lt-grid",
            "auto-footprint",
        ] {
            let run = |threads: &str| {
                let mut args = small_run(method, "11", threads);
                args.extend(["--accel", accel]);
                let out = d.join(format!("{method}-{accel}-{threads}.exr"));
                render("cornell", &out, &args)
            };
            let one = run("1");
            for threads in ["2", "4"] {
                let other = run(threads);
                if method.starts_with("auto") {
                    // The choice may differ (it weighs measured pass times); given it, the
                    // image may not.
                    if attr(&one, "footprint/method") != attr(&other, "footprint/method") {
                        eprintln!(
                            "{method} on {threads} threads chose {}, on 1 thread {}",
                            attr(&other, "footprint/method"),
                            attr(&one, "footprint/method")
                        );
                        continue;
                    }
                }
                assert_identical(
                    &one,
                    &other,
                    &format!("{method} {accel} 1 vs {threads} threads"),
                );
            }
        }
    }
}

/// Renders again from what the header of `first` records (the method, seed, passes, depth,
/// the pass settings and the photon paths shot), with `fixed` (flags that are not settings:
/// resolution, threads) and returns the new render.
fn again(first: &ExrLayers, scene: &str, out: &Path, fixed: &[&str]) -> ExrLayers {
    let method = attr(first, "footprint/method").to_string();
    let (integrator, guide) = method.split_once('-').unwrap();
    let mut args: Vec<String> = [
        "--integrator",
        integrator,
        "--guide",
        guide,
        "--spp",
        attr(first, "footprint/spp"),
        "--seed",
        attr(first, "footprint/seed"),
        "--max-depth",
        attr(first, "footprint/max_depth"),
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.extend(fixed.iter().map(|s| s.to_string()));
    let args: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
    render(scene, out, &args)
}

#[test]
fn auto_is_rendered_again_from_its_header() {
    let d = workdir("auto");
    for (request, threads) in [("auto-footprint", "1"), ("auto-auto", "2")] {
        let args = small_run(request, "4", threads);
        let first = render("cornell", &d.join(format!("{request}.exr")), &args);
        let mut fixed = vec!["--threads", "2"];
        fixed.extend(SMALL);
        let second = again(
            &first,
            "cornell",
            &d.join(format!("{request}-again.exr")),
            &fixed,
        );
        assert_identical(&first, &second, &format!("{request} rendered again"));
    }
}

/// A render with a time budget draws as many passes as fit, and a sparse photon map grows
/// with the budget: the header's passes and grown photon paths render it again without one.
#[test]
fn a_time_budget_render_is_rendered_again_from_its_header() {
    let d = workdir("time");
    let args = [
        "--integrator",
        "pt",
        "--guide",
        "footprint",
        "--time",
        "2",
        "--seed",
        "8",
        "--max-depth",
        "6",
        "--resolution",
        "24x20",
        "--photons",
        "1000",
        "--importons",
        "10000",
    ];
    let first = render("door", &d.join("first.exr"), &args);
    let grown = attr(&first, "footprint/photons_grown");
    eprintln!(
        "passes {}, photons grown to {grown}",
        attr(&first, "footprint/spp")
    );
    assert_ne!(
        grown, "1000",
        "the photon map did not grow: the test would not test it"
    );
    let fixed = [
        "--resolution",
        "24x20",
        "--photons",
        grown,
        "--importons",
        "10000",
        "--map-grow",
        "off",
    ];
    let second = again(&first, "door", &d.join("again.exr"), &fixed);
    assert_identical(&first, &second, "a time budget's render rendered again");
}
