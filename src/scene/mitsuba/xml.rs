//! The XML side of the Mitsuba 3 importer: `$name` substitution from `<default>` elements and
//! `-D name=value`, typed property lookup (`integer`, `float`, `boolean`, `string`, `rgb`,
//! `spectrum`, `point`, `vector`, `transform`) with the element's line for every error, and
//! a check that every property of an object was understood (Mitsuba 3 itself rejects
//! unreferenced properties the same way).

use crate::Rgb;
use crate::error::{Error, Result};
use glam::{Mat4, Vec3, Vec4};
use roxmltree::Node;
use std::cell::RefCell;
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

/// Tags that carry a named property value.
const PROPERTY_TAGS: &[&str] = &[
    "integer",
    "float",
    "boolean",
    "string",
    "rgb",
    "spectrum",
    "point",
    "vector",
    "transform",
];

/// Names under which a `<ref>` points to a nested object rather than a texture.
const OBJECT_NAMES: &[&str] = &[
    "bsdf", "emitter", "film", "sampler", "rfilter", "shape", "medium",
];

/// What the importer needs while walking the document.
pub struct Doc<'a> {
    pub path: &'a Path,
    pub dir: PathBuf,
    pub xml: &'a roxmltree::Document<'a>,
    /// `<default>` values, overridden by the command line's `-D`.
    pub params: HashMap<String, String>,
    pub lenient: bool,
    /// The file's `version` is below 2.0 (Mitsuba 0.5 and 0.6, as Bitterli's collection and
    /// most scenes of the path-guiding papers were written): property names are read as
    /// Mitsuba 3 upgrades them ([`upgraded_name`]).
    pub legacy: bool,
    /// What `--lenient` replaced, one line each.
    pub notes: RefCell<Vec<String>>,
}

impl<'a> Doc<'a> {
    /// `file:line:column` of a node.
    pub fn pos(&self, node: Node) -> (usize, usize) {
        let p = self.xml.text_pos_at(node.range().start);
        (p.row as usize, p.col as usize)
    }

    /// An error at `node`.
    pub fn err(&self, node: Node, message: impl Into<String>) -> Error {
        let (line, column) = self.pos(node);
        Error::Syntax {
            path: self.path.to_path_buf(),
            line,
            column,
            message: message.into(),
        }
    }

    /// Something footprint does not support: an error naming it and what is supported, or,
    /// with `--lenient`, a note saying which stand-in replaces it.
    pub fn unsupported(
        &self,
        node: Node,
        what: &str,
        supported: &str,
        stand_in: &str,
    ) -> Result<()> {
        if self.lenient {
            let (line, _) = self.pos(node);
            self.notes.borrow_mut().push(format!(
                "{}:{line}: {what} is not supported; --lenient: {stand_in}",
                self.path.display()
            ));
            Ok(())
        } else {
            Err(self.err(
                node,
                format!("{what} is not supported (supported: {supported}); --lenient replaces it with {stand_in}"),
            ))
        }
    }

    /// Attribute `name` of `node` with `$param` references substituted.
    pub fn attr(&self, node: Node, name: &str) -> Result<Option<String>> {
        match node.attribute(name) {
            None => Ok(None),
            Some(v) => self.substitute(node, v).map(Some),
        }
    }

    /// Attribute that must be present.
    pub fn req_attr(&self, node: Node, name: &str) -> Result<String> {
        self.attr(node, name)?.ok_or_else(|| {
            self.err(
                node,
                format!("<{}> needs the attribute '{name}'", node.tag_name().name()),
            )
        })
    }

    fn substitute(&self, node: Node, v: &str) -> Result<String> {
        if !v.contains('$') {
            return Ok(v.to_string());
        }
        let mut out = String::new();
        let mut rest = v;
        while let Some(i) = rest.find('$') {
            out.push_str(&rest[..i]);
            let tail = &rest[i + 1..];
            let end = tail
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(tail.len());
            let name = &tail[..end];
            if name.is_empty() {
                out.push('$');
            } else {
                let value = self.params.get(name).ok_or_else(|| {
                    self.err(
                        node,
                        format!("'${name}' has no value: add <default name=\"{name}\" value=\"...\"/> or pass -D {name}=..."),
                    )
                })?;
                out.push_str(value);
            }
            rest = &tail[end..];
        }
        out.push_str(rest);
        Ok(out)
    }

