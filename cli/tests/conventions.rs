//! Each monitor's delivery convention, honoured (docs/import.md, `smash::conventions`).
//!
//! - A synthetic world written out as TrackMan defines its numbers (dynamic loft and face angle
//!   at the centre-point of contact, speed and path of the geometric centre) and read back with
//!   the `trackman` preset gives the world's own `compare` and `diagnose` results, with no
//!   trend of error against impact location. The same export read as if its angles were at the
//!   face centre (the old reading) shows the bulge and roll counted twice: a toe trend of the
//!   azimuth error with r > 0.9.
//! - A world whose face angle is computed from the launch as a radar does
//!   (`face = (azimuth − 0.25·path)/0.75`) yields no finding that is that formula when the file
//!   says so (`face_angle_from = derived_from_launch`); read as measured (the old reading), it
//!   does.

use crate::cli_support;

use std::path::Path;
use std::process::Output;

use serde_json::Value;

use cli_support::smash_in_repo as smash;

const CLUB: &str = "configs/clubs/paper_driver.toml";

fn ok(out: &Output) -> String {
    assert!(
        out.status.success(),
        "smash failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).expect("utf-8")
}

/// The world's columns kept (no monitor exports lie tilt or clubhead spin).
const COLUMNS: [&str; 15] = [
    "shot_id",
    "group",
    "golfer",
    "club_speed_mph",
    "attack_angle_deg",
    "club_path_deg",
    "dynamic_loft_deg",
    "face_angle_deg",
    "impact_y_mm",
    "impact_z_mm",
    "ball_speed_mph",
    "launch_angle_deg",
    "azimuth_deg",
    "backspin_rpm",
    "sidespin_rpm",
];

/// The null world (the nominal club, noise only), 8 golfers, as rows of [`COLUMNS`] (text).
fn world(dir: &Path) -> Vec<Vec<String>> {
    let full = dir.join("full.csv");
    ok(&smash(&[
        "synth",
        "--config",
        "configs/synth/null_world.toml",
        "--out",
        full.to_str().unwrap(),
        "--seed",
        "21",
    ]));
    let mut rdr = csv::Reader::from_path(&full).unwrap();
    let h = rdr.headers().unwrap().clone();
    let idx: Vec<usize> = COLUMNS
        .iter()
        .map(|c| h.iter().position(|x| x == *c).unwrap())
        .collect();
    rdr.records()
        .map(|r| {
            let r = r.unwrap();
            idx.iter().map(|&i| r[i].to_owned()).collect::<Vec<_>>()
        })
        .filter(|r| r[2].as_str() <= "G08")
        .collect()
}

fn write_shots(path: &Path, head: &[&str], rows: &[Vec<String>]) {
    let mut w = csv::Writer::from_path(path).unwrap();
    w.write_record(head).unwrap();
    for r in rows {
        w.write_record(r).unwrap();
    }
    w.flush().unwrap();
}

fn num(r: &[String], c: &str) -> f64 {
    r[COLUMNS.iter().position(|x| *x == c).unwrap()]
        .parse()
        .unwrap()
}

/// The world as a TrackMan export: its real header's names and units row, loft and face angle
/// at the contact point (the library's `contact_point_angles` with the club's bulge and roll),
/// speed and path as the world's (TrackMan's geometric centre, taken as the CoM), spin as rate
/// and axis, the heel–toe offset + toward the toe.
fn trackman(rows: &[Vec<String>]) -> String {
    let club = smash::data::club_file::read_club(&cli_support::repo(CLUB)).unwrap();
    let face =
        smash::physics::FaceGeometry::new(club.nominal.bulge_m, club.nominal.roll_m).unwrap();
    let mut s = String::from(
        "Player,Club,Club Speed,Attack Angle,Club Path,Dyn. Loft,Face Angle,Ball Speed,\
         Launch Angle,Launch Direction,Spin Rate,Spin Axis,Impact Offset,Impact Height\n\
         ,,[mph],[deg],[deg],[deg],[deg],[mph],[deg],[deg],[rpm],[deg],[mm],[mm]\n",
    );
    for r in rows {
        let f = |c: &str| num(r, c);
        let (loft, fa) = smash::conventions::contact_point_angles(
            &face,
            f("impact_y_mm") * 1e-3,
            f("impact_z_mm") * 1e-3,
            (
                f("dynamic_loft_deg").to_radians(),
                f("face_angle_deg").to_radians(),
            ),
            0.0,
        )
        .unwrap();
        let (back, side) = (f("backspin_rpm"), f("sidespin_rpm"));
        s.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
            r[2],
            r[1],
            f("club_speed_mph"),
            f("attack_angle_deg"),
            f("club_path_deg"),
            loft.to_degrees(),
            fa.to_degrees(),
            f("ball_speed_mph"),
            f("launch_angle_deg"),
            f("azimuth_deg"),
            back.hypot(side),
            side.atan2(back).to_degrees(),
            f("impact_z_mm"),
            f("impact_y_mm"),
        ));
    }
    s
}

