//! Mitsuba 3's shapes as triangle meshes in their local frames: `rectangle` (`[-1, 1]²` in the
//! `z = 0` plane, facing `+z`), `cube` (`[-1, 1]³`, facing outward), `disk` (the unit disk
//! at `z = 0`, facing `+z`), `sphere` and `cylinder` (tessellated, with the exact shape's
//! normals as shading normals), and the mesh files a [`MeshSource`] names: `obj` (Mitsuba's
//! OBJ loader ignores `.mtl` files, and so does this one), `ply` (`ply.rs`) and
//! `serialized` (`serialized.rs`).
//!
//! Texture coordinates are stored in OBJ convention (`v` up), the convention of every
//! triangle in a [`crate::scene::Scene`]; Mitsuba's `(u, v)` of a primitive is `(u, 1 - v)`
//! here.

use crate::error::{Error, Result};
use crate::math::PI;
use crate::scene::MAX_COORDINATE;
use glam::{Vec2, Vec3};
use std::io::BufReader;
use std::path::{Path, PathBuf};

/// An indexed triangle mesh.
#[derive(Clone, Debug, Default)]
pub struct MeshData {
    pub positions: Vec<Vec3>,
    pub normals: Option<Vec<Vec3>>,
    /// OBJ convention (`v` up).
    pub uvs: Option<Vec<Vec2>>,
    pub indices: Vec<[u32; 3]>,
}

/// Quads of the tessellated sphere (rings x segments) and segments of the disk and the
/// cylinder: each within 0.1% of the exact shape's area (tested below).
pub const SPHERE_QUADS: (u32, u32) = (64, 128);
pub const DISK_SEGMENTS: u32 = 128;
pub const CYLINDER_SEGMENTS: u32 = 128;

/// A mesh file as a shape names it: its format, and in a `.serialized` file which mesh.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum MeshSource {
    Obj(PathBuf),
    Ply(PathBuf),
    Serialized { path: PathBuf, shape_index: u32 },
}

impl MeshSource {
    pub fn path(&self) -> &Path {
        match self {
            MeshSource::Obj(p) | MeshSource::Ply(p) => p,
            MeshSource::Serialized { path, .. } => path,
        }
    }

    /// Reads the mesh; texture coordinates come as Mitsuba reads them by default (OBJ's `v`
    /// flipped, PLY's and `.serialized`'s as stored), in the convention of [`MeshData`].
    pub fn load(&self) -> Result<MeshData> {
        match self {
            MeshSource::Obj(p) => load_obj(p),
            MeshSource::Ply(p) => super::ply::load_ply(p),
            MeshSource::Serialized { path, shape_index } => {
                super::serialized::load_serialized(path, *shape_index)
            }
        }
    }
}

/// A vertex position a file may hold: finite, and within [`MAX_COORDINATE`] of the origin
/// on every axis; else what is wrong with it.
pub fn check_position(p: &Vec3) -> std::result::Result<(), String> {
    if !p.is_finite() {
        return Err(format!(
            "position ({}, {}, {}) is not finite",
            p.x, p.y, p.z
        ));
    }
    if p.abs().max_element() > MAX_COORDINATE {
        return Err(format!(
            "position ({}, {}, {}) is farther than {MAX_COORDINATE:e} from the origin",
            p.x, p.y, p.z
        ));
    }
    Ok(())
}

/// Mitsuba `uv` to the stored convention.
fn uv(u: f32, v: f32) -> Vec2 {
    Vec2::new(u, 1.0 - v)
}

pub fn rectangle() -> MeshData {
    MeshData {
        positions: vec![
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(-1.0, 1.0, 0.0),
        ],
        normals: None,
        uvs: Some(vec![uv(0.0, 0.0), uv(1.0, 0.0), uv(1.0, 1.0), uv(0.0, 1.0)]),
        indices: vec![[0, 1, 2], [2, 3, 0]],
    }
}