    /// Child elements of `node`.
    pub fn children(&self, node: Node<'a, 'a>) -> impl Iterator<Item = Node<'a, 'a>> {
        node.children().filter(|c| c.is_element())
    }

    /// Resolves a path relative to the scene file's folder.
    pub fn file(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }
}

/// Whether a `<scene version="...">` is older than 2.0.0 (Mitsuba 0.x), whose property names
/// Mitsuba 3 upgrades when it loads the file. `None` for a version that is not numbers.
pub fn legacy_version(version: &str) -> Option<bool> {
    let major = version.split('.').next()?.trim().parse::<u32>().ok()?;
    if !version.split('.').all(|p| p.trim().parse::<u32>().is_ok()) {
        return None;
    }
    Some(major < 2)
}

/// A property's name in a file older than version 2.0, as Mitsuba 3 reads it
/// (`upgrade_from_v1` in Mitsuba's `src/core/parser.cpp`): camelCase becomes
/// underscore_case, an uppercase run after a lowercase letter lowered as one word
/// (`maxDepth` → `max_depth`, `intIOR` → `int_ior`, `toWorld` → `to_world`), and a
/// `diffuse` BSDF's `diffuseReflectance` becomes `reflectance`.
pub fn upgraded_name(name: &str, plugin: Option<&str>) -> String {
    let chars: Vec<char> = name.chars().collect();
    let mut out = String::with_capacity(name.len() + 4);
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if i > 0 && chars[i - 1].is_ascii_lowercase() && c.is_ascii_uppercase() {
            out.push('_');
            out.push(c.to_ascii_lowercase());
            while i + 1 < chars.len() && chars[i + 1].is_ascii_uppercase() {
                i += 1;
                out.push(chars[i].to_ascii_lowercase());
            }
        } else {
            out.push(c);
        }
        i += 1;
    }
    if plugin == Some("diffuse") && out == "diffuse_reflectance" {
        return "reflectance".into();
    }
    out
}

/// Parses a list of numbers separated by commas and/or white space.
pub fn numbers(s: &str) -> Option<Vec<f32>> {
    s.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(|t| t.parse::<f32>().ok().filter(|v| v.is_finite()))
        .collect()
}

/// The properties and nested objects of one Mitsuba object (`<bsdf>`, `<shape>`, ...), with
/// a record of which were read.
pub struct Props<'a, 'd> {
    doc: &'d Doc<'a>,
    named: HashMap<String, Node<'a, 'a>>,
    used: RefCell<HashSet<String>>,
    /// Nested objects, named or not (a shape's bsdf and emitter, a sensor's film, `ref`s).
    pub unnamed: Vec<Node<'a, 'a>>,
}

impl<'a, 'd> Props<'a, 'd> {
    pub fn new(doc: &'d Doc<'a>, node: Node<'a, 'a>) -> Result<Self> {
        let mut named = HashMap::new();
        let mut unnamed = Vec::new();
        let mut used = HashSet::new();
        let plugin = node.attribute("type");
        for c in doc.children(node) {
            let tag = c.tag_name().name();
            let mut name = doc.attr(c, "name")?;
            // Nested objects (bsdf, emitter, film, sampler, rfilter, ...) are objects whatever
            // their `name`; a named `ref` may be a texture property or an object (`<ref
            // name="bsdf" id="m"/>`): it is both, and counts as read when used as either.
            let property = PROPERTY_TAGS.contains(&tag) || tag == "texture" || tag == "ref";
            let object = !PROPERTY_TAGS.contains(&tag) && !(tag == "texture" && name.is_some());
            if doc.legacy && property {
                name = name.map(|n| upgraded_name(&n, plugin));
            }
            match name {
                Some(n) if property => {
                    if named.insert(n.clone(), c).is_some() {
                        return Err(doc.err(c, format!("property '{n}' is given twice")));
                    }
                    if tag == "ref" && OBJECT_NAMES.contains(&n.as_str()) {
                        used.insert(n);
                    }
                }
                Some(_) => {}
                None if PROPERTY_TAGS.contains(&tag) => {
                    return Err(doc.err(c, format!("<{tag}> needs a 'name' attribute")));
                }
                None => {}
            }
            if object {
                unnamed.push(c);
            }
        }
        Ok(Props {
            doc,
            named,
            used: RefCell::new(used),
            unnamed,
        })
    }

