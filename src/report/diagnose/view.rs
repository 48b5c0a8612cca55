//! The JSON of [`super::DiagnoseReport`] as a view model: [`DiagnoseView`], filled once from the
//! diagnosis and its noise floor with every verdict (each estimate's status and plausibility,
//! the stand-ins, ambiguities, aliases, provisional values) and serialised as it is.

use serde::Serialize;

use super::{calibrate_flags, conclusion, status, SCHEMA_VERSION};
use crate::diagnose::honest;
use crate::diagnose::noise_floor::NoiseFloor;
use crate::diagnose::Diagnosis;
use crate::fit::ParamEstimate;
use crate::report::location_mm;
use crate::report::views::{
    alike, components, delivery_noise, error_table, AliasView, Alike, AmbiguityView, ComponentMap,
    ErrorTableView, Estimate, ExplainedAliasView, FamilyCheckView, LikelihoodView, NoiseFloorView,
    RivalView, Score, StrataView, UnresolvedView,
};

/// An estimate with its plausibility and, in the final model, its status.
#[derive(Debug, Clone, Serialize)]
struct EstimateView {
    #[serde(flatten)]
    estimate: Estimate,
    #[serde(skip_serializing_if = "Option::is_none")]
    status: Option<&'static str>,
}

fn estimate(p: &ParamEstimate, status: Option<&'static str>) -> EstimateView {
    EstimateView {
        estimate: Estimate::of(p),
        status,
    }
}

/// A swap of a selected effect for a candidate.
#[derive(Debug, Clone, Serialize)]
struct SwapView {
    out: String,
    #[serde(rename = "in")]
    inn: Option<String>,
    cv_chi2_before: f64,
    cv_chi2_after: f64,
    text: String,
}

/// One candidate of a step.
#[derive(Debug, Clone, Serialize)]
struct CandidateView {
    effect: String,
    n_params: usize,
    cv_chi2: f64,
    gain: f64,
    score: &'static str,
    penalty: f64,
    margin: f64,
    eligible: bool,
    converged: bool,
    unidentified: Vec<String>,
    failure: Option<String>,
    rms_reduction: ComponentMap,
    params: Vec<EstimateView>,
}

/// One step of the selection.
#[derive(Debug, Clone, Serialize)]
struct StepView {
    step: usize,
    base: Vec<String>,
    noise_scales: ComponentMap,
    base_cv_chi2: Option<f64>,
    selected: Option<String>,
    swap: Option<SwapView>,
    at_noise_floor: bool,
    alias: Option<ExplainedAliasView>,
    rivals: Vec<RivalView>,
    candidates: Vec<CandidateView>,
    after: ErrorTableView,
    fit: Score,
}

/// The impact-location noise the model assumed, mm.
#[derive(Debug, Clone, Serialize)]
struct ImpactNoiseView {
    y: f64,
    z: f64,
    estimated: bool,
}

/// The delivery noise the model assumed.
#[derive(Debug, Clone, Serialize)]
struct DeliveryNoiseView {
    sd: std::collections::BTreeMap<&'static str, f64>,
    estimated: bool,
}

/// A value the strata found to differ, and the check it failed.
#[derive(Debug, Clone, Serialize)]
struct ProvisionalView {
    param: String,
    failed_check: String,
}

/// A value that stands in for physics the library lacks.
#[derive(Debug, Clone, Serialize)]
struct StandInView {
    param: String,
    value: f64,
    unit: &'static str,
    plausible_range: String,
    behaves_like: &'static str,
    most_alike: Vec<Alike>,
}

/// What `smash diagnose --json` prints (`docs/json.md`), filled once from the diagnosis with
/// its verdicts.
#[derive(Debug, Clone, Serialize)]
pub(super) struct DiagnoseView {
    schema_version: u32,
    command: &'static str,
    selected: Vec<String>,
    impact_noise_mm: Option<ImpactNoiseView>,
    delivery_noise: Option<DeliveryNoiseView>,
    calibrate_flags: String,
    estimates: Vec<EstimateView>,
    findings: Vec<String>,
    provisional: Vec<ProvisionalView>,
    strata: Option<StrataView>,
    ambiguous: Vec<AmbiguityView>,
    unresolved: Option<UnresolvedView>,
    rival_families: Vec<FamilyCheckView>,
    stand_ins: Vec<StandInView>,
    aliases: Vec<AliasView>,
    likelihood: LikelihoodView,
    noise_floor: NoiseFloorView,
    conclusion: String,
    steps: Vec<StepView>,
    folds: usize,
    fold_by: &'static str,
    club_mismatch: Option<String>,
    n_shots: usize,
    warnings: Vec<String>,
    before: ErrorTableView,
    after: ErrorTableView,
}

