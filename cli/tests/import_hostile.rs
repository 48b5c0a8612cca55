//! Issue 41's hostile exports that touch the import, each built from a small input in the
//! layout described: no silent wrong number, and nothing the import writes sinks a later
//! command.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::{repo, s, smash, unwrapped as stderr};

use crate::common;

fn fixture(name: &str) -> String {
    std::fs::read_to_string(repo(&format!("cli/tests/fixtures/import/{name}"))).unwrap()
}

/// Import `text` (written as `name`) with `format` (and `flags`); the shots file's header and
/// rows, and the stderr. Panics when the import fails.
fn import(
    dir: &Path,
    name: &str,
    text: &[u8],
    format: &str,
    flags: &[&str],
) -> (Vec<String>, Vec<Vec<String>>, String, PathBuf) {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let out = dir.join(format!("{name}.shots.csv"));
    let mut args = vec!["import", "--format", format, s(&path), "--out", s(&out)];
    args.extend_from_slice(flags);
    let res = smash(&args);
    assert!(res.status.success(), "{name}: {}", stderr(&res));
    let mut rdr = csv::Reader::from_path(&out).unwrap();
    let h = rdr.headers().unwrap().iter().map(str::to_owned).collect();
    let rows = rdr
        .records()
        .map(|r| r.unwrap().iter().map(str::to_owned).collect())
        .collect();
    (h, rows, stderr(&res), out)
}

fn col<'a>(h: &[String], rows: &'a [Vec<String>], name: &str) -> Vec<&'a str> {
    let i = h.iter().position(|c| c == name).unwrap();
    rows.iter().map(|r| r[i].as_str()).collect()
}

/// `smash flight` runs on a shots file.
fn flies(dir: &Path, shots: &Path) {
    let out = dir.join("flown.csv");
    let res = smash(&["flight", "--shots", s(shots), "--out", s(&out)]);
    assert!(res.status.success(), "flight: {}", stderr(&res));
}

const TOE: &[&str] = &["--impact-offset-positive", "toe"];

/// 41.1 and the louder ones: GSPro's `Carry` 0 and `ClubSpeed` 0, TrackMan's −2147483648 and
/// a 0 s flight time are "not measured": the cells are empty, counted, and flight runs.
#[test]
fn zeros_and_sentinels_are_not_measured() {
    let dir = tempfile::tempdir().unwrap();
    let gspro = fixture("gspro.csv");
    let mut lines: Vec<String> = gspro.lines().map(str::to_owned).collect();
    // Carry and TotalDistance 0 (GSPro's no value); ClubSpeed 0 on the next shot.
    lines[1] = lines[1].replacen("110.7495,118.5019", "0,0", 1);
    lines[2] = lines[2].replace(",73.71038,", ",0,");
    let (h, rows, err, out) = import(
        dir.path(),
        "g.csv",
        lines.join("\n").as_bytes(),
        "gspro",
        &[],
    );
    assert_eq!(rows.len(), 4, "{err}");
    assert_eq!(col(&h, &rows, "carry_yd")[0], "", "{err}");
    assert_eq!(col(&h, &rows, "total_yd")[0], "");
    assert_eq!(col(&h, &rows, "club_speed_mph")[1], "");
    assert!(
        err.contains("column 'Carry': 0, which vendors write"),
        "{err}"
    );
    flies(dir.path(), &out);

    let tm = fixture("trackman_older.csv");
    let mut lines: Vec<String> = tm.lines().map(str::to_owned).collect();
    // Carry Flat - Length −2147483648 on the first shot, Carry Flat - Time 0 on the second.
    lines[2] = lines[2].replace(",253.3,", ",-2147483648,");
    lines[3] = lines[3].replace(",5.82,", ",0,");
    let (h, rows, err, out) = import(
        dir.path(),
        "t.csv",
        lines.join("\n").as_bytes(),
        "trackman",
        TOE,
    );
    assert_eq!(rows.len(), 8, "{err}");
    assert_eq!(col(&h, &rows, "carry_yd")[0], "");
    assert_eq!(col(&h, &rows, "flight_time_s")[1], "");
    assert!(
        err.contains("a vendor's sentinel for not measured"),
        "{err}"
    );
    assert!(err.contains("column 'Carry Flat - Time': 0"), "{err}");
    flies(dir.path(), &out);
}

/// 41.2: a last row cut mid-row (its carry cut from 239.7 to `23`) is left out and counted.
#[test]
fn a_truncated_last_row_is_left_out() {
    let dir = tempfile::tempdir().unwrap();
    let tm = fixture("trackman_older.csv");
    let lines: Vec<&str> = tm.lines().collect();
    let last = lines[9];
    let cut = &last[..last.find(",239.7,").unwrap() + 3];
    let text = format!("{}\n{cut}", lines[..9].join("\n"));
    let (h, rows, err, _) = import(dir.path(), "t.csv", text.as_bytes(), "trackman", TOE);
    assert_eq!(rows.len(), 7, "{err}");
    assert!(!col(&h, &rows, "carry_yd").contains(&"23"));
    assert!(
        err.contains("fewer cells than the header has columns (line(s) 10"),
        "{err}"
    );
}

