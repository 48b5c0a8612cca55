//! The corpus of real export layouts (issue 44): every layout found in public repositories has a
//! fixture in `cli/tests/fixtures/import/corpus/`, in exactly the real file's layout (header,
//! units rows, quirks, sentinels, encoding) with made-up values (the real files' licences do
//! not allow shipping them, or they hold personal data; `tests/data/README.md` names the file
//! each one mimics). Each imports with `--format auto`, with its preset and with its preset's
//! mapping file (`configs/import/NAME.toml`), to the same shots file; the shots agree with the
//! raw file cell by cell (speeds, angles, spins, carry, side: units and signs), and
//! `smash flight` (and `compare`, where the file gives a whole delivery) runs on the result.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::{repo, s, smash, unwrapped as stderr};

fn fixture(name: &str) -> PathBuf {
    repo(&format!("cli/tests/fixtures/import/corpus/{name}"))
}

/// A raw cell as a number, read independently of the import: a side letter (`R`, `L`) signs
/// it, a `°` or ` s` after it is dropped.
fn raw_number(cell: &str) -> f64 {
    let t = cell.trim().replace('°', "");
    let t = t.trim_end_matches(" s").trim();
    let (sign, t) = if let Some(r) = t.strip_prefix('L') {
        (-1.0, r)
    } else if let Some(r) = t.strip_prefix('R') {
        (1.0, r)
    } else {
        (1.0, t)
    };
    sign * t
        .trim()
        .parse::<f64>()
        .unwrap_or_else(|_| panic!("'{cell}'"))
}

/// The cell under `header` on file line `line` of a CSV fixture whose header is line
/// `header_line` (1-based; a byte-order mark and leading spaces in names are ignored).
fn raw_csv(path: &Path, header_line: usize, line: usize, header: &str) -> f64 {
    let text = std::fs::read_to_string(path).unwrap();
    let text = text.trim_start_matches('\u{feff}');
    let lines: Vec<&str> = text.lines().collect();
    let split = |l: &str| {
        csv::ReaderBuilder::new()
            .has_headers(false)
            .from_reader(l.as_bytes())
            .records()
            .next()
            .unwrap()
            .unwrap()
            .iter()
            .map(|c| c.trim().to_owned())
            .collect::<Vec<String>>()
    };
    let head = split(lines[header_line - 1]);
    let i = head
        .iter()
        .position(|h| h == header)
        .unwrap_or_else(|| panic!("{header} not in {head:?}"));
    raw_number(&split(lines[line - 1])[i])
}

/// The shots file: header and rows.
fn read(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut rdr = csv::Reader::from_path(path).unwrap();
    let h = rdr.headers().unwrap().iter().map(str::to_owned).collect();
    let rows = rdr
        .records()
        .map(|r| r.unwrap().iter().map(str::to_owned).collect())
        .collect();
    (h, rows)
}

fn cell<'a>(h: &[String], rows: &'a [Vec<String>], row: usize, col: &str) -> &'a str {
    let i = h
        .iter()
        .position(|c| c == col)
        .unwrap_or_else(|| panic!("no column {col} in {h:?}"));
    &rows[row][i]
}

fn num(h: &[String], rows: &[Vec<String>], row: usize, col: &str) -> f64 {
    let c = cell(h, rows, row, col);
    c.parse()
        .unwrap_or_else(|_| panic!("{col} of row {row}: '{c}'"))
}

/// Import `file` with `format` into `dir`; the shots file's bytes and the stderr.
fn import(dir: &Path, file: &Path, format: &str, tag: &str) -> (Vec<u8>, String) {
    let out = dir.join(format!("{tag}.csv"));
    let res = smash(&[
        "import",
        "--format",
        format,
        s(file),
        "--out",
        s(&out),
        "--impact-offset-positive",
        "toe",
    ]);
    assert!(
        res.status.success(),
        "{format} on {file:?}: {}",
        stderr(&res)
    );
    (std::fs::read(&out).unwrap(), stderr(&res))
}

const MPH_PER_MS: f64 = 1.0 / 0.44704;
const MPH_PER_KMH: f64 = 1.0 / 1.609344;
const YD_PER_M: f64 = 1.0 / 0.9144;