    /// The element of property `name`, marked as read.
    pub fn get(&self, name: &str) -> Option<Node<'a, 'a>> {
        let n = self.named.get(name).copied();
        if n.is_some() {
            self.used.borrow_mut().insert(name.to_string());
        }
        n
    }

    /// The named `<texture>` elements (whatever their names), marked as read: a BSDF adapter
    /// such as `bumpmap` takes its nested texture under any name, as Mitsuba does.
    pub fn named_textures(&self) -> Vec<Node<'a, 'a>> {
        let mut found: Vec<(&String, Node<'a, 'a>)> = self
            .named
            .iter()
            .filter(|(_, n)| n.has_tag_name("texture"))
            .map(|(k, n)| (k, *n))
            .collect();
        found.sort_by_key(|(_, n)| n.range().start);
        let mut used = self.used.borrow_mut();
        found
            .into_iter()
            .map(|(k, n)| {
                used.insert(k.clone());
                n
            })
            .collect()
    }

    /// Marks properties as read that footprint accepts and ignores (they do not change the
    /// expected image, e.g. an output file format).
    pub fn ignore(&self, names: &[&str]) {
        for n in names {
            self.get(n);
        }
    }

    fn value(&self, n: Node, tags: &[&str]) -> Result<String> {
        let tag = n.tag_name().name();
        if !tags.contains(&tag) {
            return Err(self.doc.err(
                n,
                format!(
                    "property '{}' is a <{tag}>, expected <{}>",
                    n.attribute("name").unwrap_or(""),
                    tags.join("> or <")
                ),
            ));
        }
        self.doc.req_attr(n, "value")
    }

    pub fn float(&self, name: &str) -> Result<Option<f32>> {
        let Some(n) = self.get(name) else {
            return Ok(None);
        };
        let v = self.value(n, &["float", "integer"])?;
        v.trim()
            .parse::<f32>()
            .ok()
            .filter(|x| x.is_finite())
            .map(Some)
            .ok_or_else(|| {
                self.doc
                    .err(n, format!("'{name}': '{v}' is not a finite number"))
            })
    }

    pub fn float_or(&self, name: &str, default: f32) -> Result<f32> {
        Ok(self.float(name)?.unwrap_or(default))
    }

    pub fn integer(&self, name: &str) -> Result<Option<i64>> {
        let Some(n) = self.get(name) else {
            return Ok(None);
        };
        let v = self.value(n, &["integer"])?;
        v.trim().parse::<i64>().map(Some).map_err(|_| {
            self.doc
                .err(n, format!("'{name}': '{v}' is not an integer"))
        })
    }

    pub fn boolean(&self, name: &str) -> Result<Option<bool>> {
        let Some(n) = self.get(name) else {
            return Ok(None);
        };
        let v = self.value(n, &["boolean"])?;
        match v.trim() {
            "true" => Ok(Some(true)),
            "false" => Ok(Some(false)),
            _ => Err(self.doc.err(
                n,
                format!("'{name}': '{v}' is not a boolean (true or false)"),
            )),
        }
    }

    pub fn string(&self, name: &str) -> Result<Option<String>> {
        let Some(n) = self.get(name) else {
            return Ok(None);
        };
        self.value(n, &["string"]).map(Some)
    }

    /// A colour: `<rgb>`, a constant `<spectrum>` or a `<float>`.
    pub fn rgb(&self, name: &str) -> Result<Option<Rgb>> {
        let Some(n) = self.get(name) else {
            return Ok(None);
        };
        let tag = n.tag_name().name();
        if !["rgb", "spectrum", "float"].contains(&tag) {
            return Ok(None);
        }
        let v = self.doc.req_attr(n, "value")?;
        if tag == "spectrum" && v.contains(':') {
            // Wavelength:value pairs: footprint renders in RGB.
            let vals: Vec<f32> = v
                .split(',')
                .filter_map(|p| p.split(':').nth(1))
                .filter_map(|x| x.trim().parse::<f32>().ok())
                .collect();
            let mean = vals.iter().sum::<f32>() / vals.len().max(1) as f32;
            self.doc.unsupported(
                n,
                "a sampled <spectrum> (wavelength:value pairs)",
                "<rgb> or a constant <spectrum value=\"v\">",
                &format!("the grey of the values' mean, {mean}"),
            )?;
            return Ok(Some(Rgb::splat(mean)));
        }
        let c = match numbers(&v).as_deref() {
            Some([x]) => Rgb::splat(*x),
            Some([r, g, b]) => Rgb::new(*r, *g, *b),
            _ => {
                return Err(self.doc.err(
                    n,
                    format!("'{name}': '{v}' is not a colour (one value or three: \"r, g, b\")"),
                ));
            }
        };
        Ok(Some(c))
    }

