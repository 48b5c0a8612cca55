//! `smash whatif` against the hand-built answer: the designer's question "moving 5 g of
//! discretionary mass 10 mm back and 10 mm toward the heel, 95 mph golfer" answered by four
//! separate `[yards]` studies of heads computed here, independently, with the parallel-axis
//! theorem (through the inertia about the CoF, not the CoM-centred update the library uses).

use crate::cli_support;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use cli_support::{repo, s, smash, stderr};
use nalgebra::{Matrix3, Vector3};

const MASS_G: f64 = 5.0;
const FROM_MM: [f64; 3] = [-70.0, -10.0, 0.0];

/// The paper driver (configs/clubs/paper_driver.toml): mass g, CoM mm, inertia g·cm².
fn paper_head() -> (f64, Vector3<f64>, Matrix3<f64>) {
    let text = std::fs::read_to_string(repo("configs/clubs/paper_driver.toml")).unwrap();
    let club = text.split("[ball]").next().unwrap();
    let value = |key: &str| -> Vec<f64> {
        let line = club
            .lines()
            .find(|l| l.starts_with(key))
            .unwrap_or_else(|| panic!("{key}"));
        line.split('=')
            .nth(1)
            .unwrap()
            .split(['[', ']', ','])
            .filter_map(|x| x.trim().parse().ok())
            .collect()
    };
    let i = value("inertia_gcm2");
    (
        value("mass_g")[0],
        Vector3::from_column_slice(&value("com_mm")),
        Matrix3::from_row_slice(&i),
    )
}

/// Inertia of a point mass `m` at `r` about the origin: `m (|r|² 1 − r rᵀ)`.
fn point(m: f64, r: &Vector3<f64>) -> Matrix3<f64> {
    m * (Matrix3::identity() * r.norm_squared() - r * r.transpose())
}

/// The head with `MASS_G` moved from `FROM_MM` to `to`: inertia about the CoF origin, the
/// mass moved there, back to the new CoM (g, mm, g·mm² → g·cm² at the end).
fn moved_head(to: [f64; 3]) -> (Vector3<f64>, Matrix3<f64>) {
    let (m, c, i_gcm2) = paper_head();
    let i_com = i_gcm2 * 100.0; // g·cm² -> g·mm²
    let (a, b) = (Vector3::from(FROM_MM), Vector3::from(to));
    let i_origin = i_com + point(m, &c) - point(MASS_G, &a) + point(MASS_G, &b);
    let c_new = c + (b - a) * (MASS_G / m);
    let i_new = i_origin - point(m, &c_new);
    (c_new, i_new / 100.0)
}

