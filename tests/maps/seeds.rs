//! The photon map's cache seeds: the particles of a view pass's first `seed_paths` paths,
//! the same whether the pass shot only those (path tracing) or more (the combined image,
//! `auto`'s pilot), so that every method that reads the photon map builds the same cache.

use crate::common::scene_path;
use crate::pass_settings;
use footprint::guide::sampler::GuidedSampler;
use footprint::scene::load::load_scene;
use footprint_integrators::Method;
use footprint_integrators::maps::run_passes;
use footprint_integrators::passes::{
    PassOutput, SEED_PASS_SHARE, seed_paths, view_pass, view_pass_seeding,
};

/// The same particles in the same order, bit for bit.
fn assert_same_particles(a: &PassOutput, b: &PassOutput, what: &str) {
    assert_eq!(
        a.particles.len(),
        b.particles.len(),
        "{what}: particle counts"
    );
    for (p, q) in a.particles.iter().zip(&b.particles) {
        let bits = |v: glam::Vec3| v.to_array().map(f32::to_bits);
        assert_eq!(
            (bits(p.position), bits(p.dir), bits(p.weight), p.depth),
            (bits(q.position), bits(q.dir), bits(q.weight), q.depth),
            "{what}"
        );
    }
}

/// Each pass shoots its `[maps]` count, except path tracing's view pass, whose importons
/// only seed the photon map's cache: it shoots `seed_paths` of them. Light tracing's light
/// pass seeds the importance map's cache and keeps its count; the combined image reads both
/// maps. Fails if the share is applied to a pass whose map is read.
#[test]
fn only_a_view_pass_that_seeds_alone_shoots_fewer_paths() {
    let mut door = load_scene(&scene_path("door")).unwrap();
    door.maps.photons = 8_000;
    door.maps.importons = 12_000;
    let params = footprint::settings::GuideParams::default();
    let pass = pass_settings(0, 5);
    let paths = |method: &str| {
        let p = run_passes(&door, &Method::parse(method).unwrap(), &params, &pass);
        (
            p.light.map(|l| l.stats.paths),
            p.view.map(|v| v.stats.paths),
        )
    };
    let quarter = (12_000.0 * SEED_PASS_SHARE) as usize;
    assert_eq!(seed_paths(12_000), quarter);
    assert!(quarter < 12_000);
    assert_eq!(paths("pt-footprint"), (Some(8_000), Some(quarter)));
    assert_eq!(paths("lt-footprint"), (Some(8_000), Some(12_000)));
    assert_eq!(paths("combined-footprint"), (Some(8_000), Some(12_000)));
    assert_eq!(paths("pt-bsdf"), (None, None));
}

/// Path tracing's view pass and the combined image's give the photon cache the same seeds:
/// the first paths of a pass do not depend on how many follow (each path its own stream,
/// the pass's `1 / N` applied at the end), and the combined image's cache reads only those
/// paths' particles. Fails if a path's particles depended on the pass's size, or if the
/// larger pass's cache read all its particles.
#[test]
fn path_tracing_and_the_combined_image_seed_the_photon_cache_alike() {
    let mut door = load_scene(&scene_path("door")).unwrap();
    door.maps.photons = 4_000;
    door.maps.importons = 10_003; // odd: 1 / N is no power of two apart from 1 / (N / 4)
    let params = footprint::settings::GuideParams::default();
    let pass = pass_settings(0, 17);
    let view = |method: &str| {
        run_passes(&door, &Method::parse(method).unwrap(), &params, &pass)
            .view
            .unwrap()
    };
    let (pt, combined) = (view("pt-footprint"), view("combined-footprint"));
    assert!(combined.particles.len() > 2 * pt.particles.len());
    let (a, b) = (pt.photon_cache_seeds(), combined.photon_cache_seeds());
    assert_eq!(
        a.len(),
        pt.particles.len(),
        "path tracing's cache reads every importon"
    );
    assert_eq!(
        a.len(),
        b.len(),
        "the combined image's cache reads the first paths'"
    );
    for (s, t) in a.iter().zip(&b) {
        assert_eq!(
            (s.position.to_array(), s.normal.to_array()),
            (t.position.to_array(), t.normal.to_array())
        );
    }
}

/// A view pass traced as its seeding paths and then the rest is the pass traced at once:
/// the same particles, weights included, whether it keeps them all or thins them within a
/// small budget; a thinned pass no longer counts its seeding paths' particles, and its cache
/// reads them all.
#[test]
fn a_view_pass_traced_in_two_parts_is_the_pass() {
    let scene = load_scene(&scene_path("cornell")).unwrap();
    let bsdf = GuidedSampler::bsdf();
    for max_particles in [usize::MAX, 3_000] {
        let s = footprint_integrators::passes::PassSettings {
            max_particles,
            ..pass_settings(4_001, 3)
        };
        let whole = view_pass_seeding(&scene, &s, &bsdf, s.paths);
        for k in [1, 1_000, 2_500] {
            let split = view_pass_seeding(&scene, &s, &bsdf, k);
            assert_same_particles(&split, &whole, &format!("{k} first, max {max_particles}"));
            assert_eq!(split.stats.thinning, whole.stats.thinning);
            if whole.stats.thinning == 0 {
                let first = view_pass(&scene, &pass_settings(k, 3), &bsdf);
                assert_eq!(split.stats.seed_particles, Some(first.particles.len()));
            } else {
                assert_eq!(split.stats.seed_particles, None);
                assert_eq!(split.photon_cache_seeds().len(), split.particles.len());
            }
        }
        assert_eq!(whole.stats.thinning > 0, max_particles < usize::MAX);
    }
}
