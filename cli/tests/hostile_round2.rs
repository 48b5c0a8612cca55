//! The second hostile pass (issue 32): user-effect expressions nested or sized to crash the
//! parser, non-finite constants and values named in words, and the messages that named a
//! derived quantity instead of the culprit. Outputs written all or nothing are in
//! `output_plan.rs`; signals in `signals.rs`.

use crate::cli_support;
use crate::common;

use std::path::Path;

use cli_support::{club, repo, s, smash, stderr, write};

const SHOTS_HEAD: &str = "shot_id,club_speed_mph,attack_angle_deg,club_path_deg,\
                          dynamic_loft_deg,face_angle_deg,impact_y_mm,impact_z_mm";

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
        // 20 000 deep is longer than an expression may be (refused before it is tokenized);
        // 500 deep is short enough to reach the parser, which refuses it before recursing.
        let expr = format!("{}cor{}", open.repeat(20_000), close.repeat(20_000));
        let defs = write(d, "deep.toml", &definition("e_deep", &expr));
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
        common::assert_refused(&o, &["deep.toml:4", "e_deep", "expression too long"]);
        let expr = format!("{}cor{}", open.repeat(500), close.repeat(500));
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
    let long = write(
        d,
        "long.toml",
        &definition("e_long", &"cor+".repeat(25_000)),
    );
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
        (
            "e_over",
            "cor * exp(club_speed_mph * 10)",
            "too large for a double",
        ),
        (
            "e_under",
            "-cor * exp(club_speed_mph * 10)",
            "negative value too large",
        ),
        (
            "e_undefined",
            "cor * ln(club_speed_mph - 200)",
            "gave no number",
        ),
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

/// Item 9: a launch file naming a column twice is refused (the first was flown); a ball speed of
/// 1e-300 mph (which "flew" to a land angle of −12°) and a run-out deceleration of 1e-300 m/s²
/// (a 304-character total) are refused, naming the column or flag. Item 11: an empty or
/// semicolon-separated launch file is told so, not that it lacks `pred_ball_speed_mph`.
#[test]
fn launch_files_and_ground_options_are_refused_by_their_culprit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = d.join("f.csv");
    let fly = |launch: &Path, extra: &[&str]| {
        let mut args = vec!["flight", "--shots", s(launch), "--out", s(&out)];
        args.extend_from_slice(extra);
        smash(&args)
    };
    let twice = write(
        d,
        "twice.csv",
        "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm,ball_speed_mph\nd1,150,12,2600,100\n",
    );
    common::assert_refused(
        &fly(&twice, &[]),
        &[
            "twice.csv:1: column 'ball_speed_mph'",
            "given twice (columns 2 and 5)",
        ],
    );
    let slow = write(
        d,
        "slow.csv",
        "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,1e-300,12,2600\n",
    );
    common::assert_refused(
        &fly(&slow, &[]),
        &["slow.csv:2", "ball_speed_mph", "1e-300", "at least 1 mph"],
    );
    let fine = write(
        d,
        "fine.csv",
        "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,12,2600\n",
    );
    common::assert_refused(
        &fly(&fine, &["--total", "--roll-decel-m-s2", "1e-300"]),
        &["roll_decel_m_s2 = 1e-300", "within [0.1, 50]"],
    );
    let empty = write(d, "empty.csv", "");
    common::assert_refused(&fly(&empty, &[]), &["empty.csv", "the file is empty"]);
    let semi = write(
        d,
        "semi.csv",
        "shot_id;ball_speed_mph;launch_angle_deg;backspin_rpm\nd1;150;12;2600\n",
    );
    common::assert_refused(
        &fly(&semi, &[]),
        &["semi.csv:1", "separated by ';'", "comma-separated"],
    );
    assert!(!out.exists());
}

