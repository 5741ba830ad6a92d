//! `scripts/render_farm.py` on a local Dask.distributed cluster (loopback only, two
//! workers): a guided render in four shards, merged, equals one run of the same seed and
//! samples; with a shard removed from the work folder, running the same command again
//! renders only that one and gives the same image; a compare sweep fans out into one row per
//! method, value and rung. Says loudly that it skipped when Dask.distributed is not
//! installed, except under CI (`.ci/run` installs it), where that is a failure.

mod common;

use std::path::Path;
use std::process::Command;

fn dask_installed() -> bool {
    Command::new("python3")
        .args(["-c", "import distributed"])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false)
}

fn script() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scripts/render_farm.py")
}

/// Runs the driver; returns its stdout and stderr.
fn farm(args: &[&str]) -> (String, String) {
    let out = Command::new("python3")
        .arg(script())
        .args(args)
        .output()
        .expect("python3 runs");
    let (o, e) = (
        String::from_utf8_lossy(&out.stdout).to_string(),
        String::from_utf8_lossy(&out.stderr).to_string(),
    );
    assert!(
        out.status.success(),
        "render_farm.py {} failed:\n{o}\n{e}",
        args.join(" ")
    );
    (o, e)
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The render flags of every image here.
const FLAGS: [&str; 20] = [
    "--integrator",
    "combined",
    "--guide",
    "footprint",
    "--spp",
    "6",
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
    "--threads",
    "1",
    "--exposure",
    "0",
];

fn skipped() -> bool {
    if dask_installed() {
        return false;
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "Dask.distributed is not installed, and CI must have it (.ci/run installs it)"
    );
    // Straight to stderr, past the test harness's capture, so that it shows in a passing run.
    use std::io::Write;
    let _ = writeln!(
        std::io::stderr(),
        "\n*** SKIPPED render_farm: Dask.distributed is not installed (pip install 'dask[distributed]'; .ci/run installs it) ***\n"
    );
    true
}

#[test]
fn four_shards_on_a_local_dask_cluster_equal_one_run() {
    if skipped() {
        return;
    }
    let d = common::cornell_copy("farm");
    let scene = d.join("cornell.toml");
    let bin = env!("CARGO_BIN_EXE_footprint");
    let one = d.join("one.exr");
    let mut args = vec!["render", s(&scene), "--out", s(&one)];
    args.extend(FLAGS);
    let status = Command::new(bin).args(&args).output().unwrap();
    assert!(status.status.success());

    let merged = d.join("merged.exr");
    let mut args = vec![
        "render",
        s(&scene),
        "--shards",
        "4",
        "--local-workers",
        "2",
        "--footprint",
        bin,
        "--out",
        s(&merged),
        "--",
    ];
    args.extend(FLAGS);
    let (out, err) = farm(&args);
    assert!(out.contains("4 shards merged"), "{out}");
    assert!(err.contains("replicated to every worker"), "{err}");
    common::assert_same_exr(&merged, &one, "4 shards on Dask");
    assert!(d.join("merged.png").exists());

    // A shard lost: the same command renders only that one.
    let work = d.join("merged-shards");
    std::fs::remove_file(work.join("shard-2-of-4.exr")).unwrap();
    std::fs::remove_file(&merged).unwrap();
    let (_, err) = farm(&args);
    assert!(
        err.contains("3 of 4 shards already") && err.contains("shard 2/4 done"),
        "{err}"
    );
    assert!(!err.contains("shard 0/4 done"), "{err}");
    common::assert_same_exr(&merged, &one, "rerun of the missing shard");
}

#[test]
fn a_compare_sweep_fans_out_one_row_per_method_value_and_rung() {
    if skipped() {
        return;
    }
    let d = common::cornell_copy("farm-compare");
    let scene = d.join("cornell.toml");
    let out = d.join("cmp");
    farm(&[
        "compare",
        s(&scene),
        "--out",
        s(&out),
        "--time",
        "0.3",
        "--ladder",
        "0.15,0.3",
        "--sweep",
        "k_p=25,50",
        "--reference-spp",
        "8",
        "--shards",
        "2",
        "--local-workers",
        "2",
        "--footprint",
        env!("CARGO_BIN_EXE_footprint"),
        "--",
        "--resolution",
        "16x16",
        "--threads",
        "1",
        "--photons",
        "4000",
        "--importons",
        "4000",
    ]);
    let csv = std::fs::read_to_string(out.join("cornell/metrics.csv")).unwrap();
    // Header + 2 methods x 2 values x 2 rungs.
    assert_eq!(csv.lines().count(), 1 + 8, "{csv}");
    for label in [
        "pt-footprint@k_p=25",
        "pt-footprint@k_p=50",
        "lt-footprint@k_p=25",
        "lt-footprint@k_p=50",
    ] {
        assert_eq!(csv.matches(&format!("{label},")).count(), 2, "{csv}");
        assert!(out.join(format!("cornell/{label}.png")).exists());
    }
    let summary = std::fs::read_to_string(out.join("cornell/summary.csv")).unwrap();
    assert_eq!(summary.lines().count(), 1 + 4, "{summary}");
    assert!(out.join("cornell/reference.exr").exists());
}
