//! The map itself: half-float weights, the k-nearest query against brute force, the density
//! grid's bound, and the memory per particle.

use crate::random_particles;
use footprint::Rgb;
use footprint::guide::particle_map::{
    MapKind, NORMAL_COS_MIN, PLANE_FRACTION, ParticleInput, ParticleMap, f16_to_f32, weight_to_f16,
};
use footprint::rng::Rng;
use glam::Vec3;

#[test]
fn half_floats_round_trip() {
    for x in [1.0f32, 0.5, 3.14159, 1e-3, 6.1e-5, 1e-6, 32768.0, 65504.0] {
        let y = f16_to_f32(weight_to_f16(x));
        let tol = if x >= 6.2e-5 { x * 1e-3 } else { 6e-8 };
        assert!((x - y).abs() <= tol, "{x} -> {y}");
    }
    assert_eq!(weight_to_f16(-1.0), 0);
    assert_eq!(weight_to_f16(f32::NAN), 0);
    assert_eq!(f16_to_f32(weight_to_f16(1e9)), 65504.0);
}

/// The query returns exactly the `k` nearest particles that pass the exclusion rules (the
/// stored normal within the cone, near the tangent plane, positive contribution), nearest
/// first, and reports fewer when fewer exist; a brute-force loop is the reference.
#[test]
fn knn_query_matches_brute_force_with_exclusions() {
    // In the map's own (spatial) order, so that particle `i` is the map's particle `i`.
    let particles = ParticleMap::spatial_order(&random_particles(20_000, 1));
    let map = ParticleMap::build(MapKind::Photons, &particles);
    assert_eq!(map.len(), particles.len());
    let mut rng = Rng::new(2, 0, 0);
    let mut out = Vec::new();
    let mut fewer = 0;
    let mut ruled_out = 0;
    for q in 0..400 {
        let x = Vec3::new(
            rng.uniform() * 2.0 - 1.0,
            rng.uniform() * 0.4 - 0.2,
            rng.uniform() * 2.0 - 1.0,
        );
        let n = if q % 2 == 0 { Vec3::Y } else { -Vec3::Y };
        let k = [1, 10, 50, 200][q % 4];
        let max_dist = [0.05, 0.2, 0.6][q % 3];
        // Contribution: zero for particles coming from "below" some tilted plane.
        let tilt = Vec3::new(0.3, 1.0, 0.2).normalize();
        let contribution = |dir: Vec3, w: Rgb| {
            if dir.dot(tilt) > -0.2 {
                w.x + w.y + w.z
            } else {
                0.0
            }
        };
        let got = map.query(
            x,
            n,
            k,
            max_dist,
            |nb| contribution(nb.dir, nb.weight),
            &mut out,
        );
        let mut brute: Vec<(f32, u32)> = (0..particles.len() as u32)
            .filter_map(|i| {
                let p = &particles[i as usize];
                let d2 = (p.position - x).length_squared();
                let (dir, normal, w) = map.get(i);
                let ok = d2 <= max_dist * max_dist
                    && normal.dot(n) >= NORMAL_COS_MIN
                    && map.plane_distance(i, x) <= PLANE_FRACTION * max_dist
                    && contribution(dir, w) > 0.0;
                ok.then_some((d2, i))
            })
            .collect();
        brute.sort_by(|a, b| a.0.total_cmp(&b.0));
        brute.truncate(k);
        assert_eq!(got, brute.len(), "query {q}: count");
        // The density grid's bound may only rule out queries that cannot find k.
        if !map.may_hold(x, n, k, max_dist) {
            assert!(
                got < k,
                "query {q}: may_hold said no, but {got} >= {k} were found"
            );
            ruled_out += 1;
        }
        let ids: Vec<u32> = out.iter().map(|nb| nb.index).collect();
        let expect: Vec<u32> = brute.iter().map(|b| b.1).collect();
        assert_eq!(ids, expect, "query {q}: particles");
        for w in out.windows(2) {
            assert!(w[0].dist2 <= w[1].dist2);
        }
        if got < k {
            fewer += 1;
        }
    }
    assert!(
        fewer > 10 && fewer < 390,
        "the cases should include both full and short answers ({fewer})"
    );
    eprintln!("{ruled_out} of {fewer} short answers were ruled out by the density bound alone");
}

/// At most 32 bytes per particle, kd-tree included, measured by a counting allocator. The
/// allocator counts every thread, so this test runs in a child process of its own (the
/// `FOOTPRINT_MEMORY_CHILD` variable), where nothing else allocates while the map is built.
#[test]
fn memory_is_at_most_32_bytes_per_particle() {
    if std::env::var_os("FOOTPRINT_MEMORY_CHILD").is_none() {
        // The test's name as libtest knows it: its module path without the crate's name.
        let path = concat!(module_path!(), "::memory_is_at_most_32_bytes_per_particle");
        let name = path.split_once("::").map_or(path, |(_, rest)| rest);
        let out = std::process::Command::new(std::env::current_exe().unwrap())
            .args(["--exact", name, "--nocapture", "--test-threads", "1"])
            .env("FOOTPRINT_MEMORY_CHILD", "1")
            .output()
            .unwrap();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        eprintln!("{text}");
        assert!(
            out.status.success() && text.contains("bytes per particle"),
            "child failed"
        );
        return;
    }
    for n in [100_000usize, 1_000_000] {
        let particles = random_particles(n, 3);
        let before = footprint::heap::heap_bytes();
        let map = ParticleMap::build(MapKind::Photons, &particles);
        let after = footprint::heap::heap_bytes();
        let bytes = after.saturating_sub(before) as f64 / map.len() as f64;
        eprintln!("{n} particles: {bytes:.2} bytes per particle");
        assert!(bytes <= 32.0, "{bytes} bytes per particle");
        assert!(
            bytes >= ParticleMap::RECORD_BYTES as f64 + 12.0,
            "the measurement misses the tree ({bytes})"
        );
        drop(map);
    }
}

/// The density grid's bound skips the search on the dark side of a wall: particles on the
/// +x face of a plane cannot serve a query facing -x, and `may_hold` says so without a search.
#[test]
fn the_back_of_a_wall_is_ruled_out_without_a_search() {
    let mut rng = Rng::new(8, 0, 0);
    let particles: Vec<ParticleInput> = (0..5000)
        .map(|_| ParticleInput {
            position: Vec3::new(0.0, rng.uniform(), rng.uniform()),
            dir: Vec3::X,
            normal: Vec3::X,
            weight: Rgb::ONE,
            depth: 1,
            specular_chain: true,
        })
        .collect();
    let map = ParticleMap::build(MapKind::Photons, &particles);
    let x = Vec3::new(-0.01, 0.5, 0.5);
    let mut out = Vec::new();
    assert!(!map.may_hold(x, -Vec3::X, 50, 0.2));
    assert_eq!(map.query(x, -Vec3::X, 50, 0.2, |_| 1.0, &mut out), 0);
    assert!(map.may_hold(x, Vec3::X, 50, 0.2));
    assert_eq!(map.query(x, Vec3::X, 50, 0.2, |_| 1.0, &mut out), 50);
}
