//! The margins a guided candidate must clear ([`rival`]) and the order of the choice
//! ([`rank`]): by prediction, but a guided candidate that fails to beat its rival by its
//! margin steps aside.

use super::choice::Note;
use super::params::{GUIDED_MARGIN, SPLIT_MARGIN};
use super::predict::Candidate;
use crate::method::Method;

/// What a guided candidate's rival is: BSDF sampling of its own integrator.
pub const GUIDED_RIVAL: &str = "BSDF sampling of its integrator";
/// What a guided combined image's rival is: its own guide's path or light tracer.
pub const SPLIT_RIVAL: &str = "its guide's pt or lt, which split";

/// The prediction among `all` that candidate `c` fails to beat by its margin, with the
/// margin and what it is, if any: a guided candidate must beat BSDF sampling of its own
/// integrator by [`GUIDED_MARGIN`], and a guided combined image the better of its own
/// guide's pt and lt by [`SPLIT_MARGIN`].
fn rival(all: &[Candidate], c: &Candidate) -> Option<(f64, f64, &'static str)> {
    let m = Method::parse(&c.method).ok().filter(|m| m.guided())?;
    let predicted = |name: String| all.iter().find(|o| o.method == name).map(|o| o.predicted);
    let bsdf = predicted(format!("{}-bsdf", m.integrator.name()))
        .map(|u| (u, GUIDED_MARGIN, GUIDED_RIVAL));
    let split = (m.integrator.name() == "combined")
        .then(|| {
            ["pt", "lt"]
                .iter()
                .filter_map(|i| predicted(format!("{i}-{}", m.guide.name())))
                .min_by(f64::total_cmp)
        })
        .flatten()
        .map(|u| (u, SPLIT_MARGIN, SPLIT_RIVAL));
    [bsdf, split]
        .into_iter()
        .flatten()
        .find(|(u, margin, _)| *u < margin * c.predicted)
}

/// Orders `all` by prediction, best first, but a guided candidate that fails to beat its
/// rival by its margin ([`rival`]) steps aside for the first that does not (all stay in
/// order of prediction behind it). Returns the note that says so when the best predicted
/// stepped aside.
pub(super) fn rank(all: &mut Vec<Candidate>) -> Option<Note> {
    all.sort_by(|a, b| a.predicted.total_cmp(&b.predicted));
    let stepped: Vec<usize> = (0..all.len())
        .filter(|&i| rival(all, &all[i]).is_some())
        .collect();
    let note = (stepped.first() == Some(&0)).then(|| {
        let c = &all[0];
        let (u, margin, rival) = rival(all, c).expect("stepped aside");
        Note::SteppedAside {
            method: c.method.clone(),
            ratio: u / c.predicted,
            margin,
            rival,
        }
    });
    if let Some(pos) = (0..all.len()).find(|i| !stepped.contains(i)) {
        let c = all.remove(pos);
        all.insert(0, c);
    }
    note
}

#[cfg(test)]
mod tests {
    use super::*;

    fn candidate(method: &str, predicted: f64) -> Candidate {
        Candidate {
            method: method.into(),
            predicted,
            pass_seconds: 0.01,
            pass_variance: 1.0,
            unseen: 0.0,
            missing: 0.0,
        }
    }

    /// The margins: door's seed-2 predictions (`combined-footprint` 0.730 against
    /// `lt-footprint` 0.736) make the combined image step aside for the light tracer, which
    /// splits; far ahead of both tracers it stays; a guided tracer must beat its own
    /// integrator's BSDF sampling by 1.3x, and unguided candidates have no rival.
    #[test]
    fn guided_candidates_beat_their_rivals_by_the_margins() {
        let all = [
            candidate("combined-footprint", 0.730),
            candidate("lt-footprint", 0.736),
            candidate("pt-footprint", 0.877),
            candidate("combined-bsdf", 3.06),
            candidate("pt-bsdf", 1.0),
            candidate("lt-bsdf", 2.39),
        ];
        let (u, margin, _) = rival(&all, &all[0]).expect("steps aside");
        assert_eq!((u, margin), (0.736, SPLIT_MARGIN));
        assert!(
            rival(&all, &all[1]).is_none(),
            "lt-footprint 3.2x ahead of lt-bsdf"
        );
        let (u, margin, _) = rival(&all, &all[2]).expect("only 1.14x ahead of pt-bsdf");
        assert_eq!((u, margin), (1.0, GUIDED_MARGIN));
        assert!(all[3..].iter().all(|c| rival(&all, c).is_none()));
        // Far ahead of its guide's tracers the combined image is chosen.
        let ahead = [
            candidate("combined-footprint", 0.5),
            all[1].clone(),
            all[3].clone(),
        ];
        assert!(rival(&ahead, &ahead[0]).is_none());
        // The margin is against its own guide's tracers, not another guide's.
        let grid = [
            candidate("combined-footprint", 0.5),
            candidate("lt-grid", 0.4),
        ];
        assert!(rival(&grid, &grid[0]).is_none());
    }

    /// Ranking: by prediction, but the best predicted steps aside for the first candidate
    /// that clears its margins, and so does every other that fails them (door's seed-2
    /// predictions: the combined image steps aside for the light tracer, and so does
    /// guided path tracing, only 1.23x ahead of `pt-bsdf`); the others keep their
    /// order, and the note names the combined image's rival; no note where the best
    /// predicted clears its margins.
    #[test]
    fn the_best_predicted_steps_aside_for_the_first_that_clears_its_margins() {
        let mut all = vec![
            candidate("pt-bsdf", 0.9),
            candidate("lt-footprint", 0.736),
            candidate("pt-footprint", 0.733),
            candidate("combined-footprint", 0.730),
            candidate("lt-bsdf", 2.39),
        ];
        let note = rank(&mut all).expect("the combined image steps aside");
        let order: Vec<&str> = all.iter().map(|c| c.method.as_str()).collect();
        assert_eq!(
            order,
            [
                "lt-footprint",
                "combined-footprint",
                "pt-footprint",
                "pt-bsdf",
                "lt-bsdf"
            ]
        );
        let Note::SteppedAside { method, rival, .. } = &note else {
            panic!("{note}")
        };
        assert_eq!(method, "combined-footprint");
        assert_eq!(*rival, SPLIT_RIVAL, "{note}");
        let mut clear = vec![
            candidate("pt-bsdf", 1.0),
            candidate("lt-footprint", 0.5),
            candidate("lt-bsdf", 2.39),
        ];
        assert!(rank(&mut clear).is_none());
        assert_eq!(clear[0].method, "lt-footprint");
    }
}
