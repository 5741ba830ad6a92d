//! What one path teaches the learned selection probabilities
//! (`footprint::guide::selection`): its first guided vertices, and what came back through
//! each. The same for camera paths (path tracing, the combined image: what their estimate
//! received) and light paths (light tracing: what their camera connections splatted, over
//! every pixel they reached), so that both guided directions learn their `p_BSDF` per
//! region of their own guide cache.
//!
//! A path that splits (guided splitting, `crate::walk`) is followed through its branches:
//! the vertices before the split gather every branch's returns, each branch's own vertices
//! only its own.
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
    /// Records of the vertices of split branches that ended ([`Learning::restore`]).
    done: Vec<SelectionRecord>,
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

    /// Where a split path stands before its branches (the walk's `Visitor::branch`): the
    /// vertices followed so far, which every branch's returns pass through.
    #[inline]
    pub fn branch(&self) -> usize {
        self.len
    }

    /// Before a further branch of a split at `mark`: the vertices the branch before
    /// followed after the split ended with it (their records are kept); the vertices
    /// before the split go on gathering what the next branch brings back. Each branch's
    /// contributions carry its share of the throughput, as its vertices' do.
    pub fn restore(&mut self, mark: usize) {
        if mark < self.len {
            let ended = &self.vertices[mark..self.len];
            self.done
                .extend(ended.iter().filter_map(LearningVertex::record));
            self.len = mark;
        }
    }

    /// The path ended: a record per followed vertex through which light came back, with
    /// `X` = the return per unit throughput at the vertex (split branches' included).
    pub fn finish(&mut self, out: &mut Vec<SelectionRecord>) {
        out.append(&mut self.done);
        out.extend(
            self.vertices[..self.len]
                .iter()
                .filter_map(LearningVertex::record),
        );
    }
}

impl LearningVertex {
    /// The vertex's record, when light came back through it.
    fn record(&self) -> Option<SelectionRecord> {
        let d = self.draw;
        (self.returned > 0.0 && self.beta > 0.0).then(|| {
            let x = self.returned / self.beta;
            SelectionRecord {
                region: d.region,
                x2: x * x,
                pdf_bsdf_w: d.pdf_bsdf_w,
                pdf_guide_w: d.pdf_guide_w,
                pdf_w: self.pdf_w,
            }
        })
    }
}
