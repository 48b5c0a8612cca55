//! Fitting and cross-validating the candidates of one diagnose step: each effect candidate
//! (base effects plus it, fitted on all shots and on every training fold) and each
//! impact-location noise level (the base effects refitted with the locations treated as noisy).

use nalgebra::{DMatrix, DVector};

use super::spread::SpreadModel;
use super::{honest, CandidateResult, DiagnoseProgress};
use crate::club::ClubSpec;
use crate::fit::calibrate::ParamEstimate;
use crate::fit::covariance::covariance;
use crate::fit::{
    fit_quietly as fit, fit_quietly_chord_from, EffectRequest, FitData, FitError, FitProblem,
    FitRun, ParamLayout, Weighting,
};
use crate::measurement::ImpactNoise;
use crate::stats;

mod folds;
mod start;
#[cfg(test)]
use folds::fold_rows;
pub(super) use folds::{cv_chi2, make_folds, Folds};
use start::start_evaluation;

/// Residuals and Jacobian of a fit on all shots at one point, whose rows a training fold
/// started there takes instead of evaluating them again.
pub(super) type AllShots<'r> = (&'r DVector<f64>, &'r DMatrix<f64>);

/// The residuals and Jacobian of `layout` (all parameters active) on all shots of `data` at
/// `theta`; `None` when they cannot be evaluated there (each fold then evaluates its own).
pub(super) fn all_shots_at(
    club: &ClubSpec,
    layout: &ParamLayout,
    data: &FitData,
    w: Weighting,
    theta: &DVector<f64>,
) -> Option<(DVector<f64>, DMatrix<f64>)> {
    if layout.is_empty() {
        return None;
    }
    let pr = FitProblem::new(club, layout.clone(), data, w);
    Some((
        pr.residuals(theta.as_slice()).ok()?,
        pr.jacobian_full(theta).ok()?,
    ))
}

/// A candidate's layout: the base effects (minus a global effect it refines) plus its own,
/// the starting point, and how many leading parameters belong to the base.
struct CandidateLayout {
    layout: ParamLayout,
    start: DVector<f64>,
    kept: usize,
}

fn candidate_layout(
    base: &ParamLayout,
    theta_base: &DVector<f64>,
    cand: &EffectRequest,
    groups: &[String],
) -> Result<CandidateLayout, FitError> {
    let added = cand.expand(groups)?;
    // Refinement: a per-group candidate replaces the selected global effect of its kind and
    // starts every group from the global value.
    let replaced = match cand {
        EffectRequest::PerGroup(kind) => base
            .effects()
            .iter()
            .position(|e| e.kind == *kind && e.group.is_none()),
        _ => None,
    };
    let mut effects = Vec::new();
    let mut start_vals = Vec::new();
    let mut inherited: Option<Vec<f64>> = None;
    for (i, e) in base.effects().iter().enumerate() {
        let vals: Vec<f64> = theta_base.as_slice()[base.range(i)].to_vec();
        if Some(i) == replaced {
            inherited = Some(vals);
        } else {
            effects.push(e.clone());
            start_vals.extend(vals);
        }
    }
    let kept = start_vals.len();
    for e in &added {
        match &inherited {
            Some(v) => start_vals.extend(v),
            None => start_vals.extend(e.kind.params().iter().map(|s| s.default)),
        }
    }
    effects.extend(added);
    let layout = ParamLayout::new(effects)?;
    Ok(CandidateLayout {
        start: DVector::from_vec(start_vals),
        layout,
        kept,
    })
}

pub(super) fn rms_per_component(errors: &[[f64; 5]]) -> [f64; 5] {
    std::array::from_fn(|c| stats::rms(&errors.iter().map(|e| e[c]).collect::<Vec<_>>()))
}

