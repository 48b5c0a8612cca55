//! What `smash flight` reports when the shots carry measured flights, as one value:
//! [`FlightReport`]. Its text is [`FlightReport::text`], its JSON its `Serialize` (the schema:
//! `docs/json.md`), its HTML page [`crate::report::html::flight_page`].

use serde::Serialize;

use crate::data::flight_summary::FlightSummary;
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
    /// What the run warned about: rows of the launch file left out, one note per reason.
    pub warnings: Vec<String>,
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
            warnings: Vec::new(),
        }
    }

    /// The error table as text (the diagnosis's ranking is printed as the terms are fitted).
    pub fn text(&self) -> String {
        self.errors.text()
    }
}
