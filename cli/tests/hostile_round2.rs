//! The second hostile pass (issue 32): user-effect expressions nested or sized to crash the
//! parser, non-finite constants and values named in words, and the messages that named a
//! derived quantity instead of the culprit. Outputs written all or nothing are in
//! `output_plan.rs`; signals in `signals.rs`.

mod cli_support;
#[path = "../../tests/common/mod.rs"]
mod common;

use std::path::{Path, PathBuf};

use cli_support::{club, repo, s, smash, stderr};

const SHOTS_HEAD: &str = "shot_id,club_speed_mph,attack_angle_deg,club_path_deg,\
                          dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm";

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn definition(name: &str, cor: &str) -> String {
    format!("[[define_effect]]\nname = \"{name}\"\nparams = []\ncor = \"{cor}\"\n")
}

/// Item 4: an expression nested 20 000 deep (parentheses, `abs(`, unary minus), in
/// `--effect-defs` or in a club file, is one line naming the file, key and limit; the parser
/// used to overflow its stack (exit 134).
#[test]
fn a_deeply_nested_expression_is_refused_not_a_stack_overflow() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let paper = std::fs::read_to_string(repo("configs/clubs/paper_driver.toml")).unwrap();
    for (k, open, close) in [("p", "(", ")"), ("a", "abs(", ")"), ("m", "-", "")] {
        let expr = format!("{}cor{}", open.repeat(20_000), close.repeat(20_000));
        let defs = write(d, &format!("{k}.toml"), &definition("e_deep", &expr));
        let o = smash(&[
            "predict",
            "--club",
            &club(),
            "--effect-defs",
            s(&defs),
            "--speed-mph",
            "100",
            "--loft-deg",
            "12",
        ]);
        common::assert_refused(&o, &[&format!("{k}.toml:4"), "e_deep", "nested too deeply"]);
        assert!(stderr(&o).len() < 600, "{} characters", stderr(&o).len());
        // The same definition in a club file.
        let club_file = write(
            d,
            &format!("club_{k}.toml"),
            &format!("{paper}\n{}", definition("e_deep", &expr)),
        );
        let o = smash(&[
            "predict",
            "--club",
            s(&club_file),
            "--speed-mph",
            "100",
            "--loft-deg",
            "12",
        ]);
        common::assert_refused(&o, &[&format!("club_{k}.toml:"), "nested too deeply"]);
    }
}

/// Items 7 and 11: a literal beyond the largest double (`1e400`) is refused when the file is
/// read, not at the first shot; a 100 kB expression is refused with a short line; a value an
/// expression gives at a shot is named in words, never as `inf` or `NaN`.
#[test]
fn constants_sizes_and_values_of_expressions_are_checked_and_named_in_words() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let run = |defs: &Path, extra: &[&str]| {
        let mut args = vec!["predict", "--club", "X", "--effect-defs", s(defs)];
        args.extend_from_slice(extra);
        let c = club();
        let args: Vec<&str> = args
            .iter()
            .map(|a| if *a == "X" { c.as_str() } else { a })
            .collect();
        smash(&args)
    };
    let one = ["--speed-mph", "100", "--loft-deg", "12"];
    // Refused at read even though no command names the effect.
    let big = write(d, "big.toml", &definition("e_big", "cor * 1e400"));
    let o = run(&big, &one);
    common::assert_refused(&o, &["big.toml:4", "1e400 is beyond the largest"]);
    let long = write(d, "long.toml", &definition("e_long", &"cor+".repeat(25_000)));
    let o = run(&long, &one);
    common::assert_refused(&o, &["long.toml:4", "e_long", "(100000 characters)"]);
    assert!(stderr(&o).len() < 400, "{} characters", stderr(&o).len());
    // At a shot: an overflow and an undefined operation, in words.
    let paper = std::fs::read_to_string(repo("configs/clubs/paper_driver.toml")).unwrap();
    let shots = write(
        d,
        "shots.csv",
        &format!("{SHOTS_HEAD}\nfast,110,0,0,12,0,0,0\n"),
    );
    for (name, cor, words) in [
        ("e_over", "cor * exp(club_speed_mph * 10)", "too large for a double"),
        ("e_under", "-cor * exp(club_speed_mph * 10)", "negative value too large"),
        ("e_nan", "cor * ln(club_speed_mph - 200)", "gave no number"),
    ] {
        let defs = write(d, &format!("{name}.toml"), &definition(name, cor));
        let club_file = write(
            d,
            "club.toml",
            &format!("{paper}\n[[effect]]\nname = \"{name}\"\n"),
        );
        let out = d.join("pred.csv");
        let o = smash(&[
            "predict",
            "--club",
            s(&club_file),
            "--effect-defs",
            s(&defs),
            "--shots",
            s(&shots),
            "--out",
            s(&out),
        ]);
        common::assert_refused(&o, &["shots.csv:2", "shot 'fast'", name, words]);
        assert!(!out.exists());
    }
}