    /// True when property `name` exists and is not a plain colour (a texture or a `ref`).
    pub fn is_texture(&self, name: &str) -> bool {
        self.named
            .get(name)
            .is_some_and(|n| ["texture", "ref"].contains(&n.tag_name().name()))
    }

    /// A point or vector property: `x`, `y`, `z` attributes or a `value`.
    pub fn vec3(&self, name: &str) -> Result<Option<Vec3>> {
        let Some(n) = self.get(name) else {
            return Ok(None);
        };
        let tag = n.tag_name().name();
        if !["point", "vector"].contains(&tag) {
            return Err(self.doc.err(
                n,
                format!("property '{name}' is a <{tag}>, expected <point> or <vector>"),
            ));
        }
        vec3_attrs(self.doc, n, 0.0).map(Some)
    }

    /// A `<transform>` property.
    pub fn transform(&self, name: &str) -> Result<Option<Mat4>> {
        let Some(n) = self.get(name) else {
            return Ok(None);
        };
        if n.tag_name().name() != "transform" {
            return Err(self
                .doc
                .err(n, format!("property '{name}' must be a <transform>")));
        }
        parse_transform(self.doc, n).map(Some)
    }

    /// Errors (or, lenient, notes) for every property nobody read.
    pub fn finish(&self, what: &str) -> Result<()> {
        let used = self.used.borrow();
        let mut left: Vec<(&String, &Node)> = self
            .named
            .iter()
            .filter(|(k, _)| !used.contains(*k))
            .collect();
        left.sort_by_key(|(_, n)| n.range().start);
        for (k, n) in left {
            self.doc.unsupported(
                *n,
                &format!("property '{k}' of {what}"),
                "the properties listed in docs/mitsuba.md",
                "nothing (the property is ignored)",
            )?;
        }
        Ok(())
    }
}

/// `x`, `y`, `z` attributes (each defaulting to `default`), or a `value="x, y, z"`.
pub fn vec3_attrs(doc: &Doc, n: Node, default: f32) -> Result<Vec3> {
    if let Some(v) = doc.attr(n, "value")? {
        return match numbers(&v).as_deref() {
            Some([x, y, z]) => Ok(Vec3::new(*x, *y, *z)),
            Some([s]) => Ok(Vec3::splat(*s)),
            _ => Err(doc.err(n, format!("'{v}' is not three numbers \"x, y, z\""))),
        };
    }
    let mut v = [default; 3];
    for (i, a) in ["x", "y", "z"].iter().enumerate() {
        if let Some(s) = doc.attr(n, a)? {
            v[i] = s
                .trim()
                .parse::<f32>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    doc.err(n, format!("attribute {a}=\"{s}\" is not a finite number"))
                })?;
        }
    }
    Ok(Vec3::from(v))
}

fn vec3_string(doc: &Doc, n: Node, attr: &str) -> Result<Option<Vec3>> {
    let Some(s) = doc.attr(n, attr)? else {
        return Ok(None);
    };
    match numbers(&s).as_deref() {
        Some([x, y, z]) => Ok(Some(Vec3::new(*x, *y, *z))),
        _ => Err(doc.err(
            n,
            format!("{attr}=\"{s}\" is not three numbers \"x, y, z\""),
        )),
    }
}

