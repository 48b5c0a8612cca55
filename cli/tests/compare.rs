//! `compare` on synthetic worlds whose truth is known, and the `smash compare` command.

use crate::cli_support;

use std::path::Path;

use smash::compare::{compare, CompareOptions, CompareReport, Pattern};
use smash::data::club_file::read_club;
use smash::model::Shot;
use smash::physics::{Launch, LaunchComponent};
use smash::predict::predict_shots;
use smash::report::compare::{compare_files, compare_json, compare_text};
use smash::stats::{mean, std_dev};
use smash::synth::{generate, read_config};

use cli_support::smash_in_repo as smash;

/// The repository root (this package is `cli/`); the command runs from there.
const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

fn world(name: &str) -> (Vec<Shot>, Vec<Launch>) {
    let cfg = read_config(&Path::new(ROOT).join(format!("configs/synth/{name}.toml"))).unwrap();
    let club = read_club(&Path::new(ROOT).join("configs/clubs/paper_driver.toml")).unwrap();
    let run = generate(&cfg, &club).unwrap();
    let shots: Vec<Shot> = run.shots.iter().map(|s| s.to_shot()).collect();
    let pred = predict_shots(&club, &shots)
        .unwrap()
        .iter()
        .map(|o| o.launch())
        .collect();
    (shots, pred)
}

fn report(name: &str) -> (Vec<Shot>, Vec<Launch>, CompareReport) {
    let (s, p) = world(name);
    let r = compare(&s, &p, &CompareOptions::default()).unwrap();
    (s, p, r)
}

#[test]
fn paper_world_against_the_nominal_club_looks_like_the_papers_table_2() {
    let (_, _, r) = report("paper_world");
    for block in &r.table2 {
        let speed = &block.components[LaunchComponent::BallSpeed.index()];
        let m = speed.summary.mean.unwrap();
        assert!((-1.0..-0.3).contains(&m), "{}: speed bias {m}", block.group);
        assert!(speed.significant, "{}", block.group);
        let spin = &block.components[LaunchComponent::Backspin.index()];
        assert!(spin.summary.mean.unwrap() > 300.0, "{}", block.group);
        assert!(spin.significant);
    }
    let first = &r.findings[0];
    assert_eq!(first.component, "backspin_rpm");
    assert_eq!(first.pattern, Pattern::Bias);
    assert!(first.hints.iter().any(|h| h.contains("ball_offset")));
    assert!(r.findings.iter().any(
        |f| f.component == "ball_speed_mph" && f.hints.iter().any(|h| h.contains("added_mass"))
    ));
}

#[test]
fn null_world_flags_nothing_beyond_chance() {
    let (_, _, r) = report("null_world");
    assert!(r.findings.is_empty(), "{:#?}", r.findings);
    let bias_flags = r
        .table2
        .iter()
        .flat_map(|b| &b.components)
        .filter(|c| c.significant)
        .count();
    // 20 bias tests at 1 %: P(≥ 2 false flags) ≈ 1.7 %.
    assert!(bias_flags <= 1, "{bias_flags}");
}

#[test]
fn world_only_physics_is_found_where_it_is() {
    let (_, _, r) = report("cor_power_world");
    assert!(r
        .findings
        .iter()
        .any(|f| f.pattern == Pattern::Trend("club_speed_mph") && f.component == "ball_speed_mph"));
    let (_, _, r) = report("face_flex_world");
    assert!(r
        .findings
        .iter()
        .any(|f| f.pattern == Pattern::Trend("impact_r_mm") && f.component == "ball_speed_mph"));
}

#[test]
fn table2_equals_a_direct_computation() {
    let (shots, pred, r) = report("paper_world");
    for block in &r.table2 {
        let idx: Vec<usize> = (0..shots.len())
            .filter(|&k| block.group == "all" || shots[k].group == block.group)
            .collect();
        assert_eq!(block.n, idx.len());
        for c in LaunchComponent::ALL {
            let e: Vec<f64> = idx
                .iter()
                .map(|&k| pred[k].get_file(c) - shots[k].measured.unwrap().get_file(c))
                .collect();
            let s = &block.components[c.index()].summary;
            approx::assert_relative_eq!(s.mean.unwrap(), mean(&e), max_relative = 1e-12);
            approx::assert_relative_eq!(s.std.unwrap(), std_dev(&e), max_relative = 1e-12);
        }
    }
}

#[test]
fn face_bins_account_for_every_shot_and_sparse_bins_are_empty() {
    let (shots, _, r) = report("paper_world");
    assert_eq!(
        r.face.bins.iter().map(|b| b.count).sum::<usize>(),
        shots.len()
    );
    assert_eq!(r.face.bins.len(), r.face.ys_mm.len() * r.face.zs_mm.len());
    for b in &r.face.bins {
        assert_eq!(b.mean[0].is_some(), b.count >= r.face.min_count);
    }
    for t in &r.binned {
        assert_eq!(t.rows.iter().map(|x| x.count).sum::<usize>(), shots.len());
    }
}

fn check_json(v: &serde_json::Value, path: &str) {
    match v {
        serde_json::Value::Null => assert!(
            path.contains("face.bins") && (path.contains(".mean") || path.contains(".std")),
            "null at {path}"
        ),
        serde_json::Value::Number(n) => assert!(n.as_f64().unwrap().is_finite(), "{path}"),
        serde_json::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                check_json(x, &format!("{path}[{i}]"));
            }
        }
        serde_json::Value::Object(o) => {
            for (k, x) in o {
                check_json(x, &format!("{path}.{k}"));
            }
        }
        _ => {}
    }
}

