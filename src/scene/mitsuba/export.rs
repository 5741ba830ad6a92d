//! Writes a loaded scene as a Mitsuba 3 scene: `scene.xml` plus one OBJ per material in
//! `meshes/` (Mitsuba's OBJ loader ignores `.mtl` files, so meshes are split by material),
//! so that Mitsuba 3 can render footprint's own scenes and the two renderers can be compared
//! on them (`footprint export`).
//!
//! The XML reads its image size, samples, depth and pixel filter from `<default>` parameters
//! (`resx`, `resy`, `spp`, `max_depth`, `rfilter`), so either renderer can change them with
//! `-D`. Materials map one to one except two that Mitsuba 3 lacks, which are written as their
//! nearest Mitsuba counterparts and reported: the normalised Blinn lobe over a diffuse base
//! (as `roughplastic`, Beckmann, `α = sqrt(2 / (n + 2))`, IOR 1.5) and the smoothstep spot
//! profile (as Mitsuba's linear-in-angle `spot`). footprint reads the exported file back with
//! Mitsuba's definitions, so a comparison of the two renderers on it is exact either way.

use crate::Rgb;
use crate::bsdf::bump::NormalSource;
use crate::bsdf::material::{Material, MaterialKind};
use crate::bsdf::microfacet::Microfacet;
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::scene::light::{Light, SpotProfile};
use crate::scene::texture::TextureKind;
use glam::{Vec2, Vec3};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::Path;

fn v3(v: Vec3) -> String {
    format!("{:?}, {:?}, {:?}", v.x, v.y, v.z)
}

/// A position of the scene (relative to [`Scene::origin`]) where its file put it, in f64: at
/// a large origin, f32 would round a camera's look-at target by a visible angle.
fn world(scene: &Scene, p: glam::DVec3) -> String {
    let w = p + scene.origin.as_dvec3();
    format!("{:?}, {:?}, {:?}", w.x, w.y, w.z)
}

fn rgb(name: &str, c: Rgb) -> String {
    format!("<rgb name=\"{name}\" value=\"{}\"/>", v3(c))
}

/// A name usable as an XML id and a file name.
fn slug(s: &str, i: usize) -> String {
    let t: String = s
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    format!("m{i}_{t}")
}

/// What the export approximated, one line each.
pub type ExportNotes = Vec<String>;

