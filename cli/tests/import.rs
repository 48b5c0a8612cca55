//! `smash import` and `--format`: a measured experiment written as each vendor's export (by the
//! writers below, from the vendor's column names and conventions) imports to a shots file whose
//! `compare` output equals the original experiment's; bad exports are refused with one line.

use crate::cli_support;

use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;

use cli_support::smash_in_repo as smash;

use crate::common;

fn ok(out: &Output) -> String {
    assert!(
        out.status.success(),
        "smash failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).expect("utf-8")
}

/// One shot of the original experiment, in shots-file units.
#[derive(Clone)]
struct Row {
    group: String,
    golfer: String,
    speed_mph: f64,
    attack: f64,
    path: f64,
    loft: f64,
    face: f64,
    y_mm: f64,
    z_mm: f64,
    ball_mph: f64,
    launch: f64,
    azimuth: f64,
    back: f64,
    side: f64,
}

/// A synthetic experiment of the paper's world, as a launch monitor measures it: no lie tilt or
/// clubhead angular velocity (no monitor exports them), written as the original shots file.
fn original(dir: &Path) -> (PathBuf, Vec<Row>) {
    let full = dir.join("full.csv");
    ok(&smash(&[
        "synth",
        "--config",
        "configs/synth/paper_world.toml",
        "--out",
        full.to_str().unwrap(),
        "--seed",
        "11",
    ]));
    let mut rdr = csv::Reader::from_path(&full).unwrap();
    let h = rdr.headers().unwrap().clone();
    let col = |n: &str| h.iter().position(|x| x == n).unwrap();
    let mut rows = Vec::new();
    for rec in rdr.records() {
        let r = rec.unwrap();
        let f = |n: &str| r[col(n)].parse::<f64>().unwrap();
        rows.push(Row {
            group: r[col("group")].to_owned(),
            golfer: r[col("golfer")].to_owned(),
            speed_mph: f("club_speed_mph"),
            attack: f("attack_angle_deg"),
            path: f("club_path_deg"),
            loft: f("dynamic_loft_deg"),
            face: f("face_angle_deg"),
            y_mm: f("impact_y_mm"),
            z_mm: f("impact_z_mm"),
            ball_mph: f("ball_speed_mph"),
            launch: f("launch_angle_deg"),
            azimuth: f("azimuth_deg"),
            back: f("backspin_rpm"),
            side: f("sidespin_rpm"),
        });
    }
    // Keep the test quick: 10 golfers.
    rows.retain(|r| r.golfer.as_str() <= "G10");
    let mut w = csv::Writer::from_path(dir.join("original.csv")).unwrap();
    w.write_record([
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
    ])
    .unwrap();
    for (i, r) in rows.iter().enumerate() {
        let v = [
            r.speed_mph,
            r.attack,
            r.path,
            r.loft,
            r.face,
            r.y_mm,
            r.z_mm,
            r.ball_mph,
            r.launch,
            r.azimuth,
            r.back,
            r.side,
        ];
        let mut rec = vec![format!("s{i}"), r.group.clone(), r.golfer.clone()];
        rec.extend(v.iter().map(|x| format!("{x}")));
        w.write_record(&rec).unwrap();
    }
    w.flush().unwrap();
    (dir.join("original.csv"), rows)
}

const MPH: f64 = 0.44704;

fn lr(v: f64, suffix: bool) -> String {
    let (l, a) = if v < 0.0 { ('L', -v) } else { ('R', v) };
    if suffix {
        format!("{a} {l}")
    } else {
        format!("{l}{a}")
    }
}

fn rate_axis(r: &Row) -> (f64, f64) {
    (r.back.hypot(r.side), r.side.atan2(r.back).to_degrees())
}

/// The face of the club the experiment is compared with (configs/clubs/paper_driver.toml).
fn paper_face() -> smash::physics::FaceGeometry {
    let club =
        smash::data::club_file::read_club(&cli_support::repo("configs/clubs/paper_driver.toml"))
            .unwrap();
    smash::physics::FaceGeometry::new(club.nominal.bulge_m, club.nominal.roll_m).unwrap()
}

/// A row's loft and face angle as TrackMan defines them: the direction of the face normal at
/// the centre-point of contact (the library's [`smash::conventions::contact_point_angles`]),
/// deg. Speed and path are TrackMan's geometric centre, which smash takes to be the CoM: the
/// experiment's own.
fn at_contact(face: &smash::physics::FaceGeometry, r: &Row) -> (f64, f64) {
    let (l, f) = smash::conventions::contact_point_angles(
        face,
        r.y_mm * 1e-3,
        r.z_mm * 1e-3,
        (r.loft.to_radians(), r.face.to_radians()),
        0.0,
    )
    .unwrap();
    (l.to_degrees(), f.to_degrees())
}

/// TrackMan: BOM, `sep=,`, header, units row (metric speeds), spin rate and axis, impact offset
/// positive toward the heel, per-club average rows; loft and face angle at the contact point.
fn trackman(rows: &[Row]) -> String {
    trackman_with(rows, true)
}

/// [`trackman`], with loft and face angle at the contact point (`contact`, as TrackMan does)
/// or at the face centre (as the experiment states them: the old writer).
fn trackman_with(rows: &[Row], contact: bool) -> String {
    let face = paper_face();
    let mut s = String::from("\u{feff}sep=,\r\n");
    s.push_str("Date,Player,Club,Club Speed,Attack Angle,Club Path,Dyn. Loft,Face Angle,Impact Offset,Impact Height,Ball Speed,Smash Factor,Launch Angle,Launch Direction,Spin Rate,Spin Axis,Carry\r\n");
    s.push_str(
        ",,,[km/h],[deg],[deg],[deg],[deg],[mm],[mm],[km/h],[],[deg],[deg],[rpm],[deg],[m]\r\n",
    );
    for (i, r) in rows.iter().enumerate() {
        let (rate, axis) = rate_axis(r);
        let (loft, face_angle) = if contact {
            at_contact(&face, r)
        } else {
            (r.loft, r.face)
        };
        s.push_str(&format!(
            "2026-01-0{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\r\n",
            1 + i % 3,
            r.golfer,
            r.group,
            r.speed_mph * MPH * 3.6,
            r.attack,
            r.path,
            loft,
            face_angle,
            -r.z_mm,
            r.y_mm,
            r.ball_mph * MPH * 3.6,
            r.ball_mph / r.speed_mph,
            r.launch,
            r.azimuth,
            rate,
            axis,
            200.0 + i as f64
        ));
    }
    s.push_str(",Average,Average,150,0,0,10,0,0,0,220,1.47,10,0,2500,0,230\r\n");
    s
}

/// Foresight (FSX): units in the header, directions as `5.4 L` / `2.0 R`, back and side spin,
/// an `Estimated` flag, per-club average rows between the clubs.
fn foresight(rows: &[Row]) -> String {
    let mut s = String::from("Player,Club,Ball Speed (mph),Launch Angle (deg),Azimuth (deg),Back Spin (rpm),Side Spin (rpm),Carry (yd),Club Speed (mph),Efficiency,Angle of Attack (deg),Club Path (deg),Face to Target (deg),Loft (deg),Face Impact Horizontal (mm),Face Impact Vertical (mm),Estimated\n");
    let mut last_group = String::new();
    for r in rows {
        if !last_group.is_empty() && r.group != last_group {
            s.push_str(&format!(
                ",{last_group},Average,10,1 R,2500,100 L,230,110,1.4,0,0,0,10,0,0,\n"
            ));
        }
        last_group = r.group.clone();
        s.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},No\n",
            r.golfer,
            r.group,
            r.ball_mph,
            r.launch,
            lr(r.azimuth, true),
            r.back,
            lr(r.side, true),
            250.0,
            r.speed_mph,
            r.ball_mph / r.speed_mph,
            r.attack,
            lr(r.path, true),
            lr(r.face, true),
            r.loft,
            r.z_mm,
            r.y_mm
        ));
    }
    // A shot the monitor estimated: it must be reported and left out.
    s.push_str("G01,A,150,12,1 R,2600,0,240,104,1.44,0,0,0,11,0,0,Yes\n");
    s
}

