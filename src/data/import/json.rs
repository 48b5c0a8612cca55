//! JSON exports as rows of cells: a session file holding an array of shots (Foresight FSX's
//! `.session`: `{"Shots": [...]}`), a bare array of shots, or JSON Lines (one object per line,
//! as open projects log: the lines that are shots are those naming the mapping's columns). Each
//! shot's nested objects are flattened to dotted names (`BallData.BallSpeed_MS`), `null` is an
//! empty cell, and the session's own scalar fields (`SessionStartDate`) are columns of every
//! shot. A shot's "line" in messages is its line in a JSON Lines file, else its place in the
//! array (the first shot is 1).

use std::path::Path;

use serde_json::Value;

use super::cell::Row;
use crate::data::DataError;

/// Whether `text` is JSON rather than CSV: its first non-blank character opens an object or
/// an array.
pub(super) fn is_json(text: &str) -> bool {
    let t = text.trim_start();
    // An array of shots opens with an object (or is empty); a CSV's first cell may be a unit
    // in brackets (`[m]`, `[ft]`).
    t.starts_with('{')
        || t.strip_prefix('[')
            .is_some_and(|r| r.trim_start().starts_with(['{', '[', ']']))
}

/// What [`read_json`] read: the header, the shots' rows, and the lines of JSON Lines that are
/// not JSON (a log cut short while it was written), each with its error.
pub(super) struct JsonRows {
    pub header: Vec<String>,
    pub rows: Vec<Row>,
    pub broken: Vec<(usize, DataError)>,
}

/// The header (every flattened name, in first-seen order) and the rows of the shots. A row is
/// a shot when `known` recognises at least two of its names (JSON Lines' other events and a
/// session's own fields are not shots). `notes` says where the shots were found. In JSON
/// Lines, a line after the first that is not JSON is a bad row (left out and counted by the
/// import), not a reason to lose the others.
pub(super) fn read_json(
    path: &Path,
    text: &str,
    known: &dyn Fn(&str) -> bool,
    notes: &mut Vec<String>,
) -> Result<JsonRows, DataError> {
    let bad = |line: usize, e: serde_json::Error| {
        DataError::at(
            path,
            Some(line),
            None,
            format!("not valid JSON ({e}); a JSON export is one object, an array, or one object per line"),
        )
    };
    let mut shots: Vec<(usize, Vec<(String, String)>)> = Vec::new();
    let mut broken = Vec::new();
    match serde_json::from_str::<Value>(text) {
        Ok(v @ (Value::Array(_) | Value::Object(_))) => {
            for (n, cells) in rows_in(&v, &[], known).into_iter().enumerate() {
                shots.push((n + 1, cells));
            }
            notes.push(format!(
                "JSON: {} shot(s) found; a shot's line is its place among them (the first is 1)",
                shots.len()
            ));
        }
        Ok(_) => {
            return Err(DataError::file(
                path,
                "JSON that holds no shots (not an object or an array)",
            ))
        }
        Err(whole) => {
            // JSON Lines: one object per line.
            for (n, line) in text.lines().enumerate() {
                if line.trim().is_empty() {
                    continue;
                }
                match serde_json::from_str::<Value>(line) {
                    Ok(v) => shots.extend(rows_in(&v, &[], known).into_iter().map(|c| (n + 1, c))),
                    Err(_) if n == 0 => return Err(bad(whole.line(), whole)),
                    Err(e) => broken.push((n + 1, bad(n + 1, e))),
                }
            }
        }
    }
    let mut header: Vec<String> = Vec::new();
    for (_, cells) in &shots {
        for (k, _) in cells {
            if !header.contains(k) {
                header.push(k.clone());
            }
        }
    }
    let rows = shots
        .into_iter()
        .map(|(line, cells)| {
            let row = header
                .iter()
                .map(|h| {
                    cells
                        .iter()
                        .find(|(k, _)| k == h)
                        .map_or_else(String::new, |(_, v)| v.clone())
                })
                .collect();
            (line, row)
        })
        .collect();
    Ok(JsonRows {
        header,
        rows,
        broken,
    })
}

