//! Swap rounds after forward selection (stepwise refinement, `docs/diagnose-selection.md`):
//! greedy forward selection cannot undo a step, so an effect that won early as a stand-in
//! (e.g. a 3-parameter `com_offset` soaking up a mass at the hosel) keeps its place even after
//! later effects make a plausible reading the better model.
//!
//! **Gate.** A round runs only while a selected physical effect is a stand-in (a value outside
//! its plausible range at the current fit): a selection of plausible values is left as forward
//! selection made it, so the paper world and the null worlds pay nothing. (Effects aliased
//! with each other are questioned by the re-selection, [`super::reselect`], not here.)
//!
//! **Options**, each scored against the current model with its noise scales (the rest of the
//! model refitted, warm-started from its current values; new effects from their defaults):
//! - removing a stand-in;
//! - replacing a stand-in by one unselected candidate;
//! - a **pair exchange**: a stand-in and another selected effect that has kin (candidates that
//!   changed the predictions alike at its step) out, one of the stand-in's
//!   [`PAIR_FIRST_CHOICES`] best single replacements and one of that effect's kin in. The
//!   exchange is fitted from the single replacement's fit (reused, not refitted), with the
//!   other effect removed and its kin added.
//!
//! **Acceptance** is forward selection's rule: gain `CV(current) − CV(new)` against penalty
//! `(k_in − k_out)·ln n + 2·ln m`, `m` every replacement the round could offer (single
//! replacements plus all pairs the gate allows, however few of them are fitted); a removal
//! gives its parameters' `k_out·ln n` back. The option with the largest positive margin
//! (converged, identifiable) is made and reported as a step. Measurement candidates (impact-
//! and delivery-noise levels) stay as chosen. Ties keep candidate order, so the rounds are
//! deterministic.
//!
//! **Folds.** Every option is fitted on all shots; its folds are fitted only where its result
//! can matter: where it could be made, rank among the best singles a pair starts from, or be
//! reported (a round that makes a change reports every option). [`screen`] says why the
//! others cannot matter.

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use super::super::evaluate::{self, EffectFit, StepBase};
use super::super::{select, CandidateResult, Step, Swap};
use super::Search;
use crate::effects::EffectId;
use crate::fit::calibrate::{noise_scales, STRONG_CORRELATION};
use crate::fit::covariance;
use crate::fit::{fit_quietly_chord_from, EffectRequest, FitError, ParamLayout, Weighting};
use screen::could_exceed;

mod screen;

/// How many of a stand-in's best single replacements a pair exchange starts from: the pair
/// completes one of them, so only the leading few need the second effect tried (the rest of
/// the `m` pairs are still charged for in `2·ln m`).
pub(in crate::diagnose) const PAIR_FIRST_CHOICES: usize = 3;

/// The [`PAIR_FIRST_CHOICES`] best single replacements of the questioned effect `q` among
/// `singles`: eligible and cross-validated, by margin (ties in order). The pair exchanges start
/// from these, and [`screen`] cross-validates every single that could be among them.
fn best_singles(singles: &[Option_], q: usize) -> Vec<&Option_> {
    let mut own: Vec<&Option_> = singles
        .iter()
        .filter(|o| o.outs == [q] && !o.ins.is_empty() && o.result.eligible())
        .filter(|o| o.result.cv_chi2.is_finite())
        .collect();
    own.sort_by(|x, y| y.result.margin().total_cmp(&x.result.margin()));
    own.truncate(PAIR_FIRST_CHOICES);
    own
}

/// `layout` at `theta` without the effects of `kind`: layout, values, parameters removed.
fn without(
    layout: &ParamLayout,
    theta: &DVector<f64>,
    kind: EffectId,
) -> Result<(ParamLayout, DVector<f64>, usize), FitError> {
    let mut effects = Vec::new();
    let mut vals = Vec::new();
    let mut k_out = 0;
    for (i, e) in layout.effects().iter().enumerate() {
        let v = &theta.as_slice()[layout.range(i)];
        if e.kind == kind {
            k_out += v.len();
        } else {
            effects.push(e.clone());
            vals.extend_from_slice(v);
        }
    }
    Ok((ParamLayout::new(effects)?, DVector::from_vec(vals), k_out))
}

