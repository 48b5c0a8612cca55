//! User-defined effects through the command line: `synth --effect-defs` hides one, `diagnose`
//! ranks it first beside the library (and selects nothing in the null world), `calibrate`
//! writes its definition into the calibrated club, which `predict` and `run` then read alone;
//! a value out of range at evaluation names the shot; an undefined effect is refused.

use crate::cli_support;

use std::path::{Path, PathBuf};

use smash::effects::EffectKind;

use cli_support::{repo, smash};

fn example_defs() -> PathBuf {
    repo("configs/effects/example_effects.toml")
}

// ---------------------------------------------------------------------------------------------
// The commands.

fn ok(o: &std::process::Output, what: &str) {
    assert!(
        o.status.success(),
        "{what}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

fn synth_world(dir: &Path, name: &str, hidden: &str, seed: u64) -> PathBuf {
    let cfg = dir.join(format!("{name}.toml"));
    let text = format!(
        "club = {:?}\nseed = {seed}\n{hidden}\n",
        repo("configs/clubs/paper_driver.toml").to_str().unwrap()
    );
    std::fs::write(&cfg, text).unwrap();
    let shots = dir.join(format!("{name}.csv"));
    synth(&cfg, &shots);
    shots
}

/// `smash synth --config CONFIG --effect-defs <examples> --out SHOTS`, which must succeed.
fn synth(config: &Path, shots: &Path) {
    let o = smash(&[
        "synth",
        "--config",
        config.to_str().unwrap(),
        "--effect-defs",
        example_defs().to_str().unwrap(),
        "--out",
        shots.to_str().unwrap(),
    ]);
    ok(&o, "synth");
}

/// `smash COMMAND --club <paper driver> --shots SHOTS --effect-defs <examples> --json`, which
/// must succeed; its JSON report.
fn json_report(command: &str, shots: &Path) -> serde_json::Value {
    let o = smash(&[
        command,
        "--club",
        repo("configs/clubs/paper_driver.toml").to_str().unwrap(),
        "--shots",
        shots.to_str().unwrap(),
        "--effect-defs",
        example_defs().to_str().unwrap(),
        "--json",
    ]);
    ok(&o, command);
    serde_json::from_slice(&o.stdout).unwrap()
}

#[test]
fn diagnose_ranks_a_hidden_user_effect_first_and_selects_nothing_in_the_null_world() {
    let dir = tempfile::tempdir().unwrap();
    // The shipped world (configs/synth/cor_oblique_world.toml: b = 0.003 s/m, seed 5).
    let shots = dir.path().join("oblique.csv");
    synth(&repo("configs/synth/cor_oblique_world.toml"), &shots);
    let d = json_report("diagnose", &shots);
    let selected: Vec<&str> = d["selected"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(selected.first(), Some(&"cor_oblique"), "{selected:?}");
    // Ranked beside the library: its cross-validated error is below every library candidate's.
    let step = &d["steps"][0];
    let mut best_library = f64::INFINITY;
    let mut ours = f64::NAN;
    for c in step["candidates"].as_array().unwrap() {
        let (name, cv) = (
            c["effect"].as_str().unwrap(),
            c["cv_chi2"].as_f64().unwrap(),
        );
        if name == "cor_oblique" {
            ours = cv;
        } else if EffectKind::from_name(name.split('@').next().unwrap()).is_some() {
            best_library = best_library.min(cv);
        }
    }
    eprintln!("cv chi2: cor_oblique {ours}, best library candidate {best_library}");
    assert!(ours < best_library, "{ours} vs {best_library}");
    let est = &d["estimates"][0];
    let (b, se) = (
        est["value"].as_f64().unwrap(),
        est["stderr"].as_f64().unwrap(),
    );
    assert!((b - 0.003).abs() < 3.0 * se, "b = {b} ± {se}");

    // compare hints at it: the strongest ball-speed finding names cor_oblique.
    let c = json_report("compare", &shots);
    let speed = c["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["component"] == "ball_speed_mph")
        .expect("a ball-speed finding");
    assert!(
        speed["hints"]
            .as_array()
            .unwrap()
            .iter()
            .any(|h| h.as_str().unwrap().starts_with("cor_oblique (user-defined")),
        "{speed}"
    );

    let null = synth_world(dir.path(), "null", "", 1);
    let d = json_report("diagnose", &null);
    assert_eq!(
        d["selected"].as_array().unwrap().len(),
        0,
        "{}",
        d["selected"]
    );
}

#[test]
fn calibrate_predict_and_run_take_user_effects() {
    let dir = tempfile::tempdir().unwrap();
    let shots = synth_world(
        dir.path(),
        "loft",
        "[[hidden]]\nname = \"speed_loft\"\nk_deg = 0.8",
        9,
    );
    let defs = example_defs();
    let out = dir.path().join("cal.toml");
    let o = smash(&[
        "calibrate",
        "--club",
        repo("configs/clubs/paper_driver.toml").to_str().unwrap(),
        "--shots",
        shots.to_str().unwrap(),
        "--effect-defs",
        defs.to_str().unwrap(),
        "--effects",
        "speed_loft",
        "--out-club",
        out.to_str().unwrap(),
    ]);
    ok(&o, "calibrate");
    let cal = std::fs::read_to_string(&out).unwrap();
    assert!(
        cal.contains("[[define_effect]]") && cal.contains("name = \"speed_loft\""),
        "{cal}"
    );
    // The calibrated club is usable alone: predict without --effect-defs.
    let o = smash(&[
        "predict",
        "--club",
        out.to_str().unwrap(),
        "--speed-mph",
        "110",
        "--loft-deg",
        "12",
    ]);
    ok(&o, "predict");
    // A study sweeps the calibrated club (its user effect on the kernel).
    let study = dir.path().join("study.toml");
    std::fs::write(
        &study,
        format!(
            "[study]\nname = \"u\"\nclub = {:?}\noutputs = [\"ball_speed_mph\"]\n\n[delivery]\nclub_speed_mph = 110.0\ndynamic_loft_deg = 12.0\n\n[grid]\ny_mm = {{ from = -10.0, to = 10.0, count = 3 }}\nz_mm = {{ from = -10.0, to = 10.0, count = 3 }}\n",
            out.to_str().unwrap()
        ),
    )
    .unwrap();
    let o = smash(&[
        "run",
        study.to_str().unwrap(),
        "--out",
        dir.path().join("study_out").to_str().unwrap(),
    ]);
    ok(&o, "run");
}

#[test]
fn a_value_out_of_range_names_the_shot_and_an_undefined_effect_is_refused() {
    // The command names the shot too.
    let dir = tempfile::tempdir().unwrap();
    let defs = dir.path().join("nan.toml");
    std::fs::write(
        &defs,
        "[[define_effect]]\nname = \"e_nan\"\nparams = []\ncor = \"cor * ln(club_speed_mph - 100) / ln(10)\"\n",
    )
    .unwrap();
    let club = dir.path().join("club.toml");
    let text = std::fs::read_to_string(repo("configs/clubs/paper_driver.toml")).unwrap();
    std::fs::write(&club, format!("{text}\n[[effect]]\nname = \"e_nan\"\n")).unwrap();
    let shots = dir.path().join("shots.csv");
    std::fs::write(
        &shots,
        "shot_id,club_speed_mph,attack_angle_deg,club_path_deg,dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm\n\
         fast,110,0,0,12,0,0,0\nslow,90,0,0,12,0,0,0\n",
    )
    .unwrap();
    // The shot the law has no value for is left out and counted, naming it, the effect and
    // the expression (one bad row does not sink the others); --strict refuses the file there.
    let pred = dir.path().join("pred.csv");
    let run = |strict: bool| {
        let mut args = vec![
            "predict",
            "--club",
            club.to_str().unwrap(),
            "--effect-defs",
            defs.to_str().unwrap(),
            "--shots",
            shots.to_str().unwrap(),
            "--out",
            pred.to_str().unwrap(),
        ];
        if strict {
            args.push("--strict");
        }
        smash(&args)
    };
    let o = run(false);
    let err = String::from_utf8_lossy(&o.stderr).replace("\n  ", " ");
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("left out 1 of 2 rows: a shot the club cannot solve")
            && err.contains("slow")
            && err.contains("e_nan")
            && err.contains("ln(club_speed_mph - 100)"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&pred).unwrap().lines().count(), 2);
    std::fs::remove_file(&pred).unwrap();
    let o = run(true);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("slow") && err.contains("e_nan") && err.contains("ln(club_speed_mph - 100)"),
        "{err}"
    );
    assert!(!pred.exists());
    // A club file naming a user effect nobody defined.
    let o = smash(&[
        "predict",
        "--club",
        club.to_str().unwrap(),
        "--speed-mph",
        "110",
        "--loft-deg",
        "12",
    ]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("unknown effect 'e_nan'") && err.contains("[[define_effect]]"),
        "{err}"
    );
}
