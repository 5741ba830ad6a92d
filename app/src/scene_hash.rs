//! The scene's content hash: what identifies a scene wherever its files lie, so that a
//! cached reference, a saved maps file or a shard can say which scene it was made from.

use anyhow::{Context, Result};
use footprint::scene::Scene;
use std::path::Path;

/// blake3 (hex) over the scene file, every file it names (meshes, their materials,
/// textures) by content, and the parameters given on the command line (`-D`). The paths
/// themselves do not count: a copy of the scene elsewhere has the same hash.
pub fn scene_content_hash(scene_path: &Path, scene: &Scene) -> Result<String> {
    let mut h = blake3::Hasher::new();
    let text = std::fs::read(scene_path)
        .with_context(|| format!("cannot read {}", scene_path.display()))?;
    h.update(&text);
    // Every file the scene names: any quoted string (double or single quotes) that is a file
    // beside the scene, in TOML (`file = "x.obj"`) as in Mitsuba XML (`value="models/x.obj"`).
    let dir = scene_path.parent().unwrap_or(Path::new("."));
    let text = String::from_utf8_lossy(&text).to_string();
    let quoted = ['"', '\'']
        .into_iter()
        .flat_map(|q| text.split(q).skip(1).step_by(2));
    for quoted in quoted {
        if quoted.is_empty() || quoted.len() > 400 || quoted.contains('\n') {
            continue;
        }
        let p = dir.join(quoted);
        if p.is_file() {
            if let Ok(bytes) = std::fs::read(&p) {
                h.update(&bytes);
            }
            if let Ok(mtl) = std::fs::read(p.with_extension("mtl")) {
                h.update(&mtl);
            }
        }
    }
    h.update(scene.source_params.as_bytes());
    Ok(h.finalize().to_hex().to_string())
}
