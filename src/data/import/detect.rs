//! `--format auto`: which preset reads an export, from its header or its JSON keys. Every
//! preset whose required columns the file has is a candidate; the one that knows most of the
//! file's columns (mapped or known and ignored) is chosen, and the others close to it are named,
//! so that a user whose file was read as the wrong layout sees which to give instead.

use std::collections::HashSet;
use std::path::Path;

use super::cell::split_header;
use super::columns::find_column;
use super::table::read_table;
use super::target::Target;
use super::{parse_mapping, Mapping, PRESETS};
use crate::data::DataError;

/// The preset `--format auto` chose, and what to tell the user.
#[derive(Debug, Clone)]
pub struct Detected {
    /// The preset's name.
    pub preset: &'static str,
    /// The choice and its close alternatives, one line.
    pub note: String,
}

/// How well a preset reads the file: its mapped columns found, the file's columns it knows.
struct Fit {
    preset: &'static str,
    mapped: usize,
    known: usize,
    /// The required columns it does not find (empty: it can read the file).
    missing: Vec<String>,
}

fn fit(path: &Path, bytes: &[u8], preset: &'static str, m: &Mapping) -> Option<Fit> {
    let names: HashSet<String> = m
        .column
        .iter()
        .flat_map(|c| c.source.iter())
        .chain(&m.export.ignore)
        .map(|n| split_header(n).0)
        .collect();
    let known = |name: &str| names.contains(name);
    let table = read_table(path, bytes, m.export.skip_lines, &m.export.name, &known).ok()?;
    let mut used = vec![false; table.headers.len()];
    let mut mapped = 0;
    let mut missing = Vec::new();
    for spec in &m.column {
        let target = Target::parse(&spec.target)?;
        match find_column(&table, &spec.source, target, &used) {
            Some(i) => {
                used[i] = true;
                mapped += 1;
            }
            None if !spec.optional => missing.push(spec.source[0].clone()),
            None => {}
        }
    }
    let known = table
        .headers
        .iter()
        .filter(|(h, _)| names.contains(h))
        .count();
    Some(Fit {
        preset,
        mapped,
        known,
        missing,
    })
}

/// The header cells of a text export's first line (byte-order mark dropped, split at the
/// separator that gives most cells, quotes trimmed); `None` for JSON or a first line that is
/// not UTF-8 (UTF-16, a spreadsheet's binary file).
fn first_line_cells(bytes: &[u8]) -> Option<Vec<String>> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let end = bytes
        .iter()
        .position(|&b| b == b'\n')
        .unwrap_or(bytes.len());
    let line = std::str::from_utf8(&bytes[..end])
        .ok()?
        .trim_end_matches('\r');
    if line.trim_start().starts_with(['{', '[']) {
        return None;
    }
    let sep = [',', ';', '\t']
        .into_iter()
        .max_by_key(|&c| line.matches(c).count())?;
    Some(
        line.split(sep)
            .map(|c| c.trim().trim_matches('"').to_owned())
            .collect(),
    )
}

/// Why no preset reads a file, when it is plain: a shots file already (its header has the
/// shots file's own launch columns): the whole message.
fn a_shots_file(bytes: &[u8]) -> Option<String> {
    let cells = first_line_cells(bytes)?;
    ["ball_speed_mph", "launch_angle_deg"]
        .iter()
        .all(|c| cells.iter().any(|h| h == c))
        .then(|| {
            "--format auto: this is a shots file already (its header has smash's own \
             ball_speed_mph and launch_angle_deg): read it as one (--format shots, the default \
             of every command but import); --format auto and import read launch monitors' \
             exports"
                .into()
        })
}

/// A hint for a file no preset reads whose header is in another language: at least five
/// header cells, two of them with letters outside ASCII (`Køllehast.`), and no preset knowing
/// more than two of its columns.
fn another_language(bytes: &[u8], fits: &[Fit]) -> Option<&'static str> {
    let cells = first_line_cells(bytes)?;
    let foreign = cells
        .iter()
        .filter(|c| c.chars().any(|ch| ch.is_alphabetic() && !ch.is_ascii()))
        .count();
    let most = fits.iter().map(|f| f.known).max().unwrap_or(0);
    (cells.len() >= 5 && foreign >= 2 && most <= 2).then_some(
        "; its header looks like another language's (an app set to another language?): the \
         presets read the vendors' English headers, and a mapping file names the columns as \
         the file writes them",
    )
}

/// The preset that reads the export at `path` (`bytes`): the candidate (every required column
/// found) knowing most of the file's columns. Refuses a file no preset reads, naming the
/// closest presets and what each misses.
pub fn detect(path: &Path, bytes: &[u8]) -> Result<Detected, DataError> {
    let mut fits: Vec<Fit> = Vec::new();
    for (name, text) in PRESETS {
        let m = parse_mapping(Path::new(name), text)?;
        if let Some(f) = fit(path, bytes, name, &m) {
            fits.push(f);
        }
    }
    let score = |f: &Fit| f.mapped + f.known;
    fits.sort_by_key(|f| std::cmp::Reverse((f.missing.is_empty(), score(f))));
    let Some(best) = fits
        .first()
        .filter(|f| f.missing.is_empty() && f.mapped >= 3)
    else {
        if let Some(why) = a_shots_file(bytes) {
            return Err(DataError::file(path, why));
        }
        let closest: Vec<String> = fits
            .iter()
            .take(3)
            .map(|f| format!("{} (misses '{}')", f.preset, f.missing.join("', '")))
            .collect();
        return Err(DataError::file(
            path,
            format!(
                "--format auto: no preset reads this file; the closest: {}{}; give --format \
                 PRESET or a mapping file NAME.toml (docs/import.md)",
                closest.join(", "),
                another_language(bytes, &fits).unwrap_or("")
            ),
        ));
    };
    let close: Vec<String> = fits[1..]
        .iter()
        .filter(|f| f.missing.is_empty() && 10 * score(f) >= 8 * score(best))
        .map(|f| f.preset.to_owned())
        .collect();
    let mut note = format!(
        "--format auto: read as {} ({} of the file's {} column(s) known to it)",
        best.preset,
        best.known,
        fits_len(path, bytes, best.preset)
    );
    if !close.is_empty() {
        note.push_str(&format!(
            "; also close: {} (give --format NAME if the file is one of those)",
            close.join(", ")
        ));
    }
    Ok(Detected {
        preset: best.preset,
        note,
    })
}

/// The number of named columns `preset` sees in the file.
fn fits_len(path: &Path, bytes: &[u8], preset: &str) -> usize {
    let Some((_, text)) = PRESETS.iter().find(|(n, _)| *n == preset) else {
        return 0;
    };
    let Ok(m) = parse_mapping(Path::new(preset), text) else {
        return 0;
    };
    let names: HashSet<String> = m
        .column
        .iter()
        .flat_map(|c| c.source.iter())
        .chain(&m.export.ignore)
        .map(|n| split_header(n).0)
        .collect();
    let known = |name: &str| names.contains(name);
    read_table(path, bytes, m.export.skip_lines, &m.export.name, &known)
        .map_or(0, |t| t.header.iter().filter(|h| !h.is_empty()).count())
}
