//! Saved maps (`footprint maps SCENE --save maps.fpm`, `footprint render --maps maps.fpm`).
//!
//! The file holds what is expensive, the passes' output ([`Passes`]: every particle with
//! its record, the emission points, the pass statistics), not the kd-trees and guide caches:
//! those are rebuilt on load by [`footprint_integrators::maps::Guidance::from_passes`], deterministically, in
//! a second or two (the cache builds dominate), so a render with loaded maps is the same
//! image as one that ran the passes itself.
//!
//! Format version 3, little-endian:
//!
//! | bytes | what |
//! |---|---|
//! | 8 | magic `FPMAPS\r\n` |
//! | 4 | format version (u32) |
//! | 8 | payload length in bytes (u64) |
//! | 32 | blake3 hash of the payload |
//! | … | payload: the key (u32 length + UTF-8), then the light pass and the view pass |
//!
//! The key says what the passes depend on ([`maps_key`]): the scene's content hash
//! ([`crate::scene_hash`]), the resolution, the maximum depth, the seed and the settings
//! that shape the passes. A pass is a presence byte, then its
//! statistics (paths u64, emitted 3 x f32, escaped count u32 + 3 x f32 each, seconds f64,
//! the particles of the paths that seed the photon map's cache u64, `u64::MAX` for all, the
//! thinning level u32),
//! its particles (count u64; position, direction, normal, weight as 3 x f32 each, depth
//! u16, specular chain u8) and its emission points (count u64; position, normal 3 x f32).
//! Positions are the scene's own ([`Scene::origin`]: a scene far from the origin of its file
//! is centred when loaded), which its content hash fixes; version 1 wrote a far scene's
//! positions in its file's coordinates, version 2 had no seeding count and no thinning level
//! (a thinned pass thinned again on load had its weights raised by the levels it had passed).

use anyhow::{Result, bail};
use footprint::Rgb;
use footprint::guide::cache::Seed;
use footprint::guide::particle_map::ParticleInput;
use footprint::scene::Scene;
use footprint::schema::{Passes as Shapes, describe};
use footprint_integrators::maps::Passes;
use footprint_integrators::passes::{PassOutput, PassStats};
use glam::Vec3;
use std::path::Path;
use std::time::Duration;

pub const MAGIC: &[u8; 8] = b"FPMAPS\r\n";
pub const VERSION: u32 = 3;
const HEADER: usize = 8 + 4 + 8 + 32;

/// What the passes depend on, as `name=value` words; a file is used only for a render whose
/// key is equal: the scene's content, resolution, depth and seed, and the settings the
/// schema marks as shaping the passes (`footprint::schema::Passes`; with several map rounds
/// the later rounds are guided by the earlier ones' maps, so the guide's settings too).
pub fn maps_key(scene_hash: &str, scene: &Scene, max_depth: u32, seed: u64) -> String {
    let rounds = scene.maps.rounds > 1;
    let settings = describe(&scene.guide, &scene.maps, |s| match s.passes {
        Shapes::Always => true,
        Shapes::WithRounds => rounds,
        Shapes::Never => false,
    });
    format!(
        "scene={scene_hash} resolution={}x{} max_depth={max_depth} seed={seed} {settings}",
        scene.camera.width, scene.camera.height,
    )
}

/// Writes `passes` with `key` to `path`, whole or not at all.
pub fn save(path: &Path, key: &str, passes: &Passes) -> Result<()> {
    let mut p = Vec::new();
    put_bytes(&mut p, key.as_bytes());
    for pass in [&passes.light, &passes.view] {
        match pass {
            None => p.push(0),
            Some(out) => {
                p.push(1);
                put_pass(&mut p, out);
            }
        }
    }
    let mut file = Vec::with_capacity(HEADER + p.len());
    file.extend_from_slice(MAGIC);
    file.extend_from_slice(&VERSION.to_le_bytes());
    file.extend_from_slice(&(p.len() as u64).to_le_bytes());
    file.extend_from_slice(blake3::hash(&p).as_bytes());
    file.extend_from_slice(&p);
    footprint::atomic_file::atomic_write(path, |tmp| {
        std::fs::write(tmp, &file).map_err(|e| e.to_string())
    })?;
    Ok(())
}

