//! PLY meshes (`<shape type="ply">`), read as Mitsuba 3's `ply` plugin reads them
//! (`src/shapes/ply.cpp` and `ply.h`), after the format's description by Greg Turk, "The
//! PLY Polygon File Format" (1994).
//!
//! A file is a text header, `ply`, `format ascii|binary_little_endian|binary_big_endian
//! 1.0`, then `element NAME COUNT` lines each followed by its `property TYPE NAME` and
//! `property list COUNT_TYPE ITEM_TYPE NAME` lines, up to `end_header`; then the elements'
//! records in header order: whitespace-separated numbers (ASCII), or packed values
//! (binary). Types: `char uchar short ushort int uint float double` and the aliases Mitsuba
//! reads (`int8` … `uint32`, `float32`, `float64`, `long`, `ulong`, `half`, `float16`).
//!
//! Read, as Mitsuba: the `vertex` element's `x y z`, normals `nx ny nz` when all three are
//! there, texture coordinates `u v`, else `texture_u texture_v`, else `s t`; the `face`
//! element's `vertex_index`, else `vertex_indices` list. Other properties and elements are
//! skipped, data after the last element is an error, and a mesh without normals gets
//! angle-weighted vertex normals (done by the shape). Unlike Mitsuba, which refuses faces of
//! other than three vertices, polygons are fanned into triangles (`0, k, k + 1`), and
//! `obj_info` header lines are skipped like comments. Texture coordinates are stored `v` up
//! ([`MeshData`]): the file's `(u, v)` as `(u, 1 - v)`; `flip_tex_coords` is the shape's.
//!
//! Why a reader of its own rather than a crate: the established crate (`ply-rs`, and its
//! fork `ply-rs-bw`) builds a map of named properties for every vertex and reserves the
//! header's element count up front, so a large mesh costs many times its size and a header
//! that lies about a count is an unbounded allocation; footprint needs six numbers a vertex
//! read straight into its arrays, Mitsuba's property names and aliases, and errors that
//! name the element, record and byte. The format is small enough for that to be short.
//!
//! Bad input is an error naming the file and, where it helps, the element, record and byte:
//! a header that does not parse, data that ends early or runs past the last element,
//! numbers that do not parse or do not fit their type, indices out of range, positions that
//! are not finite or beyond [`crate::scene::MAX_COORDINATE`]. No array is reserved beyond
//! what the file's size can hold.

use super::meshes::{MeshData, check_position};
use crate::error::{Error, Result};
use glam::{Vec2, Vec3};
use std::path::Path;

/// Reads the PLY file at `path`.
pub fn load_ply(path: &Path) -> Result<MeshData> {
    let data = std::fs::read(path).map_err(|reason| Error::Io {
        path: path.to_path_buf(),
        reason,
    })?;
    read(&data).map_err(|message| Error::invalid(path, message))
}

/// A value's type in the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F16,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &str) -> Option<Scalar> {
        use Scalar::*;
        Some(match name {
            "char" | "int8" => I8,
            "uchar" | "uint8" => U8,
            "short" | "int16" => I16,
            "ushort" | "uint16" => U16,
            "int" | "int32" => I32,
            "uint" | "uint32" => U32,
            "long" => I64,
            "ulong" => U64,
            "half" | "float16" => F16,
            "float" | "float32" => F32,
            "double" | "float64" => F64,
            _ => return None,
        })
    }

    fn bytes(self) -> usize {
        use Scalar::*;
        match self {
            I8 | U8 => 1,
            I16 | U16 | F16 => 2,
            I32 | U32 | F32 => 4,
            I64 | U64 | F64 => 8,
        }
    }

    fn is_float(self) -> bool {
        matches!(self, Scalar::F16 | Scalar::F32 | Scalar::F64)
    }

    /// The range of an integer type.
    fn range(self) -> (f64, f64) {
        use Scalar::*;
        match self {
            I8 => (i8::MIN as f64, i8::MAX as f64),
            U8 => (0.0, u8::MAX as f64),
            I16 => (i16::MIN as f64, i16::MAX as f64),
            U16 => (0.0, u16::MAX as f64),
            I32 => (i32::MIN as f64, i32::MAX as f64),
            U32 => (0.0, u32::MAX as f64),
            I64 => (i64::MIN as f64, i64::MAX as f64),
            U64 => (0.0, u64::MAX as f64),
            F16 | F32 | F64 => (f64::NEG_INFINITY, f64::INFINITY),
        }
    }
}

