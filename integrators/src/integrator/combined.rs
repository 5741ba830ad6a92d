//! The combined image: in every pass one camera path and one light path per pixel, each
//! image kept as a layer (`pt`, `lt`), and one `combined` image in which every path is
//! weighted against the other strategies that could have made it (three-strategy power
//! heuristic, [`crate::mis`]): the camera path's light hits and next-event connections
//! against the light path's camera connections.

use super::{Context, Integrator, Paths, light_tracing, path_tracing};
use crate::mis::{CameraMis, Densities, LightMis, PilotMis};
use footprint::Rgb;
use footprint::film::SplatList;
use footprint::guide::sampler::SamplerState;
use footprint::rng::Rng;
use glam::Vec2;

/// Path tracing and light tracing combined by MIS, registered as `combined`.
pub struct Combined;

impl Integrator for Combined {
    fn name(&self) -> &'static str {
        "combined"
    }
    fn about(&self) -> &'static str {
        "Both, and one image combining them by multiple importance sampling"
    }
    fn layers(&self) -> &'static [&'static str] {
        &["combined", "pt", "lt"]
    }
    fn moment_layers(&self) -> &'static [&'static str] {
        &crate::moments::LAYERS
    }
    fn paths(&self) -> Paths {
        Paths {
            camera: true,
            light: true,
        }
    }
    fn camera_path<'a>(
        &self,
        ctx: &Context<'a>,
        raster: Vec2,
        rng: &mut Rng,
        state: &mut SamplerState<'a>,
        out: &mut [Rgb],
    ) {
        let densities = ctx.densities();
        // The second-moment layers, when asked for, follow the three (`crate::moments`).
        let c = if out.len() > 3 {
            let unguided = Densities {
                guided: false,
                ..ctx.densities()
            };
            let share = |lens| PilotMis {
                main: CameraMis::new(lens, &densities),
                unguided: CameraMis::new(lens, &unguided),
                horizon: ctx.moments,
            };
            path_tracing::camera_path(ctx, raster, rng, state, share)
        } else {
            let share = |lens| CameraMis::new(lens, &densities);
            path_tracing::camera_path(ctx, raster, rng, state, share)
        };
        out[0] += c.share;
        out[1] += c.pt;
        for (o, m) in out.iter_mut().skip(3).zip(c.m2) {
            *o += m;
        }
    }
    fn light_path<'a>(
        &self,
        ctx: &Context<'a>,
        rng: &mut Rng,
        state: &mut SamplerState<'a>,
        splats: &mut [SplatList],
    ) {
        let (own, moments) = splats.split_at_mut(3);
        let [combined, _, lt] = own else {
            return;
        };
        let pilot = !moments.is_empty();
        let share = light_tracing::Shared {
            combined,
            moments: pilot.then_some(moments),
            horizon: ctx.moments,
        };
        let densities = ctx.densities();
        let scene = ctx.scene;
        if pilot {
            let unguided = Densities {
                guided: false,
                ..ctx.densities()
            };
            light_tracing::light_path(ctx, rng, state, lt, Some(share), |li, p, n| PilotMis {
                main: LightMis::new(scene, &densities, li, p, n),
                unguided: LightMis::new(scene, &unguided, li, p, n),
                horizon: ctx.moments,
            });
        } else {
            light_tracing::light_path(ctx, rng, state, lt, Some(share), |li, p, n| {
                LightMis::new(scene, &densities, li, p, n)
            });
        }
    }
}
