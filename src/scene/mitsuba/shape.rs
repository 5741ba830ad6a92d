//! The `<shape>` element: a mesh (`meshes.rs`, and the files of `ply.rs` and
//! `serialized.rs`) with its BSDF and area emitter, transformed to the world and added to the
//! scene's triangles.

use super::builder::Builder;
use super::meshes::{self, MeshData, MeshSource};
use super::xml::{Doc, Props};
use crate::Rgb;
use crate::bsdf::material::Material;
use crate::error::Result;
use crate::scene::geometry::{TriangleGeom, TriangleShading};
use glam::{Mat3, Mat4, Vec2, Vec3};
use roxmltree::{Node, NodeId};

const SHAPES: &str = "obj, ply, serialized, rectangle, cube, disk, sphere, cylinder";

/// The mesh file a `<shape>` of type `kind` reads (`None` for the shapes that are not
/// files): its `filename`, and for `serialized` its `shape_index`.
pub(super) fn mesh_source(
    doc: &Doc,
    node: Node,
    kind: &str,
    p: &Props,
) -> Result<Option<MeshSource>> {
    if !matches!(kind, "obj" | "ply" | "serialized") {
        return Ok(None);
    }
    let file = p
        .string("filename")?
        .ok_or_else(|| doc.err(node, format!("{kind} needs 'filename'")))?;
    let path = doc.file(&file);
    Ok(Some(match kind {
        "obj" => MeshSource::Obj(path),
        "ply" => MeshSource::Ply(path),
        _ => {
            let index = p.integer("shape_index")?.unwrap_or(0);
            let shape_index = u32::try_from(index).map_err(|_| {
                doc.err(
                    node,
                    format!("'shape_index' must be a non-negative 32-bit integer, got {index}"),
                )
            })?;
            MeshSource::Serialized { path, shape_index }
        }
    }))
}

impl<'a, 'd> Builder<'a, 'd> {
    pub(super) fn shape(&mut self, node: Node<'a, 'a>) -> Result<()> {
        let kind = self.kind(node)?;
        let p = Props::new(self.doc, node)?;
        let mut to_world = p.transform("to_world")?.unwrap_or(Mat4::IDENTITY);
        let flip_normals = p.boolean("flip_normals")?.unwrap_or(false);
        let mut face_normals = false;
        let mut mesh = match kind.as_str() {
            "obj" | "ply" | "serialized" => {
                let source = mesh_source(self.doc, node, &kind, &p)?
                    .expect("obj, ply and serialized name a file");
                face_normals = p.boolean("face_normals")?.unwrap_or(false);
                // Mitsuba flips OBJ's v by default and PLY's not; .serialized has no choice.
                let flip_default = kind == "obj";
                let flip_tex = if kind == "serialized" {
                    flip_default
                } else {
                    p.boolean("flip_tex_coords")?.unwrap_or(flip_default)
                };
                let mut mesh = self.files.mesh(&source)?;
                if flip_tex != flip_default {
                    for t in mesh.uvs.iter_mut().flatten() {
                        t.y = 1.0 - t.y;
                    }
                }
                if mesh.normals.is_none() && !face_normals {
                    mesh.normals = Some(meshes::angle_weighted_normals(&mesh));
                }
                mesh
            }
            "rectangle" => meshes::rectangle(),
            "cube" => meshes::cube(),
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
                meshes::sphere(meshes::SPHERE_QUADS.0, meshes::SPHERE_QUADS.1)
            }
            "disk" => meshes::disk(meshes::DISK_SEGMENTS),
            "cylinder" => {
                let p0 = p.vec3("p0")?.unwrap_or(Vec3::ZERO);
                let p1 = p.vec3("p1")?.unwrap_or(Vec3::Z);
                let radius = p.float_or("radius", 1.0)?;
                let length = (p1 - p0).length();
                if !(radius > 0.0 && length > 0.0 && length.is_finite()) {
                    return Err(self.doc.err(
                        node,
                        format!(
                            "cylinder needs a positive radius and p0 != p1, got radius {radius}, length {length}"
                        ),
                    ));
                }
                // Mitsuba's frame about the axis (Duff et al. 2017, glam's orthonormal pair
                // is the same construction): it places u = 0.
                let axis = (p1 - p0) / length;
                let (s, t) = axis.any_orthonormal_pair();
                to_world = to_world
                    * Mat4::from_translation(p0)
                    * Mat4::from_mat3(Mat3::from_cols(s, t, axis))
                    * Mat4::from_scale(Vec3::new(radius, radius, length));
                meshes::cylinder(meshes::CYLINDER_SEGMENTS)
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
        // Mitsuba's default BSDF: one-sided diffuse of reflectance 0.5, and 0 on a shape
        // that emits (Mitsuba 3's `Shape` constructor): a light without a BSDF reflects
        // nothing.
        let (bsdf_node, mut m) = match material {
            Some((id, m)) => (Some(id), m),
            None => (
                None,
                Material {
                    name: "default".into(),
                    two_sided: false,
                    kd: if radiance.is_some() {
                        Rgb::ZERO
                    } else {
                        Material::default().kd
                    },
                    ..Material::default()
                },
            ),
        };
        if let Some(le) = radiance {
            if m.is_masked() {
                self.doc.unsupported(
                    node,
                    "a mask on an emitting shape",
                    "masks on shapes that do not emit",
                    "the shape opaque",
                )?;
                m.opacity = 1.0;
                m.opacity_texture = None;
            }
            m.ke = le;
            if let Some(id) = node.attribute("id") {
                m.name = format!("{} (emitter {id})", m.name);
            }
        }
        let material = self.material_id(bsdf_node, m);
        // Mitsuba's rectangle, disk, sphere and cylinder take their front from the
        // transformed normal (the inverse transpose), not from the winding, which a
        // mirroring transform reverses (checked with Mitsuba 3.9.1 for the disk and the
        // cylinder: a cylinder mirrored in x still faces out).
        let primitive = matches!(kind.as_str(), "rectangle" | "disk" | "sphere" | "cylinder");
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
}
