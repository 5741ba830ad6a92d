//! `auto`'s predicted error of each candidate against the error that candidate's renders
//! measure, on a door ajar and on a room seen through window panes, with Mitsuba 3's
//! references (`tests/mitsuba-references/`) as the truth.
//!
//! The pilot predicts each estimate's noise partly from paths its own passes missed, read
//! by MIS from the other strategies' paths (`footprint_integrators::moments`). Where those
//! paths are so rare that a render of the budget would not draw them either, their second
//! moment is not what the render shows: counted in full it predicted path tracing's error on
//! Veach Ajar and behind a glass ball at one to four orders of magnitude above what its
//! renders measure. These tests fail when that term is inflated: every unguided candidate's
//! prediction at the sample budget must lie within a factor [`WITHIN`] of the median of its
//! renders' relative MSE at that budget.

mod common;

use footprint::film::Image;
use footprint::film::image_io::read_exr;
use footprint::scene::Scene;
use footprint::scene::mitsuba::{self, ImportOptions};
use footprint_app::compare::rel_mse;
use footprint_integrators::auto::{AutoSpec, choose};
use footprint_integrators::{Method, RenderOptions, render};
use std::path::{Path, PathBuf};

/// How far the median prediction may lie from the median measured error. A pilot of a few
/// passes predicts a heavy-tailed error: on the pane room five pilots' predictions of one
/// candidate spread over a factor of up to 2.3 (lt-bsdf 3.98e-3 to 9.14e-3), and the
/// medians come to 1.13-2.09 of the measured errors; on Veach Ajar to 0.90-1.09. Five
/// renders' relative MSE spread by less than 1.2. The bound is not statistical: it is what
/// a useful prediction must meet (`auto` ranks candidates that differ by 1.3 and more),
/// and it fails where the unseen term counts paths the render will not draw: on the pane
/// room (a median of 4.4, one pilot at 440). On Veach Ajar, with a quarter of the
/// particles and 256 passes, that term comes to 1.48 only (at 30 s with the full maps,
/// about 100): there the test checks the predictions, the pane room the term.
const WITHIN: f64 = 2.5;

/// A Mitsuba XML scene with `defines`.
fn import(xml: &Path, defines: &[(&str, String)]) -> Scene {
    let opts = ImportOptions {
        defines: defines
            .iter()
            .map(|(k, v)| (k.to_string(), v.clone()))
            .collect(),
        lenient: false,
    };
    mitsuba::load(xml, &opts).expect("the scene imports")
}

/// A bundled scene's Mitsuba XML at the resolution and filter of its Mitsuba reference
/// (`tests/mitsuba-references/`, box filter), and that reference.
fn bundled(name: &str, res: (u32, u32), max_depth: u32) -> (Scene, Image) {
    let dir = common::scenes_dir().join(name);
    let exported = dir.join("mitsuba").join("scene.xml");
    let xml = if exported.exists() {
        exported
    } else {
        dir.join("scene.xml")
    };
    let defines = [
        ("resx", res.0.to_string()),
        ("resy", res.1.to_string()),
        ("rfilter", "box".into()),
        ("max_depth", max_depth.to_string()),
    ];
    let refs = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../tests/mitsuba-references");
    let reference = read_exr(&refs.join(format!("{name}-mean.exr"))).expect("the reference reads");
    assert_eq!((reference.width, reference.height), res);
    (import(&xml, &defines), reference)
}

