//! The files a Mitsuba scene reads (OBJ meshes and bitmap textures), loaded on every core
//! before the scene is built. Mitsuba 3 loads its shapes in parallel too; footprint's
//! builder walks the XML in order (ids, references, materials shared between shapes), so the
//! slow part, parsing and decoding the files, runs here first, largest file first, and the
//! builder takes each file's result from [`Prefetched`] where it would have loaded it.
//!
//! Only successful loads are kept: a file that fails is loaded again by the builder at its
//! place in the document, which reports the error exactly as a sequential load does (the
//! first failing element in document order, with its file name).

use super::shapes::{self, MeshData};
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

/// A file to load ahead.
enum Job {
    Mesh(PathBuf),
    Texture(PathBuf),
}

impl Prefetched {
    /// Loads every `<shape type="obj">` and `<texture type="bitmap">` file under `root` in
    /// parallel. Elements whose type or file name cannot be read are left to the builder,
    /// which reports them.
    pub fn load(doc: &Doc, root: Node) -> Prefetched {
        let file_of = |n: Node| -> Option<PathBuf> {
            let name = Props::new(doc, n).ok()?.string("filename").ok()??;
            Some(doc.file(&name))
        };
        let mut jobs: Vec<(Job, usize)> = Vec::new();
        for n in root.descendants().filter(|n| n.is_element()) {
            let kind = doc.attr(n, "type").ok().flatten();
            let job = match (n.tag_name().name(), kind.as_deref()) {
                ("shape", Some("obj")) => file_of(n).map(Job::Mesh),
                ("texture", Some("bitmap")) => file_of(n).map(Job::Texture),
                _ => None,
            };
            if let Some(job) = job {
                match jobs.iter_mut().find(|(j, _)| j.same(&job)) {
                    Some((_, uses)) => *uses += 1,
                    None => jobs.push((job, 1)),
                }
            }
        }
        // Largest first, so that the big files do not start last.
        jobs.sort_by_cached_key(|(j, _)| {
            std::cmp::Reverse(std::fs::metadata(j.path()).map_or(0, |m| m.len()))
        });
        let loaded: Vec<(Loaded, usize)> = jobs
            .into_par_iter()
            .with_max_len(1)
            .map(|(j, uses)| {
                let l = match j {
                    Job::Mesh(p) => Loaded::Mesh(shapes::load_obj(&p).ok(), p),
                    Job::Texture(p) => Loaded::Texture(Texture::load(&p).ok(), p),
                };
                (l, uses)
            })
            .collect();
        let mut out = Prefetched::default();
        for (l, uses) in loaded {
            match l {
                Loaded::Mesh(Some(m), p) => {
                    out.meshes.insert(p, (m, uses));
                }
                Loaded::Texture(Some(t), p) => {
                    out.textures.insert(p, (t, uses));
                }
                _ => {}
            }
        }
        out
    }

    /// The mesh at `path`: loaded ahead, else loaded now (and its error reported).
    pub fn mesh(&mut self, path: &Path) -> crate::error::Result<MeshData> {
        match take(&mut self.meshes, path) {
            Some(m) => Ok(m),
            None => shapes::load_obj(path),
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

enum Loaded {
    Mesh(Option<MeshData>, PathBuf),
    Texture(Option<Texture>, PathBuf),
}

impl Job {
    fn path(&self) -> &Path {
        match self {
            Job::Mesh(p) | Job::Texture(p) => p,
        }
    }

    /// The same kind of file at the same path.
    fn same(&self, other: &Job) -> bool {
        matches!(
            (self, other),
            (Job::Mesh(a), Job::Mesh(b)) | (Job::Texture(a), Job::Texture(b)) if a == b
        )
    }
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
