//! The `[study]` table: name, club, group, outputs, output folder.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use toml::Spanned;

use super::defaults;
use crate::data::{DataError, TomlDoc};
use crate::study::metrics::Output;

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawHeader {
    pub name: Spanned<String>,
    pub club: Spanned<String>,
    pub group: Option<Spanned<String>>,
    pub outputs: Option<Vec<Spanned<String>>>,
    pub output_dir: Option<String>,
}

/// The `[study]` table resolved (the club is loaded apart, see [`club_file`]).
pub(super) struct Header {
    pub name: String,
    pub group: String,
    pub outputs: Vec<Output>,
    pub output_dir: PathBuf,
}

/// The club file named by `study.club`, relative to the study file `path` unless absolute.
pub(super) fn club_file(path: &Path, h: &RawHeader) -> PathBuf {
    let club_rel = PathBuf::from(h.club.get_ref());
    if club_rel.is_absolute() {
        return club_rel;
    }
    path.parent().unwrap_or(Path::new(".")).join(club_rel)
}

pub(super) fn parse_header(doc: &TomlDoc<'_>, h: &RawHeader) -> Result<Header, DataError> {
    let name = h.name.get_ref().clone();
    if name.is_empty()
        || !name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.')
        || name.starts_with('.')
    {
        return Err(doc.err(
            h.name.span(),
            "study.name",
            format!(
                "'{}' must be a non-empty folder name of ASCII letters (a-z, A-Z), digits, '_', \
                 '-' and '.', not starting with '.'",
                crate::data::escape(&name)
            ),
        ));
    }
    let group = match &h.group {
        None => defaults::GROUP.to_string(),
        Some(g) if g.get_ref().is_empty() => {
            return Err(doc.err(g.span(), "study.group", "must not be empty"))
        }
        Some(g) => g.get_ref().clone(),
    };
    let outputs = match &h.outputs {
        None => Output::ALL.to_vec(),
        Some(list) => parse_outputs(doc, list)?,
    };
    let output_dir = h
        .output_dir
        .as_ref()
        .map_or_else(|| PathBuf::from("results").join(&name), PathBuf::from);
    Ok(Header {
        name,
        group,
        outputs,
        output_dir,
    })
}

fn parse_outputs(doc: &TomlDoc<'_>, list: &[Spanned<String>]) -> Result<Vec<Output>, DataError> {
    let allowed: Vec<(&str, Output)> = Output::ALL.iter().map(|o| (o.column(), *o)).collect();
    let mut out = Vec::new();
    for s in list {
        let o = doc.one_of(s.span(), "study.outputs", "output", s.get_ref(), &allowed)?;
        if out.contains(&o) {
            return Err(doc.err(
                s.span(),
                "study.outputs",
                format!("'{}' is listed twice", s.get_ref()),
            ));
        }
        out.push(o);
    }
    if out.is_empty() {
        return Err(doc.whole(
            "study.outputs",
            format!("the list is empty; allowed: {}", Output::all_columns()),
        ));
    }
    out.sort();
    Ok(out)
}
