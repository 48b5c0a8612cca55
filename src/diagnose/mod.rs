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
//! 7. When forward selection stops, swap rounds ([`Step::swap`], `search/swap.rs`) while a
//!    selected value is a stand-in: removing it, replacing it by an unselected candidate, or
//!    exchanging it and an effect with kin for a pair, scored against the current model by the
//!    forward rule (gain in CV χ² against `(k_in − k_out)·ln n + 2·ln m`); the best change
//!    with a positive margin is made, then forward selection resumes (within `max_steps`
//!    forward steps). When no round pays, a re-selection (`search/reselect.rs`, once) takes the
//!    questioned effects (stand-ins and cross-effect aliases) out together and reruns forward
//!    selection, kept when CV χ² + `k·ln n` drops. Greedy order can leave a stand-in that won
//!    early (more parameters, more gain) where a plausible set fits better once later effects
//!    are in; these steps correct it. A stand-in may also give way to a plausible alias of the
//!    same size whose CV χ² is worse by less than `ln n` (`search/alias.rs`: the stand-in's
//!    model is charged one parameter for the physics its value stands for). The rounds run
//!    after a forward phase capped by `max_steps` too, and make at most `max_steps` changes.
//!    When nothing else changes the selection, backward elimination (`search/earned.rs`)
//!    removes an effect whose removal raises the held-out χ² by no more than its `k·ln n`
//!    (the one that falls shortest), and the rounds run again.
//!
//! Delivery noise (club speed, loft, path, face, ...) biases a model evaluated at the measured
//! delivery (errors in variables: flatter slopes than the model's), which over thousands of
//! shots an effect that bends the slopes would absorb. With known instrument noise the fits
//! evaluate the model at the conditional mean of the true delivery
//! ([`crate::measurement::DeliveryNoise`]); without it, delivery-noise levels compete as
//! measurement candidates like the impact-noise ones.
//!
//! Once a global effect is selected, its per-group form (`added_mass@group`) stays a candidate
//! as a *refinement* that replaces it (gaining `groups − 1` parameters); other kinds already
//! selected are not offered again.
//!
//! Folds keep each golfer's shots together, so an effect cannot win by fitting one golfer's
//! habits. Without a golfer column the folds are by shot, with a warning.

mod candidates;
mod evaluate;
pub mod honest;
pub mod noise_floor;
pub mod rival_family;
mod search;
pub mod select;
pub mod shared;
mod spread;
pub mod strata;

use crate::club::ClubSpec;
use crate::fit::calibrate::ParamEstimate;
use crate::fit::{EffectRequest, FitData, FitError, Likelihood};
use crate::model::Shot;
use crate::physics::LaunchComponent;
use crate::stats::{launch_error_table, ErrorTable};
pub use candidates::{default_candidates, default_candidates_without, OPT_IN_CANDIDATES};
pub use evaluate::impact_noise_label;

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
    /// When the instruments' noise is unknown (`noise_floor` is `None`), offer delivery-noise
    /// levels, these multiples of the camera class's delivery SDs, as measurement candidates
    /// (`docs/diagnose-selection.md`); empty: assume an exact delivery.
    pub delivery_noise_scales: Vec<f64>,
    /// Keys to group the folds by when the shots have no golfers (sessions, time blocks or
    /// clubs, read from the input's columns: [`crate::data::sessions`]); `None`: by shot.
    pub fold_keys: Option<crate::stats::FoldKeys>,
    /// A token the caller may cancel: the diagnosis checks it between fits and stops with
    /// [`FitError::Cancelled`]. `None`: it runs to its end.
    pub cancel: Option<crate::cancel::Cancel>,
}

/// Delivery-noise levels diagnose tries by default when the instruments' noise is unknown:
/// once and twice the camera class's delivery SDs (a launch monitor's club data to a
/// motion-capture rig like the paper's, 0.7 mph and 0.8° against 0.4 mph and 0.5°).
pub const DEFAULT_DELIVERY_NOISE_SCALES: [f64; 2] = [1.0, 2.0];

