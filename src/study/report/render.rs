//! A study's report rendered ([`Render`]): the text summary, the JSON and the HTML page.

use super::{html, text, StudyReport};
use crate::report::charts::ChartError;
use crate::report::render::{json_text, Render};

/// What a study's text takes: the full tables (`--wide`).
#[derive(Debug, Clone, Copy, Default)]
pub struct StudyContext {
    /// One line per variant with every metric.
    pub wide: bool,
}

impl Render for StudyReport {
    type Context = StudyContext;
    fn text(&self, cx: &StudyContext) -> String {
        text::summary(self, cx.wide, crate::report::text::WIDTH)
    }
    fn json(&self) -> Option<String> {
        Some(json_text(self))
    }
    fn html(&self, _: &StudyContext) -> Option<Result<String, ChartError>> {
        Some(html::page(self))
    }
}
