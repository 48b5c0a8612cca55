//! `smash flight` and `smash predict --flight` on real files: outputs, err_ columns, the
//! atmosphere table, and one clear line (naming file, line and column or key) with a non-zero
//! exit and no output file for every kind of bad input.

mod cli_support;

use std::path::{Path, PathBuf};

use cli_support::smash;

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn table(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::Reader::from_path(path).unwrap();
    let h = r.headers().unwrap().iter().map(str::to_string).collect();
    let rows = r
        .records()
        .map(|x| x.unwrap().iter().map(str::to_string).collect())
        .collect();
    (h, rows)
}

fn col(h: &[String], name: &str) -> usize {
    h.iter()
        .position(|x| x == name)
        .unwrap_or_else(|| panic!("no column {name} in {h:?}"))
}

const LAUNCH: &str =
    "shot_id,ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,sidespin_rpm,carry_yd\n\
d1,167,10.9,0,2686,0,275\n\
d2,120,16.3,1.5,7097,-500,172\n";

#[test]
fn flies_a_launch_file_with_errors_against_measured_carry() {
    let dir = tempfile::tempdir().unwrap();
    let shots = write(dir.path(), "launch.csv", LAUNCH);
    let out = dir.path().join("f.csv");
    let o = smash(&[
        "flight",
        "--shots",
        shots.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--total",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (h, rows) = table(&out);
    for name in [
        "pred_carry_yd",
        "pred_offline_yd",
        "pred_apex_yd",
        "pred_flight_time_s",
        "pred_land_angle_deg",
        "pred_total_yd",
        "err_carry_yd",
    ] {
        col(&h, name);
    }
    assert!(
        !h.iter().any(|x| x == "err_apex_yd"),
        "no measured apex, no err_apex_yd"
    );
    let carry: f64 = rows[0][col(&h, "pred_carry_yd")].parse().unwrap();
    let err: f64 = rows[0][col(&h, "err_carry_yd")].parse().unwrap();
    assert!((err - (carry - 275.0)).abs() < 1e-6);
    let total: f64 = rows[0][col(&h, "pred_total_yd")].parse().unwrap();
    assert!(total > carry);
    // Draw spin on the 7-iron curves it left of its 1.5° push line.
    let off: f64 = rows[1][col(&h, "pred_offline_yd")].parse().unwrap();
    let carry2: f64 = rows[1][col(&h, "pred_carry_yd")].parse().unwrap();
    assert!(off < carry2 * 1.5f64.to_radians().tan());

    // Thinner air at altitude carries further; the [atmosphere] table and flags agree.
    let atm = write(
        dir.path(),
        "atm.toml",
        "[atmosphere]\ntemperature_c = 25\nelevation_m = 1600\nhumidity_pct = 30\n",
    );
    let out2 = dir.path().join("f2.csv");
    let o = smash(&[
        "flight",
        "--shots",
        shots.to_str().unwrap(),
        "--out",
        out2.to_str().unwrap(),
        "--atmosphere",
        atm.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out3 = dir.path().join("f3.csv");
    let o = smash(&[
        "flight",
        "--shots",
        shots.to_str().unwrap(),
        "--out",
        out3.to_str().unwrap(),
        "--temperature-c",
        "25",
        "--elevation-m",
        "1600",
        "--humidity-pct",
        "30",
    ]);
    assert!(o.status.success());
    let (h2, r2) = table(&out2);
    let (_, r3) = table(&out3);
    let hi: f64 = r2[0][col(&h2, "pred_carry_yd")].parse().unwrap();
    assert!(hi > carry + 5.0, "{hi} vs {carry}");
    assert_eq!(r2, r3);
}

#[test]
fn predict_with_flight_adds_the_flight_columns() {
    let dir = tempfile::tempdir().unwrap();
    let shots = write(
        dir.path(),
        "shots.csv",
        "shot_id,club_speed_mph,attack_angle_deg,club_path_deg,dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm,carry_yd\n\
         s1,110,2,0,13,0,0,0,280\n",
    );
    let club = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .join("configs/clubs/paper_driver.toml");
    let out = dir.path().join("p.csv");
    let o = smash(&[
        "predict",
        "--club",
        club.to_str().unwrap(),
        "--shots",
        shots.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--flight",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (h, rows) = table(&out);
    let carry: f64 = rows[0][col(&h, "pred_carry_yd")].parse().unwrap();
    assert!(carry > 200.0 && carry < 320.0, "{carry}");
    col(&h, "pred_ball_speed_mph");
    col(&h, "err_carry_yd");
}

const LAUNCH_ROW0: &str = "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,0,10,2500\n";
const OK_ROW: &str = "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,10,2500\n";

#[test]
fn bad_atmosphere_files_name_file_and_key() {
    let dir = tempfile::tempdir().unwrap();
    let shots = write(dir.path(), "ok.csv", OK_ROW);
    for (k, (text, expect)) in [
        (
            "[atmosphere]\ntemperature_c = 90\n",
            "atmosphere.temperature_c",
        ),
        ("[atmosphere]\nfoo = 1\n", "unknown field `foo`"),
        ("[atmosphere]\nhumidity_pct = \"wet\"\n", "invalid type"),
        ("[air]\ntemperature_c = 20\n", "no [atmosphere] table"),
    ]
    .into_iter()
    .enumerate()
    {
        let atm = write(dir.path(), &format!("atm{k}.toml"), text);
        let out = dir.path().join(format!("out{k}.csv"));
        let o = smash(&[
            "flight",
            "--shots",
            shots.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--atmosphere",
            atm.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "case {k} should fail");
        assert!(err.contains(expect), "case {k}: {err}");
        assert!(err.contains(&format!("atm{k}.toml")), "case {k}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "case {k}: {err}");
        assert!(!out.exists(), "case {k}: no output file");
    }
}

#[test]
fn bad_input_is_one_clear_line_and_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let cases: Vec<(&str, Vec<&str>, &str)> = vec![
        (
            "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,-5,10,2500\n",
            vec![],
            "column 'ball_speed_mph'",
        ),
        (
            "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,10,2500\nd2,150,95,2500\n",
            vec![],
            ":3: column 'launch_angle_deg'",
        ),
        (
            "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,10,90000\n",
            vec![],
            "column 'backspin_rpm'",
        ),
        (
            "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,10,abc\n",
            vec![],
            "'abc' is not a finite number",
        ),
        (
            "shot_id,ball_speed_mph,launch_angle_deg\nd1,150,10\n",
            vec![],
            "missing column 'backspin_rpm'",
        ),
        (
            "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,89,2500\n",
            vec!["--max-time-s", "3"],
            "has not landed",
        ),
        (
            "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,10,2500\n",
            vec!["--humidity-pct", "140"],
            "--humidity-pct",
        ),
        (
            "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,10,2500\n",
            vec!["--aero", "magic"],
            "unknown aerodynamic model 'magic'",
        ),
        (LAUNCH_ROW0, vec![], "ball_speed_mph = 0: must be > 0"),
        (
            "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,300,10,2500\n",
            vec![],
            "ball_speed_mph = 300",
        ),
        (
            "shot_id,ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm\nd1,150,10,120,2500\n",
            vec![],
            "azimuth_deg = 120: must be within [-90, 90]",
        ),
        (
            "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm,sidespin_rpm\nd1,150,10,2500,-30000\n",
            vec![],
            "column 'sidespin_rpm'",
        ),
        (
            "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,nan,10,2500\n",
            vec![],
            "'nan' is not a finite number",
        ),
        (OK_ROW, vec!["--temperature-c", "80"], "--temperature-c"),
        (OK_ROW, vec!["--elevation-m", "9000"], "--elevation-m"),
        (
            OK_ROW,
            vec!["--pressure-hpa", "1000", "--elevation-m", "100"],
            "not both",
        ),
        (OK_ROW, vec!["--wind-speed-m-s", "50"], "--wind-speed-m-s"),
        (OK_ROW, vec!["--roughness-m", "-1"], "--roughness-m"),
        (OK_ROW, vec!["--max-time-s", "-1"], "--max-time-s"),
        (OK_ROW, vec!["--dt-s", "0"], "--dt-s"),
        (OK_ROW, vec!["--spin-decay", "foo"], "--spin-decay 'foo'"),
        (
            OK_ROW,
            vec!["--total", "--ground-restitution", "3"],
            "ground restitution",
        ),
    ];
    for (k, (text, extra, expect)) in cases.into_iter().enumerate() {
        let shots = write(dir.path(), &format!("bad{k}.csv"), text);
        let out = dir.path().join(format!("out{k}.csv"));
        let mut args = vec![
            "flight",
            "--shots",
            shots.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend(extra);
        let o = smash(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "case {k} should fail");
        assert!(err.contains(expect), "case {k}: {err}");
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "case {k}: one line: {err}"
        );
        assert!(!out.exists(), "case {k}: no output file");
        assert!(!err.contains("NaN") && !err.contains("panicked"));
    }
}