/// A check of one shot against the raw file: output row, shots column, expected value.
type Check = (usize, &'static str, f64);

/// The fixtures: file, preset, shots written, and the checks against the raw file.
fn corpus() -> Vec<(&'static str, &'static str, usize, Vec<Check>)> {
    let f = fixture;
    let csv = |name: &str, head: usize, line: usize, col: &str| raw_csv(&f(name), head, line, col);
    let g = |line: usize, col: &str| csv("garmin_r10_metric.csv", 1, line, col);
    let r50 = |line: usize, col: &str| csv("garmin_r50.csv", 1, line, col);
    let fsx = |line: usize, col: &str| csv("fsx2020_lastshot.csv", 1, line, col);
    let un = |line: usize, col: &str| csv("uneekor_refine.csv", 1, line, col);
    let sq = |line: usize, col: &str| csv("square_range.csv", 3, line, col);
    let fs = |line: usize, col: &str| csv("flightscope_cloud.csv", 1, line, col);
    let session: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(f("fsx_session.session")).unwrap()).unwrap();
    let shot = |i: usize, p: &str| session["Shots"][i].pointer(p).unwrap().as_f64().unwrap();
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(f("trackman_report.json")).unwrap()).unwrap();
    let stroke = |g: usize, i: usize, p: &str| {
        report["StrokeGroups"][g]["Strokes"][i]["Measurement"][p]
            .as_f64()
            .unwrap()
    };
    let log: Vec<serde_json::Value> = std::fs::read_to_string(f("openflight.jsonl"))
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let event = |line: usize, key: &str| log[line - 1][key].as_f64().unwrap();
    vec![
        (
            "openflight.jsonl",
            "openflight",
            3,
            vec![
                (0, "ball_speed_mph", event(4, "ball_speed_mph")),
                (0, "azimuth_deg", event(4, "launch_angle_horizontal")),
                (0, "carry_yd", event(4, "estimated_carry_yards")),
                // No launch direction measured: 0 assumed (and counted).
                (1, "azimuth_deg", 0.0),
                (1, "launch_angle_deg", event(8, "launch_angle_vertical")),
                (2, "sidespin_rpm", {
                    let a = event(10, "spin_axis_deg").to_radians();
                    event(10, "spin_rpm") * a.sin()
                }),
            ],
        ),
        (
            "garmin_r10_metric.csv",
            "garmin-r10",
            5,
            vec![
                (0, "ball_speed_mph", g(3, "Ball Speed") * MPH_PER_KMH),
                (0, "club_speed_mph", g(3, "Club Speed") * MPH_PER_KMH),
                (1, "carry_yd", g(4, "Carry Distance") * YD_PER_M),
                (1, "offline_yd", g(4, "Carry Deviation Distance") * YD_PER_M),
                // Garmin's sidespin is + for a ball curving left.
                (2, "sidespin_rpm", -g(5, "Sidespin")),
                (2, "backspin_rpm", g(5, "Backspin")),
                (3, "azimuth_deg", g(6, "Launch Direction")),
                (1, "spin_estimated", 1.0),
                (0, "spin_estimated", 0.0),
            ],
        ),
        (
            "garmin_r50.csv",
            "garmin-r10",
            5,
            vec![
                (0, "ball_speed_mph", r50(3, "Ball Speed") * MPH_PER_KMH),
                // Apex in metres, carry in yards: one file, two length units.
                (0, "apex_yd", r50(3, "Apex Height") * YD_PER_M),
                (0, "carry_yd", r50(3, "Carry Distance")),
                (4, "launch_angle_deg", r50(7, "Launch Angle")),
            ],
        ),
        (
            "fsx_session.session",
            "foresight-session",
            3,
            vec![
                (
                    0,
                    "ball_speed_mph",
                    shot(0, "/BallData/BallSpeed_MS") * MPH_PER_MS,
                ),
                (0, "sidespin_rpm", shot(0, "/BallData/SideSpin_RPM")),
                (
                    1,
                    "carry_yd",
                    shot(2, "/FlightData/CarryDistance_M") * YD_PER_M,
                ),
                (
                    1,
                    "offline_yd",
                    shot(2, "/FlightData/OfflineDistance_M") * YD_PER_M,
                ),
                (
                    2,
                    "ball_speed_mph",
                    shot(4, "/BallData/BallSpeed_MS") * MPH_PER_MS,
                ),
            ],
        ),
        (
            "fsx2020_lastshot.csv",
            "foresight",
            1,
            vec![
                (0, "ball_speed_mph", fsx(2, "Ball Speed (m/s)") * MPH_PER_MS),
                (
                    0,
                    "club_speed_mph",
                    fsx(2, "Club head Speed (m/s)") * MPH_PER_MS,
                ),
                (0, "carry_yd", fsx(2, "Carry (m)") * YD_PER_M),
                (0, "sidespin_rpm", fsx(2, "Side Spin (rpm)")),
            ],
        ),
        (
            "uneekor_refine.csv",
            "uneekor",
            4,
            vec![
                (0, "offline_yd", un(2, "Side Dist")),
                (0, "azimuth_deg", un(2, "Side Angle")),
                (0, "sidespin_rpm", un(2, "Side Spin")),
                (1, "launch_angle_deg", un(3, "Launch Angle")),
                (3, "carry_yd", un(6, "Carry")),
            ],
        ),
        (
            "square_range.csv",
            "uneekor",
            5,
            vec![
                (0, "ball_speed_mph", sq(4, "Ball Speed(mph)")),
                (0, "azimuth_deg", sq(4, "Launch Direction")),
                (1, "offline_yd", sq(5, "Offline(yd)")),
                (2, "carry_yd", sq(6, "Carry(yd)")),
            ],
        ),
        (
            "trackman_report.json",
            "trackman-report",
            4,
            vec![
                (0, "ball_speed_mph", stroke(0, 0, "BallSpeed") * MPH_PER_MS),
                (0, "club_speed_mph", stroke(0, 0, "ClubSpeed") * MPH_PER_MS),
                (0, "impact_z_mm", stroke(0, 0, "ImpactOffset") * 1000.0),
                (2, "carry_yd", stroke(1, 0, "Carry") * YD_PER_M),
                (3, "offline_yd", stroke(1, 1, "CarrySide") * YD_PER_M),
            ],
        ),
        (
            "flightscope_cloud.csv",
            "flightscope-scrape",
            5,
            vec![
                (0, "ball_speed_mph", fs(2, "Ball (m/s)") * MPH_PER_MS),
                (0, "club_speed_mph", fs(2, "Club (m/s)") * MPH_PER_MS),
                (1, "carry_yd", fs(3, "Carry (m)") * YD_PER_M),
                // The scraper's rows hold launch H, launch V and the shape under the headers
                // Shape, Launch H and Launch V.
                (2, "launch_angle_deg", fs(4, "Launch H(*)")),
                (3, "azimuth_deg", fs(5, "Shape")),
            ],
        ),
    ]
}

