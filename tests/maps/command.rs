//! `footprint maps`: bad settings are errors, and its pictures show where the particles are.

use crate::common::scene_path;
use crate::{pass_settings, temp_dir};
use footprint::guide::particle_map::{MapKind, ParticleInput, ParticleMap};
use footprint::guide::sampler::GuidedSampler;
use footprint::scene::load::load_scene;
use footprint_app::map_picture::{PICTURE_K, density_picture};
use footprint_integrators::passes::light_pass;

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
