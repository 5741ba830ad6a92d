//! Mitsuba 3 scene import: `footprint render scene.xml` reads the scenes researchers already
//! keep (Bitterli's collection, the path-guiding papers' suites) and renders what Mitsuba 3
//! renders from them.
//!
//! Read: `<default>` parameters with `$name` substitution (overridden by `-D name=value`),
//! `id`/`<ref>`, `to_world` transforms, the `perspective` sensor (`fov`, `fov_axis`) with its
//! `hdrfilm` (size, `box`/`tent`/`gaussian` filter) and sampler (`sample_count`), the `path`
//! (and `ptracer`) integrator's `max_depth`; shapes `obj`, `rectangle`, `cube`, `sphere`;
//! BSDFs `diffuse`, `twosided`, `dielectric`, `thindielectric`, `conductor`, `roughconductor`,
//! `plastic`, `roughplastic`; textures `bitmap` and `checkerboard` (with `to_uv`); emitters
//! `area`, `point`, `spot`, `constant`. Anything else stops the import with an error naming
//! the element, its line and what is supported, unless `--lenient`, which replaces it with
//! the stand-in the error names and lists every replacement. `docs/mitsuba.md` tables the
//! mapping.

pub mod export;
mod prefetch;
mod shapes;
mod xml;

pub use shapes::MeshData;

use crate::Rgb;
use crate::bsdf::material::{Material, MaterialKind};
use crate::bsdf::microfacet::Microfacet;
use crate::error::{Error, Result};
use crate::film::filter::{FilterKind, PixelFilter};
use crate::math::Frame;
use crate::scene::camera::Camera;
use crate::scene::geometry::{TriangleGeom, TriangleShading};
use crate::scene::light::Light;
use crate::scene::texture::Texture;
use crate::scene::{LoadStats, Scene};
use crate::settings::{Named, RenderSettings};
use glam::{Affine2, Mat3, Mat4, Vec2, Vec3};
use roxmltree::{Node, NodeId};
use std::collections::HashMap;
use std::path::Path;
use xml::{Doc, Props};

/// Options of an import.
#[derive(Clone, Debug, Default)]
pub struct ImportOptions {
    /// `-D name=value` overrides of `<default>` parameters.
    pub defines: Vec<(String, String)>,
    /// Replace unsupported elements with documented stand-ins instead of failing.
    pub lenient: bool,
}

/// Named indices of refraction Mitsuba 3 accepts for `int_ior`/`ext_ior`.
const NAMED_IOR: &[(&str, f32)] = &[
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.333),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.575),
    ("diamond", 2.419),
];

