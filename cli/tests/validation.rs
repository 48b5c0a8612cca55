//! Hostile inputs through the built `smash` binary: caps that cannot be bypassed (no overflow,
//! no abort), no `inf` or `NaN` in any output, and degenerate data named instead of fitted.
//! Every refusal is one line on stderr naming the culprit (file and key or column, the value and
//! the allowed range) with a non-zero exit, and writes nothing.

use crate::cli_support;

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Output;

use cli_support::smash;

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

fn club() -> String {
    root()
        .join("configs/clubs/paper_driver.toml")
        .to_string_lossy()
        .into_owned()
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_string_lossy().into_owned()
}

/// Words that mean a number went wrong.
/// A study of the paper driver with `extra` appended and `(from, to)` replacements.
fn study(dir: &Path, extra: &str, replace: &[(&str, &str)]) -> String {
    let mut t = format!(
        "[study]\nname = \"v\"\nclub = \"{}\"\n\n[delivery]\nclub_speed_mph = 100.0\n\
         dynamic_loft_deg = 12.0\n\n[grid]\ny_mm = {{ from = -10.0, to = 10.0, count = 3 }}\n\
         z_mm = {{ from = -20.0, to = 20.0, count = 5 }}\n{extra}",
        club()
    );
    for (a, b) in replace {
        assert!(t.contains(a), "{a}");
        t = t.replace(a, b);
    }
    write(dir, "study.toml", &t)
}

fn run_study(dir: &Path, path: &str) -> Output {
    let out = dir.join("out");
    let o = smash(&["run", path, "--out", out.to_str().unwrap()]);
    if !o.status.success() {
        assert!(!out.exists(), "a refused study wrote {}", out.display());
    }
    o
}

/// A synthetic shots file with measurements (the null world, 600 shots).
fn shots(dir: &Path) -> String {
    let cfg = root().join("configs/synth/null_world.toml");
    let out = dir.join("null.csv");
    let o = smash(&[
        "synth",
        "--config",
        cfg.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    out.to_string_lossy().into_owned()
}

/// `shots` with column `col` of data row `row` (0-based) set to `value`.
fn with_cell(text: &str, row: usize, col: &str, value: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let i = lines[0].split(',').position(|h| h == col).expect(col);
    let mut cells: Vec<String> = lines[row + 1].split(',').map(str::to_owned).collect();
    cells[i] = value.to_owned();
    lines[row + 1] = cells.join(",");
    lines.join("\n") + "\n"
}

// ---------------------------------------------------------------------------------------------
// 3. Caps that cannot be bypassed.

#[test]
fn design_axes_whose_product_overflows_are_refused_with_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let axes = "[design]\ncom_dx_mm = { from = -1.0, to = 1.0, count = 65536 }\n\
                com_dy_mm = { from = -1.0, to = 1.0, count = 65536 }\n\
                com_dz_mm = { from = -1.0, to = 1.0, count = 65536 }\n\
                inertia_scale = { from = 0.9, to = 1.1, count = 65536 }\n";
    let p = study(dir.path(), axes, &[]);
    let o = run_study(dir.path(), &p);
    common::assert_refused(&o, &["study.toml", "design variants", "65536", "1000000"]);
}

#[test]
fn grid_points_times_variants_are_capped_before_anything_is_allocated() {
    let dir = tempfile::tempdir().unwrap();
    // 7071 × 7071 ≈ 50 million points was accepted and aborted at 15 GB before the outputs were
    // streamed; now the cap is 500 million points (time and disk, not memory): 30000² is over it.
    let p = study(
        dir.path(),
        "",
        &[
            ("count = 3", "count = 30000"),
            ("count = 5", "count = 30000"),
        ],
    );
    let o = run_study(dir.path(), &p);
    common::assert_refused(&o, &["study.toml", "grid points", "900000000", "500000000"]);
    // Variants × grid: each within its own cap, the product beyond.
    let p = study(
        dir.path(),
        "[design]\ncom_dx_mm = { from = -1.0, to = 1.0, count = 1000 }\n",
        &[("count = 3", "count = 800"), ("count = 5", "count = 800")],
    );
    common::assert_refused(
        &run_study(dir.path(), &p),
        &["grid points", "1000 (design variants)", "500000000"],
    );
}

#[test]
fn sharded_studies_too_large_to_merge_are_refused_before_any_shard_runs() {
    // `merge` streams (its cap is the run cap, MAX_MERGE_POINTS = MAX_SWEEP_POINTS): a study of
    // 25000 × 25000 = 625 M points is over it, so no shard of it may run.
    let dir = tempfile::tempdir().unwrap();
    let p = study(
        dir.path(),
        "",
        &[
            ("count = 5", "count = 25000"),
            ("count = 3", "count = 25000"),
        ],
    );
    let out = dir.path().join("shard");
    let o = smash(&[
        "run",
        &p,
        "--shard",
        "1/100",
        "--out",
        out.to_str().unwrap(),
    ]);
    common::assert_refused(&o, &["625000000", "500000000"]);
    assert!(!out.exists());
}

#[test]
fn summary_probe_lines_of_billions_of_points_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let p = study(
        dir.path(),
        "[summary]\nhalf_width_mm = 20.0\nstep_mm = 1e-9\n",
        &[],
    );
    common::assert_refused(&run_study(dir.path(), &p), &["summary.step_mm", "10001"]);
}

