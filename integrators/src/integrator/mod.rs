//! The integrator extension point: an [`Integrator`] says which paths one pass traces and
//! what each path adds to which image layer; the render driver (`crate::render`) owns the
//! budget, the threads, the films and the progress.
//!
//! * [`path_tracing`] (`pt`): camera paths with next-event estimation and MIS, guided by
//!   the photon map;
//! * [`light_tracing`] (`lt`): light paths connected to the camera, guided by the
//!   importance map;
//! * [`combined`] (`combined`): both in every pass, and one image in which every path is
//!   weighted against the other strategies ([`crate::mis`]).
//!
//! Adding an integrator: write `integrators/src/integrator/NAME.rs` with a unit struct
//! implementing [`Integrator`], declare the module below and add the struct to
//! [`INTEGRATORS`]. The command line, scene files, `compare` and the EXR header take its
//! name from there.

pub mod combined;
pub mod light_tracing;
pub mod path_tracing;

use footprint::Rgb;
use footprint::film::SplatList;
use footprint::guide::sampler::{GuidedSampler, SamplerState};
use footprint::rng::Rng;
use footprint::scene::Scene;
use footprint::scene::features::Specialisation;
use glam::Vec2;

/// Everything a path needs: the scene, the depth limit and the two direction samplers
/// (the photon map guides camera paths, the importance map guides light paths).
pub struct Context<'a> {
    pub scene: &'a Scene,
    /// Maximum path length in segments (the camera ray or the first light segment is 1).
    pub max_depth: u32,
    /// Russian roulette after scattering at vertices of this depth or deeper.
    pub rr_depth: u32,
    pub camera_sampler: GuidedSampler<'a>,
    pub light_sampler: GuidedSampler<'a>,
    /// The combined image's MIS weights use the guided samplers' densities (else the
    /// unguided ones).
    pub guided_mis: bool,
    /// The compiled path loop the paths run in (`crate::specialised!`).
    pub specialisation: Specialisation,
    /// The horizon of the second-moment layers, where they are asked for
    /// (`crate::moments::Horizon`).
    pub moments: crate::moments::Horizon,
}

impl<'a> Context<'a> {
    /// The direction densities of the combined image's weights.
    pub fn densities(&self) -> crate::mis::Densities<'_, 'a> {
        crate::mis::Densities {
            camera: &self.camera_sampler,
            light: &self.light_sampler,
            guided: self.guided_mis,
        }
    }
}

/// Which paths one pass traces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Paths {
    /// One camera path per pixel.
    pub camera: bool,
    /// One light path per pixel.
    pub light: bool,
}

/// An integrator. Every image layer is averaged over passes: camera paths add their value
/// to their pixel, light paths splat values already divided by the pixel count (one light
/// path per pixel per pass).
pub trait Integrator: Sync {
    /// The name used by `--integrator`, scene files, `compare` and EXR headers.
    fn name(&self) -> &'static str;
    /// One line for `--help`.
    fn about(&self) -> &'static str;
    /// The estimates it writes, main image first (one EXR layer each).
    fn layers(&self) -> &'static [&'static str];
    /// Second-moment layers it can add after its layers when a render asks for them
    /// (`RenderOptions::moments`, `auto`'s pilot; [`crate::moments`]); none by default.
    fn moment_layers(&self) -> &'static [&'static str] {
        &[]
    }
    /// The paths one pass traces (and so the particle maps its guided form needs).
    fn paths(&self) -> Paths;
    /// One camera path through raster position `raster`; adds to `out[layer]`.
    fn camera_path<'a>(
        &self,
        _ctx: &Context<'a>,
        _raster: Vec2,
        _rng: &mut Rng,
        _state: &mut SamplerState<'a>,
        _out: &mut [Rgb],
    ) {
    }
    /// One light path; splats into `splats[layer]`.
    fn light_path<'a>(
        &self,
        _ctx: &Context<'a>,
        _rng: &mut Rng,
        _state: &mut SamplerState<'a>,
        _splats: &mut [SplatList],
    ) {
    }
}

/// Every integrator, by name: the one registration list.
pub static INTEGRATORS: &[&dyn Integrator] = &[
    &path_tracing::PathTracing,
    &light_tracing::LightTracing,
    &combined::Combined,
];

/// The integrator named `name`.
pub fn find_integrator(name: &str) -> Option<&'static dyn Integrator> {
    INTEGRATORS.iter().copied().find(|i| i.name() == name)
}

/// The registered integrators' names, comma-separated (for error messages).
pub fn integrator_names() -> String {
    INTEGRATORS
        .iter()
        .map(|i| i.name())
        .collect::<Vec<_>>()
        .join(", ")
}