/// FlightScope: semicolon-separated with `sep=;`, speeds in m/s, `L5.4` prefixes, spin rate and
/// axis, impact in inches, lateral impact positive toward the toe.
fn flightscope(rows: &[Row]) -> String {
    let mut s = String::from("sep=;\nPlayer;Club;Club Speed (m/s);Ball Speed (m/s);Launch V (deg);Launch H (deg);Spin (rpm);Spin Axis (deg);AOA (deg);Club Path (deg);Face to Target (deg);Dynamic Loft (deg);Lateral Impact (in);Vertical Impact (in);Smash\n");
    for r in rows {
        let (rate, axis) = rate_axis(r);
        s.push_str(&format!(
            "{};{};{};{};{};{};{};{};{};{};{};{};{};{};{}\n",
            r.golfer,
            r.group,
            r.speed_mph * MPH,
            r.ball_mph * MPH,
            r.launch,
            lr(r.azimuth, false),
            rate,
            lr(axis, false),
            r.attack,
            lr(r.path, false),
            lr(r.face, false),
            r.loft,
            r.z_mm / 25.4,
            r.y_mm / 25.4,
            r.ball_mph / r.speed_mph
        ));
    }
    s
}

/// Uneekor: no units anywhere (the preset's mph, deg, rpm, mm are assumed), signed numbers,
/// impact x positive toward the heel.
fn uneekor(rows: &[Row]) -> String {
    let mut s = String::from("No,Club,Ball Speed,Launch Angle,Side Angle,Back Spin,Side Spin,Club Speed,Club Path,Face Angle,Attack Angle,Dynamic Loft,Impact X,Impact Y,Smash Factor\n");
    for (i, r) in rows.iter().enumerate() {
        s.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
            i + 1,
            r.group,
            r.ball_mph,
            r.launch,
            r.azimuth,
            r.back,
            r.side,
            r.speed_mph,
            r.path,
            r.face,
            r.attack,
            r.loft,
            -r.z_mm,
            r.y_mm,
            r.ball_mph / r.speed_mph
        ));
    }
    s
}

