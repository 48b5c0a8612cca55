//! One scale for comparing models (issue 29, item 1). In a `smash synth` world hiding an
//! anisotropic COR falloff (the user-defined law `cor − cy·y² − cz·z²` of
//! `configs/effects/cor_aniso.toml`, the COR falling ten times faster with height than toward
//! heel or toe), the right law must rank above the wrong,
//! isotropic `cor_radial` in AIC when each is fitted by its own `smash calibrate` run, and the
//! nominal model must score the same in every run: with the scales profiled and with the
//! instrument's noise given. `diagnose` scores its nominal model on the same scale.

use crate::cli_support;

use std::path::{Path, PathBuf};

use cli_support::{club, repo, s, smash, stderr};

/// A world hiding `cor_aniso` (`configs/effects/cor_aniso.toml`: COR falling with the squares
/// of the vertical and heel-toe distances, 2e-4 and 2e-5 per mm²) with synth's default noise,
/// made with `seed`; the definitions file and the shots file.
fn world(dir: &Path, seed: u64) -> (PathBuf, PathBuf) {
    let defs = repo("configs/effects/cor_aniso.toml");
    let cfg = dir.join(format!("world{seed}.toml"));
    std::fs::write(
        &cfg,
        format!(
            "club = {:?}\nseed = {seed}\n\n[[hidden]]\nname = \"cor_aniso\"\n\
             cy_per_mm2 = 2e-4\ncz_per_mm2 = 2e-5\n",
            club()
        ),
    )
    .unwrap();
    let shots = dir.join(format!("world{seed}.csv"));
    let o = smash(&[
        "synth",
        "--config",
        s(&cfg),
        "--effect-defs",
        s(&defs),
        "--out",
        s(&shots),
    ]);
    assert!(o.status.success(), "synth: {}", stderr(&o));
    (defs, shots)
}

/// `smash calibrate --effects EFFECTS --json` with `extra` flags on the world; its report.
fn calibrate(defs: &Path, shots: &Path, effects: &str, extra: &[&str]) -> serde_json::Value {
    let club = club();
    let mut args = vec![
        "calibrate",
        "--club",
        &club,
        "--shots",
        s(shots),
        "--effect-defs",
        s(defs),
        "--effects",
        effects,
        "--json",
    ];
    args.extend(extra);
    let o = smash(&args);
    assert!(o.status.success(), "calibrate {effects}: {}", stderr(&o));
    serde_json::from_slice(&o.stdout).unwrap()
}

