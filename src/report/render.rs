//! One renderer trait for every command's report, as ruff's emitters or typos' reporters: a
//! report is one value, and its text, its JSON and its HTML page are each rendered from that
//! value alone ([`Render`]). The command line picks the format (`--json`, `--report`) and
//! writes what the trait returns; it builds no output of its own.
//!
//! Implemented for the reports of `diagnose`, `calibrate`, `compare`, `flight`, `effects`,
//! `infer-club` (and its plan) here, and for the study's and `whatif`'s in [`crate::study`].

use serde::Serialize;

use super::calibrate::CalibrateReport;
use super::charts::ChartError;
use super::diagnose::text::Layout;
use super::diagnose::DiagnoseReport;
use super::effects::EffectsReport;
use super::flight::FlightReport;
use super::html::ShotResiduals;
use crate::compare::CompareReport;
use crate::infer::report::{PlanReport, Report as InferReport};

/// A command's report, rendered.
pub trait Render {
    /// What the text and the page take besides the report: the title a page carries, `--wide`,
    /// the words of the command to run next (`()` when nothing).
    type Context;

    /// The text report (stdout, or stderr under `--json`).
    fn text(&self, cx: &Self::Context) -> String;

    /// The JSON report, `None` for a command without one (the report's serde form,
    /// [`json_text`]).
    fn json(&self) -> Option<String> {
        None
    }

    /// The self-contained HTML page, `None` for a command without one.
    fn html(&self, _cx: &Self::Context) -> Option<Result<String, ChartError>> {
        None
    }
}

/// The JSON text of a report: its serde form, pretty-printed (`docs/json.md`).
pub fn json_text<T: Serialize>(report: &T) -> String {
    serde_json::to_string_pretty(report).expect("a report serializes (its maps have string keys)")
}

/// What `diagnose`'s text and page take: the text's layout and the page's title.
pub struct DiagnoseContext {
    /// The text's layout (`--wide`, the calibrate command it suggests).
    pub layout: Layout,
    /// The page's title.
    pub title: String,
}

impl Render for DiagnoseReport {
    type Context = DiagnoseContext;
    fn text(&self, cx: &DiagnoseContext) -> String {
        super::diagnose::text::render(self, &cx.layout)
    }
    fn json(&self) -> Option<String> {
        Some(json_text(self))
    }
    fn html(&self, cx: &DiagnoseContext) -> Option<Result<String, ChartError>> {
        Some(super::html::diagnose_page(self, &cx.title))
    }
}

/// What `calibrate`'s page shows besides the report: the calibrated model compared with the
/// shots under the fit's measurement model, its residuals, and the title.
pub struct CalibratePage {
    /// The comparison of the calibrated model with the shots.
    pub after: CompareReport,
    /// Its residuals per shot.
    pub residuals: ShotResiduals,
    /// The page's title.
    pub title: String,
}

/// What `calibrate`'s text and page take.
pub struct CalibrateContext {
    /// The full tables (`--wide`).
    pub wide: bool,
    /// The page's inputs, when a page is asked for.
    pub page: Option<CalibratePage>,
}

impl Render for CalibrateReport {
    type Context = CalibrateContext;
    fn text(&self, cx: &CalibrateContext) -> String {
        super::calibrate::text::render(self, cx.wide)
    }
    fn json(&self) -> Option<String> {
        Some(json_text(self))
    }
    fn html(&self, cx: &CalibrateContext) -> Option<Result<String, ChartError>> {
        cx.page
            .as_ref()
            .map(|p| super::html::calibrate_page(self, &p.after, &p.residuals, &p.title))
    }
}

/// What `compare`'s text and page take.
pub struct CompareContext {
    /// The title (`CLUB vs SHOTS (N groups)`).
    pub title: String,
    /// Table 2 in one block however many groups (`--wide`).
    pub wide: bool,
    /// The model's residuals per shot, for the page's trend charts.
    pub residuals: Option<ShotResiduals>,
}

impl Render for CompareReport {
    type Context = CompareContext;
    fn text(&self, cx: &CompareContext) -> String {
        super::compare::report_text(self, &cx.title, cx.wide)
    }
    fn json(&self) -> Option<String> {
        Some(super::compare::compare_json(self))
    }
    fn html(&self, cx: &CompareContext) -> Option<Result<String, ChartError>> {
        cx.residuals
            .as_ref()
            .map(|r| super::html::compare_page(self, r, &cx.title))
    }
}

impl Render for FlightReport {
    type Context = ();
    fn text(&self, _: &()) -> String {
        FlightReport::text(self)
    }
    fn json(&self) -> Option<String> {
        Some(json_text(self))
    }
    fn html(&self, _: &()) -> Option<Result<String, ChartError>> {
        Some(super::html::flight_page(self))
    }
}

impl Render for EffectsReport {
    type Context = ();
    fn text(&self, _: &()) -> String {
        EffectsReport::text(self)
    }
    fn json(&self) -> Option<String> {
        Some(json_text(self))
    }
}

/// `infer-club`'s report; its context is the page's title.
impl Render for InferReport {
    type Context = String;
    fn text(&self, _: &String) -> String {
        crate::infer::report::render(self)
    }
    fn json(&self) -> Option<String> {
        Some(json_text(self))
    }
    fn html(&self, title: &String) -> Option<Result<String, ChartError>> {
        Some(Ok(super::html::infer_page(self, title)))
    }
}

impl Render for PlanReport {
    type Context = ();
    fn text(&self, _: &()) -> String {
        crate::infer::report::render_plan(self)
    }
    fn json(&self) -> Option<String> {
        Some(json_text(self))
    }
}
