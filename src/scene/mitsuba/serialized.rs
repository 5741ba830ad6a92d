//! Mitsuba's `.serialized` meshes (`<shape type="serialized">`), versions 3 and 4, read as
//! Mitsuba 3's `serialized` plugin reads them (its documentation, "Serialized mesh loader",
//! and `src/shapes/serialized.cpp`).
//!
//! A file is one or more meshes, each:
//!
//! | bytes | content |
//! |---|---|
//! | `u16` | `0x041C`, the format's identifier |
//! | `u16` | version: 3 or 4 |
//! | rest | a zlib stream (RFC 1950/1951) of the fields below |
//!
//! and, in the stream, all little endian: `u32` flags (`0x0001` vertex normals, `0x0002`
//! texture coordinates, `0x0008` vertex colours, `0x0010` face normals, `0x1000` single,
//! `0x2000` double precision), in version 4 the mesh's name (UTF-8, NUL-terminated),
//! `u64` vertex count, `u64` triangle count, then the arrays: positions (`xyz` per vertex),
//! normals, texture coordinates (`uv`), colours (`rgb`), each present as the flags say, in
//! `f32` or `f64`, and the triangles as three `u32` vertex indices each. A file of several
//! meshes ends with a table of where each starts: one offset a mesh (`u64` in version 4,
//! `u32` in version 3; the first is 0) and the `u32` number of meshes. `shape_index` picks
//! the mesh; Mitsuba reads the first without the table, and so does this reader.
//!
//! As in Mitsuba 3: vertex colours are skipped, the face-normals flag is ignored (the
//! shape's `face_normals` property decides), and a mesh without normals gets angle-weighted
//! vertex normals (done by the shape, [`super::meshes::angle_weighted_normals`]).
//! Texture coordinates are stored `v` up ([`MeshData`]): Mitsuba's `(u, v)` as `(u, 1 - v)`.
//!
//! Bad input is an error naming the file: a stream that ends early or is corrupt, counts
//! larger than the data (nothing is allocated beyond the data that arrives), indices out of
//! range, positions that are not finite or beyond [`crate::scene::MAX_COORDINATE`], a
//! `shape_index` or a table entry that points outside the file.

use super::meshes::{MeshData, check_position};
use crate::error::{Error, Result};
use flate2::bufread::ZlibDecoder;
use glam::{Vec2, Vec3};
use std::fs::File;
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::Path;

/// The format's identifier, the first `u16` of a mesh.
pub const MAGIC: u16 = 0x041C;
const HAS_NORMALS: u32 = 0x0001;
const HAS_TEXCOORDS: u32 = 0x0002;
const HAS_COLORS: u32 = 0x0008;
const DOUBLE_PRECISION: u32 = 0x2000;
/// The longest mesh name read (a version 4 name without its NUL would run to the end).
const MAX_NAME_BYTES: usize = 1 << 16;
/// Deflate expands at most 1032-fold (258-byte matches in two-bit codes); a mesh whose
/// counts need more than this many bytes per compressed byte left in the file is lying.
const MAX_INFLATE_RATIO: u64 = 1032;

