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

/// Meshes and textures loaded ahead, by resolved path.
#[derive(Default)]
pub struct Prefetched {
    meshes: HashMap<PathBuf, MeshData>,
    textures: HashMap<PathBuf, Texture>,
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
        let mut jobs: Vec<Job> = Vec::new();
        for n in root.descendants().filter(|n| n.is_element()) {
            let kind = doc.attr(n, "type").ok().flatten();
            let job = match (n.tag_name().name(), kind.as_deref()) {
                ("shape", Some("obj")) => file_of(n).map(Job::Mesh),
                ("texture", Some("bitmap")) => file_of(n).map(Job::Texture),
                _ => None,
            };
            if let Some(job) = job {
                let path = job.path();
                if !jobs.iter().any(|j| j.path() == path) {
                    jobs.push(job);
                }
            }
        }
        // Largest first, so that the big files do not start last.
        jobs.sort_by_key(|j| std::cmp::Reverse(std::fs::metadata(j.path()).map_or(0, |m| m.len())));
        let loaded: Vec<Loaded> = jobs
            .par_iter()
            .with_max_len(1)
            .map(|j| match j {
                Job::Mesh(p) => Loaded::Mesh(p.clone(), shapes::load_obj(p).ok()),
                Job::Texture(p) => Loaded::Texture(p.clone(), Texture::load(p).ok()),
            })
            .collect();
        let mut out = Prefetched::default();
        for l in loaded {
            match l {
                Loaded::Mesh(p, Some(m)) => {
                    out.meshes.insert(p, m);
                }
                Loaded::Texture(p, Some(t)) => {
                    out.textures.insert(p, t);
                }
                _ => {}
            }
        }
        out
    }

    /// The mesh at `path`: loaded ahead, else loaded now (and its error reported).
    pub fn mesh(&self, path: &Path) -> crate::error::Result<MeshData> {
        match self.meshes.get(path) {
            Some(m) => Ok(m.clone()),
            None => shapes::load_obj(path),
        }
    }

    /// The texture at `path`: loaded ahead, else loaded now (and its error reported).
    pub fn texture(&self, path: &Path) -> crate::error::Result<Texture> {
        match self.textures.get(path) {
            Some(t) => Ok(t.clone()),
            None => Texture::load(path),
        }
    }
}

enum Loaded {
    Mesh(PathBuf, Option<MeshData>),
    Texture(PathBuf, Option<Texture>),
}

impl Job {
    fn path(&self) -> &Path {
        match self {
            Job::Mesh(p) | Job::Texture(p) => p,
        }
    }
}