/// Every corpus layout: `--format auto` picks its preset and writes the same shots file as the
/// preset and as the preset's own mapping file; the shots agree with the raw cells.
#[test]
fn every_corpus_layout_imports_with_auto_its_preset_and_its_mapping_file() {
    for (file, preset, shots, checks) in corpus() {
        let dir = tempfile::tempdir().unwrap();
        let path = fixture(file);
        let (auto, err) = import(dir.path(), &path, "auto", "auto");
        assert!(
            err.contains(&format!("--format auto: read as {preset} (")),
            "{file}: {err}"
        );
        let (by_preset, _) = import(dir.path(), &path, preset, "preset");
        let mapping = repo(&format!("configs/import/{preset}.toml"));
        let (by_mapping, _) = import(dir.path(), &path, s(&mapping), "mapping");
        assert_eq!(auto, by_preset, "{file}: auto and --format {preset} differ");
        assert_eq!(
            by_mapping, by_preset,
            "{file}: the mapping file and the preset differ"
        );
        let (h, rows) = read(&dir.path().join("preset.csv"));
        assert_eq!(rows.len(), shots, "{file}: {err}");
        for (row, col, want) in checks {
            let got = num(&h, &rows, row, col);
            assert!(
                (got - want).abs() <= 1e-6 * want.abs().max(1.0),
                "{file} row {row} {col}: {got} where the raw file gives {want}"
            );
        }
    }
}