/// Impact-location noise levels (1σ, mm, both axes) that diagnose tries by default: from a
/// motion-capture system (about 1 mm) to a launch monitor's face-impact estimate (3 mm).
pub const DEFAULT_IMPACT_NOISE_CANDIDATES_MM: [f64; 4] = [1.0, 1.5, 2.0, 3.0];

impl DiagnoseOptions {
    /// The delivery noise the fits calibrate for: the known instruments' delivery SDs
    /// (`docs/diagnose-selection.md`, errors in the delivery variables); `None` when unknown.
    pub fn delivery_noise(&self) -> Option<crate::measurement::DeliveryNoise> {
        self.noise_floor
            .as_ref()
            .map(|i| crate::measurement::DeliveryNoise::new(i.delivery_sd))
    }
}

impl Default for DiagnoseOptions {
    fn default() -> Self {
        Self {
            folds: 5,
            max_steps: 10,
            max_iters: 100,
            candidates: None,
            impact_noise: None,
            impact_noise_candidates_mm: DEFAULT_IMPACT_NOISE_CANDIDATES_MM.to_vec(),
            noise_floor: None,
            delivery_noise_scales: DEFAULT_DELIVERY_NOISE_SCALES.to_vec(),
            fold_keys: None,
            cancel: None,
        }
    }
}

/// How the folds were formed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FoldBy {
    /// A golfer's shots are all in one fold.
    Golfer,
    /// A session's (a date's) shots are all in one fold (no golfers).
    Session,
    /// Blocks of consecutive shots by time of day, each in one fold (no golfers, one session).
    TimeBlock,
    /// A club's shots are all in one fold (no golfers, no dates or times).
    Club,
    /// Shot by shot (no golfer column, no date or time column).
    Shot,
}

impl FoldBy {
    /// Its name in reports: `golfer`, `session`, `time block`, `club`, `shot`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Golfer => "golfer",
            Self::Session => "session",
            Self::TimeBlock => "time block",
            Self::Club => "club",
            Self::Shot => "shot",
        }
    }
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
    /// `CV(base) − CV(base + candidate)`; for an impact-noise level scored by the spread
    /// (`spread_gain`), that gain instead.
    pub gain: f64,
    /// An impact-noise level's gain in `−2 ln L` of the errors' spread (known instrument
    /// noise, `docs/diagnose-selection.md`); `None` when scored by the cross-validated χ².
    pub spread_gain: Option<f64>,
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
    /// A removal row of a step table (a swap round's or backward elimination's): the model
    /// without `label`'s effects has CV χ² `cv_chi2`, `gain` against the current model, saves
    /// `penalty` (negative), and RMS errors `rms_after` against the current model's `rms_now`.
    pub(crate) fn removal(
        label: &str,
        (cv_chi2, gain, penalty): (f64, f64, f64),
        rms_now: &[f64; 5],
        rms_after: &[f64; 5],
    ) -> Self {
        CandidateResult {
            label: format!("remove {label}"),
            n_params: 0,
            params: Vec::new(),
            cv_chi2,
            gain,
            spread_gain: None,
            penalty,
            rms_reduction: std::array::from_fn(|c| (rms_now[c] - rms_after[c]) / rms_now[c]),
            unidentified: Vec::new(),
            converged: true,
            failure: None,
        }
    }

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
    /// Cross-validated χ² of the base model (`None` when the step scored no candidate: the
    /// errors were at the noise floor and nothing was offered).
    pub base_cv_chi2: Option<f64>,
    /// Candidates, best margin first.
    pub candidates: Vec<CandidateResult>,
    /// The effect added, if any.
    pub selected: Option<String>,
    /// Errors on all shots of the model after this step.
    pub after: ErrorTable,
    /// The likelihood score of the model after this step, on the diagnosis's one scale (the
    /// instruments' noise when known, else profiled; [`crate::fit::likelihood`]): comparable
    /// across steps, unlike the cross-validated χ² whose noise scales each step re-estimates.
    pub fit: Likelihood,
    /// With a known noise floor: the base model's errors were already at it, so no physical
    /// effect was offered this step (only measurement candidates).
    pub at_noise_floor: bool,
    /// When the best candidate's value was implausible and a plausible candidate explained the
    /// same signal (an alias, see [`honest::ExplainedAlias`]), the pair; the plausible one was
    /// selected.
    pub alias: Option<honest::ExplainedAlias>,
    /// Unselected candidates that explained nearly the same signal as the selected effect
    /// ([`select::rivals`]), best first.
    pub rivals: Vec<honest::Rival>,
    /// The effect candidates whose change to the predictions was most like the selected
    /// effect's at this step, with that correlation ([`select::most_alike`], at most
    /// [`select::MOST_ALIKE`], most alike first): the measured reading of what the selected
    /// effect could be standing in for.
    pub alike: Vec<(String, f64)>,
    /// For a swap step (after forward selection stopped, see [`diagnose`]): the change made.
    /// Its `candidates` are then the removals (`remove name`) and replacements (`out → in`)
    /// tried, with gain `CV(current) − CV(changed)` and penalty `(k_in − k_out)·ln n` (plus
    /// `2·ln m` for a replacement); `selected` is `None`.
    pub swap: Option<Swap>,
}