#[test]
fn no_nan_anywhere_in_the_outputs() {
    for w in ["paper_world", "null_world", "face_flex_world"] {
        let (_, _, r) = report(w);
        let text = compare_text(&r, w, false);
        let json: serde_json::Value = serde_json::from_str(&compare_json(&r)).unwrap();
        check_json(&json, "");
        for (name, bytes) in compare_files(&r, &text) {
            let s = String::from_utf8(bytes).unwrap();
            for bad in ["NaN", "inf"] {
                assert!(!s.contains(bad), "{name} contains {bad}");
            }
        }
    }
}

#[test]
fn cli_synth_then_compare_writes_tables_pictures_and_json() {
    let dir = tempfile::tempdir().unwrap();
    let shots = dir.path().join("paper.csv");
    let truth = dir.path().join("truth.toml");
    let out = dir.path().join("cmp");
    let o = smash(&[
        "synth",
        "--config",
        "configs/synth/paper_world.toml",
        "--out",
        shots.to_str().unwrap(),
        "--truth",
        truth.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(truth.exists());
    let o = smash(&[
        "compare",
        "--club",
        "configs/clubs/paper_driver.toml",
        "--shots",
        shots.to_str().unwrap(),
        "--out-dir",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(json["n_shots"], 600);
    assert!(String::from_utf8_lossy(&o.stderr).contains("Findings"));
    for f in [
        "table2.csv",
        "face_residuals.csv",
        "face_backspin_rpm.svg",
        "residuals_by_club_speed_mph.csv",
        "correlations.csv",
        "compare.json",
    ] {
        assert!(out.join(f).exists(), "{f}");
    }
}

#[test]
fn cli_compare_without_measurements_fails_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let shots = dir.path().join("no_launch.csv");
    std::fs::write(
        &shots,
        "shot_id,club_speed_mph,attack_angle_deg,club_path_deg,dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm\n\
         s1,105,0,0,12,0,0,0\n",
    )
    .unwrap();
    let out = dir.path().join("cmp");
    let o = smash(&[
        "compare",
        "--club",
        "configs/clubs/paper_driver.toml",
        "--shots",
        shots.to_str().unwrap(),
        "--out-dir",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("no measured launch columns"), "{err}");
    assert!(err.contains("ball_speed_mph"), "{err}");
    assert!(!out.exists());
}

#[test]
fn cli_synth_bad_config_names_the_key_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("bad.toml");
    std::fs::write(&cfg, "seed = 1\n[noise.launch]\nbackspin = 100.0\n").unwrap();
    let out = dir.path().join("shots.csv");
    let o = smash(&[
        "synth",
        "--config",
        cfg.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("noise.launch.backspin") && err.contains(":3"),
        "{err}"
    );
    assert!(!out.exists());
}

/// An output folder that cannot be written (a pseudo file system) is refused before any work:
/// one error line naming it, nothing printed on stdout (the report is not shown first).
#[test]
fn cli_compare_refuses_an_unwritable_out_dir_before_the_report() {
    let dir = tempfile::tempdir().unwrap();
    let shots = cli_support::measured_shots(dir.path());
    let club = cli_support::club();
    for out in ["/proc/smash-compare-outputs", "/proc/self/smash-outputs"] {
        let o = smash(&[
            "compare",
            "--club",
            &club,
            "--shots",
            shots.to_str().unwrap(),
            "--out-dir",
            out,
        ]);
        assert!(!o.status.success(), "{out}");
        assert!(
            o.stdout.is_empty(),
            "{}",
            String::from_utf8_lossy(&o.stdout)
        );
        let err = cli_support::stderr(&o);
        let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
        assert_eq!(lines.len(), 1, "{err}");
        assert!(
            lines[0].starts_with("error: ") && lines[0].contains(out),
            "{err}"
        );
    }
}

/// Long group names (shaft names, as a fitting session writes them) get columns of their
/// width: each heading is apart from the column before, every value sits under its heading,
/// and the lines stay within 100 columns.
#[test]
fn long_group_names_keep_their_columns_apart() {
    let (mut s, p) = world("paper_world");
    for shot in &mut s {
        shot.group = match shot.group.as_str() {
            "A" => "Stiff-X-68g-Ventus".into(),
            "B" => "Regular-55g-Tensei".into(),
            g => g.to_string(),
        };
    }
    let r = compare(&s, &p, &CompareOptions::default()).unwrap();
    let text = compare_text(&r, "long names", false);
    let headers: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("Component"))
        .collect();
    assert!(headers.len() >= 2, "{text}");
    for h in &headers {
        assert!(!h.contains("STDR") && !h.contains("STDS"), "{h}");
    }
    for block in text.split("\n\n").filter(|b| b.contains("Component")) {
        let lines: Vec<&str> = block
            .lines()
            .skip_while(|l| !l.starts_with("Component"))
            .collect();
        // Every row of a block ends where its heading does (right-aligned columns).
        let width = lines[0].chars().count();
        for l in &lines[1..6] {
            assert_eq!(l.chars().count(), width, "{block}");
        }
        assert!(width <= 100, "{block}");
    }
}