#[derive(Debug)]
enum Property {
    Scalar {
        name: String,
        ty: Scalar,
    },
    List {
        name: String,
        count: Scalar,
        item: Scalar,
    },
}

impl Property {
    fn name(&self) -> &str {
        match self {
            Property::Scalar { name, .. } | Property::List { name, .. } => name,
        }
    }
}

#[derive(Debug)]
struct Element {
    name: String,
    count: u64,
    properties: Vec<Property>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Format {
    Ascii,
    Binary { big_endian: bool },
}

/// The header: the format, the elements, and where the data starts.
#[derive(Debug)]
struct Header {
    format: Format,
    elements: Vec<Element>,
    data_start: usize,
}

fn parse_header(data: &[u8]) -> std::result::Result<Header, String> {
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut at = 0;
    let mut line_no = 0;
    loop {
        let Some(len) = data[at..].iter().position(|&b| b == b'\n') else {
            return Err("the header has no end_header line".into());
        };
        let line = String::from_utf8_lossy(&data[at..at + len]);
        at += len + 1;
        line_no += 1;
        let err = |m: String| format!("header line {line_no}: {m}");
        let mut words = line.split_ascii_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        let rest: Vec<&str> = words.collect();
        if line_no == 1 && (keyword != "ply" || !rest.is_empty()) {
            return Err("is not a PLY file (its first line is not 'ply')".into());
        }
        match keyword {
            "ply" if line_no == 1 => {}
            "comment" | "obj_info" => {}
            "format" => {
                if format.is_some() {
                    return Err(err("a second 'format' line".into()));
                }
                format = Some(match rest.as_slice() {
                    ["ascii", "1.0"] => Format::Ascii,
                    ["binary_little_endian", "1.0"] => Format::Binary { big_endian: false },
                    ["binary_big_endian", "1.0"] => Format::Binary { big_endian: true },
                    _ => {
                        return Err(err(format!(
                            "'format {}': footprint reads 'ascii', 'binary_little_endian' and 'binary_big_endian', version 1.0",
                            rest.join(" ")
                        )));
                    }
                });
            }
            "element" => {
                let [name, count] = rest.as_slice() else {
                    return Err(err("'element' takes a name and a count".into()));
                };
                let count = count
                    .parse::<u64>()
                    .map_err(|_| err(format!("element '{name}': '{count}' is not a count")))?;
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    properties: Vec::new(),
                });
            }
            "property" => {
                let Some(element) = elements.last_mut() else {
                    return Err(err("a 'property' before any 'element'".into()));
                };
                let ty =
                    |t: &str| Scalar::parse(t).ok_or_else(|| err(format!("unknown type '{t}'")));
                let property = match rest.as_slice() {
                    ["list", count, item, name] => {
                        let count = ty(count)?;
                        if count.is_float() {
                            return Err(err(format!(
                                "list '{name}': its count type must be an integer type"
                            )));
                        }
                        Property::List {
                            name: name.to_string(),
                            count,
                            item: ty(item)?,
                        }
                    }
                    [t, name] => Property::Scalar {
                        name: name.to_string(),
                        ty: ty(t)?,
                    },
                    _ => {
                        return Err(err(format!(
                            "'property {}' is neither 'property TYPE NAME' nor 'property list COUNT_TYPE ITEM_TYPE NAME'",
                            rest.join(" ")
                        )));
                    }
                };
                element.properties.push(property);
            }
            "end_header" => break,
            other => return Err(err(format!("unknown keyword '{other}'"))),
        }
    }
    let format = format.ok_or("the header has no 'format' line")?;
    Ok(Header {
        format,
        elements,
        data_start: at,
    })
}