/// The shots in `v`: the objects deepest in the tree that name at least two columns `known`
/// recognises, each with the scalars of the objects around it (`inherited`: a session's date,
/// a group's club), its own cells winning a name both have.
fn rows_in(
    v: &Value,
    inherited: &[(String, String)],
    known: &dyn Fn(&str) -> bool,
) -> Vec<Vec<(String, String)>> {
    match v {
        Value::Array(items) => items
            .iter()
            .flat_map(|i| rows_in(i, inherited, known))
            .collect(),
        Value::Object(map) => {
            let own = flatten(v);
            let named = own
                .iter()
                .filter(|(k, _)| known(&super::cell::split_header(k).0))
                .count();
            let mut cells = inherited.to_vec();
            for (k, val) in own {
                match cells.iter_mut().find(|(n, _)| *n == k) {
                    Some(c) => c.1 = val,
                    None => cells.push((k, val)),
                }
            }
            let inner: Vec<Vec<(String, String)>> = map
                .values()
                .filter(|x| x.is_array())
                .flat_map(|x| rows_in(x, &cells, known))
                .collect();
            if !inner.is_empty() {
                inner
            } else if named >= 2 {
                vec![cells]
            } else {
                Vec::new()
            }
        }
        _ => Vec::new(),
    }
}

/// A scalar as a cell: `null` empty, numbers and booleans as written, strings as they are.
fn scalar(v: &Value) -> String {
    match v {
        Value::Null => String::new(),
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// An object's scalars by dotted name (`BallData.BallSpeed_MS`); arrays are not cells.
fn flatten(v: &Value) -> Vec<(String, String)> {
    fn walk(prefix: &str, v: &Value, out: &mut Vec<(String, String)>) {
        match v {
            Value::Object(map) => {
                for (k, v) in map {
                    let name = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    walk(&name, v, out);
                }
            }
            Value::Array(_) => {}
            other => out.push((prefix.to_owned(), scalar(other))),
        }
    }
    let mut out = Vec::new();
    walk("", v, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sessions_arrays_and_lines() {
        let known = |n: &str| {
            matches!(
                n,
                "balldata.ballspeed_ms" | "clubname" | "ball_speed_mph" | "club"
            )
        };
        let p = Path::new("s.session");
        let mut notes = Vec::new();
        let text = r#"{"PlayerName":"P","Date":"2024.01.29","Shots":[{"ClubName":"7","BallData":{"BallSpeed_MS":40.5,"Spin":null}},{"ClubName":null,"BallData":{"BallSpeed_MS":41}}]}"#;
        let JsonRows {
            header: h, rows, ..
        } = read_json(p, text, &known, &mut notes).unwrap();
        // serde_json's objects iterate in key order; a shot's own cells follow the session's.
        let strings = |v: &[&str]| v.iter().map(|c| c.to_string()).collect::<Vec<String>>();
        assert_eq!(
            h,
            strings(&[
                "Date",
                "PlayerName",
                "BallData.BallSpeed_MS",
                "BallData.Spin",
                "ClubName"
            ])
        );
        assert_eq!(rows[0], (1, strings(&["2024.01.29", "P", "40.5", "", "7"])));
        assert_eq!(rows[1].1[4], "");
        let lines = "{\"type\":\"start\",\"x\":1}\n\
                     {\"type\":\"shot\",\"ball_speed_mph\":120.5,\"club\":\"7-iron\"}\n";
        let JsonRows {
            header: h, rows, ..
        } = read_json(p, lines, &known, &mut notes).unwrap();
        assert_eq!(h, strings(&["ball_speed_mph", "club", "type"]));
        assert_eq!(rows, vec![(2, strings(&["120.5", "7-iron", "shot"]))]);
        assert!(read_json(p, "{\"a\":1", &known, &mut notes).is_err());
    }
}
