//! Issue 29's acceptance test on the paper's own kind of world, as a user runs it: `smash synth
//! --config configs/synth/paper_world.toml --seed N` (added mass per shaft A/B/C, 2.54, 0.88
//! and 1.18 g, and a ball offset dy 0.48, dz −0.07 mm), then `smash diagnose --noise
//! configs/noise/paper_world.toml --json` with the world's true instrument noise, over seeds
//! 1–20 (fixed before the first run and never changed to pass).
//!
//! Promise: the ball offset (each of dy and dz) within 2 SE of the truth in at least 18 of the
//! 20 seeds; a false finding (a finding of an effect the world does not hold) in at most 1.
//! Measured when the test was written (26 Nov 2026): dy within 2 SE in 18 (seeds 9 and 17 at
//! −2.8 and +2.3 SE), dz in 19 (seed 20 at −2.4 SE); one false finding (`hosel_mass.dm_g`,
//! seed 20). The added mass per shaft, which the world holds, is selected in 1 seed of 20 (and
//! `cor_level`, ambiguous, in 7): a miss, not a false finding, and not yet explained.

mod cli_support;

use cli_support::{repo, s, smash};

/// The world's truth (`configs/synth/paper_world.toml`).
const DY_MM: f64 = 0.48;
const DZ_MM: f64 = -0.07;
/// The effects the world holds.
const IN_WORLD: [&str; 2] = ["ball_offset", "added_mass"];

/// One seed's diagnosis: (dy, its SE), (dz, its SE), the findings.
fn diagnose_seed(dir: &std::path::Path, seed: u32) -> ((f64, f64), (f64, f64), Vec<String>) {
    let shots = dir.join(format!("paper_world_{seed}.csv"));
    let config = repo("configs/synth/paper_world.toml");
    let seed_arg = seed.to_string();
    let o = smash(&[
        "synth",
        "--config",
        s(&config),
        "--out",
        s(&shots),
        "--seed",
        &seed_arg,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (club, noise) = (
        repo("configs/clubs/paper_driver.toml"),
        repo("configs/noise/paper_world.toml"),
    );
    let o = smash(&[
        "diagnose",
        "--club",
        s(&club),
        "--shots",
        s(&shots),
        "--noise",
        s(&noise),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let d: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let estimate = |param: &str| {
        let e = d["estimates"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["effect"] == "ball_offset" && e["param"] == param)
            .unwrap_or_else(|| panic!("seed {seed}: no ball_offset.{param}"));
        (e["value"].as_f64().unwrap(), e["stderr"].as_f64().unwrap())
    };
    let findings = d["findings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap().to_string())
        .collect();
    (estimate("dy_mm"), estimate("dz_mm"), findings)
}

#[test]
fn paper_world_over_twenty_seeds() {
    let dir = tempfile::tempdir().unwrap();
    let (mut dy_ok, mut dz_ok, mut false_findings) = (0, 0, 0);
    for seed in 1..=20 {
        let ((dy, dy_se), (dz, dz_se), findings) = diagnose_seed(dir.path(), seed);
        let (zy, zz) = ((dy - DY_MM) / dy_se, (dz - DZ_MM) / dz_se);
        let false_here: Vec<&String> = findings
            .iter()
            .filter(|f| !IN_WORLD.iter().any(|w| f.starts_with(&format!("{w}."))))
            .collect();
        println!(
            "seed {seed}: dy {dy:.3} ± {dy_se:.3} ({zy:+.1} SE), dz {dz:.3} ± {dz_se:.3} \
             ({zz:+.1} SE), findings {findings:?}"
        );
        dy_ok += usize::from(zy.abs() <= 2.0);
        dz_ok += usize::from(zz.abs() <= 2.0);
        false_findings += usize::from(!false_here.is_empty());
    }
    println!(
        "dy within 2 SE: {dy_ok}/20, dz: {dz_ok}/20, seeds with a false finding: {false_findings}"
    );
    assert!(
        dy_ok >= 18 && dz_ok >= 18,
        "dy {dy_ok}/20, dz {dz_ok}/20 within 2 SE"
    );
    assert!(
        false_findings <= 1,
        "{false_findings} seeds with a false finding"
    );
}