/// Reads mesh `shape_index` of the `.serialized` file at `path`.
pub fn load_serialized(path: &Path, shape_index: u32) -> Result<MeshData> {
    let bad = |message: String| Error::invalid(path, message);
    let io = |reason: std::io::Error| Error::Io {
        path: path.to_path_buf(),
        reason,
    };
    let mut file = File::open(path).map_err(io)?;
    let file_bytes = file.metadata().map_err(io)?.len();
    let version = read_header(&mut file, path, "the file")?;
    let start = if shape_index == 0 {
        0
    } else {
        let at = mesh_offset(&mut file, path, file_bytes, version, shape_index)?;
        file.seek(SeekFrom::Start(at)).map_err(io)?;
        let what = format!("mesh {shape_index}, at byte {at} by the file's table,");
        if read_header(&mut file, path, &what)? != version {
            return Err(bad(format!(
                "{what} has another version than the file's first mesh"
            )));
        }
        at
    };
    let compressed_bytes = file_bytes.saturating_sub(start + 4);
    let mut s = Inflated {
        z: ZlibDecoder::new(BufReader::new(file)),
        path,
        shape_index,
        at: 0,
    };
    let flags = u32::from_le_bytes(s.array("the flags")?);
    if version == 4 {
        s.name()?;
    }
    let vertex_count = u64::from_le_bytes(s.array("the vertex count")?);
    let face_count = u64::from_le_bytes(s.array("the triangle count")?);
    if vertex_count > u32::MAX as u64 {
        return Err(bad(format!(
            "mesh {shape_index} says it has {vertex_count} vertices, more than 32-bit indices reach"
        )));
    }
    let value_bytes: u64 = if flags & DOUBLE_PRECISION != 0 { 8 } else { 4 };
    let has_normals = flags & HAS_NORMALS != 0;
    let has_uvs = flags & HAS_TEXCOORDS != 0;
    let values_per_vertex =
        3 + 3 * has_normals as u64 + 2 * has_uvs as u64 + 3 * (flags & HAS_COLORS != 0) as u64;
    let needed = face_count
        .checked_mul(12)
        .and_then(|f| f.checked_add(vertex_count * values_per_vertex * value_bytes));
    match needed {
        Some(n) if n <= compressed_bytes.saturating_mul(MAX_INFLATE_RATIO) => {}
        _ => {
            return Err(bad(format!(
                "mesh {shape_index} says it has {vertex_count} vertices and {face_count} triangles, more than the {compressed_bytes} compressed bytes left in the file can hold"
            )));
        }
    }
    let mut m = MeshData::default();
    let read_vectors = |s: &mut Inflated, what: &str, dim: usize| -> Result<Vec<f32>> {
        let bytes = s.bytes(vertex_count * dim as u64 * value_bytes, what)?;
        Ok(if value_bytes == 8 {
            bytes
                .chunks_exact(8)
                .map(|b| f64::from_le_bytes(b.try_into().unwrap()) as f32)
                .collect()
        } else {
            bytes
                .chunks_exact(4)
                .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
                .collect()
        })
    };
    let positions = read_vectors(&mut s, "the vertex positions", 3)?;
    m.positions = positions
        .chunks_exact(3)
        .map(|p| Vec3::new(p[0], p[1], p[2]))
        .collect();
    drop(positions);
    for (i, p) in m.positions.iter().enumerate() {
        check_position(p).map_err(|e| bad(format!("mesh {shape_index}, vertex {i}: {e}")))?;
    }
    if has_normals {
        let normals = read_vectors(&mut s, "the vertex normals", 3)?;
        m.normals = Some(
            normals
                .chunks_exact(3)
                .map(|n| Vec3::new(n[0], n[1], n[2]))
                .collect(),
        );
    }
    if has_uvs {
        let uvs = read_vectors(&mut s, "the texture coordinates", 2)?;
        let mut stored = Vec::with_capacity(uvs.len() / 2);
        for (i, t) in uvs.chunks_exact(2).enumerate() {
            if !(t[0].is_finite() && t[1].is_finite()) {
                return Err(bad(format!(
                    "mesh {shape_index}, vertex {i}: texture coordinates ({}, {}) are not finite",
                    t[0], t[1]
                )));
            }
            stored.push(Vec2::new(t[0], 1.0 - t[1]));
        }
        m.uvs = Some(stored);
    }
    if flags & HAS_COLORS != 0 {
        s.bytes(vertex_count * 3 * value_bytes, "the vertex colours")?;
    }
    let indices = s.bytes(face_count * 12, "the triangles")?;
    m.indices = Vec::with_capacity(face_count as usize);
    for (f, t) in indices.chunks_exact(12).enumerate() {
        let tri = [0, 4, 8].map(|k| u32::from_le_bytes(t[k..k + 4].try_into().unwrap()));
        if let Some(&i) = tri.iter().find(|&&i| i as u64 >= vertex_count) {
            return Err(bad(format!(
                "mesh {shape_index}, triangle {f} refers to vertex {i}, but the mesh has {vertex_count} vertices"
            )));
        }
        m.indices.push(tri);
    }
    Ok(m)
}

/// Reads a mesh's uncompressed header (identifier and version) from `file`'s position.
fn read_header(file: &mut File, path: &Path, what: &str) -> Result<u16> {
    let mut h = [0u8; 4];
    file.read_exact(&mut h).map_err(|_| {
        Error::invalid(
            path,
            format!("{what} is too short for a .serialized header (4 bytes)"),
        )
    })?;
    let magic = u16::from_le_bytes([h[0], h[1]]);
    let version = u16::from_le_bytes([h[2], h[3]]);
    if magic != MAGIC {
        return Err(Error::invalid(
            path,
            format!(
                "{what} does not start with a Mitsuba .serialized header (0x{MAGIC:04x}, found 0x{magic:04x})"
            ),
        ));
    }
    if version != 3 && version != 4 {
        return Err(Error::invalid(
            path,
            format!(
                "{what} is of .serialized version {version}; Mitsuba 3 and footprint read versions 3 and 4"
            ),
        ));
    }
    Ok(version)
}