/// Writes `scene` (loaded from `source`) into folder `out` as `scene.xml` + `meshes/*.obj`.
pub fn export(scene: &Scene, source: &Path, out: &Path) -> Result<ExportNotes> {
    let werr = |p: &Path, e: std::io::Error| Error::Write {
        path: p.to_path_buf(),
        message: e.to_string(),
    };
    let mesh_dir = out.join("meshes");
    std::fs::create_dir_all(&mesh_dir).map_err(|e| werr(&mesh_dir, e))?;
    let mut notes = Vec::new();
    let cam = &scene.camera;
    let s = &scene.settings;
    let mut x = String::new();
    let _ = writeln!(x, "<scene version=\"3.0.0\">");
    let _ = writeln!(
        x,
        "  <!-- Written by `footprint export` from {}. Mitsuba's OBJ loader ignores .mtl files:\n       one OBJ per material, world space. -->",
        source.display()
    );
    let (filter, filter_param) = match cam.filter.kind {
        crate::film::filter::FilterKind::Box => ("box", String::new()),
        crate::film::filter::FilterKind::Tent { radius } => (
            "tent",
            format!("<float name=\"radius\" value=\"{radius:?}\"/>"),
        ),
        crate::film::filter::FilterKind::Gaussian { stddev } => (
            "gaussian",
            format!("<float name=\"stddev\" value=\"{stddev:?}\"/>"),
        ),
    };
    for (k, v) in [
        ("spp", s.spp.to_string()),
        ("resx", cam.width.to_string()),
        ("resy", cam.height.to_string()),
        ("max_depth", s.max_depth.to_string()),
        ("rfilter", filter.to_string()),
    ] {
        let _ = writeln!(x, "  <default name=\"{k}\" value=\"{v}\"/>");
    }
    let _ = writeln!(
        x,
        "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"$max_depth\"/></integrator>"
    );
    let target = cam.position.as_dvec3() + cam.frame.z.as_dvec3();
    let _ = writeln!(
        x,
        "  <sensor type=\"{}\">",
        if cam.has_lens() {
            "thinlens"
        } else {
            "perspective"
        }
    );
    let _ = writeln!(
        x,
        "    <float name=\"fov\" value=\"{:?}\"/><string name=\"fov_axis\" value=\"y\"/>",
        cam.fov_y_deg
    );
    if cam.has_lens() {
        let _ = writeln!(
            x,
            "    <float name=\"aperture_radius\" value=\"{:?}\"/><float name=\"focus_distance\" value=\"{:?}\"/>",
            cam.lens_radius(),
            cam.focus_distance()
        );
    }
    // Mitsuba's image x runs along -(local x) = up x dir; a mirrored frame cannot be a lookat.
    if cam.frame.z.cross(cam.frame.y).dot(cam.frame.x) < 0.0 {
        return Err(Error::Other(
            "export: the camera frame is mirrored; a lookat cannot express it".into(),
        ));
    }
    let _ = writeln!(
        x,
        "    <transform name=\"to_world\"><lookat origin=\"{}\" target=\"{}\" up=\"{}\"/></transform>",
        world(scene, cam.position.as_dvec3()),
        world(scene, target),
        v3(cam.frame.y)
    );
    let _ = writeln!(
        x,
        "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/></sampler>"
    );
    // The filter's parameter is written only when it is not the default (a -D rfilter of
    // another type must not inherit it).
    let filter_param = match cam.filter.kind {
        crate::film::filter::FilterKind::Tent { radius } if radius != 1.0 => filter_param,
        crate::film::filter::FilterKind::Gaussian { stddev } if stddev != 0.5 => filter_param,
        _ => String::new(),
    };
    let _ = writeln!(
        x,
        "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"$resx\"/><integer name=\"height\" value=\"$resy\"/><rfilter type=\"$rfilter\">{filter_param}</rfilter></film>"
    );
    let _ = writeln!(x, "  </sensor>");

    // Triangles grouped by material, in material order.
    let mut groups: Vec<Vec<usize>> = vec![Vec::new(); scene.materials.len()];
    for (i, sh) in scene.shading.iter().enumerate() {
        groups[sh.material as usize].push(i);
    }
    let mut texture_files: HashMap<u32, String> = HashMap::new();
    for (mi, tris) in groups.iter().enumerate() {
        if tris.is_empty() {
            continue;
        }
        let m = &scene.materials[mi];
        let id = slug(&m.name, mi);
        let bsdf = bsdf_xml(scene, m, &id, &mut notes, &mut texture_files, out)?;
        let _ = writeln!(x, "{bsdf}");
        let smooth = tris.iter().all(|&t| scene.shading[t].normals.is_some());
        let obj = write_obj(scene, tris, smooth);
        let obj_path = mesh_dir.join(format!("{id}.obj"));
        std::fs::write(&obj_path, obj).map_err(|e| werr(&obj_path, e))?;
        let _ = writeln!(x, "  <shape type=\"obj\" id=\"shape_{id}\">");
        let _ = writeln!(
            x,
            "    <string name=\"filename\" value=\"meshes/{id}.obj\"/>"
        );
        if !smooth {
            let _ = writeln!(x, "    <boolean name=\"face_normals\" value=\"true\"/>");
        }
        let _ = writeln!(x, "    <ref id=\"{id}\"/>");
        if m.emits() {
            let _ = writeln!(
                x,
                "    <emitter type=\"area\">{}</emitter>",
                rgb("radiance", m.ke)
            );
        }
        let _ = writeln!(x, "  </shape>");
    }
    for l in &scene.lights {
        match l {
            Light::Area { .. } => {}
            Light::Environment { le, map: None, .. } => {
                let _ = writeln!(
                    x,
                    "  <emitter type=\"constant\">{}</emitter>",
                    rgb("radiance", *le)
                );
            }
            Light::Environment {
                le, map: Some(m), ..
            } => {
                // Mitsuba's `scale` is one number: a coloured `le` goes into the texels.
                let grey = le.x == le.y && le.y == le.z;
                let (scale, tint) = if grey { (le.x, Rgb::ONE) } else { (1.0, *le) };
                let file = "meshes/envmap.exr";
                let path = out.join(file);
                let (w, h) = m.size();
                exr::prelude::write_rgb_file(&path, w, h, |i, j| {
                    let t = m.texel(i, j) * tint;
                    (t.x, t.y, t.z)
                })
                .map_err(|e| Error::Write {
                    path: path.clone(),
                    message: e.to_string(),
                })?;
                let r = m.to_world();
                let _ = writeln!(
                    x,
                    "  <emitter type=\"envmap\"><string name=\"filename\" value=\"{file}\"/><float name=\"scale\" value=\"{scale:?}\"/>\n    <transform name=\"to_world\"><matrix value=\"{} 0 {} 0 {} 0 0 0 0 1\"/></transform>\n  </emitter>",
                    v3(r.row(0)).replace(',', ""),
                    v3(r.row(1)).replace(',', ""),
                    v3(r.row(2)).replace(',', "")
                );
            }
            Light::Directional {
                dir, irradiance, ..
            } => {
                let _ = writeln!(
                    x,
                    "  <emitter type=\"directional\"><vector name=\"direction\" value=\"{}\"/>{}</emitter>",
                    v3(*dir),
                    rgb("irradiance", *irradiance)
                );
            }
            Light::Point {
                position,
                intensity,
            } => {
                let _ = writeln!(
                    x,
                    "  <emitter type=\"point\"><point name=\"position\" value=\"{}\"/>{}</emitter>",
                    world(scene, position.as_dvec3()),
                    rgb("intensity", *intensity)
                );
            }
            Light::Spot {
                position,
                frame,
                intensity,
                cos_inner,
                cos_outer,
                profile,
            } => {
                if *profile == SpotProfile::Smoothstep {
                    notes.push(format!(
                        "spot light at {}: its smoothstep falloff is written as Mitsuba's linear-in-angle falloff over the same cones",
                        world(scene, position.as_dvec3())
                    ));
                }
                let _ = writeln!(
                    x,
                    "  <emitter type=\"spot\">\n    <transform name=\"to_world\"><lookat origin=\"{}\" target=\"{}\" up=\"{}\"/></transform>\n    {}<float name=\"cutoff_angle\" value=\"{:?}\"/><float name=\"beam_width\" value=\"{:?}\"/>\n  </emitter>",
                    world(scene, position.as_dvec3()),
                    world(scene, position.as_dvec3() + frame.z.as_dvec3()),
                    v3(frame.x),
                    rgb("intensity", *intensity),
                    cos_outer.clamp(-1.0, 1.0).acos().to_degrees(),
                    cos_inner.clamp(-1.0, 1.0).acos().to_degrees()
                );
            }
        }
    }
    let _ = writeln!(x, "</scene>");
    let xml_path = out.join("scene.xml");
    std::fs::write(&xml_path, x).map_err(|e| werr(&xml_path, e))?;
    Ok(notes)
}