pub fn cube() -> MeshData {
    let mut m = MeshData {
        uvs: Some(Vec::new()),
        ..Default::default()
    };
    // Each face: outward normal n and in-plane axes a, b with a × b = n.
    for n in crate::math::SIGNED_AXES {
        let a = if n.x != 0.0 {
            Vec3::Y
        } else if n.y != 0.0 {
            Vec3::Z
        } else {
            Vec3::X
        };
        let b = n.cross(a);
        debug_assert!((a.cross(b) - n).length() < 1e-6);
        let base = m.positions.len() as u32;
        for (s, t) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            m.positions.push(n + a * s + b * t);
            m.uvs
                .as_mut()
                .unwrap()
                .push(uv(0.5 * (s + 1.0), 0.5 * (t + 1.0)));
        }
        m.indices.push([base, base + 1, base + 2]);
        m.indices.push([base + 2, base + 3, base]);
    }
    m
}

/// A unit sphere at the origin as `rings` x `segments` quads (two triangles each, one at the
/// poles), with exact normals and Mitsuba's sphere `uv` (`u = φ / 2π`, `v = θ / π`).
pub fn sphere(rings: u32, segments: u32) -> MeshData {
    let mut m = MeshData {
        normals: Some(Vec::new()),
        uvs: Some(Vec::new()),
        ..Default::default()
    };
    for i in 0..=rings {
        let theta = PI * i as f32 / rings as f32;
        for j in 0..=segments {
            let phi = 2.0 * PI * j as f32 / segments as f32;
            let p = Vec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            );
            m.positions.push(p);
            m.normals.as_mut().unwrap().push(p);
            m.uvs
                .as_mut()
                .unwrap()
                .push(uv(j as f32 / segments as f32, i as f32 / rings as f32));
        }
    }
    let row = segments + 1;
    for i in 0..rings {
        for j in 0..segments {
            let a = i * row + j;
            let b = a + 1;
            let c = a + row;
            let d = c + 1;
            // Outward winding: (a, c, b) and (b, c, d); the pole rows lose one triangle.
            if i != 0 {
                m.indices.push([a, c, b]);
            }
            if i != rings - 1 {
                m.indices.push([b, c, d]);
            }
        }
    }
    m
}

/// The unit disk at the origin in the `z = 0` plane, facing `+z`, as `segments` triangles
/// fanned from the centre, with Mitsuba's disk `uv` (`u = r`, `v = φ / 2π`). The polygon's
/// area is `sin(2π/n) / (2π/n)` of the disk's (0.04% short at 128 segments).
pub fn disk(segments: u32) -> MeshData {
    let mut m = MeshData {
        normals: Some(Vec::new()),
        uvs: Some(Vec::new()),
        ..Default::default()
    };
    for j in 0..segments {
        // The centre, once a segment (its `v` is the segment's middle), and the rim.
        let base = m.positions.len() as u32;
        let v = |k: f32| (j as f32 + k) / segments as f32;
        let rim = |k: f32| {
            let phi = 2.0 * PI * v(k);
            Vec3::new(phi.cos(), phi.sin(), 0.0)
        };
        m.positions.extend([Vec3::ZERO, rim(0.0), rim(1.0)]);
        m.uvs
            .as_mut()
            .unwrap()
            .extend([uv(0.0, v(0.5)), uv(1.0, v(0.0)), uv(1.0, v(1.0))]);
        m.normals.as_mut().unwrap().extend([Vec3::Z; 3]);
        m.indices.push([base, base + 1, base + 2]);
    }
    m
}

