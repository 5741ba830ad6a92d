//! Shared helpers for the statistical tests: quantiles and the chi-square distribution (from
//! statrs), the Šidák correction, and paths to the bundled scenes.
#![allow(dead_code)]

pub mod chi2;

use statrs::distribution::ContinuousCDF;

use std::path::PathBuf;

/// Records that `test` skipped a check, and why, where a reader of the normal output sees
/// it: the line goes straight to the terminal's stderr (libtest captures only `print!` and
/// `eprint!`, so `cargo test` shows it next to the test's `ok` without `--nocapture`), and
/// it is appended to `target/skipped-tests.txt`, which `.ci/run` lists in its closing line.
pub fn skip(test: &str, reason: &str) {
    use std::io::Write;
    let line = format!("SKIPPED {test}: {reason}");
    let _ = std::io::stderr().write_all(format!("\n{line}\n").as_bytes());
    // CARGO_TARGET_TMPDIR is target/tmp.
    let list = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .map(|t| t.join("skipped-tests.txt"));
    if let Some(list) = list {
        if let Ok(mut f) = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(list)
        {
            let _ = writeln!(f, "{line}");
        }
    }
}

/// Every integrator x guide pair, as `--integrator` and `--guide` name them.
pub const PAIRS: [&str; 9] = [
    "pt-bsdf",
    "pt-grid",
    "pt-footprint",
    "lt-bsdf",
    "lt-grid",
    "lt-footprint",
    "combined-bsdf",
    "combined-grid",
    "combined-footprint",
];

/// `scene` on each acceleration structure this machine has: the CWBVH, and Embree where it
/// loads (else `test` records a visible skip).
pub fn each_accel(test: &str, scene: &footprint::scene::Scene) -> Vec<footprint::scene::Scene> {
    use footprint::scene::accel::{Accel, Backend};
    let mut out = Vec::new();
    for backend in [Backend::Cwbvh, Backend::Embree] {
        match Accel::build_with(&scene.triangles, backend) {
            Ok(a) => out.push(footprint::scene::Scene {
                bvh: std::sync::Arc::new(a),
                ..scene.clone()
            }),
            Err(e) => skip(test, &format!("the CWBVH only: {e}")),
        }
    }
    out
}

/// Folder of the bundled scenes.
pub fn scenes_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

pub fn scene_path(name: &str) -> PathBuf {
    scenes_dir().join(name).join(format!("{name}.toml"))
}

/// Per-test significance that keeps the family-wise significance at `alpha` over `n`
/// independent tests (Šidák).
pub fn sidak(alpha: f64, n: usize) -> f64 {
    1.0 - (1.0 - alpha).powf(1.0 / n as f64)
}

/// Standard normal quantile (statrs).
pub fn normal_quantile(p: f64) -> f64 {
    assert!(p > 0.0 && p < 1.0);
    statrs::distribution::Normal::standard().inverse_cdf(p)
}

/// Two-sided critical value of Student's t with `dof` degrees of freedom at significance
/// `alpha` (statrs).
pub fn t_critical(alpha: f64, dof: f64) -> f64 {
    statrs::distribution::StudentsT::new(0.0, 1.0, dof)
        .expect("positive degrees of freedom")
        .inverse_cdf(1.0 - alpha / 2.0)
}

/// P(X >= chi2) for a chi-square variable with `dof` degrees of freedom (statrs).
pub fn chi2_sf(chi2: f64, dof: f64) -> f64 {
    statrs::distribution::ChiSquared::new(dof)
        .expect("positive degrees of freedom")
        .sf(chi2)
}

/// Means over a `side x side` grid of image regions, per channel.
pub fn region_means(img: &footprint::film::Image, side: u32) -> Vec<[f64; 3]> {
    let (bw, bh) = (img.width / side, img.height / side);
    let mut out = vec![[0.0f64; 3]; (side * side) as usize];
    for y in 0..bh * side {
        for x in 0..bw * side {
            let p = img.get(x, y);
            let r = &mut out[((y / bh) * side + x / bw) as usize];
            for c in 0..3 {
                r[c] += p[c] as f64 / (bw * bh) as f64;
            }
        }
    }
    out
}

