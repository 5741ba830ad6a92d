//! Integrators of footprint and the driver that runs them over the film.
//!
//! * [`path_tracer`]: paths from the camera with next-event estimation and MIS;
//! * [`compare`]: equal-time comparisons, error against time, parameter sweeps;
//! * [`light_tracer`]: paths from the lights, every non-specular vertex connected to the
//!   pinhole camera and splatted onto the film;
//! * [`maps`]: building the maps and their pictures;
//! * [`mis`]: the combined image's weights over path tracing and light tracing;
//! * [`passes`]: the light pass (photon map) and the view pass (importance map);
//! * [`render`]: passes, threads, time budgets, progress, and the run summary.

pub mod compare;
pub mod light_tracer;
pub mod maps;
pub mod mis;
pub mod passes;
pub mod path_tracer;
pub mod render;

pub use render::{Guide, Integrator, RenderOptions, RenderResult, render, render_with};