/// A change the swap phase made to the selected effects.
#[derive(Debug, Clone, PartialEq)]
pub struct Swap {
    /// The effects taken out (labels joined by ` + `).
    pub out: String,
    /// The effects put in their place (joined by ` + `); `None`: removed.
    pub inn: Option<String>,
    /// Cross-validated χ² before and after the change (the same noise scales).
    pub cv_before: f64,
    /// See `cv_before`.
    pub cv_after: f64,
}

impl Swap {
    /// "swap com_offset → hosel_mass, CV χ² 3019.7 → 2990.1" or "remove ...".
    pub fn text(&self) -> String {
        let what = match &self.inn {
            Some(inn) => format!("swap {} → {inn}", self.out),
            None => format!("remove {}", self.out),
        };
        format!("{what}, CV χ² {:.1} → {:.1}", self.cv_before, self.cv_after)
    }
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
    /// Delivery noise (other than the impact location) the final model is calibrated for
    /// ([`crate::measurement::DeliveryNoise`]; `None`: deliveries taken as measured).
    pub delivery_noise: Option<crate::measurement::DeliveryNoise>,
    /// Was `delivery_noise` selected from the data (rather than given)?
    pub delivery_noise_estimated: bool,
    /// Warnings (e.g. folds by shot).
    pub warnings: Vec<String>,
    /// Pairs of final estimates the data cannot tell apart (|correlation| > 0.9).
    pub aliases: Vec<honest::Alias>,
    /// Each selected effect that had rivals at its step, with them; those whose readings are
    /// all plausible are ambiguous ([`honest::Ambiguity::is_ambiguous`]), not findings.
    pub ambiguities: Vec<honest::Ambiguity>,
    /// Why the shots do not match the club file, when the caller ran anyway
    /// ([`crate::club_match`]): then no estimate is a finding.
    pub club_mismatch: Option<String>,
    /// The club as given, scored on the same scale as [`Step::fit`].
    pub nominal_fit: Likelihood,
    /// The final model (the reported values), scored on the same scale.
    pub final_fit: Likelihood,
    /// The final model refitted on independent strata of the shots, and whether each value
    /// holds across them ([`strata`]; `None` when nothing is selected).
    pub strata: Option<strata::StrataCheck>,
    /// Estimates whose signal trends with structure the final model leaves ([`shared`]): set
    /// by the caller once the noise floor is known (empty until then).
    pub shared_signals: Vec<shared::SharedSignal>,
    /// Each selected effect's held-out gain over its rival family ([`rival_family`]).
    pub rival_families: Vec<rival_family::FamilyCheck>,
    /// What the data nearly show ([`honest::Unresolved`]).
    pub unresolved: Option<honest::Unresolved>,
}

