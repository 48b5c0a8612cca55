//! Diagnosis: which effects of the library does the data ask for?
//!
//! Forward selection with cross-validation grouped by golfer:
//!
//! 1. Start from the club as given (base model `B`, no free parameters).
//! 2. Each step, estimate the noise scales `σ_c` from the base model's errors (robust scale,
//!    so a bias does not inflate them) and whiten the residuals with them.
//! 3. For every candidate `C` not yet selected (each library effect as one global effect, plus
//!    `added_mass@group`), fit `B ∪ C` on all shots (to report values, error reductions and
//!    identifiability) and on each training fold; sum the whitened χ² of each held-out fold:
//!    `CV(B ∪ C)`. The base `B` is cross-validated the same way.
//! 4. The gain `CV(B) − CV(B ∪ C)` must beat a BIC-sized penalty `k·ln n` (`k` added
//!    parameters, `n` shots), plus `2·ln m` for a physical candidate picked from the `m` offered
//!    (Bonferroni: the best of m useless candidates clears a threshold about m times as often
//!    as one does; impact-noise candidates keep `ln n`). Out of sample, a useless parameter *raises* χ² by about one, so
//!    pure noise practically never clears `ln 600 ≈ 6.4` per parameter, while a real 0.25 mph
//!    speed bias over 600 shots with 0.8 mph noise gains `600·0.25²/0.8² ≈ 59`.
//! 5. The best eligible candidate (its fit converged and every parameter is identifiable: no
//!    insensitive or collinear Jacobian column, see [`crate::fit::covariance`]) with a positive
//!    margin `gain − penalty` is added; repeat until none qualifies. Plausibility does not
//!    change the choice (the evidence does), except between aliases: when the best candidate's
//!    value is implausible and another qualifying candidate with a plausible value changes the
//!    predictions alike (correlation > 0.9, [`honest::signal_correlation`]), that one is taken
//!    and the pair reported. A selected value outside its plausible range is reported as a
//!    *stand-in* ([`honest`]), not a finding.
//! 6. With known instrument noise ([`DiagnoseOptions::noise_floor`]), each step first asks the
//!    [`noise_floor`] whether the current model's errors still carry structure beyond what the
//!    instruments explain; when they do not, no physical effect is offered (measurement
//!    candidates still are) and the selection stops. This is what keeps false discoveries
//!    rare in worlds whose delivery is measured with noise (`docs/diagnose-selection.md`).
//!
//! Once a global effect is selected, its per-group form (`added_mass@group`) stays a candidate
//! as a *refinement* that replaces it (gaining `groups − 1` parameters); other kinds already
//! selected are not offered again.
//!
//! Folds keep each golfer's shots together, so an effect cannot win by fitting one golfer's
//! habits. Without a golfer column the folds are by shot, with a warning.

pub mod honest;
pub mod noise_floor;

use std::sync::Arc;

use nalgebra::DVector;
use rayon::prelude::*;

use crate::club::ClubSpec;
use crate::effects::{EffectId, EffectKind};
use crate::fit::calibrate::{calibrate_data, noise_scales, CalibrateOptions, ParamEstimate};
use crate::fit::covariance::covariance;
use crate::fit::{
    run_lm, run_lm_point, EffectRequest, FitData, FitError, FitProblem, FitRun, ParamLayout,
    Progress, Weighting,
};
use crate::measurement::ImpactNoise;
use crate::model::Shot;
use crate::physics::LaunchComponent;
use crate::stats::{self, launch_error_table, ErrorTable};

