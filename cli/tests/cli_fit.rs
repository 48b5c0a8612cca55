//! `smash calibrate` and `smash diagnose` end to end: JSON shape, written club, bad input.

#[path = "../../tests/common/mod.rs"]
mod common;

use std::path::Path;
use std::process::Command;

use common::{paper_club_path, paper_truth, shots, shots_csv, Experiment};

fn smash(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_smash"))
        .args(args)
        .output()
        .expect("runs");
    (
        out.status.success(),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_owned()
}

fn paper_shots() -> Vec<smash::model::Shot> {
    let e = Experiment {
        golfers: 8,
        ..Experiment::default()
    };
    shots(&paper_truth(), &e)
}

#[test]
fn calibrate_json_and_club_file() {
    let dir = tempfile::tempdir().unwrap();
    let s = paper_shots();
    let shots_path = write(dir.path(), "shots.csv", &shots_csv(&s, true, true));
    let club = paper_club_path();
    let out = dir.path().join("cal.toml");
    let (ok, stdout, stderr) = smash(&[
        "calibrate",
        "--club",
        club.to_str().unwrap(),
        "--shots",
        &shots_path,
        "--effects",
        "added_mass@group,ball_offset",
        "--json",
        "--out-club",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{stderr}");
    let j: serde_json::Value = serde_json::from_str(&stdout).expect("one JSON object");
    let params = j["params"].as_array().unwrap();
    assert_eq!(params.len(), 5);
    assert_eq!(params[0]["effect"], "added_mass");
    assert_eq!(params[0]["param"], "dm_g");
    assert_eq!(params[0]["group"], "A");
    assert!(params[3]["group"].is_null());
    assert!(params[3]["value"].as_f64().is_some() && params[3]["stderr"].as_f64().is_some());
    for key in ["before", "after"] {
        let m = &j[key]["B"]["backspin_rpm"];
        assert!(m["mean"].as_f64().is_some() && m["std"].as_f64().is_some());
        assert!(j[key]["A"]["ball_speed_mph"]["mean"].is_number());
    }
    for key in [
        "chi2",
        "reduced_chi2",
        "aic",
        "bic",
        "evaluations",
        "termination",
    ] {
        assert!(!j[key].is_null(), "{key}");
    }
    assert!(j["shaft_relation"]["slope_g_per_g"].is_number());
    // The club reads back and is usable by predict.
    let back = smash::data::club_file::read_club(&out).unwrap();
    assert_eq!(back.effects.len(), 4);
    let pred = dir.path().join("pred.csv");
    let (ok, _, stderr) = smash(&[
        "predict",
        "--club",
        out.to_str().unwrap(),
        "--shots",
        &shots_path,
        "--out",
        pred.to_str().unwrap(),
    ]);
    assert!(ok, "{stderr}");
    // Text form: parameter table and the side-by-side error tables.
    let (ok, stdout, _) = smash(&[
        "calibrate",
        "--club",
        club.to_str().unwrap(),
        "--shots",
        &shots_path,
        "--effects",
        "added_mass,ball_offset",
        "--method",
        "paper",
    ]);
    assert!(ok);
    assert!(stdout.contains("ball_offset.dy_mm") && stdout.contains("before (nominal)"));
    assert!(stdout.contains("W = 0 (spin)"));
}

#[test]
fn diagnose_json() {
    let dir = tempfile::tempdir().unwrap();
    let shots_path = write(
        dir.path(),
        "shots.csv",
        &shots_csv(&paper_shots(), true, true),
    );
    let out = dir.path().join("diag.toml");
    let (ok, stdout, stderr) = smash(&[
        "diagnose",
        "--club",
        paper_club_path().to_str().unwrap(),
        "--shots",
        &shots_path,
        "--json",
        "--out-club",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{stderr}");
    let j: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(j["selected"][0], "ball_offset");
    let steps = j["steps"].as_array().unwrap();
    assert!(steps.len() >= 2);
    assert_eq!(steps[0]["selected"], "ball_offset");
    let c = &steps[0]["candidates"][0];
    assert!(c["gain"].is_number() && c["rms_reduction"]["backspin_rpm"].is_number());
    assert!(out.exists());
}

/// Runs a failing command; checks one `error:` line, non-zero exit, no output file.
fn fails(args: &[&str], out: &Path, expect: &str) {
    let (ok, stdout, stderr) = smash(args);
    assert!(!ok, "should fail: {args:?}");
    assert!(stdout.is_empty(), "{stdout}");
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "one line: {stderr}");
    assert!(lines[0].starts_with("error: "), "{stderr}");
    assert!(
        lines[0].contains(expect),
        "expected '{expect}' in: {stderr}"
    );
    assert!(!out.exists(), "nothing written on failure");
}

#[test]
fn bad_input_gets_one_clear_line_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let s = paper_shots();
    let good = write(dir.path(), "good.csv", &shots_csv(&s, true, true));
    let unmeasured = write(dir.path(), "unmeasured.csv", &shots_csv(&s, false, true));
    let mut single: Vec<_> = s[..60].to_vec();
    single.iter_mut().for_each(|x| x.group = "all".into());
    let single = write(dir.path(), "single.csv", &shots_csv(&single, true, true));
    let few = write(dir.path(), "few.csv", &shots_csv(&s[..3], true, true));
    let club = paper_club_path();
    let club = club.to_str().unwrap();
    let out = dir.path().join("out.toml");
    let o = out.to_str().unwrap();
    let cal = |shots: &str, effects: &str, extra: &[&str], expect: &str| {
        let mut args = vec![
            "calibrate",
            "--club",
            club,
            "--shots",
            shots,
            "--effects",
            effects,
            "--out-club",
            o,
        ];
        args.extend_from_slice(extra);
        fails(&args, &out, expect);
    };
    cal(&unmeasured, "added_mass", &[], "no measured launch columns");
    cal(
        &single,
        "added_mass@group",
        &[],
        "use the global form 'added_mass'",
    );
    cal(
        &few,
        "com_offset,ball_offset",
        &[],
        "3 shot(s) cannot determine 5 parameter(s)",
    );
    cal(
        &good,
        "added_mas",
        &[],
        "unknown effect 'added_mas'; the library has: added_mass, ball_offset",
    );
    cal(
        &good,
        "ball_offset",
        &["--max-iters", "1"],
        "did not converge",
    );
    cal(&good, "added_mass@Z", &[], "no shot is in group 'Z'");
    fails(
        &[
            "diagnose",
            "--club",
            club,
            "--shots",
            &unmeasured,
            "--out-club",
            o,
        ],
        &out,
        "no measured launch columns",
    );
}
