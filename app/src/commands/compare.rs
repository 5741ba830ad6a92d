//! `footprint compare`: the command's flags, and its curves: each method (or `auto`) once,
//! or once per value of a swept setting.

use crate::args::{ImportArgs, SettingArgs, load_scene, parse_resolution, set_threads};
use crate::compare::{self, CompareSettings, Variant};
use anyhow::{Result, bail};
use clap::Args;
use footprint::keyword::Keyword;
use footprint::rng::Sequence;
use footprint::scene::Scene;
use footprint::settings::MapSettings;
use footprint_integrators::auto::Request;
use footprint_integrators::{Method, RenderOptions};
use std::path::PathBuf;
use std::time::Instant;

/// Compare methods at equal time (map passes included) against a reference: table, error
/// against time, parameter sweeps, and an HTML page
#[derive(Args, Debug)]
pub struct CompareArgs {
    /// Scene file: footprint TOML (.toml) or Mitsuba 3 XML (.xml)
    scene: PathBuf,
    /// Equal-time budget in seconds per method (the top of the ladder)
    #[arg(long, default_value_t = 8.0)]
    time: f64,
    /// Budgets at which the error is measured, comma-separated [default: time/8,time/4,time/2,time]
    #[arg(long, value_delimiter = ',')]
    ladder: Option<Vec<f64>>,
    /// Reference image (EXR, same resolution); default: rendered once with the combined
    /// image and BSDF sampling at --reference-spp and cached next to the scene
    #[arg(long)]
    reference: Option<PathBuf>,
    /// Samples per pixel of a rendered reference
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(1..))]
    reference_spp: u32,
    /// Folder for the cached reference [default: the scene's folder]
    #[arg(long)]
    reference_cache: Option<PathBuf>,
    /// Methods, comma-separated, each INTEGRATOR-GUIDE (pt|lt|combined - bsdf|grid|footprint),
    /// with auto for either part or alone [default: pt and lt with each guide, and
    /// combined-footprint]
    #[arg(long, value_delimiter = ',')]
    methods: Option<Vec<String>>,
    /// Parameter sweep NAME=V1,V2,...: NAME is any [guide] or [maps] setting (its key or
    /// flag: k_p, k_r, p_bsdf, guide_cache, map_rounds, ...; switches take on/off or 1/0),
    /// or sequence (sobol, independent); every method is run once per value [default
    /// methods for a sweep: pt-footprint,lt-footprint]
    #[arg(long)]
    sweep: Option<String>,
    /// Output folder [default: compare-<scene name>]
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Image size WIDTHxHEIGHT [default: the scene's]
    #[arg(long, value_parser = parse_resolution)]
    resolution: Option<(u32, u32)>,
    /// Maximum path length in segments [default: the scene's render.max_depth]
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    max_depth: Option<u32>,
    /// Random seed of the method renders
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Worker threads [default: all cores]
    #[arg(long)]
    threads: Option<usize>,
    #[command(flatten)]
    settings: SettingArgs,
    #[command(flatten)]
    import: ImportArgs,
}

