//! The document walk: the parameters (`<default>` and `-D`), then every top-level element in
//! order, each handed to the builder, and the scene made from what the builder gathered.

use super::builder::Builder;
use super::prefetch;
use super::xml::{Doc, legacy_version};
use crate::error::{Error, Result};
use crate::scene::Scene;
use std::collections::HashMap;
use std::path::Path;

/// How deep elements may nest (`<scene>` is 1; Mitsuba scenes nest a handful deep).
pub const MAX_DEPTH: usize = 64;

/// Options of an import.
#[derive(Clone, Debug, Default)]
pub struct ImportOptions {
    /// `-D name=value` overrides of `<default>` parameters.
    pub defines: Vec<(String, String)>,
    /// Replace unsupported elements with documented stand-ins instead of failing.
    pub lenient: bool,
}

/// Loads a Mitsuba 3 XML scene.
pub fn load(path: &Path, opts: &ImportOptions) -> Result<Scene> {
    load_with(path, opts, true)
}

/// [`load`], with the files loaded ahead in parallel ([`prefetch`]) or each where the builder
/// reaches it.
fn load_with(path: &Path, opts: &ImportOptions, prefetch: bool) -> Result<Scene> {
    let text = std::fs::read_to_string(path).map_err(|reason| Error::Io {
        path: path.to_path_buf(),
        reason,
    })?;
    let xml = roxmltree::Document::parse(&text).map_err(|e| {
        let p = e.pos();
        Error::Syntax {
            path: path.to_path_buf(),
            line: p.row as usize,
            column: p.col as usize,
            message: format!("XML: {e}"),
        }
    })?;
    let root = xml.root_element();
    let mut doc = Doc {
        path,
        dir: path.parent().unwrap_or(Path::new(".")).to_path_buf(),
        xml: &xml,
        params: HashMap::new(),
        lenient: opts.lenient,
        legacy: false,
        notes: Default::default(),
    };
    if root.tag_name().name() != "scene" {
        return Err(doc.err(root, "the root element must be <scene>"));
    }
    // Mitsuba 3 requires the version, and upgrades the property names of files older than
    // 2.0 (Mitsuba 0.5 and 0.6) as it loads them; footprint does the same.
    let version = root.attribute("version").ok_or_else(|| {
        doc.err(
            root,
            "<scene> needs a 'version' attribute (Mitsuba 3 requires it)",
        )
    })?;
    doc.legacy = legacy_version(version).ok_or_else(|| {
        doc.err(
            root,
            format!("version '{version}' is not a version number (such as 3.0.0)"),
        )
    })?;
    // The builder walks nested objects recursively: a bound on the depth bounds its stack.
    let mut stack = vec![(root, 1usize)];
    while let Some((node, depth)) = stack.pop() {
        if depth > MAX_DEPTH {
            return Err(doc.err(
                node,
                format!("elements are nested more than {MAX_DEPTH} deep"),
            ));
        }
        stack.extend(
            node.children()
                .filter(|c| c.is_element())
                .map(|c| (c, depth + 1)),
        );
    }
    // Parameters: <default> elements, then the command line.
    for c in root.children().filter(|c| c.has_tag_name("default")) {
        let name = c
            .attribute("name")
            .ok_or_else(|| doc.err(c, "<default> needs 'name'"))?;
        let value = c
            .attribute("value")
            .ok_or_else(|| doc.err(c, "<default> needs 'value'"))?;
        doc.params.insert(name.to_string(), value.to_string());
    }
    for (k, v) in &opts.defines {
        let used = text.match_indices(&format!("${k}")).any(|(i, m)| {
            !text[i + m.len()..]
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_alphanumeric() || c == '_')
        });
        if !used {
            return Err(Error::invalid(
                path,
                format!("-D {k}={v}: the scene has no parameter '${k}'"),
            ));
        }
        doc.params.insert(k.clone(), v.clone());
    }
    let mut b = Builder::new(&doc)?;
    if prefetch {
        b.files = prefetch::Prefetched::load(&doc, root);
    }
    for c in doc.children(root) {
        match c.tag_name().name() {
            "default" => {}
            "integrator" => b.integrator(c)?,
            "sensor" => b.sensor(c)?,
            "bsdf" => {
                b.bsdf(c)?;
            }
            "texture" => {
                b.texture(c)?;
            }
            "shape" => b.shape(c)?,
            "emitter" => b.emitter(c)?,
            other => doc.unsupported(
                c,
                &format!("<{other}>"),
                "default, integrator, sensor, bsdf, texture, shape, emitter",
                "nothing (the element is skipped)",
            )?,
        }
    }
    let camera = b
        .camera
        .take()
        .ok_or_else(|| Error::invalid(path, "the scene has no <sensor>"))?;
    if b.settings
        .integrator
        .as_ref()
        .is_some_and(|i| i.name == "lt")
        && b.lights.iter().any(|l| l.is_environment())
    {
        doc.notes.borrow_mut().push(format!(
            "{}: ptracer with an environment (constant or envmap): footprint's light tracer does not see the environment directly (the background stays black); --integrator pt or combined show it",
            path.display()
        ));
    }
    // Files loaded ahead that no element took (under an element the builder skipped).
    drop(std::mem::take(&mut b.files));
    b.stats.triangles = b.triangles.len();
    let notes = doc.notes.take();
    let mut scene = Scene::new(
        camera,
        b.triangles,
        b.shading,
        b.materials,
        b.textures,
        b.lights,
        b.settings,
        b.stats,
    )
    .map_err(|m| Error::invalid(path, m))?;
    scene.import_notes = notes;
    scene.source_params = opts
        .defines
        .iter()
        .map(|(k, v)| format!("-D {k}={v}"))
        .collect::<Vec<_>>()
        .join(" ");
    Ok(scene)
}

