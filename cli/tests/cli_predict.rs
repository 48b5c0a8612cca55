//! `smash predict` on real files: the one-shot table, and a clear one-line error with a non-zero
//! exit and no output file for every kind of bad input.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::smash;

fn paper_club_text() -> String {
    std::fs::read_to_string(
        Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
            .join("configs/clubs/paper_driver.toml"),
    )
    .unwrap()
}

const SHOTS_HEADER: &str = "shot_id,group,club_speed_mph,attack_angle_deg,club_path_deg,dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm";

struct Case {
    dir: tempfile::TempDir,
}

impl Case {
    fn new() -> Self {
        Self {
            dir: tempfile::tempdir().unwrap(),
        }
    }
    fn file(&self, name: &str, text: &str) -> PathBuf {
        let p = self.dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p
    }
    fn out(&self) -> PathBuf {
        self.dir.path().join("pred.csv")
    }
    /// Run predict `--strict` on a club text and shots text; return stderr of a failed run,
    /// checking that it failed, said one line, and wrote nothing. (Without `--strict` a bad row
    /// among good ones is left out and counted: `bad_rows.rs`.)
    fn fails(&self, club: &str, shots: &str) -> String {
        self.fails_with(club, shots, &["--strict"])
    }

    /// [`Self::fails`] with `extra` flags in place of `--strict`.
    fn fails_with(&self, club: &str, shots: &str, extra: &[&str]) -> String {
        let c = self.file("club.toml", club);
        let s = self.file("shots.csv", shots);
        let out = self.out();
        let mut args = vec![
            "predict",
            "--club",
            c.to_str().unwrap(),
            "--shots",
            s.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let o = smash(&args);
        let err = String::from_utf8_lossy(&o.stderr).to_string();
        assert!(
            !o.status.success(),
            "expected failure, got success; stderr: {err}"
        );
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "error must be one line: {err}"
        );
        assert!(err.starts_with("error: "), "{err}");
        assert!(!self.out().exists(), "no output file may be left behind");
        let leftovers: Vec<_> = std::fs::read_dir(self.dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".tmp"))
            .collect();
        assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
        err
    }
}

fn good_shots() -> String {
    format!("{SHOTS_HEADER}\ns1,A,100,0,0,12,0,0,0\ns2,B,105,-1,2,11,1,3,-5\n")
}

fn assert_has(err: &str, parts: &[&str]) {
    for p in parts {
        assert!(err.contains(p), "error should mention {p:?}: {err}");
    }
}

