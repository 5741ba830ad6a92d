//! Particle maps: the k-nearest query against brute force (exclusion rules included), the
//! memory per particle, flux conservation of the light pass, photon and importon density
//! estimates against independent estimates, colour-filtered importance behind glass, spot
//! emission sampling, bad map settings, and the pictures of `footprint maps`.

mod common;

use common::chi2::ChiSquareTest;
use common::{mean_stderr, scene_path, sidak, t_critical};
use footprint::Rgb;
use footprint::guide::particle_map::{
    MapKind, NORMAL_COS_MIN, PLANE_FRACTION, ParticleInput, ParticleMap, f16_to_f32, weight_to_f16,
};
use footprint::guide::sampler::GuidedSampler;
use footprint::math::{Frame, PI};
use footprint::rng::Rng;
use footprint::sampling::sample_cosine_hemisphere;
use footprint::scene::Scene;
use footprint::scene::geometry::offset_ray_origin;
use footprint::scene::load::load_scene;
use footprint_app::map_picture::{PICTURE_K, density_picture};
use footprint_integrators::integrator::path_tracing::radiance_along;
use footprint_integrators::passes::{PassSettings, light_pass, view_pass};
use glam::Vec3;
use std::path::PathBuf;

// The real heap footprint of a map, kd-tree included.
#[global_allocator]
static GLOBAL: footprint::heap::CountingAlloc = footprint::heap::CountingAlloc;

fn random_particles(n: usize, seed: u64) -> Vec<ParticleInput> {
    let mut rng = Rng::new(seed, 0, 0);
    let normals = [Vec3::Y, -Vec3::Y, Vec3::X, Vec3::new(0.0, 0.6, 0.8)];
    (0..n)
        .map(|i| {
            let normal = normals[i % normals.len()];
            let f = Frame::from_z(normal);
            // Points scattered around four planes through the origin region, with some offset
            // off the plane, so that the plane and normal rules both matter.
            let p = f.to_world(Vec3::new(
                rng.uniform() * 2.0 - 1.0,
                rng.uniform() * 2.0 - 1.0,
                (rng.uniform() - 0.5) * 0.2,
            ));
            ParticleInput {
                position: p,
                dir: f.to_world(sample_cosine_hemisphere(rng.uniform2())),
                normal,
                weight: Rgb::new(rng.uniform(), rng.uniform(), rng.uniform()) + Rgb::splat(0.01),
                depth: 1,
                specular_chain: true,
            }
        })
        .collect()
}

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
        let out = std::process::Command::new(std::env::current_exe().unwrap())
            .args([
                "--exact",
                "memory_is_at_most_32_bytes_per_particle",
                "--nocapture",
                "--test-threads",
                "1",
            ])
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

fn pass_settings(paths: usize, seed: u64) -> PassSettings {
    PassSettings {
        paths,
        max_depth: 16,
        rr_depth: footprint::settings::DEFAULT_RR_DEPTH,
        seed,
        soft_glossy_max: 100.0,
        specialise: true,
        target: None,
    }
}

/// The diffuse albedo of the surface a particle lies on, found by a ray down its normal.
fn albedo_at(scene: &Scene, p: &ParticleInput) -> Rgb {
    let o = p.position + p.normal * 1e-3;
    let h = scene
        .intersect(o, -p.normal, 1e-2)
        .unwrap_or_else(|| panic!("no surface under the particle at {}", p.position));
    scene.materials[h.material as usize].kd
}

