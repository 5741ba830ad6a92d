//! Rendering past one machine, through the command line: four shards merged are the image
//! of one run with the same seed and total samples (every layer, pt, lt and combined, guided
//! and not); `render --maps` with saved maps is the image of a run that built them; corrupt,
//! truncated and mismatched maps files and shards are refused with a message naming the
//! file; a killed shard leaves no image, and rendering only the missing shard completes it.

mod common;

use footprint::film::image_io::{ExrLayers, read_exr_layers};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh folder with a copy of cornell (so that a changed copy is "another scene").
fn workdir(name: &str) -> PathBuf {
    common::cornell_copy(&format!("shards-{name}"))
}

fn footprint(args: &[&str]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args(args)
        .output()
        .expect("the binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "panic: {stderr}");
    out
}

fn ok(args: &[&str]) {
    let out = footprint(args);
    assert!(
        out.status.success(),
        "footprint {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Runs a command that must fail; returns its stderr.
fn fails(args: &[&str]) -> String {
    let out = footprint(args);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(
        !out.status.success(),
        "footprint {} should fail",
        args.join(" ")
    );
    err
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// What the particle passes depend on, the same for every run of a test: small, quick maps.
const PASS_FLAGS: [&str; 10] = [
    "--resolution",
    "16x12",
    "--seed",
    "3",
    "--max-depth",
    "5",
    "--photons",
    "4000",
    "--importons",
    "4000",
];

/// The render flags every image of a test shares.
fn base<'a>(scene: &'a Path, method: &'a str) -> Vec<&'a str> {
    let (integrator, guide) = method.split_once('-').unwrap();
    let mut args = vec![
        "render",
        s(scene),
        "--integrator",
        integrator,
        "--guide",
        guide,
        "--spp",
        "6",
        "--threads",
        "2",
    ];
    args.extend(PASS_FLAGS);
    args
}

/// `footprint maps SCENE --save OUT` with the tests' pass flags (`photons` changed).
fn save_maps(scene: &Path, out: &Path, photons: &str) {
    let mut args = vec!["maps", s(scene), "--save", s(out)];
    args.extend(PASS_FLAGS);
    set(&mut args, "--photons", photons);
    ok(&args);
}

/// Sets `flag`'s value in `args` (replacing the one there, or appended).
fn set<'a>(args: &mut Vec<&'a str>, flag: &'a str, value: &'a str) {
    match args.iter().position(|a| *a == flag) {
        Some(i) => args[i + 1] = value,
        None => args.extend([flag, value]),
    }
}

fn attr<'a>(e: &'a ExrLayers, key: &str) -> &'a str {
    e.attributes
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
        .unwrap_or_else(|| panic!("no {key}"))
}

#[test]
fn four_shards_merged_equal_one_run() {
    let d = workdir("four");
    let scene = d.join("cornell.toml");
    for method in [
        "pt-bsdf",
        "lt-bsdf",
        "combined-bsdf",
        "pt-footprint",
        "lt-footprint",
        "combined-footprint",
    ] {
        let one = d.join(format!("{method}-one.exr"));
        let mut args = base(&scene, method);
        args.extend(["--out", s(&one)]);
        ok(&args);
        // 6 spp in 4 shards: 2, 2, 1 and 1 passes.
        let shards: Vec<PathBuf> = (0..4)
            .map(|i| d.join(format!("{method}-{i}.exr")))
            .collect();
        for (i, out) in shards.iter().enumerate() {
            let shard = format!("{i}/4");
            let mut args = base(&scene, method);
            args.extend(["--shard", &shard, "--out", s(out)]);
            ok(&args);
            let e = read_exr_layers(out).unwrap();
            assert_eq!(attr(&e, "footprint/shard"), shard);
            assert_eq!(attr(&e, "footprint/spp"), if i < 2 { "2" } else { "1" });
            assert_eq!(attr(&e, "footprint/spp_total"), "6");
        }
        let merged = d.join(format!("{method}-merged.exr"));
        let mut args = vec!["merge", s(&merged)];
        // In any order.
        args.extend(shards.iter().rev().map(|p| s(p)));
        ok(&args);
        common::assert_same_exr(&merged, &one, method);
        let m = read_exr_layers(&merged).unwrap();
        assert_eq!(attr(&m, "footprint/spp"), "6");
        assert_eq!(attr(&m, "footprint/shard"), "0/1");
        assert!(d.join(format!("{method}-merged.png")).exists());
    }
}

#[test]
fn saved_maps_give_the_image_of_a_run_that_built_them() {
    let d = workdir("maps");
    let scene = d.join("cornell.toml");
    let maps = d.join("maps.fpm");
    save_maps(&scene, &maps, "4000");
    // Path tracing shoots a quarter of the view pass the file holds and seeds its photon
    // cache with that quarter's importons: the file's count of them gives the same cache.
    for (method, extra) in [
        ("combined-footprint", None),
        ("pt-grid", None),
        ("pt-footprint", None),
        ("lt-footprint", Some("off")),
    ] {
        let built = d.join(format!("{method}-built.exr"));
        let loaded = d.join(format!("{method}-loaded.exr"));
        for (out, with_maps) in [(&built, false), (&loaded, true)] {
            let mut args = base(&scene, method);
            args.extend(["--out", s(out)]);
            if let Some(c) = extra {
                args.extend(["--guide-cache", c]);
            }
            if with_maps {
                args.extend(["--maps", s(&maps)]);
            }
            ok(&args);
        }
        let (a, b) = (
            read_exr_layers(&built).unwrap(),
            read_exr_layers(&loaded).unwrap(),
        );
        for ((n, x), (_, y)) in a.layers.iter().zip(&b.layers) {
            assert_eq!(x.pixels, y.pixels, "{method}: layer {n} differs");
        }
        assert_eq!(attr(&b, "footprint/maps_file"), s(&maps));
    }
    // Shards with loaded maps merge to the run that built its own.
    let shards: Vec<PathBuf> = (0..4).map(|i| d.join(format!("m{i}.exr"))).collect();
    for (i, out) in shards.iter().enumerate() {
        let shard = format!("{i}/4");
        let mut args = base(&scene, "combined-footprint");
        args.extend(["--shard", &shard, "--maps", s(&maps), "--out", s(out)]);
        ok(&args);
    }
    let merged = d.join("m.exr");
    let mut args = vec!["merge", s(&merged)];
    args.extend(shards.iter().map(|p| s(p)));
    ok(&args);
    common::assert_same_exr(
        &merged,
        &d.join("combined-footprint-built.exr"),
        "--maps shards",
    );
}

/// A pass saved thinned and loaded keeps its thinning level and its count of the photon
/// cache's seeds, so that thinning it further on load (a smaller memory budget) gives the
/// pass thinned there from the start: the same particles and weights. Fails if the level is
/// lost (the loaded pass would thin again from level 0 and raise its weights by `2^L` more)
/// or the seed count (path tracing would seed from every importon of a combined pass).
#[test]
fn a_saved_pass_keeps_its_thinning_level_and_seed_count() {
    use footprint::guide::sampler::GuidedSampler;
    use footprint_app::maps_file;
    use footprint_integrators::maps::Passes;
    use footprint_integrators::passes::{PassSettings, view_pass_seeding};
    let d = workdir("thinned");
    let scene = footprint::scene::load::load_scene(&common::scene_path("cornell")).unwrap();
    let settings = |max_particles| PassSettings {
        paths: 4_000,
        max_depth: 5,
        rr_depth: 5,
        seed: 9,
        soft_glossy_max: 100.0,
        specialise: true,
        target: None,
        max_particles,
    };
    let bsdf = GuidedSampler::bsdf();
    let view = |max| view_pass_seeding(&scene, &settings(max), &bsdf, 1_000);
    let whole = view(usize::MAX);
    let saved = view(whole.particles.len() / 3);
    let smaller = whole.particles.len() / 9;
    let there = view(smaller);
    assert!(0 < saved.stats.thinning && saved.stats.thinning < there.stats.thinning);
    let file = d.join("passes.fpm");
    let with = |view| Passes {
        view: Some(view),
        ..Passes::default()
    };
    for pass in [whole.clone(), saved] {
        let level = pass.stats.thinning;
        let seeding = pass.stats.seed_particles;
        maps_file::save(&file, "k", &with(pass)).unwrap();
        let mut loaded = maps_file::load(&file, "k").unwrap().view.unwrap();
        assert_eq!(loaded.stats.thinning, level);
        assert_eq!(loaded.stats.seed_particles, seeding);
        if level == 0 {
            assert!(seeding.is_some_and(|n| n < whole.particles.len()));
            continue;
        }
        loaded.within(smaller);
        assert_eq!(loaded.stats.thinning, there.stats.thinning);
        assert_eq!(loaded.particles.len(), there.particles.len());
        for (p, q) in loaded.particles.iter().zip(&there.particles) {
            assert_eq!((p.position, p.weight), (q.position, q.weight));
        }
    }
}

#[test]
fn bad_maps_files_are_refused_naming_the_file() {
    let d = workdir("badmaps");
    let scene = d.join("cornell.toml");
    let maps = d.join("good.fpm");
    let save = save_maps;
    save(&scene, &maps, "4000");
    let good = std::fs::read(&maps).unwrap();
    let out = d.join("out.exr");
    let render_with = |file: &Path| -> String {
        let mut args = base(&scene, "pt-footprint");
        args.extend(["--maps", s(file), "--out", s(&out)]);
        let err = fails(&args);
        assert!(
            !out.exists(),
            "an image was written with {}",
            file.display()
        );
        assert!(
            err.contains(s(file)),
            "the error should name {}: {err}",
            file.display()
        );
        err
    };
    let write = |name: &str, bytes: &[u8]| {
        let p = d.join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    };
    // Corrupt: one flipped bit in the particles.
    let mut b = good.clone();
    let i = b.len() - 1000;
    b[i] ^= 0x10;
    assert!(render_with(&write("flipped.fpm", &b)).contains("corrupt"));
    // Truncated.
    assert!(render_with(&write("cut.fpm", &good[..good.len() / 2])).contains("truncated"));
    assert!(render_with(&write("cut-header.fpm", &good[..30])).contains("truncated"));
    // Not a maps file at all, and a later format version.
    assert!(render_with(&write("text.fpm", b"hello")).contains("not a footprint maps file"));
    let mut v = good.clone();
    v[8] = 99;
    assert!(render_with(&write("v99.fpm", &v)).contains("format version 99"));
    // Missing.
    assert!(render_with(&d.join("absent.fpm")).contains("cannot read"));
    // Other settings: fewer photons, another seed.
    let few = d.join("few-photons.fpm");
    save(&scene, &few, "2000");
    let err = render_with(&few);
    assert!(
        err.contains("photons=2000") && err.contains("photons=4000"),
        "{err}"
    );
    let mut args = base(&scene, "pt-footprint");
    args.extend(["--maps", s(&maps), "--out", s(&out)]);
    set(&mut args, "--seed", "4");
    let err = fails(&args);
    assert!(err.contains("seed=3") && err.contains(s(&maps)), "{err}");
    // The view pass without the relative importance target the render would give it.
    let mut args = base(&scene, "lt-footprint");
    args.extend(["--maps", s(&maps), "--out", s(&out)]);
    set(&mut args, "--relative-importance", "off");
    let err = fails(&args);
    assert!(
        err.contains("relative_importance=on") && err.contains("relative_importance=off"),
        "{err}"
    );
    // Another scene: the same file names, another material.
    let other = workdir("badmaps-other");
    let mtl = other.join("cornell.mtl");
    let text = std::fs::read_to_string(&mtl).unwrap();
    std::fs::write(&mtl, text.replacen("Kd ", "Kd 0.1 0.1 0.1\n#", 1)).unwrap();
    let other_maps = d.join("other-scene.fpm");
    save(&other.join("cornell.toml"), &other_maps, "4000");
    assert!(render_with(&other_maps).contains("another scene"));
}

#[test]
fn bad_shards_are_refused_naming_the_file() {
    let d = workdir("badshards");
    let scene = d.join("cornell.toml");
    let shard = |name: &str, i: u32, n: u32, extra: &[&str]| -> PathBuf {
        let out = d.join(name);
        let sh = format!("{i}/{n}");
        let mut args = base(&scene, "pt-bsdf");
        args.extend(["--shard", &sh, "--out", s(&out)]);
        for pair in extra.chunks(2) {
            set(&mut args, pair[0], pair[1]);
        }
        ok(&args);
        out
    };
    let a: Vec<PathBuf> = (0..3)
        .map(|i| shard(&format!("a{i}.exr"), i, 3, &[]))
        .collect();
    let out = d.join("merged.exr");
    std::fs::write(&out, b"a good file").unwrap();
    let merge = |inputs: &[&PathBuf]| -> String {
        let mut args = vec!["merge", s(&out)];
        args.extend(inputs.iter().map(|p| s(p)));
        let err = fails(&args);
        assert_eq!(
            std::fs::read(&out).unwrap(),
            b"a good file",
            "a failed merge touched the output"
        );
        err
    };
    // Missing, and a shard given twice.
    let err = merge(&[&a[0], &a[2]]);
    assert!(err.contains("missing shard 1/3"), "{err}");
    let err = merge(&[&a[0], &a[1], &a[1], &a[2]]);
    assert!(
        err.contains("both shard 1/3") && err.contains("a1.exr"),
        "{err}"
    );
    // Another seed, other settings, another shard count, another total.
    let seed = shard("seed.exr", 1, 3, &["--seed", "9"]);
    let err = merge(&[&a[0], &seed, &a[2]]);
    assert!(err.contains("seed.exr") && err.contains("seed 9"), "{err}");
    let depth = shard("depth.exr", 1, 3, &["--max-depth", "4"]);
    let err = merge(&[&a[0], &depth, &a[2]]);
    assert!(
        err.contains("depth.exr") && err.contains("max_depth=4"),
        "{err}"
    );
    let four = shard("four.exr", 1, 4, &[]);
    let err = merge(&[&a[0], &four, &a[2]]);
    assert!(
        err.contains("four.exr") && err.contains("shard counts"),
        "{err}"
    );
    let more = shard("more.exr", 1, 3, &["--spp", "9"]);
    let err = merge(&[&a[0], &more, &a[2]]);
    assert!(err.contains("more.exr") && err.contains("9 spp"), "{err}");
    // Another scene: the same file names, another material.
    let other = workdir("badshards-other");
    let mtl = other.join("cornell.mtl");
    let text = std::fs::read_to_string(&mtl).unwrap();
    std::fs::write(&mtl, text.replacen("Kd ", "Kd 0.1 0.1 0.1\n#", 1)).unwrap();
    let o = d.join("other.exr");
    let other_scene = other.join("cornell.toml");
    let mut args = base(&other_scene, "pt-bsdf");
    args.extend(["--shard", "1/3", "--out", s(&o)]);
    ok(&args);
    let err = merge(&[&a[0], &o, &a[2]]);
    assert!(
        err.contains("other.exr") && err.contains("another scene"),
        "{err}"
    );
    // Truncated and corrupt images, and not an image.
    let bytes = std::fs::read(&a[1]).unwrap();
    let cut = d.join("cut.exr");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let err = merge(&[&a[0], &cut, &a[2]]);
    assert!(err.contains("cut.exr"), "{err}");
    let text = d.join("text.exr");
    std::fs::write(&text, b"not an image").unwrap();
    let err = merge(&[&a[0], &text, &a[2]]);
    assert!(err.contains("text.exr"), "{err}");
    // An image without the shard attributes (written by another program).
    let plain = d.join("plain.exr");
    let img = footprint::film::Image::new(16, 12);
    footprint::film::image_io::write_exr(&plain, &[("pt", &img)], &[]).unwrap();
    let err = merge(&[&a[0], &plain, &a[2]]);
    assert!(
        err.contains("plain.exr") && err.contains("footprint/"),
        "{err}"
    );
    // Bad --shard values.
    let bad = |extra: &[&str], needle: &str| {
        let mut args = base(&scene, "pt-bsdf");
        args.extend(["--out", s(&out)]);
        args.extend(extra);
        let err = fails(&args);
        assert!(err.contains(needle), "{err}");
    };
    bad(&["--shard", "3/3"], "0 <= i < N");
    bad(&["--shard", "8/9"], "cannot be split into 9 shards");
    let mut args = vec!["render", s(&scene), "--out", s(&out)];
    args.extend(["--time", "1", "--shard", "0/2"]);
    // (--spp conflicts with --time in the parser; the scene's spp is the total)
    assert!(fails(&args).contains("--shard needs --spp"));
}

#[test]
fn a_killed_shard_leaves_no_image_and_rerunning_it_completes_the_merge() {
    let d = workdir("killed");
    let scene = d.join("cornell.toml");
    let outs: Vec<PathBuf> = (0..3).map(|i| d.join(format!("k{i}.exr"))).collect();
    let out = |i: usize| &outs[i];
    let names = ["0/3", "1/3", "2/3"];
    let render = |i: usize| {
        let mut args = base(&scene, "pt-bsdf");
        args.extend(["--shard", names[i], "--out", s(out(i))]);
        args
    };
    for i in [0, 2] {
        ok(&render(i));
    }
    // Shard 1 is killed while it renders (a long render of the same shard, killed).
    let mut args = render(1);
    set(&mut args, "--spp", "100000");
    set(&mut args, "--resolution", "64x64");
    let mut child = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args(&args)
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(700));
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(!out(1).exists(), "a killed shard left an image");
    let merged = d.join("merged.exr");
    let err = fails(&["merge", s(&merged), s(out(0)), s(out(2))]);
    assert!(err.contains("missing shard 1/3"), "{err}");
    assert!(!merged.exists());
    // Rendering only the missing shard completes the image.
    ok(&render(1));
    ok(&["merge", s(&merged), s(out(0)), s(out(1)), s(out(2))]);
    let one = d.join("one.exr");
    let mut args = base(&scene, "pt-bsdf");
    args.extend(["--out", s(&one)]);
    ok(&args);
    common::assert_same_exr(&merged, &one, "rerun shard");
}
