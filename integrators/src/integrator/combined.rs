//! The combined image: in every pass one camera path and one light path per pixel, each
//! image kept as a layer (`pt`, `lt`), and one `combined` image in which every path is
//! weighted against the other strategies that could have made it (three-strategy power
//! heuristic, [`crate::mis`]): the camera path's light hits and next-event connections
//! against the light path's camera connections.

use super::{Context, Integrator, Paths, light_tracing, path_tracing};
use crate::mis::{CameraMis, LightMis};
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
        let cam = &ctx.scene.camera;
        let densities = ctx.densities();
        let c = crate::specialised!(ctx.specialisation, F => path_tracing::trace::<F, _>(
            ctx.scene,
            cam.position,
            cam.ray_dir(raster),
            (ctx.max_depth, ctx.rr_depth),
            &ctx.camera_sampler,
            state,
            rng,
            CameraMis::new(cam.position, &densities),
        ));
        out[0] += c.share;
        out[1] += c.pt;
    }
    fn light_path<'a>(
        &self,
        ctx: &Context<'a>,
        rng: &mut Rng,
        state: &mut SamplerState<'a>,
        splats: &mut [SplatList],
    ) {
        let [combined, _, lt] = splats else {
            return;
        };
        let densities = ctx.densities();
        crate::specialised!(ctx.specialisation, F => light_tracing::trace::<F, _>(
            ctx,
            rng,
            state,
            lt,
            Some(combined),
            |li, p, n| LightMis::new(ctx.scene, &densities, li, p, n),
        ));
    }
}
