//! `smash flight --diagnose` on real shots (the fit session of `tests/data/real/`, imported as
//! a user would): the ranking's text and JSON, folds by session when the file has a date
//! column and by shot otherwise, said in the output, and its refusals.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::{repo, s, smash, stderr};

/// The real 7-iron session imported, with a `date` column when `dates` (the first half one
/// day, the rest the next).
fn shots(dir: &Path, dates: bool) -> PathBuf {
    let imported = dir.join("i.csv");
    let export = repo("tests/data/real/rapsodo_mlm2pro_7i.csv");
    let o = smash(&[
        "import",
        "--format",
        "rapsodo",
        s(&export),
        "--out",
        s(&imported),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    if !dates {
        return imported;
    }
    let text = std::fs::read_to_string(&imported).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let mut out = format!("date,{}\n", lines[0]);
    for (i, l) in lines[1..].iter().enumerate() {
        let day = if i < lines.len() / 2 {
            "2026-01-27"
        } else {
            "2026-01-28"
        };
        out.push_str(&format!("{day} 16:30,{l}\n"));
    }
    let p = dir.join("dated.csv");
    std::fs::write(&p, out).unwrap();
    p
}

/// Text: the header names the model and the folds, each step's table, the selection and the
/// RMSE; every line under 100 columns; the output file holds the selected model's flights.
#[test]
fn diagnose_text_names_folds_and_terms() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("f.csv");
    for (dates, folds) in [(false, "folds by shot (5)"), (true, "folds by session (2)")] {
        let shots = shots(dir.path(), dates);
        let o = smash(&[
            "flight",
            "--shots",
            s(&shots),
            "--out",
            s(&out),
            "--diagnose",
        ]);
        let err = stderr(&o);
        assert!(o.status.success(), "{err}");
        assert!(
            err.contains(&format!(
                "flight diagnose: 59 shots, model fmm2022, {folds}"
            )),
            "{err}"
        );
        let said = if dates {
            "folds by session (sessions from column 'date')"
        } else {
            "folds by shot (no session or date column with two or more sessions)"
        };
        assert!(err.contains(said), "{err}");
        assert!(err.contains("step 1: noise carry"), "{err}");
        assert!(
            err.contains("  term          k   CV gain  penalty    margin"),
            "{err}"
        );
        for term in ["drag ", "lift ", "drag_crisis ", "spin_decay "] {
            assert!(err.contains(&format!("\n  {term}")), "{term}: {err}");
        }
        assert!(err.contains("RMSE on all shots: carry"), "{err}");
        // The diagnosis's lines (up to the folds line; the flew line names a path).
        let diagnosis = &err[..err.find(said).unwrap()];
        assert!(diagnosis.lines().all(|l| l.chars().count() < 100), "{err}");
        let text = std::fs::read_to_string(&out).unwrap();
        assert_eq!(text.lines().count(), 60);
        assert!(text.lines().next().unwrap().contains("err_carry_yd"));
    }
}

/// JSON: the diagnosis and the error summary in one object on stdout; its selected terms,
/// steps and values agree with each other.
#[test]
fn diagnose_json_is_one_object() {
    let dir = tempfile::tempdir().unwrap();
    let shots = shots(dir.path(), true);
    let out = dir.path().join("f.csv");
    let o = smash(&[
        "flight",
        "--shots",
        s(&shots),
        "--out",
        s(&out),
        "--diagnose",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let d = &j["diagnosis"];
    assert_eq!(d["folds_by"], "session");
    assert_eq!(d["shots"], 59);
    let steps = d["steps"].as_array().unwrap();
    let selected: Vec<&str> = d["selected"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_str().unwrap())
        .collect();
    let chosen: Vec<&str> = steps
        .iter()
        .filter_map(|s| s["selected"].as_str())
        .collect();
    assert_eq!(selected, chosen);
    assert_eq!(
        steps.len(),
        selected.len() + usize::from(selected.len() < 5)
    );
    // An estimate, or a value held at a bound of its term without a standard error (this
    // session holds `spin_decay` at a third of the model's moment).
    for v in d["values"].as_array().unwrap() {
        let at_bound = v["at_bound"].as_bool().unwrap();
        assert!(at_bound == v["se"].is_null(), "{v}");
        assert!(at_bound || v["se"].as_f64().unwrap() > 0.0, "{v}");
    }
    assert!(j["errors"]["rows"].is_array(), "{j}");
}

/// A value the fit holds at a bound of its term is said to sit there, in the text and in the
/// JSON (`at_bound`, no standard error), not printed as an estimate with a standard error; no
/// output says `NaN`. The session with every other shot's flight blank: its first step holds
/// `spin_decay` at a third of the model's moment.
#[test]
fn values_at_a_bound_are_said_to_be_there() {
    let dir = tempfile::tempdir().unwrap();
    let full = std::fs::read_to_string(shots(dir.path(), false)).unwrap();
    let mut lines = full.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let blank: Vec<usize> = ["carry_yd", "apex_yd", "land_angle_deg"]
        .iter()
        .map(|c| header.iter().position(|h| h == c).unwrap())
        .collect();
    let mut text = format!("{}\n", header.join(","));
    for (i, l) in lines.enumerate() {
        let mut cells: Vec<&str> = l.split(',').collect();
        if i % 2 == 1 {
            for &c in &blank {
                cells[c] = "";
            }
        }
        text.push_str(&format!("{}\n", cells.join(",")));
    }
    let shots = cli_support::write(dir.path(), "half.csv", &text);
    let out = dir.path().join("f.csv");
    let run = |json: bool| {
        let mut args = vec![
            "flight",
            "--shots",
            s(&shots),
            "--out",
            s(&out),
            "--diagnose",
        ];
        if json {
            args.push("--json");
        }
        let o = smash(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        o
    };
    let err = stderr(&run(false));
    assert!(!err.contains("NaN") && !err.contains("inf"), "{err}");
    assert!(
        err.contains("spin_decay x0.3333 (at its lower bound)"),
        "{err}"
    );
    let o = run(true);
    let json = String::from_utf8(o.stdout).unwrap();
    assert!(!json.contains("NaN"), "{json}");
    let j: serde_json::Value = serde_json::from_str(&json).unwrap();
    let mut at_bound = 0;
    for step in j["diagnosis"]["steps"].as_array().unwrap() {
        for c in step["candidates"].as_array().unwrap() {
            for v in c["values"].as_array().unwrap() {
                let value = v["value"].as_f64().unwrap();
                if v["at_bound"].as_bool().unwrap() {
                    at_bound += 1;
                    assert!(v["se"].is_null(), "{v}");
                    let bounds = [1.0 / 3.0, 3.0, -0.15, 0.40];
                    assert!(bounds.iter().any(|b| (value - b).abs() < 1e-5), "{v}");
                } else {
                    assert!(v["se"].as_f64().unwrap() > 0.0, "{v}");
                }
            }
        }
    }
    assert!(at_bound > 0, "{json}");
}

/// Refusals: with --calibrate, and on a file that states conditions per shot.
#[test]
fn diagnose_refusals() {
    let dir = tempfile::tempdir().unwrap();
    let shots = shots(dir.path(), false);
    let out = dir.path().join("f.csv");
    let both = smash(&[
        "flight",
        "--shots",
        s(&shots),
        "--out",
        s(&out),
        "--diagnose",
        "--calibrate",
        "drag",
    ]);
    assert!(!both.status.success());
    assert!(
        stderr(&both).contains("cannot be used with"),
        "{}",
        stderr(&both)
    );
    let text = std::fs::read_to_string(&shots).unwrap();
    let mut lines = text.lines();
    let mut with_air = format!("altitude_m,{}\n", lines.next().unwrap());
    for l in lines {
        with_air.push_str(&format!("1600,{l}\n"));
    }
    let p = dir.path().join("air.csv");
    std::fs::write(&p, with_air).unwrap();
    let o = smash(&["flight", "--shots", s(&p), "--out", s(&out), "--diagnose"]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("--diagnose flies every shot in one atmosphere"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
}
