//! The shots must match the club file: `compare`, `calibrate` and `diagnose` refuse another
//! club's session or a mixed-club file before anything is fitted, naming loft, and run under
//! `--ignore-club-mismatch` with no findings.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::{repo, s, smash_in_repo as smash, stderr};

const DRIVER: &str = "configs/clubs/paper_driver.toml";

/// The paper world's shots (a 9.8° driver delivered near 12°), written by `smash synth`.
fn paper_world(dir: &Path) -> PathBuf {
    let out = dir.join("paper_world.csv");
    let o = smash(&[
        "synth",
        "--config",
        "configs/synth/paper_world.toml",
        "--out",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    out
}

/// `src` with every cell of `column` replaced by `f(row index, cell)`.
fn rewrite(src: &Path, dst: &Path, column: &str, f: impl Fn(usize, &str) -> String) -> PathBuf {
    let text = std::fs::read_to_string(src).unwrap();
    let mut lines = text.lines();
    let head = lines.next().unwrap();
    let i = head.split(',').position(|h| h == column).unwrap();
    let mut out = vec![head.to_owned()];
    for (n, l) in lines.enumerate() {
        let mut cells: Vec<String> = l.split(',').map(str::to_owned).collect();
        cells[i] = f(n, &cells[i]);
        out.push(cells.join(","));
    }
    std::fs::write(dst, out.join("\n") + "\n").unwrap();
    dst.to_owned()
}

/// A refusal: non-zero exit, one error line containing each of `want`, nothing on stdout.
fn refused(args: &[&str], want: &[&str]) {
    let o = smash(args);
    let err = stderr(&o);
    assert!(!o.status.success(), "{args:?} ran: {err}");
    assert!(o.stdout.is_empty(), "{args:?}");
    // One error line (an import's notes on the export may come before it).
    let errors: Vec<&str> = err.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "{err}");
    for w in want {
        assert!(errors[0].contains(w), "'{w}' not in: {err}");
    }
}

#[test]
fn a_seven_iron_session_against_the_driver_is_refused_naming_loft() {
    // A real-format FlightScope export of 7-iron shots (dynamic loft 20–22°), read as exported.
    let shots = s(&repo("cli/tests/fixtures/import/flightscope_fsgolf.csv")).to_owned();
    for cmd in ["compare", "diagnose", "calibrate"] {
        let mut args = vec![cmd, "--club", DRIVER, "--shots", &shots];
        args.extend(["--format", "flightscope", "--impact-offset-positive", "toe"]);
        if cmd == "calibrate" {
            args.extend(["--effects", "loft_bias"]);
        }
        refused(
            &args,
            &[
                "does not match the club",
                "'7 Iron' (a 7-iron, usual loft about 34°)",
                "loft is 9.8°",
                "median dynamic loft",
                "--ignore-club-mismatch",
            ],
        );
    }
}

#[test]
fn the_delivered_loft_alone_refuses_another_club() {
    // The paper world's shots with no club names, delivered 11° more lofted: an iron's loft.
    let dir = tempfile::tempdir().unwrap();
    let world = paper_world(dir.path());
    let lofted = rewrite(
        &world,
        &dir.path().join("lofted.csv"),
        "dynamic_loft_deg",
        |_, v| format!("{}", v.parse::<f64>().unwrap() + 11.0),
    );
    refused(
        &["compare", "--club", DRIVER, "--shots", s(&lofted)],
        &["median dynamic loft is 2", "club file's loft is 9.8°"],
    );
}

#[test]
fn a_mixed_club_file_is_refused_with_the_advice_to_split_it() {
    let dir = tempfile::tempdir().unwrap();
    let world = paper_world(dir.path());
    let names = ["Driver", "7 Iron", "Pitching Wedge"];
    let mixed = rewrite(&world, &dir.path().join("mixed.csv"), "group", |n, _| {
        names[n % 3].to_owned()
    });
    for cmd in ["compare", "diagnose"] {
        refused(
            &[cmd, "--club", DRIVER, "--shots", s(&mixed)],
            &[
                "names 3 different clubs ('Driver', '7 Iron', 'Pitching Wedge')",
                "one loft",
                "split the export by club, one file per club, each with its own club file",
            ],
        );
    }
}

#[test]
fn ignoring_the_mismatch_runs_and_reports_no_findings() {
    let dir = tempfile::tempdir().unwrap();
    let world = paper_world(dir.path());
    let irons = rewrite(&world, &dir.path().join("irons.csv"), "group", |_, _| {
        "7i".to_owned()
    });
    let args = [
        "compare",
        "--club",
        DRIVER,
        "--shots",
        s(&irons),
        "--ignore-club-mismatch",
    ];
    let o = smash(&args);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("warning: ") && err.contains("no findings are reported"));
    let out = String::from_utf8(o.stdout).unwrap();
    assert!(
        out.starts_with("NO FINDINGS: the shots do not match the club"),
        "{out}"
    );
    let mut json_args = args.to_vec();
    json_args.push("--json");
    let o = smash(&json_args);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["findings"], serde_json::json!([]), "{v}");
    // The same shots as the driver they are: the paper world's findings are there.
    let o = smash(&["compare", "--club", DRIVER, "--shots", s(&world), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(!v["findings"].as_array().unwrap().is_empty());
}

#[test]
fn the_paper_world_still_passes_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let world = paper_world(dir.path());
    let o = smash(&["compare", "--club", DRIVER, "--shots", s(&world)]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(!err.contains("does not match"), "{err}");
    assert!(!String::from_utf8_lossy(&o.stdout).contains("NO FINDINGS"));
}

/// `diagnose --json` on `shots`, one cheap step: how its folds were formed and its text.
fn fold_by(shots: &Path) -> (String, String) {
    let args = [
        "diagnose",
        "--club",
        DRIVER,
        "--shots",
        s(shots),
        "--candidates",
        "loft_bias",
        "--max-steps",
        "1",
        "--folds",
        "3",
        "--exact-impact-locations",
    ];
    let o = smash(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    let mut json_args = args.to_vec();
    json_args.push("--json");
    let o = smash(&json_args);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    (v["fold_by"].as_str().unwrap().to_owned(), text)
}

#[test]
fn without_golfers_folds_hold_whole_sessions_or_time_blocks() {
    let dir = tempfile::tempdir().unwrap();
    let world = paper_world(dir.path());
    let rename = |name: &str, out: &str, f: &dyn Fn(usize, &str) -> String| {
        let p = rewrite(&world, &dir.path().join(out), "golfer", f);
        let t = std::fs::read_to_string(&p)
            .unwrap()
            .replacen("golfer", name, 1);
        std::fs::write(&p, t).unwrap();
        p
    };
    // Each golfer's shots on a day of their own: folds by session (date).
    let dated = rename("Date", "dated.csv", &|_, g| {
        format!(
            "2026-05-{:02} 10:00:00",
            g.trim_start_matches(|c: char| !c.is_ascii_digit())
                .parse::<u32>()
                .unwrap_or(0)
                % 28
                + 1
        )
    });
    let (by, text) = fold_by(&dated);
    assert_eq!(by, "session");
    assert!(
        text.contains("3-fold cross-validation by session"),
        "{text}"
    );
    // One day, one shot a minute: folds by time block.
    let timed = rename("time", "timed.csv", &|n, _| {
        format!("{}:{:02}", 8 + n / 60, n % 60)
    });
    assert_eq!(fold_by(&timed).0, "time block");
    // The golfers themselves still fold by golfer.
    assert_eq!(fold_by(&world).0, "golfer");
}

/// The same real-format 7-iron session against the shipped 7-iron head: no mismatch, and
/// `compare` runs and reports every launch component (issue 28: "compare runs on a
/// real-format iron session with the 7-iron file").
#[test]
fn a_seven_iron_session_compares_with_the_seven_iron_head() {
    let shots = s(&repo("cli/tests/fixtures/import/flightscope_fsgolf.csv")).to_owned();
    let o = smash(&[
        "compare",
        "--club",
        "configs/clubs/iron_7.toml",
        "--shots",
        &shots,
        "--format",
        "flightscope",
        "--impact-offset-positive",
        "toe",
        "--json",
    ]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(!err.contains("does not match the club"), "{err}");
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(j.get("club_mismatch").is_none(), "{j}");
    let text = j.to_string();
    for c in [
        "ball_speed_mph",
        "launch_angle_deg",
        "azimuth_deg",
        "backspin_rpm",
    ] {
        assert!(text.contains(c), "{c} missing: {text}");
    }
}
