//! `calibrate`: fit named effects to measured launch conditions.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::Context;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::inputs::{self, NamedClub, ShotsFormat, ShotsInput};
use super::Notes;
use crate::data::noise_file::read_noise_file;
use crate::data::shots::ShotTable;
use crate::diagnose::noise_floor::{self, InstrumentClass};
use crate::fit::{
    calibrate_scored, parse_effect_list, CalibrateOptions, FitError, GivenScales, Method, Progress,
};
use crate::measurement::{DeliveryNoise, ImpactNoise};
use crate::model::Shot;
use crate::physics::LaunchComponent;
use crate::report::calibrate::CalibrateReport;
use crate::report::render::CalibratePage;
use crate::ClubSpec;

/// Settings of `calibrate`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct CalibrateSettings {
    /// How the shots are read.
    #[serde(flatten)]
    pub shots: ShotsFormat,
    /// 1σ noise of the measured impact location (vertical, heel–toe), mm.
    #[serde(with = "inputs::impact_noise_mm")]
    pub impact_noise_mm: Option<ImpactNoise>,
    /// Effects to fit, comma-separated: `name` (global), `name@group` (one per group of the
    /// shots), `name@A` (group A only).
    pub effects: String,
    /// Fitting procedure.
    pub method: Method,
    /// Iteration limit of each solver run.
    pub max_iters: u64,
    /// 1σ noise of the measured delivery variables other than the impact location, as a
    /// `--delivery-noise` spec ([`super::delivery_noise`]).
    #[serde(with = "delivery_noise_spec")]
    pub delivery_noise: Option<DeliveryNoise>,
    /// Instrument class whose noise gives the scales every model is scored by.
    pub instrument: Option<InstrumentClass>,
    /// Instrument noise file giving the scales (overrides `instrument`).
    pub noise: Option<PathBuf>,
    /// Run on shots that do not match the club (the report then has no findings).
    pub ignore_club_mismatch: bool,
}

impl Default for CalibrateSettings {
    fn default() -> Self {
        Self {
            shots: ShotsFormat::default(),
            impact_noise_mm: None,
            effects: String::new(),
            method: Method::Lm,
            max_iters: 100,
            delivery_noise: None,
            instrument: None,
            noise: None,
            ignore_club_mismatch: false,
        }
    }
}

/// Serde form of an optional delivery noise: its `--delivery-noise` spec.
mod delivery_noise_spec {
    use super::*;

