//! `smash infer-club` end to end: the written club reads back in every command (compare here)
//! with each value's SE and provenance in its comments, the text and plan outputs, and bad
//! input refused in one line with a non-zero exit and nothing written.

use crate::cli_support;

use cli_support::{club, s, smash, stderr, synth_world};

#[test]
fn infers_a_head_writes_a_club_compare_reads_and_plans() {
    let dir = tempfile::tempdir().unwrap();
    let shots = synth_world(dir.path(), "face_curvature_world", 3);
    let start = club();
    let out = dir.path().join("head.toml");
    let page = dir.path().join("head.html");
    let o = smash(&[
        "infer-club",
        "--start",
        &start,
        "--shots",
        s(&shots),
        "--out-club",
        s(&out),
        "--report",
        s(&page),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The page: self-contained, the estimates' table and an ellipse of a correlated pair.
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(
        html.starts_with("<!DOCTYPE html>") && !html.contains("<script"),
        "{html}"
    );
    assert!(
        html.contains("bulge_mm") && html.contains("data-kind=\"ellipse\""),
        "{html}"
    );
    // The face map of the inferred COR.
    assert!(
        html.contains("data-kind=\"face\"") && html.contains("inferred COR over the face"),
        "{html}"
    );
    assert!(!html.contains("NaN") && !html.contains("inf<"));
    let text = String::from_utf8(o.stdout).unwrap();
    for want in [
        "Before fitting",
        "bulge_mm",
        "profile (dchi2 = 1)",
        "Prior:",
        "Rule:",
    ] {
        assert!(text.contains(want), "missing {want:?} in\n{text}");
    }
    let written = std::fs::read_to_string(&out).unwrap();
    assert!(
        written.starts_with("# Inferred by smash infer-club"),
        "{written}"
    );
    for key in [
        "com_mm[0] = ",
        "inertia_gcm2[1][1] = ",
        "bulge_mm = ",
        "cor = ",
    ] {
        let line = written
            .lines()
            .find(|l| l.starts_with(&format!("# {key}")))
            .unwrap_or_else(|| panic!("no comment for {key} in\n{written}"));
        assert!(
            line.contains("+-") && line.contains("prior share"),
            "{line}"
        );
    }
    // The world's true bulge is 250 mm (the start's 305): the inferred face says so.
    let report: serde_json::Value = {
        let o = smash(&[
            "infer-club",
            "--start",
            &start,
            "--shots",
            s(&shots),
            "--json",
            "--no-profile",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let bulge = report["params"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "bulge_mm")
        .unwrap();
    let (v, se) = (
        bulge["value"].as_f64().unwrap(),
        bulge["stderr"].as_f64().unwrap(),
    );
    assert!(
        bulge["determined"] == true && (v - 250.0).abs() < 4.0 * se + 1.0,
        "{bulge}"
    );
    // Every command reads the written club: compare with it.
    let o = smash(&["compare", "--club", s(&out), "--shots", s(&shots)]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The plan.
    let o = smash(&[
        "infer-club",
        "--start",
        &start,
        "--shots",
        s(&shots),
        "--plan",
        "--plan-shots",
        "300",
        "--target-se",
        "bulge_mm=5,cor=0.002",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    // The prose wraps at 120 columns: matched with its line breaks as spaces.
    let flat = text.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        flat.contains("planned for 300 shots") && flat.contains("n for target"),
        "{text}"
    );
}

#[test]
fn bad_input_is_refused_in_one_line_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let shots = synth_world(dir.path(), "face_curvature_world", 3);
    let start = club();
    let out = dir.path().join("head.toml");
    let bad_target = smash(&[
        "infer-club",
        "--start",
        &start,
        "--shots",
        s(&shots),
        "--plan",
        "--target-se",
        "bulge=5",
    ]);
    let bad_settings = cli_support::write(dir.path(), "s.toml", "determined_fraction = 2.0\n");
    let bad_fraction = smash(&[
        "infer-club",
        "--start",
        &start,
        "--shots",
        s(&shots),
        "--settings",
        s(&bad_settings),
        "--out-club",
        s(&out),
    ]);
    let unknown = cli_support::write(dir.path(), "u.toml", "prior_widht = 2.0\n");
    let bad_key = smash(&[
        "infer-club",
        "--start",
        &start,
        "--shots",
        s(&shots),
        "--settings",
        s(&unknown),
    ]);
    for (o, want) in [
        (bad_target, "'bulge' is not a head parameter"),
        (bad_fraction, "determined_fraction: must be in (0, 1)"),
        (bad_key, "prior_widht"),
    ] {
        let e = stderr(&o);
        assert!(!o.status.success(), "{e}");
        assert!(e.contains(want), "{e}");
        assert_eq!(e.trim().lines().count(), 1, "{e}");
    }
    assert!(!out.exists());
}