/// Item 11: a `--delivery-noise` key given twice is refused (the last value was taken
/// silently); a flight option without `--flight` is refused by `predict` (it was ignored).
#[test]
fn repeated_or_ignored_options_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let shots = cli_support::measured_shots(dir.path());
    let o = smash(&[
        "calibrate",
        "--club",
        &club(),
        "--shots",
        s(&shots),
        "--effects",
        "loft_bias",
        "--delivery-noise",
        "club_speed_mph=0.5,club_speed_mph=0.9",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("'club_speed_mph' is given twice"),
        "{}",
        stderr(&o)
    );
    let o = smash(&[
        "predict",
        "--club",
        &club(),
        "--speed-mph",
        "100",
        "--loft-deg",
        "12",
        "--temperature-c",
        "99",
    ]);
    common::assert_refused(&o, &["--temperature-c is a flight option", "--flight"]);
}

/// Item 11: parameter bounds of ±1e308 overflowed the "at bound" margin to infinity, so a fitted
/// value of about 0 was marked at its bound.
#[test]
fn huge_parameter_bounds_do_not_mark_every_value_at_its_bound() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let shots = cli_support::measured_shots(d);
    let defs = write(
        d,
        "wide.toml",
        "[[define_effect]]\nname = \"e_wide\"\nparams = [{ key = \"k_deg\", unit = \"deg\", \
         default = 0.0, lower = -1e308, upper = 1e308, plausible = [-1.0, 1.0] }]\n\
         loft_deg = \"loft_deg + k_deg / (1 + abs(k_deg))\"\n",
    );
    let o = smash(&[
        "calibrate",
        "--club",
        &club(),
        "--shots",
        s(&shots),
        "--effect-defs",
        s(&defs),
        "--effects",
        "e_wide",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let text = j.to_string();
    assert!(text.contains("\"at_bound\":false"), "{text}");
    assert!(!text.contains("\"at_bound\":true"), "{text}");
}

/// Item 6: a study whose user effect pushes the COR above 1 at toe points names the effect and
/// the impact, not a NaN metric "off the face or does not reach the ball"; a club-speed spread
/// reaching speeds below the floor names the spread, not "mean_ball_speed_mph is NaN".
#[test]
fn a_study_metric_that_cannot_be_computed_names_its_culprit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let paper = std::fs::read_to_string(repo("configs/clubs/paper_driver.toml")).unwrap();
    let club_file = write(
        d,
        "club.toml",
        &format!(
            "{paper}\n{}\n[[effect]]\nname = \"e_toe\"\n",
            definition("e_toe", "cor + 0.02 * max(impact_z_mm, 0)")
        ),
    );
    let study = |name: &str, extra: &str| {
        write(
            d,
            name,
            &format!(
                "[study]\nname = \"t\"\nclub = {:?}\noutputs = [\"ball_speed_mph\"]\n\n\
                 [delivery]\nclub_speed_mph = 100.0\ndynamic_loft_deg = 12.0\n\n[grid]\n\
                 y_mm = {{ from = -5.0, to = 5.0, count = 3 }}\n\
                 z_mm = {{ from = -5.0, to = 5.0, count = 3 }}\n{extra}",
                s(&club_file)
            ),
        )
    };
    let out = d.join("out");
    let toe = study("toe.toml", "");
    let o = smash(&["run", s(&toe), "--out", s(&out)]);
    common::assert_refused(
        &o,
        &[
            "cannot be computed",
            "e_toe",
            "cor = \"cor + 0.02",
            "impact at",
        ],
    );
    assert!(!stderr(&o).contains("off the face"), "{}", stderr(&o));
    // The same club without the effect, a spread of club speed reaching 0 mph.
    std::fs::write(&club_file, &paper).unwrap();
    let spread = study(
        "spread.toml",
        "\n[distribution]\nsigma_club_speed_mph = 40.0\n",
    );
    let o = smash(&["run", s(&spread), "--out", s(&out)]);
    common::assert_refused(
        &o,
        &["[distribution]", "club speed", "narrow the club speed"],
    );
    assert!(!out.exists());
}