fn club_file(dir: &Path, name: &str, com: Vector3<f64>, i: Matrix3<f64>) -> PathBuf {
    let text = std::fs::read_to_string(repo("configs/clubs/paper_driver.toml")).unwrap();
    let mut out = String::new();
    for line in text.lines() {
        if line.starts_with("com_mm") {
            out.push_str(&format!(
                "com_mm = [{:?}, {:?}, {:?}]\n",
                com.x, com.y, com.z
            ));
        } else if line.starts_with("inertia_gcm2") && !out.contains("[ball]") {
            let r = |k: usize| format!("[{:?}, {:?}, {:?}]", i[(k, 0)], i[(k, 1)], i[(k, 2)]);
            out.push_str(&format!("inertia_gcm2 = [{}, {}, {}]\n", r(0), r(1), r(2)));
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    let p = dir.join(name);
    std::fs::write(&p, out).unwrap();
    p
}

/// A study of one head: the golfer and mishit pattern `smash whatif` is given below.
fn study_of(dir: &Path, name: &str, club: &Path) -> HashMap<String, f64> {
    let text = format!(
        "[study]\nname = \"{name}\"\nclub = \"{}\"\noutputs = [\"ball_speed_mph\"]\n\
         [delivery]\nclub_speed_mph = 95.0\ndynamic_loft_deg = 13.0\nattack_angle_deg = 1.0\n\
         [distribution]\nmethod = \"quadrature\"\nnodes = 4\nsigma_y_mm = 4.0\nsigma_z_mm = 9.0\n\
         sigma_club_speed_mph = 1.5\nsigma_face_angle_deg = 1.0\n\
         [grid]\ny_mm = {{ from = 0.0, to = 0.0, count = 1 }}\nz_mm = {{ from = 0.0, to = 0.0, count = 1 }}\n\
         [yards]\nstatic_loft_deg = 10.5\n",
        club.to_string_lossy().replace('\\', "/")
    );
    let p = dir.join(format!("{name}_study.toml"));
    std::fs::write(&p, text).unwrap();
    let out = dir.join(format!("{name}_out"));
    let o = smash(&["run", s(&p), "--out", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    csv_rows(&out.join("yards/variants.csv")).remove(0)
}

fn csv_rows(p: &Path) -> Vec<HashMap<String, f64>> {
    let mut r = csv::Reader::from_path(p).unwrap();
    let head = r.headers().unwrap().clone();
    r.records()
        .map(|rec| {
            head.iter()
                .zip(rec.unwrap().iter())
                .filter_map(|(h, v)| Some((h.to_owned(), v.parse().ok()?)))
                .collect()
        })
        .collect()
}

/// `smash whatif` for a move to `to`: its base and changed rows, and its stdout.
fn whatif(
    dir: &Path,
    name: &str,
    to: [f64; 3],
    report: bool,
) -> (Vec<HashMap<String, f64>>, String) {
    let out = dir.join(format!("{name}.csv"));
    let mv = format!(
        "{MASS_G}g:{},{},{}:{},{},{}",
        FROM_MM[0], FROM_MM[1], FROM_MM[2], to[0], to[1], to[2]
    );
    let html = dir.join(format!("{name}.html"));
    let mut args = vec![
        "whatif",
        "--club",
        "",
        "--move-mass",
        &mv,
        "--speed",
        "95",
        "--loft",
        "13",
        "--attack",
        "1",
        "--speed-sd",
        "1.5",
        "--face-sd",
        "1",
        "--mishit-mm",
        "4,9",
        "--nodes",
        "4",
        "--out",
        s(&out),
    ];
    let club = repo("configs/clubs/paper_driver.toml");
    args[2] = s(&club);
    if report {
        args.extend(["--report", s(&html)]);
    }
    let o = smash(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    (csv_rows(&out), String::from_utf8(o.stdout).unwrap())
}

const KEYS: [&str; 8] = [
    "mean_carry_yd",
    "std_carry_yd",
    "ellipse_area_yd2",
    "mean_offline_yd",
    "std_offline_yd",
    "mean_ball_speed_mph",
    "mean_backspin_rpm",
    "mean_sidespin_rpm",
];

fn close(a: f64, b: f64, what: &str) {
    assert!(
        (a - b).abs() <= 1e-8 * b.abs().max(1.0),
        "{what}: whatif {a}, hand-built {b}"
    );
}

#[test]
fn whatif_answers_the_designers_question_as_four_studies_do() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (_, c0, i0) = paper_head();
    let base = study_of(d, "base", &club_file(d, "base.toml", c0, i0));
    let moves = [
        ("back", [-80.0, -10.0, 0.0]),
        ("heel", [-70.0, -10.0, -10.0]),
        ("back_heel", [-80.0, -10.0, -10.0]),
    ];
    for (name, to) in moves {
        let (com, i) = moved_head(to);
        let study = study_of(d, name, &club_file(d, &format!("{name}.toml"), com, i));
        let (rows, stdout) = whatif(d, &format!("w_{name}"), to, name == "back_heel");
        assert_eq!(rows.len(), 2);
        for k in KEYS {
            close(rows[0][k], base[k], &format!("{name} base {k}"));
            close(rows[1][k], study[k], &format!("{name} changed {k}"));
            close(
                rows[1][&format!("d_{k}")],
                study[k] - base[k],
                &format!("{name} d_{k}"),
            );
        }
        // The moved CoM printed is the hand-computed one.
        let printed = format!("-> ({:.2}, {:.2}, {:.2})", com.x, com.y, com.z);
        assert!(stdout.contains(&printed), "{printed} not in:\n{stdout}");
    }
    // Back and heel: the designer's answer, in yards, with its page.
    let (rows, stdout) = whatif(d, "w_back_heel", [-80.0, -10.0, -10.0], true);
    assert!(
        stdout.contains("mean carry (yd)") && stdout.contains("dispersion-ellipse area change")
    );
    assert!(rows[1]["d_mean_carry_yd_unc"] >= 0.0);
    let html = std::fs::read_to_string(d.join("w_back_heel.html")).unwrap();
    assert!(
        html.starts_with("<!DOCTYPE html>") && html.contains("mean carry") && !html.contains("NaN")
    );
}

#[test]
fn whatif_refuses_what_it_cannot_answer_in_one_line() {
    let club = repo("configs/clubs/paper_driver.toml");
    let cases: [(&[&str], &str); 4] = [
        (&["--speed", "95"], "no design change given"),
        (
            &["--speed", "95", "--move-mass", "5:-70,0,0:-80,0,0"],
            "ending in g",
        ),
        (
            &["--speed", "95", "--move-mass", "5g:-70,0:-80,0,0"],
            "expected 3 numbers",
        ),
        (
            &["--speed", "95", "--move-mass", "500g:-70,0,0:-80,0,0"],
            "below the head mass, 204 g",
        ),
    ];
    for (extra, want) in cases {
        let mut args = vec!["whatif", "--club", s(&club)];
        args.extend_from_slice(extra);
        let o = smash(&args);
        let e = stderr(&o);
        assert!(!o.status.success(), "{extra:?}");
        // One error line (clap adds its "try '--help'" hint to a bad flag value).
        let first = e.lines().next().unwrap_or_default();
        assert!(
            first.starts_with("error: ") && first.contains(want),
            "{extra:?}: {e}"
        );
        assert_eq!(
            e.lines().filter(|l| l.starts_with("error")).count(),
            1,
            "{e}"
        );
    }
}