fn step_view(i: usize, s: &crate::diagnose::Step) -> StepView {
    StepView {
        step: i + 1,
        base: s.base.clone(),
        noise_scales: components(&s.noise_scales),
        base_cv_chi2: s.base_cv_chi2,
        selected: s.selected.clone(),
        swap: s.swap.as_ref().map(|w| SwapView {
            out: w.out.clone(),
            inn: w.inn.clone(),
            cv_chi2_before: w.cv_before,
            cv_chi2_after: w.cv_after,
            text: w.text(),
        }),
        at_noise_floor: s.at_noise_floor,
        alias: s.alias.as_ref().map(ExplainedAliasView::of),
        rivals: s.rivals.iter().map(RivalView::of).collect(),
        candidates: s
            .candidates
            .iter()
            .map(|c| CandidateView {
                effect: c.label.clone(),
                n_params: c.n_params,
                cv_chi2: c.cv_chi2,
                gain: c.gain,
                score: if c.spread_gain.is_some() {
                    "spread_likelihood"
                } else {
                    "cv_chi2"
                },
                penalty: c.penalty,
                margin: c.margin(),
                eligible: c.eligible(),
                converged: c.converged,
                unidentified: c.unidentified.clone(),
                failure: c.failure.clone(),
                rms_reduction: components(&c.rms_reduction),
                params: c.params.iter().map(|p| estimate(p, None)).collect(),
            })
            .collect(),
        after: error_table(&s.after),
        fit: Score::of(&s.fit),
    }
}

/// The view of the report (the JSON of [`DiagnoseReport`]).
pub(super) fn view(d: &Diagnosis, floor: &NoiseFloor) -> DiagnoseView {
    DiagnoseView {
        schema_version: SCHEMA_VERSION,
        command: "diagnose",
        selected: d.selected.clone(),
        impact_noise_mm: d.impact_noise.map(|n| ImpactNoiseView {
            y: location_mm(n.sigma_y_m),
            z: location_mm(n.sigma_z_m),
            estimated: d.impact_noise_estimated,
        }),
        delivery_noise: d
            .delivery_noise
            .filter(|n| n.is_active())
            .map(|n| DeliveryNoiseView {
                sd: delivery_noise(&n),
                estimated: d.delivery_noise_estimated,
            }),
        calibrate_flags: calibrate_flags(d),
        estimates: d
            .estimates
            .iter()
            .map(|p| estimate(p, Some(status(d, p))))
            .collect(),
        findings: d
            .estimates
            .iter()
            .filter(|p| d.is_finding(p))
            .map(|p| p.label())
            .collect(),
        provisional: d
            .estimates
            .iter()
            .filter_map(|p| {
                d.provisional(p).map(|why| ProvisionalView {
                    param: p.label(),
                    failed_check: why,
                })
            })
            .collect(),
        strata: d.strata.as_ref().map(StrataView::of),
        ambiguous: d.ambiguities.iter().map(AmbiguityView::of).collect(),
        unresolved: d.unresolved.as_ref().map(UnresolvedView::of),
        rival_families: d.rival_families.iter().map(FamilyCheckView::of).collect(),
        stand_ins: d
            .estimates
            .iter()
            .filter_map(|p| {
                honest::stand_in(p).map(|w| StandInView {
                    param: p.label(),
                    value: p.value,
                    unit: p.unit,
                    plausible_range: honest::plausible_range_text(p),
                    behaves_like: w,
                    most_alike: alike(d.alike(p)),
                })
            })
            .collect(),
        aliases: d.aliases.iter().map(AliasView::of).collect(),
        likelihood: LikelihoodView::new("final", &d.final_fit, &d.nominal_fit),
        noise_floor: NoiseFloorView::of(floor),
        conclusion: conclusion(d, floor),
        steps: d
            .steps
            .iter()
            .enumerate()
            .map(|(i, s)| step_view(i, s))
            .collect(),
        folds: d.folds,
        fold_by: d.fold_by.name(),
        club_mismatch: d.club_mismatch.clone(),
        n_shots: d.n_shots,
        warnings: d.warnings.clone(),
        before: error_table(&d.before),
        after: error_table(&d.after),
    }
}