fn num(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

#[test]
fn the_right_law_outranks_the_wrong_one_across_separate_calibrate_runs() {
    let dir = tempfile::tempdir().unwrap();
    for seed in [1, 2, 3] {
        let (defs, shots) = world(dir.path(), seed);
        for (extra, kind, k_nominal) in [
            (&[][..], "profiled", 5),
            (&["--instrument", "camera"][..], "given", 0),
        ] {
            let right = calibrate(&defs, &shots, "cor_aniso", extra);
            let wrong = calibrate(&defs, &shots, "cor_radial", extra);
            let (lr, lw) = (&right["likelihood"], &wrong["likelihood"]);
            assert_eq!(lr["scales"], kind, "{lr}");
            assert_eq!(lw["scales"], kind, "{lw}");
            // The nominal model scores the same in both runs, to the last bit.
            let nominal = num(&lr["nominal"]["minus_2_ln_l"]);
            assert_eq!(
                nominal,
                num(&lw["nominal"]["minus_2_ln_l"]),
                "seed {seed} {kind}"
            );
            assert_eq!(lr["nominal"]["k"], k_nominal);
            assert_eq!(lr["calibrated"]["k"], k_nominal + 2);
            assert_eq!(lw["calibrated"]["k"], k_nominal + 1);
            // The right law ranks above the wrong one, and both above the nominal model.
            let (aic_r, aic_w) = (num(&right["aic"]), num(&wrong["aic"]));
            eprintln!(
                "seed {seed}, scales {kind}: AIC nominal {:.1}, cor_radial {aic_w:.1}, \
                 cor_aniso {aic_r:.1}; chi2 (own scales) cor_radial {:.1}, cor_aniso {:.1}",
                num(&lr["nominal"]["aic"]),
                num(&wrong["chi2"]),
                num(&right["chi2"]),
            );
            assert_eq!(aic_r, num(&lr["calibrated"]["aic"]));
            assert!(aic_r < aic_w, "seed {seed} {kind}: {aic_r} vs {aic_w}");
            assert!(aic_w < num(&lr["nominal"]["aic"]), "seed {seed} {kind}");
            assert!(
                num(&right["bic"]) < num(&wrong["bic"]),
                "seed {seed} {kind}"
            );
            // Given scales are the instrument's, the same in both runs; profiled ones are each
            // model's own (the right law's ball-speed scale is the smaller).
            let speed = |l: &serde_json::Value, m: &str| num(&l[m]["scales"]["ball_speed_mph"]);
            if kind == "given" {
                assert_eq!(speed(lr, "calibrated"), speed(lw, "calibrated"));
            } else {
                assert!(speed(lr, "calibrated") < speed(lw, "calibrated"));
            }
        }
    }
}

/// The text report prints the table, the scales and how they were set; a noise file that makes
/// a component's scale zero is refused in one line.
#[test]
fn the_text_report_says_how_the_models_were_scored() {
    let dir = tempfile::tempdir().unwrap();
    let (defs, shots) = world(dir.path(), 4);
    let club = club();
    let base = [
        "calibrate",
        "--club",
        &club,
        "--shots",
        s(&shots),
        "--effect-defs",
        s(&defs),
        "--effects",
        "cor_aniso",
    ];
    let o = smash(&base);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.contains("noise scales PROFILED"), "{text}");
    assert!(text.contains("scales (nominal): ball_speed_mph"), "{text}");
    assert!(
        text.contains("scales (calibrated): ball_speed_mph"),
        "{text}"
    );
    for line in text.lines().filter(|l| !l.contains('|')) {
        assert!(line.chars().count() < 100, "too long: {line}");
    }
    let row = |name: &str| {
        text.lines()
            .find(|l| l.starts_with(name))
            .unwrap_or_else(|| panic!("no row {name}: {text}"))
            .split_whitespace()
            .skip(1)
            .map(|x| x.parse::<f64>().unwrap())
            .collect::<Vec<_>>()
    };
    let (nominal, calibrated) = (row("nominal "), row("calibrated "));
    assert_eq!(nominal[0], 5.0);
    assert_eq!(calibrated[0], 7.0);
    assert!(calibrated[2] < nominal[2], "{text}");

    let noise = dir.path().join("noise.toml");
    // No launch noise on ball speed and no delivery noise: a zero scale.
    let delivery: String = [
        "club_speed_mph",
        "attack_angle_deg",
        "club_path_deg",
        "dynamic_loft_deg",
        "face_angle_deg",
        "lie_tilt_deg",
        "club_omega_x_rad_s",
        "club_omega_y_rad_s",
        "club_omega_z_rad_s",
        "impact_y_mm",
        "impact_z_mm",
    ]
    .iter()
    .map(|k| format!("{k} = 0\n"))
    .collect();
    std::fs::write(
        &noise,
        format!("[noise]\n[noise.delivery]\n{delivery}[noise.launch]\nball_speed_mph = 0\n"),
    )
    .unwrap();
    let mut args = base.to_vec();
    args.extend(["--noise", s(&noise)]);
    let o = smash(&args);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(err.contains("the noise of ball_speed_mph is 0"), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
}

/// diagnose's nominal model, scored with profiled scales, is calibrate's nominal model: the
/// same number in both commands; every step's model and the final one are on that scale.
#[test]
fn diagnose_scores_its_models_on_calibrates_scale() {
    let dir = tempfile::tempdir().unwrap();
    let (defs, shots) = world(dir.path(), 5);
    let cal = calibrate(&defs, &shots, "cor_aniso", &[]);
    let club = club();
    let o = smash(&[
        "diagnose",
        "--club",
        &club,
        "--shots",
        s(&shots),
        "--effect-defs",
        s(&defs),
        "--candidates",
        "cor_aniso,cor_radial,cor_speed",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let d: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let l = &d["likelihood"];
    assert_eq!(l["scales"], "profiled");
    assert_eq!(
        num(&l["nominal"]["minus_2_ln_l"]),
        num(&cal["likelihood"]["nominal"]["minus_2_ln_l"])
    );
    // Each step that adds an effect lowers -2 ln L; the final model scores below the nominal.
    let mut last = num(&l["nominal"]["minus_2_ln_l"]);
    for st in d["steps"].as_array().unwrap() {
        let now = num(&st["fit"]["minus_2_ln_l"]);
        if !st["selected"].is_null() {
            assert!(now < last, "{st}");
        }
        last = now;
    }
    assert!(num(&l["final"]["aic"]) < num(&l["nominal"]["aic"]));
    assert_eq!(d["selected"][0], "cor_aniso", "{}", d["selected"]);
}
