//! `footprint merge OUT.exr SHARD.exr ...`: the image of one run from the images of its
//! shards ([`footprint_integrators::shard`]).
//!
//! Every layer of a render is the mean of its passes, and a shard's `footprint/spp` says how
//! many passes it holds, so the merged layer is `Σ n_s · image_s / Σ n_s` (in f64): the
//! image one run with the same seed and the total sample count gives, to float rounding. The
//! shards must be of the same scene (content hash), settings, seed, total sample count and
//! shard count, each shard exactly once; otherwise the merge stops and says which file and
//! what differs, or which shards are missing. The result is written whole or not at all,
//! with the header of an unsharded render (`footprint/shard` = `0/1`).

use anyhow::{Context, Result, bail};
use footprint::film::Image;
use footprint::film::image_io::{ExrHeader, read_exr_header, read_exr_layers, write_exr};
use footprint::keyword::Keyword;
use footprint::scene::Scene;
use footprint_integrators::render::RenderOptions;
use footprint_integrators::shard::PassSelection;
use std::path::{Path, PathBuf};

/// Header keys a merge reads.
pub const SCENE_HASH: &str = "footprint/scene_hash";
pub const SETTINGS: &str = "footprint/settings";
pub const SEED: &str = "footprint/seed";
pub const SHARD: &str = "footprint/shard";
/// Passes (samples per pixel) this image holds.
pub const SPP: &str = "footprint/spp";
/// Passes of the whole render the image is a shard of.
pub const SPP_TOTAL: &str = "footprint/spp_total";
pub const RENDER_TIME: &str = "footprint/render_time_s";

/// The largest image side a render makes (the camera's limit): a shard's header that says
/// more is not a render's, and its layers are not allocated.
const MAX_SIDE: u32 = 32768;

/// Keys that describe one run only and are left out of a merged header.
const PER_RUN: &[&str] = &[
    "footprint/time_split_s",
    "footprint/maps_file",
    "footprint/maps_load_s",
];

/// Everything besides the scene, the seed and the sample budget that the image depends on,
/// as `name=value` words: shards merge only when these are equal.
pub fn settings_key(opts: &RenderOptions, scene: &Scene) -> String {
    format!(
        "method={} sequence={} film={:?} resolution={}x{} max_depth={} rr_depth={} {} map_max_dist={}",
        opts.method.name(),
        opts.sequence.name(),
        opts.film,
        scene.camera.width,
        scene.camera.height,
        opts.max_depth,
        opts.rr_depth,
        footprint::schema::describe(&opts.guide_params, &scene.maps, |_| true),
        scene.map_max_dist(),
    )
}

/// One input of a merge, its header read (its pixels are read one shard at a time).
struct ShardImage {
    path: PathBuf,
    exr: ExrHeader,
    shard: PassSelection,
    spp: u32,
    spp_total: u32,
}

