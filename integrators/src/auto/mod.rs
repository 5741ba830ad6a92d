//! `auto`: the renderer chooses the method. A short **pilot** renders a few independent
//! passes of the combined image, which carries the path tracer's, the light tracer's and the
//! combined estimate of the same paths as three layers, and measures per pixel what each
//! direction contributes: its mean and its variance per pass. With the time one pass of each
//! method costs, that predicts each candidate's relative MSE (`compare`'s metric) at the time
//! left, and the rest of the budget goes to the candidate predicted best (docs/auto.md;
//! how well it chooses: docs/measurements/auto.md).
//!
//! * **Prediction.** For candidate `m` with per-pass variance `σ²_m` per pixel and channel, a
//!   pass time `t_m` and the time left `T`: `E_m = mean[(σ²_m t_m / T + b²_m) / (R² + 0.01)]`,
//!   everything divided by `R`'s mean luminance as `compare` does. `R` is a combined mean
//!   over a window around the pixel, the smallest whose standard error is at most 20% of it
//!   ([`crate::window`]): a pixel's own pilot mean is heavy-tailed and usually
//!   low where rare bright paths carry the light, and `1 / (R² + 0.01)` of a low `R`
//!   overweights exactly the pixels guiding helps (on door a 3x3 window predicts
//!   `lt-footprint` at several times its error). `R` pools every pilot's combined image,
//!   each pilot weighed by the inverse of its variance ([`Pooled`]), but a pilot's passes
//!   are dealt to [`FOLDS`] folds and each fold's squared deviations are weighed with `R`
//!   without that fold's passes (cross-fitting: a bright sample must not raise the `R` that
//!   weighs it), read over a window sized by the noise of every pass (a fold must not be
//!   weighed with the near-zero `R` of passes that missed its rare light,
//!   [`fold_metrics`]). With the truth's `R` (a long reference) in its place, the
//!   predictions match equal-time renders.
//! * **Paths the pilot missed.** A few passes miss a method's rare, bright paths (on door,
//!   the camera paths that find the light through the gap: unguided path tracing's few
//!   passes predict a small part of its rendered error). The pilot's
//!   combined image also estimates each estimate's second moment by MIS from every path,
//!   and a guided pilot the unguided estimates' from its guided paths ([`crate::moments`]);
//!   what exceeds the estimate's own paths' second moment is added to `σ²_m` (the reason
//!   line says where it is most of it), each term only as far as the render will draw its
//!   paths ([`crate::moments::Horizon`]: paths rarer than one in the render's passes count
//!   with their share of the pixel, not their second moment). On door this brings
//!   `pt-bsdf`'s prediction near its rendered error (docs/measurements/door-desk.md).
//! * **Missing light.** A method that cannot make some paths is biased there: path tracing
//!   misses caustics of point, spot and directional lights (`L S+ D ... E`: a delta light behind a specular
//!   surface), light tracing misses what the pinhole sees through a specular surface and the
//!   environment seen directly. Where the scene's effects allow that, the candidate's squared
//!   difference to the combined mean (less what its noise explains) is added as `b²_m`,
//!   measured on blocks of pixels that hold [`BIAS_BLOCK_SAMPLES`] pilot samples: a
//!   point-light caustic seen only by the light tracer rules path tracing out.
//! * **Guided candidates** (`--guide auto`) are piloted only where one pass of the best
//!   unguided candidate has at least [`GUIDED_MIN_PASS_VARIANCE`] relative variance (a scene
//!   hard per sample), and when their maps are predicted to take at most
//!   [`FIRST_GUIDE_MAPS_SHARE`] of the budget for the first guide (its particle passes
//!   timed on [`PROBE_SHARE`] of their paths, the builds [`MAPS_BUILD_FACTOR`] times as
//!   long), [`GUIDED_MAPS_SHARE`] for all together after it; the guides share one
//!   pilot's time ([`PILOT_SHARE`] / the number of guides each); their maps are then built
//!   once, piloted with the same passes, and reused by the render if one of them wins. With one map round the particle passes do not depend on
//!   the guide: they run once and every guide builds its maps and caches from them. A
//!   guide not piloted (its maps would not fit) leaves its pilot time to those piloted.
//!   When a method that reads the photon map wins, its sparse photon map grows with the time
//!   left, as a fixed method's grows with its budget
//!   ([`chosen_guidance`]).
//! * **Guided splitting.** A guided path or light tracer splits where its guide expects
//!   more light; the combined image does not, so its layers measure both directions
//!   unsplit. Each splitting direction is also piloted with a few passes of its own, as it
//!   renders ([`SplitPilot`], [`SPLIT_PILOT_SHARE`]): its predicted noise is the layer's
//!   times the ratio of the two under the same weights ([`split::split_ratio`]), its time
//!   its own passes'. On door this is the difference: light tracing gains 1.7x from splitting, path
//!   tracing nothing (docs/measurements/sweeps.md, "Guided Russian roulette and splitting"),
//!   and the unsplit layers predict a near tie of two methods about 3.3x apart rendered
//!   (docs/measurements/door-desk.md).
//! * **Margins.** A guided candidate must be predicted [`GUIDED_MARGIN`] times better than
//!   BSDF sampling of its own integrator: the pilot's passes are independent samples, and
//!   what the render's Sobol sequence gains over thousands of passes it cannot measure (it
//!   gains BSDF sampling more; see the constant). A guided combined image must be predicted
//!   [`SPLIT_MARGIN`] times better than its guide's path and light tracers (measured: its
//!   prediction runs low against theirs).
//! * **Budget.** With `--time T` the pilot takes about [`PILOT_SHARE`] of `T` (at least
//!   [`MIN_BATCHES`] + [`TIMED_PASSES`] passes) and counts in the budget: the render stops
//!   at `T`, pilot included. With `--spp N` the pilot's passes (the unguided pilot's
//!   [`MIN_BATCHES`] + [`TIMED_PASSES`], and the guided pilots') are extra, the candidates
//!   are compared at the time `N` passes of path tracing take, and the chosen method renders
//!   `N` passes.

mod choice;
mod choose;
mod metric;
mod params;
mod pilot;
mod predict;
mod rank;
mod run;
mod spec;
mod split;

pub use choice::{Choice, Decision, Note, PilotTimes};
pub use choose::{choose, pilot_resolution};
pub use params::*;
pub use pilot::particle_pass_seconds;
pub use predict::Candidate;
pub use rank::{GUIDED_RIVAL, SPLIT_RIVAL};
pub use run::{Rendered, Run, SavedMaps, chosen_guidance, render_request};
pub use spec::{AutoSpec, Request};
