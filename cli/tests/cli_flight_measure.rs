//! `smash flight` in the measurement loop: the per-club and overall errors against measured
//! flights (text, `--json`, `--report`), per-shot conditions from the file (user flags over
//! them), the ball's start stated, and flights that do not depend on the time step.

use crate::cli_support;

use std::path::Path;

use cli_support::{club, s, smash, unwrapped as stderr, write};

/// Header and rows of a CSV file.
fn table(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::Reader::from_path(path).unwrap();
    let h = r.headers().unwrap().iter().map(str::to_string).collect();
    let rows = r
        .records()
        .map(|x| x.unwrap().iter().map(str::to_string).collect())
        .collect();
    (h, rows)
}

fn column(path: &Path, name: &str) -> Vec<String> {
    let (h, rows) = table(path);
    let c = h
        .iter()
        .position(|x| x == name)
        .unwrap_or_else(|| panic!("{name} in {h:?}"));
    rows.into_iter().map(|r| r[c].clone()).collect()
}

/// Two clubs, measured carry, side, apex and land angle (one apex missing).
const MEASURED: &str = "shot_id,group,ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,sidespin_rpm,carry_yd,offline_yd,apex_yd,land_angle_deg\n\
d1,driver,167,10.9,0,2686,0,275,0,32,38\n\
d2,driver,150,12,1,2600,-300,240,-3,,36\n\
i1,7-iron,120,16.3,0,7097,200,172,1,32,50\n\
i2,7-iron,115,17,-1,7000,0,160,-2,30,49\n";