/// Mitsuba's cylinder in its local frame: radius 1 about the `z` axis from `z = 0` to
/// `z = 1`, open at both ends, as `segments` quads facing outward (two triangles each), with
/// the exact (radial) normals and Mitsuba's `uv` (`u = φ / 2π`, `v = z`). The prism's side
/// area is `sin(π/n) / (π/n)` of the cylinder's (0.01% short at 128 segments).
pub fn cylinder(segments: u32) -> MeshData {
    let mut m = MeshData {
        normals: Some(Vec::new()),
        uvs: Some(Vec::new()),
        ..Default::default()
    };
    for j in 0..=segments {
        let u = j as f32 / segments as f32;
        let phi = 2.0 * PI * u;
        let n = Vec3::new(phi.cos(), phi.sin(), 0.0);
        for z in [0.0, 1.0] {
            m.positions.push(n + Vec3::Z * z);
            m.normals.as_mut().unwrap().push(n);
            m.uvs.as_mut().unwrap().push(uv(u, z));
        }
    }
    for j in 0..segments {
        // Bottom and top at φ_j (a, b) and φ_j+1 (c, d): (a, c, d) and (d, b, a) face out.
        let (a, b, c, d) = (2 * j, 2 * j + 1, 2 * j + 2, 2 * j + 3);
        m.indices.push([a, c, d]);
        m.indices.push([d, b, a]);
    }
    m
}