/// The model without one selected effect, refitted on all shots: its layout, values, errors on
/// all shots and cross-validated χ², and its residuals and Jacobian on all shots at its values
/// (`None` when they cannot be evaluated there). The round's replacements of that effect start
/// from that fit and evaluation as a forward step's candidates start from the step base's (a
/// fitted model and its evaluation: the replacement's fit then begins near its minimum, and
/// the folds' chord steps, which assume a start at the all-shots solution, begin at one).
pub(in crate::diagnose) struct Reduced {
    pub(in crate::diagnose) layout: ParamLayout,
    pub(in crate::diagnose) theta: DVector<f64>,
    errors: Vec<[f64; 5]>,
    cv: f64,
    at: Option<(DVector<f64>, DMatrix<f64>)>,
    /// Parameters the removed effect had.
    k_out: usize,
}

/// One option of a round: selected effects `outs` removed, `ins` added.
struct Option_ {
    outs: Vec<usize>,
    ins: Vec<EffectRequest>,
    /// Parameters added net of those removed.
    k_net: f64,
    /// Parameters of the effects added.
    k_in: usize,
    /// Rms per component of the model the last effect was fitted on (what the fit's
    /// `rms_reduction` is relative to).
    base_rms: [f64; 5],
    result: CandidateResult,
    fit: Option<EffectFit>,
    /// Whether `result` holds the cross-validated χ² (a removal's always does; a replacement's
    /// once [`screen`] has cross-validated it).
    validated: bool,
}

/// What every option of a round is scored against: the current CV χ², noise scales and
/// weighting, the current rms per component, and `2·ln m`.
#[derive(Clone, Copy)]
struct RoundBase {
    cv: f64,
    sigma: [f64; 5],
    w: Weighting,
    /// Rms per component of the current model.
    rms: [f64; 5],
    multiplicity: f64,
}