/// Equal JSON: same structure and strings, numbers within `rel` relative (`rel`·1e-3
/// absolute). The conversions cost a few ulps; a fit stops at its own tolerance, so fitted
/// values of inputs a few ulps apart agree to about 1e-6.
fn assert_json_eq(a: &Value, b: &Value, at: &str, rel: f64) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            assert!(
                (x - y).abs() <= rel * x.abs().max(y.abs()).max(1e-3),
                "{at}: {x} vs {y}"
            );
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{at}: lengths");
            for (i, (p, q)) in x.iter().zip(y).enumerate() {
                assert_json_eq(p, q, &format!("{at}[{i}]"), rel);
            }
        }
        (Value::Object(x), Value::Object(y)) => {
            let kx: Vec<_> = x.keys().collect();
            let ky: Vec<_> = y.keys().collect();
            assert_eq!(kx, ky, "{at}: keys");
            for (k, v) in x {
                assert_json_eq(v, &y[k], &format!("{at}.{k}"), rel);
            }
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}

fn json_of(cmd: &str, shots: &Path, extra: &[&str]) -> Value {
    let mut args = vec![cmd, "--club", CLUB, "--shots", shots.to_str().unwrap()];
    args.extend_from_slice(extra);
    args.push("--json");
    serde_json::from_str(&ok(&smash(&args))).expect("json")
}

/// The largest |r| of an error's correlation with the impact location, and that of the azimuth
/// error with the heel–toe location.
fn location_trends(compare: &Value) -> (f64, f64) {
    let mut max = 0.0f64;
    let mut az_z = 0.0;
    for k in compare["correlations"].as_array().unwrap() {
        let v = k["variable"].as_str().unwrap();
        let r = k["r"].as_f64().unwrap();
        if v.starts_with("impact_") {
            max = max.max(r.abs());
        }
        if v == "impact_z_mm" && k["component"] == "azimuth_deg" {
            az_z = r;
        }
    }
    (max, az_z)
}

