//! The files a Mitsuba scene reads (OBJ, PLY and `.serialized` meshes and bitmap textures),
//! loaded on every core before the scene is built. Mitsuba 3 loads its shapes in parallel too; footprint's
//! builder walks the XML in order (ids, references, materials shared between shapes), so the
//! slow part, parsing and decoding the files, runs here first, largest file first, and the
//! builder takes each file's result from [`Prefetched`] where it would have loaded it.
//!
//! Only successful loads are kept: a file that fails is loaded again by the builder at its
//! place in the document, which reports the error exactly as a sequential load does (the
//! first failing element in document order, with its file name).

use super::meshes::{MeshData, MeshSource};
use super::shape::mesh_source;
use super::xml::{Doc, Props};
use crate::scene::texture::Texture;
use rayon::prelude::*;
use roxmltree::Node;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Meshes (by file and, in a `.serialized` file, mesh) and textures (by resolved path)
/// loaded ahead, each with the number of elements that name it: the last of them takes the
/// file's data out (no second copy of a large mesh lives while the scene is built).
#[derive(Default)]
pub struct Prefetched {
    meshes: HashMap<MeshSource, (MeshData, usize)>,
    textures: HashMap<PathBuf, (Texture, usize)>,
}

/// A file to load ahead.
#[derive(Clone, PartialEq, Eq, Hash)]
enum Job {
    Mesh(MeshSource),
    Texture(PathBuf),
}

impl Job {
    fn path(&self) -> &Path {
        match self {
            Job::Mesh(source) => source.path(),
            Job::Texture(path) => path,
        }
    }
}

impl Prefetched {
    /// Loads the file of every `<shape>` of type `obj`, `ply` or `serialized` and every
    /// `<texture type="bitmap">` under `root` in parallel. Elements whose type or file name
    /// cannot be read are left to the builder, which reports them.
    pub fn load(doc: &Doc, root: Node) -> Prefetched {
        // Each file with the number of elements that name it.
        let mut uses: HashMap<Job, usize> = HashMap::new();
        for n in root.descendants().filter(|n| n.is_element()) {
            let Some(kind) = doc.attr(n, "type").ok().flatten() else {
                continue;
            };
            let Ok(p) = Props::new(doc, n) else {
                continue;
            };
            let job = match (n.tag_name().name(), kind.as_str()) {
                ("shape", kind) => mesh_source(doc, n, kind, &p).ok().flatten().map(Job::Mesh),
                ("texture", "bitmap") => p
                    .string("filename")
                    .ok()
                    .flatten()
                    .map(|name| Job::Texture(doc.file(&name))),
                _ => None,
            };
            if let Some(job) = job {
                *uses.entry(job).or_default() += 1;
            }
        }
        let mut jobs: Vec<_> = uses.into_iter().collect();
        // Largest first, so that the big files do not start last.
        jobs.sort_by_cached_key(|(job, _)| {
            std::cmp::Reverse(std::fs::metadata(job.path()).map_or(0, |m| m.len()))
        });
        let loaded: Vec<_> = jobs
            .into_par_iter()
            .with_max_len(1)
            .map(|(job, uses)| {
                let file = match &job {
                    Job::Mesh(source) => source.load().ok().map(File::Mesh),
                    Job::Texture(path) => Texture::load(path).ok().map(File::Texture),
                };
                (job, file, uses)
            })
            .collect();
        let mut out = Prefetched::default();
        for (job, file, uses) in loaded {
            match (job, file) {
                (Job::Mesh(source), Some(File::Mesh(m))) => {
                    out.meshes.insert(source, (m, uses));
                }
                (Job::Texture(path), Some(File::Texture(t))) => {
                    out.textures.insert(path, (t, uses));
                }
                _ => {}
            }
        }
        out
    }

    /// The mesh `source` names: loaded ahead, else loaded now (and its error reported).
    pub fn mesh(&mut self, source: &MeshSource) -> crate::error::Result<MeshData> {
        match take(&mut self.meshes, source) {
            Some(m) => Ok(m),
            None => source.load(),
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

/// The data of `key`: a copy while other elements will still ask for it, the data itself
/// for the last.
fn take<K, Q, T>(files: &mut HashMap<K, (T, usize)>, key: &Q) -> Option<T>
where
    K: std::borrow::Borrow<Q> + std::hash::Hash + Eq,
    Q: std::hash::Hash + Eq + ?Sized,
    T: Clone,
{
    let (data, uses) = files.get_mut(key)?;
    if *uses > 1 {
        *uses -= 1;
        return Some(data.clone());
    }
    files.remove(key).map(|(data, _)| data)
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
