//! `footprint compare`: every method on one scene at equal wall-clock time (the passes that
//! build the particle maps included), against a reference, with the error measured at a
//! ladder of times; written as a table (CSV and JSON), a log-log convergence plot (SVG) and
//! a self-contained HTML page. The shape follows SmallVCM's equal-time report and pbrt-v4's
//! `--mse-reference-image`.
//!
//! Metrics against the reference `R` (per pixel and channel, image `X`):
//! * relative MSE: mean of `(X - R)² / (R² + 0.01)`, both images first divided by the
//!   reference's mean so that the `0.01` means the same in dark and bright scenes;
//! * mean absolute error: mean of `|X - R|`;
//! * spots (the paper's word, fireflies): pixels whose luminance error exceeds
//!   [`SPOT_FACTOR`] times the reference luminance plus 1% of the reference's mean.

mod html;
mod metrics;
mod reference;
mod report;
mod rows;
mod run;
mod svg;

pub use metrics::*;
pub use reference::{reference, reference_key};
pub use rows::{CompareSettings, MethodSummary, Row, Variant, slope_points};
pub use run::run;
pub use svg::convergence_svg;