fn colour_or_texture(
    scene: &Scene,
    name: &str,
    c: Rgb,
    tex: Option<u32>,
    texture_files: &mut HashMap<u32, String>,
    out: &Path,
) -> Result<String> {
    let Some(t) = tex else {
        return Ok(rgb(name, c));
    };
    if c != Rgb::ONE {
        return Err(Error::Other(format!(
            "export: '{name}' is a texture scaled by {c:?}; Mitsuba's bitmap has no scale"
        )));
    }
    let texture = &scene.textures[t as usize];
    let transform = texture.to_uv.map(|a| {
        format!(
            "<transform name=\"to_uv\"><matrix value=\"{:?} {:?} 0 {:?} {:?} {:?} 0 {:?} 0 0 1 0 0 0 0 1\"/></transform>",
            a.matrix2.x_axis.x, a.matrix2.y_axis.x, a.translation.x,
            a.matrix2.x_axis.y, a.matrix2.y_axis.y, a.translation.y
        )
    }).unwrap_or_default();
    Ok(match &texture.kind {
        TextureKind::Checkerboard { color0, color1 } => format!(
            "<texture name=\"{name}\" type=\"checkerboard\">{}{}{transform}</texture>",
            rgb("color0", *color0),
            rgb("color1", *color1)
        ),
        TextureKind::Bitmap {
            width,
            height,
            texels,
        } => {
            let file = texture_files
                .entry(t)
                .or_insert_with(|| format!("meshes/texture{t}.png"))
                .clone();
            let mut img = image::RgbImage::new(*width, *height);
            for (i, p) in img.pixels_mut().enumerate() {
                let [r, g, b, _] = texels[i];
                *p = image::Rgb([r, g, b]);
            }
            let path = out.join(&file);
            img.save(&path).map_err(|e| Error::Write {
                path: path.clone(),
                message: e.to_string(),
            })?;
            let raw = if texture.raw {
                "<boolean name=\"raw\" value=\"true\"/>"
            } else {
                ""
            };
            format!(
                "<texture name=\"{name}\" type=\"bitmap\"><string name=\"filename\" value=\"{file}\"/>{raw}{transform}</texture>"
            )
        }
    })
}