/// Where mesh `index` starts, from the table at the end of the file.
fn mesh_offset(
    file: &mut File,
    path: &Path,
    file_bytes: u64,
    version: u16,
    index: u32,
) -> Result<u64> {
    let bad = |message: String| Error::invalid(path, message);
    let entry_bytes: u64 = if version == 4 { 8 } else { 4 };
    let mut read_at = |at: u64, n: usize| -> Result<u64> {
        let mut b = [0u8; 8];
        file.seek(SeekFrom::Start(at))
            .and_then(|_| file.read_exact(&mut b[..n]))
            .map_err(|reason| Error::Io {
                path: path.to_path_buf(),
                reason,
            })?;
        Ok(u64::from_le_bytes(b))
    };
    if file_bytes < 8 {
        return Err(bad(format!(
            "shape_index {index}: the file ({file_bytes} bytes) has no table of meshes"
        )));
    }
    let count = read_at(file_bytes - 4, 4)?;
    if index as u64 >= count {
        return Err(bad(format!(
            "shape_index {index} is out of range: the file's table lists {count} meshes"
        )));
    }
    let table_bytes = count * entry_bytes + 4;
    if table_bytes + 4 > file_bytes {
        return Err(bad(format!(
            "its table of meshes lists {count} meshes, more than a file of {file_bytes} bytes holds"
        )));
    }
    let meshes_end = file_bytes - table_bytes;
    let entry = file_bytes - 4 - entry_bytes * (count - index as u64);
    let at = read_at(entry, entry_bytes as usize)?;
    if at + 4 > meshes_end {
        return Err(bad(format!(
            "the table puts mesh {index} at byte {at}, past the meshes' end (byte {meshes_end})"
        )));
    }
    Ok(at)
}

/// A mesh's zlib stream, read with the number of bytes read so far for the errors.
struct Inflated<'p> {
    z: ZlibDecoder<BufReader<File>>,
    path: &'p Path,
    shape_index: u32,
    /// Bytes inflated so far.
    at: u64,
}

