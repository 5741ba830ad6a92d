//! What `auto` chose, why, and what its pilot did: structured, so that the command line
//! formats it ([`Choice::reason`]) and the tests read its fields.

use super::predict::Candidate;
use crate::maps::Guidance;
use crate::method::Method;
use std::fmt;
use std::time::Duration;

/// How the choice was made.
#[derive(Clone, Debug, PartialEq)]
pub enum Decision {
    /// One candidate only: nothing to pilot.
    OnlyCandidate,
    /// The budget is under `pairs` passes of pt and lt (`pair_s` seconds a pair): no pilot,
    /// the first unguided candidate.
    NoRoomForPilot {
        budget_s: f64,
        pairs: f64,
        pair_s: f64,
    },
    /// The unguided pilot found no light: the first candidate.
    NoLight,
    /// No candidate could be piloted: the first one.
    NothingPiloted,
    /// No guide's maps fit their share of the budget, but one pass of `pt-bsdf` has relative
    /// variance `pass_variance`, at least `HARD_PASS_VARIANCE`: guided path tracing, its maps
    /// built with the time left.
    HardSceneUnpiloted { pass_variance: f64 },
    /// The candidate predicted best (after the margins): [`Choice::candidates`]' first.
    Predicted {
        /// The time left that every candidate was predicted at.
        time_left_s: f64,
    },
}

/// Something the pilot did or found that the choice depends on.
#[derive(Clone, Debug, PartialEq)]
pub enum Note {
    /// The image has more than `PILOT_MAX_PIXELS` pixels: piloted at a lower resolution,
    /// pass times scaled by `pass_scale`.
    PilotResolution {
        pilot: (u32, u32),
        image: (u32, u32),
        pass_scale: f64,
    },
    /// A guide not piloted: one pass of the best unguided candidate (`method`) has relative
    /// variance under `GUIDED_MIN_PASS_VARIANCE`.
    EasyScene {
        guide: &'static str,
        method: String,
        pass_variance: f64,
    },
    /// A guide not piloted: its maps and pilot (about `estimate_s`) would take more than
    /// `share` of `horizon_s`.
    MapsTooCostly {
        guide: &'static str,
        estimate_s: f64,
        share: f64,
        horizon_s: f64,
    },
    /// The view pass's importance target stayed at the pilot's resolution: at the image's
    /// (`extra_s` more) the maps would not fit `share` of `horizon_s`.
    TargetAtPilotResolution {
        pilot: (u32, u32),
        image: (u32, u32),
        extra_s: f64,
        share: f64,
        horizon_s: f64,
    },
    /// The view pass read an importance target at the image's resolution.
    TargetAtImageResolution {
        pilot: (u32, u32),
        image: (u32, u32),
        extra_s: f64,
        share: f64,
        left_s: f64,
    },
    /// A guided direction's split pilot not run: its unguided layer misses more light than
    /// the best unguided candidate's predicted error.
    SplitNotPiloted { method: String },
    /// The best predicted candidate stepped aside: predicted only `ratio` times better than
    /// its rival, where it must be `margin` times.
    SteppedAside {
        method: String,
        ratio: f64,
        margin: f64,
        rival: &'static str,
    },
    /// A candidate misses light (a method that cannot make some paths), and why.
    MissesLight { method: String, why: &'static str },
    /// `share` of a candidate's predicted noise comes from paths its own pilot passes
    /// missed (seen by MIS from the other techniques).
    Unseen { method: String, share: f64 },
}

impl fmt::Display for Note {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let res = |(w, h): (u32, u32)| format!("{w}x{h}");
        match self {
            Note::PilotResolution {
                pilot,
                image,
                pass_scale,
            } => write!(
                f,
                "piloted at {} (the {} image has more than {} pixels; pass times scaled by {pass_scale:.2})",
                res(*pilot),
                res(*image),
                super::params::PILOT_MAX_PIXELS
            ),
            Note::EasyScene {
                guide,
                method,
                pass_variance,
            } => write!(
                f,
                "{guide} not piloted: one pass of {method} has relative variance {pass_variance:.2}, under {} (guiding does not repay its maps where unguided passes are this good)",
                super::params::GUIDED_MIN_PASS_VARIANCE
            ),
            Note::MapsTooCostly {
                guide,
                estimate_s,
                share,
                horizon_s,
            } => write!(
                f,
                "{guide} not piloted: its maps and pilot would take about {estimate_s:.2} s, more than {:.0}% of {horizon_s:.2} s",
                100.0 * share
            ),
            Note::TargetAtPilotResolution {
                pilot,
                image,
                extra_s,
                share,
                horizon_s,
            } => write!(
                f,
                "importance target at {}: at {} ({extra_s:.2} s more) the maps would not fit {:.0}% of {horizon_s:.2} s",
                res(*pilot),
                res(*image),
                100.0 * share
            ),
            Note::TargetAtImageResolution {
                pilot,
                image,
                extra_s,
                share,
                left_s,
            } => write!(
                f,
                "importance target at {}: about {extra_s:.2} s more than at {}, within {:.0}% of the {left_s:.2} s left",
                res(*image),
                res(*pilot),
                100.0 * share
            ),
            Note::SplitNotPiloted { method } => {
                let direction = method.split('-').next().unwrap_or("");
                write!(
                    f,
                    "{method} not piloted split: {direction}-bsdf misses more light than the best unguided candidate's predicted error"
                )
            }
            Note::SteppedAside {
                method,
                ratio,
                margin,
                rival,
            } => write!(
                f,
                "{method} stepped aside: predicted only {ratio:.2}x better than {rival} (it must be {margin}x)"
            ),
            Note::MissesLight { method, why } => write!(f, "{method} misses light ({why})"),
            Note::Unseen { method, share } => write!(
                f,
                "{method}: {:.0}% of its predicted noise from paths its own pilot passes missed (seen by MIS from the others)",
                100.0 * share
            ),
        }
    }
}

