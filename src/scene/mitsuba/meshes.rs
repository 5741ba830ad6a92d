//! Mitsuba 3's shapes as triangle meshes in their local frames: `rectangle` (`[-1, 1]²` in the
//! `z = 0` plane, facing `+z`), `cube` (`[-1, 1]³`, facing outward), `sphere` (tessellated;
//! shading normals are the exact sphere normals) and `obj` files (Mitsuba's OBJ loader
//! ignores `.mtl` files, and so does this one).
//!
//! Texture coordinates are stored in OBJ convention (`v` up), the convention of every
//! triangle in a [`crate::scene::Scene`]; Mitsuba's `(u, v)` of a primitive is `(u, 1 - v)`
//! here.

use crate::error::{Error, Result};
use crate::math::PI;
use glam::{Vec2, Vec3};
use std::io::BufReader;
use std::path::Path;

/// An indexed triangle mesh.
#[derive(Clone, Debug, Default)]
pub struct MeshData {
    pub positions: Vec<Vec3>,
    pub normals: Option<Vec<Vec3>>,
    /// OBJ convention (`v` up).
    pub uvs: Option<Vec<Vec2>>,
    pub indices: Vec<[u32; 3]>,
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
