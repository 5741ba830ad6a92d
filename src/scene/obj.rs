//! OBJ and MTL text helpers shared by the TOML loader and the Mitsuba importer: the check
//! that every vertex coordinate is a finite number (tobj would read NaN), the check of the
//! MTL's numbers (tobj would read NaN, and panics on a colour of fewer than three numbers),
//! and the degenerate-triangle rule.

use crate::error::{Error, Result};
use crate::scene::MAX_COORDINATE;
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
    read_checked(obj_path, find_bad_vertex)
}

/// A file's text, or an error at the first line `bad` finds wrong (with what is wrong).
fn read_checked(path: &Path, bad: fn(&str) -> Option<(usize, String)>) -> Result<String> {
    let text = std::fs::read_to_string(path).map_err(|reason| Error::Io {
        path: path.to_path_buf(),
        reason,
    })?;
    if let Some((line, message)) = bad(&text) {
        return Err(Error::Syntax {
            path: path.to_path_buf(),
            line,
            column: 1,
            message,
        });
    }
    Ok(text)
}

/// Scans OBJ text for vertex lines with non-finite coordinates or coordinates beyond
/// [`MAX_COORDINATE`]; returns the first line and what is wrong.
fn find_bad_vertex(text: &str) -> Option<(usize, String)> {
    for (i, line) in text.lines().enumerate() {
        let l = line.trim_start();
        if let Some(rest) = l.strip_prefix("v ").or_else(|| l.strip_prefix("v\t")) {
            for tok in rest.split_whitespace().take(3) {
                match tok.parse::<f32>() {
                    Ok(x) if x.abs() <= MAX_COORDINATE => {}
                    Ok(x) if x.is_finite() => {
                        return Some((
                            i + 1,
                            format!(
                                "vertex coordinate '{tok}' is farther than {MAX_COORDINATE:e} from the origin"
                            ),
                        ));
                    }
                    _ => {
                        return Some((
                            i + 1,
                            format!("vertex coordinate '{tok}' is not a finite number"),
                        ));
                    }
                }
            }
        }
    }
    None
}

/// An MTL file's text, checked: every colour (`Ka`, `Kd`, `Ks`, `Ke`, `Tf`) is three finite
/// numbers and every scalar (`Ns`, `Ni`, `d`) a finite number; the first line that is not
/// is named.
pub fn read_mtl_text(mtl_path: &Path) -> Result<String> {
    read_checked(mtl_path, find_bad_mtl_number)
}

/// The first MTL line whose colour or scalar is not finite numbers, and what is wrong.
fn find_bad_mtl_number(text: &str) -> Option<(usize, String)> {
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let Some(key) = words.next() else { continue };
        let n = match key {
            "Ka" | "Kd" | "Ks" | "Ke" | "Tf" => 3,
            "Ns" | "Ni" | "d" => 1,
            _ => continue,
        };
        let values: Vec<&str> = words.take(n).collect();
        if values.len() < n {
            return Some((
                i + 1,
                format!("{key} needs {n} number{}", if n > 1 { "s" } else { "" }),
            ));
        }
        for tok in values {
            match tok.parse::<f32>() {
                Ok(x) if x.is_finite() => {}
                _ => return Some((i + 1, format!("{key}: '{tok}' is not a finite number"))),
            }
        }
    }
    None
}
