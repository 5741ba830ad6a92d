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
    /// Only rays per second by kind (camera, shadow, bounce) on one thread and on all, the
    /// CWBVH and Embree side by side, on the bundled scenes and the --scene
    #[arg(long)]
    rays: bool,
    #[command(flatten)]
    import: ImportArgs,
}

/// The bundled scenes `--rays` measures (folder, file).
const RAY_SCENES: [(&str, &str); 7] = [
    ("door", "door.toml"),
    ("desk", "desk.toml"),
    ("cornell", "cornell.toml"),
    ("features", "scene.xml"),
    ("glass", "scene.xml"),
    ("panes", "scene.xml"),
    ("slit", "scene.xml"),
];

pub fn run(a: BenchArgs) -> Result<()> {
    set_threads(a.threads)?;
    if !(a.seconds.is_finite() && a.seconds > 0.0) {
        bail!("--seconds must be positive");
    }
    let extra = a
        .scene
        .map(|p| a.import.load(&p).map(|sc| (p, sc)))
        .transpose()?;
    if a.rays {
        let mut scenes = Vec::new();
        for (name, file) in RAY_SCENES {
            let path = a.scenes.join(name).join(file);
            scenes.push((name.to_string(), footprint::scene::load::load_scene(&path)?));
        }
        if let Some((path, scene)) = extra {
            // `veach-ajar/scene.xml` is named by its folder.
            let named = match path.file_stem() {
                Some(s) if s != "scene" => Some(s),
                _ => path.parent().and_then(|p| p.file_name()),
            };
            let name = named.map_or("scene".into(), |s| s.to_string_lossy().into_owned());
            scenes.push((name, scene));
        }
        return crate::ray_bench::run(&scenes, a.seconds);
    }
    crate::bench::run(
        &a.scenes,
        a.seconds,
        extra.as_ref().map(|(p, s)| (p.as_path(), s)),
    )
}
