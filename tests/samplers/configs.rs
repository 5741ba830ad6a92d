//! The particle configurations the sampler tests run: random, a tiny cone (a door gap),
//! grazing, normal and horizon, both hemispheres, one particle, contributions over 60 orders
//! of magnitude, flipped normals and narrow glossy lobes.

use crate::{diffuse, dir, glossy};
use footprint::Rgb;
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use footprint::guide::sampler::ScatterPoint;
use footprint::math::Frame;
use footprint::rng::Rng;
use footprint::sampling::{sample_cosine_hemisphere, sample_uniform_sphere};
use glam::Vec3;

pub struct Config {
    pub name: &'static str,
    pub particles: Vec<(Vec3, f32)>,
    pub bsdf: Bsdf,
    pub wo: Vec3,
    /// Harness region: axis and half-angle (π: whole sphere).
    pub axis: Vec3,
    pub theta_max: f64,
}

pub fn configs() -> Vec<Config> {
    let mut rng = Rng::new(31, 0, 0);
    let mut v = Vec::new();
    let sphere = |name, particles, bsdf, wo| Config {
        name,
        particles,
        bsdf,
        wo,
        axis: Vec3::Z,
        theta_max: std::f64::consts::PI,
    };
    // Random particles, cosine-distributed, random contributions.
    let random: Vec<(Vec3, f32)> = (0..50)
        .map(|_| {
            (
                sample_cosine_hemisphere(rng.uniform2()),
                0.1 + rng.uniform(),
            )
        })
        .collect();
    v.push(sphere("random", random.clone(), diffuse(), dir(30.0, 0.0)));
    // All particles in a tiny cone (the door gap), 0.01 rad around a direction at 60 degrees.
    let centre = dir(60.0, 40.0);
    let f = Frame::from_z(centre);
    let cone: Vec<(Vec3, f32)> = (0..50)
        .map(|_| {
            let a = 0.01 * rng.uniform().sqrt();
            let p = 6.283 * rng.uniform();
            (
                f.to_world(Vec3::new(a * p.cos(), a * p.sin(), 1.0))
                    .normalize(),
                1.0 + rng.uniform(),
            )
        })
        .collect();
    v.push(Config {
        name: "tiny cone",
        particles: cone,
        bsdf: diffuse(),
        wo: dir(10.0, 0.0),
        axis: centre,
        theta_max: 0.05,
    });
    // Grazing particles, cos θ_p from 1e-6 to 1e-2 (those under 1e-3 are left out).
    let grazing: Vec<(Vec3, f32)> = (0..50)
        .map(|i| {
            let c = 10f32.powf(-6.0 + 4.0 * i as f32 / 49.0);
            let s = (1.0 - c * c).sqrt();
            let p = 0.2 * i as f32;
            (Vec3::new(s * p.cos(), s * p.sin(), c), 1.0)
        })
        .collect();
    v.push(Config {
        name: "grazing",
        particles: grazing,
        bsdf: diffuse(),
        wo: dir(20.0, 0.0),
        axis: Vec3::Z,
        theta_max: std::f64::consts::PI,
    });
    // Exactly along the normal and exactly on the horizon.
    let mut normal_horizon: Vec<(Vec3, f32)> = (0..25).map(|_| (Vec3::Z, 1.0)).collect();
    normal_horizon.extend((0..25).map(|i| (dir(90.0, 14.4 * i as f32), 1.0)));
    v.push(sphere(
        "normal and horizon",
        normal_horizon,
        diffuse(),
        dir(45.0, 90.0),
    ));
    // Both hemispheres (transmission).
    let both: Vec<(Vec3, f32)> = (0..50)
        .map(|_| (sample_uniform_sphere(rng.uniform2()), 0.5 + rng.uniform()))
        .collect();
    v.push(sphere(
        "both hemispheres",
        both,
        diffuse(),
        dir(30.0, 200.0),
    ));
    // One particle.
    v.push(sphere(
        "one particle",
        vec![(dir(35.0, 120.0), 1.0)],
        diffuse(),
        dir(0.0, 0.0),
    ));
    // Contributions spanning 60 orders of magnitude, some zero.
    let span: Vec<(Vec3, f32)> = (0..50)
        .map(|i| {
            let c = if i % 7 == 0 {
                0.0
            } else {
                10f32.powf(-30.0 + 60.0 * i as f32 / 49.0)
            };
            (sample_cosine_hemisphere(rng.uniform2()), c)
        })
        .collect();
    v.push(sphere(
        "60 orders of magnitude, some zero",
        span,
        diffuse(),
        dir(50.0, 0.0),
    ));
    // Flipped normals: the geometric and shading normals point down, the path arrives from
    // above, so the side normal is +z again.
    let flipped = Bsdf::new(
        Lobes::Diffuse {
            kd: Rgb::splat(0.5),
        },
        -Vec3::Z,
        -Vec3::Z,
    );
    v.push(sphere(
        "flipped normals",
        random.clone(),
        flipped,
        dir(40.0, 10.0),
    ));
    // Glossy Blinn exponent 10^4: a lobe 0.02 rad wide around the mirror direction.
    let wo = dir(30.0, 0.0);
    let mirror = Vec3::new(-wo.x, -wo.y, wo.z);
    let near_mirror: Vec<(Vec3, f32)> = (0..50)
        .map(|_| {
            let f = Frame::from_z(mirror);
            let a = 0.05 * rng.uniform().sqrt();
            let p = 6.283 * rng.uniform();
            (
                f.to_world(Vec3::new(a * p.cos(), a * p.sin(), 1.0))
                    .normalize(),
                1.0,
            )
        })
        .collect();
    v.push(Config {
        name: "glossy n=1e4",
        particles: near_mirror,
        bsdf: glossy(1.0e4),
        wo,
        axis: mirror,
        theta_max: 0.12,
    });
    v.push(sphere("glossy n=30", random, glossy(30.0), dir(60.0, 0.0)));
    v
}

pub fn point<'a>(c: &'a Config) -> ScatterPoint<'a> {
    ScatterPoint {
        p: Vec3::ZERO,
        bsdf: &c.bsdf,
        wo: c.wo,
        mode: TransportMode::Radiance,
        throughput: Rgb::ONE,
    }
}
