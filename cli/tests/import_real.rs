//! Real export layouts go in as exported: every vendor-format fixture in
//! `cli/tests/fixtures/import/` (built from real exports' headers and quirks, see
//! `tests/data/README.md`) and every real export in `tests/data/real/` imports with its
//! preset alone, writes every shot and no summary row, keeps the measured flight and the
//! provenance flags, and `smash flight` on the result reports the error against the export's
//! carry. Bad rows are counted, not fatal (`--strict` restores refusal); what a file gives twice
//! is checked.

use crate::cli_support;

use std::path::{Path, PathBuf};
use std::process::Output;

use cli_support::{repo, s, smash, unwrapped as stderr};

use crate::common;

fn fixture(name: &str) -> PathBuf {
    repo(&format!("cli/tests/fixtures/import/{name}"))
}

fn ok(out: &Output) -> String {
    assert!(out.status.success(), "smash failed: {}", stderr(out));
    stderr(out)
}

/// The shots file's header and records.
fn read(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut rdr = csv::Reader::from_path(path).unwrap();
    let h = rdr.headers().unwrap().iter().map(str::to_owned).collect();
    let rows = rdr
        .records()
        .map(|r| r.unwrap().iter().map(str::to_owned).collect())
        .collect();
    (h, rows)
}

fn column<'a>(h: &[String], rows: &'a [Vec<String>], name: &str) -> Vec<&'a str> {
    let i = h
        .iter()
        .position(|c| c == name)
        .unwrap_or_else(|| panic!("no column {name} in {h:?}"));
    rows.iter().map(|r| r[i].as_str()).collect()
}

/// Import `file` with `preset` (and `flags`) into `dir`; the shots file and the stderr.
fn import(dir: &Path, file: &Path, preset: &str, flags: &[&str]) -> (PathBuf, String) {
    let out = dir.join(format!("{preset}.csv"));
    let mut args = vec!["import", "--format", preset, s(file), "--out", s(&out)];
    args.extend_from_slice(flags);
    let err = ok(&smash(&args));
    (out, err)
}

/// Every fixture: its preset alone (plus the offset sign where the file holds offsets) writes
/// `shots` shots, none of them a summary row, and `smash flight` on the shots file writes the
/// carry error of every shot whose export gives a carry.
#[test]
fn every_vendor_layout_imports_as_exported() {
    let toe: &[&str] = &["--impact-offset-positive", "toe"];
    let cases: [(&str, &str, &[&str], usize); 16] = [
        ("trackman_normalized.csv", "trackman", toe, 12),
        ("trackman_older.csv", "trackman", toe, 8),
        ("trackman_semicolon.csv", "trackman", toe, 8),
        ("flightscope_fsgolf.csv", "flightscope", toe, 6),
        ("flightscope_cp1252.csv", "flightscope", toe, 5),
        ("garmin_r10.csv", "garmin-r10", &[], 9),
        ("uneekor_range.csv", "uneekor", &[], 8),
        ("uneekor_refine.csv", "uneekor", &[], 5),
        ("foresight_fsx.csv", "foresight", &[], 3),
        ("gspro.csv", "gspro", &[], 4),
        ("skytrak.csv", "skytrak", &[], 4),
        (
            "../../../../tests/data/real/rapsodo_mlm2pro_7i.csv",
            "rapsodo",
            &[],
            59,
        ),
        (
            "../../../../tests/data/real/rapsodo_mlm2pro_mixed.csv",
            "rapsodo",
            &[],
            15,
        ),
        (
            "../../../../tests/data/real/flightscope_mevoplus_8i.csv",
            "flightscope",
            toe,
            36,
        ),
        (
            "../../../../tests/data/real/range_export_9clubs.csv",
            "uneekor",
            &[],
            62,
        ),
        (
            "../../../../tests/data/real/uneekor_14clubs.csv",
            "uneekor",
            &[],
            66,
        ),
    ];
    for (file, preset, flags, shots) in cases {
        let dir = tempfile::tempdir().unwrap();
        let (out, err) = import(dir.path(), &fixture(file), preset, flags);
        let (h, rows) = read(&out);
        assert_eq!(rows.len(), shots, "{file}: {err}");
        if h.iter().any(|c| c == "group") {
            for g in column(&h, &rows, "group") {
                let summary = ["average", "avg", "dev", "deviation", "std. dev.", ""];
                assert!(
                    !summary.contains(&g.to_lowercase().as_str()),
                    "{file}: group '{g}'"
                );
            }
        }
        let carry = column(&h, &rows, "carry_yd");
        assert!(
            carry.iter().all(|c| !c.is_empty()),
            "{file}: carry {carry:?}"
        );
        let flown = dir.path().join("flown.csv");
        ok(&smash(&["flight", "--shots", s(&out), "--out", s(&flown)]));
        let (fh, frows) = read(&flown);
        let err_carry = column(&fh, &frows, "err_carry_yd");
        assert_eq!(err_carry.len(), shots, "{file}");
        for e in err_carry {
            let e: f64 = e
                .parse()
                .unwrap_or_else(|_| panic!("{file}: err_carry '{e}'"));
            assert!(
                e.is_finite() && e.abs() < 120.0,
                "{file}: carry error {e} yd"
            );
        }
    }
}

