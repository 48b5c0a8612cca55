//! Real exports no one here had seen (found in public repositories on 29 Nov 2026, none
//! shippable: no licence), each in a fixture of its exact layout with made-up values
//! (`tests/data/README.md`, "Unseen exports"):
//!
//! - a Rapsodo MLM2PRO app set to km/h and metres, its file stating no unit: refused with the
//!   ratio the metric reading gives, and imported by a copy of the preset in those units;
//! - a GSPro export re-saved with a spreadsheet's AVERAGE row (`#DIV/0!` cells): the row is
//!   left out and counted; shots whose club angles are all 0 beside GSPro's own "not measured"
//!   0 of `AoA` have them read as not measured;
//! - Garmin's `Club Face`, a function of the launch: read as `derived_from_launch`.

use crate::cli_support;

use std::path::PathBuf;

use cli_support::{csv_rows as rows, repo, s, smash, unwrapped as stderr, write};

fn unseen(name: &str) -> PathBuf {
    repo(&format!("cli/tests/fixtures/import/unseen/{name}"))
}

#[test]
fn a_metric_rapsodo_file_is_refused_with_its_metric_reading_and_imports_in_those_units() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shots.csv");
    let file = unseen("rapsodo_mlm2pro_metric.csv");
    let o = smash(&["import", s(&file), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(!o.status.success(), "imported:\n{e}");
    assert!(!out.exists(), "a refused import wrote its output");
    let line = e.lines().find(|l| l.starts_with("error:")).unwrap();
    assert!(
        line.contains("column 'Carry Distance' (read in yd, the ball speed in mph)")
            && line.contains("; read as km/h and yd, 0.9")
            && line.contains("; read as km/h and m, 1.0")
            && line.contains("the values are in km/h and m; the file does not state its units")
            && line.contains("unit = \"km/h\" for the speeds and unit = \"m\""),
        "{line}"
    );
    let ratio: f64 = line.split("carries is ").nth(1).unwrap()[..5]
        .parse()
        .unwrap();
    assert!(ratio < 0.7, "{ratio}");
    // The fix the message names: a copy of the preset in km/h and metres.
    let preset = std::fs::read_to_string(repo("configs/import/rapsodo.toml")).unwrap();
    let metric = preset
        .replace("default_unit = \"mph\"", "default_unit = \"km/h\"")
        .replace("default_unit = \"yd\"", "default_unit = \"m\"")
        .replace("default_unit = \"ft\"", "default_unit = \"m\"");
    let mapping = write(dir.path(), "rapsodo_metric.toml", &metric);
    let o = smash(&[
        "import",
        "--format",
        s(&mapping),
        s(&file),
        "--out",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("carries is"), "{}", stderr(&o));
    let r = rows(&out);
    assert_eq!(r.len(), 9);
    let ball: f64 = r[0]["ball_speed_mph"].parse().unwrap();
    assert!((ball - 180.9 / 1.609_344).abs() < 1e-9, "{ball}");
    let carry: f64 = r[0]["carry_yd"].parse().unwrap();
    assert!((carry - 143.3 / 0.9144).abs() < 1e-9, "{carry}");
}

#[test]
fn a_spreadsheet_average_row_is_left_out_and_gspro_zero_club_angles_are_not_measured() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shots.csv");
    let file = unseen("gspro_average_row.csv");
    let o = smash(&["import", s(&file), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("left out 1 row(s): a cell holds a spreadsheet's error value"),
        "{e}"
    );
    assert!(
        e.contains("'#DIV/0!' is a spreadsheet's error value"),
        "{e}"
    );
    let r = rows(&out);
    assert_eq!(r.len(), 4, "the average row is no shot");
    assert!(r.iter().all(|row| row["group"] == "I7"));
    // Lines 3 and 5: Path 0, AoA 0 (GSPro's "not measured"), FaceToTarget 0: the club was not
    // measured, so none of its angles is kept; lines 2 and 4 keep theirs.
    for (row, measured) in r.iter().zip([true, false, true, false]) {
        assert_eq!(!row["club_path_deg"].is_empty(), measured, "{row:?}");
        assert_eq!(!row["face_angle_deg"].is_empty(), measured, "{row:?}");
    }
    assert!(e.contains("club angles all exactly 0"), "{e}");
    // Under --strict such a row refuses the file, naming its line and column (here the
    // header and the average row alone: GSPro's AoA 0 of the shots is an incomplete row
    // there, refused first).
    let text = std::fs::read_to_string(&file).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let avg = write(
        dir.path(),
        "avg.csv",
        &format!("{}\n{}\n", lines[0], lines[lines.len() - 1]),
    );
    let o = smash(&["import", "--strict", s(&avg), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(!o.status.success());
    assert!(
        e.contains("avg.csv:2: column 'Club': '#DIV/0!' is a spreadsheet's error value"),
        "{e}"
    );
}

#[test]
fn garmins_club_face_is_read_as_derived_from_the_launch() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shots.csv");
    let file = repo("cli/tests/fixtures/import/garmin_r10.csv");
    let o = smash(&[
        "import",
        "--format",
        "garmin-r10",
        s(&file),
        "--out",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let r = rows(&out);
    let with_face: Vec<_> = r
        .iter()
        .filter(|x| !x["face_angle_deg"].is_empty())
        .collect();
    assert!(!with_face.is_empty());
    assert!(
        with_face
            .iter()
            .all(|x| x["face_angle_from"] == "derived_from_launch"),
        "{with_face:?}"
    );
}

#[test]
fn a_norwegian_garmin_export_is_named_as_such_and_a_mapping_reads_its_units() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shots.csv");
    let file = unseen("garmin_r50_norwegian.csv");
    let o = smash(&["import", s(&file), "--out", s(&out)]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("no preset reads this file; the closest: ")
            && stderr(&o).contains("; its header looks like another language's"),
        "{}",
        stderr(&o)
    );
    // A mapping naming the Norwegian columns; the units row's `[km/t]`, `[opm]` and `[m]` are
    // read as written.
    let mapping = write(
        dir.path(),
        "garmin_no.toml",
        r#"[export]
name = "Garmin (Norwegian)"
unknown_columns = "note"
flight_modelled = true

[[column]]
target = "group"
source = ["Type golfkølle"]

[[column]]
target = "ball_speed_mph"
source = ["Ballhastighet"]

[[column]]
target = "launch_angle_deg"
source = ["Slagvinkel"]

[[column]]
target = "azimuth_deg"
source = ["Slagretning"]

[[column]]
target = "backspin_rpm"
source = ["Underskru"]

[[column]]
target = "sidespin_rpm"
source = ["Sideskru"]
sign = -1

[[column]]
target = "carry_yd"
source = ["Carry-distanse"]
"#,
    );
    let o = smash(&[
        "import",
        "--format",
        s(&mapping),
        s(&file),
        "--out",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let r = rows(&out);
    assert_eq!(r.len(), 3);
    let ball: f64 = r[0]["ball_speed_mph"].parse().unwrap();
    assert!((ball - 128.3342 / 1.609_344).abs() < 1e-9, "{ball}");
    let carry: f64 = r[2]["carry_yd"].parse().unwrap();
    assert!((carry - 122.88 / 0.9144).abs() < 1e-9, "{carry}");
    assert_eq!(r[1]["backspin_rpm"], "7588.903");
}

#[test]
fn a_shots_file_given_to_import_is_named_as_one() {
    let dir = tempfile::tempdir().unwrap();
    let shots = write(
        dir.path(),
        "shots.csv",
        "shot_id,group,ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,sidespin_rpm\n\
         s1,A,150.2,12.1,0.5,2650,-120\n",
    );
    let o = smash(&[
        "import",
        s(&shots),
        "--out",
        s(&dir.path().join("again.csv")),
    ]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("this is a shots file already")
            && stderr(&o).contains("--format shots"),
        "{}",
        stderr(&o)
    );
}
