//! The fourth hostile pass (29 Nov 2026, a tester attacking every command but `import`): a seed
//! the truth file cannot hold, `NaN` in diagnose's candidate table for a candidate whose fit
//! failed, negative numbers read as flags, and a plan for no shots or a negative spread. One
//! function per theme, to keep process launches few. (A COR law outside (0, 1] is
//! `cor_range.rs`.)

use crate::cli_support;

use cli_support::{club, repo, s, smash, stderr, write};

#[test]
fn seeds_are_those_a_truth_file_can_hold() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shots.csv");
    let config = repo("configs/synth/paper_world.toml");
    let o = smash(&[
        "synth",
        "--config",
        s(&config),
        "--seed",
        "18446744073709551615",
        "--out",
        s(&out),
    ]);
    let e = stderr(&o);
    assert!(!o.status.success(), "accepted");
    assert!(
        e.contains("--seed") && e.contains("9223372036854775807"),
        "{e}"
    );
    assert!(!out.exists());
}

#[test]
fn a_failed_candidate_prints_no_nan() {
    let dir = tempfile::tempdir().unwrap();
    let c = club();
    let shots = cli_support::synth_world(dir.path(), "paper_world", 3);
    // A user effect whose law is NaN for every shot slower than 100 mph: its fit cannot start.
    let defs = write(
        dir.path(),
        "nan.toml",
        "[[define_effect]]\nname = \"e_nan\"\n\
         params = [{ key = \"q\", unit = \"1\", default = 0.0, lower = 0.0, upper = 1.0 }]\n\
         cor = \"cor * (1 + q*ln(club_speed_mph - 100))\"\n",
    );
    for wide in [false, true] {
        let mut args = vec![
            "diagnose",
            "--club",
            &c,
            "--shots",
            s(&shots),
            "--effect-defs",
            s(&defs),
            "--max-steps",
            "1",
        ];
        if wide {
            args.push("--wide");
        }
        let o = smash(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let text = String::from_utf8_lossy(&o.stdout);
        let row = text
            .lines()
            .find(|l| l.trim_start().starts_with("e_nan"))
            .unwrap_or_else(|| panic!("no e_nan row:\n{text}"));
        assert!(!row.contains("NaN") && !row.contains("inf"), "{row}");
        assert!(row.contains('—'), "{row}");
    }
}

#[test]
fn negative_numbers_are_values_and_plans_need_shots() {
    let dir = tempfile::tempdir().unwrap();
    let c = club();
    let o = smash(&[
        "whatif",
        "--club",
        &c,
        "--speed",
        "100",
        "--moi-scale",
        "-1",
    ]);
    let e = stderr(&o);
    assert!(!o.status.success());
    assert!(!e.contains("unexpected argument"), "{e}");
    let o = smash(&[
        "whatif",
        "--club",
        &c,
        "--speed",
        "100",
        "--moi-scale",
        "1.1",
        "--speed-sd",
        "-2",
    ]);
    let e = stderr(&o);
    assert!(!o.status.success());
    assert!(
        e.contains("--speed-sd: a spread (σ) must be 0 or more, got -2"),
        "{e}"
    );
    let shots = cli_support::synth_world(dir.path(), "paper_world", 1);
    for (flag, value, want) in [
        ("--plan-shots", "0", "a plan needs at least 1"),
        ("--impact-spread-mm", "-1,2", "each > 0"),
    ] {
        let o = smash(&[
            "infer-club",
            "--shots",
            s(&shots),
            "--start",
            &c,
            "--plan",
            flag,
            value,
        ]);
        let e = stderr(&o);
        assert!(!o.status.success(), "{flag} {value} accepted");
        assert!(
            e.contains(want) && !e.contains("unexpected argument"),
            "{e}"
        );
    }
}

/// A shots-file row of the wrong width (an unquoted decimal comma, a cell lost) is one bad row:
/// left out and counted by every command that reads shots, as import counts it; `--strict`
/// refuses the file there.
#[test]
fn a_row_of_the_wrong_width_is_counted_not_fatal() {
    let dir = tempfile::tempdir().unwrap();
    let c = club();
    let shots = cli_support::synth_world(dir.path(), "paper_world", 2);
    let text = std::fs::read_to_string(&shots).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let n = lines.len() - 1;
    lines[5].push_str(",3");
    let bent = write(dir.path(), "bent.csv", &(lines.join("\n") + "\n"));
    let out = dir.path().join("pred.csv");
    let o = smash(&[
        "predict",
        "--club",
        &c,
        "--shots",
        s(&bent),
        "--out",
        s(&out),
    ]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains(&format!("left out 1 of {n} rows: a row whose cells do not match the header's columns (line(s) 6"))
            && e.contains("bent.csv:6: found a row with"),
        "{e}"
    );
    let rows = std::fs::read_to_string(&out).unwrap().lines().count() - 1;
    assert_eq!(rows, n - 1);
    let o = smash(&[
        "predict",
        "--strict",
        "--club",
        &c,
        "--shots",
        s(&bent),
        "--out",
        s(&out),
    ]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("bent.csv:6: found a row with"),
        "{}",
        stderr(&o)
    );
}

/// A shot the club cannot solve at its own values (here a typo: loft 80°, attack −15°, the club
/// does not approach the ball) is left out and counted by every command that reads shots, not
/// the end of the file; `--strict` refuses the file there.
#[test]
fn a_shot_the_club_cannot_solve_is_counted_not_fatal() {
    let dir = tempfile::tempdir().unwrap();
    let c = club();
    let shots = cli_support::synth_world(dir.path(), "paper_world", 4);
    let text = std::fs::read_to_string(&shots).unwrap();
    let mut r = csv::Reader::from_reader(text.as_bytes());
    let h = r.headers().unwrap().clone();
    let col = |name: &str| h.iter().position(|c| c == name).unwrap();
    let (loft, attack) = (col("dynamic_loft_deg"), col("attack_angle_deg"));
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let n = lines.len() - 1;
    let mut cells: Vec<String> = lines[7].split(',').map(str::to_owned).collect();
    (cells[loft], cells[attack]) = ("80".into(), "-15".into());
    lines[7] = cells.join(",");
    let bent = write(dir.path(), "typo.csv", &(lines.join("\n") + "\n"));
    for command in ["predict", "compare"] {
        let out = dir.path().join(format!("{command}.csv"));
        let mut args = vec![command, "--club", &c, "--shots", s(&bent)];
        if command == "predict" {
            args.extend(["--out", s(&out)]);
        }
        let o = smash(&args);
        let e = stderr(&o).replace("\n  ", " ");
        assert!(o.status.success(), "{command}: {e}");
        assert!(
            e.contains(&format!(
                "left out 1 of {n} rows: a shot the club cannot solve (line(s) 8"
            )) && e.contains("does not approach the ball"),
            "{command}: {e}"
        );
        args.push("--strict");
        let o = smash(&args);
        assert!(!o.status.success(), "{command} --strict");
        assert!(stderr(&o).contains("typo.csv:8:"), "{}", stderr(&o));
    }
}

/// An empty cell of an optional column (`lie_tilt_deg`, `club_omega_*`, `shaft_mass_g`) is what
/// an absent column gives (0; no shaft mass): the row is predicted as with those values, and a
/// column left all empty (a spreadsheet's NaN written out) does not refuse the file.
#[test]
fn empty_optional_cells_take_their_defaults() {
    let dir = tempfile::tempdir().unwrap();
    let c = club();
    let shots = cli_support::synth_world(dir.path(), "paper_world", 5);
    let text = std::fs::read_to_string(&shots).unwrap();
    let head: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let optional = |name: &str| name == "lie_tilt_deg" || name.starts_with("club_omega_");
    let blank_at = |value: &str| -> String {
        let mut out = String::new();
        for (k, line) in text.lines().enumerate() {
            let cells: Vec<String> = line
                .split(',')
                .zip(&head)
                .map(|(cell, h)| match (k, *h) {
                    (0, _) => cell.to_owned(),
                    (_, "shaft_mass_g") => String::new(),
                    (3, h) if optional(h) => value.to_owned(),
                    _ => cell.to_owned(),
                })
                .collect();
            out.push_str(&cells.join(","));
            out.push('\n');
        }
        out
    };
    let predict = |name: &str, body: &str| {
        let file = write(dir.path(), name, body);
        let out = dir.path().join(format!("{name}.pred.csv"));
        let o = smash(&[
            "predict",
            "--club",
            &c,
            "--shots",
            s(&file),
            "--out",
            s(&out),
        ]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        assert!(!stderr(&o).contains("left out"), "{name}: {}", stderr(&o));
        let text = std::fs::read_to_string(&out).unwrap();
        let h: Vec<String> = text
            .lines()
            .next()
            .unwrap()
            .split(',')
            .map(str::to_owned)
            .collect();
        let at = h.iter().position(|x| x == "pred_ball_speed_mph").unwrap();
        let row: Vec<String> = text
            .lines()
            .nth(3)
            .unwrap()
            .split(',')
            .map(str::to_owned)
            .collect();
        (text.lines().count(), row[at].clone())
    };
    let (n_blank, blank) = predict("blank.csv", &blank_at(""));
    let (n_zero, zero) = predict("zero.csv", &blank_at("0"));
    assert_eq!(n_blank, text.lines().count());
    assert_eq!((n_blank, blank), (n_zero, zero));
}
