//! The `<emitter>` element outside shapes: `point`, `spot`, `directional`, and the
//! environments `constant` and `envmap`; an `area` emitter belongs to a shape (`shape.rs`).

use super::builder::Builder;
use super::xml::Props;
use crate::Rgb;
use crate::error::Result;
use crate::scene::envmap::EnvMap;
use crate::scene::light::Light;
use glam::{Mat3, Mat4, Vec3};
use roxmltree::Node;
use std::sync::Arc;

const EMITTERS: &str = "area (on a shape), point, spot, directional, constant, envmap";

impl<'a, 'd> Builder<'a, 'd> {
    /// An emitter's colour property (`radiance` or `intensity`, default 1), which must not be
    /// negative.
    pub(super) fn emission(&self, p: &Props<'a, 'd>, name: &str) -> Result<Rgb> {
        let c = p.rgb(name)?.unwrap_or(Rgb::ONE);
        if !(c.min_element() >= 0.0) {
            return Err(self.doc.err(
                p.get(name).expect("the property was read"),
                format!("{name} must not be negative"),
            ));
        }
        Ok(c)
    }

    /// [`Builder::emission`] of an emitter of type `kind` that takes no texture for it.
    fn untextured_emission(
        &self,
        node: Node,
        p: &Props<'a, 'd>,
        name: &str,
        kind: &str,
    ) -> Result<Rgb> {
        if p.is_texture(name) {
            return Err(self
                .doc
                .err(node, format!("a textured {kind} {name} is not supported")));
        }
        self.emission(p, name)
    }

    pub(super) fn emitter(&mut self, node: Node<'a, 'a>) -> Result<()> {
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
                let le = self.untextured_emission(node, &p, "radiance", "constant")?;
                p.finish("emitter 'constant'")?;
                self.lights.push(Light::uniform_environment(le));
            }
            "directional" => {
                let irradiance = self.untextured_emission(node, &p, "irradiance", "directional")?;
                let dir = match (p.vec3("direction")?, p.transform("to_world")?) {
                    (Some(_), Some(_)) => {
                        return Err(self.doc.err(
                            node,
                            "directional: give 'direction' or 'to_world', not both",
                        ));
                    }
                    (Some(d), None) => d,
                    (None, m) => m.unwrap_or(Mat4::IDENTITY).transform_vector3(Vec3::Z),
                };
                p.finish("emitter 'directional'")?;
                let light = Light::directional(dir, irradiance).ok_or_else(|| {
                    self.doc
                        .err(node, "directional: the direction is zero or not finite")
                })?;
                self.lights.push(light);
            }
            "envmap" => {
                let file = p
                    .string("filename")?
                    .ok_or_else(|| self.doc.err(node, "envmap needs 'filename'"))?;
                let scale = p.float_or("scale", 1.0)?;
                if !(scale >= 0.0 && scale.is_finite()) {
                    return Err(self.doc.err(
                        p.get("scale").expect("the property was read"),
                        "envmap: scale must be finite and not negative",
                    ));
                }
                let m = p.transform("to_world")?.unwrap_or(Mat4::IDENTITY);
                // Changes how Mitsuba samples the map, not the image.
                p.boolean("mis_compensation")?;
                p.finish("emitter 'envmap'")?;
                let path = self.doc.file(&file);
                let map = EnvMap::load(&path, Mat3::from_mat4(m)).map_err(|e| {
                    self.doc
                        .err(node, format!("envmap '{}': {e}", path.display()))
                })?;
                self.lights.push(Light::Environment {
                    le: Rgb::splat(scale),
                    map: Some(Arc::new(map)),
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