/// Options of [`diagnose`].
#[derive(Debug, Clone, PartialEq)]
pub struct DiagnoseOptions {
    /// Number of cross-validation folds.
    pub folds: usize,
    /// Most effects to select.
    pub max_steps: usize,
    /// Iteration limit of each fit.
    pub max_iters: u64,
    /// Candidates; `None`: every library effect plus `added_mass@group` when there are groups.
    pub candidates: Option<Vec<EffectRequest>>,
    /// Noise of the measured impact locations, corrected by regression calibration. `None`:
    /// unknown, and (with `estimate_impact_noise`) offered as a measurement candidate.
    pub impact_noise: Option<crate::measurement::ImpactNoise>,
    /// When `impact_noise` is `None`, offer these isotropic impact-location noise levels (mm)
    /// as candidates beside the effects (see [`diagnose`]); empty: assume exact locations.
    pub impact_noise_candidates_mm: Vec<f64>,
    /// Known instrument noise: physical effects are offered only while the current model's
    /// errors show structure above this noise floor (see [`noise_floor`]). `None`: the
    /// penalty alone decides.
    pub noise_floor: Option<noise_floor::InstrumentNoise>,
}

/// Impact-location noise levels (1σ, mm, both axes) that diagnose tries by default: from a
/// motion-capture system (about 1 mm) to a launch monitor's face-impact estimate (3 mm).
pub const DEFAULT_IMPACT_NOISE_CANDIDATES_MM: [f64; 4] = [1.0, 1.5, 2.0, 3.0];

impl Default for DiagnoseOptions {
    fn default() -> Self {
        Self {
            folds: 5,
            max_steps: 6,
            max_iters: 100,
            candidates: None,
            impact_noise: None,
            impact_noise_candidates_mm: DEFAULT_IMPACT_NOISE_CANDIDATES_MM.to_vec(),
            noise_floor: None,
        }
    }
}

/// How the folds were formed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FoldBy {
    /// A golfer's shots are all in one fold.
    Golfer,
    /// Shot by shot (no golfer column).
    Shot,
}

/// One candidate at one step.
#[derive(Debug, Clone, PartialEq)]
pub struct CandidateResult {
    /// `name` or `name@group`.
    pub label: String,
    /// Parameters it adds.
    pub n_params: usize,
    /// Its parameters fitted on all shots (with the base effects refitted jointly).
    pub params: Vec<ParamEstimate>,
    /// Cross-validated χ² of the base plus this candidate.
    pub cv_chi2: f64,
    /// `CV(base) − CV(base + candidate)`.
    pub gain: f64,
    /// `k·ln n`.
    pub penalty: f64,
    /// Relative reduction of the RMS error per launch component on all shots (0.1 = 10 %).
    pub rms_reduction: [f64; 5],
    /// Parameters (labels) that cannot be determined: insensitive or collinear columns.
    pub unidentified: Vec<String>,
    /// Did the all-shots fit converge?
    pub converged: bool,
    /// Why the candidate could not be fitted, if so.
    pub failure: Option<String>,
}

impl CandidateResult {
    /// `gain − penalty`.
    pub fn margin(&self) -> f64 {
        self.gain - self.penalty
    }

    /// May it be selected (fitted, converged, identifiable)?
    pub fn eligible(&self) -> bool {
        self.failure.is_none() && self.converged && self.unidentified.is_empty()
    }

    /// Are all its fitted values inside their plausible ranges (a finding rather than a
    /// stand-in)? Parameters without a known range count as plausible.
    pub fn plausible(&self) -> bool {
        self.params
            .iter()
            .all(|p| honest::is_plausible(p).unwrap_or(true))
    }
}

/// One step of forward selection.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// Effects already in the model.
    pub base: Vec<String>,
    /// Noise scales used this step, file units.
    pub noise_scales: [f64; 5],
    /// Cross-validated χ² of the base model.
    pub base_cv_chi2: f64,
    /// Candidates, best margin first.
    pub candidates: Vec<CandidateResult>,
    /// The effect added, if any.
    pub selected: Option<String>,
    /// Errors on all shots of the model after this step.
    pub after: ErrorTable,
    /// With a known noise floor: the base model's errors were already at it, so no physical
    /// effect was offered this step (only measurement candidates).
    pub at_noise_floor: bool,
    /// When the best candidate's value was implausible and a plausible candidate explained the
    /// same signal (an alias, see [`honest::ExplainedAlias`]), the pair; the plausible one was
    /// selected.
    pub alias: Option<honest::ExplainedAlias>,
}

