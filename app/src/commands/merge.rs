//! `footprint merge`: the image of one render from its shards' images.

use anyhow::{Result, bail};
use clap::Args;
use footprint::film::image_io::write_png;
use std::path::PathBuf;

/// Put the shards of one render (`render --shard i/N`) together: every layer, weighted
/// by its sample count; refuses shards of other scenes, settings or seeds, a shard given
/// twice, and missing ones
#[derive(Args, Debug)]
pub struct MergeArgs {
    /// Output EXR (the PNG preview is written beside it)
    out: PathBuf,
    /// The shards' EXR files, all N of them, in any order
    #[arg(required = true)]
    shards: Vec<PathBuf>,
    /// Exposure of the PNG preview in stops
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    exposure: f32,
}

pub fn run(a: MergeArgs) -> Result<()> {
    if a.out.extension().and_then(|e| e.to_str()) != Some("exr") {
        bail!(
            "the merged image must be an .exr file, got {}",
            a.out.display()
        );
    }
    if !a.exposure.is_finite() {
        bail!("--exposure must be finite");
    }
    let m = crate::merge::merge(&a.out, &a.shards)?;
    let png = a.out.with_extension("png");
    write_png(&png, &m.image, a.exposure)?;
    println!(
        "merged {} shards ({} spp in all; layers {}) -> {}, {}",
        m.shards,
        m.spp,
        m.layers.join(", "),
        a.out.display(),
        png.display()
    );
    Ok(())
}