impl Diagnosis {
    /// Is this final estimate a finding: plausible (or of unknown range), not absent (on a
    /// bound that means "no effect", [`honest::is_absent`]), not part of an ambiguous
    /// selection, and not aliased with another selected effect's parameter (the data cannot
    /// tell which of the two effects carries the signal, so neither value is a reading of the
    /// physics; `docs/diagnose-selection.md`, "Aliased absent pairs")?
    /// It must also hold across the strata of the shots ([`strata`]): else it is
    /// [`Self::provisional`].
    pub fn is_finding(&self, p: &ParamEstimate) -> bool {
        self.passes_report_checks(p) && self.provisional(p).is_none()
    }

    /// When this estimate would be a finding but its value differs across the strata of the
    /// shots beyond its uncertainty ([`strata`]): the failed check, as text.
    /// Also when its signal shares the trend of structure the final model leaves
    /// ([`Self::shared_signals`]), and when another parameter of the same effect (and group)
    /// fails either check or is a stand-in: an effect that drifts, or stands in for other
    /// physics, in one of its parameters is compensating for something, so none of its values
    /// is a reading of the head (as with aliases, every parameter of the effect is in doubt).
    pub fn provisional(&self, p: &ParamEstimate) -> Option<String> {
        if !self.passes_report_checks(p) {
            return None;
        }
        let label = p.label();
        self.own_check_failed(p).or_else(|| {
            self.estimates
                .iter()
                .filter(|s| s.effect == p.effect && s.group == p.group && s.param != p.param)
                .find_map(|s| {
                    if honest::is_plausible(s) == Some(false) {
                        Some(format!(
                            "{label}: {} of the same effect is a stand-in",
                            s.label()
                        ))
                    } else if self.passes_report_checks(s) {
                        self.own_check_failed(s)
                            .map(|why| format!("{label}: the same effect's {why}"))
                    } else {
                        None
                    }
                })
        })
    }

    /// The candidates whose change to the predictions was most like that of `p`'s effect at
    /// the step that selected it, with the correlation (empty when none was measured).
    pub fn alike(&self, p: &ParamEstimate) -> &[(String, f64)] {
        let label = match &p.group {
            Some(_) => format!("{}@group", p.effect),
            None => p.effect.to_owned(),
        };
        self.steps
            .iter()
            .find(|s| s.selected.as_deref() == Some(label.as_str()))
            .map_or(&[], |s| s.alike.as_slice())
    }

    /// The strata or shared-signal check this estimate itself fails, as text.
    fn own_check_failed(&self, p: &ParamEstimate) -> Option<String> {
        let label = p.label();
        let strata = self.strata.as_ref().and_then(|s| s.failed(&label));
        strata
            .or_else(|| {
                self.shared_signals
                    .iter()
                    .find(|s| s.label == label)
                    .map(|s| format!("{label}: {}", s.text()))
            })
            .or_else(|| {
                self.rival_families
                    .iter()
                    .find(|f| f.is_stand_in() && rival_family::estimate_of(p, &f.label))
                    .map(|f| format!("{label}: {}", f.text()))
            })
    }

    /// The checks of [`Self::is_finding`] but the strata's.
    fn passes_report_checks(&self, p: &ParamEstimate) -> bool {
        self.club_mismatch.is_none()
            && honest::is_plausible(p) != Some(false)
            && !honest::is_absent(p)
            && !honest::is_unchanged(p, self.estimates.len())
            && !self
                .ambiguities
                .iter()
                .any(|a| a.is_ambiguous() && a.estimates.contains(p))
            && !self.cross_aliased(p)
    }

    /// Is this final estimate's effect aliased (a parameter's |r| above
    /// [`crate::fit::calibrate::STRONG_CORRELATION`]) with a parameter of another selected
    /// effect? The question is which effect carries the signal, so every parameter of both
    /// effects is in doubt, not only the correlated pair.
    pub fn cross_aliased(&self, p: &ParamEstimate) -> bool {
        self.aliases.iter().any(|a| {
            a.across_effects()
                && [&a.a, &a.b]
                    .iter()
                    .any(|l| honest::effect_of_label(l) == p.effect)
        })
    }
}

