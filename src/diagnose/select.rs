//! Choosing among the scored candidates of one step: the best eligible margin, alias
//! arbitration for an implausible winner, and the rivals of the winner (unselected candidates
//! that explained nearly the same signal about as well).

use super::honest::{self, ExplainedAlias, Rival};
use super::CandidateResult;
use crate::fit::calibrate::STRONG_CORRELATION;

/// How close (in the selection criterion, `gain − penalty`, a difference of cross-validated
/// χ²) an unselected candidate must come to the selected one to count as its rival. On the
/// `2·ln(likelihood ratio)` scale a difference below 10 is not "very strong" evidence for one
/// model over the other (Kass & Raftery 1995, J. Am. Stat. Assoc. 90, 773–795, §3.2); within
/// it, and changing the predictions alike (correlation > [`STRONG_CORRELATION`]), the data do
/// not choose between the two.
pub const RIVAL_MARGIN: f64 = 10.0;

fn margin_key(r: &CandidateResult) -> f64 {
    if r.margin().is_nan() {
        f64::NEG_INFINITY
    } else {
        r.margin()
    }
}

/// Candidate indices, best margin first (failed candidates last).
pub(super) fn by_margin(results: &[CandidateResult]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..results.len()).collect();
    order.sort_by(|&a, &b| margin_key(&results[b]).total_cmp(&margin_key(&results[a])));
    order
}

/// The candidate to add (index into `results`) and, when alias arbitration replaced an
/// implausible best candidate, the pair. The first `n_effects` results are effects (with their
/// explained signals in `explained`); the rest are measurement candidates.
///
/// The evidence (margin) decides, not plausibility: preferring a plausible candidate with less
/// evidence was tried and chains several plausible stand-ins to mimic one real effect outside
/// its plausible range. Only when the best candidate lands on an implausible value and another
/// eligible candidate with a positive margin and a plausible value explains the same signal
/// (the two fits change the predictions alike) is the plausible reading taken, so a real effect
/// outside its plausible range is not replaced by an unrelated plausible one.
pub(super) fn arbitrate(
    results: &[CandidateResult],
    explained: &[Option<Vec<f64>>],
    order: &[usize],
    n_effects: usize,
) -> (Option<usize>, Option<ExplainedAlias>) {
    let best = order
        .iter()
        .copied()
        .find(|&i| results[i].eligible() && results[i].margin() > 0.0);
    let Some(b) = best.filter(|&b| b < n_effects && !results[b].plausible()) else {
        return (best, None);
    };
    let alt = order.iter().copied().find_map(|i| {
        let ok = i < n_effects
            && i != b
            && results[i].eligible()
            && results[i].margin() > 0.0
            && results[i].plausible();
        if !ok {
            return None;
        }
        let r = honest::signal_correlation(explained[b].as_deref()?, explained[i].as_deref()?);
        (r > STRONG_CORRELATION).then_some((i, r))
    });
    match alt {
        Some((i, r)) => (
            Some(i),
            Some(ExplainedAlias {
                selected: results[i].label.clone(),
                instead_of: results[b].label.clone(),
                r,
            }),
        ),
        None => (best, None),
    }
}

/// Every other eligible effect candidate (index) with the correlation of its change to the
/// predictions with the selected `winner`'s (empty when the winner's change is unknown): what
/// [`rivals`], [`kin`] and [`most_alike`] each read their own part of.
fn correlations_with(
    results: &[CandidateResult],
    explained: &[Option<Vec<f64>>],
    winner: usize,
    n_effects: usize,
) -> Vec<(usize, f64)> {
    let Some(we) = explained.get(winner).and_then(|e| e.as_deref()) else {
        return Vec::new();
    };
    (0..n_effects)
        .filter(|&i| i != winner && results[i].eligible())
        .filter_map(|i| Some((i, honest::signal_correlation(we, explained[i].as_deref()?))))
        .collect()
}

/// The unselected effect candidates that explained nearly the same signal as the selected
/// effect `winner`: eligible, a margin at most [`RIVAL_MARGIN`] below the winner's, and a
/// prediction change correlated with the winner's above [`STRONG_CORRELATION`]. Best first.
pub(super) fn rivals(
    results: &[CandidateResult],
    explained: &[Option<Vec<f64>>],
    order: &[usize],
    winner: usize,
    n_effects: usize,
) -> Vec<Rival> {
    let correlated = correlations_with(results, explained, winner, n_effects);
    let w_margin = results[winner].margin();
    order
        .iter()
        .filter(|&&i| results[i].margin() >= w_margin - RIVAL_MARGIN)
        .filter_map(|&i| correlated.iter().find(|(j, _)| *j == i).copied())
        .filter(|&(_, r)| r > STRONG_CORRELATION)
        .map(|(i, r)| Rival {
            label: results[i].label.clone(),
            params: results[i].params.clone(),
            margin_gap: w_margin - results[i].margin(),
            r,
            plausible: results[i].plausible(),
        })
        .collect()
}

