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

    // ---- Particle maps: build time, and k = 50 queries on door's maps ----
    use footprint::particle_map::{MapKind, ParticleMap};
    use footprint_integrators::passes::{PassSettings, light_pass, view_pass};
    for paths in [50_000usize, 500_000] {
        let s = PassSettings {
            paths,
            max_depth: door.settings.max_depth,
            seed: 1,
            soft_glossy_max: door.maps.soft_glossy_max,
        };
        let pass = light_pass(&door, &s);
        let t = Instant::now();
        let map = ParticleMap::build(MapKind::Photons, &pass.particles);
        println!(
            "door photon map: {} particles built in {:.3} s ({} paths traced in {:.3} s)",
            map.len(),
            t.elapsed().as_secs_f64(),
            paths,
            pass.stats.time.as_secs_f64()
        );
    }
    let max_dist = door.map_max_dist();
    let s = PassSettings {
        paths: door.maps.photons,
        max_depth: door.settings.max_depth,
        seed: 1,
        soft_glossy_max: door.maps.soft_glossy_max,
    };
    for (kind, pass) in [
        (MapKind::Photons, light_pass(&door, &s)),
        (MapKind::Importons, view_pass(&door, &s)),
    ] {
        let map = ParticleMap::build(kind, &pass.particles);
        // Query points: where camera rays hit, the points a guided path tracer asks about.
        let points: Vec<(glam::Vec3, glam::Vec3)> = (0..4096u64)
            .filter_map(|i| {
                let mut rng = Rng::new(3, 9, i);
                let raster = rng.uniform2() * Vec2::new(cam.width as f32, cam.height as f32);
                let d = cam.ray_dir(raster);
                door.intersect(cam.position, d, f32::INFINITY)
                    .map(|h| (h.p, if h.ng.dot(d) < 0.0 { h.ng } else { -h.ng }))
            })
            .collect();
        let start = Instant::now();
        let mut queries = 0u64;
        let mut found = 0u64;
        while start.elapsed().as_secs_f64() < seconds {
            let (q, f) = points
                .par_iter()
                .map_init(Vec::new, |buf, (p, n)| {
                    (1u64, map.query(*p, *n, 50, max_dist, |_| 1.0, buf) as u64)
                })
                .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
            queries += q;
            found += f;
        }
        let qps = queries as f64 / start.elapsed().as_secs_f64();
        println!(
            "door {}: {:.3} M k=50 queries/s ({} particles, {:.1} found on average): one query costs as much as {:.0} closest-hit rays",
            kind.name(),
            qps / 1e6,
            map.len(),
            found as f64 / queries as f64,
            rps / qps
        );
    }

    // ---- Direction samplers: cost of one scattering event, single thread ----
    {
        use footprint::bsdf::TransportMode;
        use footprint::direction_sampler::{
            BsdfSampler, DirectionSampler, GuideParams, GuideState, ScatterPoint,
        };
        use footprint::footprint_sampler::FootprintSampler;
        use footprint::grid_sampler::GridSampler;
        let s = PassSettings {
            paths: door.maps.photons,
            max_depth: door.settings.max_depth,
            seed: 1,
            soft_glossy_max: door.maps.soft_glossy_max,
        };
        let map = ParticleMap::build(MapKind::Importons, &view_pass(&door, &s).particles);
        let hits: Vec<(footprint::geometry::SurfaceHit, glam::Vec3)> = (0..2000u64)
            .filter_map(|i| {
                let mut rng = Rng::new(5, 9, i);
                let raster = rng.uniform2() * Vec2::new(cam.width as f32, cam.height as f32);
                let d = cam.ray_dir(raster);
                door.intersect(cam.position, d, f32::INFINITY)
                    .map(|h| (h, -d))
            })
            .collect();
        let bsdfs: Vec<_> = hits.iter().map(|(h, _)| door.bsdf(h)).collect();
        let points: Vec<ScatterPoint> = hits
            .iter()
            .zip(&bsdfs)
            .map(|((h, wo), bsdf)| ScatterPoint {
                p: h.p,
                bsdf,
                wo: *wo,
                mode: TransportMode::Importance,
                throughput: footprint::Rgb::ONE,
            })
            .collect();
        let params = GuideParams::default();
        let fp = FootprintSampler::new(&map, params.clone(), max_dist, door.maps.soft_glossy_max);
        let grid = GridSampler::new(&map, params.clone(), max_dist, door.maps.soft_glossy_max);
        let samplers: [&dyn DirectionSampler; 3] = [&BsdfSampler, &grid, &fp];
        let mut rng = Rng::new(1, 2, 3);
        let mut buf = Vec::new();
        let reps = 5;
        let t = Instant::now();
        for _ in 0..reps {
            for at in &points {
                std::hint::black_box(map.query(
                    at.p,
                    at.side_normal(),
                    params.k_p,
                    max_dist,
                    |nb| at.contribution(nb.dir, nb.weight),
                    &mut buf,
                ));
            }
        }
        let query_ns = t.elapsed().as_nanos() as f64 / (reps * hits.len()) as f64;
        println!(
            "door importance map: {:.0} ns per k=50 query with contributions (single thread)",
            query_ns
        );
        for sampler in samplers {
            let mut state = GuideState::default();
            let (mut t_prep, mut t_sp) = (0.0f64, 0.0f64);
            for _ in 0..reps {
                for at in &points {
                    let t0 = Instant::now();
                    sampler.prepare(at, &mut state);
                    let t1 = Instant::now();
                    if let Some(s) = sampler.sample(at, &state, &mut rng) {
                        std::hint::black_box(sampler.pdf(at, &state, s.wi));
                    }
                    let t2 = Instant::now();
                    t_prep += (t1 - t0).as_secs_f64();
                    t_sp += (t2 - t1).as_secs_f64();
                }
            }
            let n = (reps * hits.len()) as f64;
            println!(
                "{:>9} sampler: prepare (query and build) {:.0} ns, sample + pdf {:.0} ns, per scattering event (single thread; {} of {} guided)",
                sampler.name(),
                t_prep / n * 1e9,
                t_sp / n * 1e9,
                state.prepared - state.fallbacks,
                state.prepared
            );
        }
    }

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