/// Equal JSON: same structure and strings, numbers within 1e-9 (relative) — the unit
/// conversions and the spin rate/axis round trip cost a few ulps, nothing more.
fn assert_json_eq(a: &Value, b: &Value, at: &str) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            assert!(
                (x - y).abs() <= 1e-9 * x.abs().max(y.abs()).max(1e-3),
                "{at}: {x} vs {y}"
            );
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{at}: lengths");
            for (i, (p, q)) in x.iter().zip(y).enumerate() {
                assert_json_eq(p, q, &format!("{at}[{i}]"));
            }
        }
        (Value::Object(x), Value::Object(y)) => {
            let kx: Vec<_> = x.keys().collect();
            let ky: Vec<_> = y.keys().collect();
            assert_eq!(kx, ky, "{at}: keys");
            for (k, v) in x {
                assert_json_eq(v, &y[k], &format!("{at}.{k}"));
            }
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}

fn compare_json(shots: &Path, format: &[&str]) -> Value {
    let mut args = vec![
        "compare",
        "--club",
        "configs/clubs/paper_driver.toml",
        "--shots",
        shots.to_str().unwrap(),
        "--json",
    ];
    args.extend_from_slice(format);
    let mut v: Value = serde_json::from_str(&ok(&smash(&args))).expect("json");
    // The notes on rows left out (an export's estimated shot) name the file's own lines; the
    // numbers are what is compared.
    let warnings = v
        .as_object_mut()
        .unwrap()
        .remove("warnings")
        .expect("warnings");
    assert!(warnings
        .as_array()
        .unwrap()
        .iter()
        .all(|w| w.as_str().unwrap().starts_with("left out ")));
    v
}

