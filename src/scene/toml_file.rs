//! Scene files: the TOML format (documented in `docs/scene-format.md`) and the OBJ/MTL meshes
//! it names.
//!
//! Every error names the file and, where there is one, the line: TOML syntax errors and
//! unknown keys come with line and column; invalid values name their field
//! (`mesh[2].transform.scale`); OBJ vertices that are NaN or infinite name their line.
//! Degenerate triangles are skipped and counted.

use crate::bsdf::material::{Material, MaterialKind};
use crate::error::{Error, Result};
use crate::math::{Frame, Rgb};
use crate::scene::camera::Camera;
use crate::scene::geometry::{TriangleGeom, TriangleShading};
use crate::scene::light::Light;
use crate::scene::texture::Texture;
use crate::scene::{LoadStats, MAX_COORDINATE, Scene};
use crate::settings::{GuideParams, MapSettings, Named, RenderSettings};
use glam::{Mat3, Mat4, Vec2, Vec3};
use serde::Deserialize;
use std::cell::RefCell;
use std::collections::HashMap;
use std::io::BufReader;
use std::path::{Path, PathBuf};

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    camera: CameraDesc,
    #[serde(default)]
    render: RenderDesc,
    #[serde(default)]
    maps: MapSettings,
    #[serde(default)]
    guide: GuideParams,
    #[serde(default)]
    mesh: Vec<MeshDesc>,
    #[serde(default)]
    light: Vec<LightDesc>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct CameraDesc {
    position: [f32; 3],
    look_at: [f32; 3],
    #[serde(default = "default_up")]
    up: [f32; 3],
    fov_y: f32,
    resolution: [u32; 2],
    /// Thin lens: aperture radius in world units (0, the default: a pinhole).
    #[serde(default)]
    aperture_radius: f32,
    /// Thin lens: distance of the plane in focus along the view axis (default: the distance
    /// to `look_at`).
    focus_distance: Option<f32>,
}

fn default_up() -> [f32; 3] {
    [0.0, 1.0, 0.0]
}

/// The `[render]` table as written: names keep their place for error messages.
#[derive(Deserialize, Debug, Default)]
#[serde(deny_unknown_fields)]
struct RenderDesc {
    integrator: Option<toml::Spanned<String>>,
    guide: Option<toml::Spanned<String>>,
    spp: Option<u32>,
    time: Option<f64>,
    max_depth: Option<u32>,
    rr_depth: Option<u32>,
    seed: Option<u64>,
    exposure: Option<f32>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct MeshDesc {
    file: String,
    transform: Option<TransformDesc>,
    material: Option<MaterialOverride>,
}

#[derive(Deserialize, Debug)]
#[serde(untagged)]
enum ScaleDesc {
    Uniform(f32),
    PerAxis([f32; 3]),
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct TransformDesc {
    translate: Option<[f32; 3]>,
    /// Degrees about X, then Y, then Z.
    rotate: Option<[f32; 3]>,
    scale: Option<ScaleDesc>,
}

#[derive(Deserialize, Debug, Default)]
#[serde(deny_unknown_fields)]
struct MaterialOverride {
    kind: Option<String>,
    kd: Option<[f32; 3]>,
    ks: Option<[f32; 3]>,
    ns: Option<f32>,
    ke: Option<[f32; 3]>,
    tf: Option<[f32; 3]>,
    ni: Option<f32>,
}

#[derive(Deserialize, Debug)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
enum LightDesc {
    Point {
        position: [f32; 3],
        intensity: [f32; 3],
    },
    Spot {
        position: [f32; 3],
        direction: Option<[f32; 3]>,
        look_at: Option<[f32; 3]>,
        intensity: [f32; 3],
        inner_angle: f32,
        outer_angle: f32,
    },
    /// Parallel light travelling along `direction` (Mitsuba's `directional`).
    Directional {
        direction: [f32; 3],
        irradiance: [f32; 3],
    },
    /// A latitude-longitude environment map, relative to the scene file (Mitsuba's `envmap`,
    /// without rotation).
    Envmap {
        file: String,
        #[serde(default = "default_scale")]
        scale: f32,
    },
}

fn default_scale() -> f32 {
    1.0
}

/// Line and column (1-based) of byte `offset` in `text`.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rfind('\n').map(|i| offset - i).unwrap_or(offset + 1);
    (line, col)
}

fn finite3(path: &Path, field: &str, v: [f32; 3]) -> Result<Vec3> {
    let v = Vec3::from(v);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::invalid(
            path,
            format!("{field} must be finite, got {v:?}"),
        ))
    }
}

