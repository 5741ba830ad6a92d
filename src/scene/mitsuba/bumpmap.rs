//! The `bumpmap` BSDF: one nested texture (the height field, under any name) and one nested
//! BSDF, as Mitsuba 3's adapter takes them (`src/bsdfs/bumpmap.cpp`), with `scale`,
//! `flip_invalid_normals` and `use_shadowing_function`. The material is the nested BSDF's
//! with a [`BumpMap`] ([`crate::bsdf::bump`]).
//!
//! An `id` on the nested BSDF names the nested BSDF alone: a `<ref>` to it gets the BSDF
//! without the bump map, as in Mitsuba 3 (its scene loader resolves the reference to the
//! nested object).

use super::builder::Builder;
use super::xml::Props;
use crate::bsdf::bump::BumpMap;
use crate::bsdf::material::{Material, MaterialKind};
use crate::error::Result;
use roxmltree::Node;

impl<'a, 'd> Builder<'a, 'd> {
    /// The material of a `<bsdf type="bumpmap">` element whose properties are `p`.
    pub(super) fn bumpmap(&mut self, node: Node<'a, 'a>, p: &Props<'a, 'd>) -> Result<Material> {
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
                        format!("a bumpmap holds one <texture> and one <bsdf>, not <{other}>"),
                    ));
                }
            }
        }
        let nested = match bsdfs.as_slice() {
            [b] => *b,
            [] => return Err(self.doc.err(node, "bumpmap needs a nested <bsdf>")),
            [_, second, ..] => {
                return Err(self
                    .doc
                    .err(*second, "bumpmap takes one nested <bsdf>, this is a second"));
            }
        };
        let height = match textures.as_slice() {
            [t] => *t,
            [] => {
                return Err(self
                    .doc
                    .err(node, "bumpmap needs a nested <texture> (the height field)"));
            }
            [_, second, ..] => {
                return Err(self.doc.err(
                    *second,
                    "bumpmap takes one nested <texture>, this is a second",
                ));
            }
        };
        let kind = self.kind(height)?;
        if kind != "bitmap" {
            return Err(self.doc.err(
                height,
                format!("a bumpmap's height field must be a 'bitmap' texture: Mitsuba's '{kind}' has no gradient"),
            ));
        }
        let scale = p.float_or("scale", 1.0)?;
        let flip_invalid_normals = p.boolean("flip_invalid_normals")?.unwrap_or(true);
        let shadowing = p.boolean("use_shadowing_function")?.unwrap_or(true);
        let mut m = self.bsdf(nested)?;
        let transmits = matches!(m.kind, MaterialKind::Glass | MaterialKind::ThinGlass);
        if transmits || m.bump.is_some() {
            let what = if transmits {
                "a bump-mapped dielectric"
            } else {
                "a bumpmap inside a bumpmap"
            };
            self.doc.unsupported(
                nested,
                what,
                "bumpmap around a reflecting BSDF",
                "the nested BSDF without this bump map",
            )?;
            return Ok(m);
        }
        let Some(texture) = self.texture(height)? else {
            return Ok(m);
        };
        m.bump = Some(BumpMap {
            texture,
            scale,
            flip_invalid_normals,
            shadowing,
            nested_two_sided: m.two_sided,
        });
        m.two_sided = false;
        Ok(m)
    }
}
