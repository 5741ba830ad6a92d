//! footprint: a physically based CPU renderer that guides both light paths and view paths
//! with particle maps (Hey & Purgathofer 2001, "Importance Sampling with Hemispherical
//! Particle Footprints").
//!
//! This crate is the core library: geometry and the BVH, scenes and their loading, materials
//! and BSDFs, lights, the camera and the film. The integrators and the command line live in
//! the `footprint-integrators` crate (`integrators/`).

pub mod bsdf;
pub mod bvh;
pub mod camera;
pub mod direction_sampler;
pub mod effects;
pub mod error;
pub mod film;
pub mod filter;
pub mod footprint_sampler;
pub mod fresnel;
pub mod geometry;
pub mod grid_sampler;
pub mod heap;
pub mod image_io;
pub mod light;
pub mod loader;
pub mod material;
pub mod math;
pub mod microfacet;
pub mod mitsuba;
pub mod particle_map;
pub mod rng;
pub mod rough_plastic;
pub mod sampling;
pub mod scene;
pub mod texture;

pub use error::{Error, Result};
pub use math::Rgb;