/// The values of the data section, one at a time.
trait Values {
    /// The next value of type `ty`, as a number (integers of every type are exact in f64
    /// up to 2^53, beyond any valid index).
    fn next(&mut self, ty: Scalar) -> std::result::Result<f64, String>;
    /// Skips `n` values of type `ty`.
    fn skip(&mut self, ty: Scalar, n: u64) -> std::result::Result<(), String>;
    /// Where the reader is, for errors.
    fn position(&self) -> String;
    /// An error if data is left after the last element.
    fn finish(&mut self) -> std::result::Result<(), String>;
}

struct Binary<'a> {
    data: &'a [u8],
    at: usize,
    big_endian: bool,
}

impl Values for Binary<'_> {
    fn next(&mut self, ty: Scalar) -> std::result::Result<f64, String> {
        let n = ty.bytes();
        let Some(b) = self.data.get(self.at..self.at + n) else {
            return Err("the data ends here".into());
        };
        self.at += n;
        let mut a = [0u8; 8];
        a[..n].copy_from_slice(b);
        if self.big_endian {
            a[..n].reverse();
        }
        use Scalar::*;
        Ok(match ty {
            I8 => a[0] as i8 as f64,
            U8 => a[0] as f64,
            I16 => i16::from_le_bytes([a[0], a[1]]) as f64,
            U16 => u16::from_le_bytes([a[0], a[1]]) as f64,
            I32 => i32::from_le_bytes(a[..4].try_into().unwrap()) as f64,
            U32 => u32::from_le_bytes(a[..4].try_into().unwrap()) as f64,
            I64 => i64::from_le_bytes(a) as f64,
            U64 => u64::from_le_bytes(a) as f64,
            F16 => half::f16::from_le_bytes([a[0], a[1]]).to_f64(),
            F32 => f32::from_le_bytes(a[..4].try_into().unwrap()) as f64,
            F64 => f64::from_le_bytes(a),
        })
    }

    fn skip(&mut self, ty: Scalar, n: u64) -> std::result::Result<(), String> {
        let left = (self.data.len() - self.at) as u64;
        match n.checked_mul(ty.bytes() as u64) {
            Some(b) if b <= left => {
                self.at += b as usize;
                Ok(())
            }
            _ => Err(format!(
                "{n} values of {} bytes do not fit in the {left} bytes left",
                ty.bytes()
            )),
        }
    }

    fn position(&self) -> String {
        format!("byte {}", self.at)
    }

    fn finish(&mut self) -> std::result::Result<(), String> {
        let left = self.data.len() - self.at;
        if left > 0 {
            return Err(format!(
                "{left} bytes follow the last element at byte {} (the header's counts are smaller than the data)",
                self.at
            ));
        }
        Ok(())
    }
}

struct Ascii<'a> {
    data: &'a [u8],
    at: usize,
    /// The line of `at`, counted from the file's first line.
    line: usize,
}

impl<'a> Ascii<'a> {
    fn token(&mut self) -> Option<&'a [u8]> {
        while let Some(&b) = self.data.get(self.at) {
            if !b.is_ascii_whitespace() {
                break;
            }
            self.line += (b == b'\n') as usize;
            self.at += 1;
        }
        let start = self.at;
        while self
            .data
            .get(self.at)
            .is_some_and(|b| !b.is_ascii_whitespace())
        {
            self.at += 1;
        }
        (self.at > start).then(|| &self.data[start..self.at])
    }
}

impl Values for Ascii<'_> {
    fn next(&mut self, ty: Scalar) -> std::result::Result<f64, String> {
        let token = self.token().ok_or("the data ends here")?;
        let text = String::from_utf8_lossy(token);
        let value = if ty.is_float() {
            text.parse::<f64>().ok().map(|v| match ty {
                Scalar::F16 => half::f16::from_f64(v).to_f64(),
                Scalar::F32 => v as f32 as f64,
                _ => v,
            })
        } else {
            let (lo, hi) = ty.range();
            text.parse::<i128>()
                .ok()
                .map(|v| v as f64)
                .filter(|v| (lo..=hi).contains(v))
        };
        value.ok_or_else(|| {
            format!(
                "'{}' is not a {}",
                text.chars().take(40).collect::<String>(),
                type_name(ty)
            )
        })
    }

    fn skip(&mut self, ty: Scalar, n: u64) -> std::result::Result<(), String> {
        // Each value is a token of at least one byte: the loop ends with the data.
        for _ in 0..n {
            self.next(ty)?;
        }
        Ok(())
    }

    fn position(&self) -> String {
        format!("line {}", self.line)
    }

    fn finish(&mut self) -> std::result::Result<(), String> {
        match self.token() {
            Some(t) => Err(format!(
                "data follows the last element: '{}' on line {} (the header's counts are smaller than the data)",
                String::from_utf8_lossy(&t[..t.len().min(40)]),
                self.line
            )),
            None => Ok(()),
        }
    }
}