/// Parses `-D name=value` arguments.
pub fn parse_define(s: &str) -> std::result::Result<(String, String), String> {
    let (k, v) = s
        .split_once('=')
        .ok_or_else(|| format!("'{s}' is not name=value"))?;
    let k = k.trim();
    if k.is_empty() || !k.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(format!(
            "'{k}' is not a parameter name (letters, digits, _)"
        ));
    }
    Ok((k.to_string(), v.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Loading the files ahead in parallel builds the same scene as loading each where the
    /// builder reaches it: the same triangles, shading, materials and textures, on a scene
    /// of OBJ meshes (desk's export), one with a bitmap texture (features) and one with PLY
    /// and `.serialized` meshes, two of one file (meshes).
    #[test]
    fn files_loaded_ahead_build_the_same_scene() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        for file in [
            "desk/mitsuba/scene.xml",
            "features/scene.xml",
            "meshes/scene.xml",
        ] {
            let path = root.join(file);
            let opts = ImportOptions::default();
            let ahead = load_with(&path, &opts, true).unwrap();
            let one_by_one = load_with(&path, &opts, false).unwrap();
            assert!(!ahead.triangles.is_empty(), "{file}");
            let same = |a: &dyn std::fmt::Debug, b: &dyn std::fmt::Debug| {
                format!("{a:?}") == format!("{b:?}")
            };
            assert!(
                same(&ahead.triangles, &one_by_one.triangles),
                "{file}: triangles"
            );
            assert!(same(&ahead.shading, &one_by_one.shading), "{file}: shading");
            assert!(
                same(&ahead.materials, &one_by_one.materials),
                "{file}: materials"
            );
            assert!(
                same(&ahead.textures, &one_by_one.textures),
                "{file}: textures"
            );
        }
        assert!(
            !load_with(
                &root.join("features/scene.xml"),
                &ImportOptions::default(),
                true
            )
            .unwrap()
            .textures
            .is_empty(),
            "features has a bitmap texture"
        );
    }
}