/// The outcome of a diagnosis.
#[derive(Debug, Clone)]
pub struct Diagnosis {
    /// How folds were formed.
    pub fold_by: FoldBy,
    /// Number of folds.
    pub folds: usize,
    /// Shots.
    pub n_shots: usize,
    /// Steps, in order.
    pub steps: Vec<Step>,
    /// Selected effects in the order added (`name` or `name@group`).
    pub selected: Vec<String>,
    /// Final estimates of the selected effects (a full calibration).
    pub estimates: Vec<ParamEstimate>,
    /// Errors of the club as given.
    pub before: ErrorTable,
    /// Errors with the selected effects.
    pub after: ErrorTable,
    /// The club with the selected effects.
    pub club: ClubSpec,
    /// Impact-location noise the final model assumes: given by the user, or selected as a
    /// measurement candidate (`None`: locations taken as measured).
    pub impact_noise: Option<crate::measurement::ImpactNoise>,
    /// Was `impact_noise` selected from the data (rather than given)?
    pub impact_noise_estimated: bool,
    /// Warnings (e.g. folds by shot).
    pub warnings: Vec<String>,
    /// Pairs of final estimates the data cannot tell apart (|correlation| > 0.9).
    pub aliases: Vec<honest::Alias>,
}

/// Receives diagnose progress (the CLI draws a bar).
pub trait DiagnoseProgress: Sync {
    /// A step starts with `jobs` fits to do.
    fn step(&self, step: usize, jobs: usize);
    /// One fit finished.
    fn job_done(&self);
}

/// Library effects that are searched only when named with `--candidates`. None at present:
/// `cor_level`, `hosel_mass` and `cor_power` were here because they alias `added_mass` and
/// `cor_speed` on launch data alone; alias arbitration (a plausible alias is preferred to an
/// implausible best candidate, and the pair reported) made them default candidates.
pub const OPT_IN_CANDIDATES: [EffectKind; 0] = [];

/// Every library effect as a global candidate (except [`OPT_IN_CANDIDATES`]), plus
/// `added_mass@group` with several groups, plus every registered user-defined effect
/// (`crate::effects::user`: those of an effects file or club file the command read) as a
/// global candidate beside them.
pub fn default_candidates(groups: &[String]) -> Vec<EffectRequest> {
    let mut c: Vec<EffectRequest> = EffectKind::ALL
        .iter()
        .filter(|k| !OPT_IN_CANDIDATES.contains(k))
        .map(|&k| EffectRequest::Global(k.into()))
        .collect();
    if groups.len() > 1 {
        c.push(EffectRequest::PerGroup(EffectKind::AddedMass.into()));
    }
    c.extend(
        crate::effects::user::registered()
            .into_iter()
            .map(|u| EffectRequest::Global(EffectId::User(u))),
    );
    c
}

struct Folds {
    train: Vec<FitData>,
    test: Vec<FitData>,
}

fn make_folds(data: &FitData, fold_of: &[usize], n_folds: usize) -> Folds {
    let pick = |keep: &dyn Fn(usize) -> bool| {
        let idx: Vec<usize> = (0..data.len()).filter(|&i| keep(fold_of[i])).collect();
        data.subset(&idx)
    };
    Folds {
        train: (0..n_folds).map(|f| pick(&|g| g != f)).collect(),
        test: (0..n_folds).map(|f| pick(&|g| g == f)).collect(),
    }
}

fn fit(
    club: &ClubSpec,
    layout: &ParamLayout,
    data: &FitData,
    w: Weighting,
    start: &DVector<f64>,
    max_iters: u64,
) -> Result<FitRun, FitError> {
    let pr = FitProblem::new(club, layout.clone(), data, w);
    run_lm(pr, start, max_iters, None::<(&Arc<dyn Progress>, &str)>)
}

