//! A fifth hostile pass (29 Nov 2026): wrong numbers written without a word, a whole command
//! lost to one row, and a CSV whose cells slipped.

use crate::cli_support;

use cli_support::{club, csv_rows, repo, s, smash, synth_world, unwrapped as stderr, write};

/// The CSV rows of `path` as cells (no header handling), for field counts.
fn raw_rows(path: &std::path::Path) -> Vec<Vec<String>> {
    csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .from_path(path)
        .unwrap()
        .records()
        .map(|r| r.unwrap().iter().map(str::to_owned).collect())
        .collect()
}

#[test]
fn an_export_whose_club_speed_is_in_another_unit_than_it_says_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let text =
        std::fs::read_to_string(repo("cli/tests/fixtures/import/unseen/awesome_golf.csv")).unwrap();
    // Club speeds in km/h under a units row that says mph.
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    for l in &mut lines[2..] {
        let mut cells: Vec<String> = l.split(',').map(str::to_owned).collect();
        let v: f64 = cells[4].parse().unwrap();
        cells[4] = format!("{:.2}", v * 1.609_344);
        *l = cells.join(",");
    }
    let file = write(dir.path(), "kmh.csv", &(lines.join("\n") + "\n"));
    let out = dir.path().join("shots.csv");
    let o = smash(&["import", s(&file), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(!o.status.success(), "{e}");
    assert!(
        e.contains("the smash factor disagrees with ball speed / club speed on 4 of 4")
            && e.contains("0.621 if a club speed in km/h is read as mph"),
        "{e}"
    );
    assert!(!out.exists());
}

#[test]
fn an_export_most_of_whose_rows_cannot_be_used_is_refused_not_cut_down() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(repo("cli/tests/fixtures/import/unseen/skytrak_legacy.csv"))
        .unwrap();
    // The twins' units swapped: the side spin read as degrees, the side angle as rpm.
    let file = write(
        dir.path(),
        "swapped.csv",
        &text.replace("RPM,RPM,DEG", "RPM,DEG,RPM"),
    );
    let out = dir.path().join("shots.csv");
    let o = smash(&["import", s(&file), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(!o.status.success(), "{e}");
    assert!(
        e.contains(
            "of 5 rows of the SkyTrak export hold values that cannot be used, more than half"
        ),
        "{e}"
    );
    assert!(!out.exists());
}

#[test]
fn predict_flight_keeps_every_prediction_when_one_launch_cannot_fly() {
    let dir = tempfile::tempdir().unwrap();
    let shots = synth_world(dir.path(), "paper_world", 1);
    let text = std::fs::read_to_string(&shots).unwrap();
    let mut lines: Vec<String> = text.lines().take(21).map(str::to_owned).collect();
    let head: Vec<&str> = lines[0].split(',').collect();
    let speed = head.iter().position(|h| *h == "club_speed_mph").unwrap();
    let mut cells: Vec<String> = lines[3].split(',').map(str::to_owned).collect();
    cells[speed] = "190".into();
    lines[3] = cells.join(",");
    let file = write(dir.path(), "fast.csv", &(lines.join("\n") + "\n"));
    let out = dir.path().join("pred.csv");
    let o = smash(&[
        "predict",
        "--club",
        &club(),
        "--shots",
        s(&file),
        "--out",
        s(&out),
        "--flight",
    ]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("1 of 20 predicted launch(es) could not be flown, their flight columns left empty (line(s) 4;"),
        "{e}"
    );
    let r = csv_rows(&out);
    assert_eq!(r.len(), 20);
    assert_eq!(r[2]["pred_carry_yd"], "");
    assert!(!r[2]["pred_ball_speed_mph"].is_empty());
    assert!(r[3]["pred_carry_yd"].parse::<f64>().unwrap() > 100.0);
}

#[test]
fn compare_writes_group_names_with_commas_and_quotes_as_csv_cells() {
    let dir = tempfile::tempdir().unwrap();
    let shots = synth_world(dir.path(), "paper_world", 1);
    let text = std::fs::read_to_string(&shots).unwrap();
    let mut rdr = csv::Reader::from_reader(text.as_bytes());
    let head = rdr.headers().unwrap().clone();
    let g = head.iter().position(|h| h == "group").unwrap();
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(&head).unwrap();
    for rec in rdr.records() {
        let rec = rec.unwrap();
        let cells: Vec<String> = rec
            .iter()
            .enumerate()
            .map(|(i, c)| {
                if i == g {
                    format!("Driver, \"{c}\"")
                } else {
                    c.to_owned()
                }
            })
            .collect();
        w.write_record(&cells).unwrap();
    }
    let file = write(
        dir.path(),
        "groups.csv",
        &String::from_utf8(w.into_inner().unwrap()).unwrap(),
    );
    let out = dir.path().join("cmp");
    let o = smash(&[
        "compare",
        "--club",
        &club(),
        "--shots",
        s(&file),
        "--out-dir",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows = raw_rows(&out.join("table2.csv"));
    assert!(rows.iter().all(|r| r.len() == 10), "{rows:?}");
    assert!(rows[1][0].starts_with("Driver, \""), "{:?}", rows[1]);
}

#[test]
fn twins_without_units_are_refused_saying_how_to_tell_them_apart() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(repo("cli/tests/fixtures/import/unseen/skytrak_legacy.csv"))
        .unwrap();
    let no_units: Vec<&str> = text.lines().filter(|l| !l.starts_with("#,")).collect();
    let file = write(dir.path(), "nounits.csv", &(no_units.join("\n") + "\n"));
    let out = dir.path().join("shots.csv");
    let o = smash(&["import", "--format", "skytrak", s(&file), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(!o.status.success());
    assert!(
        e.contains("nounits.csv:4: column 'SIDE': the header has this column twice (columns 7 and 8) and nothing tells the two apart: give each its unit"),
        "{e}"
    );
}

#[test]
fn a_file_that_names_its_clubs_in_a_column_keeps_them() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(
        dir.path(),
        "own_club.csv",
        "Club,Ball Speed,Launch Angle,Side Angle,Back Spin,Side Spin,Carry\n\
         7 Iron,112,17.4,2.6,6120,510,158\n\
         7 Iron,115,16.8,-1.2,5870,-440,163\n\
         NOTES,,,,,,\n",
    );
    let out = dir.path().join("shots.csv");
    let o = smash(&["import", "--format", "skytrak", s(&file), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(!e.contains("read as the 'Club'"), "{e}");
    let r = csv_rows(&out);
    assert_eq!(r.len(), 2);
    assert_eq!(r[1]["group"], "7 Iron");
}

#[test]
fn nan_cells_and_scaled_sentinels_are_not_measured() {
    let dir = tempfile::tempdir().unwrap();
    let text =
        std::fs::read_to_string(repo("cli/tests/fixtures/import/trackman_older.csv")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let head: Vec<&str> = lines[0].split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
    let mut rows: Vec<Vec<String>> = lines[2..]
        .iter()
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect();
    // pandas' missing value in a column the launch does not need, TrackMan's sentinel scaled
    // by ten in the flight's height.
    rows[0][col("Carry Flat - Length")] = "NaN".into();
    rows[1][col("Max Height - Height")] = "-21474836480".into();
    let body: Vec<String> = rows.iter().map(|r| r.join(",")).collect();
    let file = write(
        dir.path(),
        "nan.csv",
        &format!("{}\n{}\n{}\n", lines[0], lines[1], body.join("\n")),
    );
    let import = |file: &std::path::Path, out: &std::path::Path| {
        let o = smash(&[
            "import",
            "--format",
            "trackman",
            s(file),
            "--impact-offset-positive",
            "toe",
            "--out",
            s(out),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        (stderr(&o), csv_rows(out))
    };
    let (e0, r0) = import(
        &repo("cli/tests/fixtures/import/trackman_older.csv"),
        &dir.path().join("as_is.csv"),
    );
    let (e, r) = import(&file, &dir.path().join("shots.csv"));
    assert!(e.contains("a vendor's sentinel for not measured"), "{e}");
    assert_eq!(e.contains("left out"), e0.contains("left out"), "{e}");
    assert_eq!(r.len(), r0.len());
    assert_eq!(r[0]["shot_id"], r0[0]["shot_id"]);
    assert_eq!(r[0]["carry_yd"], "");
    assert_eq!(r[1]["apex_yd"], "");
}

#[test]
fn a_semicolon_export_with_title_lines_without_separators_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(repo("cli/tests/fixtures/import/unseen/skytrak_legacy.csv"))
        .unwrap();
    // Title lines as a spreadsheet saves them in a semicolon locale: no separator left.
    let semi: Vec<String> = text
        .lines()
        .map(|l| {
            if l.starts_with("PRACTICE") || l.starts_with("PLAYER") {
                l.trim_end_matches(',').to_owned()
            } else {
                l.replace(',', ";")
            }
        })
        .collect();
    let file = write(dir.path(), "semi.csv", &(semi.join("\n") + "\n"));
    let out = dir.path().join("shots.csv");
    let o = smash(&["import", s(&file), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("read as skytrak") && e.contains("separated by semicolons"),
        "{e}"
    );
    assert_eq!(csv_rows(&out).len(), 5);
}

#[test]
fn a_spin_axis_past_ninety_degrees_is_named_as_topspin() {
    let dir = tempfile::tempdir().unwrap();
    let text =
        std::fs::read_to_string(repo("cli/tests/fixtures/import/unseen/awesome_golf.csv")).unwrap();
    let file = write(
        dir.path(),
        "axis.csv",
        &text.replace(",2780,4.6,", ",2780,95,"),
    );
    let out = dir.path().join("shots.csv");
    let o = smash(&["import", s(&file), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("1 of 4 shot(s) have topspin, back spin below 0 (line(s) 3)"),
        "{e}"
    );
}

#[test]
fn flight_on_a_raw_export_says_to_import_it_first() {
    let o = smash(&[
        "flight",
        "--shots",
        s(&repo("cli/tests/fixtures/import/trackman_older.csv")),
        "--out",
        s(&tempfile::tempdir().unwrap().path().join("f.csv")),
    ]);
    let e = stderr(&o);
    assert!(!o.status.success());
    assert!(e.contains("smash import EXPORT.csv --out shots.csv"), "{e}");
}

#[test]
fn whatif_blames_the_swing_not_the_club_for_a_launch_too_fast_to_fly() {
    let o = smash(&[
        "whatif",
        "--club",
        &club(),
        "--speed",
        "260",
        "--moi-scale",
        "1.1",
    ]);
    let e = stderr(&o);
    assert!(!o.status.success());
    assert!(e.starts_with("error: the swing of --speed 260 mph"), "{e}");
    assert!(!e.contains("paper_driver.toml"), "{e}");
}

#[test]
fn a_gspro_file_with_a_date_column_keeps_its_sessions() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(repo("cli/tests/fixtures/import/gspro.csv")).unwrap();
    let dated: Vec<String> = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == 0 {
                format!("{l},Date")
            } else {
                format!("{l},4/12/2025 11:{:02}", 40 + i % 10)
            }
        })
        .collect();
    let file = write(dir.path(), "dated.csv", &(dated.join("\n") + "\n"));
    let out = dir.path().join("shots.csv");
    let o = smash(&["import", "--format", "gspro", s(&file), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(!e.contains("Date"), "{e}");
    let r = csv_rows(&out);
    assert!(
        r[0]["datetime"].starts_with("2025-04-12 11:4"),
        "{:?}",
        r[0]
    );
}

#[test]
fn a_spin_reading_the_preset_does_not_know_is_not_taken_as_measured() {
    let dir = tempfile::tempdir().unwrap();
    let text =
        std::fs::read_to_string(repo("cli/tests/fixtures/import/unseen/awesome_golf.csv")).unwrap();
    let file = write(
        dir.path(),
        "reading.csv",
        &text.replacen(",Actual,", ",Est.,", 1),
    );
    let out = dir.path().join("shots.csv");
    let o = smash(&["import", s(&file), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("2 of 4 shot(s) have spin the monitor estimated"),
        "{e}"
    );
    let r = csv_rows(&out);
    assert_eq!(r[0]["spin_estimated"], "1");
    assert_eq!(r[1]["spin_estimated"], "0");
}

#[test]
fn zero_solver_iterations_are_refused_up_front() {
    for cmd in ["diagnose", "calibrate"] {
        let o = smash(&[
            cmd,
            "--club",
            &club(),
            "--shots",
            "none.csv",
            "--max-iters",
            "0",
        ]);
        let e = stderr(&o);
        assert!(!o.status.success());
        assert!(
            e.contains("'0': the solver's iteration limit is a whole number of at least 1"),
            "{cmd}: {e}"
        );
    }
}