fn type_name(ty: Scalar) -> &'static str {
    use Scalar::*;
    match ty {
        I8 => "char",
        U8 => "uchar",
        I16 => "short",
        U16 => "ushort",
        I32 => "int",
        U32 => "uint",
        I64 => "long",
        U64 => "ulong",
        F16 => "half",
        F32 => "float",
        F64 => "double",
    }
}

/// Where a vertex property goes: position, normal and texture coordinate components.
#[derive(Clone, Copy, PartialEq)]
enum Slot {
    P(usize),
    N(usize),
    T(usize),
}

/// The slots of the `vertex` element's properties, by Mitsuba's names and aliases.
fn vertex_slots(e: &Element) -> std::result::Result<Vec<Option<Slot>>, String> {
    let has = |n: &str| e.properties.iter().any(|p| p.name() == n);
    let has_normals = has("nx") && has("ny") && has("nz");
    let uv_names = [("u", "v"), ("texture_u", "texture_v"), ("s", "t")]
        .into_iter()
        .find(|(u, v)| has(u) && has(v));
    let mut slots = Vec::new();
    for p in &e.properties {
        let name = p.name();
        let slot = match name {
            "x" => Some(Slot::P(0)),
            "y" => Some(Slot::P(1)),
            "z" => Some(Slot::P(2)),
            "nx" if has_normals => Some(Slot::N(0)),
            "ny" if has_normals => Some(Slot::N(1)),
            "nz" if has_normals => Some(Slot::N(2)),
            _ => match uv_names {
                Some((u, _)) if name == u => Some(Slot::T(0)),
                Some((_, v)) if name == v => Some(Slot::T(1)),
                _ => None,
            },
        };
        if let Some(slot) = slot {
            match p {
                Property::Scalar { ty, .. } if ty.is_float() => {}
                _ => {
                    return Err(format!(
                        "vertex property '{name}' must be a float, half or double"
                    ));
                }
            }
            if slots.contains(&Some(slot)) {
                return Err(format!("vertex property '{name}' is given twice"));
            }
        }
        slots.push(slot);
    }
    for (name, slot) in [("x", Slot::P(0)), ("y", Slot::P(1)), ("z", Slot::P(2))] {
        if !slots.contains(&Some(slot)) {
            return Err(format!("the vertex element has no '{name}' property"));
        }
    }
    Ok(slots)
}

/// The index of the `face` element's vertex index list.
fn face_list(e: &Element) -> std::result::Result<usize, String> {
    let find = |n: &str| e.properties.iter().position(|p| p.name() == n);
    let k = find("vertex_index")
        .or_else(|| find("vertex_indices"))
        .ok_or("the face element has no 'vertex_index' or 'vertex_indices' list")?;
    match &e.properties[k] {
        Property::List { item, .. } if !item.is_float() => Ok(k),
        p => Err(format!(
            "face property '{}' must be a list of integers",
            p.name()
        )),
    }
}