fn chi2_at(
    club: &ClubSpec,
    layout: &ParamLayout,
    data: &FitData,
    w: Weighting,
    theta: &DVector<f64>,
) -> Result<f64, FitError> {
    let pr = FitProblem::new(club, layout.clone(), data, w);
    Ok(pr.residuals(theta.as_slice())?.norm_squared())
}

/// Cross-validated χ²: fit on each training fold from `start`, sum held-out χ².
fn cv_chi2(
    club: &ClubSpec,
    layout: &ParamLayout,
    folds: &Folds,
    w: Weighting,
    start: &DVector<f64>,
    max_iters: u64,
    progress: Option<&dyn DiagnoseProgress>,
) -> Result<f64, FitError> {
    let parts: Vec<Result<f64, FitError>> = (0..folds.train.len())
        .into_par_iter()
        .map(|f| {
            let r = if layout.is_empty() {
                chi2_at(club, layout, &folds.test[f], w, start)
            } else {
                // Only the fold's solution is needed: no Jacobian at it.
                let pr = FitProblem::new(club, layout.clone(), &folds.train[f], w);
                run_lm_point(pr, start, max_iters)
                    .and_then(|run| chi2_at(club, layout, &folds.test[f], w, &run.theta))
            };
            if let Some(p) = progress {
                p.job_done();
            }
            r
        })
        .collect();
    parts.into_iter().sum()
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

fn rms_per_component(errors: &[[f64; 5]]) -> [f64; 5] {
    std::array::from_fn(|c| stats::rms(&errors.iter().map(|e| e[c]).collect::<Vec<_>>()))
}

fn group_names(data: &FitData) -> Vec<String> {
    data.group_of
        .iter()
        .map(|&g| data.groups[g].clone())
        .collect()
}

fn request_label(r: &EffectRequest) -> String {
    r.label()
}

/// Run forward selection on `shots` (with measured launch) over `club`.
pub fn diagnose(
    club: &ClubSpec,
    shots: &[Shot],
    opts: &DiagnoseOptions,
    progress: Option<&dyn DiagnoseProgress>,
) -> Result<Diagnosis, FitError> {
    let data = FitData::from_shots(shots)?.with_impact_noise(opts.impact_noise)?;
    let n = data.len();
    let noise_given = opts.impact_noise.is_some();
    let mut warnings = Vec::new();
    let (fold_of, fold_by) = {
        let golfers: Vec<&str> = data
            .golfers
            .iter()
            .map(|g| g.as_deref().unwrap_or(""))
            .collect();
        let mut distinct = golfers.clone();
        distinct.sort_unstable();
        distinct.dedup();
        if data.has_golfers() && distinct.len() >= 2 {
            (stats::grouped_folds(&golfers, opts.folds), FoldBy::Golfer)
        } else {
            warnings.push(if data.has_golfers() {
                format!(
                    "every shot is from one golfer ('{}'): cross-validation folds cannot be \
                     grouped by golfer, so they are by shot, and an effect may win by fitting \
                     that golfer's habits",
                    distinct.first().copied().unwrap_or_default()
                )
            } else {
                "no golfer column: cross-validation folds are by shot, so a golfer's shots can \
                 be in both training and test folds"
                    .to_owned()
            });
            (stats::item_folds(n, opts.folds), FoldBy::Shot)
        }
    };
    let n_folds = fold_of.iter().max().map_or(1, |m| m + 1);
    if n_folds < 2 {
        return Err(FitError::TooFewShots {
            shots: n,
            params: 2,
        });
    }
    let mut folds = make_folds(&data, &fold_of, n_folds);
    // Impact-location noise levels offered as measurement candidates, each with its data.
    let mut noise_options: Vec<(ImpactNoise, FitData, Folds)> = Vec::new();
    if opts.impact_noise.is_none() {
        for &s_mm in &opts.impact_noise_candidates_mm {
            let noise = ImpactNoise::from_mm(s_mm, s_mm)?;
            match data.clone().with_impact_noise(Some(noise)) {
                Ok(d) => {
                    let f = make_folds(&d, &fold_of, n_folds);
                    noise_options.push((noise, d, f));
                }
                Err(e) => warnings.push(format!("impact noise {s_mm} mm not tried: {e}")),
            }
        }
    }
    let mut chosen_noise: Option<ImpactNoise> = opts.impact_noise;
    let mut data = data;
    let candidates = opts
        .candidates
        .clone()
        .unwrap_or_else(|| default_candidates(&data.groups));
    // Validate the candidates against the groups up front.
    for (i, c) in candidates.iter().enumerate() {
        c.expand(&data.groups)?;
        if candidates[..i].contains(c) {
            return Err(FitError::BadEffectList(format!(
                "candidate '{}' is listed twice",
                c.label()
            )));
        }
    }
    // Degenerate data are named, not fitted (see `crate::fit::variation`).
    let unidentifiable = crate::fit::variation::check_variation(shots, &candidates)?;
    if opts.candidates.is_some() {
        if let Some((_, why)) = unidentifiable.first() {
            return Err(FitError::Degenerate(why.clone()));
        }
    }
    let candidates: Vec<EffectRequest> = candidates
        .into_iter()
        .filter(|c| !unidentifiable.iter().any(|(u, _)| u == c))
        .collect();
    warnings.extend(
        unidentifiable
            .into_iter()
            .map(|(_, why)| format!("not tried: {why}")),
    );
    let penalty_per_param = (n as f64).ln();
    let groups = group_names(&data);

    let mut base = ParamLayout::new(Vec::new())?;
    let mut theta_base = DVector::<f64>::zeros(0);
    let mut selected: Vec<EffectRequest> = Vec::new();
    let nominal_errors = FitProblem::new(club, base.clone(), &data, Weighting::launch(&[1.0; 5]))
        .launch_errors(&[])?;
    let before = launch_error_table(&groups, &nominal_errors);
    let mut steps = Vec::new();

    for step_index in 0..opts.max_steps {
        let base_labels: Vec<String> = selected.iter().map(request_label).collect();
        let base_problem = FitProblem::new(club, base.clone(), &data, Weighting::launch(&[1.0; 5]));
        let base_errors = base_problem.launch_errors(theta_base.as_slice())?;
        // With a known noise floor, physics is offered only while structure remains above it.
        let at_noise_floor = match &opts.noise_floor {
            Some(inst) => {
                let mut effects = club.effects.clone();
                effects.extend(
                    base.to_effects(theta_base.as_slice())
                        .map_err(|e| FitError::Solver(format!("base effects: {e}")))?,
                );
                let base_club = club
                    .with_effects(effects)
                    .map_err(|e| FitError::Solver(format!("base club: {e}")))?;
                !noise_floor::noise_floor_of(&base_club, shots, &base_errors, inst, chosen_noise)?
                    .structure_remains()
            }
            None => false,
        };
        // A kind already selected is not offered again, except that a selected global effect
        // may be refined into one per group (replacing it).
        let open: Vec<&EffectRequest> = candidates
            .iter()
            .filter(|_| !at_noise_floor)
            .filter(|c| {
                !selected.iter().any(|s| {
                    s.kind() == c.kind()
                        && !(matches!(s, EffectRequest::Global(_))
                            && matches!(c, EffectRequest::PerGroup(_)))
                })
            })
            .collect();
        if open.is_empty() && (chosen_noise.is_some() || noise_options.is_empty()) {
            if at_noise_floor {
                steps.push(Step {
                    base: base_labels,
                    noise_scales: noise_scales(&base_errors),
                    base_cv_chi2: f64::NAN,
                    candidates: Vec::new(),
                    selected: None,
                    after: launch_error_table(&groups, &base_errors),
                    at_noise_floor,
                    alias: None,
                });
            }
            break;
        }
        let sigma = noise_scales(&base_errors);
        let w = Weighting::launch(&sigma);
        let base_rms = rms_per_component(&base_errors);
        if let Some(p) = progress {
            p.step(step_index + 1, n_folds * (1 + open.len()) + open.len());
        }
        // Choosing the best of `m` physical candidates: a useless candidate's out-of-sample gain
        // has an upper tail of about e^(−g/2), so the best of m clears a threshold c with
        // probability about m·e^(−c/2); adding 2·ln m to every physical candidate's penalty
        // keeps that what a single candidate has (a Bonferroni correction of the BIC penalty,
        // docs/diagnose-selection.md). The impact-noise levels are one measurement question
        // asked at several sizes, not m physical claims, and keep the plain penalty.
        let multiplicity = 2.0 * (open.len().max(1) as f64).ln();
        let base_cv = cv_chi2(
            club,
            &base,
            &folds,
            w,
            &theta_base,
            opts.max_iters,
            progress,
        )?;

        // Phase 1: every candidate on all shots.
        let layouts: Vec<Result<CandidateLayout, FitError>> = open
            .iter()
            .map(|c| candidate_layout(&base, &theta_base, c, &data.groups))
            .collect();
        let full: Vec<Result<(ParamLayout, FitRun, usize), FitError>> = layouts
            .into_par_iter()
            .map(|l| {
                let l = l?;
                let run = fit(club, &l.layout, &data, w, &l.start, opts.max_iters);
                if let Some(p) = progress {
                    p.job_done();
                }
                Ok((l.layout, run?, l.kept))
            })
            .collect();
        // Phase 2: cross-validation of every candidate.
        let evaluated: Vec<(CandidateResult, Option<Vec<f64>>)> = open
            .par_iter()
            .zip(full.par_iter())
            .map(|(c, f)| {
                let k = match f {
                    // Parameters the model gains (a refinement replaces the global one).
                    Ok((l, _, _)) => l.len() - theta_base.len(),
                    Err(_) => 0,
                };
                let mut res = CandidateResult {
                    label: request_label(c),
                    n_params: k,
                    params: Vec::new(),
                    cv_chi2: f64::NAN,
                    gain: f64::NAN,
                    penalty: k as f64 * penalty_per_param + multiplicity,
                    rms_reduction: [0.0; 5],
                    unidentified: Vec::new(),
                    converged: false,
                    failure: None,
                };
                let (layout, run, kept) = match f {
                    Ok((l, r, k)) => (l, r, *k),
                    Err(e) => {
                        res.failure = Some(e.to_string());
                        if let Some(p) = progress {
                            (0..n_folds).for_each(|_| p.job_done());
                        }
                        return (res, None);
                    }
                };
                let mut explained = None;
                res.converged = run.converged;
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
                let pr = FitProblem::new(club, layout.clone(), &data, w);
                match pr.launch_errors(run.theta.as_slice()) {
                    Ok(errs) => {
                        let rms = rms_per_component(&errs);
                        res.rms_reduction =
                            std::array::from_fn(|c| (base_rms[c] - rms[c]) / base_rms[c]);
                        explained = Some(honest::explained_signal(&base_errors, &errs, &sigma));
                    }
                    Err(e) => res.failure = Some(e.to_string()),
                }
                match cv_chi2(
                    club,
                    layout,
                    &folds,
                    w,
                    &run.theta,
                    opts.max_iters,
                    progress,
                ) {
                    Ok(cv) => {
                        res.cv_chi2 = cv;
                        res.gain = base_cv - cv;
                    }
                    Err(e) => res.failure = Some(e.to_string()),
                }
                (res, explained)
            })
            .collect();
        let (mut results, explained): (Vec<CandidateResult>, Vec<Option<Vec<f64>>>) =
            evaluated.into_iter().unzip();

        // Measurement candidates: the same base model, with the measured impact locations
        // treated as noisy at each offered level (while no level has been chosen).
        let n_effects = results.len();
        let mut noise_fits: Vec<NoiseFit> = Vec::new();
        if chosen_noise.is_none() {
            let evaluated: Vec<(CandidateResult, NoiseFit)> = noise_options
                .par_iter()
                .enumerate()
                .map(|(j, (noise, nd, nf))| {
                    noise_candidate(
                        club,
                        &base,
                        &theta_base,
                        (j, noise, nd, nf),
                        (w, base_cv, &base_rms),
                        penalty_per_param,
                        opts.max_iters,
                        progress,
                    )
                })
                .collect();
            for (r, f) in evaluated {
                results.push(r);
                noise_fits.push(f);
            }
        }

        let mut order: Vec<usize> = (0..results.len()).collect();
        order.sort_by(|&a, &b| {
            let key = |r: &CandidateResult| {
                if r.margin().is_nan() {
                    f64::NEG_INFINITY
                } else {
                    r.margin()
                }
            };
            key(&results[b]).total_cmp(&key(&results[a]))
        });
        // The evidence (margin) decides, not plausibility: preferring a plausible candidate
        // with less evidence was tried and chains several plausible stand-ins to mimic one real
        // effect outside its plausible range. Implausible values are reported as stand-ins.
        let best = order
            .iter()
            .copied()
            .find(|&i| results[i].eligible() && results[i].margin() > 0.0);
        // Alias arbitration: when the best candidate lands on an implausible value and another
        // eligible candidate with a positive margin, a plausible value, explains the same
        // signal (the two fits change the predictions alike, correlation above
        // STRONG_CORRELATION), the data cannot tell them apart, and the plausible reading is
        // selected; the pair is reported. Only aliases are exchanged, so a real effect outside
        // its plausible range is not replaced by an unrelated plausible one.
        let (winner, alias) = match best {
            Some(b) if b < n_effects && !results[b].plausible() => {
                let alt = order.iter().copied().find_map(|i| {
                    let ok = i < n_effects
                        && i != b
                        && results[i].eligible()
                        && results[i].margin() > 0.0
                        && results[i].plausible();
                    if !ok {
                        return None;
                    }
                    let r = honest::signal_correlation(
                        explained[b].as_deref()?,
                        explained[i].as_deref()?,
                    );
                    (r > crate::fit::calibrate::STRONG_CORRELATION).then_some((i, r))
                });
                match alt {
                    Some((i, r)) => (
                        Some(i),
                        Some(honest::ExplainedAlias {
                            selected: results[i].label.clone(),
                            instead_of: results[b].label.clone(),
                            r,
                        }),
                    ),
                    None => (best, None),
                }
            }
            _ => (best, None),
        };
        let after;
        let chosen = match winner {
            Some(i) if i >= n_effects => {
                let (j, theta) = noise_fits[i - n_effects]
                    .clone()
                    .expect("eligible means fitted");
                let (noise, nd, nf) = noise_options.swap_remove(j);
                data = nd;
                folds = nf;
                chosen_noise = Some(noise);
                noise_options.clear();
                theta_base = theta;
                let errs = FitProblem::new(club, base.clone(), &data, w)
                    .launch_errors(theta_base.as_slice())?;
                after = launch_error_table(&groups, &errs);
                Some(results[i].label.clone())
            }
            Some(i) => {
                let (layout, run, _) = full[i].as_ref().expect("eligible means fitted");
                let errs = FitProblem::new(club, layout.clone(), &data, w)
                    .launch_errors(run.theta.as_slice())?;
                after = launch_error_table(&groups, &errs);
                base = layout.clone();
                theta_base = run.theta.clone();
                let refined = selected.iter().position(|s| s.kind() == open[i].kind());
                match refined {
                    Some(pos) => selected[pos] = open[i].clone(),
                    None => selected.push(open[i].clone()),
                }
                Some(results[i].label.clone())
            }
            None => {
                after = launch_error_table(&groups, &base_errors);
                None
            }
        };
        let sorted: Vec<CandidateResult> = order.iter().map(|&i| results[i].clone()).collect();
        steps.push(Step {
            base: base_labels,
            noise_scales: sigma,
            base_cv_chi2: base_cv,
            candidates: sorted,
            selected: chosen.clone(),
            after,
            at_noise_floor,
            alias,
        });
        if chosen.is_none() {
            break;
        }
    }

    let (estimates, after, out_club, aliases) = if base.is_empty() {
        (Vec::new(), before.clone(), club.clone(), Vec::new())
    } else {
        let cal = calibrate_data(
            club,
            &data,
            base.clone(),
            &CalibrateOptions {
                max_iters: opts.max_iters,
                ..CalibrateOptions::default()
            },
            None,
        )?;
        let aliases = honest::aliases(&cal.params, cal.correlation.as_ref());
        (cal.params, cal.after, cal.club, aliases)
    };
    Ok(Diagnosis {
        fold_by,
        folds: n_folds,
        n_shots: n,
        steps,
        selected: selected.iter().map(request_label).collect(),
        estimates,
        before,
        after,
        club: out_club,
        impact_noise: chosen_noise,
        impact_noise_estimated: chosen_noise.is_some() && !noise_given,
        warnings,
        aliases,
    })
}

/// A fitted impact-noise candidate: its index among the noise options and the refitted base
/// parameters (`None` when the fit failed).
type NoiseFit = Option<(usize, DVector<f64>)>;

/// Label of the measurement candidate for impact-location noise `noise`.
pub fn impact_noise_label(noise: &ImpactNoise) -> String {
    format!(
        "impact_noise({}, {} mm)",
        noise.sigma_y_m * 1e3,
        noise.sigma_z_m * 1e3
    )
}

/// One impact-noise level as a candidate: refit the base effects with the locations treated as
/// noisy, cross-validate, and score it like a one-parameter effect.
#[allow(clippy::too_many_arguments)]
fn noise_candidate(
    club: &ClubSpec,
    base: &ParamLayout,
    theta_base: &DVector<f64>,
    (j, noise, data, folds): (usize, &ImpactNoise, &FitData, &Folds),
    (w, base_cv, base_rms): (Weighting, f64, &[f64; 5]),
    penalty_per_param: f64,
    max_iters: u64,
    progress: Option<&dyn DiagnoseProgress>,
) -> (CandidateResult, NoiseFit) {
    let mut res = CandidateResult {
        label: impact_noise_label(noise),
        n_params: 1,
        params: Vec::new(),
        cv_chi2: f64::NAN,
        gain: f64::NAN,
        penalty: penalty_per_param,
        rms_reduction: [0.0; 5],
        unidentified: Vec::new(),
        converged: true,
        failure: None,
    };
    let outcome = (|| -> Result<(f64, [f64; 5], DVector<f64>), FitError> {
        let theta = if base.is_empty() {
            theta_base.clone()
        } else {
            let run = fit(club, base, data, w, theta_base, max_iters)?;
            if !run.converged {
                return Err(FitError::NotConverged {
                    iterations: run.iterations,
                    chi2: run.cost,
                    stage: "impact-noise candidate".into(),
                });
            }
            run.theta
        };
        let errs = FitProblem::new(club, base.clone(), data, w).launch_errors(theta.as_slice())?;
        let cv = cv_chi2(club, base, folds, w, &theta, max_iters, progress)?;
        Ok((cv, rms_per_component(&errs), theta))
    })();
    match outcome {
        Ok((cv, rms, theta)) => {
            res.cv_chi2 = cv;
            res.gain = base_cv - cv;
            res.rms_reduction = std::array::from_fn(|c| (base_rms[c] - rms[c]) / base_rms[c]);
            (res, Some((j, theta)))
        }
        Err(e) => {
            res.converged = false;
            res.failure = Some(e.to_string());
            (res, None)
        }
    }
}

/// Launch components in report order (re-exported for the CLI).
pub const COMPONENTS: [LaunchComponent; 5] = LaunchComponent::ALL;
