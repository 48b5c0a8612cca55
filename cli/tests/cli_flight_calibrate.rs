//! `smash flight --calibrate TERMS --calibrate-by ball|session`: a range ball with 8 % more
//! drag hidden among premium balls (synthetic flights, no noise) is recovered per ball and per
//! session, each part's shots flown with its own scaling; refusals name what is missing.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::{s, smash, stderr};
use smash::flight::calibrate::Scaled;
use smash::flight::integrate::fly_with;
use smash::flight::{AeroModel, FlightConfig, FlightLaunch};

/// The hidden drag scaling of the range balls.
const RANGE_DRAG: f64 = 1.08;

/// 24 launches of each ball (driver to wedge), flown with the default model and the ball's
/// drag; written with `ball_type` and a `date` (one session per ball).
fn shots(dir: &Path, with_ball: bool) -> PathBuf {
    let cfg = FlightConfig::default();
    let aero = AeroModel::default();
    let mut csv = String::from(
        "shot_id,date,ball_type,ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,\
         sidespin_rpm,carry_yd,apex_yd,land_angle_deg\n",
    );
    for (ball, drag, day) in [
        ("premium", 1.0, "2026-05-01"),
        ("range", RANGE_DRAG, "2026-05-02"),
    ] {
        let model = Scaled {
            inner: &aero,
            drag,
            lift: 1.0,
            moment: 1.0,
        };
        let launches: Vec<(f64, f64, f64)> = (0..24)
            .map(|k| {
                let t = k as f64 / 23.0;
                (160.0 - 70.0 * t, 10.0 + 18.0 * t, 2500.0 + 6500.0 * t)
            })
            .collect();
        let ls: Vec<FlightLaunch> = launches
            .iter()
            .map(|&(v, a, w)| FlightLaunch::from_file_units(v, a, 0.0, w, 0.0))
            .collect();
        for (k, (f, (v, a, w))) in fly_with(&cfg, &model, &ls)
            .iter()
            .zip(&launches)
            .enumerate()
        {
            let f = f.as_ref().unwrap();
            csv.push_str(&format!(
                "{ball}{k},{day} 10:00,{ball},{v},{a},0,{w},0,{},{},{}\n",
                f.carry_yd(),
                f.apex_yd(),
                f.land_angle_deg()
            ));
        }
    }
    if !with_ball {
        csv = csv.replace(",ball_type,", ",kind,");
    }
    let p = dir.join(if with_ball { "balls.csv" } else { "kinds.csv" });
    std::fs::write(&p, csv).unwrap();
    p
}

/// `smash flight --shots SHOTS --out OUT` with `extra` flags.
fn flight(shots: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec!["flight", "--shots", s(shots), "--out", s(out)];
    args.extend_from_slice(extra);
    smash(&args)
}

