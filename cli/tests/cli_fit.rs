//! `smash calibrate` and `smash diagnose` end to end: JSON shape, written club, bad input.

use crate::common;

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
        "unknown effect 'added_mas' (did you mean 'added_mass'?); the library has: added_mass, ball_offset",
    );
    cal(
        &good,
        "ball_offset",
        &["--max-iters", "1"],
        "did not converge",
    );
    cal(&good, "added_mass@Z", &[], "no shot is in group 'Z'");
    // A bad --delivery-noise is refused by the argument parser: its one error line (then
    // clap's pointer to --help), before any work.
    for (spec, expect) in [
        ("club_speed=1", "allowed: club_speed_mph"),
        ("impact_y_mm=2", "given with --impact-noise-mm"),
        ("club_speed_mph=-0.5", "within [0, 10000] mph"),
        ("sonar", "neither an instrument class"),
    ] {
        let (ok, stdout, stderr) = smash(&[
            "calibrate",
            "--club",
            club,
            "--shots",
            &good,
            "--effects",
            "ball_offset",
            "--delivery-noise",
            spec,
            "--out-club",
            o,
        ]);
        assert!(!ok && stdout.is_empty(), "{spec}: {stdout}");
        let first = stderr.lines().next().unwrap_or_default();
        assert!(
            first.starts_with("error: ") && first.contains(expect),
            "{spec}: {stderr}"
        );
        assert!(first.contains("--delivery-noise"), "{stderr}");
        assert!(!out.exists());
    }
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

fn field_f64(v: &serde_json::Value) -> f64 {
    v.as_f64().expect("a number")
}

/// `smash diagnose` on the paper world (delivery noise 1× the camera class and 3 mm of location
/// noise in its measured inputs) selects a delivery-noise level and an impact-location noise,
/// and prints the `smash calibrate` flags of that model; `smash calibrate` with them says so in
/// its "Measurement model:" line and JSON, and reproduces diagnose's final values (both are
/// the same whitened fit on the same corrected data: to the fit's tolerance).
#[test]
fn calibrate_takes_the_measurement_model_diagnose_selected() {
    let dir = tempfile::tempdir().unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let shots = dir.path().join("paper.csv");
    let shots = shots.to_str().unwrap();
    let world = root.join("configs/synth/paper_world.toml");
    let (ok, _, stderr) = smash(&["synth", "--config", world.to_str().unwrap(), "--out", shots]);
    assert!(ok, "{stderr}");
    let club = paper_club_path();
    let club = club.to_str().unwrap();
    let (ok, stdout, stderr) = smash(&["diagnose", "--club", club, "--shots", shots, "--json"]);
    assert!(ok, "{stderr}");
    let d: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let sd = &d["delivery_noise"]["sd"];
    assert!(
        sd["club_speed_mph"].is_number(),
        "no delivery noise selected: {}",
        d["delivery_noise"]
    );
    assert_eq!(d["delivery_noise"]["estimated"], true);
    let flags = d["calibrate_flags"].as_str().unwrap().to_owned();
    assert!(
        flags.contains("--delivery-noise club_speed_mph="),
        "{flags}"
    );
    assert!(flags.contains("--impact-noise-mm "), "{flags}");
    assert!(d["conclusion"].is_string());

    let mut args = vec!["calibrate", "--club", club, "--shots", shots, "--json"];
    args.extend(flags.split_whitespace());
    let (ok, stdout, stderr) = smash(&args);
    assert!(ok, "{stderr}");
    let c: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let m = &c["measurement_model"];
    let (used, selected) = (
        m["delivery_noise"].as_object().unwrap(),
        sd.as_object().unwrap(),
    );
    assert_eq!(used.len(), selected.len(), "{m}");
    for (k, v) in selected {
        let (a, b) = (field_f64(&used[k]), field_f64(v));
        assert!((a - b).abs() <= 1e-12 * b, "{k}: {a} vs {b}");
    }
    assert_eq!(m["impact_noise_mm"]["y"], d["impact_noise_mm"]["y"]);
    let label = |p: &serde_json::Value| format!("{}@{}.{}", p["effect"], p["group"], p["param"]);
    let want = d["estimates"].as_array().unwrap();
    let got = c["params"].as_array().unwrap();
    assert_eq!(got.len(), want.len());
    assert!(!want.is_empty());
    for w in want {
        let g = got
            .iter()
            .find(|g| label(g) == label(w))
            .expect("same parameters");
        let (a, b) = (field_f64(&g["value"]), field_f64(&w["value"]));
        let se = field_f64(&w["stderr"]);
        assert!(
            (a - b).abs() <= 1e-6 * se.max(b.abs()),
            "{}: {a} vs {b}",
            label(w)
        );
        let (sa, sb) = (field_f64(&g["stderr"]), se);
        assert!(
            (sa - sb).abs() <= 1e-6 * sb,
            "{} stderr: {sa} vs {sb}",
            label(w)
        );
    }

    // The text says what the fit assumed; without the flags it says the inputs are exact.
    args.retain(|a| *a != "--json");
    let (ok, text, stderr) = smash(&args);
    assert!(ok, "{stderr}");
    // The line and its wrapped continuation lines.
    let line: String = text
        .lines()
        .skip_while(|l| !l.starts_with("Measurement model:"))
        .take_while(|l| l.starts_with("Measurement model:") || l.starts_with("  "))
        .collect::<Vec<_>>()
        .join(" ");
    assert!(
        line.contains("impact locations with 1σ noise") && line.contains("club_speed_mph"),
        "{line}"
    );
    let (ok, text, stderr) = smash(&[
        "calibrate",
        "--club",
        club,
        "--shots",
        shots,
        "--effects",
        "ball_offset",
    ]);
    assert!(ok, "{stderr}");
    assert!(
        text.contains("Measurement model: delivery and impact locations as measured (exact)"),
        "{text}"
    );
}
