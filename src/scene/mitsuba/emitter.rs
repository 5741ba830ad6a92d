//! The `<emitter>` element outside shapes: `point`, `spot` and `constant` (the environment);
//! an `area` emitter belongs to a shape (`shape.rs`).

use super::builder::Builder;
use super::xml::Props;
use crate::Rgb;
use crate::error::Result;
use crate::scene::light::Light;
use glam::{Mat4, Vec3};
use roxmltree::Node;

const EMITTERS: &str = "area (on a shape), point, spot, constant";

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