/// OBJ text of an axis-aligned box with outward faces (vertices numbered from `first`).
pub fn box_obj(lo: [f32; 3], hi: [f32; 3], first: usize, material: &str) -> String {
    let mut s = String::new();
    for i in 0..8 {
        let v = [
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ];
        s += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    s += &format!("usemtl {material}\n");
    // Faces as quads counter-clockwise seen from outside, split in two triangles.
    for q in [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ] {
        let v = |i: usize| q[i] + first;
        s += &format!(
            "f {} {} {}\nf {} {} {}\n",
            v(0),
            v(1),
            v(2),
            v(0),
            v(2),
            v(3)
        );
    }
    s
}

/// Mean and standard error of the mean of `xs`.
pub fn mean_stderr(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let m = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0);
    (m, (var / n).sqrt())
}

/// A copy of the cornell scene in a fresh folder `footprint-{tag}-PID` under the temporary
/// folder (so that caches and outputs stay out of the repository, and a changed copy is
/// "another scene"); returns the folder.
pub fn cornell_copy(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("footprint-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    let src = scenes_dir().join("cornell");
    for f in ["cornell.toml", "cornell.obj", "cornell.mtl"] {
        std::fs::copy(src.join(f), d.join(f)).unwrap();
    }
    d
}

/// Every layer of EXR `a` equals `b`'s to float rounding (relative 10⁻⁶: a few f32 ulp), and
/// none is black.
pub fn assert_same_exr(a: &std::path::Path, b: &std::path::Path, what: &str) {
    use footprint::film::image_io::{ExrLayers, read_exr_layers};
    let (a, b) = (read_exr_layers(a).unwrap(), read_exr_layers(b).unwrap());
    let names = |e: &ExrLayers| e.layers.iter().map(|l| l.0.clone()).collect::<Vec<_>>();
    assert_eq!(names(&a), names(&b), "{what}: layers");
    let mut worst = 0.0f32;
    for ((name, x), (_, y)) in a.layers.iter().zip(&b.layers) {
        assert_eq!(x.pixels.len(), y.pixels.len());
        assert!(x.mean().max_element() > 0.0, "{what}: {name} is black");
        for (p, q) in x.pixels.iter().zip(&y.pixels) {
            for c in 0..3 {
                let d = (p[c] - q[c]).abs() / p[c].abs().max(q[c].abs()).max(1e-30);
                worst = worst.max(d);
            }
        }
    }
    assert!(worst < 1e-6, "{what}: relative difference {worst:e}");
}

/// `renders` renders of `method` on `scene` at `spp` and `max_depth`, seeds from `seed0`,
/// each reduced by `reduce` (block or region means); every pixel checked valid.
pub fn runs_of(
    scene: &footprint::scene::Scene,
    method: &str,
    (renders, spp, max_depth, seed0): (usize, u32, u32, u64),
    reduce: impl Fn(&footprint::film::Image) -> Vec<[f64; 3]>,
) -> Vec<Vec<[f64; 3]>> {
    use footprint_integrators::{Method, RenderOptions, render};
    (0..renders)
        .map(|r| {
            let o = RenderOptions {
                method: Method::parse(method).unwrap(),
                spp,
                max_depth,
                seed: seed0 + r as u64,
                ..Default::default()
            };
            let out = render(scene, &o, |_| {});
            assert!(out.image.all_valid(), "{method}: invalid pixel");
            reduce(&out.image)
        })
        .collect()
}

/// Asserts that the mean over `runs` of every block and channel lies within `crit` standard
/// errors (estimated from the runs' spread) of `want`; returns the largest |t|.
pub fn assert_runs_match(label: &str, runs: &[Vec<[f64; 3]>], want: &[[f64; 3]], crit: f64) -> f64 {
    let mut worst = 0.0f64;
    for (b, w) in want.iter().enumerate() {
        for c in 0..3 {
            let xs: Vec<f64> = runs.iter().map(|r| r[b][c]).collect();
            let (mean, se) = mean_stderr(&xs);
            let t = (mean - w[c]) / se.max(1e-12 * w[c]);
            worst = worst.max(t.abs());
            assert!(
                t.abs() < crit,
                "{label}: block {b} channel {c}: {mean:.5} against {:.5} (t = {t:.2}, critical {crit:.2})",
                w[c]
            );
        }
    }
    worst
}

/// Asserts that two sets of runs agree per block and channel: Welch's t of their means
/// within `crit`; returns the largest |t|.
pub fn assert_runs_agree(label: &str, a: &[Vec<[f64; 3]>], b: &[Vec<[f64; 3]>], crit: f64) -> f64 {
    let mut worst = 0.0f64;
    for g in 0..a[0].len() {
        for c in 0..3 {
            let xa: Vec<f64> = a.iter().map(|r| r[g][c]).collect();
            let xb: Vec<f64> = b.iter().map(|r| r[g][c]).collect();
            let ((ma, sa), (mb, sb)) = (mean_stderr(&xa), mean_stderr(&xb));
            let t = (mb - ma) / (sa * sa + sb * sb).sqrt().max(1e-12);
            worst = worst.max(t.abs());
            assert!(
                t.abs() < crit,
                "{label}: region {g} channel {c}: {mb:.5} against {ma:.5} (t = {t:.2}, critical {crit:.2})"
            );
        }
    }
    worst
}

/// The scene of the analytic sheet tests (`tests/thin_glass.rs`, `tests/cutouts.rs`): a
/// `side` x `side` camera at (0, 0, 4) looking down (fov 40°, box filter), a diffuse floor of
/// reflectance `rho` at z = 0 and a sheet of BSDF `sheet_bsdf` (Mitsuba XML) at z = 1, both
/// 100 x 100, and a point light of `intensity` at `light`; written to a folder of its own
/// (`tag`: tests run in parallel) and loaded.
pub fn sheet_over_floor(
    tag: &str,
    side: u32,
    rho: f32,
    sheet_bsdf: &str,
    light: glam::Vec3,
    intensity: f32,
) -> footprint::scene::Scene {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("sheet-{tag}"));
    std::fs::create_dir_all(&dir).unwrap();
    let xml = format!(
        r#"<scene version="3.0.0">
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm">
            <integer name="width" value="{side}"/><integer name="height" value="{side}"/>
            <rfilter type="box"/>
        </film>
    </sensor>
    <shape type="rectangle">
        <transform name="to_world"><scale value="50"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="{rho}"/></bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="50"/><translate z="1"/></transform>
        {sheet_bsdf}
    </shape>
    <emitter type="point">
        <point name="position" x="{}" y="{}" z="{}"/>
        <rgb name="intensity" value="{intensity}"/>
    </emitter>
</scene>"#,
        light.x, light.y, light.z
    );
    let path = dir.join("scene.xml");
    std::fs::write(&path, xml).unwrap();
    footprint::scene::load::load_scene(&path).expect("the sheet scene loads")
}

