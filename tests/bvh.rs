//! Each acceleration structure's closest hit equals a brute-force loop over all triangles,
//! on random rays through every bundled scene (rays from random points in the scene's
//! bounds, in uniform directions), and its shadow-ray query agrees with the closest hit (the
//! CWBVH's in both of its traversal orders): footprint's own CWBVH always, Embree where the
//! system has it (skipped visibly where not).

mod common;

use common::scene_path;
use footprint::rng::Rng;
use footprint::sampling::sample_uniform_sphere;
use footprint::scene::accel::{Accel, Backend, ShadowOrder, Toward};
use footprint::scene::embree;
use footprint::scene::load::load_scene;

/// The backends to test: the CWBVH, and Embree when it loads.
fn backends(test: &str) -> Vec<Backend> {
    match embree::available() {
        Ok(()) => vec![Backend::Cwbvh, Backend::Embree],
        Err(why) => {
            common::skip(&format!("{test} (Embree)"), &why);
            vec![Backend::Cwbvh]
        }
    }
}

/// The shadow-ray queries of `accel`: Embree's, or the CWBVH's in each of its orders.
#[allow(clippy::type_complexity)]
fn shadow_queries(
    accel: &Accel,
) -> Vec<(
    &'static str,
    Box<dyn Fn(glam::Vec3, glam::Vec3, f32) -> bool + '_>,
)> {
    match accel {
        Accel::Embree(_) => vec![(
            "embree",
            Box::new(|o, d, t| accel.unoccluded(Toward::Light, o, d, t)),
        )],
        Accel::Cwbvh(b) => ShadowOrder::ALL
            .into_iter()
            .map(|order| {
                let q: Box<dyn Fn(glam::Vec3, glam::Vec3, f32) -> bool + '_> =
                    Box::new(move |o, d, t| b.unoccluded_in(order, o, d, t).0);
                (order.describe(), q)
            })
            .collect(),
    }
}

#[test]
fn bvh_matches_brute_force_on_every_scene() {
    let backends = backends("bvh_matches_brute_force_on_every_scene");
    for (name, backend) in ["cornell", "door", "desk", "furnace"]
        .into_iter()
        .flat_map(|n| backends.iter().map(move |&b| (n, b)))
    {
        let scene = load_scene(&scene_path(name)).unwrap();
        let accel = Accel::build_with(&scene.triangles, backend).unwrap();
        let name = format!("{name} ({})", accel.name());
        let (lo, hi) = scene.bounds;
        let mut rng = Rng::new(21, 0, 0);
        let mut hits = 0;
        for _ in 0..20_000 {
            let u = glam::Vec3::new(rng.uniform(), rng.uniform(), rng.uniform());
            let o = lo + (hi - lo) * u;
            let d = sample_uniform_sphere(rng.uniform2());
            let mut best: Option<(f32, usize)> = None;
            for (i, t) in scene.triangles.iter().enumerate() {
                if let Some((t, _, _)) =
                    t.intersect(o, d, best.map(|b| b.0).unwrap_or(f32::INFINITY))
                {
                    best = Some((t, i));
                }
            }
            let got = accel.intersect(o, d, f32::INFINITY);
            // An origin within rounding distance of a surface makes "is it in front?"
            // ambiguous; the renderer never starts rays there (origins are offset).
            let eps = 1e-5;
            if scene
                .triangles
                .iter()
                .any(|t| t.intersect_range(o - eps * d, d, 0.0, 2.0 * eps).is_some())
            {
                continue;
            }
            match (best, got) {
                (None, None) => {}
                (Some((t, i)), Some(h)) => {
                    hits += 1;
                    // Möller–Trumbore's t carries rounding error proportional to the
                    // coordinates' magnitude; the BVH also starts its ray a little behind `o`.
                    let tol = 5e-5 * (1.0 + o.abs().max_element() + t);
                    assert!((t - h.t).abs() <= tol, "{name}: t {t} vs {}", h.t);
                    if h.triangle as usize != i {
                        // Only a tie (a shared edge or vertex) may pick another triangle.
                        let other =
                            scene.triangles[h.triangle as usize].intersect(o, d, f32::INFINITY);
                        assert!(
                            other.is_some_and(|(t2, _, _)| (t2 - t).abs() <= tol),
                            "{name}: different triangle"
                        );
                    }
                    // The barycentrics reported belong to the hit.
                    let p = scene.triangles[h.triangle as usize].point(h.b1, h.b2);
                    assert!(
                        (p - (o + h.t * d)).length() <= 1e-3 * (1.0 + o.length()),
                        "{name}: barycentrics"
                    );
                    for (order, unoccluded) in shadow_queries(&accel) {
                        assert!(
                            !unoccluded(o, d, h.t + tol),
                            "{name}, {order}: shadow ray missed a hit: o {o:?} d {d:?} t {} tri {}",
                            h.t,
                            h.triangle
                        );
                        assert!(
                            h.t <= tol || unoccluded(o, d, h.t - tol),
                            "{name}, {order}: shadow ray hit before the closest hit"
                        );
                    }
                }
                (b, g) => panic!("{name}: brute force {b:?} vs bvh {g:?}"),
            }
        }
        assert!(
            hits > 1000,
            "{name}: too few hits ({hits}) to mean anything"
        );
    }
}

