//! The `<sensor>` element: the `perspective` camera and the `thinlens` camera (the same with
//! an aperture and a focus distance, `footprint::scene::camera`), with its `hdrfilm` (size and
//! pixel filter) and sampler (samples per pixel).

use super::builder::Builder;
use super::xml::Props;
use crate::error::Result;
use crate::film::filter::{FilterKind, PixelFilter};
use crate::math::Frame;
use crate::scene::camera::Camera;
use glam::{Mat4, Vec3};
use roxmltree::Node;

impl<'a, 'd> Builder<'a, 'd> {
    pub(super) fn sensor(&mut self, node: Node<'a, 'a>) -> Result<()> {
        let kind = self.kind(node)?;
        if self.camera.is_some() {
            return self.doc.unsupported(
                node,
                "a second <sensor>",
                "one sensor",
                "the first sensor",
            );
        }
        let p = Props::new(self.doc, node)?;
        // The lens: Mitsuba's `thinlens` takes `aperture_radius` (required; 0 is made a
        // pinhole, where Mitsuba warns and takes a radius of machine epsilon) and
        // `focus_distance` along the view axis (default `far_clip`, itself 1e4 by default).
        let lens = if kind == "thinlens" {
            let Some(radius) = p.float("aperture_radius")? else {
                return Err(self
                    .doc
                    .err(node, "a thinlens sensor needs 'aperture_radius'"));
            };
            let far_clip = p.float_or("far_clip", 1e4)?;
            let focus = p.float_or("focus_distance", far_clip)?;
            Some((radius, focus))
        } else {
            if kind != "perspective" {
                self.doc.unsupported(
                    node,
                    &format!("sensor '{kind}'"),
                    "perspective, thinlens",
                    "a pinhole camera with the same field of view",
                )?;
                p.ignore(&["aperture_radius"]);
            }
            None
        };
        let m = p.transform("to_world")?.unwrap_or(Mat4::IDENTITY);
        let fov = p.float("fov")?;
        if fov.is_none() && p.get("focal_length").is_some() {
            return Err(self.doc.err(
                node,
                "focal_length is not supported: give the field of view as 'fov' (degrees)",
            ));
        }
        let fov = fov.unwrap_or(90.0);
        if !(fov > 0.0 && fov < 179.0) {
            return Err(self
                .doc
                .err(node, format!("fov must be in (0, 179) degrees, got {fov}")));
        }
        let axis = p.string("fov_axis")?.unwrap_or_else(|| "x".into());
        // A pinhole's focus distance changes nothing; Mitsuba's `perspective` accepts it too.
        // The clipping planes are not modelled (read above for `thinlens`'s default focus).
        p.ignore(&[
            "near_clip",
            "far_clip",
            "shutter_open",
            "shutter_close",
            "focus_distance",
        ]);
        for off in ["principal_point_offset_x", "principal_point_offset_y"] {
            if p.float(off)?.is_some_and(|v| v != 0.0) {
                self.doc
                    .unsupported(node, off, "a centred principal point", "a centred one")?;
            }
        }
        // Film and sampler.
        let (mut width, mut height) = (768u32, 576u32);
        let mut filter = FilterKind::Gaussian { stddev: 0.5 };
        let mut spp = None;
        for c in &p.unnamed {
            let c = self.deref(*c)?;
            match c.tag_name().name() {
                "film" => {
                    let fk = self.kind(c)?;
                    if fk != "hdrfilm" {
                        self.doc.unsupported(
                            c,
                            &format!("film '{fk}'"),
                            "hdrfilm",
                            "an hdrfilm",
                        )?;
                    }
                    let fp = Props::new(self.doc, c)?;
                    let dim = |name: &str, default: u32| -> Result<u32> {
                        match fp.integer(name)? {
                            None => Ok(default),
                            Some(v) if (1..=32768).contains(&v) => Ok(v as u32),
                            Some(v) => Err(self.doc.err(
                                fp.get(name).unwrap_or(c),
                                format!("film {name} must be in 1..=32768, got {v}"),
                            )),
                        }
                    };
                    width = dim("width", width)?;
                    height = dim("height", height)?;
                    for crop in [
                        "crop_offset_x",
                        "crop_offset_y",
                        "crop_width",
                        "crop_height",
                    ] {
                        if fp.integer(crop)?.is_some() {
                            self.doc
                                .unsupported(c, crop, "the full film", "the full film")?;
                        }
                    }
                    fp.ignore(&[
                        "file_format",
                        "pixel_format",
                        "component_format",
                        "banner",
                        "compensate",
                        "sample_border",
                    ]);
                    fp.finish("the film")?;
                    for rf in fp.unnamed.iter().filter(|n| n.has_tag_name("rfilter")) {
                        filter = self.rfilter(*rf)?;
                    }
                }
                "sampler" => {
                    let sp = Props::new(self.doc, c)?;
                    if let Some(n) = sp.integer("sample_count")? {
                        if !(1..=1 << 24).contains(&n) {
                            return Err(self
                                .doc
                                .err(c, format!("sample_count must be in 1..=16777216, got {n}")));
                        }
                        spp = Some(n as u32);
                    }
                    // Every sampler converges to the same image; footprint uses its own.
                    sp.ignore(&["seed", "jitter", "scramble_seed", "pixel_samples"]);
                    sp.finish("the sampler")?;
                }
                other => {
                    self.doc.unsupported(
                        c,
                        &format!("<{other}> in a sensor"),
                        "film, sampler",
                        "nothing",
                    )?;
                }
            }
        }
        p.finish(&format!("sensor '{kind}'"))?;
        if let Some(s) = spp {
            self.settings.spp = s;
        }
        let (w, h) = (width as f32, height as f32);
        let tan_half = (fov.to_radians() * 0.5).tan();
        let tan_half_y = match axis.as_str() {
            "x" => tan_half * h / w,
            "y" => tan_half,
            "diagonal" => tan_half * h / (w * w + h * h).sqrt(),
            "smaller" if w <= h => tan_half * h / w,
            "smaller" => tan_half,
            "larger" if w >= h => tan_half * h / w,
            "larger" => tan_half,
            other => {
                return Err(self.doc.err(
                    node,
                    format!("fov_axis '{other}' (expected x, y, diagonal, smaller or larger)"),
                ));
            }
        };
        let fov_y = 2.0 * tan_half_y.atan().to_degrees();
        // Mitsuba's camera looks along local +z with +y up; its image's x runs along local -x.
        let position = m.transform_point3(Vec3::ZERO);
        // Mitsuba's `thinlens` refuses a scaled to_world (its aperture is in world units).
        let scaled = [Vec3::X, Vec3::Y, Vec3::Z]
            .iter()
            .any(|a| (m.transform_vector3(*a).length() - 1.0).abs() > 1e-3);
        if lens.is_some() && scaled {
            return Err(self.doc.err(
                node,
                "scale factors in a thinlens sensor's to_world are not allowed (as in Mitsuba)",
            ));
        }
        let forward = m.transform_vector3(Vec3::Z).try_normalize();
        let up = m.transform_vector3(Vec3::Y).try_normalize();
        let left = m.transform_vector3(Vec3::X).try_normalize();
        let (Some(forward), Some(up), Some(left)) = (forward, up, left) else {
            return Err(self.doc.err(node, "the sensor's to_world has a zero axis"));
        };
        if forward.dot(up).abs() > 1e-3
            || forward.dot(left).abs() > 1e-3
            || up.dot(left).abs() > 1e-3
        {
            return Err(self.doc.err(
                node,
                "the sensor's to_world is not a rotation (its axes are not perpendicular)",
            ));
        }
        let frame = Frame {
            x: -left,
            y: up,
            z: forward,
        };
        let mut camera = Camera::from_frame(position, frame, fov_y, width, height)
            .and_then(|c| match lens {
                Some((radius, focus)) => c.with_lens(radius, focus),
                None => Ok(c),
            })
            .map_err(|e| self.doc.err(node, e))?;
        camera.filter = PixelFilter::new(filter);
        self.camera = Some(camera);
        Ok(())
    }

    fn rfilter(&self, node: Node<'a, 'a>) -> Result<FilterKind> {
        let kind = self.kind(node)?;
        let p = Props::new(self.doc, node)?;
        let f = match kind.as_str() {
            "box" => FilterKind::Box,
            "tent" => {
                let radius = p.float_or("radius", 1.0)?;
                if !(radius > 0.0 && radius <= 6.0) {
                    return Err(self.doc.err(node, "tent radius must be in (0, 6] pixels"));
                }
                FilterKind::Tent { radius }
            }
            "gaussian" => {
                let stddev = p.float_or("stddev", 0.5)?;
                if !(stddev > 0.0 && stddev <= 1.5) {
                    return Err(self
                        .doc
                        .err(node, "gaussian stddev must be in (0, 1.5] pixels"));
                }
                FilterKind::Gaussian { stddev }
            }
            other => {
                self.doc.unsupported(
                    node,
                    &format!("rfilter '{other}'"),
                    "box, tent, gaussian",
                    "Mitsuba's default gaussian filter",
                )?;
                return Ok(FilterKind::Gaussian { stddev: 0.5 });
            }
        };
        p.finish(&format!("rfilter '{kind}'"))?;
        Ok(f)
    }
}