/// Receives diagnose progress (the CLI draws a bar).
pub trait DiagnoseProgress: Sync {
    /// A step starts with `jobs` fits to do.
    fn step(&self, step: usize, jobs: usize);
    /// One fit finished.
    fn job_done(&self);
}

/// Run forward selection on `shots` (with measured launch) over `club`.
pub fn diagnose(
    club: &ClubSpec,
    shots: &[Shot],
    opts: &DiagnoseOptions,
    progress: Option<&dyn DiagnoseProgress>,
) -> Result<Diagnosis, FitError> {
    let data = FitData::from_shots(shots)?
        .with_delivery_noise(opts.delivery_noise())
        .with_impact_noise(opts.impact_noise)?;
    let mut warnings = Vec::new();
    let (fold_of, fold_by) =
        search::fold_assignment(&data, opts.folds, opts.fold_keys.as_ref(), &mut warnings);
    let n_folds = fold_of.iter().max().map_or(1, |m| m + 1);
    if n_folds < 2 {
        return Err(FitError::TooFewShots {
            shots: data.len(),
            params: 2,
        });
    }
    let candidates = search::offered_candidates(opts, &data, shots, &mut warnings)?;
    let mut search = search::Search::new(
        club,
        shots,
        opts,
        progress,
        data,
        (&fold_of, n_folds),
        &mut warnings,
    )?;
    let nominal = search.errors_of(&search.base, &[])?;
    let before = launch_error_table(&search.groups, &nominal);
    // Scored before any step chooses a noise level (which would be counted as a parameter).
    let nominal_fit = search.likelihood_of(&nominal);
    let mut steps = Vec::new();
    // Forward steps (at most `max_steps`), then swap rounds (or a re-selection) while one
    // improves, then forward again while steps are left. The step cap bounds run time, not the
    // selection: the rounds run after a capped forward phase too, and are themselves bounded
    // by `max_steps` changes (each round fits every questioned effect against every candidate).
    let mut forward = 0;
    let mut changes = 0;
    let mut checked = Vec::new();
    let halt = || {
        if crate::cancel::cancelled(opts.cancel.as_ref()) {
            Err(FitError::Cancelled)
        } else {
            Ok(())
        }
    };
    loop {
        halt()?;
        while forward < opts.max_steps {
            halt()?;
            forward += 1;
            let Some(step) = search.step(steps.len(), &candidates)? else {
                break;
            };
            let stop = step.selected.is_none();
            steps.push(step);
            if stop {
                break;
            }
        }
        if changes >= opts.max_steps {
            if search.has_stand_in() {
                warnings.push(format!(
                "the swap rounds stopped after {changes} changes (--max-steps bounds them too): \
                 a further round might still change the selection"
                ));
            }
            break;
        }
        halt()?;
        if let Some(step) = search.swap_round(&candidates)? {
            steps.push(step);
            changes += 1;
            continue;
        }
        // No single or pair change pays: the last resort, re-selection (`search/reselect.rs`).
        halt()?;
        let Some(more) = search.reselect(&candidates, steps.len())? else {
            halt()?;
            // Backward elimination: an effect the final model does not need is removed, and
            // the rounds run again on the smaller model (`search/earned.rs`).
            if let Some(step) = search.prune()? {
                steps.push(step);
                changes += 1;
                continue;
            }
            // The selection stands unless its final fit shows a stand-in the rounds did not
            // see: then the rounds run on that fit (`search/final_fit.rs`).
            if search.adopt_final_stand_ins(&mut checked)? {
                warnings.push(
                    "the final fit (started afresh) showed a stand-in the rounds' fit did not: \
                     the swap rounds ran again on the final fit"
                        .to_owned(),
                );
                continue;
            }
            break;
        };
        steps.extend(more);
        changes += 1;
    }
    halt()?;
    search.finish(
        (fold_by, n_folds),
        steps,
        (before, nominal_fit),
        (warnings, &candidates),
    )
}

/// Launch components in report order (re-exported for the CLI).
pub const COMPONENTS: [LaunchComponent; 5] = LaunchComponent::ALL;