/// Reads an OBJ file's geometry (all objects and groups into one mesh).
pub fn load_obj(path: &Path) -> Result<MeshData> {
    let text = crate::scene::obj::read_obj_text(path)?;
    let opts = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj_buf(&mut BufReader::new(text.as_bytes()), &opts, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| Error::Obj {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let mut m = MeshData::default();
    let mut all_normals = true;
    let mut all_uvs = true;
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    for model in &models {
        let mesh = &model.mesh;
        let base = m.positions.len() as u32;
        let n = mesh.positions.len() / 3;
        m.positions.extend(
            mesh.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        if mesh.normals.len() == 3 * n && n > 0 {
            normals.extend(
                mesh.normals
                    .chunks_exact(3)
                    .map(|p| Vec3::new(p[0], p[1], p[2])),
            );
        } else {
            all_normals = false;
        }
        if mesh.texcoords.len() == 2 * n && n > 0 {
            uvs.extend(
                mesh.texcoords
                    .chunks_exact(2)
                    .map(|t| Vec2::new(t[0], t[1])),
            );
        } else {
            all_uvs = false;
        }
        for f in mesh.indices.chunks_exact(3) {
            if f.iter().any(|&i| i as usize >= n) {
                return Err(Error::Obj {
                    path: path.to_path_buf(),
                    message: "face refers to a vertex that does not exist".into(),
                });
            }
            m.indices.push([base + f[0], base + f[1], base + f[2]]);
        }
    }
    if all_normals && !normals.is_empty() {
        m.normals = Some(normals);
    }
    if all_uvs && !uvs.is_empty() {
        m.uvs = Some(uvs);
    }
    Ok(m)
}

/// Smooth vertex normals where a mesh has none and Mitsuba would compute them: each face's
/// normal added to its vertices weighted by the face's angle there (Mitsuba 3's
/// `recompute_vertex_normals`, after Thürmer & Wüthrich 1998).
pub fn angle_weighted_normals(m: &MeshData) -> Vec<Vec3> {
    let mut n = vec![Vec3::ZERO; m.positions.len()];
    for f in &m.indices {
        let p = f.map(|i| m.positions[i as usize]);
        let face_n = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
        if face_n == Vec3::ZERO {
            continue;
        }
        for k in 0..3 {
            let e1 = (p[(k + 1) % 3] - p[k]).normalize_or_zero();
            let e2 = (p[(k + 2) % 3] - p[k]).normalize_or_zero();
            let angle = e1.dot(e2).clamp(-1.0, 1.0).acos();
            n[f[k] as usize] += face_n * angle;
        }
    }
    n.iter().map(|v| v.normalize_or_zero()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(m: &MeshData) -> f64 {
        m.indices
            .iter()
            .map(|f| {
                let p = f.map(|i| m.positions[i as usize].as_dvec3());
                0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length()
            })
            .sum()
    }

    /// Every triangle faces the side its vertex normals point to, and the normals are unit
    /// vectors.
    fn faces_its_normals(m: &MeshData, what: &str) {
        let normals = m.normals.as_ref().expect("normals");
        for f in &m.indices {
            let p = f.map(|i| m.positions[i as usize]);
            let ng = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
            for &i in f {
                let n = normals[i as usize];
                assert!(
                    (n.length() - 1.0).abs() < 1e-5,
                    "{what}: |n| = {}",
                    n.length()
                );
                assert!(ng.dot(n) > 0.99, "{what}: face {ng} against normal {n}");
            }
        }
    }

    /// The tessellated sphere, disk and cylinder have the exact shapes' areas (4π, π and 2π
    /// for the open unit cylinder) within 0.1%, their triangles face their normals, and the
    /// normals are the exact shapes': radial for the sphere and the cylinder, +z for the disk.
    #[test]
    fn tessellated_shapes_have_the_exact_areas_and_normals() {
        let sphere = sphere(SPHERE_QUADS.0, SPHERE_QUADS.1);
        let disk = disk(DISK_SEGMENTS);
        let cylinder = cylinder(CYLINDER_SEGMENTS);
        for (what, m, exact) in [
            ("sphere", &sphere, 4.0 * std::f64::consts::PI),
            ("disk", &disk, std::f64::consts::PI),
            ("cylinder", &cylinder, 2.0 * std::f64::consts::PI),
        ] {
            let a = area(m);
            assert!(
                (a / exact - 1.0).abs() < 1e-3,
                "{what}: area {a}, exact {exact}"
            );
            assert!(a < exact, "{what}: inscribed");
            faces_its_normals(m, what);
        }
        let n = sphere.normals.as_ref().unwrap();
        assert!(
            sphere
                .positions
                .iter()
                .zip(n)
                .all(|(p, n)| (*p - *n).length() < 1e-6)
        );
        assert!(disk.normals.as_ref().unwrap().iter().all(|n| *n == Vec3::Z));
        assert!(
            disk.positions
                .iter()
                .all(|p| p.z == 0.0 && p.length() <= 1.0 + 1e-6)
        );
        let n = cylinder.normals.as_ref().unwrap();
        for (p, n) in cylinder.positions.iter().zip(n) {
            assert!((p.truncate() - n.truncate()).length() < 1e-6 && n.z == 0.0);
            assert!(p.z == 0.0 || p.z == 1.0);
        }
    }

    /// Mitsuba's `uv`: the disk's `(r, φ / 2π)` and the cylinder's `(φ / 2π, z)`, stored
    /// `v` up.
    #[test]
    fn disk_and_cylinder_uvs_are_mitsubas() {
        let phi_of = |p: Vec3| {
            let phi = p.y.atan2(p.x) / (2.0 * PI);
            if phi < 0.0 { phi + 1.0 } else { phi }
        };
        let d = disk(16);
        for (p, t) in d.positions.iter().zip(d.uvs.as_ref().unwrap()) {
            let (u, v) = (t.x, 1.0 - t.y);
            assert!((u - p.length()).abs() < 1e-6);
            if u > 0.0 {
                let phi = phi_of(*p);
                assert!(
                    (v - phi).abs() < 1e-5 || (v - phi).abs() > 1.0 - 1e-5,
                    "{v} {phi}"
                );
            }
        }
        let c = cylinder(16);
        for (p, t) in c.positions.iter().zip(c.uvs.as_ref().unwrap()) {
            let (u, v) = (t.x, 1.0 - t.y);
            assert!((v - p.z).abs() < 1e-6);
            let phi = phi_of(*p);
            assert!(
                (u - phi).abs() < 1e-5 || (u - phi).abs() > 1.0 - 1e-5,
                "{u} {phi}"
            );
        }
    }
}
