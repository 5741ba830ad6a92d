//! The `bumpmap` and `normalmap` BSDFs: one nested texture (the height field or the normal
//! map, under any name; Mitsuba's `normalmap` names it `normalmap`) and one nested BSDF, as
//! Mitsuba 3's adapters take them (`src/bsdfs/bumpmap.cpp`, `src/bsdfs/normalmap.cpp`), with
//! `flip_invalid_normals` and `use_shadowing_function`, and a bump map's `scale`. The
//! material is the nested BSDF's with a [`BumpMap`] ([`crate::bsdf::bump`]).
//!
//! An `id` on the nested BSDF names the nested BSDF alone: a `<ref>` to it gets the BSDF
//! without the bump map, as in Mitsuba 3 (its scene loader resolves the reference to the
//! nested object).

use super::builder::Builder;
use super::xml::Props;
use crate::bsdf::bump::{BumpMap, NormalSource};
use crate::bsdf::material::{Material, MaterialKind};
use crate::error::Result;
use roxmltree::Node;

impl<'a, 'd> Builder<'a, 'd> {
    /// The material of a `<bsdf type="bumpmap">` element whose properties are `p`, or of a
    /// `<bsdf type="normalmap">` with `normals`.
    pub(super) fn bumpmap(
        &mut self,
        node: Node<'a, 'a>,
        p: &Props<'a, 'd>,
        normals: bool,
    ) -> Result<Material> {
        let (plugin, what) = if normals {
            ("normalmap", "the normal map")
        } else {
            ("bumpmap", "the height field")
        };
        let mut bsdfs = Vec::new();
        let mut textures = p.named_textures();
        for n in &p.unnamed {
            let target = self.deref(*n)?;
            match target.tag_name().name() {
                "bsdf" => bsdfs.push(target),
                "texture" => textures.push(target),
                other => {
                    return Err(self.doc.err(
                        *n,
                        format!("a {plugin} holds one <texture> and one <bsdf>, not <{other}>"),
                    ));
                }
            }
        }
        let nested = match bsdfs.as_slice() {
            [b] => *b,
            [] => {
                return Err(self
                    .doc
                    .err(node, format!("{plugin} needs a nested <bsdf>")));
            }
            [_, second, ..] => {
                return Err(self.doc.err(
                    *second,
                    format!("{plugin} takes one nested <bsdf>, this is a second"),
                ));
            }
        };
        let height = match textures.as_slice() {
            [t] => *t,
            [] => {
                return Err(self
                    .doc
                    .err(node, format!("{plugin} needs a nested <texture> ({what})")));
            }
            [_, second, ..] => {
                return Err(self.doc.err(
                    *second,
                    format!("{plugin} takes one nested <texture>, this is a second"),
                ));
            }
        };
        let kind = self.kind(height)?;
        if kind != "bitmap" {
            let why = if normals {
                "footprint reads normal maps from images".to_string()
            } else {
                format!("Mitsuba's '{kind}' has no gradient")
            };
            return Err(self.doc.err(
                height,
                format!("a {plugin}'s texture must be a 'bitmap' texture, not '{kind}': {why}"),
            ));
        }
        let source = if normals {
            NormalSource::Normals
        } else {
            NormalSource::Height {
                scale: p.float_or("scale", 1.0)?,
            }
        };
        let flip_invalid_normals = p.boolean("flip_invalid_normals")?.unwrap_or(true);
        let shadowing = p.boolean("use_shadowing_function")?.unwrap_or(true);
        let mut m = self.bsdf(nested)?;
        let transmits = matches!(m.kind, MaterialKind::Glass | MaterialKind::ThinGlass);
        let principled = m.kind == MaterialKind::Principled;
        let principled_transmits = principled && m.principled.may_transmit();
        // The bumped frame has no tangent of its own here: an anisotropic lobe would lose
        // its orientation.
        let principled_anisotropic = principled && m.principled.may_be_anisotropic();
        if transmits || principled_transmits || principled_anisotropic || m.bump.is_some() {
            let what = if transmits {
                format!("a dielectric inside a {plugin}")
            } else if principled_transmits {
                format!("a principled BSDF with 'spec_trans' inside a {plugin}")
            } else if principled_anisotropic {
                format!("an anisotropic principled BSDF inside a {plugin}")
            } else {
                format!("a {plugin} inside a bumpmap or normalmap")
            };
            self.doc.unsupported(
                nested,
                &what,
                &format!("{plugin} around a reflecting BSDF"),
                &format!("the nested BSDF without this {plugin}"),
            )?;
            return Ok(m);
        }
        // The lobes are evaluated in a frame about the tilted normal whose tangent does not
        // follow ∂p/∂u, which an anisotropic roughness would need.
        if m.is_anisotropic() {
            let alpha = (m.alpha * m.alpha_v.unwrap_or(m.alpha)).sqrt();
            self.doc.unsupported(
                nested,
                &format!("anisotropic roughness inside a {plugin}"),
                "isotropic roughness",
                &format!("isotropic alpha = sqrt(alpha_u alpha_v) = {alpha}"),
            )?;
            (m.alpha, m.alpha_v) = (alpha, None);
        }
        let Some(texture) = self.texture(height)? else {
            return Ok(m);
        };
        m.bump = Some(BumpMap {
            texture,
            source,
            flip_invalid_normals,
            shadowing,
            nested_two_sided: m.two_sided,
        });
        m.two_sided = false;
        Ok(m)
    }
}
