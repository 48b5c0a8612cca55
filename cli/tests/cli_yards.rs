//! `smash run` on a study with a `[yards]` table: the yard maps, robust metrics, constraint
//! report and the optimisation, and refusals of a bad `[yards]` table.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::smash;

fn club() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../configs/clubs/paper_driver.toml")
        .to_string_lossy()
        .replace('\\', "/")
}

fn study(dir: &Path, yards: &str, distribution: bool) -> PathBuf {
    let dist = if distribution {
        "[distribution]\nmethod = \"quadrature\"\nnodes = 2\nsigma_y_mm = 3.0\nsigma_z_mm = 6.0\nsigma_club_speed_mph = 2.0\n"
    } else {
        ""
    };
    let text = format!(
        "[study]\nname = \"y\"\nclub = \"{}\"\noutputs = [\"ball_speed_mph\"]\n\n\
         [delivery]\nclub_speed_mph = 100.0\ndynamic_loft_deg = 13.0\n\n{dist}\n\
         [grid]\ny_mm = {{ from = -10.0, to = 10.0, count = 3 }}\nz_mm = {{ from = -20.0, to = 20.0, count = 5 }}\n\n{yards}",
        club()
    );
    let p = dir.join("study.toml");
    std::fs::write(&p, text).unwrap();
    p
}

