//! Integrators of footprint and the driver that runs them over the film.
//!
//! * [`path_tracer`]: paths from the camera with next-event estimation and MIS;
//! * [`light_tracer`]: paths from the lights, every non-specular vertex connected to the
//!   pinhole camera and splatted onto the film;
//! * [`render`]: passes, threads, time budgets, progress, and the run summary.

pub mod light_tracer;
pub mod path_tracer;
pub mod render;

pub use render::{Integrator, RenderOptions, RenderResult, render};
