//! Degenerate geometry and light: zero-area and sliver triangles, coincident surfaces, a
//! light shut in a closed box, a camera inside a closed box, radiance 10⁶ next to 10⁻⁶, a
//! one-pixel image. Every integrator x guide pair finishes with finite, non-negative pixels
//! and no rejected sample, the loader counts the triangles it left out, and where no light
//! can reach the camera the image is black: a ray that slipped through a closed box's wall
//! (at its edges and corners, where the offsets of two faces meet) would show light.

mod common;

use common::PAIRS;
use footprint::scene::Scene;
use footprint::scene::load::load_scene;
use footprint_integrators::{Method, RenderOptions, RenderResult, render};
use std::path::PathBuf;

/// The materials every scene here may use.
const MTL: &str = "newmtl white\nKd 0.7 0.7 0.7\nillum 1\n\
newmtl red\nKd 0.7 0.1 0.1\nillum 1\n\
newmtl light\nKd 0 0 0\nKe 10 10 10\nillum 1\n\
newmtl bright\nKd 0 0 0\nKe 1e6 1e6 1e6\nillum 1\n\
newmtl dim\nKd 0 0 0\nKe 1e-6 1e-6 1e-6\nillum 1\n\
newmtl shiny\nKd 0.05 0.05 0.05\nKs 0.9 0.9 0.9\nNs 10000\nillum 2\n";

/// A scene of `obj` (with the materials of [`MTL`]) and the TOML's `camera` and `extra`
/// tables, in a fresh folder; small maps.
fn scene(tag: &str, obj: &str, camera: &str, extra: &str) -> Scene {
    let mut s = load_scene(&scene_file(tag, obj, camera, extra)).unwrap();
    s.maps.photons = 5_000;
    s.maps.importons = 5_000;
    s
}

