//! `smash flight` and `smash predict --flight` on real files: outputs, err_ columns, the
//! atmosphere table, and one clear line (naming file, line and column or key) with a non-zero
//! exit and no output file for every kind of bad input.

use crate::cli_support;

use std::path::Path;

use cli_support::{club, s, smash, write};

/// The command failed cleanly: exit 1 (not a panic's 101), one line on stderr starting
/// `error: ` and holding every needle. (A message may quote the user's `NaN` cell.)
fn assert_refused(o: &std::process::Output, needles: &[&str]) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "exit {:?}: {err}", o.status);
    assert_eq!(err.trim_end().lines().count(), 1, "not one line: {err:?}");
    assert!(
        err.starts_with("error: ") && !err.contains("panicked"),
        "{err}"
    );
    for n in needles {
        assert!(err.contains(n), "missing {n:?} in: {err}");
    }
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
    let club = club();
    let out = dir.path().join("p.csv");
    let o = smash(&[
        "predict",
        "--club",
        &club,
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
        (LAUNCH_ROW0, vec![], "ball_speed_mph = 0: must be at least 1 mph"),
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
        // --strict: a bad row refuses the file (without it the row is left out:
        // `bad_rows.rs`); a file of one bad row is refused either way.
        let mut args = vec![
            "flight",
            "--shots",
            shots.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--strict",
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

/// `smash flight --strict` on `text` (written to `dir/name`) with `extra` flags must be refused
/// with one line holding every needle, and write nothing; the message is returned. (Without
/// `--strict` a bad row among good ones is left out and counted: `bad_rows.rs`.)
fn refused(dir: &Path, name: &str, text: &str, extra: &[&str], needles: &[&str]) -> String {
    let shots = write(dir, name, text);
    let out = dir.join(format!("{name}.out.csv"));
    let mut args = vec!["flight", "--shots", s(&shots), "--out", s(&out), "--strict"];
    args.extend(extra);
    let o = smash(&args);
    assert_refused(&o, needles);
    assert!(!out.exists(), "{name}: no output file");
    String::from_utf8_lossy(&o.stderr).into_owned()
}

const MEASURED_HEAD: &str =
    "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm,carry_yd,apex_yd,flight_time_s,land_angle_deg,total_yd\n";

/// Measured flight columns are read for the `err_` columns, so they are checked like the launch
/// columns: a cell that is not a finite number or not a golf shot is one line naming the file,
/// line and column, on the streamed path (plain files), the one-piece path (quoted cells) and
/// `smash predict --flight`. An empty cell is "not measured".
#[test]
fn measured_flight_columns_are_checked() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let ok = "d1,167,10.9,2686,275,32,7,38,\n";
    for (k, (row, needles)) in [
        ("d2,150,12,2600,abc,,,,", vec![":3: column 'carry_yd': 'abc' is not a finite number", "[-600, 600] yd"]),
        ("d2,150,12,2600,NaN,,,,", vec![":3: column 'carry_yd': 'NaN' is not a finite number"]),
        ("d2,150,12,2600,1e308,,,,", vec![":3: column 'carry_yd': measured carry 1e308 is outside the physical range [-600, 600] yd"]),
        ("d2,150,12,2600,,-3,,,", vec!["column 'apex_yd': measured apex -3 is outside the physical range [0, 700] yd"]),
        ("d2,150,12,2600,,,0,,", vec!["column 'flight_time_s': measured flight time 0 is outside the physical range (0, 30] s"]),
        ("d2,150,12,2600,,,,95,", vec!["column 'land_angle_deg': measured land angle 95 is outside the physical range [0, 90] deg"]),
    ]
    .into_iter()
    .enumerate()
    {
        let text = format!("{MEASURED_HEAD}{ok}{row}\n");
        let e = refused(d, &format!("m{k}.csv"), &text, &[], &needles);
        assert!(e.len() < 200, "short: {e}");
        // The same with a quoted cell (the one-piece reader).
        let quoted = text.replacen("d1,", "\"d,1\",", 1);
        refused(d, &format!("q{k}.csv"), &quoted, &[], &needles);
    }
    // total_yd is compared (and so checked) only with --total.
    let text = format!("{MEASURED_HEAD}{ok}d2,150,12,2600,,,,,1e300\n");
    let shots = write(d, "total.csv", &text);
    let out = d.join("total.out.csv");
    let o = smash(&["flight", "--shots", s(&shots), "--out", s(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    refused(
        d,
        "total2.csv",
        &text,
        &["--total"],
        &[":3: column 'total_yd': measured total 1e300"],
    );

    // smash predict --flight names the shots file and line.
    let shots = write(
        d,
        "shots.csv",
        "shot_id,club_speed_mph,attack_angle_deg,club_path_deg,dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm,carry_yd\n\
         s1,110,2,0,13,0,0,0,280\n\
         s2,110,2,0,13,0,0,0,1e308\n",
    );
    let out = d.join("p.csv");
    let club = club();
    let args = [
        "predict",
        "--club",
        &club,
        "--shots",
        s(&shots),
        "--out",
        s(&out),
        "--flight",
        "--strict",
    ];
    assert_refused(
        &smash(&args),
        &["shots.csv:3: column 'carry_yd': measured carry 1e308"],
    );
    assert!(!out.exists());
}

/// Line numbers in messages are right whatever the line ends: LF, CRLF (Excel, Python's csv)
/// or a lone CR, with blank lines before the bad row, in the launch file, a shots file and a
/// coefficient table.
#[test]
fn messages_name_the_right_line_with_any_line_ends() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let club = club();
    for (k, end) in ["\n", "\r\n", "\r"].into_iter().enumerate() {
        let launch = [
            "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm",
            "d1,150,12,2600",
            "",
            "d2,150,95,2600",
        ]
        .join(end);
        refused(
            d,
            &format!("l{k}.csv"),
            &launch,
            &[],
            &[&format!("l{k}.csv:4: column 'launch_angle_deg'")],
        );
        let bad_cell = launch.replace("95", "x");
        refused(
            d,
            &format!("c{k}.csv"),
            &bad_cell,
            &[],
            &[&format!("c{k}.csv:4: column 'launch_angle_deg'")],
        );
        let short = launch.replace("d2,150,95,2600", "d2,150");
        refused(
            d,
            &format!("w{k}.csv"),
            &short,
            &[],
            &[&format!(
                "w{k}.csv:4: found a row with 2 field(s), but the header has 4"
            )],
        );
        // A shots file for predict: the bad club speed is on line 4.
        let shots = [
            "shot_id,club_speed_mph,attack_angle_deg,club_path_deg,dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm",
            "s1,110,2,0,13,0,0,0",
            "",
            "s2,abc,2,0,13,0,0,0",
            "",
        ]
        .join(end);
        let shots = write(d, &format!("s{k}.csv"), &shots);
        let out = d.join(format!("p{k}.csv"));
        let args = [
            "predict",
            "--club",
            &club,
            "--shots",
            s(&shots),
            "--out",
            s(&out),
            "--strict",
        ];
        assert_refused(&smash(&args), &[&format!("s{k}.csv:4:")]);
        // A coefficient table with a comment and a blank line: the bad cl is on line 5.
        let table = [
            "# my ball",
            "spin_factor,cd,cl",
            "0.1,0.25,0.15",
            "",
            "0.3,0.3,x",
        ]
        .join(end);
        let table = write(d, &format!("t{k}.csv"), &table);
        let aero = format!("table:{}", s(&table));
        let launch_ok = write(d, "ok.csv", OK_ROW);
        let out = d.join("t.csv");
        let args = [
            "flight",
            "--shots",
            s(&launch_ok),
            "--out",
            s(&out),
            "--aero",
            &aero,
        ];
        assert_refused(&smash(&args), &[&format!("t{k}.csv: line 5, column cl")]);
    }
}

/// Carry is the signed distance along the target line: a pop-up blown back by a gale lands
/// behind the golfer with a negative carry (it used to be the unsigned distance to the landing).
#[test]
fn a_ball_blown_back_has_a_negative_carry() {
    let dir = tempfile::tempdir().unwrap();
    let shots = write(
        dir.path(),
        "pop.csv",
        "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\np,40,80,1000\n",
    );
    let out = dir.path().join("f.csv");
    let o = smash(&[
        "flight",
        "--shots",
        s(&shots),
        "--out",
        s(&out),
        "--wind-speed-m-s",
        "30",
        "--wind-direction-deg",
        "180",
        "--total",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (h, rows) = table(&out);
    let carry: f64 = rows[0][col(&h, "pred_carry_yd")].parse().unwrap();
    let total: f64 = rows[0][col(&h, "pred_total_yd")].parse().unwrap();
    assert!(
        carry < -1.0 && total <= carry,
        "carry {carry}, total {total}"
    );
}

/// Range errors of the atmosphere and ground flags print the value short (never 309 digits).
#[test]
fn huge_atmosphere_and_ground_values_are_printed_short() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (k, flags) in [
        vec!["--temperature-c", "1e308"],
        vec!["--elevation-m", "1e308"],
        vec!["--pressure-hpa", "-1e308"],
        vec!["--humidity-pct", "1e308"],
        vec!["--wind-speed-m-s", "1e308"],
        vec!["--wind-direction-deg", "1e308"],
        vec!["--wind-height-m", "1e308"],
        vec!["--roughness-m", "1e308"],
        vec!["--total", "--ground-restitution", "1e308"],
        vec!["--total", "--roll-decel-m-s2", "1e308"],
    ]
    .into_iter()
    .enumerate()
    {
        let e = refused(d, &format!("a{k}.csv"), OK_ROW, &flags, &["e308"]);
        assert!(e.len() < 200, "{flags:?}: {e}");
    }
    let atm = write(
        d,
        "atm.toml",
        "[atmosphere]\nwind_height_m = 5\nroughness_m = 1e-300\n",
    );
    let e = refused(
        d,
        "b.csv",
        OK_ROW,
        &["--atmosphere", s(&atm)],
        &["atmosphere.roughness_m", "1e-300"],
    );
    assert!(e.len() < 200, "{e}");
}
