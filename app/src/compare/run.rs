//! The comparison's loop: every variant at every budget of the ladder, its maps charged
//! to the budget, `auto`'s pilot inside it; then the files.

use super::html::html;
use super::metrics::*;
use super::reference::reference;
use super::report::{csv, json};
use super::rows::{CompareSettings, MethodSummary, Row, slope_points};
use super::svg::convergence_svg;
use anyhow::{Context, Result};
use footprint::film::image_io::write_png;
use footprint::scene::Scene;
use footprint_integrators::auto::{Choice, Request, Run, render_request};
use footprint_integrators::maps::Guidance;
use footprint_integrators::render::{RenderOptions, StopRule, guidance, render_prepared};
use std::path::Path;

/// Runs the comparison and writes every file; returns the rows.
pub fn run(
    scene_path: &Path,
    scene: &mut Scene,
    given_ref: Option<&Path>,
    s: &CompareSettings,
    max_depth: u32,
    log: &mut dyn FnMut(&str),
) -> Result<Vec<Row>> {
    std::fs::create_dir_all(&s.out)
        .with_context(|| format!("cannot create {}", s.out.display()))?;
    let (reference, ref_source) = reference(
        scene_path,
        scene,
        given_ref,
        s.reference_spp,
        max_depth,
        s.reference_cache.as_deref(),
        log,
    )?;
    let exposure = preview_exposure(&reference);
    write_png(&s.out.join("reference.png"), &reference, exposure)?;
    let total_runs = s.variants.len() * s.ladder.len();
    let ladder_sum: f64 = s.ladder.iter().sum();
    // Wall-clock time of the runs so far and the budgets they were given: the time left is
    // the remaining budgets scaled by what the runs so far really took.
    let (mut wall, mut budgets_done) = (0.0f64, 0.0f64);
    let mut rows = Vec::new();
    let scene_maps = scene.maps.clone();
    for (mi, v) in s.variants.iter().enumerate() {
        scene.maps = v.maps.clone();
        let fixed = v.request.fixed();
        let opts = RenderOptions {
            method: fixed.unwrap_or(v.opts.method),
            time: None,
            seed: s.seed,
            max_depth,
            ..v.opts.clone()
        };
        // The maps and caches once per method; their time is charged to every rung, as a
        // render of that budget would spend it.
        let left = |wall: f64, done: f64| {
            let remaining = ladder_sum * s.variants.len() as f64 - done;
            if done > 0.0 {
                format!("about {:.0} s left", remaining * wall / done)
            } else {
                format!("at least {remaining:.0} s left")
            }
        };
        let g0 = std::time::Instant::now();
        // `auto` chooses at every rung, its pilot inside the rung's budget. A sparse photon
        // map grows with the budget (`maps.grow`): then every rung builds its own maps for
        // its own budget, as a render of that budget would.
        let g = match fixed {
            Some(_) => guidance(scene, &opts, &|| None),
            None => Guidance::default(),
        };
        let per_rung = footprint_integrators::maps::may_grow(scene, &opts.guide_params)
            && g.photon_cache
                .as_ref()
                .zip(g.photons.as_ref())
                .is_some_and(|(c, m)| {
                    matches!(
                        footprint_integrators::maps::growth(
                            c,
                            &m.pass.particles,
                            &opts.guide_params
                        ),
                        footprint_integrators::maps::Growth::Grows(_)
                    )
                });
        let maps = g.timings.total();
        if fixed.is_some_and(|m| m.guided()) {
            log(&format!(
                "[{}/{total_runs}] {}: maps and caches built in {:.2} s, {}",
                mi * s.ladder.len() + 1,
                v.label,
                maps.as_secs_f64(),
                if per_rung {
                    "and again for every rung (its sparse photon map grows with the rung's budget)"
                } else {
                    "charged to every rung"
                }
            ));
        }
        wall += g0.elapsed().as_secs_f64();
        for (li, &t) in s.ladder.iter().enumerate() {
            let run_index = mi * s.ladder.len() + li + 1;
            log(&format!(
                "[{run_index}/{total_runs}] {} for {t} s ({})",
                v.label,
                left(wall, budgets_done)
            ));
            let opts = RenderOptions {
                time: Some(t),
                ..opts.clone()
            };
            let r0 = std::time::Instant::now();
            let (r, maps) = match &v.request {
                Request::Auto(_) => {
                    let run = Run {
                        rule: StopRule::WithinBudget,
                        ..Run::default()
                    };
                    let mut said = |c: &Choice| {
                        log(&format!(
                            "[{run_index}/{total_runs}] {} chose {} ({:.2} s pilot): {}",
                            v.label,
                            c.method.name(),
                            c.pilot.total.as_secs_f64(),
                            c.reason()
                        ))
                    };
                    let out = render_request(scene, &opts, &v.request, &run, &mut said, |_| {})
                        .map_err(anyhow::Error::msg)?;
                    // The pilot and the chosen method's maps are charged to the budget.
                    let charged = out
                        .result
                        .elapsed
                        .saturating_sub(out.result.timings.tracing);
                    (out.result, charged)
                }
                Request::Fixed(_) if per_rung => {
                    let own = guidance(scene, &opts, &|| None);
                    let maps = own.timings.total();
                    let r =
                        render_prepared(scene, &opts, &own, maps, StopRule::WithinBudget, |_| {});
                    (r, maps)
                }
                Request::Fixed(_) => (
                    render_prepared(scene, &opts, &g, maps, StopRule::WithinBudget, |_| {}),
                    maps,
                ),
            };
            wall += r0.elapsed().as_secs_f64();
            budgets_done += t;
            let tm = &r.timings;
            let seconds = r.elapsed.as_secs_f64();
            let budget_missed = missed(seconds, maps.as_secs_f64(), t);
            if budget_missed {
                let why = if maps.as_secs_f64() >= t {
                    format!("its maps alone take {:.2} s", maps.as_secs_f64())
                } else {
                    format!(
                        "maps {:.2} s plus one pass {:.2} s",
                        maps.as_secs_f64(),
                        tm.tracing.as_secs_f64() / r.passes.max(1) as f64
                    )
                };
                log(&format!(
                    "warning: {} cannot keep the {t} s budget ({why}): it took {seconds:.2} s for {} spp; the row is marked budget_missed",
                    v.label, r.passes
                ));
            }
            rows.push(Row {
                method: v.label.clone(),
                time_budget: t,
                seconds,
                map_seconds: tm.maps.total().as_secs_f64(),
                tracing_seconds: tm.tracing.as_secs_f64(),
                spp: r.passes,
                rel_mse: rel_mse(&r.image, &reference),
                mae: mae(&r.image, &reference),
                spots: spots(&r.image, &reference),
                largest_share: largest_share(&r),
                budget_missed,
                chosen: match v.request {
                    Request::Auto(_) => r.method.name(),
                    Request::Fixed(_) => String::new(),
                },
            });
            if li + 1 == s.ladder.len() {
                write_png(&s.out.join(format!("{}.png", v.label)), &r.image, exposure)?;
                write_png(
                    &s.out.join(format!("{}-error.png", v.label)),
                    &error_image(&r.image, &reference),
                    0.0,
                )?;
            }
        }
    }
    scene.maps = scene_maps;
    let names: Vec<String> = s.variants.iter().map(|v| v.label.clone()).collect();
    // Slopes, and the time each method needs to reach the median of the equal-time errors
    // (of the runs that kept the budget, if any did).
    let last = *s.ladder.last().unwrap();
    let kept = rows
        .iter()
        .any(|r| r.time_budget == last && !r.budget_missed);
    let mut finals: Vec<f64> = rows
        .iter()
        .filter(|r| r.time_budget == last && (!kept || !r.budget_missed))
        .map(|r| r.rel_mse)
        .collect();
    finals.sort_by(|a, b| a.total_cmp(b));
    let target = finals.get(finals.len() / 2).copied().unwrap_or(0.0);
    let summary: Vec<MethodSummary> = names
        .iter()
        .map(|m| {
            let pts = slope_points(&rows, m);
            MethodSummary {
                method: m.clone(),
                slope: log_log_slope(&pts),
                time_to_target_s: time_to_reach(&pts, target),
            }
        })
        .collect();
    std::fs::write(s.out.join("metrics.csv"), csv(&rows)?)?;
    std::fs::write(
        s.out.join("metrics.json"),
        json(
            &scene_path.display().to_string(),
            &ref_source,
            &rows,
            &summary,
            target,
        )?,
    )?;
    std::fs::write(
        s.out.join("convergence.svg"),
        convergence_svg(&rows, &names),
    )?;
    std::fs::write(
        s.out.join("index.html"),
        html(
            scene_path,
            &ref_source,
            &rows,
            &summary,
            &names,
            s,
            target,
            scene,
        ),
    )?;
    Ok(rows)
}
