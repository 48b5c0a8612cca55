//! The hint a refused import gives when its file is a shots file already: such a file is read
//! with `--format shots`, which a project file's `format` (or a habit of typing `--format`)
//! easily hides.

use std::io::Read as _;
use std::path::Path;

/// `e`, the refusal of an import of `path` as `format`, with a hint when `path` is a shots file
/// already (its header has every required shots column); `format_from`: the project file that
/// set `format`, when one did. A format that is not one (a typo) keeps its own error: that is
/// the thing to fix, not the file.
pub fn add(
    path: &Path,
    format: &str,
    format_from: Option<&Path>,
    e: anyhow::Error,
) -> anyhow::Error {
    let mut head = Vec::new();
    let read = std::fs::File::open(path).and_then(|f| f.take(1 << 16).read_to_end(&mut head));
    let text = String::from_utf8_lossy(&head);
    let line = text
        .trim_start_matches('\u{feff}')
        .lines()
        .next()
        .unwrap_or("");
    let header: Vec<&str> = line
        .split(',')
        .map(|h| h.trim().trim_matches('"'))
        .collect();
    let required = smash::data::shots::required_columns();
    let known =
        format.eq_ignore_ascii_case("auto") || smash::data::import::load_mapping(format).is_ok();
    if read.is_err() || !known || !required.iter().all(|c| header.contains(c)) {
        return e;
    }
    let from = match format_from {
        Some(p) => format!(" (format = {format} is the project file {}'s)", p.display()),
        None => String::new(),
    };
    anyhow::anyhow!(
        "{e:#}; {} looks like a shots file already (its header has {}): read it with \
         --format shots{from}",
        path.display(),
        required.join(", ")
    )
}
