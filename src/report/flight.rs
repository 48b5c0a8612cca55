//! What `smash flight` reports when the shots carry measured flights, as one value:
//! [`FlightReport`]. Its text is [`FlightReport::text`], its JSON its `Serialize` (the schema:
//! `docs/json.md`), its HTML page [`crate::report::html::flight_page`].

use serde::Serialize;

use crate::data::flight_summary::FlightSummary;
use crate::flight::calibrate::{bound_reached, reported_se, uncertainty_text, SCALE_BOUNDS};
use crate::flight::diagnose::FlightDiagnosis;

/// The version of flight's JSON schema (`schema_version`); raised when a key changes meaning
/// or goes away (a new key does not raise it).
pub const SCHEMA_VERSION: u32 = 1;

/// The flight model against the measured flights: the errors per club and, with
/// `--diagnose`, which aerodynamic term the flights asked for. Text, JSON and HTML all render
/// this one value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FlightReport {
    /// [`SCHEMA_VERSION`].
    pub schema_version: u32,
    /// `"flight"`.
    pub command: &'static str,
    /// What was flown: shots, aerodynamic model, air.
    pub flown: String,
    /// The errors (predicted − measured) per club and over all shots.
    pub errors: FlightSummary,
    /// The aerodynamic diagnosis (`--diagnose`), else `null`.
    pub diagnosis: Option<FlightDiagnosis>,
    /// The scalings fitted (`--calibrate`), one entry per part (all shots, or each ball or
    /// session with `--calibrate-by`); empty without `--calibrate`.
    pub calibration: Vec<CalibratedPart>,
    /// What the run warned about: rows of the launch file left out, one note per reason.
    pub warnings: Vec<String>,
}

/// One part's calibration (`--calibrate`): the scalings with their standard errors.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CalibratedPart {
    /// The part (`ball_type 'range'`, `date '2026-05-02'`), or `null` for all shots.
    pub part: Option<String>,
    /// Each term fitted: `term` (`drag`, `lift`, `spin_decay`), `scale`, `se`.
    pub terms: Vec<CalibratedTerm>,
    /// Measured values fitted to (carry, apex, land angle).
    pub values: usize,
    /// Every value fitted to is the vendor's flight model (`flight_modelled = 1`).
    pub modelled: bool,
    /// Root mean square of the weighted residuals before the fit (all scales 1).
    pub rms_before: f64,
    /// The same after it.
    pub rms_after: f64,
}

/// One term's scaling.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CalibratedTerm {
    /// `drag`, `lift` or `spin_decay`.
    pub term: &'static str,
    /// The scaling of the model's term (1: as the model has it).
    pub scale: f64,
    /// Its standard error; `null` when the scale sits at a bound (`at_bound`) or is not
    /// determined.
    pub se: Option<f64>,
    /// The bound of the scales (a third and three times the model's coefficient) the fit
    /// stopped at: `"lower"`, `"upper"` (in JSON `true`), else `None` (`false`).
    #[serde(serialize_with = "crate::flight::calibrate::serialize_at_bound")]
    pub at_bound: Option<&'static str>,
}

impl CalibratedTerm {
    /// `drag x1.0800 ± 0.0011`, `spin_decay x3.0000 (at its upper bound)`.
    pub fn text(&self) -> String {
        format!(
            "{} x{:.4} {}",
            self.term,
            self.scale,
            uncertainty_text(self.se, self.at_bound)
        )
    }
}

impl CalibratedPart {
    /// `cal`, fitted to `part`'s values (`modelled`: every one the vendor's model).
    pub fn new(
        part: Option<String>,
        cal: &crate::flight::calibrate::Calibration,
        modelled: bool,
    ) -> Self {
        Self {
            part,
            terms: cal
                .terms
                .iter()
                .zip(cal.scale.iter().zip(&cal.se))
                .map(|(t, (&scale, &se))| {
                    let at_bound = bound_reached(scale, SCALE_BOUNDS);
                    CalibratedTerm {
                        term: t.name(),
                        scale,
                        se: reported_se(se, at_bound),
                        at_bound,
                    }
                })
                .collect(),
            values: cal.residuals,
            modelled,
            rms_before: cal.rms_before,
            rms_after: cal.rms_after,
        }
    }
}

impl FlightReport {
    /// The report of `errors` (and `diagnosis`) for the shots flown as `flown` says.
    pub fn new(flown: String, errors: FlightSummary, diagnosis: Option<FlightDiagnosis>) -> Self {
        Self {
            schema_version: SCHEMA_VERSION,
            command: "flight",
            flown,
            errors,
            diagnosis,
            calibration: Vec::new(),
            warnings: Vec::new(),
        }
    }

    /// The error table as text (the diagnosis's ranking is printed as the terms are fitted).
    pub fn text(&self) -> String {
        self.errors.text()
    }
}