fn round_trip(preset: &str, flags: &[&str], expect_note: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let (orig, rows) = original(dir.path());
    let text = match preset {
        "trackman" => trackman(&rows),
        "foresight" => foresight(&rows),
        "flightscope" => flightscope(&rows),
        "uneekor" => uneekor(&rows),
        _ => unreachable!(),
    };
    let exp = dir.path().join(format!("{preset}.csv"));
    std::fs::write(&exp, text).unwrap();
    let out = dir.path().join("imported.csv");
    let mut args = vec![
        "import",
        "--format",
        preset,
        exp.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(flags);
    let res = smash(&args);
    ok(&res);
    let stderr = String::from_utf8_lossy(&res.stderr);
    for note in expect_note {
        assert!(
            stderr.contains(note),
            "{preset}: expected '{note}' in: {stderr}"
        );
    }
    let want = compare_json(&orig, &[]);
    let got = compare_json(&out, &[]);
    assert_json_eq(&want, &got, preset);
    // The same export read directly by compare with --format.
    let mut fmt = vec!["--format", preset];
    fmt.extend_from_slice(flags);
    let direct = compare_json(&exp, &fmt);
    assert_json_eq(&want, &direct, &format!("{preset} --format"));
}

#[test]
fn trackman_round_trip() {
    round_trip(
        "trackman",
        &["--impact-offset-positive", "heel"],
        &["skipped 1 average row"],
    );
    // Carry is carried through, converted to yards.
    let dir = tempfile::tempdir().unwrap();
    let (_, rows) = original(dir.path());
    let exp = dir.path().join("tm.csv");
    std::fs::write(&exp, trackman(&rows[..3])).unwrap();
    let out = dir.path().join("s.csv");
    ok(&smash(&[
        "import",
        "--format",
        "trackman",
        exp.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--impact-offset-positive",
        "heel",
    ]));
    let mut rdr = csv::Reader::from_path(&out).unwrap();
    let h = rdr.headers().unwrap().clone();
    let carry = h.iter().position(|c| c == "carry_yd").expect("carry_yd");
    let golfer = h.iter().position(|c| c == "golfer").expect("golfer");
    let first = rdr.records().next().unwrap().unwrap();
    let c: f64 = first[carry].parse().unwrap();
    assert!((c - 200.0 / 0.9144).abs() < 1e-9, "carry {c}");
    assert_eq!(&first[golfer], rows[0].golfer.as_str());
}

#[test]
fn foresight_round_trip() {
    round_trip(
        "foresight",
        &["--impact-offset-positive", "toe"],
        &["average row", "1 of", "spin the monitor estimated"],
    );
}

#[test]
fn flightscope_round_trip() {
    round_trip("flightscope", &["--impact-offset-positive", "toe"], &[]);
}

#[test]
fn uneekor_round_trip() {
    round_trip(
        "uneekor",
        &["--impact-offset-positive", "heel"],
        &["units were assumed"],
    );
}

/// A user's mapping file: a made-up monitor with metres, feet and a flipped sign.
#[test]
fn mapping_file() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("mine.toml");
    std::fs::write(
        &map,
        r#"
[export]
name = "Mine"
skip_lines = 2
impact_offset_positive = "toe"

[[column]]
target = "shot_id"
source = ["id"]
[[column]]
target = "club_speed_mph"
source = ["v_club"]
unit = "m/s"
[[column]]
target = "attack_angle_deg"
source = ["aoa"]
unit = "deg"
[[column]]
target = "club_path_deg"
source = ["path"]
unit = "deg"
sign = -1
[[column]]
target = "dynamic_loft_deg"
source = ["loft"]
unit = "deg"
[[column]]
target = "face_angle_deg"
source = ["face"]
unit = "deg"
[[column]]
target = "impact_offset_mm"
source = ["x"]
unit = "in"
[[column]]
target = "impact_y_mm"
source = ["y"]
unit = "mm"
[[column]]
target = "apex_yd"
source = ["apex"]
unit = "ft"
"#,
    )
    .unwrap();
    let exp = dir.path().join("e.csv");
    std::fs::write(
        &exp,
        "My Monitor v2\nexported today\nid,v_club,aoa,path,loft,face,x,y,apex\nq1,44.704,1,2,10,0,1,3,30\n",
    )
    .unwrap();
    let out = dir.path().join("s.csv");
    ok(&smash(&[
        "import",
        "--format",
        map.to_str().unwrap(),
        exp.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]));
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "shot_id,club_speed_mph,attack_angle_deg,club_path_deg,dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm,apex_yd,\
         face_at,velocity_at,face_angle_from"
    );
    let v: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(v[0], "q1");
    let num = |i: usize| v[i].parse::<f64>().unwrap();
    assert!((num(1) - 100.0).abs() < 1e-12);
    assert_eq!(num(3), -2.0);
    assert!((num(7) - 25.4).abs() < 1e-12);
    assert!((num(8) - 10.0).abs() < 1e-12);
    // A mapping that states no convention is read in the model's own, and the file says so.
    assert_eq!(v[9..], ["face_centre", "com", "measured"]);
}