/// The model of one step that every candidate is measured against.
pub(super) struct StepBase<'a> {
    pub(super) club: &'a ClubSpec,
    pub(super) data: &'a FitData,
    pub(super) folds: &'a Folds,
    pub(super) layout: &'a ParamLayout,
    pub(super) theta: &'a DVector<f64>,
    /// The base model's launch errors on all shots, file units.
    pub(super) errors: &'a [[f64; 5]],
    /// Noise scales of this step (file units) and the weighting made from them.
    pub(super) sigma: [f64; 5],
    pub(super) w: Weighting,
    pub(super) rms: [f64; 5],
    /// Cross-validated χ² of the base; NaN while a step computes it beside the candidates
    /// (their gains, `cv − cv_chi2`, are then completed by the step).
    pub(super) cv: f64,
    /// The base's residuals and Jacobian on all shots at `theta` with `w`, when known: an
    /// effect candidate's fit starts from them ([`start_evaluation`]).
    pub(super) at: Option<AllShots<'a>>,
    pub(super) max_iters: u64,
    pub(super) progress: Option<&'a dyn DiagnoseProgress>,
    /// The caller's token: a fit not yet started is not started once it is cancelled.
    pub(super) cancel: Option<&'a crate::cancel::Cancel>,
    /// With known instrument noise: the base model's covariance model and the base errors'
    /// `−2 ln L` under it (exact locations), to score impact-noise levels by the spread.
    pub(super) spread: Option<(&'a SpreadModel, f64)>,
}

/// An effect candidate after fitting: its scores, its all-shots fit (layout and run) and what
/// that fit changed in the predictions ([`honest::explained_signal`]).
pub(super) struct EffectFit {
    pub(super) result: CandidateResult,
    pub(super) fit: Option<(ParamLayout, FitRun)>,
    pub(super) explained: Option<Vec<f64>>,
}

fn empty_result(label: String, n_params: usize, penalty: f64) -> CandidateResult {
    CandidateResult {
        label,
        n_params,
        params: Vec::new(),
        cv_chi2: f64::NAN,
        gain: f64::NAN,
        spread_gain: None,
        penalty,
        rms_reduction: [0.0; 5],
        unidentified: Vec::new(),
        converged: false,
        failure: None,
    }
}

/// Fit one effect candidate on all shots, read its identifiability and estimates, and
/// cross-validate it. `penalty_per_param` is `ln n`, `multiplicity` the `2·ln m` of the step.
pub(super) fn evaluate_effect(
    b: &StepBase,
    cand: &EffectRequest,
    penalty_per_param: f64,
    multiplicity: f64,
) -> EffectFit {
    let mut f = fit_effect(b, cand, penalty_per_param, multiplicity);
    cross_validate(b, &mut f);
    f
}

/// [`evaluate_effect`] up to its cross-validation: the candidate fitted on all shots, its
/// estimates, identifiability and rms reductions; its cross-validated χ² and gain are NaN until
/// [`cross_validate`] completes them (a fit that failed has its folds counted done here).
pub(super) fn fit_effect(
    b: &StepBase,
    cand: &EffectRequest,
    penalty_per_param: f64,
    multiplicity: f64,
) -> EffectFit {
    let n_folds = b.folds.train.len();
    if crate::cancel::cancelled(b.cancel) {
        let mut res = empty_result(cand.label(), 0, multiplicity);
        res.failure = Some(FitError::Cancelled.to_string());
        return EffectFit {
            result: res,
            fit: None,
            explained: None,
        };
    }
    let fitted = candidate_layout(b.layout, b.theta, cand, &b.data.groups).and_then(|l| {
        let at_start = start_evaluation(b, &l);
        let run = fit_quietly_chord_from(
            b.club,
            &l.layout,
            b.data,
            b.w,
            &l.start,
            b.max_iters,
            at_start,
        );
        if let Some(p) = b.progress {
            p.job_done();
        }
        Ok((l.layout, run?, l.kept))
    });
    // Parameters the model gains (a refinement replaces the global one).
    let k = fitted
        .as_ref()
        .map_or(0, |(l, _, _)| l.len() - b.theta.len());
    let mut res = empty_result(cand.label(), k, k as f64 * penalty_per_param + multiplicity);
    let (layout, run, kept) = match fitted {
        Ok(f) => f,
        Err(e) => {
            res.failure = Some(e.to_string());
            if let Some(p) = b.progress {
                (0..n_folds).for_each(|_| p.job_done());
            }
            return EffectFit {
                result: res,
                fit: None,
                explained: None,
            };
        }
    };
    res.converged = run.converged;
    read_estimates(&mut res, &layout, &run, kept);
    let mut explained = None;
    match FitProblem::new(b.club, layout.clone(), b.data, b.w).launch_errors(run.theta.as_slice()) {
        Ok(errs) => {
            let rms = rms_per_component(&errs);
            res.rms_reduction = std::array::from_fn(|c| (b.rms[c] - rms[c]) / b.rms[c]);
            explained = Some(honest::explained_signal(b.errors, &errs, &b.sigma));
        }
        Err(e) => res.failure = Some(e.to_string()),
    }
    EffectFit {
        result: res,
        fit: Some((layout, run)),
        explained,
    }
}

