//! OBJ text helpers shared by the TOML loader and the Mitsuba importer: the check that every
//! vertex coordinate is a finite number (tobj would read NaN), and the degenerate-triangle
//! rule.

use crate::error::{Error, Result};
use crate::scene::geometry::TriangleGeom;
use std::path::Path;

/// Degenerate: zero (or non-finite) area, or so thin that its normal is noise.
pub fn is_degenerate(geom: &TriangleGeom) -> bool {
    let len = geom.cross().length();
    let longest = geom
        .e1
        .length()
        .max(geom.e2.length())
        .max((geom.e2 - geom.e1).length());
    !(len.is_finite() && len > 0.0 && len > 1e-10 * longest * longest)
}

/// An OBJ file's text, checked for vertex coordinates that are not finite numbers (which
/// tobj would read as NaN).
pub fn read_obj_text(obj_path: &Path) -> Result<String> {
    let text = std::fs::read_to_string(obj_path).map_err(|reason| Error::Io {
        path: obj_path.to_path_buf(),
        reason,
    })?;
    if let Some((line, tok)) = find_bad_vertex(&text) {
        return Err(Error::Syntax {
            path: obj_path.to_path_buf(),
            line,
            column: 1,
            message: format!("vertex coordinate '{tok}' is not a finite number"),
        });
    }
    Ok(text)
}

/// Scans OBJ text for vertex lines with non-finite coordinates; returns the first line.
fn find_bad_vertex(text: &str) -> Option<(usize, String)> {
    for (i, line) in text.lines().enumerate() {
        let l = line.trim_start();
        if let Some(rest) = l.strip_prefix("v ").or_else(|| l.strip_prefix("v\t")) {
            for tok in rest.split_whitespace().take(3) {
                match tok.parse::<f32>() {
                    Ok(x) if x.is_finite() => {}
                    _ => return Some((i + 1, tok.to_string())),
                }
            }
        }
    }
    None
}
