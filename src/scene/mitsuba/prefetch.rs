//! The files a Mitsuba scene reads (OBJ meshes and bitmap textures), loaded on every core
//! before the scene is built. Mitsuba 3 loads its shapes in parallel too; footprint's
//! builder walks the XML in order (ids, references, materials shared between shapes), so the
//! slow part, parsing and decoding the files, runs here first, largest file first, and the
//! builder takes each file's result from [`Prefetched`] where it would have loaded it.
//!
//! Only successful loads are kept: a file that fails is loaded again by the builder at its
//! place in the document, which reports the error exactly as a sequential load does (the
//! first failing element in document order, with its file name).

use super::meshes::{self, MeshData};
use super::xml::{Doc, Props};
use crate::scene::texture::Texture;
use rayon::prelude::*;
use roxmltree::Node;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Meshes and textures loaded ahead, by resolved path, each with the number of elements
/// that name it: the last of them takes the file's data out (no second copy of a large
/// mesh lives while the scene is built).
#[derive(Default)]
pub struct Prefetched {
    meshes: HashMap<PathBuf, (MeshData, usize)>,
    textures: HashMap<PathBuf, (Texture, usize)>,
}

/// The kinds of file loaded ahead.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Kind {
    Mesh,
    Texture,
}

impl Prefetched {
    /// Loads every `<shape type="obj">` and `<texture type="bitmap">` file under `root` in
    /// parallel. Elements whose type or file name cannot be read are left to the builder,
    /// which reports them.
    pub fn load(doc: &Doc, root: Node) -> Prefetched {
        // Each file with the number of elements that name it.
        let mut uses: HashMap<(Kind, PathBuf), usize> = HashMap::new();
        for n in root.descendants().filter(|n| n.is_element()) {
            let kind = match (
                n.tag_name().name(),
                doc.attr(n, "type").ok().flatten().as_deref(),
            ) {
                ("shape", Some("obj")) => Kind::Mesh,
                ("texture", Some("bitmap")) => Kind::Texture,
                _ => continue,
            };
            let name = Props::new(doc, n)
                .ok()
                .and_then(|p| p.string("filename").ok().flatten());
            if let Some(name) = name {
                *uses.entry((kind, doc.file(&name))).or_default() += 1;
            }
        }
        let mut jobs: Vec<_> = uses.into_iter().collect();
        // Largest first, so that the big files do not start last.
        jobs.sort_by_cached_key(|((_, path), _)| {
            std::cmp::Reverse(std::fs::metadata(path).map_or(0, |m| m.len()))
        });
        let loaded: Vec<_> = jobs
            .into_par_iter()
            .with_max_len(1)
            .map(|((kind, path), uses)| {
                let file = match kind {
                    Kind::Mesh => meshes::load_obj(&path).ok().map(File::Mesh),
                    Kind::Texture => Texture::load(&path).ok().map(File::Texture),
                };
                (path, file, uses)
            })
            .collect();
        let mut out = Prefetched::default();
        for (path, file, uses) in loaded {
            match file {
                Some(File::Mesh(m)) => {
                    out.meshes.insert(path, (m, uses));
                }
                Some(File::Texture(t)) => {
                    out.textures.insert(path, (t, uses));
                }
                None => {}
            }
        }
        out
    }

    /// The mesh at `path`: loaded ahead, else loaded now (and its error reported).
    pub fn mesh(&mut self, path: &Path) -> crate::error::Result<MeshData> {
        match take(&mut self.meshes, path) {
            Some(m) => Ok(m),
            None => meshes::load_obj(path),
        }
    }

    /// The texture at `path`: loaded ahead, else loaded now (and its error reported).
    pub fn texture(&mut self, path: &Path) -> crate::error::Result<Texture> {
        match take(&mut self.textures, path) {
            Some(t) => Ok(t),
            None => Texture::load(path),
        }
    }
}

/// A file loaded ahead.
enum File {
    Mesh(MeshData),
    Texture(Texture),
}

/// The data at `path`: a copy while other elements will still ask for it, the data itself
/// for the last.
fn take<T: Clone>(files: &mut HashMap<PathBuf, (T, usize)>, path: &Path) -> Option<T> {
    let (data, uses) = files.get_mut(path)?;
    if *uses > 1 {
        *uses -= 1;
        return Some(data.clone());
    }
    files.remove(path).map(|(data, _)| data)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file named by two elements is handed to both, the second time taken out of the
    /// cache; a path never loaded ahead gives nothing (the builder then loads it itself).
    #[test]
    fn a_file_named_twice_is_handed_out_twice_then_dropped() {
        let path = PathBuf::from("mesh.obj");
        let mut files = HashMap::from([(path.clone(), (vec![1u8, 2, 3], 2usize))]);
        assert_eq!(take(&mut files, &path), Some(vec![1, 2, 3]));
        assert_eq!(files[&path].1, 1, "one use left");
        assert_eq!(take(&mut files, &path), Some(vec![1, 2, 3]));
        assert!(files.is_empty(), "the last use takes the data out");
        assert_eq!(take(&mut files, &path), None);
    }
}
