//! Writing a file whole or not at all: the content goes to a temporary file in the target's
//! folder (`.NAME.tmp-PID`), which is then renamed over the target. A failed, interrupted or
//! killed writer never leaves a partly written file under the target's name, and never
//! damages a good one that was there.

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// The temporary file `atomic_write` writes before renaming it over `path`.
pub fn tmp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.tmp-{}", std::process::id()))
}

/// Runs `write` against a temporary file, then renames it over `path`.
pub fn atomic_write(
    path: &Path,
    write: impl FnOnce(&Path) -> std::result::Result<(), String>,
) -> Result<()> {
    let tmp = tmp_path(path);
    if let Err(message) = write(&tmp) {
        let _ = std::fs::remove_file(&tmp);
        return Err(Error::Write {
            path: path.to_path_buf(),
            message,
        });
    }
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        Error::Write {
            path: path.to_path_buf(),
            message: e.to_string(),
        }
    })
}