/// A number property `name` of material `m` that may be a texture (whose luminance Mitsuba
/// reads): `value` alone, or the texture where `value` is 1.
fn number_or_texture(
    scene: &Scene,
    m: &Material,
    name: &str,
    value: f32,
    texture: Option<u32>,
    tf: &mut HashMap<u32, String>,
    out: &Path,
) -> Result<String> {
    match texture {
        Some(t) if value == 1.0 => colour_or_texture(scene, name, Rgb::ONE, Some(t), tf, out),
        Some(_) => Err(Error::Other(format!(
            "export: material '{}': a '{name}' texture scaled by {value}; Mitsuba's bitmap has no scale",
            m.name
        ))),
        None => Ok(format!("<float name=\"{name}\" value=\"{value:?}\"/>")),
    }
}

/// The `<bsdf>` element of material `m`, with the id `id`.
fn bsdf_xml(
    scene: &Scene,
    m: &Material,
    id: &str,
    notes: &mut ExportNotes,
    tf: &mut HashMap<u32, String>,
    out: &Path,
) -> Result<String> {
    let body = bsdf_body(scene, m, notes, tf, out)?;
    // The id goes on the outermost BSDF.
    Ok(format!(
        "  {}",
        body.replacen("<bsdf ", &format!("<bsdf id=\"{id}\" "), 1)
    ))
}

/// The `<bsdf>` element of material `m`, without an id: its kind (or its blend), wrapped in
/// its bump map, its `twosided` and its mask.
fn bsdf_body(
    scene: &Scene,
    m: &Material,
    notes: &mut ExportNotes,
    tf: &mut HashMap<u32, String>,
    out: &Path,
) -> Result<String> {
    let inner = match &m.blend {
        Some(b) => {
            // The weight, then bsdf_0 and bsdf_1, each with its own sidedness.
            let first = Material {
                blend: None,
                bump: None,
                opacity: 1.0,
                opacity_texture: None,
                ..m.clone()
            };
            let weight =
                number_or_texture(scene, m, "weight", b.weight, b.weight_texture, tf, out)?;
            format!(
                "<bsdf type=\"blendbsdf\">{weight}{}{}</bsdf>",
                bsdf_body(scene, &first, notes, tf, out)?,
                bsdf_body(scene, &b.other, notes, tf, out)?
            )
        }
        None => match kind_xml(scene, m, notes, tf, out)? {
            Kind::Reflecting(x) => x,
            // Scatters on both sides by itself: never wrapped in `twosided`.
            Kind::Transmitting(x) => return Ok(x),
        },
    };
    // A bump map wraps the BSDF (and the `twosided` nested in it); the material's own
    // `two_sided` wraps the bump map.
    let inner = match &m.bump {
        Some(b) => {
            let nested = if b.nested_two_sided {
                format!("<bsdf type=\"twosided\">{inner}</bsdf>")
            } else {
                inner
            };
            let (plugin, name, scale) = match b.source {
                NormalSource::Height { scale } => (
                    "bumpmap",
                    "map",
                    format!("<float name=\"scale\" value=\"{scale:?}\"/>"),
                ),
                NormalSource::Normals => ("normalmap", "normalmap", String::new()),
            };
            let map = colour_or_texture(scene, name, Rgb::ONE, Some(b.texture), tf, out)?;
            format!(
                "<bsdf type=\"{plugin}\">{map}{scale}<boolean name=\"flip_invalid_normals\" value=\"{}\"/><boolean name=\"use_shadowing_function\" value=\"{}\"/>{nested}</bsdf>",
                b.flip_invalid_normals, b.shadowing
            )
        }
        None => inner,
    };
    let inner = if m.two_sided && m.blend.is_none() {
        format!("<bsdf type=\"twosided\">{inner}</bsdf>")
    } else {
        inner
    };
    // A cut-out wraps everything else, as Mitsuba's `mask` takes its opacity at the surface.
    let inner = if m.is_masked() {
        let opacity =
            number_or_texture(scene, m, "opacity", m.opacity, m.opacity_texture, tf, out)?;
        format!("<bsdf type=\"mask\">{opacity}{inner}</bsdf>")
    } else {
        inner
    };
    Ok(inner)
}