impl Search<'_> {
    /// Selected physical effects (indices into `selected`) with a value outside its plausible
    /// range at the current fit: the gate of the swap rounds.
    fn stand_ins(&self) -> Vec<usize> {
        let kinds = Self::implausible_kinds(&self.base, &self.theta_base);
        let mut out: Vec<usize> = (0..self.selected.len())
            .filter(|&o| kinds.contains(&self.selected[o].kind()))
            .collect();
        out.sort_unstable();
        out
    }

    /// Pairs of selected effects (indices into `selected`, first < second) with parameters
    /// whose estimates correlate beyond [`STRONG_CORRELATION`] at the current fit, weighted by
    /// `w`: the data cannot tell them apart, so the pair is questioned like a stand-in.
    fn aliased(&self, w: Weighting) -> Vec<(usize, usize)> {
        let Some((_, jac)) =
            evaluate::all_shots_at(self.club, &self.base, &self.data, w, &self.theta_base)
        else {
            return Vec::new();
        };
        let (lo, hi) = (self.base.lower(), self.base.upper());
        let ranges: Vec<f64> = (0..self.base.len()).map(|j| hi[j] - lo[j]).collect();
        let Some(corr) = covariance(&jac, 1.0, &ranges).correlation else {
            return Vec::new();
        };
        let owner: Vec<Option<usize>> = self
            .base
            .params()
            .map(|(i, _)| {
                let kind = self.base.effects()[i].kind;
                self.selected.iter().position(|r| r.kind() == kind)
            })
            .collect();
        let mut pairs = Vec::new();
        for a in 0..corr.nrows() {
            for b in a + 1..corr.ncols() {
                if let (Some(x), Some(y)) = (owner[a], owner[b]) {
                    let pair = (x.min(y), x.max(y));
                    if x != y && corr[(a, b)].abs() > STRONG_CORRELATION && !pairs.contains(&pair) {
                        pairs.push(pair);
                    }
                }
            }
        }
        pairs.sort_unstable();
        pairs
    }

    /// The gate: selected effects that are stand-ins or aliased with another selected effect
    /// (sorted indices into `selected`), and the aliased pairs.
    pub(in crate::diagnose) fn questioned(
        &self,
        w: Weighting,
    ) -> (Vec<usize>, Vec<(usize, usize)>) {
        let alias_pairs = self.aliased(w);
        let mut questioned = self.stand_ins();
        questioned.extend(alias_pairs.iter().flat_map(|&(x, y)| [x, y]));
        questioned.sort_unstable();
        questioned.dedup();
        (questioned, alias_pairs)
    }

    /// The current layout and values without the selected effects `outs` (indices into
    /// `selected`), not refitted, and the number of parameters dropped.
    fn dropped(&self, outs: &[usize]) -> Result<(ParamLayout, DVector<f64>, usize), FitError> {
        let (mut layout, mut theta, mut k_out) = (self.base.clone(), self.theta_base.clone(), 0);
        for &o in outs {
            let (l, t, k) = without(&layout, &theta, self.selected[o].kind())?;
            (layout, theta, k_out) = (l, t, k_out + k);
        }
        Ok((layout, theta, k_out))
    }

    /// The model without the selected effects `outs`, refitted on all shots (warm-started from
    /// the current values): the layout and its values.
    pub(in crate::diagnose) fn refit_without(
        &self,
        outs: &[usize],
        w: Weighting,
    ) -> Result<(ParamLayout, DVector<f64>), FitError> {
        let (layout, theta, _) = self.dropped(outs)?;
        if layout.is_empty() {
            return Ok((layout, theta));
        }
        // Chord steps from the start's own evaluation to the refit's own minimum (only its
        // point is wanted).
        let at_start = evaluate::all_shots_at(self.club, &layout, &self.data, w, &theta);
        let run = fit_quietly_chord_from(
            self.club,
            &layout,
            &self.data,
            w,
            &theta,
            self.opts.max_iters,
            at_start,
        )?;
        Ok((layout, run.theta))
    }

    /// The model without the selected effects `outs`, refitted on all shots (warm-started from
    /// the current values), with its errors and cross-validated χ² (a removal option of a
    /// round) and its evaluation on all shots.
    pub(in crate::diagnose) fn reduced_by(
        &self,
        outs: &[usize],
        w: Weighting,
    ) -> Result<Reduced, FitError> {
        let (_, _, k_out) = self.dropped(outs)?;
        let (layout, theta) = self.refit_without(outs, w)?;
        let errors = self.errors_of(&layout, theta.as_slice())?;
        let at = evaluate::all_shots_at(self.club, &layout, &self.data, w, &theta);
        let cv = self.cv_given(&layout, &theta, w, at.as_ref().map(|(r, j)| (r, j)))?;
        Ok(Reduced {
            layout,
            theta,
            errors,
            cv,
            at,
            k_out,
        })
    }

    /// The base an option's effect is fitted on: the model `(layout, theta)` with its `errors`,
    /// CV χ² and its residuals and Jacobian on all shots at `theta` when known (`at`: the
    /// effect's fit then starts from them plus its own columns, [`evaluate::evaluate_effect`]).
    fn step_base<'s>(
        &'s self,
        (layout, theta, errors): (&'s ParamLayout, &'s DVector<f64>, &'s [[f64; 5]]),
        (cv, at): (f64, Option<evaluate::AllShots<'s>>),
        rb: RoundBase,
    ) -> StepBase<'s> {
        StepBase {
            club: self.club,
            data: &self.data,
            folds: &self.folds,
            layout,
            theta,
            errors,
            sigma: rb.sigma,
            w: rb.w,
            rms: evaluate::rms_per_component(errors),
            cv,
            at,
            max_iters: self.opts.max_iters,
            progress: None,
            cancel: self.opts.cancel.as_ref(),
            spread: None,
        }
    }

    /// Score a fitted option: gain against the current model, penalty for the parameters it
    /// adds net of those it removes, plus the round's `2·ln m`.
    /// `base_rms` is the rms of the model the option's last effect was fitted on, which its
    /// `rms_reduction` is relative to; the result's is made relative to the current model.
    fn rescore(
        &self,
        f: &EffectFit,
        (label, k_in): (String, usize),
        (k_net, base_rms): (f64, [f64; 5]),
        rb: RoundBase,
    ) -> CandidateResult {
        let mut result = f.result.clone();
        result.label = label;
        result.n_params = k_in;
        result.rms_reduction = std::array::from_fn(|c| {
            let after = base_rms[c] * (1.0 - f.result.rms_reduction[c]);
            (rb.rms[c] - after) / rb.rms[c]
        });
        result.gain = rb.cv - result.cv_chi2;
        result.penalty = k_net * self.penalty_per_param + rb.multiplicity;
        result
    }

    /// The selected effects a pair exchange may take out beside a questioned one, each with
    /// its kin that are not selected.
    fn pair_partners(&self) -> Vec<(usize, Vec<EffectRequest>)> {
        (0..self.selected.len())
            .filter_map(|o| {
                let kind = self.selected[o].kind();
                let (_, _, kin) = self.kin_of.iter().find(|(_, r, _)| r.kind() == kind)?;
                let open: Vec<EffectRequest> = kin
                    .iter()
                    .map(|(c, _)| c.clone())
                    .filter(|c| !self.selected.iter().any(|s| s.kind() == c.kind()))
                    .collect();
                (!open.is_empty()).then_some((o, open))
            })
            .collect()
    }

    /// Pair exchanges (see the module docs): questioned `q` → `a` (from its fitted single
    /// replacement) and `e` → `b`, where `e` is a partner with kin and `b` one of them, or `q`'s
    /// alias and `b` one of its best single replacements; fitted from the single
    /// replacement's values.
    fn pair_options(
        &self,
        singles: &[Option_],
        questioned: &[usize],
        partners: &[(usize, Vec<EffectRequest>)],
        rb: RoundBase,
    ) -> Vec<Option_> {
        let mut jobs: Vec<(&Option_, usize, EffectRequest)> = Vec::new();
        for &q in questioned {
            for st in best_singles(singles, q) {
                for (e, kin) in partners.iter().filter(|(e, _)| *e != q) {
                    for b in kin.iter().filter(|b| b.kind() != st.ins[0].kind()) {
                        jobs.push((st, *e, b.clone()));
                    }
                }
            }
        }
        jobs.par_iter()
            .filter_map(|(st, e, b)| self.pair_option(st, *e, b, rb))
            .collect()
    }

    /// One pair exchange: single replacement `st` of a questioned effect, then `e` removed and
    /// `b` added.
    fn pair_option(
        &self,
        st: &Option_,
        e: usize,
        b: &EffectRequest,
        rb: RoundBase,
    ) -> Option<Option_> {
        let (layout, run) = st.fit.as_ref()?.fit.as_ref()?;
        let (l2, t2, k_e) = without(layout, &run.theta, self.selected[e].kind()).ok()?;
        let errors = self.errors_of(&l2, t2.as_slice()).ok()?;
        let at = evaluate::all_shots_at(self.club, &l2, &self.data, rb.w, &t2);
        let at = at.as_ref().map(|(r, j)| (r, j));
        let base = self.step_base((&l2, &t2, &errors), (f64::NAN, at), rb);
        // Fitted only: cross-validated where it can matter (`screen`).
        let f = evaluate::fit_effect(&base, b, self.penalty_per_param, 0.0);
        let mut o = Option_ {
            outs: vec![st.outs[0], e],
            ins: vec![st.ins[0].clone(), b.clone()],
            k_net: st.k_net + f.result.n_params as f64 - k_e as f64,
            k_in: st.result.n_params + f.result.n_params,
            base_rms: base.rms,
            result: f.result.clone(),
            fit: Some(f),
            validated: false,
        };
        o.result = self.score_option(&o, rb);
        Some(o)
    }

    /// Removing the selected effects `outs` (model `r`), as an option of the round.
    fn removal(&self, outs: Vec<usize>, r: &Reduced, rb: RoundBase) -> Option_ {
        let rms = evaluate::rms_per_component(&r.errors);
        let label = outs
            .iter()
            .map(|&o| self.selected[o].label())
            .collect::<Vec<_>>()
            .join(" + ");
        Option_ {
            outs,
            ins: Vec::new(),
            k_net: -(r.k_out as f64),
            k_in: 0,
            base_rms: rms,
            result: CandidateResult::removal(
                &label,
                (
                    r.cv,
                    rb.cv - r.cv,
                    -(r.k_out as f64) * self.penalty_per_param,
                ),
                &rb.rms,
                &rms,
            ),
            fit: None,
            validated: true,
        }
    }

    /// Every option of a round for the questioned effects and aliased pairs (module docs).
    fn swap_options(
        &self,
        candidates: &[EffectRequest],
        questioned: &[usize],
        rb: RoundBase,
    ) -> Result<Vec<Option_>, FitError> {
        let outs: Vec<Vec<usize>> = questioned.iter().map(|&q| vec![q]).collect();
        let reduced: Vec<Reduced> = outs
            .par_iter()
            .map(|o| self.reduced_by(o, rb.w))
            .collect::<Result<_, _>>()?;
        let unselected: Vec<&EffectRequest> = candidates
            .iter()
            .filter(|c| !self.selected.iter().any(|s| s.kind() == c.kind()))
            .collect();
        let partners = self.pair_partners();
        // Every replacement the round could offer: singles, and pairs with a partner's kin
        // (the first effect any unselected candidate).
        let u = unselected.len();
        let kin_pairs: usize = questioned
            .iter()
            .map(|q| {
                partners
                    .iter()
                    .filter(|(e, _)| e != q)
                    .map(|(_, k)| k.len() * u)
                    .sum::<usize>()
            })
            .sum();
        let n_options = questioned.len() * u + kin_pairs;
        let rb = RoundBase {
            multiplicity: 2.0 * (n_options.max(1) as f64).ln(),
            ..rb
        };
        let jobs: Vec<(usize, &EffectRequest)> = (0..questioned.len())
            .flat_map(|r| unselected.iter().map(move |c| (r, *c)))
            .collect();
        // Fitted only: cross-validated where it can matter (`screen`).
        let mut singles: Vec<Option_> = jobs
            .par_iter()
            .map(|&(r, c)| {
                let red = &reduced[r];
                let at = red.at.as_ref().map(|(r, j)| (r, j));
                let base = self.step_base((&red.layout, &red.theta, &red.errors), (red.cv, at), rb);
                let f = evaluate::fit_effect(&base, c, self.penalty_per_param, 0.0);
                let mut o = Option_ {
                    outs: vec![questioned[r]],
                    ins: vec![c.clone()],
                    k_net: f.result.n_params as f64 - red.k_out as f64,
                    k_in: f.result.n_params,
                    base_rms: base.rms,
                    result: f.result.clone(),
                    fit: Some(f),
                    validated: false,
                };
                o.result = self.score_option(&o, rb);
                o
            })
            .collect();
        // Any base of the round serves the cross-validations (only its club, folds, weighting
        // and limits are read).
        let red = &reduced[0];
        let cv_base = self.step_base((&red.layout, &red.theta, &red.errors), (rb.cv, None), rb);
        self.screen_singles(&mut singles, questioned, &cv_base, rb);
        let mut pairs = self.pair_options(&singles, questioned, &partners, rb);
        let due: Vec<usize> = (0..pairs.len())
            .filter(|&i| could_exceed(&pairs[i], 0.0, rb))
            .collect();
        self.validate(&mut pairs, &due, &cv_base, rb);
        let removals: Vec<Option_> = outs
            .into_iter()
            .zip(&reduced)
            .map(|(o, r)| self.removal(o, r, rb))
            .collect();
        let mut options: Vec<Option_> = removals.into_iter().chain(singles).chain(pairs).collect();
        self.validate_if_made(&mut options, &cv_base, rb);
        Ok(options)
    }

    /// Make option `chosen`: the model, the selection and the kin bookkeeping.
    fn make_swap(&mut self, chosen: Option_, w: Weighting) -> Result<(), FitError> {
        let out_kinds: Vec<EffectId> = chosen
            .outs
            .iter()
            .map(|&o| self.selected[o].kind())
            .collect();
        // A partner's kin stay kin of what replaces it (they changed the predictions alike).
        let mut inherited: Vec<(EffectRequest, f64)> = Vec::new();
        if let [_, e] = chosen.outs[..] {
            let kind = self.selected[e].kind();
            if let Some((_, req, kin)) = self.kin_of.iter().find(|(_, r, _)| r.kind() == kind) {
                let r_in = kin
                    .iter()
                    .find(|(c, _)| Some(c) == chosen.ins.get(1))
                    .map_or(1.0, |(_, r)| *r);
                inherited.push((req.clone(), r_in));
                inherited.extend(
                    kin.iter()
                        .filter(|(c, _)| Some(c) != chosen.ins.get(1))
                        .cloned(),
                );
            }
        }
        match chosen.fit {
            Some(EffectFit {
                fit: Some((layout, run)),
                ..
            }) => {
                self.base = layout;
                self.theta_base = run.theta;
            }
            _ => (self.base, self.theta_base) = self.refit_without(&chosen.outs, w)?,
        }
        self.selected.retain(|s| !out_kinds.contains(&s.kind()));
        self.kin_of
            .retain(|(_, req, _)| !out_kinds.contains(&req.kind()));
        for (j, inn) in chosen.ins.iter().enumerate() {
            self.selected.push(inn.clone());
            let kin = if j == 1 {
                std::mem::take(&mut inherited)
            } else {
                Vec::new()
            };
            self.kin_of.push((inn.label(), inn.clone(), kin));
        }
        Ok(())
    }

    /// One round of swaps: the change that lowers CV χ² + penalty most, made and reported as a
    /// step; `None` when no selected value is a stand-in or no option improves.
    pub(in crate::diagnose) fn swap_round(
        &mut self,
        candidates: &[EffectRequest],
    ) -> Result<Option<Step>, FitError> {
        if self.selected.is_empty() {
            return Ok(None);
        }
        let errors = self.errors_of(&self.base, self.theta_base.as_slice())?;
        let sigma = noise_scales(&errors);
        let w = Weighting::launch(&sigma);
        // Swap rounds question the stand-ins only; effects merely aliased with each other
        // are left to the re-selection (`reselect.rs`), which costs one forward run, not a
        // round per alias.
        let questioned = self.stand_ins();
        if questioned.is_empty() {
            return Ok(None);
        }
        let base_labels: Vec<String> = self.selected.iter().map(|r| r.label()).collect();
        let current_cv = self.cv_at(&self.base, &self.theta_base, w)?;
        let rb = RoundBase {
            cv: current_cv,
            sigma,
            w,
            rms: evaluate::rms_per_component(&errors),
            multiplicity: 0.0,
        };
        let mut options = self.swap_options(candidates, &questioned, rb)?;
        let results: Vec<CandidateResult> = options.iter().map(|o| o.result.clone()).collect();
        let order = select::by_margin(&results);
        let Some(&best) = order
            .iter()
            .find(|&&i| results[i].eligible() && results[i].margin() > 0.0)
        else {
            return Ok(None);
        };
        let chosen = options.swap_remove(best);
        let label_of = |v: Vec<String>| (!v.is_empty()).then(|| v.join(" + "));
        let out_label = chosen
            .outs
            .iter()
            .map(|&o| self.selected[o].label())
            .collect::<Vec<_>>()
            .join(" + ");
        let in_label = label_of(chosen.ins.iter().map(EffectRequest::label).collect());
        self.make_swap(chosen, w)?;
        let candidates = order.iter().map(|&i| results[i].clone()).collect();
        let swap = Swap {
            out: out_label,
            inn: in_label,
            cv_before: current_cv,
            cv_after: results[best].cv_chi2,
        };
        self.swap_step(base_labels, sigma, candidates, swap)
            .map(Some)
    }
}