impl ShardImage {
    fn attr(&self, key: &str) -> Option<&str> {
        self.exr
            .attributes
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    fn read(path: &Path) -> Result<Self> {
        let exr = read_exr_header(path)?;
        let mut s = ShardImage {
            path: path.to_path_buf(),
            exr,
            shard: PassSelection::ALL,
            spp: 0,
            spp_total: 0,
        };
        let name = path.display();
        for key in [SCENE_HASH, SETTINGS, SEED, SHARD, SPP, SPP_TOTAL] {
            if s.attr(key).is_none() {
                bail!(
                    "{name} has no {key} in its header: not a render of this footprint (older renders cannot be merged)"
                );
            }
        }
        let number = |key: &str| -> Result<u32> {
            let v = s.attr(key).unwrap_or_default();
            v.parse()
                .map_err(|_| anyhow::anyhow!("{name}: {key} is '{v}', not a count"))
        };
        let (spp, spp_total) = (number(SPP)?, number(SPP_TOTAL)?);
        let shard = PassSelection::parse(s.attr(SHARD).unwrap_or_default())
            .map_err(|e| anyhow::anyhow!("{name}: {SHARD}: {e}"))?;
        if s.exr.layers.is_empty() {
            bail!("{name} has no image layer");
        }
        for (layer, w, h) in &s.exr.layers {
            if *w == 0 || *h == 0 || *w > MAX_SIDE || *h > MAX_SIDE {
                bail!(
                    "{name}: layer '{layer}' is {w}x{h} pixels in its header, not an image of a render (1 to {MAX_SIDE} pixels a side)"
                );
            }
        }
        (s.shard, s.spp, s.spp_total) = (shard, spp, spp_total);
        Ok(s)
    }
}

/// What a merge did.
pub struct Merged {
    pub shards: u32,
    pub spp: u32,
    pub layers: Vec<String>,
    /// The merged main layer (for the PNG preview).
    pub image: Image,
}

/// Merges the shard images `inputs` into `out` (see the module doc).
pub fn merge(out: &Path, inputs: &[PathBuf]) -> Result<Merged> {
    if inputs.is_empty() {
        bail!("no shard images to merge");
    }
    let shards = inputs
        .iter()
        .map(|p| ShardImage::read(p))
        .collect::<Result<Vec<_>>>()?;
    let first = &shards[0];
    let n = first.shard.count;
    let (a, na) = (first, first.path.display());
    for s in &shards[1..] {
        let nb = s.path.display();
        if s.attr(SCENE_HASH) != a.attr(SCENE_HASH) {
            bail!(
                "{nb} is a render of another scene than {na} (scene content hash {} there, {} here)",
                short(s.attr(SCENE_HASH)),
                short(a.attr(SCENE_HASH))
            );
        }
        if s.attr(SETTINGS) != a.attr(SETTINGS) {
            bail!(
                "{nb} was rendered with other settings than {na}: {}",
                word_difference(s.attr(SETTINGS), a.attr(SETTINGS))
            );
        }
        if s.attr(SEED) != a.attr(SEED) {
            bail!(
                "{nb} has seed {}, {na} seed {}: shards of one image share the seed",
                s.attr(SEED).unwrap_or_default(),
                a.attr(SEED).unwrap_or_default()
            );
        }
        if s.spp_total != a.spp_total {
            bail!(
                "{nb} is a shard of {} spp, {na} of {} spp: shards of one image share --spp",
                s.spp_total,
                a.spp_total
            );
        }
        if s.shard.count != n {
            bail!(
                "{nb} is shard {}, {na} shard {}: the shard counts differ",
                s.shard,
                a.shard
            );
        }
        if s.exr.layers != a.exr.layers {
            bail!(
                "{nb} has layers {:?}, {na} {:?} (name, width, height)",
                s.exr.layers,
                a.exr.layers
            );
        }
    }
    // The shard count comes from a header: the shards are kept by index, not in a list of
    // `n` places, so that no count allocates more than the inputs.
    let mut by_index: std::collections::BTreeMap<u32, &ShardImage> = Default::default();
    for s in &shards {
        if let Some(o) = by_index.get(&s.shard.index) {
            bail!(
                "{} and {} are both shard {} (a shard given twice)",
                o.path.display(),
                s.path.display(),
                s.shard
            );
        }
        let expected = s.shard.passes_of(s.spp_total);
        if s.spp != expected {
            bail!(
                "{} holds {} passes, but shard {} of {} spp has {expected}",
                s.path.display(),
                s.spp,
                s.shard,
                s.spp_total
            );
        }
        by_index.insert(s.shard.index, s);
    }
    let missing_count = n as usize - by_index.len();
    if missing_count > 0 {
        // The first few by name (a count of thousands is named by its number).
        const NAMED: usize = 8;
        let mut missing: Vec<String> = (0..n)
            .filter(|i| !by_index.contains_key(i))
            .take(NAMED)
            .map(|i| format!("{i}/{n}"))
            .collect();
        if missing_count > NAMED {
            missing.push(format!("and {} more", missing_count - NAMED));
        }
        bail!(
            "missing shard{} {} of {} spp (render {} with --shard and merge again)",
            if missing_count > 1 { "s" } else { "" },
            missing.join(", "),
            first.spp_total,
            if missing_count > 1 { "them" } else { "it" }
        );
    }
    // Weighted by passes, in shard order, in f64; one shard's pixels in memory at a time.
    let total: u32 = shards.iter().map(|s| s.spp).sum();
    let ordered: Vec<&ShardImage> = by_index.into_values().collect();
    let base = ordered[0];
    let mut sums: Vec<Vec<[f64; 3]>> = base
        .exr
        .layers
        .iter()
        .map(|(_, w, h)| vec![[0.0f64; 3]; *w as usize * *h as usize])
        .collect();
    for s in &ordered {
        let img = read_exr_layers(&s.path)?;
        let found: Vec<(String, u32, u32)> = img
            .layers
            .iter()
            .map(|(n, i)| (n.clone(), i.width, i.height))
            .collect();
        if found != base.exr.layers {
            bail!(
                "{}: its layers are not what its header says",
                s.path.display()
            );
        }
        let w = s.spp as f64;
        for (sum, (_, layer)) in sums.iter_mut().zip(&img.layers) {
            for (acc, p) in sum.iter_mut().zip(&layer.pixels) {
                for c in 0..3 {
                    acc[c] += p[c] as f64 * w;
                }
            }
        }
    }
    let inv = 1.0 / total as f64;
    let mut layers: Vec<(String, Image)> = base
        .exr
        .layers
        .iter()
        .zip(&sums)
        .map(|((name, width, height), sum)| {
            let pixels = sum
                .iter()
                .map(|a| {
                    footprint::Rgb::new(
                        (a[0] * inv) as f32,
                        (a[1] * inv) as f32,
                        (a[2] * inv) as f32,
                    )
                })
                .collect();
            let img = Image {
                width: *width,
                height: *height,
                pixels,
            };
            (name.clone(), img)
        })
        .collect();
    let render_time: f64 = ordered
        .iter()
        .filter_map(|s| s.attr(RENDER_TIME)?.parse::<f64>().ok())
        .sum();
    let mut header: Vec<(String, String)> = base
        .exr
        .attributes
        .iter()
        .filter(|(k, _)| !PER_RUN.contains(&k.as_str()))
        .cloned()
        .collect();
    for (k, v) in header.iter_mut() {
        match k.as_str() {
            SHARD => *v = PassSelection::ALL.to_string(),
            SPP => *v = total.to_string(),
            RENDER_TIME => *v = format!("{render_time:.3}"),
            _ => {}
        }
    }
    header.push(("footprint/merged_shards".into(), n.to_string()));
    let refs: Vec<(&str, &Image)> = layers.iter().map(|(n, i)| (n.as_str(), i)).collect();
    write_exr(out, &refs, &header).with_context(|| format!("merging into {}", out.display()))?;
    Ok(Merged {
        shards: n,
        spp: total,
        layers: layers.iter().map(|(n, _)| n.clone()).collect(),
        image: layers.swap_remove(0).1,
    })
}

/// The first 16 characters of a hash (a header's text may be anything: cut at a character).
fn short(h: Option<&str>) -> &str {
    let h = h.unwrap_or_default();
    h.char_indices().nth(16).map_or(h, |(i, _)| &h[..i])
}

/// The `name=value` words of `found` that differ from `expected`'s.
fn word_difference(found: Option<&str>, expected: Option<&str>) -> String {
    let (f, e) = (found.unwrap_or_default(), expected.unwrap_or_default());
    let ew: Vec<&str> = e.split_whitespace().collect();
    let fw: Vec<&str> = f.split_whitespace().collect();
    let diffs: Vec<String> = fw
        .iter()
        .zip(&ew)
        .filter(|(a, b)| a != b)
        .map(|(a, b)| format!("{a} (not {b})"))
        .collect();
    if diffs.is_empty() {
        format!("'{f}' against '{e}'")
    } else {
        diffs.join(", ")
    }
}