/// Every candidate `spec` pilots: its prediction at `spp` samples per pixel, the median over
/// `runs` pilots (seeds), against the median relative MSE of `runs` renders of it at `spp`
/// (fixed seeds).
fn check(name: &str, scene: &Scene, reference: &Image, spp: u32, spec: &AutoSpec, runs: u64) {
    let opts = RenderOptions {
        spp,
        max_depth: scene.settings.max_depth,
        ..Default::default()
    };
    // Each candidate's predictions at `spp` passes of it (`predicted` is at the time of
    // `spp` path-tracing passes, which is another pass count for lt and combined).
    let mut predictions: Vec<(String, Vec<f64>)> = Vec::new();
    for seed in 0..runs {
        let choice = choose(
            scene,
            &RenderOptions {
                seed: 7 + seed,
                ..opts.clone()
            },
            spec,
        );
        for c in &choice.candidates {
            let p = c.pass_variance / spp as f64 + c.missing;
            match predictions.iter_mut().find(|(m, _)| *m == c.method) {
                Some((_, ps)) => ps.push(p),
                None => predictions.push((c.method.clone(), vec![p])),
            }
        }
    }
    assert!(!predictions.is_empty(), "{name}: nothing piloted");
    let median = |mut xs: Vec<f64>| {
        xs.sort_by(f64::total_cmp);
        xs[xs.len() / 2]
    };
    let fmt = |xs: &[f64]| {
        xs.iter()
            .map(|e| format!("{e:.2e}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    let mut report = Vec::new();
    let mut off = Vec::new();
    for (method, ps) in predictions {
        let errors: Vec<f64> = (0..runs)
            .map(|k| {
                let o = RenderOptions {
                    method: Method::parse(&method).unwrap(),
                    seed: 1000 + k,
                    ..opts.clone()
                };
                let out = render(scene, &o, |_| {});
                assert!(out.image.all_valid());
                rel_mse(&out.image, reference)
            })
            .collect();
        let (predicted, measured) = (median(ps.clone()), median(errors.clone()));
        let ratio = predicted / measured;
        report.push(format!(
            "{method}: predicted {predicted:.3e} ({}), measured {measured:.3e} ({}), ratio {ratio:.2}",
            fmt(&ps),
            fmt(&errors)
        ));
        if !(ratio < WITHIN && ratio > 1.0 / WITHIN) {
            off.push(method);
        }
    }
    let report = report.join("\n  ");
    eprintln!("{name} at {spp} spp:\n  {report}");
    assert!(
        off.is_empty(),
        "{name}: predictions off by more than {WITHIN}x for {off:?}:\n  {report}"
    );
}

/// Two coloured window panes before a lit room: every path to the camera passes a pane.
/// No guide is piloted here (one unguided pass is good enough, `GUIDED_MIN_PASS_VARIANCE`):
/// the unguided pilot's own MIS estimates are checked. Counted in full, path tracing's
/// unseen term reads 0.006-1.8 (median 4.4x its measured error).
#[test]
fn auto_predicts_the_pane_room_as_its_renders_measure() {
    let (scene, reference) = bundled("panes", (48, 48), 8);
    check(
        "panes",
        &scene,
        &reference,
        256,
        &AutoSpec::new(None, None),
        5,
    );
}

/// Veach Ajar (`../shared/scenes-ext`, with Mitsuba 3's reference of `../shared/refs`), the
/// door ajar: the guided pilot's light paths read unguided path tracing's second moment,
/// which counted in full predicted it about 100 times above its renders' error.
#[test]
fn auto_predicts_veach_ajar_as_its_renders_measure() {
    let shared = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared");
    let xml = shared.join("scenes-ext/veach-ajar/scene.xml");
    let reference = shared.join("refs/veach-ajar_128x72.exr");
    if !xml.exists() || !reference.exists() {
        common::skip(
            "auto_predicts_veach_ajar_as_its_renders_measure",
            "../shared/scenes-ext/veach-ajar or ../shared/refs is absent",
        );
        return;
    }
    let mut scene = import(&xml, &[("resx", "128".into()), ("resy", "72".into())]);
    // A quarter of the default particles, so that the footprints' maps fit the pilot's
    // share of 256 passes and the guided pilot runs (its paths read the unguided
    // candidates' second moments).
    scene.maps.photons /= 4;
    scene.maps.importons /= 4;
    let reference = read_exr(&reference).expect("the reference reads");
    // Path tracing, unguided and guided: the estimate whose unseen term the guided paths
    // read, and the one `auto` chooses here (the combined images, 0.90-1.09 of their
    // measured errors, are left out for time; light tracing cannot see the teapots'
    // reflections, and its missing light is estimated apart from the term checked here).
    let mut spec = AutoSpec::new(None, None);
    spec.candidates
        .retain(|m| ["pt-bsdf", "pt-footprint"].contains(&m.name().as_str()));
    check("veach-ajar", &scene, &reference, 256, &spec, 3);
}