/// A `<transform>`: its operations applied in document order (each one after the ones
/// before it, as Mitsuba composes them).
pub fn parse_transform(doc: &Doc, node: Node) -> Result<Mat4> {
    let mut m = Mat4::IDENTITY;
    for op in doc.children(node) {
        let t = match op.tag_name().name() {
            "translate" => Mat4::from_translation(vec3_attrs(doc, op, 0.0)?),
            "scale" => {
                let s = vec3_attrs(doc, op, 1.0)?;
                if s.abs().min_element() < 1e-12 {
                    return Err(doc.err(op, "scale by zero"));
                }
                Mat4::from_scale(s)
            }
            "rotate" => {
                let axis = vec3_attrs(doc, op, 0.0)?;
                let angle: f32 = doc
                    .req_attr(op, "angle")?
                    .trim()
                    .parse()
                    .map_err(|_| doc.err(op, "rotate: 'angle' is not a number (degrees)"))?;
                let axis = axis
                    .try_normalize()
                    .ok_or_else(|| doc.err(op, "rotate: the axis is zero"))?;
                Mat4::from_axis_angle(axis, angle.to_radians())
            }
            "matrix" => {
                let v = doc.req_attr(op, "value")?;
                let a = numbers(&v).unwrap_or_default();
                match a.len() {
                    16 => Mat4::from_cols_array(&[
                        a[0], a[4], a[8], a[12], a[1], a[5], a[9], a[13], a[2], a[6], a[10], a[14],
                        a[3], a[7], a[11], a[15],
                    ]),
                    9 => Mat4::from_cols(
                        Vec4::new(a[0], a[3], a[6], 0.0),
                        Vec4::new(a[1], a[4], a[7], 0.0),
                        Vec4::new(a[2], a[5], a[8], 0.0),
                        Vec4::W,
                    ),
                    _ => {
                        return Err(doc.err(
                            op,
                            "matrix needs 16 (4x4) or 9 (3x3) finite numbers, row by row",
                        ));
                    }
                }
            }
            "lookat" => {
                let origin = vec3_string(doc, op, "origin")?
                    .ok_or_else(|| doc.err(op, "lookat needs 'origin'"))?;
                let target = vec3_string(doc, op, "target")?
                    .ok_or_else(|| doc.err(op, "lookat needs 'target'"))?;
                let dir = (target - origin)
                    .try_normalize()
                    .ok_or_else(|| doc.err(op, "lookat: origin and target coincide"))?;
                let up = match vec3_string(doc, op, "up")? {
                    Some(u) => u,
                    None => dir.any_orthonormal_vector(),
                };
                let left = up
                    .cross(dir)
                    .try_normalize()
                    .ok_or_else(|| doc.err(op, "lookat: 'up' is parallel to the view direction"))?;
                let new_up = dir.cross(left);
                Mat4::from_cols(
                    left.extend(0.0),
                    new_up.extend(0.0),
                    dir.extend(0.0),
                    origin.extend(1.0),
                )
            }
            other => {
                return Err(doc.err(
                    op,
                    format!("unknown transform operation <{other}> (supported: translate, rotate, scale, matrix, lookat)"),
                ));
            }
        };
        m = t * m;
    }
    if !m.is_finite() || m.determinant().abs() < 1e-20 {
        return Err(doc.err(node, "the transform is singular or not finite"));
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The names Mitsuba 3's `camel_to_underscore_case` gives the properties of Bitterli's
    /// version 0.5 files, worked out by hand from its rule.
    #[test]
    fn legacy_names_upgrade_as_mitsuba_3() {
        for (old, new) in [
            ("maxDepth", "max_depth"),
            ("toWorld", "to_world"),
            ("sampleCount", "sample_count"),
            ("intIOR", "int_ior"),
            ("extIOR", "ext_ior"),
            ("specularReflectance", "specular_reflectance"),
            ("filterType", "filter_type"),
            ("alphaU", "alpha_u"),
            ("fov", "fov"),
            ("max_depth", "max_depth"),
            ("IOR", "IOR"),
            ("rfilter", "rfilter"),
        ] {
            assert_eq!(upgraded_name(old, Some("roughplastic")), new, "{old}");
        }
        assert_eq!(
            upgraded_name("diffuseReflectance", Some("diffuse")),
            "reflectance"
        );
        assert_eq!(
            upgraded_name("diffuseReflectance", Some("plastic")),
            "diffuse_reflectance"
        );
    }

    #[test]
    fn versions_below_two_are_legacy() {
        assert_eq!(legacy_version("0.5.0"), Some(true));
        assert_eq!(legacy_version("0.6.0"), Some(true));
        assert_eq!(legacy_version("2.0.0"), Some(false));
        assert_eq!(legacy_version("3.0.0"), Some(false));
        assert_eq!(legacy_version("three"), None);
        assert_eq!(legacy_version("3.x"), None);
    }
}
