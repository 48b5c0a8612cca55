//! Real exports of a third round (found in public repositories by a scout on 29 Nov 2026, none
//! shippable: no licence), each in a fixture of its exact layout with made-up values
//! (`tests/data/README.md`, "Unseen exports, third round"):
//!
//! - SkyTrak's app CSV, legacy and current (quoted) layouts: title lines, `SIDE` twice (side
//!   spin and side angle) told apart only by a units row without brackets, the club as a row of
//!   its own above its shots, `AVG` rows, notes at the end;
//! - Awesome Golf's export (read as SkyTrak before, its face, club and spin reading unused): a
//!   face and dynamic loft made from the launch;
//! - the original Mevo's export, whose refusal named a column the file has;
//! - Square Golf's range export (read as Uneekor before): club speed in m/s beside a ball speed
//!   in mph, `T708` for topspin.

use crate::cli_support;

use std::path::PathBuf;

use cli_support::{csv_rows as rows, repo, s, smash, unwrapped as stderr};

fn unseen(name: &str) -> PathBuf {
    repo(&format!("cli/tests/fixtures/import/unseen/{name}"))
}

#[test]
fn skytrak_exports_of_both_layouts_import_with_their_clubs_and_both_sides() {
    let dir = tempfile::tempdir().unwrap();
    for (name, groups, shots) in [
        (
            "skytrak_legacy.csv",
            ["8I", "8I", "D", "D", "D"].as_slice(),
            5,
        ),
        (
            "skytrak_current.csv",
            ["7 IRON", "7 IRON", "DRIVER"].as_slice(),
            3,
        ),
    ] {
        let out = dir.path().join(format!("{name}.shots.csv"));
        for format in ["auto", "skytrak"] {
            let o = smash(&[
                "import",
                "--format",
                format,
                s(&unseen(name)),
                "--out",
                s(&out),
            ]);
            let e = stderr(&o);
            assert!(o.status.success(), "{name} {format}:\n{e}");
            assert!(
                e.contains(
                    "2 row(s) with text in the first cell only read as the 'Club' of the rows \
                     under them"
                ) && e.contains("skipped 2 summary row(s)"),
                "{name}:\n{e}"
            );
            // Whole-mph speeds: their ratio agrees with the factor within its rounding.
            assert!(!e.contains("smash factor disagrees"), "{name}:\n{e}");
            let r = rows(&out);
            assert_eq!(r.len(), shots, "{name}: {r:?}");
            let got: Vec<&str> = r.iter().map(|x| x["group"].as_str()).collect();
            assert_eq!(got, groups, "{name}");
        }
        let r = rows(&out);
        // The RPM `SIDE` is the side spin, the DEG `SIDE` the launch direction.
        let (spin, side) = if name.contains("legacy") {
            ("-350", "3")
        } else {
            ("510", "2.6")
        };
        assert_eq!(r[0]["sidespin_rpm"], spin, "{name}");
        assert_eq!(r[0]["azimuth_deg"], side, "{name}");
        // FTT is the face angle to the target, PATH the club path.
        let (face, path) = if name.contains("legacy") {
            ("1.8", "3.1")
        } else {
            ("1.4", "3.3")
        };
        assert_eq!(r[0]["face_angle_deg"], face, "{name}");
        assert_eq!(r[0]["club_path_deg"], path, "{name}");
        assert_eq!(r[0]["flight_modelled"], "1", "{name}");
    }
}

#[test]
fn an_awesome_golf_export_is_read_as_itself_with_its_face_derived_from_the_launch() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shots.csv");
    let o = smash(&["import", s(&unseen("awesome_golf.csv")), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("read as awesome-golf (31 of the file's 31 column(s) known to it)"),
        "{e}"
    );
    assert!(!e.contains("not used by"), "{e}");
    assert!(
        e.contains("1 of 4 shot(s) have spin the monitor estimated"),
        "{e}"
    );
    let r = rows(&out);
    assert_eq!(r.len(), 4);
    assert_eq!(r[0]["group"], "Driver");
    assert_eq!(r[3]["group"], "7 Iron");
    assert_eq!(r[0]["face_angle_from"], "derived_from_launch");
    assert_eq!(r[0]["face_angle_deg"], "1.2");
    assert_eq!(r[2]["spin_estimated"], "1");
    // The loft the app made from the launch angle is not read.
    assert!(!r[0].contains_key("dynamic_loft_deg"), "{:?}", r[0]);
    // Peak Height in feet, written in yards.
    let apex: f64 = r[0]["apex_yd"].parse().unwrap();
    assert!((apex - 78.2 / 3.0).abs() < 1e-9, "{apex}");
    // Rate and axis make back and side spin; + axis (a fade) is + side spin.
    let side: f64 = r[0]["sidespin_rpm"].parse().unwrap();
    let back: f64 = r[0]["backspin_rpm"].parse().unwrap();
    assert!(
        (side - 2780.0 * 4.6f64.to_radians().sin()).abs() < 1e-6 && back > 2700.0,
        "{side} {back}"
    );
}

#[test]
fn an_original_mevo_export_is_refused_naming_what_it_lacks_not_what_it_has() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shots.csv");
    for format in ["auto", "flightscope"] {
        let o = smash(&[
            "import",
            "--format",
            format,
            s(&unseen("mevo_original.csv")),
            "--out",
            s(&out),
        ]);
        let e = stderr(&o);
        assert!(!o.status.success());
        assert!(
            e.contains("'Launch H'") && e.contains("'Spin Axis'") && !e.contains("'Launch V'"),
            "{format}: {e}"
        );
        assert!(!out.exists());
    }
    let o = smash(&[
        "import",
        "--format",
        "flightscope",
        s(&unseen("mevo_original.csv")),
        "--out",
        s(&out),
    ]);
    assert!(stderr(&o).contains("`assume` value"), "{}", stderr(&o));
}

#[test]
fn a_square_golf_export_reads_its_club_speed_in_m_s_and_its_topspin() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shots.csv");
    let o = smash(&["import", s(&unseen("square_golf.csv")), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("read as square-golf (22 of the file's 22 column(s) known to it)"),
        "{e}"
    );
    assert!(e.contains("skipped 2 average row(s)"), "{e}");
    assert!(e.contains("ClubSpeed in m/s"), "{e}");
    let r = rows(&out);
    assert_eq!(r.len(), 4, "{r:?}");
    // Line 4: every club cell 0, the club not measured.
    assert_eq!(r[0]["club_speed_mph"], "");
    assert_eq!(r[0]["face_angle_deg"], "");
    // 36.9 m/s.
    let club: f64 = r[1]["club_speed_mph"].parse().unwrap();
    assert!((club - 36.9 / 0.44704).abs() < 1e-9, "{club}");
    assert_eq!(r[1]["face_angle_deg"], "-2.4");
    assert_eq!(r[1]["club_path_deg"], "1.1");
    // A topped ball: `T35` is 35 rpm of topspin.
    assert_eq!(r[2]["backspin_rpm"], "-35");
    assert_eq!(r[2]["sidespin_rpm"], "-654");
    // Impact is not read: its vertical zero is not the face centre.
    assert!(!r[1].contains_key("impact_y_mm"), "{:?}", r[1]);
}