/// A material's own kind as Mitsuba XML.
enum Kind {
    Reflecting(String),
    /// Scatters on both sides by itself.
    Transmitting(String),
}

/// The `<bsdf>` of material `m`'s own kind (no blend, bump map, `twosided` or mask).
fn kind_xml(
    scene: &Scene,
    m: &Material,
    notes: &mut ExportNotes,
    tf: &mut HashMap<u32, String>,
    out: &Path,
) -> Result<Kind> {
    // The microfacet properties when `m` is of the rough kind `k`.
    let rough = |k: MaterialKind| {
        if m.kind != k {
            return String::new();
        }
        let dist = match m.microfacet {
            Microfacet::Beckmann => "beckmann",
            Microfacet::Ggx => "ggx",
        };
        let alpha = match m.alpha_v {
            Some(v) => format!(
                "<float name=\"alpha_u\" value=\"{:?}\"/><float name=\"alpha_v\" value=\"{v:?}\"/>",
                m.alpha
            ),
            None => format!("<float name=\"alpha\" value=\"{:?}\"/>", m.alpha),
        };
        format!("<string name=\"distribution\" value=\"{dist}\"/>{alpha}")
    };
    Ok(Kind::Reflecting(match m.kind {
        MaterialKind::Diffuse => format!(
            "<bsdf type=\"diffuse\">{}</bsdf>",
            colour_or_texture(scene, "reflectance", m.kd, m.kd_texture, tf, out)?
        ),
        MaterialKind::Glossy => {
            let alpha = (2.0 / (m.ns + 2.0)).sqrt();
            notes.push(format!(
                "material '{}': the Blinn lobe (Ns {}) has no Mitsuba counterpart; written as roughplastic (beckmann, alpha {alpha:.4}, IOR 1.5)",
                m.name, m.ns
            ));
            format!(
                "<bsdf type=\"roughplastic\"><string name=\"distribution\" value=\"beckmann\"/><float name=\"alpha\" value=\"{alpha:?}\"/><float name=\"int_ior\" value=\"1.5\"/><float name=\"ext_ior\" value=\"1.0\"/>{}</bsdf>",
                colour_or_texture(scene, "diffuse_reflectance", m.kd, m.kd_texture, tf, out)?
            )
        }
        MaterialKind::Mirror => format!(
            "<bsdf type=\"conductor\"><string name=\"material\" value=\"none\"/>{}</bsdf>",
            colour_or_texture(scene, "specular_reflectance", m.ks, m.ks_texture, tf, out)?
        ),
        MaterialKind::Conductor | MaterialKind::RoughConductor => {
            let rough = rough(MaterialKind::RoughConductor);
            let ior = if m.eta == Rgb::ZERO && m.k == Rgb::ONE {
                "<string name=\"material\" value=\"none\"/>".to_string()
            } else {
                format!("{}{}", rgb("eta", m.eta), rgb("k", m.k))
            };
            format!(
                "<bsdf type=\"{}\">{rough}{ior}{}</bsdf>",
                if rough.is_empty() {
                    "conductor"
                } else {
                    "roughconductor"
                },
                colour_or_texture(scene, "specular_reflectance", m.ks, m.ks_texture, tf, out)?
            )
        }
        MaterialKind::Plastic | MaterialKind::RoughPlastic => {
            let rough = rough(MaterialKind::RoughPlastic);
            format!(
                "<bsdf type=\"{}\">{rough}<float name=\"int_ior\" value=\"{:?}\"/><float name=\"ext_ior\" value=\"1.0\"/><boolean name=\"nonlinear\" value=\"{}\"/>{}{}</bsdf>",
                if rough.is_empty() {
                    "plastic"
                } else {
                    "roughplastic"
                },
                m.ni,
                m.nonlinear,
                colour_or_texture(scene, "diffuse_reflectance", m.kd, m.kd_texture, tf, out)?,
                colour_or_texture(scene, "specular_reflectance", m.ks, m.ks_texture, tf, out)?
            )
        }
        MaterialKind::RoughGlass => {
            return Ok(Kind::Transmitting(format!(
                "<bsdf type=\"roughdielectric\">{}<float name=\"int_ior\" value=\"{:?}\"/><float name=\"ext_ior\" value=\"1.0\"/>{}{}</bsdf>",
                rough(MaterialKind::RoughGlass),
                m.ni,
                colour_or_texture(scene, "specular_reflectance", m.ks, m.ks_texture, tf, out)?,
                rgb("specular_transmittance", m.tf.map(f32::sqrt))
            )));
        }
        MaterialKind::Principled => {
            let pr = &m.principled;
            let mut props = colour_or_texture(scene, "base_color", m.kd, m.kd_texture, tf, out)?;
            for (name, s) in pr.scalars() {
                props += &match s.texture {
                    Some(t) => colour_or_texture(scene, name, Rgb::ONE, Some(t), tf, out)?,
                    None => format!("<float name=\"{name}\" value=\"{:?}\"/>", s.value),
                };
            }
            let r = pr.rates;
            for (name, v) in [
                ("eta", pr.eta),
                ("diffuse_reflectance_sampling_rate", r.diffuse),
                ("main_specular_sampling_rate", r.specular),
                ("clearcoat_sampling_rate", r.clearcoat),
            ] {
                let _ = write!(props, "<float name=\"{name}\" value=\"{v:?}\"/>");
            }
            let xml = format!("<bsdf type=\"principled\">{props}</bsdf>");
            if pr.may_transmit() {
                // Scatters on both sides by itself: never wrapped in `twosided` (Mitsuba
                // refuses a transmitting BSDF there).
                return Ok(Kind::Transmitting(xml));
            }
            xml
        }
        MaterialKind::Glass | MaterialKind::ThinGlass => {
            // footprint's `tf` is per passage through a solid (two interfaces) for glass.
            let st = if m.kind == MaterialKind::Glass {
                Rgb::new(m.tf.x.sqrt(), m.tf.y.sqrt(), m.tf.z.sqrt())
            } else {
                m.tf
            };
            return Ok(Kind::Transmitting(format!(
                "<bsdf type=\"{}\"><float name=\"int_ior\" value=\"{:?}\"/><float name=\"ext_ior\" value=\"1.0\"/>{}</bsdf>",
                if m.kind == MaterialKind::Glass {
                    "dielectric"
                } else {
                    "thindielectric"
                },
                m.ni,
                rgb("specular_transmittance", st)
            )));
        }
    }))
}

