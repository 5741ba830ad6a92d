//! `footprint export`: a scene as Mitsuba 3 XML.

use crate::args::ImportArgs;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

/// Write a scene as Mitsuba 3 XML (scene.xml + one OBJ per material in meshes/), for
/// rendering it with Mitsuba; the XML takes -D resx, resy, spp, max_depth, rfilter
#[derive(Args, Debug)]
pub struct ExportArgs {
    /// Scene file: footprint TOML (.toml) or Mitsuba 3 XML (.xml)
    scene: PathBuf,
    /// Output folder (created if missing)
    #[arg(long, short)]
    out: PathBuf,
    #[command(flatten)]
    import: ImportArgs,
}

pub fn run(a: ExportArgs) -> Result<()> {
    let sc = a.import.load(&a.scene)?;
    let notes = footprint::scene::mitsuba::export::export(&sc, &a.scene, &a.out)?;
    for n in &notes {
        eprintln!("note: {n}");
    }
    println!(
        "{} -> {}",
        a.scene.display(),
        a.out.join("scene.xml").display()
    );
    Ok(())
}