/// Reads the passes saved in `path`, refusing a file that is not one, of another format
/// version, truncated, corrupt, or made with another key than `expected` (every error names
/// the file, and a key mismatch the settings that differ).
pub fn load(path: &Path, expected: &str) -> Result<Passes> {
    let name = path.display();
    let bytes = std::fs::read(path).map_err(|e| anyhow::anyhow!("cannot read {name}: {e}"))?;
    if bytes.len() < 8 || &bytes[..8] != MAGIC {
        bail!("{name} is not a footprint maps file (made by `footprint maps --save`)");
    }
    if bytes.len() < HEADER {
        bail!(
            "{name} is truncated ({} bytes, shorter than the header)",
            bytes.len()
        );
    }
    let version = u32::from_le_bytes(bytes[8..12].try_into().unwrap());
    if version != VERSION {
        bail!(
            "{name} is a maps file of format version {version}; this footprint reads version {VERSION}: build the maps again"
        );
    }
    let len = u64::from_le_bytes(bytes[12..20].try_into().unwrap());
    let payload = &bytes[HEADER..];
    if (payload.len() as u64) < len {
        bail!(
            "{name} is truncated: {} of its {len} bytes of data are there",
            payload.len()
        );
    }
    if payload.len() as u64 > len {
        bail!(
            "{name} is corrupt: {} bytes of data where its header says {len}",
            payload.len()
        );
    }
    if blake3::hash(payload).as_bytes() != &bytes[20..52] {
        bail!("{name} is corrupt (its checksum does not match its content)");
    }
    let corrupt = || {
        anyhow::anyhow!(
            "{name} is corrupt (its content does not parse, or holds a number that is not finite)"
        )
    };
    let mut r = Reader { b: payload, at: 0 };
    let key = String::from_utf8(r.bytes().ok_or_else(corrupt)?.to_vec()).map_err(|_| corrupt())?;
    if key != expected {
        bail!("{name} {}", key_difference(&key, expected));
    }
    let mut passes = [None, None];
    for p in &mut passes {
        *p = match r.u8().ok_or_else(corrupt)? {
            0 => None,
            1 => Some(r.pass().ok_or_else(corrupt)?),
            _ => return Err(corrupt()),
        };
    }
    if r.at != payload.len() {
        return Err(corrupt());
    }
    let [light, view] = passes;
    // The passes were not run now: nothing of their time is this run's.
    Ok(Passes {
        light,
        view,
        light_time: Duration::ZERO,
        view_time: Duration::ZERO,
        rounds: Vec::new(),
    })
}

/// "was made for another scene" or "was made with photons=1000, this run has photons=2000".
fn key_difference(found: &str, expected: &str) -> String {
    let words = |s: &str| -> Vec<(String, String)> {
        s.split_whitespace()
            .map(|w| {
                let (k, v) = w.split_once('=').unwrap_or((w, ""));
                (k.to_string(), v.to_string())
            })
            .collect()
    };
    let (f, e) = (words(found), words(expected));
    let value = |list: &[(String, String)], k: &str| {
        list.iter()
            .find(|(a, _)| a == k)
            .map(|(_, v)| v.clone())
            .unwrap_or_else(|| "(none)".into())
    };
    if value(&f, "scene") != value(&e, "scene") {
        return format!(
            "was made for another scene (content hash {} there, {} here: the scene file, a file it names or a -D parameter differs)",
            short(&value(&f, "scene")),
            short(&value(&e, "scene"))
        );
    }
    let diffs: Vec<String> = e
        .iter()
        .filter(|(k, v)| value(&f, k) != *v)
        .map(|(k, v)| format!("{k}={} (this run: {k}={v})", value(&f, k)))
        .collect();
    format!("was made with other settings: {}", diffs.join(", "))
}

/// The first 16 characters of a hash (a file's key may be anything: cut at a character).
fn short(h: &str) -> &str {
    h.char_indices().nth(16).map_or(h, |(i, _)| &h[..i])
}

fn put_bytes(p: &mut Vec<u8>, b: &[u8]) {
    p.extend_from_slice(&(b.len() as u32).to_le_bytes());
    p.extend_from_slice(b);
}

fn put_f32s(p: &mut Vec<u8>, v: &[f32]) {
    for x in v {
        p.extend_from_slice(&x.to_le_bytes());
    }
}

