//! `footprint bench`: the command's flags (the measurements are [`crate::bench`]).

use crate::args::{ImportArgs, set_threads};
use anyhow::{Result, bail};
use clap::Args;
use std::path::PathBuf;

/// Measure speed: closest-hit rays per second on door, path samples per second on cornell
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Folder holding the bundled scenes
    #[arg(long, default_value = "scenes")]
    scenes: PathBuf,
    /// Seconds to spend on each measurement
    #[arg(long, default_value_t = 3.0)]
    seconds: f64,
    /// Worker threads [default: all cores]
    #[arg(long)]
    threads: Option<usize>,
    /// A further scene (TOML or Mitsuba XML, e.g. Veach Ajar with -D resx=128 -D
    /// resy=72) whose guided path throughput is measured next to door's
    #[arg(long)]
    scene: Option<PathBuf>,
    #[command(flatten)]
    import: ImportArgs,
}

pub fn run(a: BenchArgs) -> Result<()> {
    set_threads(a.threads)?;
    if !(a.seconds.is_finite() && a.seconds > 0.0) {
        bail!("--seconds must be positive");
    }
    let extra = a
        .scene
        .map(|p| a.import.load(&p).map(|sc| (p, sc)))
        .transpose()?;
    crate::bench::run(
        &a.scenes,
        a.seconds,
        extra.as_ref().map(|(p, s)| (p.as_path(), s)),
    )
}