/// Flux conservation on cornell (all surfaces diffuse, one light): every photon's first hit
/// is stored with the emitted flux per path, so first-hit flux plus the flux escaping
/// straight out of the open front equals the emitted power; and the flux stored at second
/// hits plus what escapes after the first bounce equals the first-hit flux times each hit
/// surface's reflectance share (no Russian roulette before the second hit, and a diffuse
/// bounce's weight is exactly its albedo), up to float rounding.
#[test]
fn light_pass_conserves_flux_on_cornell() {
    let scene = load_scene(&scene_path("cornell")).unwrap();
    let out = light_pass(&scene, &pass_settings(200_000, 5), &GuidedSampler::bsdf());
    let s = &out.stats;
    // Sums in double precision: 10^5 single-precision additions drift by ~1e-3.
    let sum =
        |it: &mut dyn Iterator<Item = Rgb>| it.fold(glam::DVec3::ZERO, |a, w| a + w.as_dvec3());
    let first = sum(&mut out
        .particles
        .iter()
        .filter(|p| p.depth == 1)
        .map(|p| p.weight));
    let second = sum(&mut out
        .particles
        .iter()
        .filter(|p| p.depth == 2)
        .map(|p| p.weight));
    let reflected = sum(&mut out
        .particles
        .iter()
        .filter(|p| p.depth == 1)
        .map(|p| p.weight * albedo_at(&scene, p)));
    let emitted = s.emitted.as_dvec3();
    let escaped0 = s.escaped.first().copied().unwrap_or_default().as_dvec3();
    let escaped1 = s.escaped.get(1).copied().unwrap_or_default().as_dvec3();
    eprintln!(
        "emitted {emitted}, first {first}, escaped {escaped0}; reflected {reflected}, second {second}, escaped {escaped1}"
    );
    let rel = |a: glam::DVec3, b: glam::DVec3| {
        ((a - b).abs() / b.max(glam::DVec3::splat(1e-9))).max_element()
    };
    assert!(rel(first + escaped0, emitted) < 1e-3, "first hits");
    assert!(
        escaped0.max_element() > 0.0 && escaped1.max_element() > 0.0,
        "cornell's open front lets some flux out"
    );
    assert!(rel(second + escaped1, reflected) < 1e-3, "second hits");
}

/// A point on the surface seen from `from` along `dir`, and its normal toward `from`.
fn surface_point(scene: &Scene, from: Vec3, dir: Vec3) -> (Vec3, Vec3) {
    let h = scene
        .intersect(from, dir.normalize(), f32::INFINITY)
        .unwrap_or_else(|| panic!("no surface from {from} along {dir}"));
    let n = if h.ng.dot(dir) < 0.0 { h.ng } else { -h.ng };
    (h.p, n)
}