/// Complete a fit of [`fit_effect`] with its cross-validated χ² and gain (nothing to do for a
/// fit that failed): what [`evaluate_effect`] does after fitting.
pub(super) fn cross_validate(b: &StepBase, f: &mut EffectFit) {
    let Some((layout, run)) = &f.fit else {
        return;
    };
    match cv_chi2(
        b.club,
        layout,
        b.folds,
        b.w,
        &run.theta,
        Some((&run.residuals, &run.jacobian)),
        b.max_iters,
        b.progress,
        b.cancel,
    ) {
        Ok(cv) => {
            f.result.cv_chi2 = cv;
            f.result.gain = b.cv - cv;
        }
        Err(e) => f.result.failure = Some(e.to_string()),
    }
}

/// The candidate's own estimates (parameters after the `kept` base ones) with standard errors,
/// and the parameters the Jacobian cannot determine.
fn read_estimates(res: &mut CandidateResult, layout: &ParamLayout, run: &FitRun, kept: usize) {
    let p = layout.len();
    let dof = (run.residuals.len() - p).max(1);
    let (lo, hi) = (layout.lower(), layout.upper());
    let ranges: Vec<f64> = (0..p).map(|j| hi[j] - lo[j]).collect();
    let cov = covariance(&run.jacobian, run.cost / dof as f64, &ranges);
    let labels = layout.labels();
    res.unidentified = cov
        .identifiability
        .unidentified()
        .into_iter()
        .map(|j| labels[j].clone())
        .collect();
    res.params = layout
        .params()
        .enumerate()
        .skip(kept)
        .map(|(j, (i, s))| ParamEstimate {
            effect: layout.effects()[i].kind.name(),
            group: layout.effects()[i].group.clone(),
            param: s.key,
            unit: s.unit,
            value: run.theta[j],
            stderr: cov.stderr[j],
            at_bound: false,
        })
        .collect();
}

/// A fitted impact-noise candidate: its index among the noise options and the refitted base
/// parameters (`None` when the fit failed).
pub(super) type NoiseFit = Option<(usize, DVector<f64>)>;

/// A fitted impact-noise level: cross-validated χ², launch errors on all shots (file units)
/// and the refitted base parameters.
type NoiseOutcome = (f64, Vec<[f64; 5]>, DVector<f64>);

/// Label of the measurement candidate for impact-location noise `noise`.
pub fn impact_noise_label(noise: &ImpactNoise) -> String {
    format!(
        "impact_noise({}, {} mm)",
        noise.sigma_y_m * 1e3,
        noise.sigma_z_m * 1e3
    )
}

/// One impact-noise level as a candidate: refit the base effects with the locations treated as
/// noisy, cross-validate, and score it as a one-parameter candidate: by the gain in `−2 ln L`
/// of the errors' spread when the instruments' noise is known ([`super::spread`]), else by the
/// gain in cross-validated χ² like an effect.
pub(super) fn noise_candidate(
    b: &StepBase,
    (j, noise, data, folds): (usize, &ImpactNoise, &FitData, &Folds),
    penalty_per_param: f64,
) -> (CandidateResult, NoiseFit) {
    measurement_candidate(
        b,
        (j, impact_noise_label(noise), data, folds),
        Some(noise),
        penalty_per_param,
    )
}