fn findings(compare: &Value) -> Vec<String> {
    compare["findings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| format!("{}: {}", f["component"], f["text"]))
        .collect()
}

const DIAGNOSE: [&str; 2] = ["--max-steps", "2"];

#[test]
fn a_trackman_export_reads_back_as_the_world() {
    let dir = tempfile::tempdir().unwrap();
    let rows = world(dir.path());
    let orig = dir.path().join("world.csv");
    write_shots(&orig, &COLUMNS, &rows);
    let export = dir.path().join("trackman.csv");
    std::fs::write(&export, trackman(&rows)).unwrap();
    let flags = ["--format", "trackman", "--impact-offset-positive", "toe"];

    let want = json_of("compare", &orig, &[]);
    let got = json_of("compare", &export, &flags);
    assert_json_eq(&want, &got, "compare", 1e-9);
    let (max_r, _) = location_trends(&got);
    assert!(max_r < 0.3, "a trend against impact location: r = {max_r}");
    let mut dflags = flags.to_vec();
    dflags.extend_from_slice(&DIAGNOSE);
    assert_json_eq(
        &json_of("diagnose", &orig, &DIAGNOSE),
        &json_of("diagnose", &export, &dflags),
        "diagnose",
        1e-4,
    );

    // The old reading: the contact-point angles taken as the face centre's count the bulge
    // and roll twice, and the azimuth error follows the heel–toe location.
    let preset = std::fs::read_to_string(cli_support::repo("configs/import/trackman.toml"))
        .unwrap()
        .replace("at = \"contact_point\"", "at = \"face_centre\"");
    let old = dir.path().join("trackman_as_face_centre.toml");
    std::fs::write(&old, preset).unwrap();
    let old_flags = [
        "--format",
        old.to_str().unwrap(),
        "--impact-offset-positive",
        "toe",
    ];
    let bad = json_of("compare", &export, &old_flags);
    let (_, az_z) = location_trends(&bad);
    assert!(az_z > 0.9, "old reading: azimuth error vs toe r = {az_z}");
    assert!(
        findings(&bad).iter().any(|f| f.contains("toward the toe")),
        "{:?}",
        findings(&bad)
    );
}

/// The world with its face angle replaced by the radar formula on the shots of `derived`
/// groups, `face_angle_from` saying so when `honest` (else the column says `measured`: the old
/// reading, which took every face angle as measured).
fn radar(rows: &[Vec<String>], derived: &[&str], honest: bool) -> Vec<Vec<String>> {
    rows.iter()
        .map(|r| {
            let mut r = r.clone();
            let is_derived = derived.contains(&r[1].as_str());
            if is_derived {
                let face = (num(&r, "azimuth_deg") - 0.25 * num(&r, "club_path_deg")) / 0.75;
                r[7] = format!("{face}");
            }
            let from = if is_derived && honest {
                "derived_from_launch"
            } else {
                "measured"
            };
            r.push(from.to_owned());
            r
        })
        .collect()
}

/// Does diagnose report unexplained structure in the azimuth error?
fn azimuth_structure(d: &Value) -> bool {
    d["noise_floor"]["components"]
        .as_array()
        .unwrap()
        .iter()
        .any(|c| c["component"] == "azimuth_deg" && c["structure"] == true)
}

#[test]
fn a_face_angle_derived_from_the_launch_is_no_finding() {
    let dir = tempfile::tempdir().unwrap();
    let rows = world(dir.path());
    let mut head = COLUMNS.to_vec();
    head.push("face_angle_from");
    let formula = |f: &String| f.contains("azimuth_deg") || f.contains("face_angle_deg");

    // Every shot's face angle derived: compare draws no finding from the formula.
    let all = dir.path().join("all.csv");
    write_shots(&all, &head, &radar(&rows, &["A", "B", "C"], true));
    let honest = findings(&json_of("compare", &all, &[]));
    assert!(!honest.iter().any(formula), "{honest:?}");
    let out = smash(&["diagnose", "--club", CLUB, "--shots", all.to_str().unwrap()]);
    assert!(!out.status.success());
    let err = cli_support::stderr(&out);
    assert!(err.contains("every shot's face angle is derived"), "{err}");

    // Read as measured (the old reading), the formula is the top finding.
    let old = dir.path().join("old.csv");
    write_shots(&old, &head, &radar(&rows, &["A", "B", "C"], false));
    let naive = findings(&json_of("compare", &old, &[]));
    assert!(naive.iter().any(formula), "{naive:?}");

    // Two groups derived, one measured: diagnose fits the measured one and finds the world's
    // nothing; read as measured, the formula's shots leave structure in the azimuth (the
    // formula's face share against the model's) that diagnose reports as unexplained.
    let mixed = dir.path().join("mixed.csv");
    write_shots(&mixed, &head, &radar(&rows, &["B", "C"], true));
    let d = json_of("diagnose", &mixed, &DIAGNOSE);
    assert_eq!(d["findings"], serde_json::json!([]), "{}", d["findings"]);
    assert!(!azimuth_structure(&d), "{}", d["noise_floor"]);
    let mixed_old = dir.path().join("mixed_old.csv");
    write_shots(&mixed_old, &head, &radar(&rows, &["B", "C"], false));
    let d = json_of("diagnose", &mixed_old, &DIAGNOSE);
    assert!(azimuth_structure(&d), "{}", d["noise_floor"]);
}