/// Photon density estimates of irradiance at fixed points on cornell agree with an
/// independent estimate (direct light by light sampling plus indirect light by cosine-sampled
/// path tracing). The photon estimate's standard error comes from 16 independent light
/// passes (batch means); the path-traced one from its samples. Two-sided t-test at 0.01,
/// Šidák-corrected over the points, 15 degrees of freedom (the smaller sample). The disc
/// radius (0.2 m in a 5.5 m box, on flat areas clear of edges) keeps the kernel's blur well
/// below the noise.
#[test]
fn photon_irradiance_agrees_with_path_tracing_on_cornell() {
    let scene = load_scene(&scene_path("cornell")).unwrap();
    let centre = Vec3::new(2.78, 2.74, 2.8);
    let points = [
        surface_point(&scene, Vec3::new(4.2, 1.0, 1.2), -Vec3::Y), // floor, front right
        surface_point(&scene, Vec3::new(1.2, 3.5, 2.0), Vec3::Z),  // back wall, left
        surface_point(&scene, Vec3::new(4.0, 3.0, 1.5), Vec3::X),  // red wall
        surface_point(&scene, Vec3::new(1.0, 4.0, 1.0), Vec3::Y),  // ceiling, front
    ];
    let _ = centre;
    let r = 0.2f32;
    let batches = 16;
    let mut photon_est = vec![Vec::new(); points.len()];
    let mut buf = Vec::new();
    for b in 0..batches {
        let out = light_pass(
            &scene,
            &pass_settings(150_000, 100 + b),
            &GuidedSampler::bsdf(),
        );
        let map = ParticleMap::build(MapKind::Photons, &out.particles);
        for (i, (p, n)) in points.iter().enumerate() {
            map.query(*p, *n, usize::MAX, r, |_| 1.0, &mut buf);
            let e: Rgb = buf.iter().map(|nb| nb.weight).sum::<Rgb>() / (PI * r * r);
            photon_est[i].push(e.x as f64);
        }
    }
    let crit = t_critical(sidak(0.01, points.len()), (batches - 1) as f64);
    let mut rng = Rng::new(77, 0, 0);
    for (i, (p, n)) in points.iter().enumerate() {
        let (pm, pse) = mean_stderr(&photon_est[i]);
        // Independent estimate: E = E_direct + E_indirect (red channel).
        let m = 40_000;
        let frame = Frame::from_z(*n);
        let o = offset_ray_origin(*p, *n);
        let xs: Vec<f64> = (0..m)
            .map(|_| {
                // Direct: one light sample.
                let (li, pmf) = scene.light_distribution.sample(rng.uniform());
                let mut e = 0.0;
                if let Some(ls) = scene.lights[li].sample_li(*p, rng.uniform2()) {
                    let cos = ls.wi.dot(*n);
                    if cos > 0.0 && scene.visible(*p, *n, ls.p, ls.n) {
                        e += (ls.li.x * cos / (ls.pdf_w * pmf)) as f64;
                    }
                }
                // Indirect: a cosine-sampled ray, emission at its first hit removed.
                let d = frame.to_world(sample_cosine_hemisphere(rng.uniform2()));
                let mut l = radiance_along(&scene, o, d, 16, &mut rng);
                if let Some(h) = scene.intersect(o, d, f32::INFINITY) {
                    if let Some(li) = h.light {
                        l -= scene.lights[li as usize].emitted(-d);
                    }
                }
                e + (PI * l.x) as f64
            })
            .collect();
        let (em, ese) = mean_stderr(&xs);
        let se = (pse * pse + ese * ese).sqrt();
        let t = (pm - em).abs() / se;
        eprintln!(
            "point {i}: photons {pm:.4} ± {pse:.4}, path traced {em:.4} ± {ese:.4}, |t| {t:.2} (critical {crit:.2})"
        );
        assert!(
            t <= crit,
            "point {i}: photon irradiance {pm} vs path-traced {em}"
        );
    }
}

/// Importons' first hits estimate the camera's importance: the density estimate
/// `Σ W_p / (π r²)` at a point equals `W_e(ω) cos θ_cam / d² · cos θ_x` (importance
/// irradiance from the camera, normalised over the image). Batch-mean standard errors,
/// t-test as above.
#[test]
fn importon_density_matches_camera_importance_on_cornell() {
    let scene = load_scene(&scene_path("cornell")).unwrap();
    let cam = &scene.camera;
    let points = [
        surface_point(
            &scene,
            cam.position,
            Vec3::new(2.78, 2.74, 5.59) - cam.position,
        ),
        surface_point(
            &scene,
            cam.position,
            Vec3::new(1.0, 4.0, 5.59) - cam.position,
        ),
        surface_point(
            &scene,
            cam.position,
            Vec3::new(4.2, 0.0, 1.5) - cam.position,
        ),
    ];
    let r = 0.15f32;
    let batches = 16;
    let mut est = vec![Vec::new(); points.len()];
    let mut buf = Vec::new();
    for b in 0..batches {
        let out = view_pass(
            &scene,
            &pass_settings(100_000, 200 + b),
            &GuidedSampler::bsdf(),
        );
        let first: Vec<ParticleInput> = out
            .particles
            .iter()
            .filter(|p| p.depth == 1)
            .copied()
            .collect();
        let map = ParticleMap::build(MapKind::Importons, &first);
        for (i, (p, n)) in points.iter().enumerate() {
            map.query(*p, *n, usize::MAX, r, |_| 1.0, &mut buf);
            let w: Rgb = buf.iter().map(|nb| nb.weight).sum::<Rgb>() / (PI * r * r);
            est[i].push(w.y as f64);
        }
    }
    let crit = t_critical(sidak(0.01, points.len()), (batches - 1) as f64);
    for (i, (p, n)) in points.iter().enumerate() {
        let conn = cam.connect(*p).unwrap();
        let expect = (conn.we_geom * conn.dir_to_camera.dot(*n).abs()) as f64;
        let (m, se) = mean_stderr(&est[i]);
        let t = (m - expect).abs() / se;
        eprintln!(
            "point {i}: importons {m:.5} ± {se:.5}, camera importance {expect:.5}, |t| {t:.2}"
        );
        assert!(t <= crit, "point {i}: importance {m} vs {expect}");
    }
}