/// A measurement candidate labelled `label` whose data (`data`, `folds`) carry its noise model:
/// refit the base effects on them and score it as a one-parameter candidate, by the spread when
/// it is an impact-noise level (`spread_noise`) and the instruments' noise is known, else by
/// the gain in cross-validated χ².
pub(super) fn measurement_candidate(
    b: &StepBase,
    (j, label, data, folds): (usize, String, &FitData, &Folds),
    spread_noise: Option<&ImpactNoise>,
    penalty_per_param: f64,
) -> (CandidateResult, NoiseFit) {
    let mut res = empty_result(label, 1, penalty_per_param);
    res.converged = true;
    let outcome = (|| -> Result<NoiseOutcome, FitError> {
        if crate::cancel::cancelled(b.cancel) {
            return Err(FitError::Cancelled);
        }
        let run = if b.layout.is_empty() {
            None
        } else {
            let run = fit(b.club, b.layout, data, b.w, b.theta, b.max_iters)?;
            if !run.converged {
                return Err(FitError::NotConverged {
                    iterations: run.iterations,
                    chi2: run.cost,
                    stage: "measurement candidate".into(),
                });
            }
            Some(run)
        };
        let theta = run
            .as_ref()
            .map_or_else(|| b.theta.clone(), |r| r.theta.clone());
        let errs =
            FitProblem::new(b.club, b.layout.clone(), data, b.w).launch_errors(theta.as_slice())?;
        let cv = cv_chi2(
            b.club,
            b.layout,
            folds,
            b.w,
            &theta,
            run.as_ref().map(|r| (&r.residuals, &r.jacobian)),
            b.max_iters,
            b.progress,
            b.cancel,
        )?;
        Ok((cv, errs, theta))
    })();
    match outcome {
        Ok((cv, errs, theta)) => {
            let rms = rms_per_component(&errs);
            res.cv_chi2 = cv;
            res.gain = b.cv - cv;
            if let (Some((model, base_dev)), Some(noise)) = (b.spread, spread_noise) {
                match model.deviance(&errs, Some(*noise)) {
                    Some(dev) => {
                        res.spread_gain = Some(base_dev - dev);
                        res.gain = base_dev - dev;
                    }
                    None => {
                        res.failure =
                            Some("the spread's covariance is not positive definite".into())
                    }
                }
            }
            res.rms_reduction = std::array::from_fn(|c| (b.rms[c] - rms[c]) / b.rms[c]);
            (res, Some((j, theta)))
        }
        Err(e) => {
            res.converged = false;
            res.failure = Some(e.to_string());
            (res, None)
        }
    }
}

