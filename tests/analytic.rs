//! The analytic scene (as pbrt-v4's integrator tests): the camera inside a closed sphere
//! whose inner surface is Lambertian with albedo 0.5 and emits radiance 0.5, so that the
//! radiance is exactly `0.5 / (1 - 0.5) = 1` everywhere, whatever the tessellation. Both
//! integrators must find 1 within a bound derived from their standard error.
//!
//! Bound: each render is an independent estimate of the image; over `R` renders with
//! different seeds, the mean of the image means has a standard error estimated from their
//! spread. The test fails when `|mean - 1|` exceeds the two-sided Student-t critical value at
//! significance 0.01 (Šidák-corrected over the 6 channel x integrator tests) times that
//! standard error, plus the deterministic truncation bias `0.5^max_depth` (below 1e-19 here).

mod common;

use common::{mean_stderr, scene_path, sidak, t_critical};
use footprint::scene::load::load_scene;
use footprint_integrators::{Method, RenderOptions, render};

#[test]
fn furnace_radiance_is_one_for_both_integrators() {
    let scene = load_scene(&scene_path("furnace")).expect("furnace scene loads");
    let renders = 24;
    let tests = 6;
    let crit = t_critical(sidak(0.01, tests), (renders - 1) as f64);
    for integrator in ["pt", "lt"] {
        let mut means = [Vec::new(), Vec::new(), Vec::new()];
        for r in 0..renders {
            let opts = RenderOptions {
                method: Method::from_names(integrator, "bsdf").unwrap(),
                spp: 4,
                time: None,
                max_depth: 64,
                seed: 1000 + r as u64,
                ..Default::default()
            };
            let out = render(&scene, &opts, |_| {});
            assert!(out.image.all_valid(), "{integrator:?}: invalid pixel");
            assert_eq!(out.stats.rejected, 0);
            let m = out.image.mean();
            for c in 0..3 {
                means[c].push(m[c] as f64);
            }
        }
        for (c, m) in means.iter().enumerate() {
            let (mean, se) = mean_stderr(m);
            let bound = crit * se + 0.5f64.powi(64);
            eprintln!("{integrator:?} channel {c}: mean {mean:.5} ± {se:.5} (bound {bound:.5})");
            assert!(
                se > 0.0 && se < 0.02,
                "{integrator:?}: standard error {se} is implausible"
            );
            assert!(
                (mean - 1.0).abs() <= bound,
                "{integrator:?} channel {c}: mean radiance {mean} differs from 1 by more than {bound}"
            );
        }
    }
}

/// A convex Lambertian sphere (albedo 0.5) under a uniform environment of radiance `L`
/// (Mitsuba's `constant` emitter): every point of a convex surface sees only the environment,
/// so the sphere's radiance is exactly `0.5 L` (tessellated or not) and the background's is
/// `L`. Every integrator, guided or not, must find both (the light tracer cannot see the
/// environment directly, so only the sphere is checked for it).
///
/// Bound as above: per region and channel, the mean over `R` independent renders against
/// the exact value, Student-t at 0.01 Šidák-corrected over all tests, times the standard
/// error from the renders' spread.
#[test]
fn uniform_environment_lights_a_convex_sphere_exactly() {
    convex_sphere_under_uniform_environment(
        "diffuse",
        r#"<bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></bsdf>"#,
        (0.5, 0.5),
        &GUIDED_AND_NOT,
    );
}

/// The same with a blend (`blendbsdf`, weight 0.3) of two Lambertian BSDFs of albedo 0.2
/// and 0.9: the sphere's radiance is exactly `(0.7 · 0.2 + 0.3 · 0.9) L` = `0.41 L`, guided
/// or not.
#[test]
fn a_blend_under_a_uniform_environment_is_the_blend_of_its_albedos() {
    convex_sphere_under_uniform_environment(
        "blend",
        r#"<bsdf type="twosided"><bsdf type="blendbsdf"><float name="weight" value="0.3"/>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.2"/></bsdf>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.9"/></bsdf></bsdf></bsdf>"#,
        (0.41, 0.41),
        &GUIDED_AND_NOT,
    );
}

/// A blend (weight 0.5) of a perfect mirror and a Lambertian BSDF of albedo 0.5: exactly
/// `(0.5 · 1 + 0.5 · 0.5) L` = `0.75 L`. Directions from the mirror carry its weight alone,
/// with the probability of the pick times the lobe's (`crate::bsdf::blend`); Mitsuba 3.9.1's
/// `blendbsdf` adds the Lambertian density and value to a delta sample, and renders this
/// sphere at 0.69 L (docs/mitsuba.md). The light tracer sees the Lambertian half alone,
/// `0.25 L` (the mirror's image of the environment reaches the pinhole by no connection).
/// Not guided: a blend with a delta component is not where particles guide.
#[test]
fn a_blend_with_a_mirror_under_a_uniform_environment_is_exact() {
    convex_sphere_under_uniform_environment(
        "blend-mirror",
        r#"<bsdf type="blendbsdf"><float name="weight" value="0.5"/>
            <bsdf type="twosided"><bsdf type="conductor"><string name="material" value="none"/></bsdf></bsdf>
            <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></bsdf></bsdf>"#,
        (0.75, 0.25),
        &[("pt", "bsdf"), ("lt", "bsdf"), ("combined", "bsdf")],
    );
}

