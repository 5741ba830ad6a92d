//! `footprint bench`: closest-hit rays per second on `door`, the maps and samplers, the path
//! loop compiled for a scene's effects against the general one (cornell, desk and the
//! `--scene`), and path samples per second on `cornell`, each measured for a fixed time on
//! all threads.

use anyhow::Result;
use footprint::keyword::Keyword;
use footprint::rng::{Rng, Sequence};
use footprint::sampling::sample_uniform_sphere;
use footprint::scene::Scene;
use footprint::scene::load::load_scene;
use footprint_integrators::maps::Guidance;
use footprint_integrators::passes::{PassSettings, light_pass, view_pass};
use footprint_integrators::{Method, RenderOptions, render};
use glam::Vec2;
use rayon::prelude::*;
use std::path::Path;
use std::time::Instant;

/// Paired runs (a general and a specialised one, their order alternating) of each path-loop
/// measurement, each `seconds / LOOP_ROUNDS` long. Many short pairs rather than a few long
/// ones: the host's speed drifts over seconds and shifts both runs of a short pair alike, so
/// the median of the pairs' ratios settles where a few long pairs' does not
/// (docs/benchmarks.md).
const LOOP_ROUNDS: usize = 15;

/// Runs every measurement; `extra` is a scene (e.g. Veach Ajar) whose guided path
/// throughput is measured next to door's.
pub fn run(scenes: &Path, seconds: f64, extra: Option<(&Path, &Scene)>) -> Result<()> {
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
                        door.spawn_origin(h.p, h.ng, d2),
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
        "door: {:.2} M closest-hit rays/s ({} triangles, {})",
        rps / 1e6,
        door.triangles.len(),
        door.bvh.name()
    );

    // ---- Particle maps: build time, and k = 50 queries on door's maps ----
    use footprint::guide::particle_map::{MapKind, ParticleMap};
    let bsdf = footprint::guide::sampler::GuidedSampler::bsdf();
    for paths in [50_000usize, 500_000] {
        let s = PassSettings {
            paths,
            max_depth: door.settings.max_depth,
            rr_depth: footprint::settings::DEFAULT_RR_DEPTH,
            seed: 1,
            soft_glossy_max: door.maps.soft_glossy_max,
            specialise: true,
            target: None,
            max_particles: usize::MAX,
        };
        let pass = light_pass(&door, &s, &bsdf);
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
        rr_depth: footprint::settings::DEFAULT_RR_DEPTH,
        seed: 1,
        soft_glossy_max: door.maps.soft_glossy_max,
        specialise: true,
        target: None,
        max_particles: usize::MAX,
    };
    for (kind, pass) in [
        (MapKind::Photons, light_pass(&door, &s, &bsdf)),
        (MapKind::Importons, view_pass(&door, &s, &bsdf)),
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
        use footprint::guide::sampler::{SamplerState, ScatterPoint};
        let hits: Vec<(footprint::scene::geometry::SurfaceHit, glam::Vec3)> = (0..2000u64)
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
        let pass = PassSettings {
            paths: 0,
            max_depth: door.settings.max_depth,
            rr_depth: footprint::settings::DEFAULT_RR_DEPTH,
            seed: 1,
            soft_glossy_max: door.maps.soft_glossy_max,
            specialise: true,
            target: None,
            max_particles: usize::MAX,
        };
        // (method, cache, raster): footprints cached are measured sampled from their caps
        // (raster 0) and rasterised (the scene's `raster`).
        let raster = door.guide.raster;
        for (method, cache, raster) in [
            ("lt-bsdf", false, raster),
            ("lt-grid", false, raster),
            ("lt-footprint", false, raster),
            ("lt-grid", true, raster),
            ("lt-footprint", true, 0),
            ("lt-footprint", true, raster),
        ] {
            let method = Method::parse(method).map_err(anyhow::Error::msg)?;
            let params = footprint::settings::GuideParams {
                cache,
                raster,
                ..door.guide.clone()
            };
            let g = Guidance::build(&door, &method, &params, &pass, &|| None);
            let sampler = g.light_sampler(&door, &method, &params);
            let mut rng = Rng::new(1, 2, 3);
            let mut state = SamplerState::default();
            let reps = if cache || !method.guided() { 200 } else { 5 };
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
                "{:>9} guide, {}: prepare {:.0} ns, sample + pdf {:.0} ns per scattering event (single thread; {} of {} events at guiding surfaces guided)",
                method.guide.name(),
                if !method.guided() {
                    "no map".to_string()
                } else if !cache {
                    "per event (query and build)".to_string()
                } else if method.guide.name() == "footprint" && raster == 0 {
                    "cached (region lookup), sampled from the caps".to_string()
                } else if method.guide.name() == "footprint" {
                    format!("cached (region lookup), rasterised {raster}x{raster}")
                } else {
                    "cached (region lookup)".to_string()
                },
                t_prep / n * 1e9,
                t_sp / n * 1e9,
                state.prepared_events - state.fallbacks,
                state.prepared_events
            );
        }
    }

    // ---- Guided path throughput against unguided, map passes and caches excluded ----
    let door_path = scenes.join("door/door.toml");
    let mut throughput_scenes = vec![(door_path.as_path(), &door)];
    throughput_scenes.extend(extra);
    for (path, sc) in throughput_scenes {
        for (unguided, guided) in [("pt-bsdf", "pt-footprint"), ("lt-bsdf", "lt-footprint")] {
            let mut rate = [0.0f64; 2];
            for (k, m) in [unguided, guided].iter().enumerate() {
                let method = Method::parse(m).map_err(anyhow::Error::msg)?;
                let mut opts = RenderOptions::from_scene(sc, method);
                opts.time = Some(seconds);
                let r = render(sc, &opts, |_| {});
                rate[k] = r.paths as f64 / r.timings.tracing.as_secs_f64();
            }
            println!(
                "{}: {unguided} {:.3} M paths/s, {guided} {:.3} M paths/s (cached): ratio {:.2}",
                path.display(),
                rate[0] / 1e6,
                rate[1] / 1e6,
                rate[1] / rate[0]
            );
        }
    }

    // ---- The path loop compiled for the scene's effects against the general one ----
    let desk = load_scene(&scenes.join("desk/desk.toml"))?;
    let cornell_path = scenes.join("cornell/cornell.toml");
    let cornell = load_scene(&cornell_path)?;
    let desk_path = scenes.join("desk/desk.toml");
    let mut loop_scenes = vec![
        (cornell_path.as_path(), &cornell),
        (desk_path.as_path(), &desk),
    ];
    loop_scenes.extend(extra);
    for (path, sc) in loop_scenes {
        for m in ["pt-bsdf", "lt-bsdf"] {
            let method = Method::parse(m).map_err(anyhow::Error::msg)?;
            let mut opts = RenderOptions::from_scene(sc, method);
            opts.time = Some(seconds / LOOP_ROUNDS as f64);
            // Paired runs, each round a general and a specialised one back to back: the
            // ratio of each pair, and their median and range (a virtual machine's speed
            // drifts between runs seconds apart, which a ratio of separate bests does not
            // cancel).
            let mut best = [0.0f64; 2];
            let mut ratios = Vec::with_capacity(LOOP_ROUNDS);
            for round in 0..LOOP_ROUNDS {
                let mut rate = [0.0f64; 2];
                // The order alternates, so that a drift within a pair cancels over the rounds.
                let order = if round % 2 == 0 { [0, 1] } else { [1, 0] };
                for k in order {
                    opts.specialise = k == 1;
                    let r = render(sc, &opts, |_| {});
                    rate[k] = r.paths as f64 / r.timings.tracing.as_secs_f64();
                    best[k] = best[k].max(rate[k]);
                }
                ratios.push(rate[1] / rate[0]);
            }
            ratios.sort_by(f64::total_cmp);
            let quartile = |q: usize| ratios[(q * (LOOP_ROUNDS - 1) + 2) / 4];
            println!(
                "{}: {m} path loop, general {:.3} M paths/s, specialised ({}) {:.3} M paths/s (the best of {LOOP_ROUNDS}): ratio {:.3}, median of {LOOP_ROUNDS} paired runs (quartiles {:.3}-{:.3}, range {:.3}-{:.3})",
                path.display(),
                best[0] / 1e6,
                opts.specialisation(sc).name(),
                best[1] / 1e6,
                quartile(2),
                quartile(1),
                quartile(3),
                ratios[0],
                ratios[LOOP_ROUNDS - 1]
            );
        }
    }

    // ---- Path samples on cornell, with each number sequence ----
    let mut opts = RenderOptions::from_scene(&cornell, Method::default());
    opts.time = Some(seconds);
    let mut rate = Vec::new();
    for sequence in [Sequence::Independent, Sequence::Sobol] {
        opts.sequence = sequence;
        let r = render(&cornell, &opts, |_| {});
        rate.push(r.paths as f64 / r.elapsed.as_secs_f64());
        println!(
            "cornell: {:.3} M path samples/s (pt, {} numbers, max_depth {}, {}x{}, {} spp in {:.2} s)",
            rate[rate.len() - 1] / 1e6,
            sequence.name(),
            opts.max_depth,
            cornell.camera.width,
            cornell.camera.height,
            r.passes,
            r.elapsed.as_secs_f64()
        );
    }
    println!(
        "cornell: Sobol / independent path samples per second {:.3}",
        rate[1] / rate[0]
    );
    Ok(())
}