/// A point: finite, and within [`MAX_COORDINATE`] of the origin on every axis.
fn position3(path: &Path, field: &str, v: [f32; 3]) -> Result<Vec3> {
    let v = finite3(path, field, v)?;
    if v.abs().max_element() > MAX_COORDINATE {
        return Err(Error::invalid(
            path,
            format!("{field} is farther than {MAX_COORDINATE:e} from the origin, got {v:?}"),
        ));
    }
    Ok(v)
}

fn non_negative3(path: &Path, field: &str, v: [f32; 3]) -> Result<Vec3> {
    let v = finite3(path, field, v)?;
    if v.min_element() < 0.0 {
        return Err(Error::invalid(
            path,
            format!("{field} must be non-negative, got {v:?}"),
        ));
    }
    Ok(v)
}

/// Loads a TOML scene file (the format of `docs/scene-format.md`).
pub fn load(path: &Path) -> Result<Scene> {
    let text = std::fs::read_to_string(path).map_err(|reason| Error::Io {
        path: path.to_path_buf(),
        reason,
    })?;
    let file: SceneFile = toml::from_str(&text).map_err(|e| {
        let (line, column) = e.span().map(|s| line_col(&text, s.start)).unwrap_or((0, 0));
        Error::Syntax {
            path: path.to_path_buf(),
            line,
            column,
            message: e.message().trim().to_string(),
        }
    })?;
    let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    build_scene(path, &text, &dir, file)
}