/// 41.3: a units row above the header, or under the first shot, is read: 193.4 km/h is not
/// written as 193.4 mph.
#[test]
fn units_rows_above_the_header_or_under_the_first_shot_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let tm = fixture("trackman_older.csv");
    // The speeds (club, ball, ball at landing) written in km/h.
    let kmh: Vec<String> = tm
        .lines()
        .map(|l| {
            let mut cells: Vec<String> = l.split(',').map(str::to_owned).collect();
            for i in [2, 11, 27] {
                if let Ok(v) = cells[i].parse::<f64>() {
                    cells[i] = format!("{:.1}", v * 1.609344);
                }
            }
            cells.join(",")
        })
        .collect();
    let lines: Vec<&str> = kmh.iter().map(String::as_str).collect();
    let units_kmh = lines[1].replace("[mph]", "[km/h]");
    let first = lines[2];
    let want = 250.1 / 1.609344; // 155.4 mph written as 250.1 km/h
                                 // Above the header.
    let above = format!("{units_kmh}\n{}\n{}", lines[0], lines[2..].join("\n"));
    let (h, rows, err, _) = import(dir.path(), "a.csv", above.as_bytes(), "trackman", TOE);
    let bs: f64 = col(&h, &rows, "ball_speed_mph")[0].parse().unwrap();
    assert!((bs - want).abs() < 1e-9, "{bs}: {err}");
    // Under the first shot.
    let under = format!(
        "{}\n{first}\n{units_kmh}\n{}",
        lines[0],
        lines[3..].join("\n")
    );
    let (h, rows, err, _) = import(dir.path(), "u.csv", under.as_bytes(), "trackman", TOE);
    assert_eq!(rows.len(), 8, "{err}");
    let bs: f64 = col(&h, &rows, "ball_speed_mph")[0].parse().unwrap();
    assert!((bs - want).abs() < 1e-9, "{bs}: {err}");
    assert!(err.contains("the units row is line 3"), "{err}");
    // A legend cell before the units (TrackMan's web sheets).
    let legend = format!(
        "{}\n\"Yds/Ft, Mph\"{}\n{}",
        lines[0],
        lines[1],
        lines[2..].join("\n")
    );
    let (_, rows, err, _) = import(dir.path(), "l.csv", legend.as_bytes(), "trackman", TOE);
    assert_eq!(rows.len(), 8, "{err}");
}

/// 41.4: `3.083` in a semicolon-separated file with decimal commas is 3,083 rpm.
#[test]
fn thousands_separators_in_a_decimal_comma_file() {
    let dir = tempfile::tempdir().unwrap();
    let text = fixture("trackman_semicolon.csv").replace(";3083;", ";3.083;");
    let (h, rows, err, _) = import(dir.path(), "t.csv", text.as_bytes(), "trackman", TOE);
    let back: f64 = col(&h, &rows, "backspin_rpm")[0].parse().unwrap();
    assert!(back > 3000.0, "{back}: {err}");
}

/// 41.8: one day written `5/1/2026` and `2026-05-01` is one date; Excel serials are dates.
#[test]
fn dates_in_any_form_are_one_form() {
    let dir = tempfile::tempdir().unwrap();
    let tm = fixture("trackman_older.csv");
    let lines: Vec<&str> = tm.lines().collect();
    let dates = [
        "5/1/2026 10:00",
        "2026-05-01 10:05",
        "46143.4236",
        "46144.5",
    ];
    let mut text = format!("Date,{}\n,{}\n", lines[0], lines[1]);
    for (i, l) in lines[2..6].iter().enumerate() {
        text.push_str(&format!("{},{l}\n", dates[i]));
    }
    let (h, rows, err, _) = import(dir.path(), "d.csv", text.as_bytes(), "trackman", TOE);
    assert_eq!(
        col(&h, &rows, "datetime"),
        [
            "2026-05-01 10:00:00",
            "2026-05-01 10:05:00",
            "2026-05-01 10:09:59.040",
            "2026-05-02 12:00:00"
        ],
        "{err}"
    );
}

/// 41.10: golfers named Dev or Mean are golfers; a club cell reading Mean is still a summary.
#[test]
fn golfers_named_dev_or_mean_are_kept() {
    let dir = tempfile::tempdir().unwrap();
    let g = fixture("corpus/garmin_r10_metric.csv");
    let text = g
        .replacen("Player 1", "Dev", 2)
        .replacen("Player 1", "Mean", 1);
    let (h, rows, err, _) = import(dir.path(), "g.csv", text.as_bytes(), "garmin", &[]);
    assert_eq!(rows.len(), 5, "{err}");
    assert_eq!(&col(&h, &rows, "golfer")[..3], ["Dev", "Dev", "Mean"]);
}