/// The mesh of a PLY file's bytes; an error says what is wrong and where.
fn read(data: &[u8]) -> std::result::Result<MeshData, String> {
    let header = parse_header(data)?;
    let body = &data[header.data_start..];
    let header_lines = data[..header.data_start]
        .iter()
        .filter(|&&b| b == b'\n')
        .count();
    let mut values: Box<dyn Values> = match header.format {
        Format::Ascii => Box::new(Ascii {
            data: body,
            at: 0,
            line: header_lines + 1,
        }),
        Format::Binary { big_endian } => Box::new(Binary {
            data: body,
            at: 0,
            big_endian,
        }),
    };
    let find = |n: &str| header.elements.iter().filter(|e| e.name == n).count();
    for n in ["vertex", "face"] {
        if find(n) > 1 {
            return Err(format!("the header has two '{n}' elements"));
        }
    }
    let vertex_count = header
        .elements
        .iter()
        .find(|e| e.name == "vertex")
        .map_or(0, |e| e.count);
    if vertex_count > u32::MAX as u64 {
        return Err(format!(
            "the header says {vertex_count} vertices, more than 32-bit indices reach"
        ));
    }
    let mut m = MeshData::default();
    // Every record takes at least one byte: no array is reserved beyond the file's size.
    let capacity = |count: u64| count.min(body.len() as u64) as usize;
    for e in &header.elements {
        if e.properties.is_empty() {
            // Records of nothing take no room: nothing to read, however many.
            continue;
        }
        let at = |values: &dyn Values, record: u64, m: String| {
            format!(
                "element '{}', record {record} of {} ({}): {m}",
                e.name,
                e.count,
                values.position()
            )
        };
        match e.name.as_str() {
            "vertex" => {
                let slots = vertex_slots(e)?;
                let has_normals = slots.contains(&Some(Slot::N(0)));
                let has_uvs = slots.contains(&Some(Slot::T(0)));
                m.positions = Vec::with_capacity(capacity(e.count));
                let mut normals =
                    Vec::with_capacity(if has_normals { capacity(e.count) } else { 0 });
                let mut uvs = Vec::with_capacity(if has_uvs { capacity(e.count) } else { 0 });
                for r in 0..e.count {
                    let (mut p, mut n, mut t) = ([0.0f32; 3], [0.0f32; 3], [0.0f32; 2]);
                    for (prop, slot) in e.properties.iter().zip(&slots) {
                        let v = match prop {
                            Property::Scalar { ty, .. } => values.next(*ty),
                            Property::List { count, item, .. } => values
                                .next(*count)
                                .and_then(|k| list_len(k, *count))
                                .and_then(|k| values.skip(*item, k))
                                .map(|_| 0.0),
                        }
                        .map_err(|m| at(values.as_ref(), r, m))?
                            as f32;
                        match slot {
                            Some(Slot::P(k)) => p[*k] = v,
                            Some(Slot::N(k)) => n[*k] = v,
                            Some(Slot::T(k)) => t[*k] = v,
                            None => {}
                        }
                    }
                    let p = Vec3::from(p);
                    check_position(&p).map_err(|e| format!("vertex {r}: {e}"))?;
                    if !(t[0].is_finite() && t[1].is_finite()) {
                        return Err(format!(
                            "vertex {r}: texture coordinates ({}, {}) are not finite",
                            t[0], t[1]
                        ));
                    }
                    m.positions.push(p);
                    if has_normals {
                        normals.push(Vec3::from(n));
                    }
                    if has_uvs {
                        uvs.push(Vec2::new(t[0], 1.0 - t[1]));
                    }
                }
                m.normals = has_normals.then_some(normals);
                m.uvs = has_uvs.then_some(uvs);
            }
            "face" => {
                let list = face_list(e)?;
                m.indices = Vec::with_capacity(capacity(e.count));
                let mut polygon: Vec<u32> = Vec::new();
                for r in 0..e.count {
                    for (k, prop) in e.properties.iter().enumerate() {
                        match prop {
                            Property::Scalar { ty, .. } => {
                                values.skip(*ty, 1).map_err(|m| at(values.as_ref(), r, m))?
                            }
                            Property::List { count, item, .. } => {
                                let n = values
                                    .next(*count)
                                    .and_then(|n| list_len(n, *count))
                                    .map_err(|m| at(values.as_ref(), r, m))?;
                                if k != list {
                                    values
                                        .skip(*item, n)
                                        .map_err(|m| at(values.as_ref(), r, m))?;
                                    continue;
                                }
                                if n < 3 {
                                    return Err(at(
                                        values.as_ref(),
                                        r,
                                        format!("a face of {n} vertices (a face has at least 3)"),
                                    ));
                                }
                                polygon.clear();
                                for _ in 0..n {
                                    let i = values
                                        .next(*item)
                                        .map_err(|m| at(values.as_ref(), r, m))?;
                                    if !(i >= 0.0 && i < vertex_count as f64) {
                                        return Err(format!(
                                            "face {r} refers to vertex {i}, but the file has {vertex_count} vertices"
                                        ));
                                    }
                                    polygon.push(i as u32);
                                }
                            }
                        }
                    }
                    for k in 2..polygon.len() {
                        m.indices.push([polygon[0], polygon[k - 1], polygon[k]]);
                    }
                }
            }
            _ => {
                for r in 0..e.count {
                    for prop in &e.properties {
                        match prop {
                            Property::Scalar { ty, .. } => values.skip(*ty, 1),
                            Property::List { count, item, .. } => values
                                .next(*count)
                                .and_then(|n| list_len(n, *count))
                                .and_then(|n| values.skip(*item, n)),
                        }
                        .map_err(|m| at(values.as_ref(), r, m))?;
                    }
                }
            }
        }
    }
    values.finish()?;
    Ok(m)
}