fn build_scene(path: &Path, text: &str, dir: &Path, file: SceneFile) -> Result<Scene> {
    // ---- Camera ----
    let c = &file.camera;
    let camera = Camera::new(
        position3(path, "camera.position", c.position)?,
        position3(path, "camera.look_at", c.look_at)?,
        finite3(path, "camera.up", c.up)?,
        c.fov_y,
        c.resolution[0],
        c.resolution[1],
    )
    .and_then(|cam| {
        let to_target = Vec3::from(c.look_at) - Vec3::from(c.position);
        let focus = c.focus_distance.unwrap_or(to_target.length());
        cam.with_lens(c.aperture_radius, focus)
    })
    .map_err(|m| Error::invalid(path, m))?;

    // ---- Render settings ----
    let r = &file.render;
    let named = |n: &Option<toml::Spanned<String>>| {
        n.as_ref().map(|n| {
            let (line, column) = line_col(text, n.span().start);
            Named {
                name: n.get_ref().clone(),
                at: format!("{}:{line}:{column}", path.display()),
            }
        })
    };
    let defaults = RenderSettings::default();
    let settings = RenderSettings {
        integrator: named(&r.integrator),
        guide: named(&r.guide),
        spp: r.spp.unwrap_or(defaults.spp),
        time: r.time,
        max_depth: r.max_depth.unwrap_or(defaults.max_depth),
        rr_depth: r.rr_depth.unwrap_or(defaults.rr_depth),
        seed: r.seed.unwrap_or(defaults.seed),
        exposure: r.exposure.unwrap_or(defaults.exposure),
    };
    settings
        .validate()
        .map_err(|e| Error::invalid(path, e.to_string()))?;

    // ---- Meshes ----
    let mut triangles = Vec::new();
    let mut shading = Vec::new();
    let mut materials: Vec<Material> = Vec::new();
    let mut textures: Vec<Texture> = Vec::new();
    let mut texture_ids: HashMap<PathBuf, u32> = HashMap::new();
    let mut stats = LoadStats::default();
    for (mi, mesh) in file.mesh.iter().enumerate() {
        let field = format!("mesh[{mi}]");
        let transform = mesh_transform(path, &field, mesh.transform.as_ref())?;
        let overrides = mesh
            .material
            .as_ref()
            .map(|o| check_override(path, &field, o))
            .transpose()?;
        let obj_path = dir.join(&mesh.file);
        load_obj(
            &obj_path,
            transform,
            overrides.as_ref(),
            &mut triangles,
            &mut shading,
            &mut materials,
            &mut textures,
            &mut texture_ids,
            &mut stats,
        )?;
        stats.meshes += 1;
    }

    // ---- Lights ----
    let mut lights = Vec::new();
    for (li, l) in file.light.iter().enumerate() {
        let field = format!("light[{li}]");
        lights.push(match l {
            LightDesc::Point { position, intensity } => Light::Point {
                position: position3(path, &format!("{field}.position"), *position)?,
                intensity: non_negative3(path, &format!("{field}.intensity"), *intensity)?,
            },
            LightDesc::Spot { position, direction, look_at, intensity, inner_angle, outer_angle } => {
                let position = position3(path, &format!("{field}.position"), *position)?;
                let dir = match (direction, look_at) {
                    (Some(d), None) => finite3(path, &format!("{field}.direction"), *d)?,
                    (None, Some(t)) => position3(path, &format!("{field}.look_at"), *t)? - position,
                    _ => {
                        return Err(Error::invalid(
                            path,
                            format!("{field}: a spot light needs exactly one of 'direction' or 'look_at'"),
                        ));
                    }
                };
                let dir = dir
                    .try_normalize()
                    .ok_or_else(|| Error::invalid(path, format!("{field}: spot direction is zero")))?;
                if !(*outer_angle > 0.0 && *outer_angle <= 180.0) {
                    return Err(Error::invalid(path, format!("{field}.outer_angle must be in (0, 180] degrees")));
                }
                if !(*inner_angle >= 0.0 && inner_angle <= outer_angle) {
                    return Err(Error::invalid(path, format!("{field}.inner_angle must be in [0, outer_angle] degrees")));
                }
                Light::Spot {
                    position,
                    frame: Frame::from_z(dir),
                    intensity: non_negative3(path, &format!("{field}.intensity"), *intensity)?,
                    cos_inner: inner_angle.to_radians().cos(),
                    cos_outer: outer_angle.to_radians().cos(),
                    profile: crate::scene::light::SpotProfile::Smoothstep,
                }
            }
            LightDesc::Directional { direction, irradiance } => {
                let dir = finite3(path, &format!("{field}.direction"), *direction)?;
                let irradiance = non_negative3(path, &format!("{field}.irradiance"), *irradiance)?;
                Light::directional(dir, irradiance)
                    .ok_or_else(|| Error::invalid(path, format!("{field}: directional light's direction is zero")))?
            }
            LightDesc::Envmap { file, scale } => {
                if !(*scale >= 0.0 && scale.is_finite()) {
                    return Err(Error::invalid(path, format!("{field}.scale must be finite and not negative")));
                }
                let map_path = path.parent().unwrap_or(Path::new(".")).join(file);
                let map = crate::scene::envmap::EnvMap::load(&map_path, Mat3::IDENTITY)
                    .map_err(|e| Error::invalid(path, format!("{field}.file '{}': {e}", map_path.display())))?;
                Light::Environment {
                    le: Rgb::splat(*scale),
                    map: Some(std::sync::Arc::new(map)),
                    center: Vec3::ZERO,
                    radius: 1.0,
                }
            }
        });
    }

    // ---- Particle maps and direction samplers ----
    file.maps
        .validate()
        .map_err(|e| Error::invalid(path, e.to_string()))?;
    file.guide
        .validate()
        .map_err(|e| Error::invalid(path, e.to_string()))?;

    stats.triangles = triangles.len();
    let mut scene = Scene::new(
        camera, triangles, shading, materials, textures, lights, settings, stats,
    )
    .map_err(|m| Error::invalid(path, m))?;
    scene.maps = file.maps;
    scene.guide = file.guide;
    Ok(scene)
}

