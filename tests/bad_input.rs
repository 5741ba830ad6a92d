//! Bad input gets a clear error naming the file, line or field, a non-zero exit, no panic,
//! and never a partly written image over a good one.

use std::path::{Path, PathBuf};
use std::process::Command;

const QUAD_OBJ: &str = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0 1 0\nv 1 1 0\nv 1 1 1\nusemtl white\nf 1 2 3\nf 1 3 4\nusemtl light\nf 5 7 6\n";
const MTL: &str = "newmtl white\nKd 0.5 0.5 0.5\nnewmtl light\nKd 0 0 0\nKe 5 5 5\n";
const CAMERA: &str = "[camera]\nposition = [0.5, 0.5, -2.0]\nlook_at = [0.5, 0.5, 0.0]\nfov_y = 40.0\nresolution = [8, 8]\n";

/// A fresh folder with the given files.
fn dir_with(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let d = std::env::temp_dir().join(format!("footprint-bad-input-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    for (f, text) in files {
        std::fs::write(d.join(f), text).unwrap();
    }
    d
}

fn scene(body: &str) -> String {
    format!("{CAMERA}[render]\nspp = 1\n[[mesh]]\nfile = \"q.obj\"\n{body}")
}

/// Runs `footprint render` and returns (success, stderr). A failure must exit with status 1
/// (as docs/cli.md says), whether the argument parser or the renderer
/// found the bad input.
fn render(dir: &Path, scene_file: &str, extra: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .arg("render")
        .arg(dir.join(scene_file))
        .arg("--out")
        .arg(dir.join("out.exr"))
        .args(extra)
        .output()
        .expect("the binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!stderr.contains("panicked"), "panic: {stderr}");
    if !out.status.success() {
        assert_eq!(out.status.code(), Some(1), "exit status of: {stderr}");
    }
    (out.status.success(), stderr)
}

fn expect_error(name: &str, files: &[(&str, &str)], extra: &[&str], needles: &[&str]) {
    let d = dir_with(name, files);
    let (ok, err) = render(&d, "s.toml", extra);
    assert!(!ok, "{name}: expected failure, got success");
    for n in needles {
        assert!(
            err.contains(n),
            "{name}: error should mention '{n}', got: {err}"
        );
    }
    assert!(!d.join("out.exr").exists(), "{name}: an image was written");
}

#[test]
fn a_good_scene_renders() {
    let d = dir_with(
        "good",
        &[("q.obj", QUAD_OBJ), ("m.mtl", MTL), ("s.toml", &scene(""))],
    );
    let (ok, err) = render(&d, "s.toml", &[]);
    assert!(ok, "{err}");
    assert!(d.join("out.exr").exists() && d.join("out.png").exists());
}

#[test]
fn missing_files() {
    expect_error("no-scene", &[], &[], &["s.toml"]);
    expect_error("no-obj", &[("s.toml", &scene(""))], &[], &["q.obj"]);
    expect_error(
        "no-mtl",
        &[("q.obj", QUAD_OBJ), ("s.toml", &scene(""))],
        &[],
        &["m.mtl"],
    );
    let textured = MTL.replace("Kd 0.5 0.5 0.5", "Kd 0.5 0.5 0.5\nmap_Kd wood.png");
    expect_error(
        "no-texture",
        &[
            ("q.obj", QUAD_OBJ),
            ("m.mtl", &textured),
            ("s.toml", &scene("")),
        ],
        &[],
        &["wood.png"],
    );
    expect_error(
        "bad-texture",
        &[
            ("q.obj", QUAD_OBJ),
            ("m.mtl", &textured),
            ("wood.png", "not a png"),
            ("s.toml", &scene("")),
        ],
        &[],
        &["wood.png"],
    );
}

#[test]
fn toml_syntax_errors_and_unknown_keys_name_the_line() {
    let files = |s: String| {
        vec![
            ("q.obj", QUAD_OBJ.to_string()),
            ("m.mtl", MTL.to_string()),
            ("s.toml", s),
        ]
    };
    let run = |name: &str, s: String, needles: &[&str]| {
        let f = files(s);
        let f: Vec<(&str, &str)> = f.iter().map(|(a, b)| (*a, b.as_str())).collect();
        expect_error(name, &f, &[], needles);
    };
    // Line 4 (`fov_y`) holds the broken value.
    run(
        "syntax",
        format!("{CAMERA}").replace("fov_y = 40.0", "fov_y = = 40"),
        &["s.toml:4:"],
    );
    run(
        "unknown-key",
        scene("").replace("spp = 1", "spp = 1\nsamples = 4"),
        &["s.toml:8:", "samples"],
    );
    run(
        "unknown-light",
        scene("[[light]]\ntype = \"laser\"\nposition = [0,0,0]\n"),
        &["s.toml:", "laser"],
    );
    run(
        "bad-integrator",
        scene("").replace("spp = 1", "spp = 1\nintegrator = \"bdpt\""),
        &["render.integrator", "bdpt"],
    );
    run(
        "zero-spp",
        scene("").replace("spp = 1", "spp = 0"),
        &["render.spp"],
    );
    run(
        "nan-exposure",
        scene("").replace("spp = 1", "spp = 1\nexposure = nan"),
        &["render.exposure"],
    );
    run(
        "bad-scale",
        scene("transform = { scale = 0.0 }\n"),
        &["mesh[0].transform.scale"],
    );
}

#[test]
fn bad_geometry() {
    let nan = QUAD_OBJ.replace("v 1 0 1", "v 1 nan 1");
    expect_error(
        "nan-vertex",
        &[("q.obj", &nan), ("m.mtl", MTL), ("s.toml", &scene(""))],
        &[],
        &["q.obj:4", "not a finite"],
    );
    let inf = QUAD_OBJ.replace("v 1 0 1", "v 1 inf 1");
    expect_error(
        "inf-vertex",
        &[("q.obj", &inf), ("m.mtl", MTL), ("s.toml", &scene(""))],
        &[],
        &["q.obj:4"],
    );
    // Degenerate triangles are skipped with a warning, and the rest renders.
    // Two repeated-vertex triangles and one with three collinear vertices.
    let degenerate = format!(
        "{}usemtl white\nf 1 2 2\nf 1 2 1\nf 1 2 8\n",
        QUAD_OBJ.replace("usemtl white", "v 2 0 0\nusemtl white")
    );
    let d = dir_with(
        "degenerate",
        &[
            ("q.obj", &degenerate),
            ("m.mtl", MTL),
            ("s.toml", &scene("")),
        ],
    );
    let (ok, err) = render(&d, "s.toml", &[]);
    assert!(ok, "{err}");
    assert!(err.contains("skipped 3 degenerate triangles"), "{err}");
}

#[test]
fn scene_without_lights() {
    let dark = MTL.replace("Ke 5 5 5", "Ke 0 0 0");
    expect_error(
        "no-lights",
        &[
            ("q.obj", QUAD_OBJ),
            ("m.mtl", &dark),
            ("s.toml", &scene("")),
        ],
        &[],
        &["no lights"],
    );
}

#[test]
fn impossible_cameras() {
    fn files(s: &str) -> Vec<(&str, &str)> {
        vec![("q.obj", QUAD_OBJ), ("m.mtl", MTL), ("s.toml", s)]
    }
    let zero_look = scene("").replace("look_at = [0.5, 0.5, 0.0]", "look_at = [0.5, 0.5, -2.0]");
    expect_error(
        "zero-look",
        &files(&zero_look),
        &[],
        &["look direction is zero"],
    );
    let parallel = scene("").replace("look_at = [0.5, 0.5, 0.0]", "look_at = [0.5, 3.0, -2.0]");
    expect_error("parallel-up", &files(&parallel), &[], &["parallel to up"]);
    let zero_res = scene("").replace("resolution = [8, 8]", "resolution = [0, 8]");
    expect_error("zero-resolution", &files(&zero_res), &[], &["resolution"]);
    let fov = scene("").replace("fov_y = 40.0", "fov_y = 0.0");
    expect_error("zero-fov", &files(&fov), &[], &["fov_y"]);
}

#[test]
fn bad_flags() {
    let files = [
        ("q.obj", QUAD_OBJ),
        ("m.mtl", MTL),
        ("s.toml", &scene("") as &str),
    ];
    expect_error(
        "flag-integrator",
        &files,
        &["--integrator", "bdpt"],
        &["bdpt"],
    );
    expect_error("flag-spp", &files, &["--spp", "0"], &["spp"]);
    expect_error("flag-time", &files, &["--time", "-3"], &["time"]);
    expect_error("flag-unknown", &files, &["--frobnicate"], &["frobnicate"]);
    expect_error(
        "flag-resolution",
        &files,
        &["--resolution", "0x10"],
        &["resolution", "0x10"],
    );
    expect_error("flag-threads", &files, &["--threads", "0"], &["threads"]);
    expect_error(
        "flag-accel",
        &files,
        &["--accel", "kdtree"],
        &["accel", "kdtree"],
    );
}

/// An unknown `FOOTPRINT_ACCEL` is an error naming the variable, not a silent default.
#[test]
fn an_unknown_accel_variable_is_named() {
    let d = dir_with(
        "env-accel",
        &[
            ("q.obj", QUAD_OBJ),
            ("m.mtl", MTL),
            ("s.toml", &scene("") as &str),
        ],
    );
    let out = Command::new(env!("CARGO_BIN_EXE_footprint"))
        .env("FOOTPRINT_ACCEL", "kdtree")
        .arg("render")
        .arg(d.join("s.toml"))
        .arg("--out")
        .arg(d.join("out.exr"))
        .output()
        .expect("the binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("FOOTPRINT_ACCEL=kdtree"), "{stderr}");
    assert!(!d.join("out.exr").exists());
}

/// `--help` is not an error: it prints to stdout and exits with 0.
#[test]
fn help_exits_with_zero() {
    for args in [&["--help"][..], &["render", "--help"], &["maps", "--help"]] {
        let out = Command::new(env!("CARGO_BIN_EXE_footprint"))
            .args(args)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(0), "{args:?}");
        assert!(String::from_utf8_lossy(&out.stdout).contains("Usage"));
    }
}

/// The operating system's reason is said once, not repeated by the error chain.
#[test]
fn io_errors_say_the_reason_once() {
    let d = dir_with("io-once", &[]);
    let (ok, err) = render(&d, "s.toml", &[]);
    assert!(!ok);
    assert!(
        err.contains("cannot read") && err.contains("s.toml"),
        "{err}"
    );
    assert_eq!(err.matches("os error").count(), 1, "{err}");
    // Not UTF-8: the decoder's reason once.
    let d = dir_with("utf8-once", &[]);
    std::fs::write(d.join("s.toml"), b"\xff\xfe[camera]\n").unwrap();
    let (ok, err) = render(&d, "s.toml", &[]);
    assert!(!ok);
    assert!(err.contains("s.toml"), "{err}");
    assert_eq!(err.matches("valid UTF-8").count(), 1, "{err}");
    // A missing OBJ and MTL beside a good scene file: once each.
    expect_error("no-obj-once", &[("s.toml", &scene(""))], &[], &["q.obj"]);
    let d = dir_with("no-obj-once2", &[("s.toml", &scene(""))]);
    let (_, err) = render(&d, "s.toml", &[]);
    assert_eq!(err.matches("os error").count(), 1, "{err}");
    let d = dir_with(
        "no-mtl-once",
        &[("q.obj", QUAD_OBJ), ("s.toml", &scene(""))],
    );
    let (_, err) = render(&d, "s.toml", &[]);
    assert!(err.contains("m.mtl"), "{err}");
    assert_eq!(err.matches("os error").count(), 1, "{err}");
}

#[test]
fn a_failed_run_leaves_a_good_image_alone() {
    let d = dir_with(
        "keep",
        &[("q.obj", QUAD_OBJ), ("m.mtl", MTL), ("s.toml", &scene(""))],
    );
    let (ok, err) = render(&d, "s.toml", &[]);
    assert!(ok, "{err}");
    let before = std::fs::read(d.join("out.exr")).unwrap();
    // Break the scene and render over the same output.
    std::fs::write(d.join("m.mtl"), MTL.replace("Ke 5 5 5", "Ke 0 0 0")).unwrap();
    let (ok, _) = render(&d, "s.toml", &[]);
    assert!(!ok);
    assert_eq!(
        std::fs::read(d.join("out.exr")).unwrap(),
        before,
        "the good image was changed"
    );
    // No temporary files are left behind.
    let leftovers: Vec<_> = std::fs::read_dir(&d)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp"))
        .collect();
    assert!(leftovers.is_empty());
}