/// Import → flight → compare on each corpus layout: no command refuses the file; compare runs
/// where some shots have a whole delivery (a launch-only file is for flight alone).
#[test]
fn corpus_shots_fly_and_compare() {
    for (file, preset, _, _) in corpus() {
        let dir = tempfile::tempdir().unwrap();
        let (_, err) = import(dir.path(), &fixture(file), preset, "shots");
        let shots = dir.path().join("shots.csv");
        let flown = dir.path().join("flown.csv");
        let res = smash(&["flight", "--shots", s(&shots), "--out", s(&flown)]);
        assert!(res.status.success(), "{file}: flight: {}", stderr(&res));
        let (h, rows) = read(&flown);
        if h.iter().any(|c| c == "err_carry_yd") {
            assert!(
                (0..rows.len()).any(|r| !cell(&h, &rows, r, "err_carry_yd").is_empty()),
                "{file}: no carry error"
            );
        }
        // Shots with a whole delivery, as the import counts them.
        let whole = err
            .split(" with a complete delivery")
            .next()
            .and_then(|a| a.rsplit('(').next())
            .and_then(|n| n.trim().parse::<usize>().ok())
            .unwrap_or_else(|| panic!("{file}: {err}"));
        if whole > 0 {
            let res = smash(&[
                "compare",
                "--club",
                s(&repo("configs/clubs/paper_driver.toml")),
                "--shots",
                s(&shots),
                "--ignore-club-mismatch",
            ]);
            assert!(res.status.success(), "{file}: compare: {}", stderr(&res));
        }
    }
}

/// The quirks of the corpus, each said in the import's summary: sentinels and zeros read as not
/// measured, a disabled FSX shot, a shot without a club name, dates in one form.
#[test]
fn corpus_quirks_are_counted_and_dates_are_one_form() {
    let dir = tempfile::tempdir().unwrap();
    let (_, err) = import(dir.path(), &fixture("fsx_session.session"), "fsx", "fsx");
    assert!(err.contains("Enabled = 'false'"), "{err}");
    // A misread shot, every spin 0: no spin measured, so no launch (left out and counted).
    assert!(
        err.contains(
            "left out 1 row(s): no measured launch (back and side spin both exactly 0: the \
             monitor lost the spin)"
        ),
        "{err}"
    );
    let (h, rows) = read(&dir.path().join("fsx.csv"));
    assert_eq!(cell(&h, &rows, 0, "group"), "(no club)");
    assert_eq!(cell(&h, &rows, 0, "datetime"), "2024-01-29");
    // FSX writes 2^24 in club cells it did not measure: never a face-to-path of 16777216°.
    assert!(
        !String::from_utf8(std::fs::read(dir.path().join("fsx.csv")).unwrap())
            .unwrap()
            .contains("1677721")
    );
    let (_, err) = import(dir.path(), &fixture("fsx2020_lastshot.csv"), "fsx", "last");
    let (h, rows) = read(&dir.path().join("last.csv"));
    assert_eq!(cell(&h, &rows, 0, "face_angle_deg"), "", "{err}");
    // Day-first dates (a day above 12 says so) and US dates with AM/PM become one form.
    let (_, _) = import(dir.path(), &fixture("garmin_r10_metric.csv"), "garmin", "g");
    let (h, rows) = read(&dir.path().join("g.csv"));
    assert_eq!(cell(&h, &rows, 0, "datetime"), "2025-09-20 18:40:00");
    let (_, err) = import(dir.path(), &fixture("garmin_r50.csv"), "garmin", "r50");
    let (h, rows) = read(&dir.path().join("r50.csv"));
    assert_eq!(cell(&h, &rows, 0, "datetime"), "2025-05-10 13:00:10");
    // The shot without club data: its Club Face 0.0 is not a measured square face.
    assert_eq!(cell(&h, &rows, 3, "face_angle_deg"), "", "{err}");
    assert!(
        err.contains("club angle exactly 0 beside an unmeasured club speed"),
        "{err}"
    );
    // Camera range exports write 0.0 for every club angle they do not measure.
    let (_, err) = import(dir.path(), &fixture("square_range.csv"), "uneekor", "sq");
    assert!(err.contains("club angles all exactly 0"), "{err}");
}
