//! Honest reports, end to end: implausible values are stand-ins (not findings) in calibrate and
//! diagnose output, text and JSON; the noise-floor verdict is in every diagnose report and says
//! "noise" when only noise remains and names the structure when the model is wrong.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::smash;

fn repo(p: &str) -> String {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .join(p)
        .to_str()
        .unwrap()
        .to_owned()
}

/// A 300-shot world (10 golfers × 3 shafts × 10 swings) with `extra` TOML, written by synth.
fn world(dir: &Path, name: &str, seed: u64, extra: &str) -> PathBuf {
    let cfg = dir.join(format!("{name}.toml"));
    std::fs::write(
        &cfg,
        format!(
            "club = {:?}\nseed = {seed}\n\n[design]\ngolfers = 10\n\n{extra}\n",
            repo("configs/clubs/paper_driver.toml")
        ),
    )
    .unwrap();
    let shots = dir.join(format!("{name}.csv"));
    let o = smash(&[
        "synth",
        "--config",
        cfg.to_str().unwrap(),
        "--out",
        shots.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    shots
}

fn run_ok(args: &[&str]) -> String {
    let o = smash(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).unwrap()
}

#[test]
fn calibrate_marks_an_implausible_value_as_a_stand_in() {
    let dir = tempfile::tempdir().unwrap();
    let club = repo("configs/clubs/paper_driver.toml");
    // A 5 degree loft bias is beyond what a calibrated monitor shows (plausible ±3 deg): the
    // fit recovers it, and the report must call it a stand-in, not a finding.
    let biased = world(
        dir.path(),
        "loft5",
        41,
        "[[hidden]]\nname = \"loft_bias\"\ndeg = 5.0\n",
    );
    let calibrate = |s: &PathBuf, json: bool| {
        let mut a = vec![
            "calibrate",
            "--club",
            &club,
            "--shots",
            s.to_str().unwrap(),
            "--effects",
            "loft_bias",
        ];
        if json {
            a.push("--json");
        }
        run_ok(&a)
    };
    let j: serde_json::Value = serde_json::from_str(&calibrate(&biased, true)).unwrap();
    let p = &j["params"][0];
    assert!((p["value"].as_f64().unwrap() - 5.0).abs() < 0.3, "{p}");
    assert_eq!(p["plausible"], false, "{p}");
    assert!(
        p["stand_in"].as_str().unwrap().contains("behaves like"),
        "{p}"
    );
    assert!(j["aliases"].is_array());
    let t = calibrate(&biased, false);
    assert!(t.contains("stand-in, not a finding"), "{t}");
    assert!(t.contains("IMPLAUSIBLE"), "{t}");

    // A 1.5 degree bias is plausible: a finding, no stand-in.
    let small = world(
        dir.path(),
        "loft15",
        42,
        "[[hidden]]\nname = \"loft_bias\"\ndeg = 1.5\n",
    );
    let j: serde_json::Value = serde_json::from_str(&calibrate(&small, true)).unwrap();
    assert_eq!(j["params"][0]["plausible"], true);
    assert!(j["params"][0]["stand_in"].is_null());
    assert!(!calibrate(&small, false).contains("stand-in"));
}

#[test]
fn diagnose_reports_the_noise_floor_and_stops_at_it() {
    let dir = tempfile::tempdir().unwrap();
    let club = repo("configs/clubs/paper_driver.toml");
    // Nothing hidden: with the instruments known (synth's defaults are the camera class), what
    // remains is noise.
    let null = world(dir.path(), "null", 43, "");
    let j: serde_json::Value = serde_json::from_str(&run_ok(&[
        "diagnose",
        "--club",
        &club,
        "--shots",
        null.to_str().unwrap(),
        "--instrument",
        "camera",
        "--json",
    ]))
    .unwrap();
    let floor = &j["noise_floor"];
    assert_eq!(floor["structure_remains"], false, "{floor}");
    assert_eq!(floor["components"].as_array().unwrap().len(), 5);
    for c in floor["components"].as_array().unwrap() {
        let ratio = c["ratio"].as_f64().unwrap();
        assert!((0.85..1.15).contains(&ratio), "{c}");
        assert!(c["expected_sd"].as_f64().unwrap() > 0.0);
    }
    assert!(j["conclusion"]
        .as_str()
        .unwrap()
        .starts_with("what remains is noise"));
    assert!(
        j["selected"].as_array().unwrap().is_empty(),
        "{}",
        j["selected"]
    );

    // A COR that falls with speed, and no candidate allowed to explain it: structure remains
    // in ball speed, trending with club speed, and the report says so.
    let cor = world(
        dir.path(),
        "cor",
        44,
        "[[hidden]]\nname = \"cor_power\"\nq = 0.3\n",
    );
    let args = [
        "diagnose",
        "--club",
        &club,
        "--shots",
        cor.to_str().unwrap(),
        "--instrument",
        "camera",
        "--candidates",
        "face_bias",
    ];
    let mut json_args = args.to_vec();
    json_args.push("--json");
    let j: serde_json::Value = serde_json::from_str(&run_ok(&json_args)).unwrap();
    let speed = &j["noise_floor"]["components"][0];
    assert_eq!(speed["component"], "ball_speed_mph");
    assert_eq!(speed["structure"], true, "{speed}");
    assert_eq!(speed["trend"]["variable"], "club_speed_mph", "{speed}");
    let conclusion = j["conclusion"].as_str().unwrap();
    assert!(
        conclusion.contains("unexplained structure remains in ball_speed_mph"),
        "{conclusion}"
    );
    let t = run_ok(&args);
    assert!(t.contains("Noise floor"), "{t}");
    assert!(
        t.contains("unexplained structure remains in ball_speed_mph"),
        "{t}"
    );
}

#[test]
fn a_bad_noise_file_is_one_clear_line() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("noise.toml");
    std::fs::write(
        &f,
        "[noise]\ninstrument = \"camera\"\n[noise.launch]\nspin = 3.0\n",
    )
    .unwrap();
    let club = repo("configs/clubs/paper_driver.toml");
    let shots = world(dir.path(), "n", 45, "");
    let o = smash(&[
        "diagnose",
        "--club",
        &club,
        "--shots",
        shots.to_str().unwrap(),
        "--noise",
        f.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("noise.toml:4"), "{e}");
    assert!(e.contains("noise.launch.spin"), "{e}");
    assert!(e.contains("backspin_rpm"), "{e}");
}