/// Every integrator with BSDF sampling, and the guided path tracer and combined image.
const GUIDED_AND_NOT: [(&str, &str); 5] = [
    ("pt", "bsdf"),
    ("lt", "bsdf"),
    ("combined", "bsdf"),
    ("pt", "footprint"),
    ("combined", "footprint"),
];

/// A sphere of BSDF `bsdf_xml` (Mitsuba XML) under a uniform environment `L`: radiance
/// exactly `factor · L` on the sphere (`lt_factor · L` for the light tracer) and `L` around
/// it, for each of `configs` (guided ones must guide at most of their vertices).
fn convex_sphere_under_uniform_environment(
    tag: &str,
    bsdf_xml: &str,
    (factor, lt_factor): (f64, f64),
    configs: &[(&str, &str)],
) {
    let dir = std::env::temp_dir().join(format!("footprint-env-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let xml = dir.join("scene.xml");
    std::fs::write(
        &xml,
        format!(
            r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="6"/></integrator>
  <sensor type="perspective"><float name="fov" value="30"/>
    <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/><rfilter type="box"/></film>
  </sensor>
  <emitter type="constant"><rgb name="radiance" value="1, 0.5, 0.25"/></emitter>
  <shape type="sphere"><float name="radius" value="1"/>
    {bsdf_xml}</shape>
</scene>"#
        ),
    )
    .unwrap();
    let mut scene = footprint::scene::mitsuba::load(&xml, &Default::default()).unwrap();
    assert!(scene.effects.environment);
    // Enough photons that the sphere's queries find k_p = 50 and guiding happens.
    scene.maps.photons = 400_000;
    scene.maps.importons = 50_000;
    let l = [1.0f64, 0.5, 0.25];
    let renders = 16;
    let crit = t_critical(sidak(0.01, configs.len() * 6), (renders - 1) as f64);
    // Sphere: the central 4x4 pixels; background: the four 2x2 corners.
    let sphere = |x: u32, y: u32| (6..10).contains(&x) && (6..10).contains(&y);
    let background = |x: u32, y: u32| (x < 2 || x >= 14) && (y < 2 || y >= 14);
    for &(integrator, guide) in configs {
        let mut samples = vec![
            [Vec::new(), Vec::new(), Vec::new()],
            [Vec::new(), Vec::new(), Vec::new()],
        ];
        for r in 0..renders {
            let opts = RenderOptions {
                method: Method::from_names(integrator, guide).unwrap(),
                spp: 16,
                time: None,
                max_depth: 6,
                seed: 500 + r as u64,
                passes: Default::default(),
                // Every photon here carries direct light (depth 1): keep them, so that guiding
                // happens.
                guide_params: footprint::settings::GuideParams {
                    min_depth: 1,
                    ..Default::default()
                },
                ..Default::default()
            };
            let out = render(&scene, &opts, |_| {});
            assert!(out.image.all_valid() && out.stats.rejected == 0);
            if guide == "footprint" {
                let g = &out.camera_guide;
                assert!(
                    g.prepared > 0 && g.fallbacks * 2 < g.prepared,
                    "{integrator:?}: guided at {} of {} vertices",
                    g.prepared - g.fallbacks,
                    g.prepared
                );
            }
            for (k, region) in [&sphere as &dyn Fn(u32, u32) -> bool, &background]
                .iter()
                .enumerate()
            {
                let mut sum = [0.0f64; 3];
                let mut n = 0.0;
                for y in 0..16 {
                    for x in 0..16 {
                        if region(x, y) {
                            let c = out.image.get(x, y);
                            sum[0] += c.x as f64;
                            sum[1] += c.y as f64;
                            sum[2] += c.z as f64;
                            n += 1.0;
                        }
                    }
                }
                for c in 0..3 {
                    samples[k][c].push(sum[c] / n);
                }
            }
        }
        let sphere_factor = if integrator == "lt" {
            lt_factor
        } else {
            factor
        };
        for (k, (name, factor)) in [("sphere", sphere_factor), ("background", 1.0)]
            .iter()
            .enumerate()
        {
            if k == 1 && integrator == "lt" {
                continue;
            }
            for c in 0..3 {
                let (mean, se) = mean_stderr(&samples[k][c]);
                let want = factor * l[c];
                eprintln!(
                    "{integrator:?}/{guide:?} {name} channel {c}: {mean:.5} ± {se:.5}, exact {want}"
                );
                assert!(
                    (mean - want).abs() <= crit * se + 1e-6,
                    "{integrator:?}/{guide:?} {name} channel {c}: {mean} ± {se}, exact {want}"
                );
            }
        }
    }
}