/// The drag scaling printed for `part` (`ball_type 'range'`, `date '2026-05-02'`).
fn drag_of(err: &str, part: &str) -> f64 {
    let line = err
        .lines()
        .find(|l| l.contains(&format!("for {part} on")))
        .unwrap_or_else(|| panic!("no calibration for {part}:\n{err}"));
    let x = line.split("drag x").nth(1).unwrap();
    x.split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn a_range_ball_s_drag_is_recovered_per_ball_and_per_session() {
    let dir = tempfile::tempdir().unwrap();
    let shots = shots(dir.path(), true);
    let out = dir.path().join("f.csv");
    for (by, premium, range) in [
        ("ball", "ball_type 'premium'", "ball_type 'range'"),
        ("session", "date '2026-05-01'", "date '2026-05-02'"),
    ] {
        let o = flight(&shots, &out, &["--calibrate", "drag", "--calibrate-by", by]);
        let err = stderr(&o);
        assert!(o.status.success(), "{err}");
        let (p, r) = (drag_of(&err, premium), drag_of(&err, range));
        assert!(
            (p - 1.0).abs() < 1e-3 && (r - RANGE_DRAG).abs() < 1e-3,
            "{err}"
        );
        // Each part flown with its own scaling: the flights are the measured ones.
        let text = std::fs::read_to_string(&out).unwrap();
        let mut rows = text.lines();
        let head: Vec<&str> = rows.next().unwrap().split(',').collect();
        let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
        let (m, p) = (col("carry_yd"), col("pred_carry_yd"));
        for row in rows {
            let c: Vec<f64> = row
                .split(',')
                .map(|x| x.parse().unwrap_or(f64::NAN))
                .collect();
            assert!((c[m] - c[p]).abs() < 0.05, "{by}: {row}");
        }
    }
}

#[test]
fn calibrate_by_refusals() {
    let dir = tempfile::tempdir().unwrap();
    let shots = shots(dir.path(), false);
    let out = dir.path().join("f.csv");
    let o = flight(
        &shots,
        &out,
        &["--calibrate", "drag", "--calibrate-by", "ball"],
    );
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(
        err.contains("--calibrate-by ball:") && err.contains("has no ball_type column"),
        "{err}"
    );
    assert!(!out.exists());
    let o = flight(&shots, &out, &["--calibrate-by", "session"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--calibrate"), "{}", stderr(&o));
}

/// The shots of [`shots`] with a `flight_modelled` column: the range balls' flights marked as
/// the vendor's model (`range`), the premium balls' as `premium` (cells as written).
fn flagged(dir: &Path, premium: &str, range: &str) -> PathBuf {
    let text = std::fs::read_to_string(shots(dir, true)).unwrap();
    let mut lines = text.lines();
    let mut out = format!("{},flight_modelled\n", lines.next().unwrap());
    for l in lines {
        let flag = if l.starts_with("range") {
            range
        } else {
            premium
        };
        out.push_str(&format!("{l},{flag}\n"));
    }
    let p = dir.join("flagged.csv");
    std::fs::write(&p, out).unwrap();
    p
}

/// The drag scaling of a single calibration line.
fn drag(err: &str) -> f64 {
    let x = err
        .split("drag x")
        .nth(1)
        .unwrap_or_else(|| panic!("{err}"));
    x.split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn the_vendors_modelled_flights_are_not_fitted_to_beside_tracked_ones() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("f.csv");
    // Unflagged, the fit blends the premium balls' drag (1) with the range balls' (1.08).
    let o = flight(
        &flagged(dir.path(), "0", "0"),
        &out,
        &["--calibrate", "drag"],
    );
    let blended = drag(&stderr(&o));
    assert!(blended > 1.02 && blended < 1.06, "{}", stderr(&o));
    // The range balls' flights marked as the vendor's model: the fit takes the tracked ones.
    let o = flight(
        &flagged(dir.path(), "0", "1"),
        &out,
        &["--calibrate", "drag"],
    );
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!((drag(&err) - 1.0).abs() < 1e-3, "{err}");
    assert!(
        err.contains("left out of the fit 24 shot(s) whose carry, apex and landing are the")
            && err.contains("fitted to the 24 other(s)")
            && err.contains("on 72 measured value(s)"),
        "{err}"
    );
    // Every shot modelled: fitted, and said to be a model matched to a model.
    let o = flight(
        &flagged(dir.path(), "1", "true"),
        &out,
        &["--calibrate", "drag"],
    );
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    let flat = err.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        flat.contains("all 48 shot(s) fitted to have the vendor's flight model")
            && flat.contains("on 144 value(s) of the vendor's flight model (flight_modelled = 1)"),
        "{err}"
    );
    // Per ball, each part decides: the premium balls' tracked flights, the range balls' all
    // modelled (fitted, with the caveat for that part).
    let o = flight(
        &flagged(dir.path(), "0", "1"),
        &out,
        &["--calibrate", "drag", "--calibrate-by", "ball"],
    );
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    let flat = err.split_whitespace().collect::<Vec<_>>().join(" ");
    // The range part's calibration line wraps: read the scalings from the joined text.
    let drag_for = |part: &str| drag(flat.split(&format!("for {part} on")).nth(1).unwrap());
    let (p, r) = (
        drag_for("ball_type 'premium'"),
        drag_for("ball_type 'range'"),
    );
    assert!(
        (p - 1.0).abs() < 1e-3 && (r - RANGE_DRAG).abs() < 1e-3,
        "{err}"
    );
    assert!(
        flat.contains("all 24 shot(s) fitted to for ball_type 'range' have the vendor's"),
        "{err}"
    );
    // --diagnose works on the rows fitted to (their folds, penalty and count).
    let o = flight(&flagged(dir.path(), "0", "1"), &out, &["--diagnose"]);
    let err = stderr(&o);
    assert!(
        o.status.success() && err.contains("flight diagnose: 24 shots"),
        "{err}"
    );
    // --strict refuses a flag that is not one, at its line.
    let o = flight(
        &flagged(dir.path(), "0", "yes"),
        &out,
        &["--calibrate", "drag", "--strict"],
    );
    let err = stderr(&o);
    assert!(
        !o.status.success()
            && err.contains("flagged.csv:26: column 'flight_modelled': 'yes' is not a flag"),
        "{err}"
    );
    // A flag that is not one leaves its row out of the fit, counted; so does
    // --diagnose, and the JSON carries the notes.
    let o = flight(
        &flagged(dir.path(), "0", "2"),
        &out,
        &["--diagnose", "--json"],
    );
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let warnings = json["warnings"].to_string();
    assert!(
        warnings.contains("left out of the fit 24 shot(s) whose flight_modelled is not a flag")
            && warnings.contains("the first: '2'"),
        "{warnings}"
    );
    assert_eq!(json["errors"]["modelled"], 0);
}

#[test]
fn a_comparison_with_modelled_flights_says_two_models_are_compared() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("f.csv");
    let o = flight(&flagged(dir.path(), "0", "1"), &out, &[]);
    let flat = stderr(&o).split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        flat.contains("flight: 24 of the 48 shots compared have the vendor's flight model")
            && flat.contains("two models are compared"),
        "{flat}"
    );
    let o = flight(&flagged(dir.path(), "0", "1"), &out, &["--json"]);
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(json["errors"]["modelled"], 24);
    assert_eq!(json["errors"]["compared"], 48);
    // Without modelled flights, no such note.
    let o = flight(&flagged(dir.path(), "0", ""), &out, &[]);
    assert!(
        !stderr(&o).contains("vendor's flight model"),
        "{}",
        stderr(&o)
    );
    // A cell that is not a flag is compared as tracked, and said so.
    let o = flight(&flagged(dir.path(), "0", "2"), &out, &[]);
    let flat = stderr(&o).split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        flat.contains("24 of the 48 shots compared have a flight_modelled cell that is not a flag"),
        "{flat}"
    );
    // --json carries the scalings per part.
    let o = flight(
        &flagged(dir.path(), "0", "1"),
        &out,
        &["--calibrate", "drag", "--calibrate-by", "ball", "--json"],
    );
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let parts = json["calibration"].as_array().unwrap();
    assert_eq!(parts.len(), 2, "{json}");
    assert_eq!(parts[1]["part"], "ball_type 'range'");
    assert_eq!(parts[1]["modelled"], true);
    assert_eq!(parts[0]["values"], 72);
    let range = parts[1]["terms"][0]["scale"].as_f64().unwrap();
    assert!((range - RANGE_DRAG).abs() < 1e-3, "{json}");
    // The HTML page carries the caveat too.
    let page = dir.path().join("r.html");
    let o = flight(
        &flagged(dir.path(), "0", "1"),
        &out,
        &["--report", s(&page)],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(
        html.contains("two models are compared"),
        "no caveat in the page"
    );
}
