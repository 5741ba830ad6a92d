//! Density estimates of photons and importons against independent estimates, importons
//! behind coloured glass, and spot emission sampling.

use crate::common::chi2::ChiSquareTest;
use crate::common::{mean_stderr, scene_path, sidak, t_critical};
use crate::{pass_settings, temp_dir};
use footprint::Rgb;
use footprint::guide::particle_map::{MapKind, ParticleInput, ParticleMap};
use footprint::guide::sampler::GuidedSampler;
use footprint::math::{Frame, PI};
use footprint::rng::Rng;
use footprint::sampling::sample_cosine_hemisphere;
use footprint::scene::Scene;
use footprint::scene::load::load_scene;
use footprint_integrators::integrator::path_tracing::radiance_along;
use footprint_integrators::passes::{light_pass, view_pass};
use glam::Vec3;

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
    let points = [
        surface_point(&scene, Vec3::new(4.2, 1.0, 1.2), -Vec3::Y), // floor, front right
        surface_point(&scene, Vec3::new(1.2, 3.5, 2.0), Vec3::Z),  // back wall, left
        surface_point(&scene, Vec3::new(4.0, 3.0, 1.5), Vec3::X),  // red wall
        surface_point(&scene, Vec3::new(1.0, 4.0, 1.0), Vec3::Y),  // ceiling, front
    ];
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
        let o = scene.offset_origin(*p, *n);
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
    importon_density_matches_camera_importance(load_scene(&scene_path("cornell")).unwrap(), 16);
}

/// The same through a thin lens (radius 0.3, focused in front of the back wall): importons
/// leave from points of the lens, and the importance at a point is the mean over the lens
/// of what a connection to each lens point carries (a 64 x 64 grid of lens samples,
/// unoccluded ones only). Eight batches: the importons' normalisation and spread from the
/// lens are what this checks (at these points, near the plane in focus, the lens changes the
/// importance by under 1%; the images' blur is `tests/mitsuba.rs`'s `thin_lens` cases).
#[test]
fn importon_density_matches_thin_lens_importance_on_cornell() {
    let mut scene = load_scene(&scene_path("cornell")).unwrap();
    scene.camera = scene.camera.clone().with_lens(0.3, 11.0).unwrap();
    importon_density_matches_camera_importance(scene, 8);
}

fn importon_density_matches_camera_importance(scene: Scene, batches: u64) {
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
    // The importance at a point: a connection's, averaged over the lens (one sample for the
    // pinhole).
    let side = if cam.has_lens() { 64 } else { 1 };
    for (i, (p, n)) in points.iter().enumerate() {
        let mut expect = 0.0f64;
        for k in 0..side * side {
            let u = glam::Vec2::new((k % side) as f32 + 0.5, (k / side) as f32 + 0.5) / side as f32;
            if let Some(conn) = cam.connect(*p, u) {
                if !cam.has_lens() || scene.visible(*p, *n, conn.lens, None) {
                    expect += (conn.we_geom * conn.dir_to_camera.dot(*n).abs()) as f64;
                }
            }
        }
        expect /= (side * side) as f64;
        let (m, se) = mean_stderr(&est[i]);
        let t = (m - expect).abs() / se;
        eprintln!(
            "point {i}: importons {m:.5} ± {se:.5}, camera importance {expect:.5}, |t| {t:.2}"
        );
        assert!(t <= crit, "point {i}: importance {m} vs {expect}");
    }
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
    obj += &crate::common::box_obj([-0.5, -0.5, -0.05], [0.5, 0.5, 0.05], 1, "glass");
    obj += &crate::common::box_obj([-3.0, -3.0, 2.0], [3.0, 3.0, 2.2], 9, "wall");
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
