//! Particle maps: the k-nearest query against brute force (exclusion rules included), the
//! memory per particle, flux conservation of the light pass, photon and importon density
//! estimates against independent estimates, colour-filtered importance behind glass, spot
//! emission sampling, bad map settings, the photon cache's seeds, and the pictures of
//! `footprint maps`.
//!
//! The parts live in `tests/maps/`; this root holds what they share.

mod common;

#[path = "maps/command.rs"]
mod command;
#[path = "maps/estimates.rs"]
mod estimates;
#[path = "maps/flux.rs"]
mod flux;
#[path = "maps/growth.rs"]
mod growth;
#[path = "maps/query.rs"]
mod query;
#[path = "maps/seeds.rs"]
mod seeds;

use footprint::Rgb;
use footprint::guide::particle_map::ParticleInput;
use footprint::math::Frame;
use footprint::rng::Rng;
use footprint::sampling::sample_cosine_hemisphere;
use footprint_integrators::passes::PassSettings;
use glam::Vec3;
use std::path::PathBuf;

// The real heap footprint of a map, kd-tree included.
#[global_allocator]
static GLOBAL: footprint::heap::CountingAlloc = footprint::heap::CountingAlloc;

/// `n` particles scattered about four planes, with random directions and colours.
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

/// The particle passes' settings of `paths` paths from `seed`.
fn pass_settings(paths: usize, seed: u64) -> PassSettings {
    PassSettings {
        paths,
        max_depth: 16,
        rr_depth: footprint::settings::DEFAULT_RR_DEPTH,
        seed,
        soft_glossy_max: 100.0,
        specialise: true,
        target: None,
        max_particles: usize::MAX,
    }
}

/// A fresh folder for a scene or output written by a test.
fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("footprint-maps-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}
