//! Writing images: OpenEXR (linear float RGB, one layer per estimate, settings in the
//! header) and a PNG preview. Both are written whole or not at all ([`crate::atomic_file`]),
//! so a failed or interrupted run never truncates a good image.
//!
//! PNG tone map: `srgb(clamp(2^exposure · rgb, 0, 1))`, with the sRGB transfer function
//! (IEC 61966-2-1); exposure 0 by default. No other curve is applied.

use crate::atomic_file::atomic_write;
use crate::error::Result;
use crate::film::Image;
use std::path::Path;

/// Writes an EXR with one RGB layer per `(name, image)` and text attributes in the header.
pub fn write_exr(
    path: &Path,
    layers: &[(&str, &Image)],
    header: &[(String, String)],
) -> Result<()> {
    use exr::meta::attribute::{AttributeValue, Text};
    use exr::prelude::*;
    let Some((_, first)) = layers.first() else {
        return Err(crate::error::Error::Write {
            path: path.to_path_buf(),
            message: "no layers to write".into(),
        });
    };
    let size = Vec2(first.width as usize, first.height as usize);
    fn layer<'a>(
        name: &str,
        img: &'a crate::film::Image,
        size: Vec2<usize>,
    ) -> Layer<
        SpecificChannels<
            impl Sync + Fn(Vec2<usize>) -> (f32, f32, f32) + 'a,
            (ChannelDescription, ChannelDescription, ChannelDescription),
        >,
    > {
        let w = img.width as usize;
        Layer::new(
            size,
            LayerAttributes::named(name),
            Encoding::SMALL_LOSSLESS,
            SpecificChannels::rgb(move |p: Vec2<usize>| {
                let c = img.pixels[p.y() * w + p.x()];
                (c.x, c.y, c.z)
            }),
        )
    }
    let all: Vec<_> = layers.iter().map(|(n, img)| layer(n, img, size)).collect();
    let mut attrs = ImageAttributes::new(IntegerBounds::from_dimensions(size));
    for (k, v) in header {
        attrs.other.insert(
            Text::from(k.as_str()),
            AttributeValue::Text(Text::from(v.as_str())),
        );
    }
    let image = exr::image::Image::from_layers(attrs, all);
    atomic_write(path, |tmp| {
        image.write().to_file(tmp).map_err(|e| e.to_string())
    })
}

/// sRGB transfer function from linear.
#[inline]
pub fn linear_to_srgb(v: f32) -> f32 {
    if v <= 0.0031308 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

/// Writes the tone-mapped PNG preview (see the module doc).
pub fn write_png(path: &Path, img: &Image, exposure: f32) -> Result<()> {
    let scale = exposure.exp2();
    let mut buf = Vec::with_capacity(img.pixels.len() * 3);
    for p in &img.pixels {
        for c in [p.x, p.y, p.z] {
            let v = if c.is_finite() {
                (c * scale).clamp(0.0, 1.0)
            } else {
                0.0
            };
            buf.push((linear_to_srgb(v) * 255.0 + 0.5) as u8);
        }
    }
    atomic_write(path, |tmp| {
        image::save_buffer_with_format(
            tmp,
            &buf,
            img.width,
            img.height,
            image::ExtendedColorType::Rgb8,
            image::ImageFormat::Png,
        )
        .map_err(|e| e.to_string())
    })
}

/// Reads the first RGB(A) layer of an EXR file.
pub fn read_exr(path: &Path) -> Result<Image> {
    use exr::prelude::*;
    let img = read_first_rgba_layer_from_file(
        path,
        |res, _| {
            let w = res.width();
            let h = res.height();
            (w, vec![glam::Vec3::ZERO; w * h])
        },
        |(w, px): &mut (usize, Vec<glam::Vec3>), pos, (r, g, b, _a): (f32, f32, f32, f32)| {
            px[pos.y() * *w + pos.x()] = glam::Vec3::new(r, g, b);
        },
    )
    .map_err(|e| crate::error::Error::Other(format!("{}: {e}", path.display())))?;
    let size = img.layer_data.size;
    let (_, pixels) = img.layer_data.channel_data.pixels;
    Ok(crate::film::Image {
        width: size.width() as u32,
        height: size.height() as u32,
        pixels,
    })
}

/// A text attribute of an EXR's header (as [`write_exr`] writes them), if present.
pub fn read_exr_text_attribute(path: &Path, key: &str) -> Option<String> {
    use exr::meta::attribute::{AttributeValue, Text};
    let meta = exr::meta::MetaData::read_from_file(path, false).ok()?;
    let header = meta.headers.first()?;
    // Written as an image attribute; a single-part file may read it back as a layer attribute.
    let key = Text::from(key);
    let value = header
        .shared_attributes
        .other
        .get(&key)
        .or_else(|| header.own_attributes.other.get(&key))?;
    match value {
        AttributeValue::Text(t) => Some(t.to_string()),
        _ => None,
    }
}

/// The header of an EXR as [`write_exr`] writes it: every layer's name and size, and the
/// text attributes, sorted by key.
pub struct ExrHeader {
    pub layers: Vec<(String, u32, u32)>,
    pub attributes: Vec<(String, String)>,
}

/// The text attributes among `maps`, first occurrence of a key kept, sorted by key.
fn text_attributes<'a>(
    maps: impl Iterator<
        Item = &'a std::collections::HashMap<
            exr::meta::attribute::Text,
            exr::meta::attribute::AttributeValue,
        >,
    >,
) -> Vec<(String, String)> {
    use exr::meta::attribute::AttributeValue;
    let mut out: Vec<(String, String)> = Vec::new();
    for m in maps {
        for (k, v) in m {
            if let AttributeValue::Text(t) = v {
                let k = k.to_string();
                if !out.iter().any(|(a, _)| *a == k) {
                    out.push((k, t.to_string()));
                }
            }
        }
    }
    out.sort();
    out
}