/// TrackMan's normalized export: blank impact cells keep the shot (for flight), estimated spin
/// and the vendor-modelled flight are flagged, the `Condition` sentence gives the conditions,
/// and the summary says all of it; `--strict` refuses at the first blank impact cell; compare
/// leaves out what lacks an impact location and what was estimated, and says so.
#[test]
fn trackman_normalized_summary_flags_and_strict() {
    let dir = tempfile::tempdir().unwrap();
    let file = fixture("trackman_normalized.csv");
    let toe = ["--impact-offset-positive", "toe"];
    let (out, err) = import(dir.path(), &file, "trackman", &toe);
    for needle in [
        "2 of 12 shot(s) have no impact location (line(s) 6, 10)",
        "2 of 12 shot(s) have spin the monitor estimated",
        "12 of 12 shot(s) have a carry from the vendor's flight model",
    ] {
        assert!(err.contains(needle), "missing {needle:?} in: {err}");
    }
    let (h, rows) = read(&out);
    let z = column(&h, &rows, "impact_z_mm");
    assert_eq!((z[2], z[6]), ("", ""));
    assert!(z.iter().filter(|v| v.is_empty()).count() == 2, "{z:?}");
    assert_eq!(
        column(&h, &rows, "spin_estimated"),
        ["0", "0", "0", "1", "0", "0", "0", "0", "1", "0", "0", "0"]
    );
    assert!(column(&h, &rows, "flight_modelled")
        .iter()
        .all(|f| *f == "1"));
    assert!(column(&h, &rows, "ball_type")
        .iter()
        .all(|b| *b == "Premium"));
    assert!(column(&h, &rows, "altitude_m").iter().all(|a| *a == "0"));
    for t in column(&h, &rows, "air_temperature_c") {
        assert!((t.parse::<f64>().unwrap() - 25.0).abs() < 1e-9, "{t}");
    }
    // --strict: the first blank impact cell refuses the file, with its line and column.
    let strict = smash(&[
        "import",
        "--format",
        "trackman",
        s(&file),
        "--out",
        s(&dir.path().join("x.csv")),
        "--impact-offset-positive",
        "toe",
        "--strict",
    ]);
    common::assert_refused(&strict, &[":6:", "Impact Height", "empty cell"]);
    // compare on the export leaves out 2 without impact location and 2 with estimated spin.
    let cmp = smash(&[
        "compare",
        "--club",
        s(&repo("configs/clubs/paper_driver.toml")),
        "--shots",
        s(&file),
        "--format",
        "trackman",
        "--impact-offset-positive",
        "toe",
        "--json",
    ]);
    let err = ok(&cmp);
    assert!(
        err.contains("left out 2 of 12 rows: no impact location (line(s) 6, 10"),
        "{err}"
    );
    assert!(
        err.contains("left out 2 of 12 rows: estimated spin (spin_estimated = 1"),
        "{err}"
    );
    let json: serde_json::Value = serde_json::from_slice(&cmp.stdout).unwrap();
    assert_eq!(json["n_shots"].as_u64(), Some(8), "{json}");
    let with = smash(&[
        "compare",
        "--club",
        s(&repo("configs/clubs/paper_driver.toml")),
        "--shots",
        s(&file),
        "--format",
        "trackman",
        "--impact-offset-positive",
        "toe",
        "--json",
        "--include-estimated",
    ]);
    let json: serde_json::Value = serde_json::from_slice(&with.stdout).unwrap();
    assert_eq!(json["n_shots"].as_u64(), Some(10), "{}", stderr(&with));
}

