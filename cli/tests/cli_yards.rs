//! `smash run` on a study with a `[yards]` table: the yard maps, robust metrics, constraint
//! report and the optimisation, and refusals of a bad `[yards]` table.

mod cli_support;

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
