//! Which options of a swap round are cross-validated (`super`): every option is fitted on all
//! shots, but its folds are fitted only where the result can matter.
//!
//! **The bound.** With `θ*` the option's all-shots minimum and `θ_k` fold `k`'s fit (started at
//! `θ*`, every accepted step lowering the training χ²): `χ²_train(θ_k) ≤ χ²_train(θ*)` and,
//! `θ*` minimising the sum, `χ²_train(θ*) + χ²_test(θ*) ≤ χ²_train(θ_k) + χ²_test(θ_k)`; so
//! `χ²_test(θ_k) ≥ χ²_test(θ*)` fold by fold, and as the held-out folds partition the shots the
//! cross-validated χ² is at least the all-shots χ² at `θ*`. An option's margin, `CV(current) −
//! CV(option) − penalty`, is therefore at most `CV(current) − χ²(θ*) − penalty`, known once the
//! option is fitted. The bound needs `θ*` to be a minimum: it is used only for eligible options
//! (converged, identifiable; an option that is not can be neither made nor ranked), with a slack
//! ([`SLACK_ABS`], [`SLACK_REL`]) far above the fits' tolerances.
//!
//! **What is cross-validated.** An option whose bound could exceed 0 (it could be made); for
//! each questioned effect, its single replacements in order of bound until
//! [`PAIR_FIRST_CHOICES`](super::PAIR_FIRST_CHOICES) are cross-validated and eligible, then every
//! other whose bound reaches the margin of the last of those (it could start a pair exchange);
//! and, when the round makes a change (some option has a positive margin), every option, since
//! the step reports them all. A round that makes no change reports nothing, so its choice and
//! the pairs it fits are what they would be with every option cross-validated, and a round that
//! makes one reports the same numbers: only the folds of options that cannot matter are left
//! unfitted (`screen/tests.rs` compares a whole report both ways).
//!
//! Measured on the shaft-fitting season (`docs/performance-history.md`): the bound was below
//! −1,000 for 183 of the 196 options of the two rounds that made no change, and every
//! eligible option's cross-validated χ² was at least its all-shots χ² (604 options of every
//! kind, the ties of an empty base to the last bit).

use rayon::prelude::*;

use super::super::Search;
use super::{best_singles, Option_, RoundBase, PAIR_FIRST_CHOICES};
use crate::diagnose::evaluate::{self, StepBase};
use crate::diagnose::CandidateResult;

/// Absolute slack on the bound, in χ² units (the fits stop within about 1e-8 of χ² of their
/// minima: `docs/performance-history.md`, "Where the own-minimum fits go").
const SLACK_ABS: f64 = 1.0;
/// Slack on the bound relative to the option's χ².
const SLACK_REL: f64 = 1e-3;

#[cfg(test)]
thread_local! {
    /// Whether the options are screened on this thread (a test compares both ways).
    pub(in crate::diagnose) static SCREEN: std::cell::Cell<bool> =
        const { std::cell::Cell::new(true) };
    /// Options whose folds were left unfitted on this thread.
    pub(in crate::diagnose) static UNVALIDATED: std::cell::Cell<u64> =
        const { std::cell::Cell::new(0) };
}

/// Whether options are screened ([`SCREEN`] in the tests).
#[cfg(test)]
fn screening() -> bool {
    SCREEN.with(std::cell::Cell::get)
}

/// Whether options are screened: always.
#[cfg(not(test))]
const fn screening() -> bool {
    true
}

/// Could option `o`'s margin exceed `threshold` once cross-validated? `false` for an option
/// already cross-validated, one whose fit failed (there is nothing to cross-validate), one that
/// is not eligible, and one whose bound (module docs) stays at or below `threshold`.
pub(super) fn could_exceed(o: &Option_, threshold: f64, rb: RoundBase) -> bool {
    match upper(o, rb) {
        None => false,
        // NaN: cross-validated.
        Some(u) => !screening() || !(u <= threshold),
    }
}