#[test]
fn synth_caps_the_total_number_of_shots_not_only_per_group() {
    let dir = tempfile::tempdir().unwrap();
    let groups: Vec<String> = (0..100)
        .map(|i| format!("{{ name = \"g{i}\", shaft_mass_g = 60.0 }}"))
        .collect();
    let cfg = write(
        dir.path(),
        "big.toml",
        &format!(
            "club = \"{}\"\n[design]\ngolfers = 1000\nswings_per_golfer = 10000\ngroups = [{}]\n",
            club(),
            groups.join(", ")
        ),
    );
    let out = dir.path().join("big.csv");
    let o = smash(&["synth", "--config", &cfg, "--out", out.to_str().unwrap()]);
    common::assert_refused(&o, &["big.toml", "100 (groups)", "1000000000", "2000000"]);
    assert!(!out.exists());
}

// ---------------------------------------------------------------------------------------------
// 5. No inf or NaN ever reaches the user.

#[test]
fn one_shot_prediction_refuses_a_speed_outside_the_physical_range() {
    for speed in ["1e155", "1e308", "300"] {
        let o = smash(&[
            "predict",
            "--club",
            &club(),
            "--speed",
            speed,
            "--loft",
            "12",
        ]);
        common::assert_refused(&o, &["--speed", speed, "[1, 250] mph"]);
    }
    let o = smash(&[
        "predict",
        "--club",
        &club(),
        "--speed",
        "100",
        "--loft",
        "12",
        "--omega-x-rad-s",
        "1e300",
    ]);
    common::assert_refused(&o, &["--omega-x-rad-s", "1e300", "rad/s"]);
}

#[test]
fn a_shots_row_outside_the_physical_ranges_is_named_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(shots(dir.path())).unwrap();
    let cases = [
        ("club_speed_mph", "1e200", "[1, 250] mph"),
        ("impact_z_mm", "1e300", "[-100, 100] mm"),
        ("club_omega_y_rad_s", "-5000", "rad/s"),
        ("dynamic_loft_deg", "400", "[-90, 90] deg"),
        ("ball_speed_mph", "1e200", "mph"),
        ("backspin_rpm", "1e300", "rpm"),
    ];
    for (col, value, range) in cases {
        let bad = write(dir.path(), "bad.csv", &with_cell(&text, 3, col, value));
        let out = dir.path().join("pred.csv");
        // Without --strict the row is left out with a note naming the same (`bad_rows.rs`).
        let o = smash(&[
            "predict",
            "--club",
            &club(),
            "--shots",
            &bad,
            "--out",
            out.to_str().unwrap(),
            "--strict",
        ]);
        common::assert_refused(&o, &["bad.csv:5", &format!("column '{col}'"), value, range]);
        assert!(!out.exists(), "{col} = {value} wrote predictions");
    }
}

#[test]
fn calibrate_refuses_an_unphysical_measurement_and_writes_no_club() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(shots(dir.path())).unwrap();
    let bad = write(
        dir.path(),
        "bad.csv",
        &with_cell(&text, 0, "backspin_rpm", "1e300"),
    );
    let out = dir.path().join("cal.toml");
    let o = smash(&[
        "calibrate",
        "--club",
        &club(),
        "--shots",
        &bad,
        "--effects",
        "ball_offset",
        "--out-club",
        out.to_str().unwrap(),
        "--strict",
    ]);
    common::assert_refused(&o, &["bad.csv:2", "backspin_rpm", "1e300", "rpm"]);
    assert!(!out.exists());
}