fn refused(preset: &str, text: &str, flags: &[&str], want: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let exp = dir.path().join("bad.csv");
    std::fs::write(&exp, text).unwrap();
    let out = dir.path().join("s.csv");
    let mut args = vec![
        "import",
        "--format",
        preset,
        exp.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(flags);
    let res = smash(&args);
    // Exit 1, no panic, one line starting `error: ` naming the file and every needle, no
    // inf/NaN on either stream.
    let mut needles = want.to_vec();
    needles.push("bad.csv");
    common::assert_refused(&res, &needles);
    assert!(!out.exists(), "no output on error");
}

const TM_HEAD: &str = "Club,Club Speed,Attack Angle,Club Path,Dyn. Loft,Face Angle,Impact Offset,Impact Height,Ball Speed,Launch Angle,Launch Direction,Spin Rate,Spin Axis";
const TM_ROW: &str = "Driver,105,1,2,11,0.5,3,4,155,12,1.2,2600,-3";

#[test]
fn bad_exports_are_refused_with_one_line() {
    let units = ",[mph],[deg],[deg],[deg],[deg],[mm],[mm],[mph],[deg],[deg],[rpm],[deg]";
    let flag = ["--impact-offset-positive", "toe"];
    // An unknown column, in a user's mapping (strict by default; the presets list such
    // columns in the summary instead).
    let maps = tempfile::tempdir().unwrap();
    let strict = maps.path().join("tm_strict.toml");
    let preset =
        std::fs::read_to_string(cli_support::repo("configs/import/trackman.toml")).unwrap();
    std::fs::write(&strict, preset.replace("unknown_columns = \"note\"\n", "")).unwrap();
    refused(
        strict.to_str().unwrap(),
        &format!("{TM_HEAD},Wobble\n{units},[deg]\n{TM_ROW},3\n"),
        &flag,
        &["unknown column", "'Wobble'", "--ignore-unknown-columns"],
    );
    // A unit row that disagrees with what the column holds.
    refused(
        "trackman",
        &format!(
            "{TM_HEAD}\n,[deg],[deg],[deg],[deg],[deg],[mm],[mm],[mph],[deg],[deg],[rpm],[deg]\n{TM_ROW}\n"
        ),
        &flag,
        &["unit row says '[deg]'", "Club Speed", "mph, km/h, m/s"],
    );
    // Header and unit row disagree.
    refused(
        "foresight",
        "Club,Ball Speed (mph),Launch Angle,Azimuth,Back Spin,Side Spin,Club Speed,Angle of Attack,Club Path,Face to Target,Loft,Face Impact Horizontal,Face Impact Vertical\n\
         ,[km/h],[deg],[deg],[rpm],[rpm],[mph],[deg],[deg],[deg],[deg],[mm],[mm]\n\
         7i,120,15,1 R,6000,100 L,85,-3,1 L,0,25,1,2\n",
        &flag,
        &["header says mph but the unit row says km/h"],
    );
    // Mixed units inside a column: the row is refused under --strict (without it, it is left
    // out and counted).
    refused(
        "trackman",
        &format!(
            "{TM_HEAD}\n{units}\n{TM_ROW}\nDriver,169 km/h,1,2,11,0.5,3,4,155,12,1.2,2600,-3\n"
        ),
        &["--impact-offset-positive", "toe", "--strict"],
        &["mixed units", "km/h", "mph", ":4:"],
    );
    // No units at all in a TrackMan export: refused, not assumed.
    refused(
        "trackman",
        &format!("{TM_HEAD}\n{TM_ROW}\n"),
        &flag,
        &["no unit"],
    );
    // The heel–toe sign is not guessed.
    refused(
        "trackman",
        &format!("{TM_HEAD}\n{units}\n{TM_ROW}\n"),
        &[],
        &["--impact-offset-positive", "does not guess"],
    );
    // A missing column names what the file has.
    refused(
        "trackman",
        "Club,Club Speed\n,[mph]\nDriver,100\n",
        &flag,
        &[
            "missing column(s)",
            "'Ball Speed'",
            "the file has: Club, Club Speed",
        ],
    );
    // A cell that is not a number.
    refused(
        "trackman",
        &format!("{TM_HEAD}\n{units}\nDriver,fast,1,2,11,0.5,3,4,155,12,1.2,2600,-3\n"),
        &flag,
        &["'fast' is not a number", "column 'Club Speed'"],
    );
    // L/R letters where the column does not take them.
    refused(
        "trackman",
        &format!("{TM_HEAD}\n{units}\nDriver,105,1 L,2,11,0.5,3,4,155,12,1.2,2600,-3\n"),
        &flag,
        &["does not take L/R"],
    );
}

#[test]
fn unknown_columns_can_be_dropped_on_request() {
    let dir = tempfile::tempdir().unwrap();
    let exp = dir.path().join("tm.csv");
    let units = ",[mph],[deg],[deg],[deg],[deg],[mm],[mm],[mph],[deg],[deg],[rpm],[deg],";
    std::fs::write(&exp, format!("{TM_HEAD},Wobble\n{units}\n{TM_ROW},3\n")).unwrap();
    let out = dir.path().join("s.csv");
    let res = smash(&[
        "import",
        "--format",
        "trackman",
        exp.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--impact-offset-positive",
        "toe",
        "--ignore-unknown-columns",
    ]);
    ok(&res);
    assert!(String::from_utf8_lossy(&res.stderr)
        .contains("not used by the TrackMan format (left in the export): Wobble"));
    // Spin rate 2600 at axis −3°: backspin = 2600 cos 3°, sidespin = −2600 sin 3° (draw spin).
    let text = std::fs::read_to_string(&out).unwrap();
    let mut rdr = csv::Reader::from_reader(text.as_bytes());
    let h = rdr.headers().unwrap().clone();
    let r = rdr.records().next().unwrap().unwrap();
    let f = |n: &str| {
        r[h.iter().position(|c| c == n).unwrap()]
            .parse::<f64>()
            .unwrap()
    };
    assert!((f("backspin_rpm") - 2600.0 * 3f64.to_radians().cos()).abs() < 1e-9);
    assert!((f("sidespin_rpm") + 2600.0 * 3f64.to_radians().sin()).abs() < 1e-9);
    assert_eq!(f("impact_z_mm"), 3.0);
    assert_eq!(&r[h.iter().position(|c| c == "group").unwrap()], "Driver");
}