// ---- Scenes written by the tests ----

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("footprint-maps-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Behind a coloured glass pane, importons carry the pane's colour: an importon that reached
/// the wall through the pane (a specular chain through both interfaces) has `W_p` in the
/// ratio of `Tf`; one that reached it directly has grey `W_p`.
#[test]
fn importons_behind_coloured_glass_carry_its_colour() {
    let d = temp_dir("glass");
    let tf = Rgb::new(0.9, 0.5, 0.2);
    let mtl = format!(
        "newmtl glass\nKd 0 0 0\nNi 1.5\nTf {} {} {}\nillum 7\nnewmtl wall\nKd 0.6 0.6 0.6\nillum 1\n",
        tf.x, tf.y, tf.z
    );
    let mut obj = "mtllib m.mtl\n".to_string();
    obj += &common::box_obj([-0.5, -0.5, -0.05], [0.5, 0.5, 0.05], 1, "glass");
    obj += &common::box_obj([-3.0, -3.0, 2.0], [3.0, 3.0, 2.2], 9, "wall");
    std::fs::write(d.join("m.mtl"), mtl).unwrap();
    std::fs::write(d.join("g.obj"), obj).unwrap();
    let toml = "[camera]\nposition = [0.0, 0.0, -3.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y = 40.0\nresolution = [64, 64]\n\
                [[mesh]]\nfile = \"g.obj\"\n[[light]]\ntype = \"point\"\nposition = [0.0, 2.0, -1.0]\nintensity = [1.0, 1.0, 1.0]\n";
    std::fs::write(d.join("s.toml"), toml).unwrap();
    let scene = load_scene(&d.join("s.toml")).unwrap();
    assert!(scene.effects.coloured_filtering && scene.effects.refraction);
    let out = view_pass(&scene, &pass_settings(100_000, 9), &GuidedSampler::bsdf());
    let on_wall = |p: &&ParticleInput| (p.position.z - 2.0).abs() < 1e-3;
    let (mut through, mut direct) = (0, 0);
    for p in out.particles.iter().filter(on_wall) {
        let ratio = p.weight / p.weight.x;
        if p.specular_chain && p.depth >= 3 {
            through += 1;
            let expect = tf / tf.x;
            assert!(
                (ratio - expect).abs().max_element() < 2e-3,
                "through glass: {ratio} vs {expect}"
            );
        } else if p.depth == 1 {
            direct += 1;
            assert!(
                (ratio - Rgb::ONE).abs().max_element() < 1e-5,
                "direct: {ratio}"
            );
        }
    }
    eprintln!("{through} importons through the pane, {direct} direct");
    assert!(through > 1000 && direct > 1000);
}

/// Spot lights emit in proportion to their falloff: `sample_le` directions against
/// `pdf_le_dir` (chi-square, significance 0.01).
#[test]
fn spot_emission_sampling_matches_its_pdf() {
    let scene = load_scene(&scene_path("desk")).unwrap();
    let light = &scene.lights[0];
    let test = ChiSquareTest {
        axis: -Vec3::Y,
        theta_max: 1.2,
        res_theta: 40,
        res_phi: 40,
        samples: 1_000_000,
        integration_res: 6,
        seed: 4,
    };
    let r = test.run(
        |rng| {
            light
                .sample_le(rng.uniform2(), rng.uniform2())
                .map(|e| e.dir)
        },
        |d| light.pdf_le_dir(d) as f64,
    );
    eprintln!("spot: chi2 {:.1} dof {} p {:.3}", r.chi2, r.dof, r.p_value);
    assert!(r.p_value > 0.01);
    assert!(
        (r.integral - 1.0).abs() < 1e-3,
        "the pdf integrates to {}",
        r.integral
    );
    // Every photon of the spot carries the same flux: the light's power.
    let mut rng = Rng::new(1, 0, 0);
    for _ in 0..1000 {
        let e = light.sample_le(rng.uniform2(), rng.uniform2()).unwrap();
        let flux = e.le / e.pdf_dir;
        assert!(
            (flux - light.power_rgb()).abs().max_element() < 1e-3 * light.power_rgb().max_element()
        );
    }
}

/// Zero or absurd particle counts and a zero maximum distance are errors naming the field.
#[test]
fn bad_map_settings_are_errors() {
    let run = |args: &[&str]| {
        let d = temp_dir(&format!(
            "bad-{}",
            args.join("").replace(['-', '.', '/'], "")
        ));
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_footprint"))
            .arg("maps")
            .arg(scene_path("cornell"))
            .arg("--out")
            .arg(&d)
            .args(args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr).to_string();
        assert!(!out.status.success(), "{args:?} should fail");
        assert!(!err.contains("panicked"));
        assert!(!d.join("photons.png").exists());
        err
    };
    assert!(run(&["--photons", "0"]).contains("--photons"));
    assert!(run(&["--importons", "99999999999"]).contains("absurd"));
    assert!(run(&["--max-dist", "0"]).contains("--max-dist"));
    assert!(run(&["--max-dist", "-1"]).contains("--max-dist"));
    // And in the scene file.
    let d = temp_dir("bad-toml");
    let text = std::fs::read_to_string(scene_path("cornell"))
        .unwrap()
        .replace(
            "cornell.obj",
            &scene_path("cornell")
                .with_file_name("cornell.obj")
                .display()
                .to_string(),
        );
    std::fs::write(
        d.join("s.toml"),
        format!("{text}\n[maps]\nmax_dist = 0.0\n"),
    )
    .unwrap();
    match load_scene(&d.join("s.toml")) {
        Err(e) => assert!(e.to_string().contains("maps.max_dist"), "{e}"),
        Ok(_) => panic!("max_dist = 0 accepted"),
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

/// `footprint maps`' pictures show where the particles are: with every photon of cornell the
/// whole visible surface has a density estimate; with only the photons of the box's left half
/// (x > 2.78, image left) the right half is the grey of "none" and the left half is coloured,
/// and a legend strip lies below the image.
#[test]
fn map_pictures_show_where_the_particles_are() {
    let mut scene = load_scene(&scene_path("cornell")).unwrap();
    let (w, h) = (64u32, 48u32);
    scene.camera = scene.camera.with_resolution(w, h).unwrap();
    let out = light_pass(&scene, &pass_settings(20_000, 5), &GuidedSampler::bsdf());
    let full = ParticleMap::build(MapKind::Photons, &out.particles);
    let pic = density_picture(&scene, &full, PICTURE_K);
    assert_eq!(pic.image.width, w);
    assert!(pic.image.height > h, "no legend strip");
    assert!(pic.covered > 0.95, "covered {}", pic.covered);
    let (lo, hi) = pic.range.unwrap();
    assert!(lo > 0.0 && hi > lo);
    let left: Vec<ParticleInput> = out
        .particles
        .iter()
        .filter(|p| p.position.x > 2.78)
        .cloned()
        .collect();
    let half = ParticleMap::build(MapKind::Photons, &left);
    let pic = density_picture(&scene, &half, PICTURE_K);
    assert!(
        pic.covered > 0.25 && pic.covered < 0.75,
        "covered {}",
        pic.covered
    );
    // "None" is a grey (a black pixel would be no surface at all).
    let grey = |x: u32, y: u32| {
        let p = pic.image.get(x, y);
        p.x == p.y && p.y == p.z && p.x > 0.0
    };
    for y in [h / 3, h / 2, 2 * h / 3] {
        assert!(!grey(w / 6, y), "left, row {y}: no estimate");
        assert!(
            grey(w - w / 6, y),
            "right, row {y}: an estimate without particles"
        );
    }
}

/// The maps of an unguided round on cornell, for guiding the passes of the next round.
fn first_round(scene: &Scene) -> footprint_integrators::maps::Guidance {
    let method = footprint_integrators::Method::parse("combined-footprint").unwrap();
    let params = footprint::settings::GuideParams::default();
    footprint_integrators::maps::Guidance::build(
        scene,
        &method,
        &params,
        &pass_settings(0, 77),
        &|| None,
    )
}

/// A light pass guided by an importance map (the maps refining each other) still conserves
/// flux, now in expectation: every guided direction weighs its photon by `f cos / pdf`, so
/// per batch the first hits plus the flux escaping at once equal the emitted power, and the
/// second hits plus the second escape equal the first hits times their albedo, up to noise.
/// t-tests on 16 batch values against the exact laws (Student's quantile at 0.01, Šidák over
/// 2 laws x 3 channels).
#[test]
fn a_guided_light_pass_conserves_flux_in_expectation() {
    let mut scene = load_scene(&scene_path("cornell")).unwrap();
    scene.maps.photons = 40_000;
    scene.maps.importons = 40_000;
    let g = first_round(&scene);
    let method = footprint_integrators::Method::parse("combined-footprint").unwrap();
    let params = footprint::settings::GuideParams::default();
    let sampler = g.light_sampler(&scene, &method, &params);
    let batches = 16;
    let (mut first_law, mut second_law) = (vec![Vec::new(); 3], vec![Vec::new(); 3]);
    let mut guided = 0;
    for b in 0..batches {
        let out = light_pass(&scene, &pass_settings(20_000, 300 + b), &sampler);
        guided += out.stats.guided_events - out.stats.fallbacks;
        let sum =
            |it: &mut dyn Iterator<Item = Rgb>| it.fold(glam::DVec3::ZERO, |a, w| a + w.as_dvec3());
        let first = sum(&mut out
            .particles
            .iter()
            .filter(|p| p.depth == 1)
            .map(|p| p.weight));
        let second = sum(&mut out
            .particles
            .iter()
            .filter(|p| p.depth == 2)
            .map(|p| p.weight));
        let reflected = sum(&mut out
            .particles
            .iter()
            .filter(|p| p.depth == 1)
            .map(|p| p.weight * albedo_at(&scene, p)));
        let e0 = out
            .stats
            .escaped
            .first()
            .copied()
            .unwrap_or_default()
            .as_dvec3();
        let e1 = out
            .stats
            .escaped
            .get(1)
            .copied()
            .unwrap_or_default()
            .as_dvec3();
        let emitted = out.stats.emitted.as_dvec3();
        for c in 0..3 {
            // Relative deviations from the laws, one value per batch.
            first_law[c].push((first[c] + e0[c]) / emitted[c] - 1.0);
            second_law[c].push((second[c] + e1[c]) / reflected[c] - 1.0);
        }
    }
    assert!(
        guided > 100_000,
        "the light pass was hardly guided ({guided} events)"
    );
    let crit = t_critical(sidak(0.01, 6), (batches - 1) as f64);
    for (law, devs) in [("first hits", &first_law), ("second hits", &second_law)] {
        for (c, d) in devs.iter().enumerate() {
            let (m, se) = mean_stderr(d);
            let t = m.abs() / se.max(1e-12);
            eprintln!("{law}, channel {c}: relative deviation {m:.5} ± {se:.5} (|t| {t:.2})");
            assert!(t <= crit, "{law}, channel {c}: {m} ± {se}");
        }
    }
}

/// A view pass guided by a photon map still carries the camera's importance: its first hits
/// are not guided (they leave the camera), and after the first guided bounce the importance
/// reaching the second hits plus what escapes equals the first hits' importance times their
/// albedo in expectation (t-tests on 16 batch values against 0, Student's quantile at 0.01,
/// Šidák over the channels).
#[test]
fn a_guided_view_pass_keeps_the_cameras_importance() {
    let mut scene = load_scene(&scene_path("cornell")).unwrap();
    scene.maps.photons = 40_000;
    scene.maps.importons = 40_000;
    let g = first_round(&scene);
    let method = footprint_integrators::Method::parse("combined-footprint").unwrap();
    let params = footprint::settings::GuideParams::default();
    let sampler = g.camera_sampler(&scene, &method, &params);
    let batches = 16;
    let mut law = vec![Vec::new(); 3];
    let mut guided = 0;
    for b in 0..batches {
        let out = view_pass(&scene, &pass_settings(20_000, 400 + b), &sampler);
        guided += out.stats.guided_events - out.stats.fallbacks;
        let sum =
            |it: &mut dyn Iterator<Item = Rgb>| it.fold(glam::DVec3::ZERO, |a, w| a + w.as_dvec3());
        let second = sum(&mut out
            .particles
            .iter()
            .filter(|p| p.depth == 2)
            .map(|p| p.weight));
        let reflected = sum(&mut out
            .particles
            .iter()
            .filter(|p| p.depth == 1)
            .map(|p| p.weight * albedo_at(&scene, p)));
        let e1 = out
            .stats
            .escaped
            .get(1)
            .copied()
            .unwrap_or_default()
            .as_dvec3();
        for c in 0..3 {
            law[c].push((second[c] + e1[c]) / reflected[c] - 1.0);
        }
    }
    assert!(
        guided > 50_000,
        "the view pass was hardly guided ({guided} events)"
    );
    let crit = t_critical(sidak(0.01, 3), (batches - 1) as f64);
    for (c, d) in law.iter().enumerate() {
        let (m, se) = mean_stderr(d);
        let t = m.abs() / se.max(1e-12);
        eprintln!("importance after the first bounce, channel {c}: {m:.5} ± {se:.5} (|t| {t:.2})");
        assert!(t <= crit, "channel {c}: {m} ± {se}");
    }
}

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
    assert!(!plain.summaries.iter().any(|s| s.contains("grown")));
    let grown = Guidance::build_within(&door, &method, &params, &pass, budget, &|| None);
    let line = grown
        .summaries
        .iter()
        .find(|s| s.contains("grown"))
        .expect("a summary of the growth");
    eprintln!("{line}");
    let paths = grown.photons.as_ref().unwrap().pass.stats.paths;
    // Neither the generous budget nor the path limit stops it: every doubling is taken.
    assert_eq!(paths, 20_000 << footprint_integrators::maps::MAX_GROWTHS);
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
    assert!(!kept.summaries.iter().any(|s| s.contains("grown")));
    let left = Some(10_000.0);
    let g =
        footprint_integrators::auto::chosen_guidance(&door, &chosen, plain_both, left, &|| None);
    assert_eq!(
        g.photons.as_ref().unwrap().pass.stats.paths,
        20_000 << footprint_integrators::maps::MAX_GROWTHS
    );
    assert!(g.summaries.iter().any(|s| s.contains("grown")));
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
    assert!(!g.summaries.iter().any(|s| s.contains("grown")));
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
