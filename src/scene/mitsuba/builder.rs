//! The builder an import fills: the scene's parts as the elements are read, the elements
//! already built (a shared BSDF or texture is built once), and `id`/`<ref>` resolution.

use super::prefetch;
use super::xml::Doc;
use crate::bsdf::material::Material;
use crate::error::Result;
use crate::scene::LoadStats;
use crate::scene::camera::Camera;
use crate::scene::geometry::{TriangleGeom, TriangleShading};
use crate::scene::light::Light;
use crate::scene::texture::Texture;
use crate::settings::RenderSettings;
use roxmltree::{Node, NodeId};
use std::collections::HashMap;

pub(super) struct Builder<'a, 'd> {
    pub(super) doc: &'d Doc<'a>,
    /// Elements with an `id`.
    pub(super) ids: HashMap<String, Node<'a, 'a>>,
    pub(super) camera: Option<Camera>,
    pub(super) settings: RenderSettings,
    pub(super) triangles: Vec<TriangleGeom>,
    pub(super) shading: Vec<TriangleShading>,
    pub(super) materials: Vec<Material>,
    pub(super) textures: Vec<Texture>,
    pub(super) lights: Vec<Light>,
    pub(super) stats: LoadStats,
    /// Built BSDF elements (their material) and texture elements (texture index).
    pub(super) material_of: HashMap<NodeId, Material>,
    pub(super) texture_of: HashMap<NodeId, u32>,
    /// Index of each scene material by the BSDF element it comes from and its emission.
    pub(super) material_index: HashMap<(Option<NodeId>, [u32; 3]), u32>,
    /// BSDF elements being built (a reference cycle is an error, not a stack overflow).
    pub(super) building: Vec<NodeId>,
    /// The meshes and textures, loaded ahead in parallel.
    pub(super) files: prefetch::Prefetched,
}

impl<'a, 'd> Builder<'a, 'd> {
    pub(super) fn new(doc: &'d Doc<'a>) -> Result<Self> {
        let mut ids = HashMap::new();
        for n in doc
            .xml
            .descendants()
            .filter(|n| n.is_element() && !n.has_tag_name("ref"))
        {
            if let Some(id) = n.attribute("id") {
                if let Some(prev) = ids.insert(id.to_string(), n) {
                    let (line, _) = doc.pos(prev);
                    return Err(doc.err(n, format!("id '{id}' is already used on line {line}")));
                }
            }
        }
        let settings = RenderSettings {
            // Mitsuba's `path` integrator has no depth limit by default.
            max_depth: 1024,
            ..RenderSettings::default()
        };
        Ok(Builder {
            doc,
            ids,
            camera: None,
            settings,
            triangles: Vec::new(),
            shading: Vec::new(),
            materials: Vec::new(),
            textures: Vec::new(),
            lights: Vec::new(),
            stats: LoadStats::default(),
            material_of: HashMap::new(),
            texture_of: HashMap::new(),
            material_index: HashMap::new(),
            building: Vec::new(),
            files: Default::default(),
        })
    }

    pub(super) fn kind(&self, node: Node) -> Result<String> {
        self.doc.req_attr(node, "type")
    }

    /// The element a `<ref id="...">` points to.
    pub(super) fn deref(&self, node: Node<'a, 'a>) -> Result<Node<'a, 'a>> {
        if node.tag_name().name() != "ref" {
            return Ok(node);
        }
        let id = self.doc.req_attr(node, "id")?;
        self.ids
            .get(&id)
            .copied()
            .ok_or_else(|| self.doc.err(node, format!("no element has id '{id}'")))
    }
}