const YARDS: &str = "[yards]\nstatic_loft_deg = 10.5\nconfidence = 0.9\n\
[yards.mass]\nmass_g = 10.0\nat_mm = [-70.0, -10.0, 0.0]\nbounds_mm = [[-20.0, 30.0], [-5.0, 10.0], [-30.0, 30.0]]\n\
[yards.optimise]\ngoal = \"max_mean_carry\"\nmax_iters = 15\n\
[yards.constraints]\nmass_g = [200.0, 210.0]\nmoi_vertical_max_gcm2 = 6000.0\n";

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn rows(p: &Path) -> Vec<Vec<String>> {
    read(p)
        .lines()
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

#[test]
fn run_writes_yard_maps_metrics_constraints_and_optimum() {
    let dir = tempfile::tempdir().unwrap();
    let s = study(dir.path(), YARDS, true);
    let out = dir.path().join("out");
    let o = smash(&["run", s.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let y = out.join("yards");
    for stem in [
        "carry_yd",
        "offline_yd",
        "mean_carry_yd",
        "std_carry_yd",
        "ellipse_area_yd2",
    ] {
        let csv = read(&y.join(format!("{stem}.csv")));
        assert_eq!(csv.lines().count(), 4, "{stem}: header + 3 rows");
        assert!(!csv.contains("NaN") && !csv.contains("inf"), "{stem}");
        let svg = read(&y.join(format!("{stem}.svg")));
        assert!(svg.starts_with("<svg") && !svg.contains("NaN"), "{stem}");
    }
    // Carry at the centre of the face is a driver's (100 mph club speed: 200–260 yd).
    let carry = rows(&y.join("carry_yd.csv"));
    let centre: f64 = carry[2][3].parse().unwrap();
    assert!((200.0..260.0).contains(&centre), "{centre}");
    // Metrics: base and optimum; the optimum is at least as good (the base is in the simplex).
    let m = rows(&y.join("metrics.csv"));
    assert_eq!(m[1][0], "base");
    assert_eq!(m[2][0], "optimum");
    let (base, best): (f64, f64) = (m[1][4].parse().unwrap(), m[2][4].parse().unwrap());
    assert!(best >= base, "optimum {best} below base {base}");
    assert_eq!(m[1][9], "0.9");
    // Constraints: every one holds at the base and at the optimum, and the MOI row is there
    // with the stated limit.
    let c = rows(&y.join("constraints.csv"));
    let moi = c.iter().find(|r| r[0].starts_with("MOI")).expect("MOI row");
    assert_eq!(moi[1], "6000");
    for r in &c[1..] {
        assert_eq!(r[4], "true", "{r:?}");
        assert_eq!(r[7], "true", "{r:?}");
    }
    let opt = read(&y.join("optimise.csv"));
    assert!(opt.contains("status,done"), "{opt}");
    // The resolved study.toml keeps the [yards] table and repeats the run.
    let resolved = out.join("study.toml");
    assert!(read(&resolved).contains("[yards.constraints]"));
    let out2 = dir.path().join("out2");
    let o = smash(&[
        "run",
        resolved.to_str().unwrap(),
        "--out",
        out2.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        read(&y.join("metrics.csv")),
        read(&out2.join("yards/metrics.csv"))
    );
}

#[test]
fn a_base_design_breaking_a_constraint_is_reported_not_optimised() {
    let dir = tempfile::tempdir().unwrap();
    let s = study(
        dir.path(),
        &YARDS.replace(
            "moi_vertical_max_gcm2 = 6000.0",
            "moi_vertical_max_gcm2 = 4000.0",
        ),
        true,
    );
    let out = dir.path().join("out");
    let o = smash(&["run", s.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("breaks MOI"), "{err}");
    let c = rows(&out.join("yards/constraints.csv"));
    let moi = c.iter().find(|r| r[0].starts_with("MOI")).unwrap();
    assert_eq!(moi[4], "false");
    assert!(moi[3].starts_with('-'), "negative margin: {moi:?}");
    assert!(read(&out.join("yards/optimise.csv")).contains("not run"));
    assert!(!read(&out.join("yards/metrics.csv")).contains("optimum"));
}

#[test]
fn bad_yards_tables_are_one_clear_line() {
    let dir = tempfile::tempdir().unwrap();
    let cases: Vec<(String, bool, &str)> = vec![
        (YARDS.to_string(), false, "needs the study's [distribution]"),
        (
            YARDS.replace("confidence = 0.9", "confidence = 1.5"),
            true,
            "yards.confidence",
        ),
        (
            YARDS.replace("max_mean_carry", "max_fun"),
            true,
            "unknown goal 'max_fun'",
        ),
        (
            YARDS.replace("static_loft_deg = 10.5", "static_loft_deg = 10.5\nloft = 3"),
            true,
            "unknown field `loft`",
        ),
        (
            YARDS.replace("[[-20.0, 30.0]", "[[5.0, 30.0]"),
            true,
            "yards.mass.bounds_mm",
        ),
        (
            YARDS.replace(
                "[yards.mass]",
                "[yards.atmosphere]\ntemperature_c = 99\n[yards.mass]",
            ),
            true,
            "yards.atmosphere",
        ),
        (
            YARDS.replace(
                "static_loft_deg = 10.5",
                "static_loft_deg = 10.5\nmodel = \"magic\"",
            ),
            true,
            "unknown aerodynamic model 'magic'",
        ),
    ];
    for (k, (yards, dist, expect)) in cases.into_iter().enumerate() {
        let sub = dir.path().join(format!("c{k}"));
        std::fs::create_dir_all(&sub).unwrap();
        let s = study(&sub, &yards, dist);
        let out = sub.join("out");
        let o = smash(&["run", s.to_str().unwrap(), "--out", out.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "case {k} should fail");
        assert!(err.contains(expect), "case {k}: {err}");
        assert!(
            err.contains("study.toml"),
            "case {k}: names the file: {err}"
        );
        assert_eq!(err.trim_end().lines().count(), 1, "case {k}: {err}");
        assert!(!out.exists(), "case {k}: no output");
    }
}

/// The paper driver's club file with its CoM (mm) replaced.
fn club_with_com(dir: &Path, name: &str, com_mm: [f64; 3]) -> PathBuf {
    let text = read(Path::new(&club()));
    let line = text
        .lines()
        .find(|l| l.starts_with("com_mm"))
        .expect("the club file has com_mm");
    let moved = text.replace(
        line,
        &format!(
            "com_mm = [{:?}, {:?}, {:?}]",
            com_mm[0], com_mm[1], com_mm[2]
        ),
    );
    let p = dir.join(name);
    std::fs::write(&p, moved).unwrap();
    p
}

/// A [yards] study of one swing and distribution with `club` and `extra` sections.
fn single_study(dir: &Path, name: &str, club: &Path, extra: &str) -> PathBuf {
    let text = format!(
        "[study]\nname = \"{name}\"\nclub = \"{}\"\noutputs = [\"ball_speed_mph\"]\n\n\
         [delivery]\nclub_speed_mph = 100.0\ndynamic_loft_deg = 13.0\n\n\
         [distribution]\nmethod = \"quadrature\"\nnodes = 3\nsigma_y_mm = 3.0\nsigma_z_mm = 8.0\nsigma_face_angle_deg = 1.0\n\n\
         [grid]\ny_mm = {{ from = 0.0, to = 0.0, count = 1 }}\nz_mm = {{ from = 0.0, to = 0.0, count = 1 }}\n\n\
         [yards]\nstatic_loft_deg = 10.5\n{extra}",
        club.to_string_lossy().replace('\\', "/")
    );
    let p = dir.join(format!("{name}.toml"));
    std::fs::write(&p, text).unwrap();
    p
}

/// `yards/variants.csv` as rows of named cells.
fn variant_rows(out: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let mut r = csv::Reader::from_path(out.join("yards/variants.csv")).unwrap();
    let head = r.headers().unwrap().clone();
    r.records()
        .map(|rec| {
            let rec = rec.unwrap();
            head.iter()
                .zip(rec.iter())
                .map(|(h, v)| (h.to_owned(), v.to_owned()))
                .collect()
        })
        .collect()
}

fn num(row: &std::collections::HashMap<String, String>, key: &str) -> f64 {
    row[key]
        .parse()
        .unwrap_or_else(|_| panic!("{key} = '{}'", row[key]))
}

#[test]
fn design_variants_are_judged_in_yards_as_separate_heads_are() {
    // Three variants moving the CoM 4 mm toward the heel, not at all and toward the toe: each
    // row of yards/variants.csv must be what a study of that head alone computes.
    let dir = tempfile::tempdir().unwrap();
    let base_com = [-42.3, 2.9, 1.0];
    let s = single_study(
        dir.path(),
        "sweep",
        Path::new(&club()),
        "\n[design]\ncom_dz_mm = [-4.0, 0.0, 4.0]\n",
    );
    let out = dir.path().join("out");
    let o = smash(&["run", s.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("yards per design against the base"), "{err}");
    let rows = variant_rows(&out);
    let labels: Vec<&str> = rows.iter().map(|r| r["label"].as_str()).collect();
    assert_eq!(labels, ["base", "variant 0", "variant 1", "variant 2"]);
    // Keyed as the study's variants.csv is: a variant's row joins its row there on
    // `variant_id`; the base (no variant) has none.
    let ids: Vec<&str> = rows.iter().map(|r| r["variant_id"].as_str()).collect();
    assert_eq!(ids, ["", "0", "1", "2"]);
    let study_ids: Vec<String> = csv::Reader::from_path(out.join("variants.csv"))
        .unwrap()
        .records()
        .map(|r| r.unwrap()[0].to_owned())
        .collect();
    assert_eq!(study_ids, ["0", "1", "2"]);
    assert_eq!(rows[1]["design"], "com_dz_mm = -4");
    let keys = [
        "mean_carry_yd",
        "std_carry_yd",
        "ellipse_area_yd2",
        "mean_offline_yd",
        "std_offline_yd",
        "mean_ball_speed_mph",
        "mean_backspin_rpm",
        "mean_sidespin_rpm",
    ];
    for (i, dz) in [-4.0, 0.0, 4.0].into_iter().enumerate() {
        let row = &rows[i + 1];
        let com = [base_com[0], base_com[1], base_com[2] + dz];
        let c = club_with_com(dir.path(), &format!("club{i}.toml"), com);
        let single = single_study(dir.path(), &format!("single{i}"), &c, "");
        let single_out = dir.path().join(format!("single{i}_out"));
        let o = smash(&[
            "run",
            single.to_str().unwrap(),
            "--out",
            single_out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let alone = &variant_rows(&single_out)[0];
        // The single-head study's own metrics file agrees with its table.
        let m = rows_of_metrics(&single_out);
        assert_eq!(m[1][4], alone["mean_carry_yd"]);
        for k in keys {
            let (a, b) = (num(row, k), num(alone, k));
            assert!(
                (a - b).abs() <= 1e-9 * b.abs().max(1.0),
                "variant {i} {k}: {a} in the sweep, {b} alone"
            );
            let d = num(row, &format!("d_{k}"));
            assert!(
                (d - (a - num(&rows[0], k))).abs() <= 1e-9 * a.abs().max(1.0),
                "variant {i} d_{k}"
            );
        }
        // A quadrature has its error estimate; a moved CoM changes carry and offline.
        assert!(!row["d_mean_carry_yd_unc"].is_empty());
        if dz != 0.0 {
            assert!(num(row, "d_mean_carry_yd").abs() > 1e-3, "{row:?}");
            assert!(num(row, "d_mean_offline_yd").abs() > 0.1, "{row:?}");
        } else {
            assert_eq!(num(row, "d_mean_carry_yd"), 0.0);
        }
    }
    // Toe-ward and heel-ward CoM moves send the ball to opposite sides.
    assert!(num(&rows[1], "d_mean_offline_yd") * num(&rows[3], "d_mean_offline_yd") < 0.0);
}

fn rows_of_metrics(out: &Path) -> Vec<Vec<String>> {
    rows(&out.join("yards/metrics.csv"))
}
