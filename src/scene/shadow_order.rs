//! The order in which a shadow ray visits a CWBVH node's inner children.
//!
//! A closest-hit query visits children near to far (by the distance at which the ray
//! enters their boxes, [`crate::scene::cwbvh_walk`]), so that the closest hit found early
//! culls what lies behind it. A shadow ray stops at the first hit anywhere on its segment,
//! and any order finds the same answer; only the work differs. Two orders are kept:
//!
//! * [`ShadowOrder::NearFirst`], the closest-hit order: it bets that the blocker lies near
//!   the ray's origin (the wall between a room's points and a light behind it).
//! * [`ShadowOrder::FarReaching`]: the child whose box the segment leaves last first. A
//!   shadow ray starts on a surface, inside every box that holds its origin, and those
//!   all tie on entry; the one the segment runs through longest is the likeliest to hold
//!   its blocker. It wins where the segments are long and pass through clutter: light
//!   tracing's connections to the camera.
//!
//! A node's leaves are tested before its inner children in both. Which order a scene's
//! shadow rays take is chosen per kind of shadow ray ([`Toward`]) when the scene is built,
//! from probe rays (`Bvh::choose_shadow_order`).

/// The order in which a shadow ray visits a node's inner children.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadowOrder {
    /// By the distance at which the ray enters each child's box, nearest first (the
    /// closest-hit order).
    NearFirst,
    /// By the distance at which the ray leaves each child's box, farthest first.
    FarReaching,
}

impl ShadowOrder {
    /// Both orders, in the order the probes report them.
    pub const ALL: [ShadowOrder; 2] = [ShadowOrder::NearFirst, ShadowOrder::FarReaching];

    /// How the order reads in a report.
    pub fn describe(self) -> &'static str {
        match self {
            ShadowOrder::NearFirst => "near first",
            ShadowOrder::FarReaching => "far-reaching first",
        }
    }
}

/// Where a shadow ray ends: the two kinds of shadow rays are blocked in different places (a
/// light inside a lamp's shade is hidden near the light; the camera stands in the open), so
/// each kind has its own [`ShadowOrder`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Toward {
    /// Next-event estimation: from a surface to a point on a light.
    Light,
    /// A connection to the camera's lens (light tracing, the importance map's particles).
    Camera,
}

impl Toward {
    /// How the kind reads in a report.
    pub fn describe(self) -> &'static str {
        match self {
            Toward::Light => "a light",
            Toward::Camera => "the camera",
        }
    }
}