    pub fn serialize<S: Serializer>(v: &Option<DeliveryNoise>, s: S) -> Result<S::Ok, S::Error> {
        v.as_ref()
            .and_then(crate::report::delivery_noise::spec)
            .serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<DeliveryNoise>, D::Error> {
        match Option::<String>::deserialize(d)? {
            None => Ok(None),
            Some(spec) => super::super::delivery_noise::parse(&spec)
                .map(Some)
                .map_err(|e| serde::de::Error::custom(format!("delivery_noise: {e}"))),
        }
    }
}

/// Calibrate `club` on the shots of `input` (read, prepared and checked against the club):
/// what the Python package calls. `progress` sees the solver's iterations.
pub fn run(
    settings: &CalibrateSettings,
    club: NamedClub,
    input: &ShotsInput,
    notes: &mut dyn Notes,
    progress: Option<Arc<dyn Progress>>,
) -> anyhow::Result<(CalibrateReport, ShotTable)> {
    inputs::check_max_iters(settings.max_iters)?;
    let prepared = inputs::prepare(club, input, &settings.shots, (true, true), notes)?;
    let mismatch = inputs::club_check(
        settings.ignore_club_mismatch,
        club,
        input.label(),
        &prepared.table.shots,
        notes,
    )?;
    let report = run_prepared(
        settings,
        club.spec,
        input.label(),
        &prepared.table,
        mismatch,
        progress,
    )?;
    Ok((report, prepared.table))
}

/// The report of the calibration of `table` (prepared, named `shots_path` in messages) with
/// `club`, refused when any reported number is not finite; `club_mismatch`: why the shots are
/// another club's, when the club check let them through.
pub fn run_prepared(
    settings: &CalibrateSettings,
    club: &ClubSpec,
    shots_path: &Path,
    table: &ShotTable,
    club_mismatch: Option<String>,
    progress: Option<Arc<dyn Progress>>,
) -> anyhow::Result<CalibrateReport> {
    let here = || shots_path.display().to_string();
    if !table.has_measurements() {
        return Err(FitError::NoMeasurements).with_context(here);
    }
    let requests = parse_effect_list(&settings.effects)?;
    let opts = CalibrateOptions {
        method: settings.method,
        max_iters: settings.max_iters,
        parallel: true,
        impact_noise: settings.impact_noise_mm,
        delivery_noise: settings.delivery_noise,
    };
    let given = given_scales(
        (settings.noise.as_deref(), settings.instrument),
        club,
        &table.shots,
        settings.impact_noise_mm,
    )
    .with_context(here)?;
    let cal = calibrate_scored(
        club,
        &table.shots,
        &requests,
        &opts,
        given.as_ref(),
        progress,
    )
    .with_context(here)?;
    // Nothing infinite or undefined is reported or written into a club file.
    let mut numbers: Vec<(String, f64)> = vec![
        ("chi2".into(), cal.chi2),
        ("nominal chi2".into(), cal.chi2_before),
        ("reduced chi2".into(), cal.reduced_chi2),
        ("-2 ln L".into(), cal.likelihood.minus_2_ln_l),
        (
            "nominal -2 ln L".into(),
            cal.likelihood_nominal.minus_2_ln_l,
        ),
    ];
    numbers.extend(cal.params.iter().map(|p| (p.label(), p.value)));
    if let Some((name, v)) = numbers.iter().find(|(_, v)| !v.is_finite()) {
        anyhow::bail!(
            "{}: the fit's {name} is {v}, not a number; the measurements do not fit this model \
             (check the shots' measured launch values)",
            shots_path.display()
        );
    }
    Ok(CalibrateReport {
        calibration: cal,
        n_shots: table.shots.len(),
        club_mismatch,
        warnings: table.left_out_notes(),
    })
}

/// What the HTML page of a calibration of `table` (named `shots_path`) shows besides the
/// report: the calibrated model under the fit's measurement model (at the expected true
/// deliveries, averaged over the likely impact locations) compared with the shots.
pub fn page(
    report: &CalibrateReport,
    table: &ShotTable,
    settings: &CalibrateSettings,
    (shots_path, title): (&Path, String),
) -> anyhow::Result<CalibratePage> {
    let cal = &report.calibration;
    let mut expected = table.shots.clone();
    if let Some(noise) = cal.delivery_noise {
        let deliveries: Vec<_> = expected.iter().map(|s| s.delivery).collect();
        let golfers: Vec<_> = expected.iter().map(|s| s.golfer.clone()).collect();
        for (s, d) in expected
            .iter_mut()
            .zip(noise.calibrate(&deliveries, &golfers))
        {
            s.delivery = d;
        }
    }
    let launches =
        crate::predict::expected_launches(&cal.club, &expected, settings.impact_noise_mm)
            .with_context(|| shots_path.display().to_string())?;
    let after = crate::compare::compare(
        &table.shots,
        &launches,
        &crate::compare::CompareOptions::default(),
    )?;
    Ok(CalibratePage {
        after,
        residuals: crate::report::html::ShotResiduals::new(&table.shots, &launches),
        title,
    })
}

/// The scales the models are scored by when the instruments' noise is given (a noise file,
/// else an instrument class): each shot's expected error variance through the nominal model
/// `club` with the location correction `impact_noise`; `None` (profiled scales) when neither is
/// given. A zero scale is refused: it would make any error infinitely unlikely.
pub fn given_scales(
    (noise, instrument): (Option<&Path>, Option<InstrumentClass>),
    club: &ClubSpec,
    shots: &[Shot],
    impact_noise: Option<ImpactNoise>,
) -> anyhow::Result<Option<GivenScales>> {
    let inst = match (noise, instrument) {
        (Some(p), _) => read_noise_file(p)?,
        (None, Some(c)) => c.noise(),
        (None, None) => return Ok(None),
    };
    let given = noise_floor::given_scales(club, shots, &inst, impact_noise)?;
    let scales = given.scales();
    if let Some(c) = LaunchComponent::ALL
        .iter()
        .find(|c| !(scales[c.index()] > 1e-9 && scales[c.index()].is_finite()))
    {
        anyhow::bail!(
            "{}: the noise of {} is {}; scoring needs a positive noise for every launch \
             component (give it in [noise.launch])",
            inst.name,
            c.column(),
            scales[c.index()]
        );
    }
    Ok(Some(given))
}