/// The unselected effect candidates (indices) whose fits changed the predictions like the
/// selected `winner`'s (correlation above [`STRONG_CORRELATION`]), whatever their margin at
/// this step, with that correlation: the kin tried in its place once the selection is complete
/// (see [`RIVAL_MARGIN`]).
pub(super) fn kin(
    results: &[CandidateResult],
    explained: &[Option<Vec<f64>>],
    winner: usize,
    n_effects: usize,
) -> Vec<(usize, f64)> {
    correlations_with(results, explained, winner, n_effects)
        .into_iter()
        .filter(|&(_, r)| r > STRONG_CORRELATION)
        .collect()
}

/// The unselected effect candidates (indices) that nearly matched the selected `winner` at
/// this step without being its kin: eligible, a margin at most [`RIVAL_MARGIN`] below the
/// winner's, and a prediction change correlated with the winner's at most
/// [`STRONG_CORRELATION`] (with that correlation, 0 when it cannot be measured). Two effects
/// whose fits differ in ways the shots do not resolve (a level of ball speed, and a mass at
/// the hosel that changes it a little differently across the face) can change the predictions
/// unlike each other and still fit the shots alike; whether they do is decided in the final
/// model, by swapping one in for the other (`search/readings.rs`), as for kin.
pub(super) fn near(
    results: &[CandidateResult],
    explained: &[Option<Vec<f64>>],
    winner: usize,
    n_effects: usize,
) -> Vec<(usize, f64)> {
    let w_margin = results[winner].margin();
    let correlated = correlations_with(results, explained, winner, n_effects);
    (0..n_effects)
        .filter(|&i| i != winner && results[i].eligible())
        .filter(|&i| results[i].margin() >= w_margin - RIVAL_MARGIN)
        .filter_map(|i| {
            let r = correlated
                .iter()
                .find(|(j, _)| *j == i)
                .map_or(0.0, |&(_, r)| if r.is_finite() { r } else { 0.0 });
            (r <= STRONG_CORRELATION).then_some((i, r))
        })
        .collect()
}

/// How many of the most alike candidates a step keeps ([`most_alike`]).
pub const MOST_ALIKE: usize = 3;

/// The [`MOST_ALIKE`] other effect candidates whose fits changed the predictions most like
/// the selected `winner`'s, with that correlation (positive only), most alike first: measured
/// on these shots, whatever their margin.
pub(super) fn most_alike(
    results: &[CandidateResult],
    explained: &[Option<Vec<f64>>],
    winner: usize,
    n_effects: usize,
) -> Vec<(String, f64)> {
    let mut alike: Vec<(String, f64)> = correlations_with(results, explained, winner, n_effects)
        .into_iter()
        .filter(|&(_, r)| r.is_finite() && r > 0.0)
        .map(|(i, r)| (results[i].label.clone(), r))
        .collect();
    alike.sort_by(|a, b| b.1.total_cmp(&a.1));
    alike.truncate(MOST_ALIKE);
    alike
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cand(label: &str, gain: f64) -> CandidateResult {
        CandidateResult {
            label: label.into(),
            n_params: 1,
            params: Vec::new(),
            cv_chi2: 0.0,
            gain,
            spread_gain: None,
            penalty: 6.0,
            rms_reduction: [0.0; 5],
            unidentified: Vec::new(),
            converged: true,
            failure: None,
        }
    }

    #[test]
    fn rivals_are_close_in_margin_and_alike_in_prediction_change() {
        let results = vec![
            cand("a", 100.0),
            cand("close_alike", 95.0),
            cand("close_different", 99.0),
            cand("far_alike", 80.0),
        ];
        let signal = vec![1.0, 2.0, -1.0, 0.5];
        let explained = vec![
            Some(signal.clone()),
            Some(signal.iter().map(|x| 0.9 * x).collect()),
            Some(vec![-2.0, 1.0, 0.5, 1.0]),
            Some(signal.clone()),
        ];
        let order = by_margin(&results);
        assert_eq!(order[0], 0);
        let r = rivals(&results, &explained, &order, 0, results.len());
        let names: Vec<&str> = r.iter().map(|x| x.label.as_str()).collect();
        assert_eq!(names, ["close_alike"]);
        assert!((r[0].margin_gap - 5.0).abs() < 1e-12 && r[0].r > 0.99);
        // Kin ignore the margin: the far alike candidate is tried in the final model too.
        let k: Vec<usize> = kin(&results, &explained, 0, results.len())
            .into_iter()
            .map(|(i, _)| i)
            .collect();
        assert_eq!(k, [1, 3]);
        // Near candidates are close in margin and not kin: the close but different one only
        // (the close alike one is kin, the far one too far).
        let n = near(&results, &explained, 0, results.len());
        assert_eq!(n.len(), 1, "{n:?}");
        assert_eq!(n[0].0, 2);
        assert!(n[0].1 < STRONG_CORRELATION);
    }

    #[test]
    fn near_candidates_without_a_measured_signal_count_as_unlike() {
        let results = vec![cand("a", 100.0), cand("b", 92.0), cand("c", 50.0)];
        let explained = vec![Some(vec![1.0, 2.0, 3.0]), None, None];
        assert_eq!(near(&results, &explained, 0, results.len()), [(1, 0.0)]);
        // An ineligible candidate is never near.
        let mut failed = results.clone();
        failed[1].converged = false;
        assert!(near(&failed, &explained, 0, failed.len()).is_empty());
    }
}