/// Surfaces very close to a ray's origin are found (the CWBVH's node test alone culls boxes
/// left before t = 1e-4, which would let rays in corners pass through walls).
#[test]
fn surfaces_close_to_the_origin_are_hit() {
    let scene = load_scene(&scene_path("cornell")).unwrap();
    for backend in backends("surfaces_close_to_the_origin_are_hit") {
        let accel = Accel::build_with(&scene.triangles, backend).unwrap();
        let mut rng = Rng::new(22, 0, 0);
        for gap in [1e-3f32, 1e-4, 5e-5, 2e-5] {
            for _ in 0..1000 {
                // Just above the floor (y = 0) near the open front, clear of the blocks,
                // heading down at a random slant.
                let o = glam::Vec3::new(0.5 + 4.0 * rng.uniform(), gap, 0.2 + 0.3 * rng.uniform());
                let d = glam::Vec3::new(rng.uniform() - 0.5, -1.0, rng.uniform() - 0.5).normalize();
                let h = accel
                    .intersect(o, d, f32::INFINITY)
                    .expect("the floor is hit");
                assert!((h.t * -d.y - gap).abs() <= 1e-5, "gap {gap}: t {}", h.t);
                for (order, unoccluded) in shadow_queries(&accel) {
                    assert!(
                        !unoccluded(o, d, 1.0),
                        "{order}: gap {gap}: shadow ray passed through the floor"
                    );
                }
            }
        }
    }
}

/// Axis-aligned directions, negative zeros included (`-Vec3::Y` is `(-0, -1, -0)`), hit what
/// they point at: obvhs alone misses them.
#[test]
fn axis_aligned_rays_with_negative_zeros_hit() {
    let scene = load_scene(&scene_path("cornell")).unwrap();
    for backend in backends("axis_aligned_rays_with_negative_zeros_hit") {
        let accel = Accel::build_with(&scene.triangles, backend).unwrap();
        let o = glam::Vec3::new(4.2, 1.0, 1.2);
        for (d, what) in [
            (-glam::Vec3::Y, "floor"),
            (glam::Vec3::Y, "ceiling"),
            (glam::Vec3::Z, "back wall"),
            (-glam::Vec3::X, "green wall"),
            (glam::Vec3::X, "red wall"),
        ] {
            let h = accel.intersect(o, d, f32::INFINITY);
            assert!(h.is_some(), "{what}: missed along {d:?}");
            for (order, unoccluded) in shadow_queries(&accel) {
                assert!(
                    !unoccluded(o, d, 100.0),
                    "{order}: {what}: shadow ray passed"
                );
            }
        }
    }
}

/// The CWBVH chooses each kind of shadow ray's order from probe rays, and the choice is the
/// cheaper one where the orders differ most: on desk, rays toward the camera take the
/// far-reaching order; on door, whose light is behind a wall (blockers near the rays'
/// origins), rays toward the light stay near first; each tests at least a fifth fewer
/// nodes and triangles than the other order. The scenes as loaded on the CWBVH carry the
/// same choice.
#[test]
fn shadow_rays_take_the_cheaper_order() {
    use footprint::scene::accel::set_backend;
    for (name, toward, expected) in [
        ("desk", Toward::Camera, ShadowOrder::FarReaching),
        ("door", Toward::Light, ShadowOrder::NearFirst),
    ] {
        let scene = load_scene(&scene_path(name)).unwrap();
        let mut accel = Accel::build_with(&scene.triangles, Backend::Cwbvh).unwrap();
        let segments = scene.probe_shadow_segments(toward);
        assert!(
            segments.len() > 500,
            "{name}: {} probe rays",
            segments.len()
        );
        let (order, visits) = accel.choose_shadow_order(toward, &segments).unwrap();
        assert_eq!(order, expected, "{name}: visits per ray {visits:?}");
        let (cheaper, dearer) = match expected {
            ShadowOrder::FarReaching => (visits[1], visits[0]),
            ShadowOrder::NearFirst => (visits[0], visits[1]),
        };
        assert!(cheaper < 0.8 * dearer, "{name}: visits per ray {visits:?}");
        // As loaded (this test's process only: nextest runs each test in its own).
        set_backend(Backend::Cwbvh);
        let loaded = load_scene(&scene_path(name)).unwrap();
        let Accel::Cwbvh(b) = &*loaded.bvh else {
            panic!("{name}: the CWBVH was asked for");
        };
        assert_eq!(b.shadow_order(toward), expected, "{name} as loaded");
    }
}