/// The scene file of [`scene`].
fn scene_file(tag: &str, obj: &str, camera: &str, extra: &str) -> PathBuf {
    let d: PathBuf =
        std::env::temp_dir().join(format!("footprint-degenerate-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("m.mtl"), MTL).unwrap();
    std::fs::write(d.join("s.obj"), format!("mtllib m.mtl\n{obj}")).unwrap();
    std::fs::write(
        d.join("s.toml"),
        format!("[camera]\n{camera}\n[[mesh]]\nfile = \"s.obj\"\n{extra}"),
    )
    .unwrap();
    d.join("s.toml")
}

/// A room 4 x 2.5 x 4 of thick white walls (vertices from 1), and the number of vertices.
fn room() -> (String, usize) {
    let mut obj = String::new();
    let mut n = 1;
    for (lo, hi) in [
        ([-0.1, -0.1, -0.1], [4.1, 0.0, 4.1]),
        ([-0.1, 2.5, -0.1], [4.1, 2.6, 4.1]),
        ([-0.1, 0.0, -0.1], [0.0, 2.5, 4.1]),
        ([4.0, 0.0, -0.1], [4.1, 2.5, 4.1]),
        ([-0.1, 0.0, 4.0], [4.1, 2.5, 4.1]),
        ([-0.1, 0.0, -0.1], [4.1, 2.5, 0.0]),
    ] {
        obj += &common::box_obj(lo, hi, n, "white");
        n += 8;
    }
    (obj, n)
}

/// The camera in the room's corner looking at the far corner's floor, `w` x `h` pixels.
fn room_camera(w: u32, h: u32) -> String {
    moved_camera(w, h, 0.0)
}

/// [`room_camera`] with the scene moved by `t` along every axis.
fn moved_camera(w: u32, h: u32, t: f64) -> String {
    let p = |x: f64, y: f64, z: f64| format!("[{:?}, {:?}, {:?}]", x + t, y + t, z + t);
    format!(
        "position = {}\nlook_at = {}\nfov_y = 70.0\nresolution = [{w}, {h}]",
        p(0.3, 2.0, 0.3),
        p(3.0, 0.3, 3.0)
    )
}

/// The mesh transform that moves a scene by `t` along every axis.
fn moved_mesh(t: f64) -> String {
    format!("transform = {{ translate = [{t:?}, {t:?}, {t:?}] }}\n")
}

/// Where the closed boxes are tried: at the origin, and 10⁵ away from it (where, without the
/// scene's move to its centre, ray offsets of two units would carry rays through the walls).
const PLACES: [f64; 2] = [0.0, 1e5];

/// Renders `scene` with `method` (2 passes, depth 8).
fn run(scene: &Scene, method: &str) -> RenderResult {
    let o = RenderOptions {
        method: Method::parse(method).unwrap(),
        spp: 2,
        time: None,
        max_depth: 8,
        seed: 5,
        ..Default::default()
    };
    render(scene, &o, |_| {})
}

/// Every pair renders `scene`, on each acceleration structure, to finite, non-negative
/// pixels in every layer without rejecting a sample; returns each render's main image mean
/// (green), named by its pair and structure.
fn stable(name: &str, scene: &Scene) -> Vec<(String, f32)> {
    let mut means = Vec::new();
    for s in common::each_accel(name, scene) {
        let accel = s.bvh.name();
        for m in PAIRS {
            let out = run(&s, m);
            for (layer, img) in &out.layers {
                assert!(img.all_valid(), "{name} {m} {accel} {layer}: invalid pixel");
            }
            assert_eq!(
                out.stats.rejected, 0,
                "{name} {m} {accel}: rejected samples"
            );
            assert!(out.stats.max_luminance.is_finite(), "{name} {m} {accel}");
            eprintln!(
                "{name} {m} {accel}: mean {:.4e}, largest sample {:.3e}",
                out.image.mean().y,
                out.stats.max_luminance
            );
            means.push((format!("{m} {accel}"), out.image.mean().y));
        }
    }
    means
}

/// Zero-area triangles (a repeated vertex, three points on a line, a triangle whose edges
/// cancel in f32) and needles thinner than the degenerate rule are left out and counted;
/// slivers just above it, a tiny well-shaped triangle, an emitting sliver, a shiny sliver
/// and coincident surfaces (a red quad on the floor's plane, a light quad in the ceiling's)
/// render.
#[test]
fn degenerate_and_sliver_triangles_and_coincident_surfaces_render() {
    let (mut obj, n) = room();
    let v = |p: [f64; 3]| format!("v {:?} {:?} {:?}\n", p[0], p[1], p[2]);
    let tri = |m: &str, p: [[f64; 3]; 3], k: &mut usize| {
        let mut s = format!("usemtl {m}\n");
        for q in p {
            s += &v(q);
        }
        s += &format!("f {} {} {}\n", *k, *k + 1, *k + 2);
        *k += 3;
        s
    };
    let mut k = n;
    // Left out: zero area, and needles under 1e-10 of their longest edge squared.
    let skipped = [
        ("white", [[1.0, 0.5, 1.0], [2.0, 0.5, 1.0], [1.0, 0.5, 1.0]]),
        (
            "white",
            [[1.0, 0.5, 1.0], [2.0, 0.75, 1.0], [3.0, 1.0, 1.0]],
        ),
        ("light", [[1.0, 1.0, 2.0], [3.0, 1.0, 2.0], [2.0, 1.0, 2.0]]),
        (
            "white",
            [[0.5, 1.0, 3.0], [3.5, 1.0, 3.0], [2.0, 1.0 + 1e-12, 3.0]],
        ),
        (
            "light",
            [[0.5, 2.0, 3.0], [3.5, 2.0, 3.0], [2.0, 2.0, 3.0 + 1e-11]],
        ),
    ];
    for (m, p) in skipped {
        obj += &tri(m, p, &mut k);
    }
    // Kept: slivers just above the rule, a tiny triangle, an emitting and a shiny sliver.
    for (m, p) in [
        (
            "white",
            [[0.5, 1.2, 3.5], [3.5, 1.2, 3.5], [2.0, 1.2 + 1e-4, 3.5]],
        ),
        (
            "shiny",
            [[0.5, 0.3, 2.5], [3.5, 0.3, 2.5], [2.0, 0.3, 2.5 + 1e-4]],
        ),
        (
            "light",
            [[1.0, 2.4, 1.0], [3.0, 2.4, 1.0], [2.0, 2.4, 1.0 + 1e-4]],
        ),
        (
            "white",
            [
                [2.0, 1.0, 2.0],
                [2.0 + 1e-6, 1.0, 2.0],
                [2.0, 1.0 + 1e-6, 2.0],
            ],
        ),
        (
            "light",
            [
                [2.0, 2.0, 2.0],
                [2.0, 2.0, 2.0 + 1e-6],
                [2.0 + 1e-6, 2.0, 2.0],
            ],
        ),
    ] {
        obj += &tri(m, p, &mut k);
    }
    // Coincident surfaces: a red quad in the floor's plane, a light quad in the ceiling's.
    for (m, y, flip) in [("red", 0.0, false), ("light", 2.5, true)] {
        let q = [[1.0, y, 1.0], [3.0, y, 1.0], [3.0, y, 3.0], [1.0, y, 3.0]];
        let q = if flip {
            [q[0], q[1], q[2], q[3]]
        } else {
            [q[0], q[3], q[2], q[1]]
        };
        obj += &tri(m, [q[0], q[1], q[2]], &mut k);
        obj += &tri(m, [q[0], q[2], q[3]], &mut k);
    }
    let s = scene("slivers", &obj, &room_camera(12, 12), "");
    assert_eq!(
        s.stats.degenerate_skipped,
        skipped.len(),
        "degenerate triangles left out"
    );
    let means = stable("slivers", &s);
    assert!(
        means.iter().all(|m| m.1 > 0.0),
        "the lit room is black: {means:?}"
    );
    // `render` says so, and its EXR records it.
    let file = scene_file("slivers-cli", &obj, &room_camera(8, 8), "");
    let exr = file.with_extension("exr");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_footprint"))
        .args(["render", file.to_str().unwrap(), "--spp", "1", "-o"])
        .args([
            exr.to_str().unwrap(),
            "--integrator",
            "pt",
            "--guide",
            "bsdf",
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("skipped 5 degenerate triangles"),
        "{stderr}"
    );
    let header = footprint::film::image_io::read_exr_layers(&exr)
        .unwrap()
        .attributes;
    assert!(
        header.contains(&("footprint/degenerate_triangles_skipped".into(), "5".into())),
        "{header:?}"
    );
}

/// A point light and an area light shut in closed boxes of zero-thickness faces, in the
/// room the camera sees: no light gets out, so every pair's image is black, at the origin
/// and far from it.
#[test]
fn a_light_shut_in_a_closed_box_lights_nothing() {
    let (mut obj, n) = room();
    obj += &common::box_obj([1.5, 0.0, 1.5], [2.5, 1.0, 2.5], n, "white");
    // An emitting box inside a closed box: emits outward onto the box's inside.
    obj += &common::box_obj([2.9, 0.5, 2.9], [3.1, 0.7, 3.1], n + 8, "light");
    obj += &common::box_obj([2.8, 0.4, 2.8], [3.2, 0.8, 3.2], n + 16, "white");
    for t in PLACES {
        let light = format!(
            "[[light]]\ntype = \"point\"\nposition = [{:?}, {:?}, {:?}]\nintensity = [50.0, 50.0, 50.0]\n",
            2.0 + t,
            0.5 + t,
            2.0 + t
        );
        let extra = moved_mesh(t) + &light;
        let s = scene(&format!("shut-{t}"), &obj, &moved_camera(12, 12, t), &extra);
        let means = stable(&format!("shut at {t}"), &s);
        for (m, mean) in &means {
            assert_eq!(*mean, 0.0, "{m} at {t}: light escaped a closed box");
        }
    }
}

/// The camera inside a closed box of zero-thickness faces, the light outside it: every pair's
/// image is black, at the origin and far from it.
#[test]
fn a_camera_inside_a_closed_box_sees_black() {
    let (mut obj, n) = room();
    obj += &common::box_obj([0.1, 1.8, 0.1], [0.6, 2.3, 0.6], n, "white");
    obj += "usemtl light\nv 1.5 2.45 1.5\nv 2.5 2.45 1.5\nv 2.5 2.45 2.5\nv 1.5 2.45 2.5\n";
    obj += &format!(
        "f {a} {b} {c}\nf {a} {c} {d}\n",
        a = n + 8,
        b = n + 9,
        c = n + 10,
        d = n + 11
    );
    for t in PLACES {
        let s = scene(
            &format!("inside-{t}"),
            &obj,
            &moved_camera(12, 12, t),
            &moved_mesh(t),
        );
        let means = stable(&format!("inside at {t}"), &s);
        for (m, mean) in &means {
            assert_eq!(
                *mean, 0.0,
                "{m} at {t}: the camera sees out of a closed box"
            );
        }
    }
}

/// A light of radiance 10⁶ beside one of 10⁻⁶ (a light choice of probability 10⁻¹²), and a
/// one-pixel image: finite pixels, no rejected sample.
#[test]
fn radiance_over_twelve_orders_and_a_one_pixel_image_stay_finite() {
    let (mut obj, n) = room();
    for (m, x, k) in [("bright", 1.0, n), ("dim", 2.5, n + 4)] {
        obj += &format!(
            "usemtl {m}\nv {x} 2.45 1.5\nv {} 2.45 1.5\nv {} 2.45 2.5\nv {x} 2.45 2.5\nf {k} {} {}\nf {k} {} {}\n",
            x + 0.5,
            x + 0.5,
            k + 1,
            k + 2,
            k + 2,
            k + 3
        );
    }
    let s = scene("orders", &obj, &room_camera(12, 12), "");
    assert!(
        s.light_choice_own_number,
        "the dim light is chosen with its own number"
    );
    assert!(stable("orders", &s).iter().all(|m| m.1 > 0.0));
    let mut one = s.clone();
    one.camera = one.camera.with_resolution(1, 1).unwrap();
    assert!(stable("one pixel", &one).iter().all(|m| m.1 > 0.0));
    // `auto` pilots and renders the one pixel too (its pilot's windows, folds and blocks).
    use footprint_integrators::auto::{Request, Run, render_request};
    let request = Request::default()
        .with_names(Some("auto"), Some("auto"))
        .unwrap();
    let o = RenderOptions {
        spp: 4,
        seed: 5,
        ..Default::default()
    };
    let out = render_request(&one, &o, &request, &Run::default(), &mut |_| {}, |_| {}).unwrap();
    assert!(out.choice.is_some(), "auto chose");
    assert!(out.result.image.all_valid() && out.result.stats.rejected == 0);
}