/// The bound on option `o`'s margin with its slack, `None` when it is not to be cross-validated
/// whatever its margin could be ([`could_exceed`]).
fn upper(o: &Option_, rb: RoundBase) -> Option<f64> {
    let (_, run) = o.fit.as_ref().and_then(|f| f.fit.as_ref())?;
    if o.validated || (screening() && !o.result.eligible()) {
        return None;
    }
    let chi2 = run.residuals.norm_squared();
    Some(rb.cv - chi2 - o.result.penalty + SLACK_ABS + SLACK_REL * chi2)
}

impl Search<'_> {
    /// Option `o`'s scores against the current model (its fit's, rescored): gain, penalty for
    /// the parameters it adds net of those it removes plus the round's `2·ln m`, and, for a
    /// stand-in replaced by its plausible alias (`alias.rs`), one parameter charged to the
    /// stand-in's model for the physics its value stands for.
    pub(super) fn score_option(&self, o: &Option_, rb: RoundBase) -> CandidateResult {
        let Some(f) = &o.fit else {
            return o.result.clone();
        };
        let side = |v: Vec<String>| v.join(" + ");
        let label = format!(
            "{} → {}",
            side(o.outs.iter().map(|&s| self.selected[s].label()).collect()),
            side(o.ins.iter().map(|r| r.label()).collect())
        );
        let mut result = self.rescore(f, (label, o.k_in), (o.k_net, o.base_rms), rb);
        if let ([q], [c]) = (&o.outs[..], &o.ins[..]) {
            if let Some(r) = self.plausible_alias(*q, c, f, o.k_net) {
                result.label = format!("{} (plausible alias, r = {r:.2})", result.label);
                result.penalty = (o.k_net - 1.0) * self.penalty_per_param;
            }
        }
        result
    }

    /// Cross-validate the options `which` (indices into `options`) in parallel, and score them
    /// again. `cv_base`: any base of the round (its club, folds, weighting and limits are read).
    pub(super) fn validate(
        &self,
        options: &mut [Option_],
        which: &[usize],
        cv_base: &StepBase,
        rb: RoundBase,
    ) {
        let mut fits: Vec<(usize, evaluate::EffectFit)> = which
            .iter()
            .filter_map(|&i| options[i].fit.take().map(|f| (i, f)))
            .collect();
        fits.par_iter_mut()
            .for_each(|(_, f)| evaluate::cross_validate(cv_base, f));
        for (i, f) in fits {
            let o = &mut options[i];
            o.fit = Some(f);
            o.validated = true;
            o.result = self.score_option(o, rb);
        }
    }

    /// Cross-validate the single replacements that could be made, then, for each questioned
    /// effect, those that could still be among its [`PAIR_FIRST_CHOICES`] best (by margin,
    /// eligible, cross-validated): while fewer are known, the ones of highest bound next; then
    /// every one whose bound reaches the last of them; until none could.
    pub(super) fn screen_singles(
        &self,
        singles: &mut [Option_],
        questioned: &[usize],
        cv_base: &StepBase,
        rb: RoundBase,
    ) {
        let first: Vec<usize> = (0..singles.len())
            .filter(|&i| could_exceed(&singles[i], 0.0, rb))
            .collect();
        self.validate(singles, &first, cv_base, rb);
        loop {
            let mut more = Vec::new();
            for &q in questioned {
                let mine: Vec<usize> = (0..singles.len())
                    .filter(|&i| singles[i].outs == [q])
                    .collect();
                let best = best_singles(singles, q);
                if let Some(last) = best.get(PAIR_FIRST_CHOICES - 1).map(|o| o.result.margin()) {
                    more.extend(
                        mine.into_iter()
                            .filter(|&i| could_exceed(&singles[i], last, rb)),
                    );
                } else {
                    let mut open: Vec<(f64, usize)> = mine
                        .into_iter()
                        .filter_map(|i| upper(&singles[i], rb).map(|u| (u, i)))
                        .collect();
                    // Highest bound first (NaN first: it could be anything); ties in order.
                    open.sort_by(|a, b| match (a.0.is_nan(), b.0.is_nan()) {
                        (false, false) => b.0.total_cmp(&a.0),
                        (x, y) => y.cmp(&x),
                    });
                    let want = PAIR_FIRST_CHOICES - best.len();
                    more.extend(open.into_iter().take(want).map(|(_, i)| i));
                }
            }
            if more.is_empty() {
                return;
            }
            self.validate(singles, &more, cv_base, rb);
        }
    }

    /// When some cross-validated option would be made (eligible, positive margin), cross-validate
    /// every other: the step reports them all.
    pub(super) fn validate_if_made(
        &self,
        options: &mut [Option_],
        cv_base: &StepBase,
        rb: RoundBase,
    ) {
        let made = options
            .iter()
            .any(|o| o.validated && o.result.eligible() && o.result.margin() > 0.0);
        let rest: Vec<usize> = (0..options.len())
            .filter(|&i| !options[i].validated)
            .filter(|&i| options[i].fit.as_ref().is_some_and(|f| f.fit.is_some()))
            .collect();
        if made {
            self.validate(options, &rest, cv_base, rb);
        } else {
            #[cfg(test)]
            UNVALIDATED.with(|n| n.set(n.get() + rest.len() as u64));
        }
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::{SCREEN, UNVALIDATED};
    use crate::app::diagnose::{run, DiagnoseSettings};
    use crate::app::inputs::{NamedClub, ShotsInput};
    use crate::app::CollectedNotes;
    use crate::diagnose::default_candidates;
    use crate::effects::EffectId;
    use crate::fit::EffectRequest;

    /// `smash diagnose --club configs/clubs/paper_driver.toml` on the shots `smash synth` writes for
    /// `configs/synth/unknown_head_world.toml` (a head unlike the club file's: four swap rounds, two
    /// of which make a change), with the swap rounds' options screened or all cross-validated: the
    /// report as JSON, and how many options' folds were left unfitted. The candidates are the
    /// library's defaults, named (a user-defined effect another test registers is not among them).
    fn unknown_head(screen: bool) -> (String, u64) {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let (_, world) = crate::app::synth::generate_world(
            &root.join("configs/synth/unknown_head_world.toml"),
            None,
        )
        .expect("world generates");
        let club_path = root.join("configs/clubs/paper_driver.toml");
        let club = crate::data::club_file::read_club(&club_path).expect("club reads");
        let input = ShotsInput::Csv {
            label: "unknown_head_world.csv".into(),
            bytes: crate::synth::files::synth_shots_csv(&world),
        };
        let named = NamedClub {
            spec: &club,
            path: &club_path,
        };
        SCREEN.with(|s| s.set(screen));
        UNVALIDATED.with(|n| n.set(0));
        let shots: Vec<crate::model::Shot> = world.shots.iter().map(|s| s.to_shot()).collect();
        let candidates: Vec<String> = default_candidates(&crate::fit::distinct_groups(&shots))
            .into_iter()
            .filter(|c| !matches!(c, EffectRequest::Global(EffectId::User(_))))
            .map(|c| c.label())
            .collect();
        let settings = DiagnoseSettings {
            candidates: Some(candidates.join(",")),
            ..DiagnoseSettings::default()
        };
        let mut notes = CollectedNotes::default();
        let (report, _) =
            run(&settings, named, &input, &mut notes, (None, None)).expect("diagnoses");
        SCREEN.with(|s| s.set(true));
        let json = serde_json::to_string(&report).expect("report serialises");
        (json, UNVALIDATED.with(std::cell::Cell::get))
    }

    /// Screening changes no number of the diagnosis (the whole report as JSON, where each `f64` is
    /// printed exactly) and leaves folds unfitted in the rounds that make none.
    #[test]
    fn screening_leaves_the_report_bit_for_bit_and_skips_folds() {
        let (all, none_left) = unknown_head(false);
        let (screened, left) = unknown_head(true);
        assert_eq!(none_left, 0);
        // A round that makes no change leaves no step: the count is what shows it ran.
        assert!(left > 0, "no option was screened out");
        assert_eq!(screened, all);
    }
}
