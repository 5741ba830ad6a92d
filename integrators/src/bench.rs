//! `footprint bench`: closest-hit rays per second on `door` and path samples per second on
//! `cornell`, each measured for a fixed time on all threads.

use anyhow::Result;
use footprint::geometry::spawn_origin;
use footprint::loader::load_scene;
use footprint::rng::Rng;
use footprint::sampling::sample_uniform_sphere;
use footprint_integrators::{Integrator, RenderOptions, render};
use glam::Vec2;
use rayon::prelude::*;
use std::path::Path;
use std::time::Instant;

pub fn run(scenes: &Path, seconds: f64) -> Result<()> {
    let threads = rayon::current_num_threads();
    println!("footprint bench: {threads} threads, {seconds} s per measurement");

    // ---- Closest-hit rays on door: camera rays, then rays from their hits in uniform directions ----
    let door = load_scene(&scenes.join("door/door.toml"))?;
    let cam = &door.camera;
    let batch = 1u64 << 16;
    let start = Instant::now();
    let mut rays = 0u64;
    let mut round = 0u64;
    while start.elapsed().as_secs_f64() < seconds {
        let hits: u64 = (0..batch)
            .into_par_iter()
            .map(|i| {
                let mut rng = Rng::new(round, 7, i);
                let raster = rng.uniform2() * Vec2::new(cam.width as f32, cam.height as f32);
                let dir = cam.ray_dir(raster);
                // Rays cast: the camera ray, and a second one from its hit.
                let mut cast = 1u64;
                if let Some(h) = door.intersect(cam.position, dir, f32::INFINITY) {
                    let d2 = sample_uniform_sphere(rng.uniform2());
                    cast += 1;
                    std::hint::black_box(door.intersect(
                        spawn_origin(h.p, h.ng, d2),
                        d2,
                        f32::INFINITY,
                    ));
                }
                cast
            })
            .sum();
        rays += hits;
        round += 1;
    }
    let rps = rays as f64 / start.elapsed().as_secs_f64();
    println!(
        "door: {:.2} M closest-hit rays/s ({} triangles)",
        rps / 1e6,
        door.triangles.len()
    );

    // ---- Path samples on cornell ----
    let cornell = load_scene(&scenes.join("cornell/cornell.toml"))?;
    let mut opts = RenderOptions::from_scene(&cornell);
    opts.integrator = Integrator::Pt;
    opts.time = Some(seconds);
    let r = render(&cornell, &opts, |_| {});
    println!(
        "cornell: {:.3} M path samples/s (pt, max_depth {}, {}x{}, {} spp in {:.2} s)",
        r.paths as f64 / r.elapsed.as_secs_f64() / 1e6,
        opts.max_depth,
        cornell.camera.width,
        cornell.camera.height,
        r.passes,
        r.elapsed.as_secs_f64()
    );
    Ok(())
}
