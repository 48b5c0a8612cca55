//! What `smash run` and `smash merge` share: the `--format` values of the long table and the
//! summary printed once a study's outputs are written (rendered from the run's
//! [`StudyReport`]).

use std::path::Path;

use smash::report::render::Render;
use smash::study::output::TableFormat;
use smash::study::report::StudyReport;

/// `--format` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum TableFormatArg {
    /// maps_long.csv
    Csv,
    /// maps_long.parquet
    Parquet,
}

impl From<TableFormatArg> for TableFormat {
    fn from(f: TableFormatArg) -> Self {
        match f {
            TableFormatArg::Csv => TableFormat::Csv,
            TableFormatArg::Parquet => TableFormat::Parquet,
        }
    }
}

/// What a run or merge prints once its outputs are written: the report's text summary and
/// where the files went (on stdout), or with `json` the report as one JSON object on stdout and
/// the text on stderr.
pub fn print_summary(
    report: &StudyReport,
    dir: &Path,
    n_files: usize,
    wide: bool,
    json: bool,
) -> Result<(), crate::stdout::StdoutError> {
    let text = smash::app::study::summary_text(report, dir, n_files, wide);
    if json {
        eprint!("{text}");
        return crate::stdout::println(report.json().expect("a study report has JSON"));
    }
    crate::stdout::print(text)
}
