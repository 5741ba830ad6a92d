//! The `<integrator>` element: the method (`path` and `volpath` as footprint's path tracer,
//! `ptracer` as its light tracer) and the path depth. On surfaces Mitsuba's `volpath` is its
//! `path` that passes cut-outs (`mask`) and thin sheets without a vertex, with next-event
//! estimation through them, as footprint's walks and connections do for cut-outs; scenes
//! with masks are checked against it (`path` weighs light seen through a cut-out by MIS
//! against a light sample the cut-out blocks, and loses part of it).

use super::builder::Builder;
use super::xml::Props;
use crate::error::Result;
use crate::settings::Named;
use roxmltree::Node;

impl<'a, 'd> Builder<'a, 'd> {
    /// A method name given by `node`, with its place for error messages.
    fn named(&self, node: Node, name: &str) -> Named {
        let (line, column) = self.doc.pos(node);
        Named {
            name: name.into(),
            at: format!("{}:{line}:{column}", self.doc.path.display()),
        }
    }

    pub(super) fn integrator(&mut self, node: Node<'a, 'a>) -> Result<()> {
        let kind = self.kind(node)?;
        let p = Props::new(self.doc, node)?;
        match kind.as_str() {
            "path" | "volpath" | "ptracer" => {
                self.settings.integrator =
                    Some(self.named(node, if kind == "ptracer" { "lt" } else { "pt" }));
            }
            other => {
                self.doc.unsupported(
                    node,
                    &format!("integrator '{other}'"),
                    "path, volpath, ptracer",
                    "footprint's path tracer",
                )?;
                self.settings.integrator = Some(self.named(node, "pt"));
                return Ok(());
            }
        }
        if let Some(d) = p.integer("rr_depth")? {
            self.settings.rr_depth = match d {
                1..=1024 => d as u32,
                _ => {
                    return Err(self.doc.err(
                        p.get("rr_depth").unwrap_or(node),
                        format!("rr_depth must be in 1..=1024, got {d}"),
                    ));
                }
            };
        }
        if let Some(d) = p.integer("max_depth")? {
            self.settings.max_depth = match d {
                -1 => 1024,
                1..=1024 => d as u32,
                _ => {
                    return Err(self.doc.err(
                        p.get("max_depth").unwrap_or(node),
                        format!("max_depth must be -1 (unlimited) or in 1..=1024, got {d}"),
                    ));
                }
            };
        }
        if p.boolean("hide_emitters")? == Some(true) {
            self.doc.unsupported(
                node,
                "hide_emitters = true",
                "hide_emitters = false",
                "visible emitters",
            )?;
        }
        // Russian roulette changes the noise, not the expected image.
        p.ignore(&["rr_depth", "samples_per_pass", "timeout"]);
        p.finish(&format!("integrator '{kind}'"))
    }
}