fn mesh_transform(path: &Path, field: &str, t: Option<&TransformDesc>) -> Result<Mat4> {
    let Some(t) = t else {
        return Ok(Mat4::IDENTITY);
    };
    let translate = match t.translate {
        Some(v) => position3(path, &format!("{field}.transform.translate"), v)?,
        None => Vec3::ZERO,
    };
    let rotate = match t.rotate {
        Some(v) => finite3(path, &format!("{field}.transform.rotate"), v)?,
        None => Vec3::ZERO,
    };
    let scale = match &t.scale {
        Some(ScaleDesc::Uniform(s)) => Vec3::splat(*s),
        Some(ScaleDesc::PerAxis(v)) => Vec3::from(*v),
        None => Vec3::ONE,
    };
    if !scale.is_finite() || scale.abs().min_element() < 1e-12 {
        return Err(Error::invalid(
            path,
            format!("{field}.transform.scale must be finite and non-zero, got {scale:?}"),
        ));
    }
    let r = Mat4::from_rotation_z(rotate.z.to_radians())
        * Mat4::from_rotation_y(rotate.y.to_radians())
        * Mat4::from_rotation_x(rotate.x.to_radians());
    Ok(Mat4::from_translation(translate) * r * Mat4::from_scale(scale))
}

fn check_override(path: &Path, field: &str, o: &MaterialOverride) -> Result<MaterialOverride> {
    let f = |name: &str, v: Option<[f32; 3]>| -> Result<Option<[f32; 3]>> {
        match v {
            Some(v) => Ok(Some(
                non_negative3(path, &format!("{field}.material.{name}"), v)?.into(),
            )),
            None => Ok(None),
        }
    };
    if let Some(k) = &o.kind {
        if MaterialKind::parse(k).is_none() {
            return Err(Error::invalid(
                path,
                format!(
                    "{field}.material.kind: unknown kind '{k}' (expected diffuse, glossy, mirror or glass)"
                ),
            ));
        }
    }
    if let Some(ns) = o.ns {
        if !(ns.is_finite() && ns >= 0.0) {
            return Err(Error::invalid(
                path,
                format!("{field}.material.ns must be finite and >= 0"),
            ));
        }
    }
    if let Some(ni) = o.ni {
        if !(ni.is_finite() && ni > 0.0) {
            return Err(Error::invalid(
                path,
                format!("{field}.material.ni must be finite and > 0"),
            ));
        }
    }
    Ok(MaterialOverride {
        kind: o.kind.clone(),
        kd: f("kd", o.kd)?,
        ks: f("ks", o.ks)?,
        ns: o.ns,
        ke: f("ke", o.ke)?,
        tf: f("tf", o.tf)?,
        ni: o.ni,
    })
}

fn apply_override(mut m: Material, o: &MaterialOverride) -> Material {
    if let Some(k) = &o.kind {
        m.kind = MaterialKind::parse(k).unwrap_or(m.kind);
    }
    if let Some(v) = o.kd {
        m.kd = Rgb::from(v);
        m.kd_texture = None;
    }
    if let Some(v) = o.ks {
        m.ks = Rgb::from(v);
        if o.kind.is_none() && m.kind == MaterialKind::Diffuse && m.ks.max_element() > 0.0 {
            m.kind = MaterialKind::Glossy;
        }
    }
    if let Some(v) = o.ns {
        m.ns = v;
    }
    if let Some(v) = o.ke {
        m.ke = Rgb::from(v);
    }
    if let Some(v) = o.tf {
        m.tf = Rgb::from(v);
    }
    if let Some(v) = o.ni {
        m.ni = v;
    }
    m.sanitized()
}

