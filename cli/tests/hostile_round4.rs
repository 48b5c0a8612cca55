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
