//! Say what was assumed (issue 29, item 4). Without `--noise` or `--instrument`, diagnose's
//! noise floor assumes the camera class; its conclusion (text, JSON, HTML) must then say that the
//! verdict rests on that assumption and give the observed-to-expected spread ratio of every
//! component. In a null world measured by instruments three times quieter than the class, the
//! ratios are well below 1 and the conclusion must say the assumed noise is too large to see
//! structure; in one twice as noisy, well above 1 and it must say structure or larger noise
//! remains. Given the noise, the note is absent.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::{club, s, smash, stderr};

/// A null world (the paper's driver, nothing hidden) whose instruments' noise is `factor` times
/// synth's defaults (the camera class) on every delivery variable and launch component.
fn world(dir: &Path, name: &str, factor: f64, seed: u64) -> PathBuf {
    // synth's default noise (configs/synth/README.md), the camera class's.
    let delivery = [
        ("club_speed_mph", 0.4),
        ("attack_angle_deg", 0.3),
        ("club_path_deg", 0.3),
        ("dynamic_loft_deg", 0.5),
        ("face_angle_deg", 0.3),
        ("lie_tilt_deg", 0.5),
        ("club_omega_x_rad_s", 0.5),
        ("club_omega_y_rad_s", 0.5),
        ("club_omega_z_rad_s", 0.5),
        ("impact_y_mm", 1.5),
        ("impact_z_mm", 1.5),
    ];
    let launch = [
        ("ball_speed_mph", 0.5),
        ("launch_angle_deg", 0.3),
        ("azimuth_deg", 0.5),
        ("backspin_rpm", 120.0),
        ("sidespin_rpm", 150.0),
    ];
    let table = |rows: &[(&str, f64)]| -> String {
        rows.iter()
            .map(|(k, v)| format!("{k} = {}\n", v * factor))
            .collect()
    };
    let cfg = dir.join(format!("{name}.toml"));
    std::fs::write(
        &cfg,
        format!(
            "club = {:?}\nseed = {seed}\n\n[noise.delivery]\n{}\n[noise.launch]\n{}",
            club(),
            table(&delivery),
            table(&launch)
        ),
    )
    .unwrap();
    let shots = dir.join(format!("{name}.csv"));
    let o = smash(&["synth", "--config", s(&cfg), "--out", s(&shots)]);
    assert!(o.status.success(), "synth: {}", stderr(&o));
    shots
}

/// `smash diagnose` on `shots` with `extra` flags (few candidates: the conclusion is the
/// subject); stdout as text.
fn diagnose(shots: &Path, extra: &[&str]) -> String {
    let club = club();
    let mut args = vec![
        "diagnose",
        "--club",
        &club,
        "--shots",
        s(shots),
        "--candidates",
        "cor_speed,loft_bias",
        "--exact-impact-locations",
    ];
    args.extend(extra);
    let o = smash(&args);
    assert!(o.status.success(), "diagnose: {}", stderr(&o));
    String::from_utf8(o.stdout).unwrap()
}

/// The conclusion's ratios as printed, checked against the JSON's noise floor to 2 decimals.
fn check_ratios(j: &serde_json::Value, conclusion: &str) -> Vec<f64> {
    j["noise_floor"]["components"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| {
            let (name, ratio) = (
                c["component"].as_str().unwrap(),
                c["ratio"].as_f64().unwrap(),
            );
            let shown = format!("{name} {ratio:.2}");
            assert!(conclusion.contains(&shown), "{shown} not in: {conclusion}");
            ratio
        })
        .collect()
}

#[test]
fn an_assumed_noise_too_large_is_said_and_so_is_one_too_small() {
    let dir = tempfile::tempdir().unwrap();
    let quiet = world(dir.path(), "quiet", 1.0 / 3.0, 11);
    let report = dir.path().join("quiet.html");
    let j: serde_json::Value =
        serde_json::from_str(&diagnose(&quiet, &["--json", "--report", s(&report)])).unwrap();
    let c = j["conclusion"].as_str().unwrap();
    assert!(
        c.contains("This verdict rests on the ASSUMED camera instrument noise"),
        "{c}"
    );
    assert_eq!(j["noise_floor"]["assumed"], true);
    let ratios = check_ratios(&j, c);
    eprintln!("quiet world: ratios {ratios:?}");
    assert!(ratios.iter().all(|r| *r < 0.9), "{ratios:?}");
    for comp in j["noise_floor"]["components"].as_array().unwrap() {
        assert_eq!(comp["spread_band"], "well_below", "{comp}");
    }
    assert!(
        c.contains(
            "well below 1 (under 0.90) in ball_speed_mph, launch_angle_deg, azimuth_deg, \
             backspin_rpm, sidespin_rpm: the assumed noise is too large for these errors, so \
             the test cannot see structure there"
        ),
        "{c}"
    );
    assert!(!c.contains("well above 1"), "{c}");
    // The HTML report shows the same conclusion.
    let html = std::fs::read_to_string(&report).unwrap();
    assert!(
        html.contains("ASSUMED camera instrument noise"),
        "no note in the HTML"
    );

    // The text report: the same words, wrapped under 100 columns, and the floor's header says it.
    let text = diagnose(&quiet, &[]);
    assert!(text.contains("(that noise is ASSUMED: no --noise or --instrument was given)"));
    let conclusion: String = text
        .lines()
        .skip_while(|l| !l.starts_with("Conclusion: "))
        .take_while(|l| !l.is_empty())
        .map(str::trim)
        .collect::<Vec<_>>()
        .join(" ");
    assert_eq!(conclusion, format!("Conclusion: {c}"));
    for line in text.lines().skip_while(|l| !l.starts_with("Conclusion: ")) {
        if line.is_empty() {
            break;
        }
        assert!(line.chars().count() < 100, "too long: {line}");
    }

    // Given the noise (the same class), no assumption to report.
    let j: serde_json::Value =
        serde_json::from_str(&diagnose(&quiet, &["--json", "--instrument", "camera"])).unwrap();
    let c = j["conclusion"].as_str().unwrap();
    assert!(!c.contains("ASSUMED"), "{c}");
    assert_eq!(j["noise_floor"]["assumed"], false);

    // Twice the class's noise: the ratios are well above 1, and the conclusion says what that
    // can mean.
    let loud = world(dir.path(), "loud", 2.0, 12);
    let j: serde_json::Value = serde_json::from_str(&diagnose(&loud, &["--json"])).unwrap();
    let c = j["conclusion"].as_str().unwrap();
    let ratios = check_ratios(&j, c);
    eprintln!("loud world: ratios {ratios:?}");
    assert!(ratios.iter().all(|r| *r > 1.1), "{ratios:?}");
    assert!(
        c.contains("structure remains there, or the instruments are noisier than assumed"),
        "{c}"
    );
    assert!(!c.contains("well below 1"), "{c}");
}
