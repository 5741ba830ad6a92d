//! The `principled` `<bsdf>`: every parameter Mitsuba 3.9's `principled.cpp` reads, with
//! its defaults and its adjustments, into a principled material
//! ([`crate::bsdf::principled`]).

use super::builder::Builder;
use super::xml::Props;
use crate::Rgb;
use crate::bsdf::material::{Material, MaterialKind};
use crate::bsdf::principled::{PrincipledParams, SamplingRates, Scalar};
use crate::error::Result;
use roxmltree::Node;

impl<'a, 'd> Builder<'a, 'd> {
    /// A parameter of `principled` in [0, 1] that may be a texture (Mitsuba's
    /// `get_texture`): a `<float>` or a `<texture>` (whose luminance is the value). A
    /// textured parameter keeps `default` for where textures are not looked up.
    fn unit_scalar(&mut self, p: &Props<'a, 'd>, name: &str, default: f32) -> Result<Scalar> {
        if let Some(texture) = self.property_texture(p, name, "a <float>")? {
            return Ok(Scalar {
                value: default,
                texture,
            });
        }
        let Some(value) = p.float(name)? else {
            return Ok(Scalar::constant(default));
        };
        if !(0.0..=1.0).contains(&value) {
            return Err(self.doc.err(
                p.get(name).unwrap(),
                format!("principled '{name}' must lie in [0, 1], got {value}"),
            ));
        }
        Ok(Scalar::constant(value))
    }

    /// A constant that is not a texture in Mitsuba (`props.get<float>`).
    fn principled_float(&self, p: &Props<'a, 'd>, name: &str) -> Result<Option<f32>> {
        if p.is_texture(name) {
            return Err(self.doc.err(
                p.get(name).unwrap(),
                format!("principled '{name}' must be a <float> (Mitsuba reads no texture here)"),
            ));
        }
        p.float(name)
    }

    /// Fills `m` from a `principled` element `node` with properties `p`.
    pub(super) fn principled(
        &mut self,
        p: &Props<'a, 'd>,
        node: Node<'a, 'a>,
        m: &mut Material,
    ) -> Result<()> {
        m.kind = MaterialKind::Principled;
        (m.kd, m.kd_texture) = self.color_or_texture(p, "base_color", Rgb::splat(0.5))?;
        if m.kd_texture.is_none() && !(m.kd.min_element() >= 0.0 && m.kd.max_element() <= 1.0) {
            return Err(self.doc.err(
                p.get("base_color").unwrap_or(node),
                format!("principled 'base_color' must lie in [0, 1], got {}", m.kd),
            ));
        }
        let d = PrincipledParams::default();
        let mut params = PrincipledParams {
            roughness: self.unit_scalar(p, "roughness", d.roughness.value)?,
            anisotropic: self.unit_scalar(p, "anisotropic", 0.0)?,
            metallic: self.unit_scalar(p, "metallic", 0.0)?,
            spec_trans: self.unit_scalar(p, "spec_trans", 0.0)?,
            spec_tint: self.unit_scalar(p, "spec_tint", 0.0)?,
            sheen: self.unit_scalar(p, "sheen", 0.0)?,
            sheen_tint: self.unit_scalar(p, "sheen_tint", 0.0)?,
            flatness: self.unit_scalar(p, "flatness", 0.0)?,
            clearcoat: self.unit_scalar(p, "clearcoat", 0.0)?,
            clearcoat_gloss: self.unit_scalar(p, "clearcoat_gloss", 0.0)?,
            ..d
        };
        let rate = |name: &str| -> Result<f32> {
            let r = self.principled_float(p, name)?.unwrap_or(1.0);
            if r < 0.0 {
                return Err(self.doc.err(
                    p.get(name).unwrap(),
                    format!("principled '{name}' must not be negative, got {r}"),
                ));
            }
            Ok(r)
        };
        params.rates = SamplingRates {
            diffuse: rate("diffuse_reflectance_sampling_rate")?,
            specular: rate("main_specular_sampling_rate")?,
            clearcoat: rate("clearcoat_sampling_rate")?,
        };
        let transmits = params.may_transmit();
        params.eta = match (
            self.principled_float(p, "eta")?,
            self.principled_float(p, "specular")?,
        ) {
            (Some(_), Some(_)) => {
                return Err(self
                    .doc
                    .err(node, "principled takes 'eta' or 'specular', not both"));
            }
            (Some(eta), None) => {
                if eta <= 0.0 {
                    return Err(self.doc.err(
                        p.get("eta").unwrap(),
                        format!("principled 'eta' must be positive, got {eta}"),
                    ));
                }
                // An index-matched interface cannot transmit: Mitsuba takes 1.001.
                if transmits && eta == 1.0 { 1.001 } else { eta }
            }
            (None, specular) => {
                let s = specular.unwrap_or(0.5);
                if !(0.0..=1.0).contains(&s) {
                    return Err(self.doc.err(
                        p.get("specular").unwrap(),
                        format!("principled 'specular' must lie in [0, 1], got {s}"),
                    ));
                }
                // Nor can specular 0 (η = 1): Mitsuba takes 1e-3.
                let s = if transmits && s == 0.0 { 1e-3 } else { s };
                PrincipledParams::eta_of_specular(s)
            }
        };
        m.ni = params.eta;
        m.principled = params;
        Ok(())
    }
}
