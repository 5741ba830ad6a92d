//! The `<texture>` element (`bitmap`, `checkerboard`) and colour properties that may be
//! textures.

use super::builder::Builder;
use super::xml::Props;
use crate::Rgb;
use crate::error::Result;
use crate::scene::texture::Texture;
use glam::{Affine2, Vec2};
use roxmltree::Node;

const TEXTURES: &str = "bitmap, checkerboard";

impl<'a, 'd> Builder<'a, 'd> {
    /// The texture of property `name` when it is one (a `<texture>` or a `<ref>` to one):
    /// `Some` of its index (`None` inside with `--lenient` for an unsupported type); an error
    /// saying the property must be `kinds` when it refers to anything else.
    pub(super) fn property_texture(
        &mut self,
        p: &Props<'a, 'd>,
        name: &str,
        kinds: &str,
    ) -> Result<Option<Option<u32>>> {
        if !p.is_texture(name) {
            return Ok(None);
        }
        let n = p.get(name).unwrap();
        let t = self.deref(n)?;
        if t.tag_name().name() != "texture" {
            return Err(self
                .doc
                .err(n, format!("'{name}' must be {kinds} or a <texture>")));
        }
        self.texture(t).map(Some)
    }

    /// A colour property that may be a texture: the constant factor and the texture index.
    pub(super) fn color_or_texture(
        &mut self,
        p: &Props<'a, 'd>,
        name: &str,
        default: Rgb,
    ) -> Result<(Rgb, Option<u32>)> {
        if let Some(id) = self.property_texture(p, name, "a colour")? {
            return Ok((Rgb::ONE, id));
        }
        Ok(match p.rgb(name)? {
            Some(c) => (c, None),
            None => {
                if let Some(n) = p.get(name) {
                    return Err(self.doc.err(
                        n,
                        format!("'{name}' must be an <rgb>, <spectrum>, <float> or <texture>"),
                    ));
                }
                (default, None)
            }
        })
    }

    /// Builds a `<texture>` once; `None` with `--lenient` when its type is unsupported (the
    /// colour factor then stands alone).
    pub(super) fn texture(&mut self, node: Node<'a, 'a>) -> Result<Option<u32>> {
        if let Some(&i) = self.texture_of.get(&node.id()) {
            return Ok(Some(i));
        }
        let kind = self.kind(node)?;
        let p = Props::new(self.doc, node)?;
        let mut tex = match kind.as_str() {
            "bitmap" => {
                let file = p
                    .string("filename")?
                    .ok_or_else(|| self.doc.err(node, "bitmap needs 'filename'"))?;
                let ft = p
                    .string("filter_type")?
                    .unwrap_or_else(|| "bilinear".into());
                if ft != "bilinear" {
                    self.doc.unsupported(
                        node,
                        &format!("filter_type '{ft}'"),
                        "bilinear",
                        "bilinear filtering",
                    )?;
                }
                let wrap = p.string("wrap_mode")?.unwrap_or_else(|| "repeat".into());
                if wrap != "repeat" {
                    self.doc.unsupported(
                        node,
                        &format!("wrap_mode '{wrap}'"),
                        "repeat",
                        "repeat",
                    )?;
                }
                let raw = p.boolean("raw")?.unwrap_or(false);
                let mut tex = self.files.texture(&self.doc.file(&file))?;
                tex.raw = raw;
                tex
            }
            "checkerboard" => {
                let c0 = p.rgb("color0")?.unwrap_or(Rgb::splat(0.4));
                let c1 = p.rgb("color1")?.unwrap_or(Rgb::splat(0.2));
                if p.is_texture("color0") || p.is_texture("color1") {
                    return Err(self.doc.err(node, "checkerboard colours must be constant"));
                }
                Texture::checkerboard(c0, c1)
            }
            other => {
                self.doc.unsupported(
                    node,
                    &format!("texture '{other}'"),
                    TEXTURES,
                    "no texture (the colour factor alone)",
                )?;
                return Ok(None);
            }
        };
        if self.doc.legacy {
            // Mitsuba 0.x's `uoffset`, `voffset`, `uscale`, `vscale`, which Mitsuba 3 turns
            // into `to_uv` = scale · translate as it loads such a file.
            let o = Vec2::new(p.float_or("uoffset", 0.0)?, p.float_or("voffset", 0.0)?);
            let s = Vec2::new(p.float_or("uscale", 1.0)?, p.float_or("vscale", 1.0)?);
            if o != Vec2::ZERO || s != Vec2::ONE {
                tex.to_uv = Some(Affine2::from_scale(s) * Affine2::from_translation(o));
            }
        }
        if let Some(m) = p.transform("to_uv")? {
            // The 2-D affine part: rows and columns x, y and translation.
            let c = m.to_cols_array_2d();
            tex.to_uv = Some(Affine2::from_cols_array(&[
                c[0][0], c[0][1], c[1][0], c[1][1], c[3][0], c[3][1],
            ]));
        }
        p.finish(&format!("texture '{kind}'"))?;
        self.textures.push(tex);
        let i = self.textures.len() as u32 - 1;
        self.texture_of.insert(node.id(), i);
        Ok(Some(i))
    }
}