const SHAPES: &str = "obj, rectangle, cube, sphere";
const BSDFS: &str = "diffuse, twosided, dielectric, thindielectric, conductor, roughconductor, plastic, roughplastic";
const EMITTERS: &str = "area (on a shape), point, spot, constant";
const TEXTURES: &str = "bitmap, checkerboard";

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
        notes: Default::default(),
    };
    if root.tag_name().name() != "scene" {
        return Err(doc.err(root, "the root element must be <scene>"));
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
            "{}: ptracer with a constant emitter: footprint's light tracer does not see the environment directly (the background stays black); --integrator pt or combined show it",
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

struct Builder<'a, 'd> {
    doc: &'d Doc<'a>,
    /// Elements with an `id`.
    ids: HashMap<String, Node<'a, 'a>>,
    camera: Option<Camera>,
    settings: RenderSettings,
    triangles: Vec<TriangleGeom>,
    shading: Vec<TriangleShading>,
    materials: Vec<Material>,
    textures: Vec<Texture>,
    lights: Vec<Light>,
    stats: LoadStats,
    /// Built BSDF elements (material index) and texture elements (texture index).
    material_of: HashMap<NodeId, Material>,
    texture_of: HashMap<NodeId, u32>,
    /// Index of each scene material by the BSDF element it comes from and its emission.
    material_index: HashMap<(Option<NodeId>, [u32; 3]), u32>,
    /// BSDF elements being built (a reference cycle is an error, not a stack overflow).
    building: Vec<NodeId>,
    /// The meshes and textures, loaded ahead in parallel.
    files: prefetch::Prefetched,
}

impl<'a, 'd> Builder<'a, 'd> {
    fn new(doc: &'d Doc<'a>) -> Result<Self> {
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

    fn kind(&self, node: Node) -> Result<String> {
        self.doc.req_attr(node, "type")
    }

    /// The element a `<ref id="...">` points to.
    fn deref(&self, node: Node<'a, 'a>) -> Result<Node<'a, 'a>> {
        if node.tag_name().name() != "ref" {
            return Ok(node);
        }
        let id = self.doc.req_attr(node, "id")?;
        self.ids
            .get(&id)
            .copied()
            .ok_or_else(|| self.doc.err(node, format!("no element has id '{id}'")))
    }

    // ---- integrator, sensor ----

    /// A method name given by `node`, with its place for error messages.
    fn named(&self, node: Node, name: &str) -> Named {
        let (line, column) = self.doc.pos(node);
        Named {
            name: name.into(),
            at: format!("{}:{line}:{column}", self.doc.path.display()),
        }
    }

    fn integrator(&mut self, node: Node<'a, 'a>) -> Result<()> {
        let kind = self.kind(node)?;
        let p = Props::new(self.doc, node)?;
        match kind.as_str() {
            "path" | "ptracer" => {
                self.settings.integrator =
                    Some(self.named(node, if kind == "path" { "pt" } else { "lt" }));
            }
            other => {
                self.doc.unsupported(
                    node,
                    &format!("integrator '{other}'"),
                    "path, ptracer",
                    "footprint's path tracer",
                )?;
                self.settings.integrator = Some(self.named(node, "pt"));
                return Ok(());
            }
        }
        if let Some(d) = p.integer("rr_depth")? {
            self.settings.rr_depth = match d {
                1..=1024 => d as u32,
                _ => {
                    return Err(self.doc.err(
                        p.get("rr_depth").unwrap_or(node),
                        format!("rr_depth must be in 1..=1024, got {d}"),
                    ));
                }
            };
        }
        if let Some(d) = p.integer("max_depth")? {
            self.settings.max_depth = match d {
                -1 => 1024,
                1..=1024 => d as u32,
                _ => {
                    return Err(self.doc.err(
                        p.get("max_depth").unwrap_or(node),
                        format!("max_depth must be -1 (unlimited) or in 1..=1024, got {d}"),
                    ));
                }
            };
        }
        if p.boolean("hide_emitters")? == Some(true) {
            self.doc.unsupported(
                node,
                "hide_emitters = true",
                "hide_emitters = false",
                "visible emitters",
            )?;
        }
        // Russian roulette changes the noise, not the expected image.
        p.ignore(&["rr_depth", "samples_per_pass", "timeout"]);
        p.finish(&format!("integrator '{kind}'"))
    }

    fn sensor(&mut self, node: Node<'a, 'a>) -> Result<()> {
        let kind = self.kind(node)?;
        if self.camera.is_some() {
            return self.doc.unsupported(
                node,
                "a second <sensor>",
                "one sensor",
                "the first sensor",
            );
        }
        let p = Props::new(self.doc, node)?;
        if kind != "perspective" {
            self.doc.unsupported(
                node,
                &format!("sensor '{kind}'"),
                "perspective",
                "a pinhole camera with the same field of view",
            )?;
            p.ignore(&["aperture_radius", "focus_distance"]);
        }
        let m = p.transform("to_world")?.unwrap_or(Mat4::IDENTITY);
        let fov = p.float("fov")?;
        if fov.is_none() && p.get("focal_length").is_some() {
            return Err(self.doc.err(
                node,
                "focal_length is not supported: give the field of view as 'fov' (degrees)",
            ));
        }
        let fov = fov.unwrap_or(90.0);
        if !(fov > 0.0 && fov < 179.0) {
            return Err(self
                .doc
                .err(node, format!("fov must be in (0, 179) degrees, got {fov}")));
        }
        let axis = p.string("fov_axis")?.unwrap_or_else(|| "x".into());
        p.ignore(&["near_clip", "far_clip", "shutter_open", "shutter_close"]);
        for off in ["principal_point_offset_x", "principal_point_offset_y"] {
            if p.float(off)?.is_some_and(|v| v != 0.0) {
                self.doc
                    .unsupported(node, off, "a centred principal point", "a centred one")?;
            }
        }
        // Film and sampler.
        let (mut width, mut height) = (768u32, 576u32);
        let mut filter = FilterKind::Gaussian { stddev: 0.5 };
        let mut spp = None;
        for c in &p.unnamed {
            let c = self.deref(*c)?;
            match c.tag_name().name() {
                "film" => {
                    let fk = self.kind(c)?;
                    if fk != "hdrfilm" {
                        self.doc.unsupported(
                            c,
                            &format!("film '{fk}'"),
                            "hdrfilm",
                            "an hdrfilm",
                        )?;
                    }
                    let fp = Props::new(self.doc, c)?;
                    let dim = |name: &str, default: u32| -> Result<u32> {
                        match fp.integer(name)? {
                            None => Ok(default),
                            Some(v) if (1..=32768).contains(&v) => Ok(v as u32),
                            Some(v) => Err(self.doc.err(
                                fp.get(name).unwrap_or(c),
                                format!("film {name} must be in 1..=32768, got {v}"),
                            )),
                        }
                    };
                    width = dim("width", width)?;
                    height = dim("height", height)?;
                    for crop in [
                        "crop_offset_x",
                        "crop_offset_y",
                        "crop_width",
                        "crop_height",
                    ] {
                        if fp.integer(crop)?.is_some() {
                            self.doc
                                .unsupported(c, crop, "the full film", "the full film")?;
                        }
                    }
                    fp.ignore(&[
                        "file_format",
                        "pixel_format",
                        "component_format",
                        "banner",
                        "compensate",
                        "sample_border",
                    ]);
                    fp.finish("the film")?;
                    for rf in fp.unnamed.iter().filter(|n| n.has_tag_name("rfilter")) {
                        filter = self.rfilter(*rf)?;
                    }
                }
                "sampler" => {
                    let sp = Props::new(self.doc, c)?;
                    if let Some(n) = sp.integer("sample_count")? {
                        if !(1..=1 << 24).contains(&n) {
                            return Err(self
                                .doc
                                .err(c, format!("sample_count must be in 1..=16777216, got {n}")));
                        }
                        spp = Some(n as u32);
                    }
                    // Every sampler converges to the same image; footprint uses its own.
                    sp.ignore(&["seed", "jitter", "scramble_seed", "pixel_samples"]);
                    sp.finish("the sampler")?;
                }
                other => {
                    self.doc.unsupported(
                        c,
                        &format!("<{other}> in a sensor"),
                        "film, sampler",
                        "nothing",
                    )?;
                }
            }
        }
        p.finish(&format!("sensor '{kind}'"))?;
        if let Some(s) = spp {
            self.settings.spp = s;
        }
        let (w, h) = (width as f32, height as f32);
        let tan_half = (fov.to_radians() * 0.5).tan();
        let tan_half_y = match axis.as_str() {
            "x" => tan_half * h / w,
            "y" => tan_half,
            "diagonal" => tan_half * h / (w * w + h * h).sqrt(),
            "smaller" if w <= h => tan_half * h / w,
            "smaller" => tan_half,
            "larger" if w >= h => tan_half * h / w,
            "larger" => tan_half,
            other => {
                return Err(self.doc.err(
                    node,
                    format!("fov_axis '{other}' (expected x, y, diagonal, smaller or larger)"),
                ));
            }
        };
        let fov_y = 2.0 * tan_half_y.atan().to_degrees();
        // Mitsuba's camera looks along local +z with +y up; its image's x runs along local -x.
        let position = m.transform_point3(Vec3::ZERO);
        let forward = m.transform_vector3(Vec3::Z).try_normalize();
        let up = m.transform_vector3(Vec3::Y).try_normalize();
        let left = m.transform_vector3(Vec3::X).try_normalize();
        let (Some(forward), Some(up), Some(left)) = (forward, up, left) else {
            return Err(self.doc.err(node, "the sensor's to_world has a zero axis"));
        };
        if forward.dot(up).abs() > 1e-3
            || forward.dot(left).abs() > 1e-3
            || up.dot(left).abs() > 1e-3
        {
            return Err(self.doc.err(
                node,
                "the sensor's to_world is not a rotation (its axes are not perpendicular)",
            ));
        }
        let frame = Frame {
            x: -left,
            y: up,
            z: forward,
        };
        let mut camera = Camera::from_frame(position, frame, fov_y, width, height)
            .map_err(|e| self.doc.err(node, e))?;
        camera.filter = PixelFilter::new(filter);
        self.camera = Some(camera);
        Ok(())
    }

    fn rfilter(&self, node: Node<'a, 'a>) -> Result<FilterKind> {
        let kind = self.kind(node)?;
        let p = Props::new(self.doc, node)?;
        let f = match kind.as_str() {
            "box" => FilterKind::Box,
            "tent" => {
                let radius = p.float_or("radius", 1.0)?;
                if !(radius > 0.0 && radius <= 6.0) {
                    return Err(self.doc.err(node, "tent radius must be in (0, 6] pixels"));
                }
                FilterKind::Tent { radius }
            }
            "gaussian" => {
                let stddev = p.float_or("stddev", 0.5)?;
                if !(stddev > 0.0 && stddev <= 1.5) {
                    return Err(self
                        .doc
                        .err(node, "gaussian stddev must be in (0, 1.5] pixels"));
                }
                FilterKind::Gaussian { stddev }
            }
            other => {
                self.doc.unsupported(
                    node,
                    &format!("rfilter '{other}'"),
                    "box, tent, gaussian",
                    "Mitsuba's default gaussian filter",
                )?;
                return Ok(FilterKind::Gaussian { stddev: 0.5 });
            }
        };
        p.finish(&format!("rfilter '{kind}'"))?;
        Ok(f)
    }

    // ---- textures ----

    /// A colour property that may be a texture: the constant factor and the texture index.
    fn color_or_texture(
        &mut self,
        p: &Props<'a, 'd>,
        name: &str,
        default: Rgb,
    ) -> Result<(Rgb, Option<u32>)> {
        if p.is_texture(name) {
            let n = p.get(name).unwrap();
            let t = self.deref(n)?;
            if t.tag_name().name() != "texture" {
                return Err(self
                    .doc
                    .err(n, format!("'{name}' must be a colour or a <texture>")));
            }
            let id = self.texture(t)?;
            return Ok((Rgb::ONE, id));
        }
        Ok(match p.rgb(name)? {
            Some(c) => (c, None),
            None => {
                if let Some(n) = p.get(name) {
                    return Err(self.doc.err(
                        n,
                        format!("'{name}' must be an <rgb>, <spectrum>, <float> or <texture>"),
                    ));
                }
                (default, None)
            }
        })
    }

    /// Builds a `<texture>` once; `None` with `--lenient` when its type is unsupported (the
    /// colour factor then stands alone).
    fn texture(&mut self, node: Node<'a, 'a>) -> Result<Option<u32>> {
        if let Some(&i) = self.texture_of.get(&node.id()) {
            return Ok(Some(i));
        }
        let kind = self.kind(node)?;
        let p = Props::new(self.doc, node)?;
        let mut tex = match kind.as_str() {
            "bitmap" => {
                let file = p
                    .string("filename")?
                    .ok_or_else(|| self.doc.err(node, "bitmap needs 'filename'"))?;
                let ft = p
                    .string("filter_type")?
                    .unwrap_or_else(|| "bilinear".into());
                if ft != "bilinear" {
                    self.doc.unsupported(
                        node,
                        &format!("filter_type '{ft}'"),
                        "bilinear",
                        "bilinear filtering",
                    )?;
                }
                let wrap = p.string("wrap_mode")?.unwrap_or_else(|| "repeat".into());
                if wrap != "repeat" {
                    self.doc.unsupported(
                        node,
                        &format!("wrap_mode '{wrap}'"),
                        "repeat",
                        "repeat",
                    )?;
                }
                if p.boolean("raw")? == Some(true) {
                    self.doc.unsupported(
                        node,
                        "raw = true",
                        "sRGB-encoded 8-bit images",
                        "sRGB decoding",
                    )?;
                }
                self.files.texture(&self.doc.file(&file))?
            }
            "checkerboard" => {
                let c0 = p.rgb("color0")?.unwrap_or(Rgb::splat(0.4));
                let c1 = p.rgb("color1")?.unwrap_or(Rgb::splat(0.2));
                if p.is_texture("color0") || p.is_texture("color1") {
                    return Err(self.doc.err(node, "checkerboard colours must be constant"));
                }
                Texture::checkerboard(c0, c1)
            }
            other => {
                self.doc.unsupported(
                    node,
                    &format!("texture '{other}'"),
                    TEXTURES,
                    "no texture (the colour factor alone)",
                )?;
                return Ok(None);
            }
        };
        if let Some(m) = p.transform("to_uv")? {
            // The 2-D affine part: rows and columns x, y and translation.
            let c = m.to_cols_array_2d();
            tex.to_uv = Some(Affine2::from_cols_array(&[
                c[0][0], c[0][1], c[1][0], c[1][1], c[3][0], c[3][1],
            ]));
        }
        p.finish(&format!("texture '{kind}'"))?;
        self.textures.push(tex);
        let i = self.textures.len() as u32 - 1;
        self.texture_of.insert(node.id(), i);
        Ok(Some(i))
    }

    // ---- BSDFs ----

    fn ior(&self, p: &Props<'a, 'd>, name: &str, default: f32) -> Result<f32> {
        let Some(n) = p.get(name) else {
            return Ok(default);
        };
        let v = self.doc.req_attr(n, "value")?;
        if let Ok(x) = v.trim().parse::<f32>() {
            if x.is_finite() && x > 0.0 {
                return Ok(x);
            }
        }
        NAMED_IOR
            .iter()
            .find(|(k, _)| *k == v.trim().to_lowercase())
            .map(|(_, x)| *x)
            .ok_or_else(|| {
                self.doc.err(
                    n,
                    format!(
                        "'{name}': '{v}' is neither a positive number nor a known material ({})",
                        NAMED_IOR
                            .iter()
                            .map(|(k, _)| *k)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                )
            })
    }

    fn microfacet(&self, p: &Props<'a, 'd>, node: Node) -> Result<(Microfacet, f32)> {
        let dist = match p.string("distribution")?.as_deref().unwrap_or("beckmann") {
            "beckmann" => Microfacet::Beckmann,
            "ggx" => Microfacet::Ggx,
            other => {
                return Err(self.doc.err(
                    node,
                    format!("distribution '{other}' (expected beckmann or ggx)"),
                ));
            }
        };
        let alpha = match (p.float("alpha")?, p.float("alpha_u")?, p.float("alpha_v")?) {
            (Some(a), None, None) => a,
            (None, Some(u), Some(v)) => {
                if (u - v).abs() > 1e-6 * u.max(v) {
                    self.doc.unsupported(
                        node,
                        "anisotropic roughness (alpha_u != alpha_v)",
                        "isotropic alpha",
                        &format!(
                            "isotropic alpha = sqrt(alpha_u alpha_v) = {}",
                            (u * v).sqrt()
                        ),
                    )?;
                }
                (u * v).sqrt()
            }
            (None, None, None) => 0.1,
            _ => {
                return Err(self
                    .doc
                    .err(node, "give either 'alpha' or both 'alpha_u' and 'alpha_v'"));
            }
        };
        if !(alpha > 0.0 && alpha <= 4.0) {
            return Err(self
                .doc
                .err(node, format!("alpha must be in (0, 4], got {alpha}")));
        }
        if p.is_texture("alpha") {
            return Err(self.doc.err(node, "a textured alpha is not supported"));
        }
        p.ignore(&["sample_visible"]);
        Ok((dist, alpha.max(1e-4)))
    }

    fn conductor_ior(&self, p: &Props<'a, 'd>, node: Node) -> Result<(Rgb, Rgb)> {
        let eta = p.rgb("eta")?;
        let k = p.rgb("k")?;
        let material = p.string("material")?;
        // Mitsuba's eta and k are relative to the exterior's index.
        let ext = self.ior(p, "ext_eta", 1.0)?;
        match (eta, k, material.as_deref()) {
            (Some(e), Some(k), None) => Ok((e / ext, k / ext)),
            // Mitsuba: `k` defaults to 1 when `eta` is given.
            (Some(e), None, None) => Ok((e / ext, Rgb::ONE / ext)),
            // Mitsuba's default `none`: η = 0, k = 1, whose Fresnel factor is 1 at every angle
            // (a perfect mirror).
            (None, None, None | Some("none")) => Ok((Rgb::ZERO, Rgb::ONE)),
            (None, None, Some(m)) => {
                self.doc.unsupported(
                    node,
                    &format!("conductor material '{m}'"),
                    "material 'none' or explicit 'eta' and 'k' colours",
                    "a perfect mirror (material 'none')",
                )?;
                Ok((Rgb::ZERO, Rgb::ONE))
            }
            _ => Err(self.doc.err(
                node,
                "give 'eta' (and 'k', default 1) or a 'material', not both",
            )),
        }
    }

    /// Builds a `<bsdf>` (once per element); the material is not yet in the scene.
    fn bsdf(&mut self, node: Node<'a, 'a>) -> Result<Material> {
        if let Some(m) = self.material_of.get(&node.id()) {
            return Ok(m.clone());
        }
        if self.building.contains(&node.id()) {
            return Err(self
                .doc
                .err(node, "this BSDF contains itself (a cycle of references)"));
        }
        self.building.push(node.id());
        let m = self.build_bsdf(node);
        self.building.pop();
        m
    }

    fn build_bsdf(&mut self, node: Node<'a, 'a>) -> Result<Material> {
        let kind = self.kind(node)?;
        let p = Props::new(self.doc, node)?;
        let name = node
            .attribute("id")
            .map(str::to_string)
            .unwrap_or_else(|| format!("{kind}@{}", self.doc.pos(node).0));
        let mut m = Material {
            name,
            two_sided: false,
            ..Material::default()
        };
        match kind.as_str() {
            "twosided" => {
                let inner: Vec<Node> = p
                    .unnamed
                    .iter()
                    .map(|n| self.deref(*n))
                    .collect::<Result<_>>()?;
                let inner: Vec<Node> = inner
                    .into_iter()
                    .filter(|n| n.has_tag_name("bsdf"))
                    .collect();
                match inner.as_slice() {
                    [b] => {
                        let mut im = self.bsdf(*b)?;
                        im.two_sided = true;
                        im.name = m.name;
                        m = im;
                    }
                    [b, ..] => {
                        self.doc.unsupported(
                            node,
                            "twosided with different front and back BSDFs",
                            "twosided with one BSDF",
                            "the front BSDF on both sides",
                        )?;
                        let mut im = self.bsdf(*b)?;
                        im.two_sided = true;
                        m = im;
                    }
                    [] => return Err(self.doc.err(node, "twosided needs a nested <bsdf>")),
                }
            }
            "diffuse" => {
                m.kind = MaterialKind::Diffuse;
                (m.kd, m.kd_texture) = self.color_or_texture(&p, "reflectance", Rgb::splat(0.5))?;
            }
            "dielectric" | "thindielectric" => {
                let int = self.ior(&p, "int_ior", 1.5046)?;
                let ext = self.ior(&p, "ext_ior", 1.000277)?;
                m.ni = int / ext;
                let (sr, srt) = self.color_or_texture(&p, "specular_reflectance", Rgb::ONE)?;
                let (st, stt) = self.color_or_texture(&p, "specular_transmittance", Rgb::ONE)?;
                if srt.is_some() || stt.is_some() || sr != Rgb::ONE {
                    self.doc.unsupported(
                        node,
                        "a textured or non-white specular_reflectance, or a textured specular_transmittance, of a dielectric",
                        "a constant specular_transmittance",
                        "white reflectance and the constant factor",
                    )?;
                }
                m.ks = sr;
                if kind == "dielectric" {
                    m.kind = MaterialKind::Glass;
                    // `tf` is the transmittance of a passage in and out: two interfaces.
                    m.tf = st * st;
                } else {
                    m.kind = MaterialKind::ThinGlass;
                    m.tf = st;
                }
            }
            "conductor" | "roughconductor" => {
                (m.eta, m.k) = self.conductor_ior(&p, node)?;
                (m.ks, m.ks_texture) =
                    self.color_or_texture(&p, "specular_reflectance", Rgb::ONE)?;
                if kind == "conductor" {
                    m.kind = MaterialKind::Conductor;
                } else {
                    m.kind = MaterialKind::RoughConductor;
                    (m.microfacet, m.alpha) = self.microfacet(&p, node)?;
                }
            }
            "plastic" | "roughplastic" => {
                let int = self.ior(&p, "int_ior", 1.49)?;
                let ext = self.ior(&p, "ext_ior", 1.000277)?;
                m.ni = int / ext;
                (m.kd, m.kd_texture) =
                    self.color_or_texture(&p, "diffuse_reflectance", Rgb::splat(0.5))?;
                (m.ks, m.ks_texture) =
                    self.color_or_texture(&p, "specular_reflectance", Rgb::ONE)?;
                m.nonlinear = p.boolean("nonlinear")?.unwrap_or(false);
                if kind == "plastic" {
                    m.kind = MaterialKind::Plastic;
                } else {
                    m.kind = MaterialKind::RoughPlastic;
                    (m.microfacet, m.alpha) = self.microfacet(&p, node)?;
                }
            }
            other => {
                self.doc.unsupported(
                    node,
                    &format!("bsdf '{other}'"),
                    BSDFS,
                    "a grey diffuse BSDF (reflectance 0.5)",
                )?;
                self.material_of.insert(node.id(), m.clone());
                return Ok(m);
            }
        }
        p.finish(&format!("bsdf '{kind}'"))?;
        let m = m.sanitized();
        self.material_of.insert(node.id(), m.clone());
        Ok(m)
    }

    /// Index of `m` in the scene's materials, adding it when new.
    /// Index of the scene material made from BSDF element `bsdf` (`None`: the default BSDF)
    /// with emission `m.ke`, adding `m` when new.
    fn material_id(&mut self, bsdf: Option<NodeId>, m: Material) -> u32 {
        let key = (bsdf, m.ke.to_array().map(f32::to_bits));
        if let Some(&i) = self.material_index.get(&key) {
            return i;
        }
        self.materials.push(m);
        let i = self.materials.len() as u32 - 1;
        self.material_index.insert(key, i);
        i
    }

    // ---- shapes ----

    fn shape(&mut self, node: Node<'a, 'a>) -> Result<()> {
        let kind = self.kind(node)?;
        let p = Props::new(self.doc, node)?;
        let mut to_world = p.transform("to_world")?.unwrap_or(Mat4::IDENTITY);
        let flip_normals = p.boolean("flip_normals")?.unwrap_or(false);
        let mut face_normals = false;
        let mut mesh = match kind.as_str() {
            "obj" => {
                let file = p
                    .string("filename")?
                    .ok_or_else(|| self.doc.err(node, "obj needs 'filename'"))?;
                face_normals = p.boolean("face_normals")?.unwrap_or(false);
                let flip_tex = p.boolean("flip_tex_coords")?.unwrap_or(true);
                let mut mesh = self.files.mesh(&self.doc.file(&file))?;
                if !flip_tex {
                    // Mitsuba then reads v as stored: flip it into the OBJ convention.
                    for t in mesh.uvs.iter_mut().flatten() {
                        t.y = 1.0 - t.y;
                    }
                }
                if mesh.normals.is_none() && !face_normals {
                    mesh.normals = Some(shapes::angle_weighted_normals(&mesh));
                }
                mesh
            }
            "rectangle" => shapes::rectangle(),
            "cube" => shapes::cube(),
            "sphere" => {
                let center = p.vec3("center")?.unwrap_or(Vec3::ZERO);
                let radius = p.float_or("radius", 1.0)?;
                if !(radius > 0.0) {
                    return Err(self.doc.err(
                        node,
                        format!("sphere radius must be positive, got {radius}"),
                    ));
                }
                to_world = to_world
                    * Mat4::from_translation(center)
                    * Mat4::from_scale(Vec3::splat(radius));
                shapes::sphere(64, 128)
            }
            other => {
                return self.doc.unsupported(
                    node,
                    &format!("shape '{other}'"),
                    SHAPES,
                    "nothing (the shape is skipped)",
                );
            }
        };
        p.ignore(&["face_normals"]);
        p.finish(&format!("shape '{kind}'"))?;
        // BSDF and area emitter among the nested objects.
        let mut material: Option<(NodeId, Material)> = None;
        let mut radiance = None;
        for c in &p.unnamed {
            let c = self.deref(*c)?;
            match c.tag_name().name() {
                "bsdf" => {
                    if material.is_some() {
                        return Err(self.doc.err(c, "a shape has one BSDF"));
                    }
                    material = Some((c.id(), self.bsdf(c)?));
                }
                "emitter" => {
                    let ek = self.kind(c)?;
                    if ek != "area" {
                        return Err(self
                            .doc
                            .err(c, format!("a shape's emitter must be 'area', not '{ek}'")));
                    }
                    let ep = Props::new(self.doc, c)?;
                    if ep.is_texture("radiance") {
                        self.doc.unsupported(
                            c,
                            "a textured radiance",
                            "a constant radiance",
                            "radiance 1",
                        )?;
                    }
                    let le = self.emission(&ep, "radiance")?;
                    ep.finish("emitter 'area'")?;
                    radiance = Some(le);
                }
                other => {
                    self.doc.unsupported(
                        c,
                        &format!("<{other}> in a shape"),
                        "bsdf, emitter, ref",
                        "nothing",
                    )?;
                }
            }
        }
        // Mitsuba's default BSDF: one-sided diffuse of reflectance 0.5.
        let (bsdf_node, mut m) = match material {
            Some((id, m)) => (Some(id), m),
            None => (
                None,
                Material {
                    name: "default".into(),
                    two_sided: false,
                    ..Material::default()
                },
            ),
        };
        if let Some(le) = radiance {
            m.ke = le;
            if let Some(id) = node.attribute("id") {
                m.name = format!("{} (emitter {id})", m.name);
            }
        }
        let material = self.material_id(bsdf_node, m);
        // Mitsuba's rectangle and sphere take their front from the transformed normal (the
        // inverse transpose), not from the winding, which a mirroring transform reverses.
        let primitive = matches!(kind.as_str(), "rectangle" | "sphere");
        let mirrored = primitive && Mat3::from_mat4(to_world).determinant() < 0.0;
        self.push_mesh(
            &mesh,
            to_world,
            material,
            face_normals,
            flip_normals,
            mirrored,
        );
        self.stats.meshes += 1;
        mesh.indices.clear();
        Ok(())
    }

    /// Adds a mesh's triangles; `flip` (flip_normals) turns normals and winding around,
    /// `rewind` reverses the winding only (a mirrored primitive).
    fn push_mesh(
        &mut self,
        mesh: &MeshData,
        to_world: Mat4,
        material: u32,
        face_normals: bool,
        flip: bool,
        rewind: bool,
    ) {
        let normal_matrix = Mat3::from_mat4(to_world).inverse().transpose();
        let pos: Vec<Vec3> = mesh
            .positions
            .iter()
            .map(|p| to_world.transform_point3(*p))
            .collect();
        let normals: Option<Vec<Vec3>> = if face_normals {
            None
        } else {
            mesh.normals.as_ref().map(|ns| {
                ns.iter()
                    .map(|n| {
                        let n = (normal_matrix * *n).normalize_or_zero();
                        if flip { -n } else { n }
                    })
                    .collect()
            })
        };
        for f in &mesh.indices {
            let [i0, i1, i2] = f.map(|i| i as usize);
            let (i0, i2) = if flip != rewind { (i2, i0) } else { (i0, i2) };
            let geom = TriangleGeom::new(pos[i0], pos[i1], pos[i2]);
            if crate::scene::obj::is_degenerate(&geom) {
                self.stats.degenerate_skipped += 1;
                continue;
            }
            let tri_normals = normals.as_ref().and_then(|n| {
                let t = [n[i0], n[i1], n[i2]];
                t.iter()
                    .all(|v| v.is_finite() && *v != Vec3::ZERO)
                    .then_some(t)
            });
            // Without texture coordinates Mitsuba uses the barycentrics (b1, b2) of the face as
            // written: its vertices at (0, 0), (1, 0), (0, 1), stored here OBJ-style (v up).
            let swapped = flip != rewind;
            let tri_uvs: [Vec2; 3] = match &mesh.uvs {
                Some(u) => [u[i0], u[i1], u[i2]],
                None => {
                    let b = |k: usize| {
                        [
                            Vec2::new(0.0, 1.0),
                            Vec2::new(1.0, 1.0),
                            Vec2::new(0.0, 0.0),
                        ][k]
                    };
                    if swapped {
                        [b(2), b(1), b(0)]
                    } else {
                        [b(0), b(1), b(2)]
                    }
                }
            };
            self.triangles.push(geom);
            self.shading.push(TriangleShading {
                normals: tri_normals,
                uvs: Some(tri_uvs),
                material,
                light: None,
            });
        }
    }

    // ---- emitters ----

    /// An emitter's colour property (`radiance` or `intensity`, default 1), which must not be
    /// negative.
    fn emission(&self, p: &Props<'a, 'd>, name: &str) -> Result<Rgb> {
        let c = p.rgb(name)?.unwrap_or(Rgb::ONE);
        if !(c.min_element() >= 0.0) {
            return Err(self.doc.err(
                p.get(name).expect("the property was read"),
                format!("{name} must not be negative"),
            ));
        }
        Ok(c)
    }

    fn emitter(&mut self, node: Node<'a, 'a>) -> Result<()> {
        let kind = self.kind(node)?;
        let p = Props::new(self.doc, node)?;
        match kind.as_str() {
            "point" => {
                let m = p.transform("to_world")?.unwrap_or(Mat4::IDENTITY);
                let position = match p.vec3("position")? {
                    Some(v) => v,
                    None => m.transform_point3(Vec3::ZERO),
                };
                let intensity = self.emission(&p, "intensity")?;
                p.finish("emitter 'point'")?;
                self.lights.push(Light::Point {
                    position,
                    intensity,
                });
            }
            "spot" => {
                let m = p.transform("to_world")?.unwrap_or(Mat4::IDENTITY);
                let intensity = self.emission(&p, "intensity")?;
                let cutoff = p.float_or("cutoff_angle", 20.0)?;
                let beam = p.float_or("beam_width", cutoff * 0.75)?;
                if !(cutoff > 0.0 && cutoff <= 90.0 && beam >= 0.0 && beam <= cutoff) {
                    return Err(self.doc.err(
                        node,
                        "spot: need 0 < cutoff_angle <= 90 and 0 <= beam_width <= cutoff_angle (degrees)",
                    ));
                }
                if p.is_texture("texture") {
                    self.doc
                        .unsupported(node, "a projected texture", "none", "no texture")?;
                }
                p.finish("emitter 'spot'")?;
                let dir = m
                    .transform_vector3(Vec3::Z)
                    .try_normalize()
                    .ok_or_else(|| self.doc.err(node, "spot: to_world has a zero z axis"))?;
                self.lights.push(Light::spot_linear_angle(
                    m.transform_point3(Vec3::ZERO),
                    dir,
                    intensity,
                    beam.to_radians(),
                    cutoff.to_radians(),
                ));
            }
            "constant" => {
                if p.is_texture("radiance") {
                    return Err(self
                        .doc
                        .err(node, "a textured constant radiance is not supported"));
                }
                let le = self.emission(&p, "radiance")?;
                p.finish("emitter 'constant'")?;
                self.lights.push(Light::Environment {
                    le,
                    center: Vec3::ZERO,
                    radius: 1.0,
                });
            }
            "area" => {
                return Err(self
                    .doc
                    .err(node, "an area emitter belongs inside a <shape>"));
            }
            other => {
                return self.doc.unsupported(
                    node,
                    &format!("emitter '{other}'"),
                    EMITTERS,
                    "nothing (the emitter is skipped)",
                );
            }
        }
        Ok(())
    }
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
    /// of OBJ meshes (desk's export) and one with a bitmap texture (features).
    #[test]
    fn files_loaded_ahead_build_the_same_scene() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        for file in ["desk/mitsuba/scene.xml", "features/scene.xml"] {
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
