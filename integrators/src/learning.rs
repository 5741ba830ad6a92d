//! What one path teaches the learned selection probabilities
//! (`footprint::guide::selection`): its first guided vertices, and what came back through
//! each. The same for camera paths (path tracing, the combined image: what their estimate
//! received) and light paths (light tracing: what their camera connections splatted, over
//! every pixel they reached), so that both guided directions learn their `p_BSDF` per
//! region of their own guide cache.
//!
//! A light path's return through a vertex is the sum of its later splats' luminances; its
//! square counts the products of splats to different pixels, which the per-pixel error
//! does not hold. It is the same objective for a path that reaches one pixel, and an upper
//! bound (the sum's square over the sum of squares) otherwise.

use crate::walk::Vertex;
use footprint::Rgb;
use footprint::guide::sampler::{DirectionSample, GuidedDraw};
use footprint::guide::selection::SelectionRecord;
use footprint::math::luminance;

/// Guided vertices of one path followed for the learned selection probabilities
/// (`footprint::guide::selection`): what the path brings back through each.
#[derive(Default)]
pub struct Learning {
    /// Whether the path's sampler learns (else nothing is followed).
    pub on: bool,
    vertices: [LearningVertex; MAX_LEARNING_VERTICES],
    len: usize,
}

/// The first guided vertices of a path that teach (deeper ones carry little).
const MAX_LEARNING_VERTICES: usize = 8;

#[derive(Clone, Copy, Default)]
struct LearningVertex {
    draw: GuidedDraw,
    pdf_w: f32,
    /// Luminance of the throughput arriving at the vertex.
    beta: f32,
    /// Luminance of the path's contributions found since the vertex scattered.
    returned: f32,
}

impl Learning {
    /// Follows a path's guided vertices when `on`.
    pub fn new(on: bool) -> Self {
        Learning {
            on,
            ..Learning::default()
        }
    }

    /// A guided vertex scattered.
    #[inline]
    pub fn scattered(&mut self, v: &Vertex, s: &DirectionSample) {
        let Some(draw) = s.guided.filter(|_| self.on) else {
            return;
        };
        if self.len < MAX_LEARNING_VERTICES {
            self.vertices[self.len] = LearningVertex {
                draw,
                pdf_w: s.pdf_w,
                beta: luminance(v.beta),
                returned: 0.0,
            };
            self.len += 1;
        }
    }

    /// The path's estimate received `c`. Every vertex followed so far scattered before it
    /// (a vertex's own connection, next-event estimate or camera connection, comes before
    /// its scattering), so `c` came back through each of them.
    #[inline]
    pub fn credit(&mut self, c: Rgb) {
        if self.len > 0 {
            let l = luminance(c);
            for v in &mut self.vertices[..self.len] {
                v.returned += l;
            }
        }
    }

    /// The path ended: a record per followed vertex through which light came back, with
    /// `X` = the return per unit throughput at the vertex.
    pub fn finish(&self, out: &mut Vec<SelectionRecord>) {
        for v in &self.vertices[..self.len] {
            let d = v.draw;
            if v.returned > 0.0 && v.beta > 0.0 {
                let x = v.returned / v.beta;
                out.push(SelectionRecord {
                    region: d.region,
                    x2: x * x,
                    pdf_bsdf_w: d.pdf_bsdf_w,
                    pdf_guide_w: d.pdf_guide_w,
                    pdf_w: v.pdf_w,
                });
            }
        }
    }
}
