//! The default text output of compare, calibrate, diagnose, flight, run, whatif and synth fits
//! 120 columns (their renderers aim at 100) on the shipped inputs, on stdout and stderr alike,
//! and `--wide` still prints the full tables: a column or line only `--wide` shows is there.
//! Every documented command's output is checked the same way by `docs_run.rs`.

use crate::cli_support;

use std::path::Path;
use std::process::{Command, Output};

use cli_support::{repo, s, SMASH};
use unicode_width::UnicodeWidthStr;

/// The hard limit of a default text line, in display columns.
const MAX_COLUMNS: usize = 120;

/// Run `smash` from the repository's root; it must succeed.
fn run(args: &[&str]) -> Output {
    let o = Command::new(SMASH)
        .args(args)
        .current_dir(repo(""))
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "smash {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

/// Every line of stdout and stderr of `smash args` is at most [`MAX_COLUMNS`] wide; the
/// command's stdout.
fn fits(args: &[&str]) -> String {
    let o = run(args);
    for (name, bytes) in [("stdout", &o.stdout), ("stderr", &o.stderr)] {
        let text = String::from_utf8(bytes.clone()).unwrap();
        for (i, line) in text.lines().enumerate() {
            assert!(
                line.width() <= MAX_COLUMNS,
                "smash {}: {name} line {} is {} columns wide:\n{line}",
                args.join(" "),
                i + 1,
                line.width()
            );
        }
    }
    String::from_utf8(o.stdout).unwrap()
}

/// The paper's world (600 shots), written into `dir`.
fn paper_world(dir: &Path) -> String {
    let shots = dir.join("paper_world.csv");
    fits(&[
        "synth",
        "--config",
        "configs/synth/paper_world.toml",
        "--out",
        s(&shots),
    ]);
    s(&shots).to_owned()
}

const CLUB: &str = "configs/clubs/paper_driver.toml";

#[test]
fn compare_calibrate_and_diagnose_fit_and_widen() {
    let dir = tempfile::tempdir().unwrap();
    let shots = paper_world(dir.path());
    let compare = ["compare", "--club", CLUB, "--shots", &shots];
    let text = fits(&compare);
    assert!(text.contains("Findings, strongest first:"), "{text}");
    // Three groups fit in one block: --wide prints the same report.
    assert_eq!(
        run(&[&compare[..], &["--wide"]].concat()).stdout,
        text.as_bytes()
    );

    let calibrate = [
        "calibrate",
        "--club",
        CLUB,
        "--shots",
        &shots,
        "--effects",
        "added_mass@group,ball_offset",
        "--impact-noise-mm",
        "3,3",
    ];
    let text = fits(&calibrate);
    assert!(text.contains("before (nominal):\ncomponent"), "{text}");
    let wide = String::from_utf8(run(&[&calibrate[..], &["--wide"]].concat()).stdout).unwrap();
    assert!(
        wide.lines()
            .any(|l| l.starts_with("Ball speed (mph)") && l.contains("| Ball speed (mph)")),
        "{wide}"
    );

    let diagnose = ["diagnose", "--club", CLUB, "--shots", &shots];
    let text = fits(&diagnose);
    // The next command stands on lines of its own, and runs as printed.
    let at = text
        .find("Fit the same model with:\n  smash calibrate --club")
        .unwrap();
    assert!(text[at..].contains("--effects ball_offset"), "{text}");
    let wide = String::from_utf8(run(&[&diagnose[..], &["--wide"]].concat()).stdout).unwrap();
    let header = |t: &str, col: &str| {
        t.lines()
            .any(|l| l.starts_with("candidate") && l.contains(col))
    };
    assert!(
        header(&wide, "parameters") && header(&wide, "Δrms speed"),
        "{wide}"
    );
    assert!(!header(&text, "parameters"), "{text}");
    assert!(wide.contains("dy_mm = 0.") && wide.lines().any(|l| l.ends_with("expected spread)")));
}

#[test]
fn flight_fits() {
    let dir = tempfile::tempdir().unwrap();
    let launch = dir.path().join("rapsodo.csv");
    run(&[
        "import",
        "--format",
        "rapsodo",
        "tests/data/real/rapsodo_mlm2pro_7i.csv",
        "--out",
        s(&launch),
    ]);
    let out = dir.path().join("flight.csv");
    fits(&["flight", "--shots", s(&launch), "--out", s(&out)]);
    fits(&[
        "flight",
        "--shots",
        s(&launch),
        "--out",
        s(&out),
        "--diagnose",
    ]);
    fits(&[
        "flight",
        "--shots",
        s(&launch),
        "--out",
        s(&out),
        "--calibrate",
        "drag,lift,spin_decay",
    ]);
}

#[test]
fn run_fits_and_widens() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("com_sweep");
    let text = fits(&["run", "configs/studies/com_sweep.toml", "--out", s(&out)]);
    assert!(
        text.contains("CoF mph") && !text.contains("cof_ball_speed_mph ="),
        "{text}"
    );
    let out = dir.path().join("com_sweep_wide");
    let wide = run(&[
        "run",
        "configs/studies/com_sweep.toml",
        "--out",
        s(&out),
        "--wide",
    ]);
    let wide = String::from_utf8(wide.stdout).unwrap();
    assert!(wide.contains("  variant 0 (com_dx_mm = -5, com_dy_mm = -3): cof_ball_speed_mph = "));
    for study in ["yards_driver", "optimise"] {
        let out = dir.path().join(study);
        fits(&[
            "run",
            &format!("configs/studies/{study}.toml"),
            "--out",
            s(&out),
        ]);
    }
}

#[test]
fn whatif_fits() {
    // The setting (golfer, mishits, quadrature) is one sentence, wrapped.
    let text = fits(&[
        "whatif",
        "--club",
        CLUB,
        "--speed",
        "95",
        "--loft",
        "13",
        "--move-mass",
        "5g:-70,-10,0:-80,-10,-10",
    ]);
    assert!(
        text.contains("golfer: 95 mph") && text.contains("\n  dispersion ellipse\n"),
        "{text}"
    );
}