/// The final model with the selected effect `out` swapped for the candidate `inn`, fitted on
/// all shots: the candidate's estimates and the swapped model's `χ² + k·ln n` minus the final
/// model's (`final_score`). `None` when the swap cannot be fitted or does not converge.
pub(super) fn swap_score(
    b: &StepBase,
    out: &EffectRequest,
    inn: &EffectRequest,
    penalty_per_param: f64,
    final_score: f64,
) -> Option<(Vec<ParamEstimate>, f64)> {
    let mut effects = Vec::new();
    let mut start = Vec::new();
    for (i, e) in b.layout.effects().iter().enumerate() {
        if e.kind != out.kind() {
            effects.push(e.clone());
            start.extend_from_slice(&b.theta.as_slice()[b.layout.range(i)]);
        }
    }
    let kept = start.len();
    let added = inn.expand(&b.data.groups).ok()?;
    for e in &added {
        start.extend(e.kind.params().iter().map(|s| s.default));
    }
    effects.extend(added);
    let layout = ParamLayout::new(effects).ok()?;
    let run = fit(
        b.club,
        &layout,
        b.data,
        b.w,
        &DVector::from_vec(start),
        b.max_iters,
    )
    .ok()?;
    if !run.converged {
        return None;
    }
    let mut res = empty_result(inn.label(), 0, 0.0);
    read_estimates(&mut res, &layout, &run, kept);
    let score = run.cost + layout.len() as f64 * penalty_per_param;
    Some((res.params, score - final_score))
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::fit::spec::parse_effect_list;

    /// The paper world with `golfers` golfers per shaft, as shots.
    pub(super) fn world(golfers: usize) -> (ClubSpec, Vec<crate::model::Shot>) {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut cfg = crate::synth::read_config(&root.join("configs/synth/paper_world.toml"))
            .expect("paper world reads");
        cfg.golfers = golfers;
        let club = crate::data::club_file::read_club(&root.join("configs/clubs/paper_driver.toml"))
            .expect("club reads");
        let run = crate::synth::generate(&cfg, &club).expect("world generates");
        (club, run.shots.iter().map(|s| s.to_shot()).collect())
    }

    /// A fold's fit given the rows of the all-shots fit's residuals and Jacobian is the same
    /// fit, bit for bit, as one that evaluates its own start; cross-validation, which keeps
    /// those rows' Jacobian for the folds' steps ([`crate::fit::run_lm_point_near`]), gives the
    /// cross-validated χ² of the folds' own fits to 1e-5 relative (7e-7 measured: 0.001 of a
    /// χ² of 1541, where a candidate's penalty is about 12): with exact locations (one
    /// site a shot, serial evaluation) and with impact-location noise (nine sites a shot,
    /// evaluated in parallel chunks), from the all-shots solution and from a base point
    /// evaluated afresh.
    #[test]
    fn folds_started_from_the_all_shots_rows_give_the_same_cv() {
        let (club, shots) = world(10);
        let fold_of: Vec<usize> = (0..shots.len()).map(|i| (i / 10) % 5).collect();
        let layout = ParamLayout::from_requests(
            &parse_effect_list("added_mass@group,ball_offset").unwrap(),
            &FitData::from_shots(&shots).unwrap().groups,
        )
        .unwrap();
        for noise in [None, Some(ImpactNoise::from_mm(2.0, 2.0).unwrap())] {
            let data = FitData::from_shots(&shots)
                .unwrap()
                .with_impact_noise(noise)
                .unwrap();
            let folds = make_folds(&data, &fold_of, 5);
            let w = Weighting::launch(&[1.4, 1.0, 0.7, 400.0, 190.0]);
            let run = fit(&club, &layout, &data, w, &layout.defaults(), 100).unwrap();
            let cv = |start: &DVector<f64>, at: Option<AllShots>| {
                cv_chi2(&club, &layout, &folds, w, start, at, 100, None, None).unwrap()
            };
            // The first fold's fit with and without its rows given: the same point, one
            // residual and one Jacobian evaluation (2 per parameter) fewer.
            let pr = || FitProblem::new(&club, layout.clone(), &folds.train[0], w);
            let rows = fold_rows(
                (&run.residuals, &run.jacobian),
                &folds.train_idx[0],
                w.rows_per_shot(),
            );
            let own = crate::fit::run::execute(pr(), &run.theta, 100, None, false, None).unwrap();
            let given =
                crate::fit::run::execute(pr(), &run.theta, 100, None, false, Some(rows)).unwrap();
            assert_eq!(given.theta, own.theta);
            assert_eq!(given.cost.to_bits(), own.cost.to_bits());
            assert_eq!(given.iterations, own.iterations);
            assert_eq!(
                given.evaluations + 1 + 2 * layout.len() as u64,
                own.evaluations
            );
            let close = |own: f64, near: f64| {
                assert!(
                    (near - own).abs() <= 1e-5 * own,
                    "noise {noise:?}: {near} against {own}"
                );
            };
            let plain = cv(&run.theta, None);
            close(plain, cv(&run.theta, Some((&run.residuals, &run.jacobian))));
            // A point that is not a fit's solution, evaluated on all shots.
            let start = layout.defaults();
            let at = all_shots_at(&club, &layout, &data, w, &start).unwrap();
            close(cv(&start, None), cv(&start, Some((&at.0, &at.1))));
        }
    }

    /// The launch errors, now evaluated on the lanes, agree with solving each shot afresh by
    /// the scalar solve to 1e-9 relative (of the component's scale).
    #[test]
    fn launch_errors_agree_with_the_scalar_solve() {
        let (club, shots) = world(4);
        let data = FitData::from_shots(&shots).unwrap();
        let layout = ParamLayout::new(Vec::new()).unwrap();
        let errors = FitProblem::new(&club, layout, &data, Weighting::launch(&[1.0; 5]))
            .launch_errors(&[])
            .unwrap();
        assert_eq!(errors.len(), shots.len());
        for (s, e) in shots.iter().zip(&errors) {
            let model = club.model_for_group(&s.group).unwrap();
            let launch = model.solve(&s.delivery).unwrap().launch().to_file_units();
            let measured = s.measured.unwrap().to_file_units();
            for c in 0..5 {
                let want = launch[c] - measured[c];
                let tol = 1e-9 * launch[c].abs().max(1.0);
                assert!(
                    (e[c] - want).abs() <= tol,
                    "shot {}: {} vs {want}",
                    s.id,
                    e[c]
                );
            }
        }
    }
}
