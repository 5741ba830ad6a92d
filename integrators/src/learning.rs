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
    /// Luminance of the path's contributions found since the vertex scattered: `β X`, what
    /// came back through the vertex (`footprint::guide::selection`, weighed by `β²`).
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
    pub fn scattered(&mut self, s: &DirectionSample) {
        let Some(draw) = s.guided.filter(|_| self.on) else {
            return;
        };
        if self.len < MAX_LEARNING_VERTICES {
            self.vertices[self.len] = LearningVertex {
                draw,
                pdf_w: s.pdf_w,
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
    /// what came back through it (split branches' included).
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
        (self.returned > 0.0).then(|| SelectionRecord {
            region: d.region,
            returned2: self.returned * self.returned,
            pdf_bsdf_w: d.pdf_bsdf_w,
            pdf_guide_w: d.pdf_guide_w,
            pdf_w: self.pdf_w,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn guided(region: u32) -> DirectionSample {
        DirectionSample {
            wi: Vec3::Z,
            pdf_w: 0.75,
            weight: Rgb::splat(1.0),
            rr_weight: Rgb::splat(1.0),
            delta: false,
            guided: Some(GuidedDraw {
                region,
                pdf_bsdf_w: 0.5,
                pdf_guide_w: 1.0,
            }),
        }
    }

    /// Each record holds the square of what came back through its vertex in the path's
    /// estimate (`β X`, not the return per unit throughput `X`): the pixel's variance
    /// weighs a vertex by `β²`. Returns found before a vertex scattered are not its own.
    #[test]
    fn records_what_came_back_through_each_vertex() {
        let mut l = Learning::new(true);
        l.credit(Rgb::splat(5.0)); // before any guided vertex: nobody's
        l.scattered(&guided(3));
        l.credit(Rgb::splat(0.5));
        l.scattered(&guided(4));
        l.credit(Rgb::splat(0.25));
        let mut out = Vec::new();
        l.finish(&mut out);
        assert_eq!(out.len(), 2);
        assert_eq!((out[0].region, out[0].returned2), (3, 0.75 * 0.75));
        assert_eq!((out[1].region, out[1].returned2), (4, 0.25 * 0.25));
        assert_eq!(
            (out[0].pdf_bsdf_w, out[0].pdf_guide_w, out[0].pdf_w),
            (0.5, 1.0, 0.75)
        );
    }

    /// A vertex through which nothing came back teaches nothing (its sums would gain 0),
    /// and a path that does not learn follows nothing.
    #[test]
    fn vertices_without_return_and_paths_that_do_not_learn_make_no_record() {
        let mut l = Learning::new(true);
        l.scattered(&guided(0));
        l.credit(Rgb::splat(1.0));
        l.scattered(&guided(1));
        let mut out = Vec::new();
        l.finish(&mut out);
        assert_eq!(out.len(), 1);
        assert_eq!(out[0].region, 0);
        let mut off = Learning::new(false);
        off.scattered(&guided(0));
        off.credit(Rgb::splat(1.0));
        let mut out = Vec::new();
        off.finish(&mut out);
        assert!(out.is_empty());
    }
}
