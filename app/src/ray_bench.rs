//! `footprint bench --rays`: rays per second by kind on each ray tracer this machine has,
//! side by side. Per scene, three fixed sets of rays are drawn once (so that both ray
//! tracers trace the very same rays and the drawing is not timed):
//!
//! * **camera**: closest hits of pinhole rays through uniform raster positions;
//! * **shadow**: from each camera hit to a point sampled on a light (chosen by power), the
//!   any-hit query of next-event estimation, with the same segment ends it uses;
//! * **bounce**: closest hits of cosine-distributed rays leaving each camera hit on the
//!   side the camera sees, the path's next segment.
//!
//! Each set is traced on one thread and on all, by the CWBVH and by Embree in alternation,
//! round after round, so that the machine's drift shifts both alike; a cell's rays per
//! second is its rays over its time summed over the rounds.

use footprint::rng::Rng;
use footprint::sampling::sample_cosine_hemisphere;
use footprint::scene::Scene;
use footprint::scene::accel::{Accel, Backend, ShadowOrder, Toward};
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use std::time::Instant;

/// Rays of each kind per scene.
const RAYS: usize = 1 << 16;

/// Rays a worker takes at a time.
const GRAIN: usize = 256;

/// One ray: origin, unit direction, length.
type Ray = (Vec3, Vec3, f32);

/// The kinds of rays, in the table's order.
const KINDS: [&str; 3] = ["camera", "shadow", "bounce"];

/// The three sets of rays of `scene` ([`KINDS`] order).
fn draw_rays(scene: &Scene) -> [Vec<Ray>; 3] {
    let cam = &scene.camera;
    let size = Vec2::new(cam.width as f32, cam.height as f32);
    let (mut camera, mut shadow, mut bounce) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..RAYS as u64 {
        let mut rng = Rng::new(1, 77, i);
        let dir = cam.ray_dir(rng.uniform2() * size);
        camera.push((cam.position, dir, f32::INFINITY));
        let Some(h) = scene.intersect(cam.position, dir, f32::INFINITY) else {
            continue;
        };
        let n = if h.ng.dot(dir) < 0.0 { h.ng } else { -h.ng };
        let (light, _, u) = scene.choose_light(&mut rng);
        if let Some(s) = scene.lights[light].sample_li(h.p, u) {
            shadow.extend(scene.shadow_segment(h.p, n, s.p, s.n));
        }
        let d =
            footprint::math::Frame::from_z(n).to_world(sample_cosine_hemisphere(rng.uniform2()));
        bounce.push((scene.spawn_origin(h.p, n, d), d, f32::INFINITY));
    }
    [camera, shadow, bounce]
}

/// Seconds to trace `rays` (closest hits, or any hit for `shadow`) with `accel`.
fn trace(accel: &Accel, rays: &[Ray], shadow: bool) -> f64 {
    let start = Instant::now();
    let found: usize = rays
        .par_chunks(GRAIN)
        .map(|chunk| {
            chunk
                .iter()
                .filter(|(o, d, t)| {
                    if shadow {
                        !accel.unoccluded(Toward::Light, *o, *d, *t)
                    } else {
                        accel.intersect(*o, *d, *t).is_some()
                    }
                })
                .count()
        })
        .sum();
    std::hint::black_box(found);
    start.elapsed().as_secs_f64()
}

/// Measures `scenes` (name, scene) for about `seconds` each and prints the table.
pub fn run(scenes: &[(String, Scene)], seconds: f64) -> anyhow::Result<()> {
    let all = rayon::current_num_threads();
    let pools: Vec<(usize, rayon::ThreadPool)> = [1, all]
        .into_iter()
        .filter(|&n| n == 1 || all > 1)
        .take(if all > 1 { 2 } else { 1 })
        .map(|n| Ok((n, rayon::ThreadPoolBuilder::new().num_threads(n).build()?)))
        .collect::<anyhow::Result<_>>()?;
    println!(
        "rays by kind, {RAYS} of each drawn per scene, traced in alternation round after round for about {seconds} s a scene (M rays/s; CWBVH / Embree: the CWBVH's rays per second over Embree's)"
    );
    println!(
        "{:<14} {:<7} {:>7} {:>9} {:>9} {:>9}",
        "scene", "rays", "threads", "CWBVH", "Embree", "ratio"
    );
    for (name, scene) in scenes {
        let mut cwbvh =
            Accel::build_with(&scene.triangles, Backend::Cwbvh).map_err(anyhow::Error::msg)?;
        // The order the scene's own CWBVH chose for its shadow rays.
        for toward in [Toward::Light, Toward::Camera] {
            let segments = scene.probe_shadow_segments(toward);
            if let Some((order, visits)) = cwbvh.choose_shadow_order(toward, &segments) {
                let per_order: Vec<String> = ShadowOrder::ALL
                    .iter()
                    .zip(visits)
                    .map(|(o, v)| format!("{} {v:.2}", o.describe()))
                    .collect();
                println!(
                    "{name}: shadow rays toward {}: {} (nodes and triangles tested per probe ray: {})",
                    toward.describe(),
                    order.describe(),
                    per_order.join(", ")
                );
            }
        }
        let mut accels = vec![cwbvh];
        match Accel::build_with(&scene.triangles, Backend::Embree) {
            Ok(a) => accels.push(a),
            Err(e) => println!("{name}: the CWBVH only ({e})"),
        }
        let sets = draw_rays(scene);
        // Seconds per (kind, pool, accel), and the rounds.
        let cells = KINDS.len() * pools.len() * accels.len();
        let mut time = vec![0.0f64; cells];
        let start = Instant::now();
        let mut rounds = 0usize;
        while rounds < 3 || start.elapsed().as_secs_f64() < seconds {
            for (k, set) in sets.iter().enumerate() {
                for (p, (_, pool)) in pools.iter().enumerate() {
                    for j in 0..accels.len() {
                        // Alternate which goes first.
                        let a = (j + rounds) % accels.len();
                        let cell = (k * pools.len() + p) * accels.len() + a;
                        time[cell] += pool.install(|| trace(&accels[a], set, k == 1));
                    }
                }
            }
            rounds += 1;
        }
        for (k, set) in sets.iter().enumerate() {
            for (p, (threads, _)) in pools.iter().enumerate() {
                let rate = |a: usize| {
                    let t = time[(k * pools.len() + p) * accels.len() + a];
                    (set.len() * rounds) as f64 / t / 1e6
                };
                let (cw, em) = (rate(0), (accels.len() > 1).then(|| rate(1)));
                println!(
                    "{:<14} {:<7} {:>7} {:>9.2} {:>9} {:>9}",
                    name,
                    KINDS[k],
                    threads,
                    cw,
                    em.map_or("-".into(), |e| format!("{e:.2}")),
                    em.map_or("-".into(), |e| format!("{:.2}", cw / e)),
                );
            }
        }
    }
    Ok(())
}