#[test]
fn one_shot_form_prints_the_launch_table() {
    let case = Case::new();
    let c = case.file("club.toml", &paper_club_text());
    let o = smash(&[
        "predict",
        "--club",
        c.to_str().unwrap(),
        "--speed",
        "100",
        "--loft",
        "12",
        "--impact-z",
        "-5",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8(o.stdout).unwrap();
    for label in [
        "Ball speed",
        "Launch angle",
        "Azimuth",
        "Backspin",
        "Sidespin",
        "Smash factor",
        "mph",
        "rpm",
    ] {
        assert!(out.contains(label), "missing {label}: {out}");
    }
}

#[test]
fn good_files_write_predictions_with_errors_when_measured() {
    let case = Case::new();
    let c = case.file("club.toml", &paper_club_text());
    let shots = format!(
        "{SHOTS_HEADER},ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,sidespin_rpm,note\n\
         s1,A,100,0,0,12,0,0,0,146,9.7,0,2900,70,keep me\n"
    );
    let s = case.file("shots.csv", &shots);
    let o = smash(&[
        "predict",
        "--club",
        c.to_str().unwrap(),
        "--shots",
        s.to_str().unwrap(),
        "--out",
        case.out().to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(case.out()).unwrap();
    let header = text.lines().next().unwrap();
    assert!(
        header.contains("note")
            && header.contains("pred_backspin_rpm")
            && header.contains("err_ball_speed_mph")
    );
    assert!(text.contains("keep me"));
    assert!(!text.to_lowercase().contains("nan"));
}

#[test]
fn bad_club_files_name_the_key_and_line() {
    let case = Case::new();
    let club = paper_club_text();
    let shots = good_shots();
    let cases: Vec<(String, Vec<&str>)> = vec![
        (club.replace("cor = 0.83", "cor = 0.83\ncolour = \"red\""), vec!["unknown field `colour`", "club.toml:12: column 1"]),
        (club.replace("roll_mm = 305.0\n", ""), vec!["missing field `roll_mm`"]),
        (club.replace("mass_g = 204.0", "mass_g = -204.0"), vec!["club.mass_g", "physical range [1, 10000] g", ":"]),
        (club.replace("mass_g = 204.0", "mass_g = \"heavy\""), vec!["mass_g", "invalid type"]),
        (club.replace("cor = 0.83", "cor = 1.3"), vec!["club.cor", "(0, 1]"]),
        (club.replace("[-733.0, 5679.0, 0.5]", "[-700.0, 5679.0, 0.5]"), vec!["club.inertia_gcm2", "symmetric"]),
        (
            club.replace("[[2843.0, -733.0, 530.2], [-733.0, 5679.0, 0.5], [530.2, 0.5, 4085.0]]", "[[1000.0, 0.0, 0.0], [0.0, 1000.0, 0.0], [0.0, 0.0, 4000.0]]"),
            vec!["club.inertia_gcm2", "triangle inequality"],
        ),
        (
            club.replace("[[2843.0, -733.0, 530.2], [-733.0, 5679.0, 0.5], [530.2, 0.5, 4085.0]]", "[[2843.0, 5000.0, 0.0], [5000.0, 5679.0, 0.0], [0.0, 0.0, 4085.0]]"),
            vec!["club.inertia_gcm2", "positive definite"],
        ),
        (club.replace("radius_mm = 21.3", "radius_mm = 0"), vec!["ball.radius_mm", "physical range [1, 200] mm"]),
        (format!("{club}\n[[effect]]\nname = \"shaft_flex\"\n"), vec!["unknown effect 'shaft_flex'", "added_mass", "inertia_scale"]),
        (format!("{club}\n[[effect]]\nname = \"added_mass\"\ndm = 2\n"), vec!["unknown key `dm`", "dm_g"]),
        (format!("{club}\n[[effect]]\nname = \"ball_offset\"\ndy_mm = 0.5\n"), vec!["missing `dz_mm`"]),
        (format!("{club}\n[[effect]]\nname = \"friction\"\nmu = -1\n"), vec!["friction.mu", "physical range"]),
        (
            format!("{club}\n[[effect]]\nname = \"ball_offset\"\ndy_mm = 10\ndz_mm = 10\n[[effect]]\nname = \"ball_offset\"\ndy_mm = 10\ndz_mm = 10\ngroup = \"A\"\n"),
            vec!["not physical", "ball offset", "ball radius"],
        ),
    ];
    for (text, parts) in cases {
        let err = case.fails(&text, &shots);
        assert_has(&err, &parts);
        assert_has(&err, &["club.toml"]);
    }
}

#[test]
fn bad_shots_files_name_the_row_and_column() {
    let case = Case::new();
    let club = paper_club_text();
    let cases: Vec<(String, Vec<&str>)> = vec![
        ("".to_string(), vec!["header"]),
        (
            "shot_id,club_speed_mph\ns1,100\n".to_string(),
            vec!["missing required column", "attack_angle_deg", "impact_z_mm"],
        ),
        (format!("{SHOTS_HEADER}\n"), vec!["no shots"]),
        (
            format!("{SHOTS_HEADER}\ns1,A,fast,0,0,12,0,0,0\n"),
            vec![":2", "column 'club_speed_mph'", "'fast' is not a number"],
        ),
        (
            format!("{SHOTS_HEADER}\ns1,A,100,0,0,12,0,0,0\ns2,A,100,0,0,NaN,0,0,0\n"),
            vec![":3", "dynamic_loft_deg", "not finite"],
        ),
        (
            format!("{SHOTS_HEADER}\ns1,A,100,0,0,12,0,0,0\ns1,A,100,0,0,12,0,0,0\n"),
            vec![":3", "used twice"],
        ),
        (
            format!("{SHOTS_HEADER}\ns1,A,100,0,0,12,0\n"),
            vec![":2", "found a row with 7 field(s), but the header has 9"],
        ),
        (
            format!("{SHOTS_HEADER}\ns1,A,-100,0,0,12,0,0,0\n"),
            vec![
                ":2",
                "club_speed_mph",
                "-100",
                "physical range [1, 250] mph",
            ],
        ),
        (
            format!("{SHOTS_HEADER},ball_speed_mph\ns1,A,100,0,0,12,0,0,0,150\n"),
            vec!["all present or all absent", "backspin_rpm"],
        ),
    ];
    for (text, parts) in cases {
        let err = case.fails(&club, &text);
        assert_has(&err, &parts);
        assert_has(&err, &["shots.csv"]);
    }
    // A row without its impact location is left out (and counted); with nothing left the file
    // is refused, pointing at --strict, which names the cell.
    let text = format!("{SHOTS_HEADER}\ns1,A,100,0,0,12,0,,0\n");
    let err = case.fails_with(&club, &text, &[]);
    assert_has(
        &err,
        &[
            "shots.csv",
            "no shots",
            "line 2: no impact location",
            "--strict",
        ],
    );
    let err = case.fails(&club, &text);
    assert_has(&err, &["shots.csv:2: column 'impact_y_mm': empty cell"]);
}

#[test]
fn an_off_face_impact_and_a_receding_club_name_the_shot() {
    let case = Case::new();
    // A small face (40 mm radii): an impact 60 mm toward the toe, inside the physical range of
    // impact locations, is off it.
    let club = paper_club_text()
        .replace("bulge_mm = 305.0", "bulge_mm = 40.0")
        .replace("roll_mm = 305.0", "roll_mm = 40.0");
    let off = format!("{SHOTS_HEADER}\ns1,A,100,0,0,12,0,0,0\nfar_toe,A,100,0,0,12,0,0,60\n");
    let err = case.fails(&club, &off);
    assert_has(
        &err,
        &[
            ":3: columns impact_y_mm, impact_z_mm",
            "far_toe",
            "outside the face",
        ],
    );
    // Path 60° right, face 60° closed: the face normal points 120° away from the club's motion.
    let away = format!("{SHOTS_HEADER}\nbackwards,A,100,0,60,12,-60,0,0\n");
    let err = case.fails(&club, &away);
    assert_has(&err, &["backwards", "does not approach"]);
}

#[test]
fn missing_files_and_incomplete_command_lines_fail_clearly() {
    let o = smash(&[
        "predict",
        "--club",
        "/nonexistent/club.toml",
        "--speed",
        "100",
        "--loft",
        "12",
    ]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("/nonexistent/club.toml"));
    let case = Case::new();
    let c = case.file("club.toml", &paper_club_text());
    let o = smash(&["predict", "--club", c.to_str().unwrap(), "--speed", "100"]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--loft"));
}

#[test]
fn crlf_shots_files_report_the_right_line() {
    let case = Case::new();
    let shots = format!("{SHOTS_HEADER}\r\ns1,A,100,0,0,12,0,0,0\r\ns2,A,100,0,0,12,0,0,x\r\n");
    let err = case.fails(&paper_club_text(), &shots);
    assert_has(
        &err,
        &["shots.csv:3", "column 'impact_z_mm'", "'x' is not a number"],
    );
    // Two short rows of three: more than half, so the file is refused naming the first (one
    // would be left out and counted).
    let short = format!("{SHOTS_HEADER}\r\ns1,A,100,0,0,12,0,0,0\r\ns2,A,100\r\ns3,A,100\r\n");
    let err = case.fails(&paper_club_text(), &short);
    assert_has(
        &err,
        &["shots.csv:3: found a row with 3 field(s), but the header has 9 (one per column)"],
    );
}

#[test]
fn unphysically_small_masses_are_rejected_not_turned_into_nan() {
    let case = Case::new();
    let club = paper_club_text().replace("mass_g = 204.0", "mass_g = 1e-300");
    let err = case.fails(&club, &good_shots());
    assert_has(&err, &["club.mass_g", "physical range"]);
}
