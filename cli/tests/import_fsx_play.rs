//! More real exports no one here had seen (found in public repositories on 29 Nov 2026 by a
//! scout, none shippable: no licence), each in a fixture of its exact layout with made-up values
//! or as a one-cell change of a shipped fixture (`tests/data/README.md`, "Unseen exports"):
//!
//! - Foresight's FSX Play / FSX Live session export: `Push/Pull`, `Club Name`, `Shot Created
//!   Date` and a sign legend in every signed column's header (`(deg L-/R+)`,
//!   `(mm toe-/heel+)`); a club not measured written as zeros; a lost spin written as zeros;
//!   a re-saved file whose byte-order mark was saved twice;
//! - a FlightScope file without its `club` column: `Club (mph)` is not the club;
//! - a Garmin smash factor of `inf` beside a club speed of 0: the shot keeps its launch.

use crate::cli_support;

use std::path::PathBuf;

use cli_support::{csv_rows as rows, repo, s, smash, unwrapped as stderr, write};

fn fixture(name: &str) -> PathBuf {
    repo(&format!("cli/tests/fixtures/import/{name}"))
}

#[test]
fn an_fsx_play_session_imports_with_the_signs_its_header_states() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shots.csv");
    let file = fixture("unseen/fsx_play.csv");
    for format in ["auto", "foresight"] {
        let o = smash(&["import", "--format", format, s(&file), "--out", s(&out)]);
        let e = stderr(&o);
        assert!(o.status.success(), "{format}:\n{e}");
        // The spin lost on line 4 (back, side and total 0): left out and counted.
        assert!(
            e.contains(
                "left out 1 row(s): no measured launch (back and side spin both exactly 0: the \
                 monitor lost the spin)"
            ) && e.contains(
                "fsx_play.csv:4: column 'Back Spin (rpm)': back and side spin are both exactly 0"
            ),
            "{e}"
        );
        assert!(!e.contains("-0"), "{e}");
        let r = rows(&out);
        assert_eq!(r.len(), 4, "{r:?}");
        assert_eq!(r[0]["group"], "Driver");
        assert_eq!(r[0]["datetime"], "2025-04-02 17:05:11");
        assert_eq!(r[0]["azimuth_deg"], "-1.8");
        assert_eq!(r[0]["sidespin_rpm"], "-240");
        // Line 5: a club not measured, every club cell 0: no delivery, no impact, no lie.
        for col in [
            "club_speed_mph",
            "face_angle_deg",
            "impact_y_mm",
            "impact_z_mm",
        ] {
            assert_eq!(r[2][col], "", "{col}");
        }
        assert_eq!(r[2]["dynamic_lie_deg"], "");
        // Line 6: `toe-/heel+` makes 6.5 mm toward the heel, -6.5 in the shots file; open and
        // in-to-out are + as the shots file has them.
        assert_eq!(r[3]["impact_z_mm"], "-6.5");
        assert_eq!(r[3]["impact_y_mm"], "3");
        assert_eq!(r[3]["face_angle_deg"], "0.9");
        assert_eq!(r[3]["club_path_deg"], "1.8");
        let text = std::fs::read_to_string(&out).unwrap();
        assert!(!text.contains(",-0,"), "{text}");
    }
    // A side stated against the header's legend is refused, naming both.
    let o = smash(&[
        "import",
        s(&file),
        "--impact-offset-positive",
        "toe",
        "--out",
        s(&out),
    ]);
    let e = stderr(&o);
    assert!(!o.status.success());
    assert!(
        e.contains("column 'Face Impact Horizontal (mm toe-/heel+)'")
            && e.contains("positive offset points to the heel")
            && e.contains("--impact-offset-positive option says the toe"),
        "{e}"
    );
    // A legend naming sides of another kind is refused, not read.
    let bent = std::fs::read_to_string(&file)
        .unwrap()
        .replace("Push/Pull (deg L-/R+)", "Push/Pull (deg low-/high+)");
    let bent = write(dir.path(), "bent.csv", &bent);
    let o = smash(&["import", s(&bent), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(!o.status.success());
    assert!(
        e.contains("column 'Push/Pull (deg low-/high+)'")
            && e.contains("its sign legend 'low-/high+' does not name the sides of azimuth_deg"),
        "{e}"
    );
}

#[test]
fn a_byte_order_mark_saved_twice_is_dropped_with_a_note() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shots.csv");
    let o = smash(&[
        "import",
        s(&fixture("unseen/fsx_play_resaved.csv")),
        "--out",
        s(&out),
    ]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(e.contains("byte-order mark saved twice"), "{e}");
    assert!(!e.contains("not used"), "{e}");
    let r = rows(&out);
    assert_eq!(r.len(), 2);
    assert_eq!(r[1]["ball_speed_mph"], "136");
}

#[test]
fn a_column_with_a_unit_is_never_the_club() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shots.csv");
    // The FS Golf layout without its `club` column (a user's re-save dropped it).
    let text = std::fs::read_to_string(fixture("flightscope_fsgolf.csv")).unwrap();
    let cut: String = text
        .lines()
        .map(|l| l.split_once(',').map_or(l, |(_, rest)| rest))
        .map(|l| format!("{l}\n"))
        .collect();
    let file = write(dir.path(), "noclub.csv", &cut);
    let o = smash(&[
        "import",
        "--format",
        "flightscope",
        s(&file),
        "--impact-offset-positive",
        "toe",
        "--out",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let r = rows(&out);
    assert!(!r[0].contains_key("group"), "{:?}", r[0]);
    assert_eq!(r[0]["club_speed_mph"], "87.8");
}

#[test]
fn a_non_finite_cell_the_launch_does_not_need_leaves_the_shot_its_launch() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shots.csv");
    let text = std::fs::read_to_string(fixture("garmin_r10.csv")).unwrap();
    let all = {
        let o = smash(&["import", s(&fixture("garmin_r10.csv")), "--out", s(&out)]);
        assert!(o.status.success(), "{}", stderr(&o));
        rows(&out).len()
    };
    // The smash factor of the first shot (column 11) as Garmin writes it for a club speed of 0.
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let mut cells: Vec<String> = lines[2].split(',').map(str::to_owned).collect();
    cells[10] = "inf".into();
    lines[2] = cells.join(",");
    let file = write(dir.path(), "inf.csv", &(lines.join("\n") + "\n"));
    let o = smash(&["import", s(&file), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("column 'Smash Factor': not a finite number")
            && e.contains("line 3: 'inf' is not a finite number"),
        "{e}"
    );
    assert_eq!(rows(&out).len(), all);
    // --strict refuses the file there.
    let o = smash(&["import", "--strict", s(&file), "--out", s(&out)]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains(":3: column 'Smash Factor'"),
        "{}",
        stderr(&o)
    );
}