/// The JSON's statistics are those of the written `err_` columns, by hand: bias, RMSE and the
/// count per club and overall; the text table lists every club and all shots.
#[test]
fn json_and_text_summaries_match_the_written_errors() {
    let dir = tempfile::tempdir().unwrap();
    let shots = write(dir.path(), "m.csv", MEASURED);
    let out = dir.path().join("f.csv");
    let o = smash(&["flight", "--shots", s(&shots), "--out", s(&out), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let groups = column(&out, "group");
    let err: Vec<f64> = column(&out, "err_carry_yd")
        .iter()
        .map(|c| c.parse().unwrap())
        .collect();
    assert_eq!(json["command"], "flight", "{json}");
    assert_eq!(json["schema_version"], 1, "{json}");
    let rows = json["errors"]["rows"].as_array().unwrap();
    let names: Vec<&str> = rows.iter().map(|r| r["group"].as_str().unwrap()).collect();
    assert_eq!(names, ["driver", "7-iron", "all"]);
    for r in rows {
        let g = r["group"].as_str().unwrap();
        let e: Vec<f64> = err
            .iter()
            .zip(&groups)
            .filter(|(_, gr)| g == "all" || gr.as_str() == g)
            .map(|(e, _)| *e)
            .collect();
        let n = e.len() as f64;
        let bias = e.iter().sum::<f64>() / n;
        let rmse = (e.iter().map(|x| x * x).sum::<f64>() / n).sqrt();
        let carry = r["errors"]
            .as_array()
            .unwrap()
            .iter()
            .find(|q| q[0] == "carry_yd")
            .unwrap();
        assert_eq!(carry[1]["n"].as_u64(), Some(e.len() as u64), "{g}");
        assert!(
            (carry[1]["bias"].as_f64().unwrap() - bias).abs() < 1e-9,
            "{g}"
        );
        assert!(
            (carry[1]["rmse"].as_f64().unwrap() - rmse).abs() < 1e-9,
            "{g}"
        );
    }
    // The driver's apex is measured once, the land angle twice.
    let apex = rows[0]["errors"]
        .as_array()
        .unwrap()
        .iter()
        .find(|q| q[0] == "apex_yd")
        .unwrap();
    assert_eq!(apex[1]["n"].as_u64(), Some(1));
    // Text on stderr without --json: every quantity, club and all.
    let o = smash(&["flight", "--shots", s(&shots), "--out", s(&out)]);
    let err = stderr(&o);
    assert!(o.status.success() && o.stdout.is_empty(), "{err}");
    for needle in [
        "ball on the ground",
        "carry error (yd, predicted - measured)",
        "side error",
        "apex error",
        "land angle error",
        "driver",
        "7-iron",
        "\nall ",
        "median %",
    ] {
        assert!(err.contains(needle), "{needle:?} in {err}");
    }
}

/// `--report` writes a page with a bias chart per quantity and the carry scatter; without a
/// measured column, `--json` and `--report` are refused in one line.
#[test]
fn report_page_and_refusal_without_measurements() {
    let dir = tempfile::tempdir().unwrap();
    let shots = write(dir.path(), "m.csv", MEASURED);
    let (out, page) = (dir.path().join("f.csv"), dir.path().join("r.html"));
    let o = smash(&[
        "flight",
        "--shots",
        s(&shots),
        "--out",
        s(&out),
        "--report",
        s(&page),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let html = std::fs::read_to_string(&page).unwrap();
    assert_eq!(html.matches("data-kind=\"flight-bias\"").count(), 4);
    assert_eq!(html.matches("data-kind=\"flight-carry\"").count(), 1);
    let bare = write(
        dir.path(),
        "l.csv",
        "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,12,2600\n",
    );
    let o = smash(&["flight", "--shots", s(&bare), "--out", s(&out), "--json"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("no measured flight column"), "{err}");
    // The error is one line, the last, after the (wrapped) message of what was flown.
    let lines: Vec<&str> = err.trim_end().lines().collect();
    assert_eq!(
        lines.iter().filter(|l| l.starts_with("error: ")).count(),
        1,
        "{err}"
    );
    assert!(lines.last().unwrap().starts_with("error: "), "{err}");
}

/// Per-shot conditions: the same launch flies farther at 1,600 m than at sea level and in
/// warm air than in cold; the stated columns (and the passed-through ball and flags) are
/// kept; the user's flags override the file's for every shot and the message says which.
#[test]
fn per_shot_conditions_from_the_file_and_user_overrides() {
    let dir = tempfile::tempdir().unwrap();
    let text = "shot_id,group,ball_speed_mph,launch_angle_deg,backspin_rpm,carry_yd,altitude_m,air_temperature_c,relative_humidity_pct,ball_type,spin_estimated,club_estimated,flight_modelled\n\
a,7i,120,16.3,7097,172,0,15,50,Premium,0,0,1\n\
b,7i,120,16.3,7097,172,1600,15,50,Premium,0,0,1\n\
c,7i,120,16.3,7097,172,0,35,,Range,1,0,0\n";
    let shots = write(dir.path(), "c.csv", text);
    let out = dir.path().join("f.csv");
    let o = smash(&["flight", "--shots", s(&shots), "--out", s(&out)]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    // The message wraps at 100 columns: compare its words.
    let words = err.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        words.contains(
            "air per shot from the file's altitude_m, air_temperature_c, relative_humidity_pct (3 distinct)"
        ),
        "{err}"
    );
    let carry: Vec<f64> = column(&out, "pred_carry_yd")
        .iter()
        .map(|c| c.parse().unwrap())
        .collect();
    assert!(
        carry[1] > carry[0] + 3.0 && carry[2] > carry[0] + 1.0,
        "{carry:?}"
    );
    assert_eq!(column(&out, "ball_type"), ["Premium", "Premium", "Range"]);
    assert_eq!(column(&out, "flight_modelled"), ["1", "1", "0"]);
    // The user's elevation and temperature for every shot: a and b fly alike.
    let o = smash(&[
        "flight",
        "--shots",
        s(&shots),
        "--out",
        s(&out),
        "--elevation-m",
        "0",
        "--temperature-c",
        "15",
    ]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        // c's empty humidity is the default 50 %: with the user's elevation and temperature
        // all three shots fly in one air.
        err.split_whitespace()
            .collect::<Vec<_>>()
            .join(" ")
            .contains("relative_humidity_pct (1 distinct); the user's temperature, pressure"),
        "{err}"
    );
    let carry = column(&out, "pred_carry_yd");
    assert_eq!(carry[0], carry[1]);
    // A bad condition cell: file, line, column.
    let bad = write(
        dir.path(),
        "bad.csv",
        &text.replace("0,35,,Range", "0,hot,,Range"),
    );
    // Without --strict the row is left out and counted; with it the file is refused.
    let o = smash(&["flight", "--shots", s(&bad), "--out", s(&out)]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("left out 1 of 3 rows: a cell that is not a number in column 'air_temperature_c' (line(s) 4; the first: ")
            && err.contains("bad.csv:4: column 'air_temperature_c': 'hot' is not a finite number"),
        "{err}"
    );
    assert_eq!(column(&out, "pred_carry_yd").len(), 2);
    let o = smash(&["flight", "--shots", s(&bad), "--out", s(&out), "--strict"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("bad.csv:4: column 'air_temperature_c': 'hot' is not a finite number"),
        "{err}"
    );
    let hot = write(
        dir.path(),
        "hot.csv",
        &text.replace("0,35,,Range", "0,95,,Range"),
    );
    let o = smash(&["flight", "--shots", s(&hot), "--out", s(&out)]);
    let err = stderr(&o);
    assert!(
        err.contains("hot.csv:4: column 'air_temperature_c'") && err.contains("95"),
        "{err}"
    );
}

/// The carry lines of `smash predict --flight` for one delivery at a step.
fn predicted_flight(extra: &[&str], dt: &str) -> String {
    let club = club();
    let mut args = vec!["predict", "--club", &club, "--flight", "--dt-s", dt];
    args.extend_from_slice(extra);
    let o = smash(&args);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(o.status.success(), "{}", stderr(&o));
    out
}

fn line<'a>(text: &'a str, label: &str) -> &'a str {
    text.lines()
        .find(|l| l.starts_with(label))
        .unwrap_or_else(|| panic!("{label} in {text}"))
}

/// The case: a delivery launching the ball about 1.1° downward gave 190.2 yd or 0 yd
/// by the step. Now the same carry at the default-sized and a fine step, from the ground and
/// from a tee, and the ball's start is printed.
#[test]
fn predict_flight_of_a_downward_launch_does_not_depend_on_the_step() {
    let delivery = [
        "--speed-mph",
        "100",
        "--loft-deg",
        DOWNWARD_LOFT_DEG,
        "--attack-deg",
        "-6",
    ];
    let coarse = predicted_flight(&delivery, "0.35");
    let launch: f64 = line(&coarse, "Launch angle")
        .split_whitespace()
        .nth(2)
        .unwrap()
        .parse()
        .unwrap();
    assert!((-1.5..-0.7).contains(&launch), "{coarse}");
    assert!(
        line(&coarse, "Ball start").contains("on the ground"),
        "{coarse}"
    );
    let fine = predicted_flight(&delivery, "0.01");
    assert_eq!(line(&coarse, "Carry"), line(&fine, "Carry"));
    assert_eq!(
        line(&coarse, "Carry").split_whitespace().nth(1),
        Some("0.0")
    );
    let mut teed = delivery.to_vec();
    teed.extend(["--tee-mm", "40"]);
    let (a, b) = (
        predicted_flight(&teed, "0.35"),
        predicted_flight(&teed, "0.01"),
    );
    assert!(line(&a, "Ball start").contains("teed 40 mm"), "{a}");
    assert_eq!(line(&a, "Carry"), line(&b, "Carry"));
}

/// Dynamic loft that launches the ball about 1.1° below horizontal with the delivery above.
const DOWNWARD_LOFT_DEG: &str = "0";

/// A tee beyond what the Rules allow, or below the ground, is refused in one line naming the
/// flag and the range; the message of a teed run states the tee.
#[test]
fn tee_heights_out_of_range_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let shots = write(
        dir.path(),
        "l.csv",
        "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,-1,2600\n",
    );
    let out = dir.path().join("f.csv");
    for bad in ["-1", "200", "NaN"] {
        let o = smash(&[
            "flight",
            "--shots",
            s(&shots),
            "--out",
            s(&out),
            "--tee-mm",
            bad,
        ]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(
            err.starts_with(&format!(
                "error: --tee-mm {bad}: must be within [0, 101.6] mm"
            )),
            "{err}"
        );
        assert!(!out.exists());
    }
    let o = smash(&[
        "flight",
        "--shots",
        s(&shots),
        "--out",
        s(&out),
        "--tee-mm",
        "30",
    ]);
    assert!(stderr(&o).contains("ball teed 30 mm"), "{}", stderr(&o));
}