/// Shots without a club name go in as their own group (flight needs no club).
#[test]
fn shots_without_a_club_are_their_own_group() {
    let dir = tempfile::tempdir().unwrap();
    let tm =
        fixture("trackman_older.csv").replacen("\nDriver,Premium,101.0", "\n,Premium,101.0", 1);
    let (h, rows, err, out) = import(dir.path(), "t.csv", tm.as_bytes(), "trackman", TOE);
    assert_eq!(rows.len(), 8, "{err}");
    assert_eq!(col(&h, &rows, "group")[1], "(no club)");
    flies(dir.path(), &out);
}

/// UTF-16 without a byte-order mark is read as such; 5,000 unknown columns give a short note.
#[test]
fn utf16_without_a_bom_and_thousands_of_unknown_columns() {
    let dir = tempfile::tempdir().unwrap();
    let tm = fixture("trackman_older.csv");
    let utf16: Vec<u8> = tm.encode_utf16().flat_map(u16::to_le_bytes).collect();
    let (_, rows, err, _) = import(dir.path(), "w.csv", &utf16, "trackman", TOE);
    assert_eq!(rows.len(), 8, "{err}");
    assert!(err.contains("without a byte-order mark"), "{err}");
    let lines: Vec<&str> = tm.lines().collect();
    let extra = |f: &dyn Fn(usize) -> String| (0..5000).map(f).collect::<Vec<_>>().join(",");
    let mut text = format!("{},{}\n", lines[0], extra(&|i| format!("X{i}")));
    text.push_str(&format!("{},{}\n", lines[1], extra(&|_| String::new())));
    for l in &lines[2..] {
        text.push_str(&format!("{l},{}\n", extra(&|_| "1".to_owned())));
    }
    let (_, _, err, _) = import(dir.path(), "x.csv", text.as_bytes(), "trackman", TOE);
    assert!(err.contains("… and 4980 more"), "{err}");
    assert!(err.len() < 4000, "{} bytes of notes", err.len());
}

/// Units checked by physics: ball speeds in m/s read as mph give carries no launch could fly.
#[test]
fn speeds_in_the_wrong_unit_are_caught() {
    let dir = tempfile::tempdir().unwrap();
    let tm = fixture("trackman_older.csv");
    let lines: Vec<String> = tm.lines().map(str::to_owned).collect();
    // Ball speed written in m/s under an [mph] units row.
    let mut text = format!("{}\n{}\n", lines[0], lines[1]);
    for l in &lines[2..] {
        let mut cells: Vec<String> = l.split(',').map(str::to_owned).collect();
        if let Ok(v) = cells[11].parse::<f64>() {
            cells[11] = format!("{:.1}", v * 0.44704);
        }
        text.push_str(&cells.join(","));
        text.push('\n');
    }
    let path = dir.path().join("ms.csv");
    std::fs::write(&path, text).unwrap();
    let res = smash(&[
        "import",
        "--format",
        "trackman",
        s(&path),
        "--out",
        s(&dir.path().join("o.csv")),
        "--impact-offset-positive",
        "toe",
    ]);
    common::assert_refused(&res, &["ball speed / club speed", "ball speed in mph"]);
}

/// A mutation sweep over the vendor fixtures: the last shot cut at every cell boundary is left
/// out (never written with a cut cell) or, cut after its last mapped cell, kept whole; the
/// import never fails for it.
#[test]
fn every_fixture_cut_anywhere_loses_at_most_its_last_shot() {
    let dir = tempfile::tempdir().unwrap();
    for (file, preset, flags) in [
        ("trackman_older.csv", "trackman", TOE),
        ("uneekor_refine.csv", "uneekor", &[][..]),
        ("garmin_r10.csv", "garmin-r10", &[][..]),
        ("gspro.csv", "gspro", &[][..]),
        ("corpus/garmin_r50.csv", "garmin-r10", &[][..]),
        (
            "corpus/flightscope_cloud.csv",
            "flightscope-scrape",
            &[][..],
        ),
    ] {
        let text = fixture(file);
        let full = import(dir.path(), "full.csv", text.as_bytes(), preset, flags).1;
        // The last line holding a shot: the last whose first cell is not a summary word.
        let lines: Vec<&str> = text.lines().collect();
        let last = (0..lines.len())
            .rev()
            .find(|&i| {
                let c = lines[i].split(',').next().unwrap_or("").to_lowercase();
                !lines[i].trim().is_empty() && !["average", "avg", ""].contains(&c.as_str())
            })
            .unwrap();
        let cuts: Vec<usize> = lines[last].match_indices(',').map(|(i, _)| i).collect();
        for &at in &cuts {
            // Cut inside the next cell when it has two characters or more, else at the comma.
            let end = (at + 3).min(lines[last].len());
            let mut cut: Vec<&str> = lines[..last].to_vec();
            cut.push(&lines[last][..end]);
            let (_, rows, err, _) = import(
                dir.path(),
                "cut.csv",
                cut.join("\n").as_bytes(),
                preset,
                flags,
            );
            assert!(
                rows.len() == full.len() || rows.len() + 1 == full.len(),
                "{file} cut at {end}: {} of {} shots: {err}",
                rows.len(),
                full.len()
            );
            if rows.len() == full.len() {
                assert_eq!(rows.last(), full.last(), "{file} cut at {end}: {err}");
            }
        }
    }
}