/// The triangles `tris` as an OBJ (shared vertices deduplicated exactly).
fn write_obj(scene: &Scene, tris: &[usize], smooth: bool) -> String {
    let mut o = String::new();
    let mut index: HashMap<[u32; 8], usize> = HashMap::new();
    let mut faces = String::new();
    let mut nv = 0usize;
    let has_uv = tris.iter().all(|&t| scene.shading[t].uvs.is_some());
    for &t in tris {
        let g = &scene.triangles[t];
        let sh = &scene.shading[t];
        let ps = [g.p0, g.p0 + g.e1, g.p0 + g.e2];
        let mut f = [0usize; 3];
        for k in 0..3 {
            let n = if smooth {
                sh.normals.unwrap()[k]
            } else {
                Vec3::ZERO
            };
            let uv = if has_uv {
                sh.uvs.unwrap()[k]
            } else {
                Vec2::ZERO
            };
            let key = [
                ps[k].x.to_bits(),
                ps[k].y.to_bits(),
                ps[k].z.to_bits(),
                n.x.to_bits(),
                n.y.to_bits(),
                n.z.to_bits(),
                uv.x.to_bits(),
                uv.y.to_bits(),
            ];
            f[k] = *index.entry(key).or_insert_with(|| {
                nv += 1;
                // Back where the file put it: the vertex was moved by exactly `-origin`.
                let w = ps[k] + scene.origin;
                let _ = writeln!(o, "v {:?} {:?} {:?}", w.x, w.y, w.z);
                if smooth {
                    let _ = writeln!(o, "vn {:?} {:?} {:?}", n.x, n.y, n.z);
                }
                if has_uv {
                    let _ = writeln!(o, "vt {:?} {:?}", uv.x, uv.y);
                }
                nv
            });
        }
        let _ = match (smooth, has_uv) {
            (true, true) => writeln!(
                faces,
                "f {0}/{0}/{0} {1}/{1}/{1} {2}/{2}/{2}",
                f[0], f[1], f[2]
            ),
            (true, false) => writeln!(faces, "f {0}//{0} {1}//{1} {2}//{2}", f[0], f[1], f[2]),
            (false, true) => writeln!(faces, "f {0}/{0} {1}/{1} {2}/{2}", f[0], f[1], f[2]),
            (false, false) => writeln!(faces, "f {} {} {}", f[0], f[1], f[2]),
        };
    }
    o.push_str(&faces);
    o
}