#[test]
fn study_values_outside_the_physical_ranges_name_their_key() {
    let dir = tempfile::tempdir().unwrap();
    // (appended sections, replacements, what the message must name)
    type Case<'a> = (String, Vec<(&'a str, &'a str)>, Vec<&'a str>);
    let cases: Vec<Case> = vec![
        (
            String::new(),
            vec![("club_speed_mph = 100.0", "club_speed_mph = 1e200")],
            vec!["delivery.club_speed_mph", "1e200", "[1, 250] mph"],
        ),
        (
            "[summary]\nhalf_width_mm = 400\n".into(),
            vec![],
            vec!["summary.half_width_mm", "400", "mm"],
        ),
        (
            String::new(),
            vec![("to = 20.0", "to = 1e308")],
            vec!["grid.z_mm.to", "1e308", "mm"],
        ),
        (
            String::new(),
            vec![("from = -20.0", "from = -1e308")],
            vec!["grid.z_mm.from", "-1e308", "mm"],
        ),
        (
            "[design]\ncom_dx_mm = [0.0, 1e300]\n".into(),
            vec![],
            vec!["design.com_dx_mm", "1e300", "[-100, 100] mm"],
        ),
        (
            "[design]\ninertia_scale = [1.0, 1e9]\n".into(),
            vec![],
            vec!["design.inertia_scale", "1e9", "[0.1, 10]"],
        ),
        (
            String::new(),
            vec![("dynamic_loft_deg = 12.0", "dynamic_loft_deg = 12.0\nclub_omega_rad_s = [0.0, 1e200, 0.0]")],
            vec!["delivery.club_omega_rad_s", "1e200"],
        ),
        (
            "[distribution]\nsigma_y_mm = 1e300\n".into(),
            vec![],
            vec!["distribution.sigma_y_mm", "1e300"],
        ),
        (
            "[optimise]\ngoal = \"maximise\"\nobjective = { cof_ball_speed_mph = 1.0 }\nbounds = { com_dx_mm = [-1e300, 1.0] }\n".into(),
            vec![],
            vec!["optimise.bounds.com_dx_mm", "-1e300"],
        ),
    ];
    for (extra, replace, needles) in cases {
        let p = study(dir.path(), &extra, &replace);
        common::assert_refused(&run_study(dir.path(), &p), &needles);
    }
}

#[test]
fn probe_lines_off_a_small_face_are_refused_before_the_sweep() {
    let dir = tempfile::tempdir().unwrap();
    // A face with a 40 mm roll radius: probe lines 45 mm up the face are off it.
    let text = std::fs::read_to_string(club())
        .unwrap()
        .replace("roll_mm = 305.0", "roll_mm = 40.0");
    let small = write(dir.path(), "small.toml", &text);
    let p = study(
        dir.path(),
        "[summary]\nhalf_width_mm = 45.0\n",
        &[(club().as_str(), small.as_str())],
    );
    common::assert_refused(
        &run_study(dir.path(), &p),
        &["summary.half_width_mm", "off the face", "roll 40.0 mm"],
    );
}

#[test]
fn club_files_outside_the_physical_ranges_name_their_key() {
    let dir = tempfile::tempdir().unwrap();
    let base = std::fs::read_to_string(club()).unwrap();
    let cases = [
        (
            "bulge_mm = 305.0",
            "bulge_mm = 200.0",
            vec!["club.bulge_mm", "roll_mm"],
        ),
        (
            "com_mm = [-42.3, 2.9, 1.0]",
            "com_mm = [-42.3, 1e300, 1.0]",
            vec!["club.com_mm", "1e300", "mm"],
        ),
        (
            "[[2843.0, -733.0, 530.2]",
            "[[1e300, -733.0, 530.2]",
            vec!["club.inertia_gcm2", "1e300"],
        ),
    ];
    for (from, to, needles) in cases {
        assert!(base.contains(from), "{from}");
        let c = write(dir.path(), "club.toml", &base.replace(from, to));
        let o = smash(&["predict", "--club", &c, "--speed", "100", "--loft", "12"]);
        common::assert_refused(&o, &needles);
    }
}

#[test]
fn synth_refuses_unphysical_delivery_means_instead_of_writing_empty_cells() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(
        dir.path(),
        "fast.toml",
        &format!(
            "club = \"{}\"\n[delivery]\nclub_speed_mph = {{ mean = 1e300, between = 1.0, within = 1.0 }}\n",
            club()
        ),
    );
    let out = dir.path().join("fast.csv");
    let o = smash(&["synth", "--config", &cfg, "--out", out.to_str().unwrap()]);
    common::assert_refused(
        &o,
        &[
            "fast.toml",
            "delivery.club_speed_mph.mean",
            "1e300",
            "[1, 250] mph",
        ],
    );
    assert!(!out.exists());
}