pub fn run(a: CompareArgs) -> Result<()> {
    set_threads(a.threads)?;
    let mut sc = load_scene(&a.scene, &a.import, &a.settings, a.resolution)?;
    let time = a.time;
    if !(time.is_finite() && time > 0.0) {
        bail!("--time must be a positive number of seconds, got {time}");
    }
    let ladder = a
        .ladder
        .unwrap_or_else(|| vec![time / 8.0, time / 4.0, time / 2.0, time]);
    if ladder.is_empty()
        || ladder.iter().any(|t| !(t.is_finite() && *t > 0.0))
        || ladder.windows(2).any(|w| w[0] >= w[1])
    {
        bail!("--ladder must be positive, increasing times, got {ladder:?}");
    }
    let base = RenderOptions::from_scene(&sc, Method::default());
    let max_depth = a.max_depth.unwrap_or(base.max_depth);
    let methods = a.methods.unwrap_or_else(|| {
        if a.sweep.is_some() {
            vec!["pt-footprint".to_string(), "lt-footprint".to_string()]
        } else {
            Method::all().iter().map(|m| m.name()).collect()
        }
    });
    let requests = methods
        .iter()
        .map(|m| Request::parse(m).map_err(|e| anyhow::anyhow!("--methods: {e}")))
        .collect::<Result<Vec<_>>>()?;
    let variants = variants(&requests, &base, &sc, a.sweep.as_deref())?;
    let stem = a
        .scene
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or("scene".into());
    let out = a
        .out
        .unwrap_or_else(|| PathBuf::from(format!("compare-{stem}")));
    let settings = CompareSettings {
        variants,
        ladder,
        reference_spp: a.reference_spp,
        reference_cache: a.reference_cache.clone(),
        out: out.clone(),
        seed: a.seed,
    };
    let start = Instant::now();
    let rows = compare::run(
        &a.scene,
        &mut sc,
        a.reference.as_deref(),
        &settings,
        max_depth,
        &mut |m| eprintln!("{m}"),
    )?;
    let last = *settings.ladder.last().expect("a ladder");
    println!(
        "{:<28} {:>6} {:>9} {:>12} {:>12} {:>7} {:>9}  budget",
        "method", "spp", "seconds", "rel. MSE", "MAE", "spots", "largest"
    );
    for r in rows.iter().filter(|r| r.time_budget == last) {
        println!(
            "{:<28} {:>6} {:>9.2} {:>12.4e} {:>12.4e} {:>7} {:>8.2}%  {}",
            r.method,
            r.spp,
            r.seconds,
            r.rel_mse,
            r.mae,
            r.spots,
            100.0 * r.largest_share,
            if r.budget_missed { "MISSED" } else { "kept" }
        );
    }
    let missed: Vec<String> = rows
        .iter()
        .filter(|r| r.budget_missed)
        .map(|r| format!("{} at {} s ({:.2} s)", r.method, r.time_budget, r.seconds))
        .collect();
    if !missed.is_empty() {
        eprintln!(
            "warning: {} of {} runs missed their budget (took more than {:.0}% longer, or their maps alone took longer; budget_missed in metrics.csv and metrics.json, red in index.html): {}",
            missed.len(),
            rows.len(),
            100.0 * compare::BUDGET_TOLERANCE,
            missed.join(", ")
        );
    }
    println!(
        "wrote {} (index.html, metrics.csv, metrics.json, convergence.svg) in {:.0} s",
        out.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The curves of a comparison: each request once, or once per value of a swept setting
/// (any setting of the schema, `footprint::schema`, or `sequence`).
pub fn variants(
    requests: &[Request],
    base: &RenderOptions,
    scene: &Scene,
    sweep: Option<&str>,
) -> Result<Vec<Variant>> {
    let variant = |r: &Request, label: String, opts: RenderOptions, maps: MapSettings| Variant {
        label,
        request: r.clone(),
        opts,
        maps,
    };
    let Some(sweep) = sweep else {
        return Ok(requests
            .iter()
            .map(|r| variant(r, r.label(), base.clone(), scene.maps.clone()))
            .collect());
    };
    let (name, values) = sweep
        .split_once('=')
        .ok_or_else(|| anyhow::anyhow!("--sweep: expected NAME=V1,V2,..., got '{sweep}'"))?;
    let name = name.trim();
    let mut out = Vec::new();
    for v in values.split(',').map(str::trim) {
        let mut opts = base.clone();
        let mut maps = scene.maps.clone();
        if name == "sequence" {
            opts.sequence = Sequence::from_name(v).ok_or_else(|| {
                anyhow::anyhow!(
                    "--sweep: sequence '{v}' (expected one of {})",
                    Sequence::names()
                )
            })?;
        } else {
            let setting = footprint::schema::find(name).ok_or_else(|| {
                anyhow::anyhow!(
                    "--sweep: unknown parameter '{name}' (expected sequence or one of {})",
                    footprint::schema::names()
                )
            })?;
            footprint::schema::set(&mut opts.guide_params, &mut maps, setting, v)
                .map_err(|e| anyhow::anyhow!("--sweep: {e}"))?;
        }
        for r in requests {
            let label = format!("{}@{name}={v}", r.label());
            out.push(variant(r, label, opts.clone(), maps.clone()));
        }
    }
    Ok(out)
}