impl Inflated<'_> {
    /// `n` bytes of `what`: an error if the stream ends first. The buffer grows with the data
    /// that arrives, so a count larger than the data allocates no more than the data.
    fn bytes(&mut self, n: u64, what: &str) -> Result<Vec<u8>> {
        let mut out = Vec::with_capacity(n.min(1 << 16) as usize);
        let got = (&mut self.z)
            .take(n)
            .read_to_end(&mut out)
            .map_err(|e| self.corrupt(what, e))?;
        if (got as u64) < n {
            return Err(Error::invalid(
                self.path,
                format!(
                    "mesh {}: the data ends within {what}, {} bytes into the inflated mesh ({n} bytes of it expected, {got} found): the file is truncated or its counts are wrong",
                    self.shape_index,
                    self.at + got as u64
                ),
            ));
        }
        self.at += n;
        Ok(out)
    }

    fn array<const N: usize>(&mut self, what: &str) -> Result<[u8; N]> {
        Ok(self.bytes(N as u64, what)?.try_into().unwrap())
    }

    /// A version 4 mesh's name, NUL-terminated (read and dropped).
    fn name(&mut self) -> Result<()> {
        for _ in 0..MAX_NAME_BYTES {
            if self.array::<1>("the mesh's name")?[0] == 0 {
                return Ok(());
            }
        }
        Err(Error::invalid(
            self.path,
            format!(
                "mesh {}: its name runs past {MAX_NAME_BYTES} bytes without its closing NUL",
                self.shape_index
            ),
        ))
    }

    fn corrupt(&self, what: &str, e: std::io::Error) -> Error {
        let (i, at) = (self.shape_index, self.at);
        Error::invalid(
            self.path,
            if e.kind() == std::io::ErrorKind::UnexpectedEof {
                format!(
                    "mesh {i}: the compressed data ends within {what}, {at} bytes into the inflated mesh: the file is truncated"
                )
            } else {
                format!(
                    "mesh {i}: the compressed data is corrupt within {what}, {at} bytes into the inflated mesh: {e}"
                )
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use flate2::write::ZlibEncoder;
    use std::io::Write;

    /// A mesh to write: positions, optional normals, texture coordinates and colours, and
    /// triangles.
    #[derive(Clone)]
    struct Mesh {
        positions: Vec<[f64; 3]>,
        normals: Option<Vec<[f64; 3]>>,
        uvs: Option<Vec<[f64; 2]>>,
        colors: bool,
        triangles: Vec<[u32; 3]>,
    }

    /// A mesh's inflated stream, as Mitsuba writes it.
    fn stream(m: &Mesh, version: u16, double: bool) -> Vec<u8> {
        let mut flags = if double { DOUBLE_PRECISION } else { 0x1000 };
        flags |= if m.normals.is_some() { HAS_NORMALS } else { 0 };
        flags |= if m.uvs.is_some() { HAS_TEXCOORDS } else { 0 };
        flags |= if m.colors { HAS_COLORS } else { 0 };
        let mut s = flags.to_le_bytes().to_vec();
        if version == 4 {
            s.extend_from_slice(b"a mesh\0");
        }
        s.extend_from_slice(&(m.positions.len() as u64).to_le_bytes());
        s.extend_from_slice(&(m.triangles.len() as u64).to_le_bytes());
        let mut put = |vs: &mut dyn Iterator<Item = f64>| {
            for v in vs {
                if double {
                    s.extend_from_slice(&v.to_le_bytes());
                } else {
                    s.extend_from_slice(&(v as f32).to_le_bytes());
                }
            }
        };
        put(&mut m.positions.iter().flatten().copied());
        if let Some(n) = &m.normals {
            put(&mut n.iter().flatten().copied());
        }
        if let Some(t) = &m.uvs {
            put(&mut t.iter().flatten().copied());
        }
        if m.colors {
            put(&mut m.positions.iter().flatten().map(|_| 0.5));
        }
        for t in &m.triangles {
            for i in t {
                s.extend_from_slice(&i.to_le_bytes());
            }
        }
        s
    }

    /// A `.serialized` file of `meshes`, with the table of offsets at the end.
    fn file(meshes: &[Mesh], version: u16, double: bool) -> Vec<u8> {
        let mut out = Vec::new();
        let mut offsets = Vec::new();
        for m in meshes {
            offsets.push(out.len() as u64);
            out.extend_from_slice(&MAGIC.to_le_bytes());
            out.extend_from_slice(&version.to_le_bytes());
            let mut z = ZlibEncoder::new(Vec::new(), flate2::Compression::default());
            z.write_all(&stream(m, version, double)).unwrap();
            out.extend_from_slice(&z.finish().unwrap());
        }
        for o in &offsets {
            if version == 4 {
                out.extend_from_slice(&o.to_le_bytes());
            } else {
                out.extend_from_slice(&(*o as u32).to_le_bytes());
            }
        }
        out.extend_from_slice(&(meshes.len() as u32).to_le_bytes());
        out
    }

    fn quad() -> Mesh {
        Mesh {
            positions: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.5],
                [0.0, 1.0, 0.0],
            ],
            normals: Some(vec![[0.0, 0.0, 1.0]; 4]),
            uvs: Some(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 0.75], [0.0, 1.0]]),
            colors: true,
            triangles: vec![[0, 1, 2], [2, 3, 0]],
        }
    }

    fn triangle() -> Mesh {
        Mesh {
            positions: vec![[0.0, 0.0, 2.0], [0.1, 0.0, 2.0], [0.0, 0.3, 2.0]],
            normals: None,
            uvs: None,
            colors: false,
            triangles: vec![[0, 1, 2]],
        }
    }

    fn write(name: &str, data: &[u8]) -> std::path::PathBuf {
        let d = std::env::temp_dir().join(format!("footprint-serialized-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        let p = d.join(name);
        std::fs::write(&p, data).unwrap();
        p
    }

    fn same(read: &MeshData, m: &Mesh) {
        let p: Vec<Vec3> = m
            .positions
            .iter()
            .map(|p| Vec3::from(p.map(|x| x as f32)))
            .collect();
        assert_eq!(read.positions, p);
        let n = m
            .normals
            .as_ref()
            .map(|n| n.iter().map(|n| Vec3::from(n.map(|x| x as f32))).collect());
        assert_eq!(read.normals, n);
        let t = m.uvs.as_ref().map(|t| {
            t.iter()
                .map(|t| Vec2::new(t[0] as f32, 1.0 - t[1] as f32))
                .collect()
        });
        assert_eq!(read.uvs, t, "texture coordinates, v stored up");
        assert_eq!(read.indices, m.triangles);
    }

    /// Versions 3 and 4, single and double precision, three meshes a file: each
    /// `shape_index` reads its mesh, with normals, texture coordinates and colours (skipped)
    /// as its flags say.
    #[test]
    fn versions_precisions_and_shape_indices_read() {
        let meshes = [quad(), triangle(), quad()];
        for version in [3, 4] {
            for double in [false, true] {
                let what = format!("v{version} double {double}");
                let path = write(
                    &format!("{version}-{double}.serialized"),
                    &file(&meshes, version, double),
                );
                for (i, m) in meshes.iter().enumerate() {
                    let read = load_serialized(&path, i as u32)
                        .unwrap_or_else(|e| panic!("{what}, mesh {i}: {e}"));
                    same(&read, m);
                }
                let e = load_serialized(&path, 3).unwrap_err().to_string();
                assert!(
                    e.contains("shape_index 3 is out of range: the file's table lists 3 meshes"),
                    "{e}"
                );
            }
        }
    }

    fn err(name: &str, data: &[u8], shape_index: u32) -> String {
        let path = write(name, data);
        let e = load_serialized(&path, shape_index)
            .expect_err("a bad file is refused")
            .to_string();
        assert!(e.contains(name), "the error names the file: {e}");
        e
    }

    /// Bad files give errors that name the file and say what is wrong, and nothing is
    /// allocated for counts the data cannot hold.
    #[test]
    fn bad_files_are_refused_with_what_and_where() {
        let good = file(&[quad(), triangle()], 4, false);
        let with = |f: &dyn Fn(&mut Mesh)| {
            let mut m = quad();
            f(&mut m);
            file(&[m], 4, false)
        };
        let cases: Vec<(Vec<u8>, u32, &str)> = vec![
            (
                b"ply\n".to_vec(),
                0,
                "does not start with a Mitsuba .serialized header",
            ),
            (vec![0x1c], 0, "too short"),
            ([&[0x1c, 0x04, 5, 0], &good[4..]].concat(), 0, "version 5"),
            (
                good[..good.len() / 3].to_vec(),
                0,
                "the compressed data ends within the vertex positions",
            ),
            (good[..good.len() - 4].to_vec(), 1, "out of range"),
            (
                [&good[..good.len() - 4], &1000u32.to_le_bytes()[..]].concat(),
                1,
                "lists 1000 meshes, more than a file of",
            ),
            (
                {
                    let mut f = good.clone();
                    let n = f.len();
                    f[n - 12..n - 4].copy_from_slice(&1_000_000u64.to_le_bytes());
                    f
                },
                1,
                "past the meshes' end",
            ),
            (
                {
                    let mut f = good.clone();
                    let n = f.len();
                    f[n - 12..n - 4].copy_from_slice(&6u64.to_le_bytes());
                    f
                },
                1,
                "does not start with a Mitsuba .serialized header",
            ),
            (
                {
                    let mut f = good.clone();
                    for b in &mut f[12..40] {
                        *b ^= 0x5a;
                    }
                    f
                },
                0,
                "corrupt",
            ),
            (
                with(&|m| m.triangles[1][2] = 4),
                0,
                "triangle 1 refers to vertex 4, but the mesh has 4 vertices",
            ),
            (
                with(&|m| m.positions[2][1] = f64::NAN),
                0,
                "vertex 2: position (1, NaN, 0.5) is not finite",
            ),
            (
                with(&|m| m.positions[3][0] = 1e20),
                0,
                "vertex 3: position (100000000000000000000, 1, 0) is farther than 1e15",
            ),
            (
                with(&|m| m.uvs.as_mut().unwrap()[1][0] = f64::INFINITY),
                0,
                "texture coordinates (inf, 0) are not finite",
            ),
        ];
        for (k, (data, index, needle)) in cases.into_iter().enumerate() {
            let e = err(&format!("bad-{k}.serialized"), &data, index);
            assert!(e.contains(needle), "case {k}: '{needle}' not in: {e}");
        }
        // Counts that lie: more vertices than the stream holds, and counts no file can hold.
        for (vertices, triangles, needle) in [
            (5u64, 2u64, "the data ends within the vertex"),
            (4, 3, "the data ends within the triangles"),
            (1 << 31, 1 << 40, "more than the"),
            (1 << 33, 0, "more than 32-bit indices reach"),
        ] {
            let mut s = stream(&quad(), 4, false);
            let at = 4 + b"a mesh\0".len();
            s[at..at + 8].copy_from_slice(&vertices.to_le_bytes());
            s[at + 8..at + 16].copy_from_slice(&triangles.to_le_bytes());
            let mut z = ZlibEncoder::new(Vec::new(), flate2::Compression::default());
            z.write_all(&s).unwrap();
            let data = [&[0x1c, 0x04, 4, 0], &z.finish().unwrap()[..]].concat();
            let e = err("lying.serialized", &data, 0);
            assert!(
                e.contains(needle),
                "{vertices} {triangles}: '{needle}' not in: {e}"
            );
        }
    }
}