/// Asserts that light tracing, the combined image and the guided methods agree with
/// unguided path tracing on `scene` per region (`side` x `side`) and channel, over `renders`
/// renders each at `spp` and `max_depth` (seeds from 900); prints each method's image mean
/// over path tracing's and largest |t|.
///
/// Bound: per region and channel, Welch's t of the two methods' region means against the
/// two-sided Student-t critical value at 0.01 (Welch–Satterthwaite degrees of freedom, taken
/// at the smaller `renders - 1`), Šidák-corrected over every region, channel and compared
/// method.
pub fn assert_integrators_agree(
    scene: &footprint::scene::Scene,
    (renders, spp, max_depth): (usize, u32, u32),
    side: u32,
) {
    let regions = |m: &str| {
        runs_of(scene, m, (renders, spp, max_depth, 900), |img| {
            region_means(img, side)
        })
    };
    let pt = regions("pt-bsdf");
    let others = [
        "lt-bsdf",
        "combined-bsdf",
        "pt-footprint",
        "lt-footprint",
        "combined-footprint",
    ];
    let n = (side * side) as usize;
    let crit = t_critical(sidak(0.01, others.len() * n * 3), (renders - 1) as f64);
    let total = |runs: &[Vec<[f64; 3]>]| -> f64 { runs.iter().flatten().flatten().sum() };
    for m in others {
        let runs = regions(m);
        let worst = assert_runs_agree(&format!("{m} against pt-bsdf"), &pt, &runs, crit);
        eprintln!(
            "{m}: image mean {:.4} of pt-bsdf's, largest |t| {worst:.2} (critical {crit:.2})",
            total(&runs) / total(&pt)
        );
    }
}