#[test]
fn every_synthetic_shot_reads_back_within_the_physical_ranges() {
    // Wide spreads draw values beyond the ranges; those swings are redrawn, so what synth
    // writes, predict reads.
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(
        dir.path(),
        "wide.toml",
        &format!(
            "club = \"{}\"\n[design]\ngolfers = 4\nswings_per_golfer = 10\n\
             [delivery]\nclub_speed_mph = {{ mean = 240.0, between = 5.0, within = 5.0 }}\n",
            club()
        ),
    );
    let out = dir.path().join("wide.csv");
    let o = smash(&["synth", "--config", &cfg, "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let pred = dir.path().join("pred.csv");
    let o = smash(&[
        "predict",
        "--club",
        &club(),
        "--shots",
        out.to_str().unwrap(),
        "--out",
        pred.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&pred).unwrap();
    assert!(
        !common::has_non_finite(&text) && !text.contains(",,"),
        "{text}"
    );
}

// ---------------------------------------------------------------------------------------------
// 7. Degenerate data are named.

fn identical_shots(dir: &Path, n: usize) -> String {
    let text = std::fs::read_to_string(shots(dir)).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    let first = lines.next().unwrap();
    let rest = first.split_once(',').unwrap().1;
    let mut t = format!("{header}\n");
    for i in 0..n {
        t.push_str(&format!("s{i},{rest}\n"));
    }
    write(dir, "same.csv", &t)
}

#[test]
fn diagnose_names_identical_shots_instead_of_selecting_an_effect() {
    let dir = tempfile::tempdir().unwrap();
    let same = identical_shots(dir.path(), 60);
    let o = smash(&["diagnose", "--club", &club(), "--shots", &same]);
    common::assert_refused(&o, &["same.csv", "degenerate", "same delivery", "60 shots"]);
    assert!(String::from_utf8_lossy(&o.stdout).trim().is_empty());
}

#[test]
fn calibrate_names_identical_shots_instead_of_fitting() {
    let dir = tempfile::tempdir().unwrap();
    let same = identical_shots(dir.path(), 60);
    let out = dir.path().join("cal.toml");
    let o = smash(&[
        "calibrate",
        "--club",
        &club(),
        "--shots",
        &same,
        "--effects",
        "com_offset",
        "--out-club",
        out.to_str().unwrap(),
    ]);
    common::assert_refused(&o, &["same.csv", "degenerate", "same delivery"]);
    assert!(!out.exists());
}

#[test]
fn an_effect_that_needs_a_variable_to_vary_is_refused_when_it_is_constant() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(shots(dir.path())).unwrap();
    let mut t = text.clone();
    for row in 0..text.lines().count() - 1 {
        t = with_cell(&t, row, "club_speed_mph", "100");
    }
    let constant = write(dir.path(), "constant.csv", &t);
    let club = club();
    for cmd in [
        vec!["calibrate", "--effects", "cor_speed"],
        vec!["diagnose", "--candidates", "cor_speed"],
    ] {
        let mut args = cmd.clone();
        args.extend(["--club", club.as_str(), "--shots", constant.as_str()]);
        let o = smash(&args);
        common::assert_refused(&o, &["constant.csv", "cor_speed", "club_speed_mph = 100"]);
    }
}

#[test]
fn diagnose_leaves_out_a_default_candidate_the_data_cannot_identify_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(shots(dir.path())).unwrap();
    // 60 shots, every one at the face centre: a COR falloff from the centre cannot be seen.
    let mut t: String = text.lines().take(61).collect::<Vec<_>>().join("\n") + "\n";
    for row in 0..60 {
        t = with_cell(&t, row, "impact_y_mm", "0");
        t = with_cell(&t, row, "impact_z_mm", "0");
    }
    let centre = write(dir.path(), "centre.csv", &t);
    let o = smash(&[
        "diagnose",
        "--club",
        &club(),
        "--shots",
        &centre,
        "--max-steps",
        "1",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("not tried: cor_radial") && err.contains("impact_y_mm = 0"),
        "{err}"
    );
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(!common::has_non_finite(&out), "{out}");
}

#[test]
fn diagnose_says_when_one_golfer_makes_golfer_grouped_folds_impossible() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(shots(dir.path())).unwrap();
    let mut t: String = text.lines().take(61).collect::<Vec<_>>().join("\n") + "\n";
    for row in 0..60 {
        t = with_cell(&t, row, "golfer", "G07");
    }
    let one = write(dir.path(), "one.csv", &t);
    let o = smash(&[
        "diagnose",
        "--club",
        &club(),
        "--shots",
        &one,
        "--candidates",
        "loft_bias",
        "--max-steps",
        "1",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("one golfer ('G07')") && err.contains("by shot"),
        "{err}"
    );
}