/// A list's length as read: a non-negative integer.
fn list_len(n: f64, ty: Scalar) -> std::result::Result<u64, String> {
    if n < 0.0 {
        return Err(format!("a list of {n} values ({} count)", type_name(ty)));
    }
    Ok(n as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Writes a PLY file: `format` (`ascii`, `binary_little_endian`, `binary_big_endian`),
    /// the vertex properties (type, name) with one row of values a vertex, the faces' list
    /// types and the faces, and extra header and data text for the elements after them.
    struct Ply<'a> {
        format: &'a str,
        vertex: &'a [(&'a str, &'a str)],
        rows: &'a [&'a [f64]],
        list: (&'a str, &'a str),
        faces: &'a [&'a [u32]],
    }

    fn put(out: &mut Vec<u8>, format: &str, ty: &str, v: f64) {
        if format == "ascii" {
            out.extend_from_slice(format!("{v} ").as_bytes());
            return;
        }
        let mut b: Vec<u8> = match Scalar::parse(ty).unwrap() {
            Scalar::I8 => (v as i8).to_le_bytes().to_vec(),
            Scalar::U8 => (v as u8).to_le_bytes().to_vec(),
            Scalar::I16 => (v as i16).to_le_bytes().to_vec(),
            Scalar::U16 => (v as u16).to_le_bytes().to_vec(),
            Scalar::I32 => (v as i32).to_le_bytes().to_vec(),
            Scalar::U32 => (v as u32).to_le_bytes().to_vec(),
            Scalar::I64 => (v as i64).to_le_bytes().to_vec(),
            Scalar::U64 => (v as u64).to_le_bytes().to_vec(),
            Scalar::F16 => half::f16::from_f64(v).to_le_bytes().to_vec(),
            Scalar::F32 => (v as f32).to_le_bytes().to_vec(),
            Scalar::F64 => v.to_le_bytes().to_vec(),
        };
        if format == "binary_big_endian" {
            b.reverse();
        }
        out.extend_from_slice(&b);
    }

    impl Ply<'_> {
        fn bytes(&self) -> Vec<u8> {
            let mut h = format!(
                "ply\nformat {} 1.0\ncomment made by hand\nelement vertex {}\n",
                self.format,
                self.rows.len()
            );
            for (ty, name) in self.vertex {
                h += &format!("property {ty} {name}\n");
            }
            h += &format!(
                "element face {}\nproperty list {} {} vertex_indices\nend_header\n",
                self.faces.len(),
                self.list.0,
                self.list.1
            );
            let mut out = h.into_bytes();
            for row in self.rows {
                for ((ty, _), v) in self.vertex.iter().zip(row.iter()) {
                    put(&mut out, self.format, ty, *v);
                }
                if self.format == "ascii" {
                    out.push(b'\n');
                }
            }
            for f in self.faces {
                put(&mut out, self.format, self.list.0, f.len() as f64);
                for &i in *f {
                    put(&mut out, self.format, self.list.1, i as f64);
                }
                if self.format == "ascii" {
                    out.push(b'\n');
                }
            }
            out
        }
    }

    const XYZ: [(&str, &str); 3] = [("float", "x"), ("float", "y"), ("float", "z")];
    /// A unit square in z = 0 as one quad, and a triangle above it.
    const SQUARE: [&[f64]; 5] = [
        &[0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0],
        &[1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0],
        &[1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        &[0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0],
        &[0.5, 0.5, 1.0, 0.0, 0.6, 0.8, 0.5, 0.25],
    ];
    const FACES: [&[u32]; 2] = [&[0, 1, 2, 3], &[0, 1, 4]];
    const FORMATS: [&str; 3] = ["ascii", "binary_little_endian", "binary_big_endian"];

    fn square(format: &str, vertex: &[(&str, &str)], list: (&str, &str)) -> Vec<u8> {
        Ply {
            format,
            vertex,
            rows: &SQUARE,
            list,
            faces: &FACES,
        }
        .bytes()
    }

    /// ASCII, little and big endian files of the same mesh read the same: positions, the
    /// quad fanned into two triangles, and normals and texture coordinates where the file
    /// has them (`v` stored up), under each of Mitsuba's texture coordinate names.
    #[test]
    fn ascii_and_binary_files_read_the_same_mesh() {
        let full = [
            XYZ[0],
            XYZ[1],
            XYZ[2],
            ("float", "nx"),
            ("float", "ny"),
            ("float", "nz"),
            ("float", "u"),
            ("float", "v"),
        ];
        for format in FORMATS {
            let m = read(&square(format, &XYZ, ("uchar", "int"))).unwrap();
            assert_eq!(m.positions.len(), 5, "{format}");
            assert_eq!(m.positions[4], Vec3::new(0.5, 0.5, 1.0));
            assert_eq!(m.indices, vec![[0, 1, 2], [0, 2, 3], [0, 1, 4]], "{format}");
            assert!(m.normals.is_none() && m.uvs.is_none(), "{format}");

            let m = read(&square(format, &full, ("uint8", "uint32"))).unwrap();
            assert_eq!(m.indices.len(), 3);
            let n = m.normals.as_ref().unwrap();
            assert_eq!(n[4], Vec3::new(0.0, 0.6, 0.8), "{format}");
            let t = m.uvs.as_ref().unwrap();
            assert_eq!(t[4], Vec2::new(0.5, 0.75), "{format}: v stored up");
            assert_eq!(t[2], Vec2::new(1.0, 0.0), "{format}");
            for (u, v) in [("s", "t"), ("texture_u", "texture_v")] {
                let mut named = full;
                named[6].1 = u;
                named[7].1 = v;
                let other = read(&square(format, &named, ("uchar", "int"))).unwrap();
                assert_eq!(other.uvs, m.uvs, "{format} {u} {v}");
            }
        }
    }

    /// Doubles, halves, other list types, normals with one component missing (no normals,
    /// as Mitsuba), colours and other properties, other elements and lists in the face
    /// element are read or skipped as they should be.
    #[test]
    fn other_types_properties_and_elements() {
        for format in FORMATS {
            let vertex = [
                ("double", "x"),
                ("uchar", "red"),
                ("double", "y"),
                ("half", "z"),
                ("float", "nx"),
                ("float", "ny"),
            ];
            let rows: Vec<Vec<f64>> = SQUARE
                .iter()
                .map(|r| vec![r[0], 200.0, r[1], r[2], 0.5, 0.5])
                .collect();
            let rows: Vec<&[f64]> = rows.iter().map(|r| r.as_slice()).collect();
            let mut bytes = Ply {
                format,
                vertex: &vertex,
                rows: &rows,
                list: ("ushort", "short"),
                faces: &FACES,
            }
            .bytes();
            let m = read(&bytes).unwrap();
            assert_eq!(m.positions[4], Vec3::new(0.5, 0.5, 1.0), "{format}");
            assert!(m.normals.is_none(), "{format}: nz is missing");
            assert_eq!(m.indices.len(), 3);
            // An element after the faces, with a list, is skipped.
            let end = bytes.windows(10).position(|w| w == b"end_header").unwrap();
            bytes.splice(
                end..end,
                b"element edge 2\nproperty int a\nproperty list uchar int b\n"
                    .iter()
                    .copied(),
            );
            for (a, b) in [(0.0, [1.0, 2.0]), (3.0, [4.0, 0.0])] {
                put(&mut bytes, format, "int", a);
                put(&mut bytes, format, "uchar", 2.0);
                for v in b {
                    put(&mut bytes, format, "int", v);
                }
            }
            assert_eq!(read(&bytes).unwrap().indices, m.indices, "{format}");
        }
    }

    fn err(data: &[u8]) -> String {
        read(data).expect_err("a bad file is refused")
    }

    /// Bad files give errors that say what and where, and nothing is allocated for counts
    /// the data cannot hold.
    #[test]
    fn bad_files_are_refused_with_what_and_where() {
        let ascii = square("ascii", &XYZ, ("uchar", "int"));
        let binary = square("binary_little_endian", &XYZ, ("uchar", "int"));
        let text = String::from_utf8(ascii.clone()).unwrap();
        let cases: Vec<(Vec<u8>, &str)> = vec![
            (b"solid cube\n".to_vec(), "not a PLY file"),
            (
                b"ply\nformat ascii 1.0\nelement vertex 3\n".to_vec(),
                "no end_header",
            ),
            (
                text.replace("ascii 1.0", "ascii 2.0").into_bytes(),
                "header line 2: 'format ascii 2.0'",
            ),
            (
                text.replace("float z", "quad z").into_bytes(),
                "unknown type 'quad'",
            ),
            (
                text.replace("float z", "int z").into_bytes(),
                "vertex property 'z' must be a float",
            ),
            (
                text.replace("vertex_indices", "corners").into_bytes(),
                "no 'vertex_index' or 'vertex_indices' list",
            ),
            // Cut inside the data.
            (
                binary[..binary.len() - 3].to_vec(),
                "element 'face', record 1 of 2",
            ),
            (ascii[..ascii.len() - 4].to_vec(), "the data ends here"),
            // Counts larger, and smaller, than the data.
            (
                text.replace("element vertex 5", "element vertex 1000000000")
                    .into_bytes(),
                "element 'vertex', record 8 of 1000000000 (line 18): the data ends here",
            ),
            (
                swap(&binary, "element face 2", "element face 4000000000"),
                "element 'face', record 2 of 4000000000",
            ),
            (
                text.replace("element face 2", "element face 1")
                    .into_bytes(),
                "data follows the last element: '3' on line",
            ),
            (
                [binary.clone(), vec![0]].concat(),
                "1 bytes follow the last element",
            ),
            // Values that do not fit, indices out of range, positions that are not finite.
            (
                text.replace("4 0 1 2 3", "300 0 1 2 3").into_bytes(),
                "'300' is not a uchar",
            ),
            (
                text.replace("3 0 1 4", "3 0 1 5").into_bytes(),
                "face 1 refers to vertex 5",
            ),
            (
                text.replace("3 0 1 4", "3 0 1 -1").into_bytes(),
                "face 1 refers to vertex -1",
            ),
            (
                text.replace("3 0 1 4", "2 0 1").into_bytes(),
                "a face of 2 vertices",
            ),
            (
                text.replace("0.5 0.5 1 ", "0.5 nan 1 ").into_bytes(),
                "vertex 4: position (0.5, NaN, 1) is not finite",
            ),
            (
                text.replace("0.5 0.5 1 ", "0.5 1e30 1 ").into_bytes(),
                "farther than 1e15",
            ),
            (
                text.replace("element vertex 5", "element vertex 99999999999")
                    .into_bytes(),
                "more than 32-bit indices reach",
            ),
        ];
        for (data, needle) in cases {
            let e = err(&data);
            assert!(e.contains(needle), "'{needle}' not in: {e}");
        }
        // A face whose list says four billion vertices, with `uint` counts: refused where the
        // data ends, with no list of that size reserved.
        let mut huge = square("binary_little_endian", &XYZ, ("uint", "int"));
        let at = huge.len() - 16; // the second face's count, then its three indices
        huge[at..at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
        let e = err(&huge);
        assert!(
            e.contains("record 1 of 2") && e.contains("data ends"),
            "{e}"
        );
    }

    /// `data` with the first `from` replaced by `to` (a header edit of a binary file).
    fn swap(data: &[u8], from: &str, to: &str) -> Vec<u8> {
        let at = data
            .windows(from.len())
            .position(|w| w == from.as_bytes())
            .unwrap();
        [&data[..at], to.as_bytes(), &data[at + from.len()..]].concat()
    }
}