/// Where the pilot's time went.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PilotTimes {
    /// The whole pilot (maps of guided candidates included).
    pub total: Duration,
    /// The unguided pilot's passes (pass timings included).
    pub unguided_s: f64,
    /// The guided pilots' particle passes, maps and caches.
    pub maps_s: f64,
    /// The guided pilots' passes.
    pub guided_passes_s: f64,
    /// Passes of the unguided pilot.
    pub passes: usize,
}

impl PilotTimes {
    /// What the predictions took: the rest of the pilot.
    pub fn predictions_s(&self) -> f64 {
        (self.total.as_secs_f64() - self.unguided_s - self.maps_s - self.guided_passes_s).max(0.0)
    }
}

/// What `auto` chose and why.
pub struct Choice {
    /// The request's label (`auto`, `pt-auto`, `auto-bsdf`).
    pub label: String,
    pub method: Method,
    pub decision: Decision,
    /// Every candidate piloted and wanted, in the order of the choice (the chosen first).
    pub candidates: Vec<Candidate>,
    pub notes: Vec<Note>,
    pub pilot: PilotTimes,
    /// Maps built by the pilot for the chosen method (guided winners reuse them).
    pub guidance: Option<Guidance>,
}

impl fmt::Debug for Choice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.method.name(), self.reason())
    }
}

impl Choice {
    /// A choice made without a pilot's prediction.
    pub(super) fn unpiloted(label: &str, method: Method, decision: Decision) -> Self {
        Choice {
            label: label.to_string(),
            method,
            decision,
            candidates: Vec::new(),
            notes: Vec::new(),
            pilot: PilotTimes::default(),
            guidance: None,
        }
    }

    /// True when some note is of the kind `pred` accepts.
    pub fn noted(&self, pred: impl Fn(&Note) -> bool) -> bool {
        self.notes.iter().any(pred)
    }

    /// One line: the choice, its predicted error against the others', where the pilot's
    /// time went, and the notes.
    pub fn reason(&self) -> String {
        let notes = || self.notes.iter().map(|n| n.to_string()).collect::<Vec<_>>();
        let name = self.method.name();
        match &self.decision {
            Decision::OnlyCandidate => "the only candidate".into(),
            Decision::NoRoomForPilot {
                budget_s,
                pairs,
                pair_s,
            } => format!(
                "{name}: no pilot, the budget of {budget_s:.2} s is under {pairs} passes of pt and lt ({pair_s:.3} s a pair)"
            ),
            Decision::NoLight => "the pilot found no light: the first candidate".into(),
            Decision::NothingPiloted => format!(
                "{name}: no candidate could be piloted ({})",
                notes().join("; ")
            ),
            Decision::HardSceneUnpiloted { pass_variance } => format!(
                "{name}, not piloted: one pass of pt-bsdf has relative variance {pass_variance:.1}, at least {} (guided path tracing wins by far on scenes this hard), and no guide's maps fit a pilot ({})",
                super::params::HARD_PASS_VARIANCE,
                notes().join("; ")
            ),
            Decision::Predicted { time_left_s } => {
                let (best, others) = self.candidates.split_first().expect("a candidate");
                let others: Vec<String> = others
                    .iter()
                    .map(|c| format!("{} {:.3e}", c.method, c.predicted))
                    .collect();
                let p = &self.pilot;
                let mut line = format!(
                    "{} predicted relative MSE {:.3e} at {time_left_s:.1} s ({}); pilot {} passes; pilot {:.2} s: unguided passes {:.2} s, particle passes, maps and caches {:.2} s, guided passes {:.2} s, predictions {:.2} s",
                    best.method,
                    best.predicted,
                    others.join(", "),
                    p.passes,
                    p.total.as_secs_f64(),
                    p.unguided_s,
                    p.maps_s,
                    p.guided_passes_s,
                    p.predictions_s()
                );
                for n in notes() {
                    line += "; ";
                    line += &n;
                }
                line
            }
        }
    }
}
