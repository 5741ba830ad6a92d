//! Loading a scene file by its kind: footprint's TOML (`.toml`, [`super::toml_file`]) or
//! Mitsuba 3 XML (`.xml`, [`super::mitsuba`]).

use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::scene::mitsuba::ImportOptions;
use std::path::Path;

/// Loads a scene file: footprint's TOML (`.toml`) or Mitsuba 3 XML (`.xml`).
pub fn load_scene(path: &Path) -> Result<Scene> {
    load_scene_with(path, &ImportOptions::default())
}

/// Loads a scene file; `opts` applies to Mitsuba 3 XML scenes (`-D`, `--lenient`).
pub fn load_scene_with(path: &Path, opts: &ImportOptions) -> Result<Scene> {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"))
    {
        return crate::scene::mitsuba::load(path, opts);
    }
    if !opts.defines.is_empty() {
        return Err(Error::invalid(
            path,
            "-D overrides Mitsuba XML parameters; this is not an .xml scene",
        ));
    }
    crate::scene::toml_file::load(path)
}