fn put_pass(p: &mut Vec<u8>, out: &PassOutput) {
    let s = &out.stats;
    p.extend_from_slice(&(s.paths as u64).to_le_bytes());
    put_f32s(p, &s.emitted.to_array());
    p.extend_from_slice(&(s.escaped.len() as u32).to_le_bytes());
    for e in &s.escaped {
        put_f32s(p, &e.to_array());
    }
    p.extend_from_slice(&s.time.as_secs_f64().to_le_bytes());
    let seeding = s.seed_particles.map_or(u64::MAX, |n| n as u64);
    p.extend_from_slice(&seeding.to_le_bytes());
    p.extend_from_slice(&s.thinning.to_le_bytes());
    p.extend_from_slice(&(out.particles.len() as u64).to_le_bytes());
    p.reserve(out.particles.len() * 51);
    for q in &out.particles {
        for v in [q.position, q.dir, q.normal, q.weight] {
            put_f32s(p, &v.to_array());
        }
        p.extend_from_slice(&q.depth.to_le_bytes());
        p.push(q.specular_chain as u8);
    }
    p.extend_from_slice(&(out.emission_points.len() as u64).to_le_bytes());
    for e in &out.emission_points {
        put_f32s(p, &e.position.to_array());
        put_f32s(p, &e.normal.to_array());
    }
}

/// A bounds-checked cursor over the payload: `None` when the data ends early.
struct Reader<'a> {
    b: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let end = self.at.checked_add(n)?;
        let s = self.b.get(self.at..end)?;
        self.at = end;
        Some(s)
    }
    fn u8(&mut self) -> Option<u8> {
        Some(self.take(1)?[0])
    }
    fn u16(&mut self) -> Option<u16> {
        Some(u16::from_le_bytes(self.take(2)?.try_into().ok()?))
    }
    fn u32(&mut self) -> Option<u32> {
        Some(u32::from_le_bytes(self.take(4)?.try_into().ok()?))
    }
    fn u64(&mut self) -> Option<u64> {
        Some(u64::from_le_bytes(self.take(8)?.try_into().ok()?))
    }
    fn f32(&mut self) -> Option<f32> {
        Some(f32::from_le_bytes(self.take(4)?.try_into().ok()?))
    }
    /// Three finite floats (every vector of a pass is: a NaN or infinity is corruption).
    fn vec3(&mut self) -> Option<Vec3> {
        Some(Vec3::new(self.f32()?, self.f32()?, self.f32()?)).filter(|v| v.is_finite())
    }
    fn bytes(&mut self) -> Option<&'a [u8]> {
        let n = self.u32()? as usize;
        self.take(n)
    }
    /// A count of items of `size` bytes each that the remaining data can hold.
    fn count(&mut self, size: usize) -> Option<usize> {
        let n = usize::try_from(self.u64()?).ok()?;
        (n.checked_mul(size)? <= self.b.len() - self.at).then_some(n)
    }
    fn pass(&mut self) -> Option<PassOutput> {
        let paths = usize::try_from(self.u64()?).ok()?;
        let emitted: Rgb = self.vec3()?;
        let n = self.u32()? as usize;
        let escaped = (0..n).map(|_| self.vec3()).collect::<Option<Vec<_>>>()?;
        let time =
            Duration::try_from_secs_f64(f64::from_le_bytes(self.take(8)?.try_into().ok()?)).ok()?;
        let seed_particles = match self.u64()? {
            u64::MAX => None,
            n => Some(usize::try_from(n).ok()?),
        };
        // The level the pass was kept at: thinning it further on load raises from there
        // (from 0, levels it already passed would raise its weights again).
        let thinning = self.u32().filter(|&l| l < 64)?;
        let n = self.count(51)?;
        let mut particles = Vec::with_capacity(n);
        for _ in 0..n {
            particles.push(ParticleInput {
                position: self.vec3()?,
                dir: self.vec3()?,
                normal: self.vec3()?,
                weight: self.vec3()?,
                depth: self.u16()?,
                specular_chain: self.u8()? != 0,
            });
        }
        let n = self.count(24)?;
        let emission_points = (0..n)
            .map(|_| {
                Some(Seed {
                    position: self.vec3()?,
                    normal: self.vec3()?,
                })
            })
            .collect::<Option<Vec<_>>>()?;
        let particles_drawn = particles.len();
        Some(PassOutput {
            particles,
            emission_points,
            stats: PassStats {
                paths,
                emitted,
                escaped,
                time,
                particles_drawn,
                seed_particles: seed_particles.filter(|&n| n <= particles_drawn),
                thinning,
                ..Default::default()
            },
        })
    }
}