#[allow(clippy::too_many_arguments)]
fn load_obj(
    obj_path: &Path,
    transform: Mat4,
    overrides: Option<&MaterialOverride>,
    triangles: &mut Vec<TriangleGeom>,
    shading: &mut Vec<TriangleShading>,
    materials: &mut Vec<Material>,
    textures: &mut Vec<Texture>,
    texture_ids: &mut HashMap<PathBuf, u32>,
    stats: &mut LoadStats,
) -> Result<()> {
    let text = crate::scene::obj::read_obj_text(obj_path)?;
    let obj_dir = obj_path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let mtl_error: RefCell<Option<Error>> = RefCell::new(None);
    let opts = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ..Default::default()
    };
    let (models, mats) = tobj::load_obj_buf(&mut BufReader::new(text.as_bytes()), &opts, |p| {
        let mtl_path = obj_dir.join(p);
        match crate::scene::obj::read_mtl_text(&mtl_path) {
            Ok(text) => tobj::load_mtl_buf(&mut BufReader::new(text.as_bytes())).map_err(|e| {
                *mtl_error.borrow_mut() = Some(Error::Obj {
                    path: mtl_path.clone(),
                    message: e.to_string(),
                });
                e
            }),
            Err(e) => {
                *mtl_error.borrow_mut() = Some(e);
                Err(tobj::LoadError::OpenFileFailed)
            }
        }
    })
    .map_err(|e| Error::Obj {
        path: obj_path.to_path_buf(),
        message: e.to_string(),
    })?;
    if let Some(e) = mtl_error.into_inner() {
        return Err(e);
    }
    let mats = mats.map_err(|e| Error::Obj {
        path: obj_path.to_path_buf(),
        message: format!("materials: {e}"),
    })?;

    // Materials of this file, appended to the scene's, plus a default for faces without one.
    let base = materials.len() as u32;
    for m in &mats {
        let kd_texture = match &m.diffuse_texture {
            Some(t) if !t.trim().is_empty() => {
                let tp = obj_dir.join(t.trim());
                let id = match texture_ids.get(&tp) {
                    Some(&id) => id,
                    None => {
                        let tex = Texture::load(&tp)?;
                        textures.push(tex);
                        let id = textures.len() as u32 - 1;
                        texture_ids.insert(tp, id);
                        id
                    }
                };
                Some(id)
            }
            _ => None,
        };
        let mut mat = Material::from_mtl(m, kd_texture);
        if mat.kd_texture.is_some() && m.diffuse.is_none() {
            mat.kd = Rgb::ONE;
        }
        materials.push(match overrides {
            Some(o) => apply_override(mat, o),
            None => mat,
        });
    }
    let default_id = materials.len() as u32;
    materials.push(match overrides {
        Some(o) => apply_override(Material::default(), o),
        None => Material::default(),
    });

    let normal_matrix = Mat3::from_mat4(transform).inverse().transpose();
    let flips = Mat3::from_mat4(transform).determinant() < 0.0;
    for model in &models {
        let m = &model.mesh;
        let positions: Vec<Vec3> = m
            .positions
            .chunks_exact(3)
            .map(|p| transform.transform_point3(Vec3::new(p[0], p[1], p[2])))
            .collect();
        let normals: Vec<Vec3> = m
            .normals
            .chunks_exact(3)
            .map(|n| (normal_matrix * Vec3::new(n[0], n[1], n[2])).normalize_or_zero())
            .collect();
        let uvs: Vec<Vec2> = m
            .texcoords
            .chunks_exact(2)
            .map(|t| Vec2::new(t[0], t[1]))
            .collect();
        let material = m.material_id.map(|i| base + i as u32).unwrap_or(default_id);
        for f in m.indices.chunks_exact(3) {
            let (mut i0, i1, mut i2) = (f[0] as usize, f[1] as usize, f[2] as usize);
            if flips {
                std::mem::swap(&mut i0, &mut i2);
            }
            let (Some(&p0), Some(&p1), Some(&p2)) =
                (positions.get(i0), positions.get(i1), positions.get(i2))
            else {
                return Err(Error::Obj {
                    path: obj_path.to_path_buf(),
                    message: "face refers to a vertex that does not exist".into(),
                });
            };
            let geom = TriangleGeom::new(p0, p1, p2);
            if crate::scene::obj::is_degenerate(&geom) {
                stats.degenerate_skipped += 1;
                continue;
            }
            let tri_normals = if normals.len() == positions.len() && !normals.is_empty() {
                let n = [normals[i0], normals[i1], normals[i2]];
                if n.iter().all(|v| v.is_finite() && *v != Vec3::ZERO) {
                    Some(n)
                } else {
                    None
                }
            } else {
                None
            };
            let tri_uvs = if uvs.len() == positions.len() && !uvs.is_empty() {
                Some([uvs[i0], uvs[i1], uvs[i2]])
            } else {
                None
            };
            triangles.push(geom);
            shading.push(TriangleShading {
                normals: tri_normals,
                uvs: tri_uvs,
                material,
                light: None,
            });
        }
    }
    Ok(())
}