/// Reads the header of an EXR (no pixels): cheap, for checks before reading many files.
pub fn read_exr_header(path: &Path) -> crate::error::Result<ExrHeader> {
    let fail = |m: String| crate::error::Error::Other(format!("{}: {m}", path.display()));
    let meta = exr::meta::MetaData::read_from_file(path, false)
        .map_err(|e| fail(format!("not a readable EXR ({e})")))?;
    let layers = meta
        .headers
        .iter()
        .map(|h| {
            let name = h
                .own_attributes
                .layer_name
                .as_ref()
                .map(|n| n.to_string())
                .unwrap_or_default();
            (
                name,
                h.layer_size.width() as u32,
                h.layer_size.height() as u32,
            )
        })
        .collect();
    let attributes = text_attributes(
        meta.headers
            .iter()
            .flat_map(|h| [&h.shared_attributes.other, &h.own_attributes.other]),
    );
    Ok(ExrHeader { layers, attributes })
}

/// An EXR as [`write_exr`] writes it: every layer's RGB image by name, and the header's text
/// attributes, sorted by key.
pub struct ExrLayers {
    pub layers: Vec<(String, Image)>,
    pub attributes: Vec<(String, String)>,
}

/// Reads every RGB layer and the text attributes of an EXR. A layer without R, G and B
/// channels is an error naming the file.
pub fn read_exr_layers(path: &Path) -> crate::error::Result<ExrLayers> {
    use exr::prelude::*;
    let fail = |m: String| crate::error::Error::Other(format!("{}: {m}", path.display()));
    let img = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .from_file(path)
        .map_err(|e| fail(format!("not a readable EXR ({e})")))?;
    let attributes = text_attributes(
        std::iter::once(&img.attributes.other)
            .chain(img.layer_data.iter().map(|l| &l.attributes.other)),
    );
    let mut layers = Vec::new();
    for layer in &img.layer_data {
        let name = layer
            .attributes
            .layer_name
            .as_ref()
            .map(|n| n.to_string())
            .unwrap_or_default();
        let (w, h) = (layer.size.width(), layer.size.height());
        let channel = |c: &str| -> crate::error::Result<Vec<f32>> {
            layer
                .channel_data
                .list
                .iter()
                .find(|ch| ch.name.to_string() == c)
                .map(|ch| ch.sample_data.values_as_f32().collect())
                .ok_or_else(|| fail(format!("layer '{name}' has no {c} channel")))
        };
        let (r, g, b) = (channel("R")?, channel("G")?, channel("B")?);
        let pixels = (0..w * h)
            .map(|i| glam::Vec3::new(r[i], g[i], b[i]))
            .collect();
        layers.push((
            name,
            crate::film::Image {
                width: w as u32,
                height: h as u32,
                pixels,
            },
        ));
    }
    Ok(ExrLayers { layers, attributes })
}