/// A launch-only export (no dynamic loft or impact location): the import writes it for flight
/// and says the impact model cannot use it.
#[test]
fn launch_only_exports_import_for_flight() {
    let dir = tempfile::tempdir().unwrap();
    let (out, err) = import(dir.path(), &fixture("garmin_r10.csv"), "garmin-r10", &[]);
    assert!(
        err.contains("9 shots (0 with a complete delivery)"),
        "{err}"
    );
    assert!(
        err.contains("1 of 9 shot(s) have spin the monitor estimated"),
        "{err}"
    );
    let (h, rows) = read(&out);
    assert!(!h.iter().any(|c| c == "dynamic_loft_deg"), "{h:?}");
    // US units converted; Garmin's sidespin (+ = curving left) turned to the shots file's sign.
    let side: Vec<f64> = column(&h, &rows, "sidespin_rpm")
        .iter()
        .map(|v| v.parse().unwrap())
        .collect();
    let azimuth_right = column(&h, &rows, "sidespin_rpm").len();
    assert_eq!(side.len(), azimuth_right);
    // compare refuses it with the reason.
    let cmp = smash(&[
        "compare",
        "--club",
        s(&repo("configs/clubs/paper_driver.toml")),
        "--shots",
        s(&out),
    ]);
    common::assert_refused(&cmp, &["missing required column(s)", "dynamic_loft_deg"]);
}

/// The same Garmin file read by a mapping that forgets Garmin's sidespin sign: back and side
/// spin disagree with rate and axis on every shot, and the file is refused naming the sign.
#[test]
fn a_flipped_sidespin_is_caught() {
    let dir = tempfile::tempdir().unwrap();
    let preset = std::fs::read_to_string(repo("configs/import/garmin-r10.toml")).unwrap();
    let wrong = preset.replace(
        "source = [\"Sidespin\"]\nsign = -1",
        "source = [\"Sidespin\"]",
    );
    assert_ne!(wrong, preset);
    let map = dir.path().join("garmin_wrong.toml");
    std::fs::write(&map, wrong).unwrap();
    let res = smash(&[
        "import",
        "--format",
        s(&map),
        s(&fixture("garmin_r10.csv")),
        "--out",
        s(&dir.path().join("x.csv")),
    ]);
    common::assert_refused(
        &res,
        &[
            "disagree",
            "of 9 Garmin R10 shots",
            "sign of sidespin flipped",
        ],
    );
}

/// Quirks: a Windows-1252 byte is read and named; a decimal comma in the last column of a
/// comma-separated file shifts the row, which is left out with its line (never read as −3);
/// an unnamed column holding data is reported; UTF-16 is read as such.
#[test]
fn encodings_and_shifted_rows() {
    let dir = tempfile::tempdir().unwrap();
    let toe = ["--impact-offset-positive", "toe"];
    let (_, err) = import(
        dir.path(),
        &fixture("flightscope_cp1252.csv"),
        "flightscope",
        &toe,
    );
    assert!(
        err.contains("read as Windows-1252 (the first on line 1: 0xB0"),
        "{err}"
    );

    let text = std::fs::read_to_string(fixture("trackman_older.csv")).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    // Line 3, the first shot: the last cell written with a decimal comma, unquoted.
    lines[2] = format!("{},5", lines[2]);
    let shifted = dir.path().join("shifted.csv");
    std::fs::write(&shifted, lines.join("\n") + "\n").unwrap();
    let (out, err) = import(dir.path(), &shifted, "trackman", &toe);
    assert!(
        err.contains("left out 1 row(s): more cells than the header has columns (line(s) 3;"),
        "{err}"
    );
    assert_eq!(read(&out).1.len(), 7);
    let strict = smash(&[
        "import",
        "--format",
        "trackman",
        s(&shifted),
        "--out",
        s(&dir.path().join("y.csv")),
        "--impact-offset-positive",
        "toe",
        "--strict",
    ]);
    common::assert_refused(&strict, &[":3:", "cells where the header has"]);

    // A column without a name that holds data: noted by a preset, refused by a user mapping.
    let unnamed: String = text
        .lines()
        .enumerate()
        .map(|(i, l)| format!("{l},{}\n", if i < 2 { "" } else { "7" }))
        .collect();
    let path = dir.path().join("unnamed.csv");
    std::fs::write(&path, unnamed).unwrap();
    let (_, err) = import(dir.path(), &path, "trackman", &toe);
    assert!(
        err.contains("column 36 (no name in the header, holds data)"),
        "{err}"
    );
    let strict_map = std::fs::read_to_string(repo("configs/import/trackman.toml"))
        .unwrap()
        .replace("unknown_columns = \"note\"\n", "");
    let map = dir.path().join("tm_strict.toml");
    std::fs::write(&map, strict_map).unwrap();
    let res = smash(&[
        "import",
        "--format",
        s(&map),
        s(&path),
        "--out",
        s(&dir.path().join("z.csv")),
        "--impact-offset-positive",
        "toe",
    ]);
    common::assert_refused(&res, &["unknown column(s)", "column 36 (no name"]);

    // UTF-16 (here with a byte-order mark) is read as such, and said; broken UTF-16 is refused
    // in one line.
    let utf16 = dir.path().join("utf16.csv");
    let text = std::fs::read_to_string(fixture("trackman_older.csv")).unwrap();
    let mut bytes = vec![0xFF, 0xFE];
    bytes.extend(text.encode_utf16().flat_map(u16::to_le_bytes));
    std::fs::write(&utf16, &bytes).unwrap();
    let args = |f: &Path| {
        smash(&[
            "import",
            "--format",
            "trackman",
            s(f),
            "--out",
            s(&dir.path().join("u.csv")),
            "--impact-offset-positive",
            "toe",
        ])
    };
    let err = ok(&args(&utf16));
    assert!(
        err.contains("UTF-16 text (little-endian, with a byte-order mark)"),
        "{err}"
    );
    std::fs::write(&utf16, b"\xFF\xFEC\x00l\x00u\x00b").unwrap();
    common::assert_refused(&args(&utf16), &["not valid UTF-16", ":1:"]);
}

