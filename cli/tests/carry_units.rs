//! Carries in metres read as yards are caught by physics (issue 44, item 4): the real sessions
//! of `tests/data/real/` import without a note on their carry unit, and the same sessions with
//! every distance written in metres (the header still reading as yards: an export whose units
//! a user changed in the app, or a preset's default unit that does not hold) are flagged with
//! one note naming the column, the ratio seen and the fix.

use crate::cli_support;

use std::path::Path;

use cli_support::{repo, s, smash, unwrapped as stderr, write};

/// `text` with the cells of `columns` (under the header, the first line naming them all)
/// multiplied by 0.9144 (yards to metres), written to one decimal; other lines as they are.
fn in_metres(text: &str, columns: &[&str]) -> String {
    let split = |l: &str| -> Vec<String> {
        csv::ReaderBuilder::new()
            .has_headers(false)
            .from_reader(l.as_bytes())
            .records()
            .next()
            .map(|r| r.unwrap().iter().map(str::to_owned).collect())
            .unwrap_or_default()
    };
    let mut out = String::new();
    let mut idx: Option<Vec<usize>> = None;
    for line in text.lines() {
        let cells = split(line);
        match &idx {
            None => {
                let found: Vec<usize> = columns
                    .iter()
                    .filter_map(|c| cells.iter().position(|h| h == c))
                    .collect();
                if found.len() == columns.len() {
                    idx = Some(found);
                }
                out.push_str(line);
            }
            Some(idx) => {
                let mut cells = cells;
                for &i in idx {
                    if let Some(v) = cells.get(i).and_then(|c| c.parse::<f64>().ok()) {
                        cells[i] = format!("{:.1}", v * 0.9144);
                    }
                }
                let mut w = csv::Writer::from_writer(Vec::new());
                w.write_record(&cells).unwrap();
                out.push_str(
                    String::from_utf8(w.into_inner().unwrap())
                        .unwrap()
                        .trim_end(),
                );
            }
        }
        out.push('\n');
    }
    assert!(idx.is_some(), "no header naming {columns:?}");
    out
}

/// stderr of `smash import --format PRESET FILE`, which must succeed.
fn import(dir: &Path, preset: &str, file: &Path) -> String {
    let out = dir.join("shots.csv");
    let o = smash(&["import", "--format", preset, s(file), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    stderr(&o)
}

/// The ratio the carry note states (`… carries is 0.929 times …`).
fn stated_ratio(note: &str) -> f64 {
    let after = note.split("carries is ").nth(1).unwrap();
    after.split(' ').next().unwrap().parse().unwrap()
}

#[test]
fn metres_read_as_yards_are_flagged_and_real_yards_are_not() {
    let dir = tempfile::tempdir().unwrap();
    // The third file states its yards in the header (`Carry(yd)`): taken at its word, the note
    // says what it saw and recommends nothing (a real wedge session stating yards reads 0.949).
    for (file, preset, carry, columns, stated) in [
        (
            "tests/data/real/rapsodo_mlm2pro_7i.csv",
            "rapsodo",
            "Carry Distance",
            &["Carry Distance", "Total Distance", "Side Carry"][..],
            false,
        ),
        (
            "tests/data/real/uneekor_14clubs.csv",
            "uneekor",
            "Carry",
            &["Carry", "Total"][..],
            false,
        ),
        (
            "tests/data/real/range_export_9clubs.csv",
            "uneekor",
            "Carry(yd)",
            &["Carry(yd)", "Total(yd)", "Apex(yd)"][..],
            true,
        ),
    ] {
        let real = repo(file);
        let e = import(dir.path(), preset, &real);
        assert!(
            !e.contains("carries is"),
            "{file}: a note on a real file:\n{e}"
        );
        let text = std::fs::read_to_string(&real).unwrap();
        let metres = write(dir.path(), "metres.csv", &in_metres(&text, columns));
        let e = import(dir.path(), preset, &metres);
        let notes: Vec<&str> = e.lines().filter(|l| l.contains("carries is")).collect();
        assert_eq!(notes.len(), 1, "{file}:\n{e}");
        let note = notes[0];
        assert!(
            note.contains(&format!("column '{carry}' (read in yd)"))
                && (note.contains("the carries are in metres") && note.contains("unit = \"m\""))
                    != stated
                && note.contains("the file states yards") == stated,
            "{note}"
        );
        let r = stated_ratio(note);
        assert!((0.88..=0.95).contains(&r), "{file}: {r}");
    }
}
