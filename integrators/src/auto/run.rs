//! `auto` as a layer above the render driver: the pilot chooses ([`choose`]), and the
//! chosen method renders the rest of the budget with the maps the pilot built for it
//! ([`chosen_guidance`]).

use super::choice::Choice;
use super::choose::choose;
use super::spec::Request;
use crate::maps::Guidance;
use crate::render::{
    RenderOptions, RenderResult, StopRule, guidance, pass_settings, render_prepared,
};
use footprint::scene::Scene;
use std::time::{Duration, Instant};

/// A render of a [`Request`]: the image and what it took, and `auto`'s choice when it
/// chose.
pub struct Rendered {
    pub result: RenderResult,
    pub choice: Option<Choice>,
}

/// Saved maps for the options given (a guided method), or why they cannot be had.
pub type SavedMaps<'a> = &'a dyn Fn(&RenderOptions) -> Result<Guidance, String>;

/// How a render gets its maps and when it stops.
pub struct Run<'a> {
    /// When a time budget ends the passes.
    pub rule: StopRule,
    /// The heap bytes in use (a counting allocator), for the maps' summaries.
    pub heap: &'a dyn Fn() -> Option<usize>,
    /// Maps from elsewhere (saved passes, `footprint render --maps`) for a guided method the
    /// pilot built none for; `None` builds them.
    pub saved: Option<SavedMaps<'a>>,
}

impl Default for Run<'_> {
    /// Stops within half a pass of the budget (`render --time`), no heap counter, maps
    /// built.
    fn default() -> Self {
        Run {
            rule: StopRule::HalfPass,
            heap: &|| None,
            saved: None,
        }
    }
}

/// Renders `request` with `opts` (whose `method` is replaced by the request's): a fixed
/// method with its maps, or `auto`'s pilot and then its choice for the rest of the budget
/// (the pilot counts in it), with the maps the pilot built for it. `on_choice` is told the
/// choice before the chosen method renders.
pub fn render_request(
    scene: &Scene,
    opts: &RenderOptions,
    request: &Request,
    run: &Run,
    on_choice: &mut dyn FnMut(&Choice),
    on_progress: impl FnMut(f64),
) -> Result<Rendered, String> {
    let start = Instant::now();
    let (method, piloted, choice) = match request {
        Request::Fixed(method) => (*method, None, None),
        Request::Auto(spec) => {
            let mut choice = choose(scene, opts, spec);
            on_choice(&choice);
            (choice.method, choice.guidance.take(), Some(choice))
        }
    };
    let o = RenderOptions {
        method,
        ..opts.clone()
    };
    let g = match piloted {
        Some(piloted) => {
            let left = o.time.map(|t| t - start.elapsed().as_secs_f64());
            chosen_guidance(scene, &o, piloted, left, run.heap)
        }
        None => maps_of(scene, &o, run)?,
    };
    let result = render_prepared(scene, &o, &g, start.elapsed(), run.rule, on_progress);
    Ok(Rendered { result, choice })
}

/// The maps of a method the pilot built none for: saved ones where given (and the method
/// reads maps), else built.
fn maps_of(scene: &Scene, opts: &RenderOptions, run: &Run) -> Result<Guidance, String> {
    match run.saved {
        Some(load) if opts.method.guided() => load(opts),
        _ => Ok(guidance(scene, opts, run.heap)),
    }
}

/// The maps of `auto`'s chosen method (`chosen`) from the pilot's, `piloted`: a sparse
/// photon map grown with the `left` seconds of the budget as a fixed method's grows with
/// its budget ([`Guidance::grow_within`]).
pub fn chosen_guidance(
    scene: &Scene,
    chosen: &RenderOptions,
    piloted: Guidance,
    left: Option<f64>,
    heap: &dyn Fn() -> Option<usize>,
) -> Guidance {
    match left {
        Some(left) if scene.maps.grow => {
            let times = (piloted.timings.light_pass, piloted.timings.view_pass);
            let left = Duration::from_secs_f64(left.max(0.0));
            let (method, params) = (&chosen.method, &chosen.guide_params);
            let pass = pass_settings(scene, chosen);
            piloted.grow_within(scene, method, params, &pass, None, times, left, heap)
        }
        _ => piloted,
    }
}