/// A mapping's `skip_lines` past the end of the file is refused at once (it used to spin).
#[test]
fn skip_lines_past_the_end_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("m.toml");
    std::fs::write(
        &map,
        "[export]\nname = \"M\"\nskip_lines = 9223372036854775807\n\n[[column]]\ntarget = \"ball_speed_mph\"\nsource = [\"Ball\"]\n",
    )
    .unwrap();
    let exp = dir.path().join("e.csv");
    std::fs::write(&exp, "Ball\n150\n").unwrap();
    let start = std::time::Instant::now();
    let res = smash(&[
        "import",
        "--format",
        s(&map),
        s(&exp),
        "--out",
        s(&dir.path().join("o.csv")),
    ]);
    common::assert_refused(
        &res,
        &["skip_lines = 9223372036854775807", "only 2 line(s)"],
    );
    assert!(start.elapsed().as_secs_f64() < 5.0);
}

/// A shots file whose row lacks its impact location: predict leaves it out and says so; under
/// --strict the file is refused naming the cell.
#[test]
fn shots_without_impact_location_are_left_out_and_counted() {
    let dir = tempfile::tempdir().unwrap();
    let shots = dir.path().join("shots.csv");
    std::fs::write(
        &shots,
        "shot_id,club_speed_mph,attack_angle_deg,club_path_deg,dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm\n\
         a,100,0,0,12,0,0,0\nb,100,0,0,12,0,,\nc,101,0,0,12,0,1,2\n",
    )
    .unwrap();
    let club = repo("configs/clubs/paper_driver.toml");
    let out = dir.path().join("p.csv");
    let res = smash(&[
        "predict",
        "--club",
        s(&club),
        "--shots",
        s(&shots),
        "--out",
        s(&out),
    ]);
    let err = ok(&res);
    assert!(
        err.contains(
            "left out 1 of 3 rows: no impact location (line(s) 3; --strict refuses the file)"
        ),
        "{err}"
    );
    assert_eq!(read(&out).1.len(), 2);
    let out2 = dir.path().join("q.csv");
    let res = smash(&[
        "predict",
        "--club",
        s(&club),
        "--shots",
        s(&shots),
        "--out",
        s(&out2),
        "--strict",
    ]);
    common::assert_refused(&res, &[":3:", "impact_y_mm", "empty cell"]);
    assert!(!out2.exists());
}

/// TrackMan's `Date` cell (the date and the time of day) is kept as `datetime` (in one form), so that an
/// export without golfers is cross-validated by session or by blocks of consecutive shots, never
/// shot by shot: here one evening's session, so time blocks.
#[test]
fn trackman_dates_become_the_folds() {
    let dir = tempfile::tempdir().unwrap();
    let toe = ["--impact-offset-positive", "toe"];
    let (out, _) = import(
        dir.path(),
        &fixture("trackman_normalized.csv"),
        "trackman",
        &toe,
    );
    let (h, rows) = read(&out);
    let dates = column(&h, &rows, "datetime");
    // Written in one form (`5/6/2026 7:01:07 PM` in the export).
    assert_eq!(dates[0], "2026-05-06 19:01:07", "{dates:?}");
    assert!(
        dates.iter().all(|d| d.starts_with("2026-05-06 ")),
        "{dates:?}"
    );
    let opts = smash::data::shots::ReadOptions {
        include_estimated: true,
        ..Default::default()
    };
    let table = smash::data::shots::read_shots_with(&out, opts).unwrap();
    let keys = smash::data::sessions::fold_keys(&table, 5)
        .unwrap()
        .expect("folds by the dates, not by shot");
    assert_eq!(keys.kind, smash::stats::KeyKind::TimeBlock);
    assert_eq!(keys.column, "datetime");
}
