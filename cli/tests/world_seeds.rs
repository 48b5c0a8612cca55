//! Issue 29's acceptance tests over seeds, as a user runs them: `smash synth --config WORLD
//! --seed N`, then `smash diagnose --json` on the shots. Seeds fixed before the first run and
//! never changed to pass.
//!
//! **The paper's own kind of world** (`configs/synth/paper_world.toml`: added mass per shaft
//! A/B/C, 2.54, 0.88 and 1.18 g, and a ball offset dy 0.48, dz −0.07 mm), diagnosed with the
//! world's true instrument noise (`--noise configs/noise/paper_world.toml`), seeds 1–20.
//! Promise: the ball offset (each of dy and dz) within 2 SE of the truth in at least 18 of the
//! 20 seeds; a false finding (a finding of an effect the world does not hold) in at most 1.
//! Measured when the test was written (26 Nov 2026): dy within 2 SE in 18 (seeds 9 and 17 at
//! −2.8 and +2.3 SE), dz in 19 (seed 20 at −2.4 SE); one false finding (`hosel_mass.dm_g`,
//! seed 20). The added mass per shaft, which the world holds, is selected in 1 seed of 20 (and
//! `cor_level`, ambiguous, in 7): a miss, not a false finding; explained (issue 43) in
//! `docs/rival-families.md` and now stated as not resolved when it is missed. With
//! `face_curvature`, `cor_spot`, `shaft_fraction` and `hosel_mass@group` among the candidates:
//! dy 18/20, dz 20/20, no false finding.
//!
//! **A twisted face** (`configs/synth/twisted_face_world.toml`: loft +0.075°/mm and face
//! +0.05°/mm toward the toe, which no library form expresses, and 2 g of added mass),
//! diagnosed with `--instrument camera` (the world's noise class), seeds 1–10. Before the
//! shared-signal check (`src/diagnose/shared.rs`) `inertia_scale` was a finding in every seed
//! and `hosel_mass`/`contact_time` in four; now every one of them is provisional, naming the
//! structure it shares. Measured: one seed of ten with a false finding (seed 4, `cor_radial`,
//! whose signal is radial and shares no trend); issue 29 asks for none, so the bound is the
//! measured one and may only tighten. With `face_curvature` in the library, its bulge is a
//! finding in every seed: the face-angle half of the twist turns the face normal heel to toe,
//! which is what a bulge radius is (`face_angle_twist_is_a_bulge_error`), so it counts as the
//! world's. Its roll is "unchanged" (not significant over the model's parameters). Seed 4's
//! `ball_offset.dz_mm` (−0.023 ± 0.006 mm) passed its own checks while the same effect's dy
//! drifted from heel to toe; an effect failing a check in one parameter is now provisional in
//! all of them, and no seed of ten reports a finding outside the world, as the issue asks.

use crate::cli_support;

use cli_support::{diagnose_json, repo, s, smash, synth_world};

/// The paper world's truth (`configs/synth/paper_world.toml`).
const DY_MM: f64 = 0.48;
const DZ_MM: f64 = -0.07;

/// `smash synth --config WORLD --seed N`, then `smash diagnose … ARGS --json`: the JSON.
fn diagnose_world(
    dir: &std::path::Path,
    world: &str,
    seed: u32,
    args: &[&str],
) -> serde_json::Value {
    diagnose_json(&synth_world(dir, world, seed), args)
}

/// The findings of a diagnosis.
fn findings(d: &serde_json::Value) -> Vec<String> {
    d["findings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap().to_string())
        .collect()
}

/// Findings of effects `in_world` does not list.
fn false_findings(findings: &[String], in_world: &[&str]) -> Vec<String> {
    findings
        .iter()
        .filter(|f| !in_world.iter().any(|w| f.starts_with(&format!("{w}."))))
        .cloned()
        .collect()
}

/// One paper-world seed: (dy, its SE), (dz, its SE), the findings.
fn paper_seed(dir: &std::path::Path, seed: u32) -> ((f64, f64), (f64, f64), Vec<String>) {
    let noise = repo("configs/noise/paper_world.toml");
    let d = diagnose_world(dir, "paper_world", seed, &["--noise", s(&noise)]);
    let estimate = |param: &str| {
        let e = d["estimates"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["effect"] == "ball_offset" && e["param"] == param)
            .unwrap_or_else(|| panic!("seed {seed}: no ball_offset.{param}"));
        (e["value"].as_f64().unwrap(), e["stderr"].as_f64().unwrap())
    };
    (estimate("dy_mm"), estimate("dz_mm"), findings(&d))
}

#[test]
fn paper_world_over_twenty_seeds() {
    let dir = tempfile::tempdir().unwrap();
    let (mut dy_ok, mut dz_ok, mut false_seeds) = (0, 0, 0);
    for seed in 1..=20 {
        let ((dy, dy_se), (dz, dz_se), found) = paper_seed(dir.path(), seed);
        let (zy, zz) = ((dy - DY_MM) / dy_se, (dz - DZ_MM) / dz_se);
        println!(
            "seed {seed}: dy {dy:.3} ± {dy_se:.3} ({zy:+.1} SE), dz {dz:.3} ± {dz_se:.3} \
             ({zz:+.1} SE), findings {found:?}"
        );
        dy_ok += usize::from(zy.abs() <= 2.0);
        dz_ok += usize::from(zz.abs() <= 2.0);
        let wrong = false_findings(&found, &["ball_offset", "added_mass"]);
        false_seeds += usize::from(!wrong.is_empty());
    }
    println!(
        "dy within 2 SE: {dy_ok}/20, dz: {dz_ok}/20, seeds with a false finding: {false_seeds}"
    );
    assert!(
        dy_ok >= 18 && dz_ok >= 18,
        "dy {dy_ok}/20, dz {dz_ok}/20 within 2 SE"
    );
    assert!(false_seeds <= 1, "{false_seeds} seeds with a false finding");
}

#[test]
fn twisted_face_over_ten_seeds() {
    let dir = tempfile::tempdir().unwrap();
    let mut false_seeds = 0;
    for seed in 1..=10 {
        let d = diagnose_world(
            dir.path(),
            "twisted_face_world",
            seed,
            &["--instrument", "camera"],
        );
        let found = findings(&d);
        let provisional: Vec<&str> = d["provisional"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p["failed_check"].as_str().unwrap())
            .collect();
        println!("seed {seed}: findings {found:?}, provisional {provisional:#?}");
        // The stand-ins the issue found must not be findings in any seed, nor the roll radius:
        // the twist turns the loft heel to toe, not crown to sole.
        for stand_in in [
            "inertia_scale.s",
            "contact_time.tau_ms",
            "loft_bias.deg",
            "face_curvature.d_roll_mm",
        ] {
            assert!(
                !found.iter().any(|f| f == stand_in),
                "seed {seed}: {stand_in}"
            );
        }
        // The face-angle half of the twist turns the face normal heel to toe: that is a bulge
        // radius (`face_angle_twist_is_a_bulge_error` below), so a bulge change is the world's.
        let wrong = false_findings(&found, &["added_mass", "face_curvature"]);
        false_seeds += usize::from(!wrong.is_empty());
    }
    println!("twisted face: seeds with a false finding: {false_seeds} of 10");
    assert_eq!(
        false_seeds, 0,
        "{false_seeds} of 10 seeds with a false finding"
    );
}

/// The face-angle half of the twisted face alone (face +0.05°/mm toward the toe, loft
/// untwisted, nothing else): the face normal turns 0.05°/mm faster heel to toe than the file's
/// 305 mm bulge turns it, which to first order is a bulge radius of 1/(1/305 mm + 8.73e-4/mm) =
/// 241 mm, a change of −64 mm. Diagnose finds `face_curvature` with the bulge 50–62 mm tighter
/// (the twist turns the whole head, not only the normal, so the first-order figure is not
/// exact), its roll unchanged, and nothing else. Measured on seeds 1 and 2: −55.6 ± 2.5 and
/// −60.3 ± 2.4 mm.
#[test]
fn face_angle_twist_is_a_bulge_error() {
    let dir = tempfile::tempdir().unwrap();
    let twisted = std::fs::read_to_string(repo("configs/synth/twisted_face_world.toml")).unwrap();
    let club = repo("configs/clubs/paper_driver.toml");
    let config: String = twisted
        .replace("loft_deg_per_mm = 0.075", "loft_deg_per_mm = 0.0")
        .replace("[[hidden]]\nname = \"added_mass\"\ndm_g = 2.0\n", "")
        .replace("\"../clubs/paper_driver.toml\"", &format!("{:?}", s(&club)));
    assert!(!config.contains("added_mass") && config.contains("loft_deg_per_mm = 0.0"));
    let path = dir.path().join("face_twist_only.toml");
    std::fs::write(&path, config).unwrap();
    for seed in 1..=2 {
        let shots = dir.path().join(format!("f{seed}.csv"));
        let seed_arg = seed.to_string();
        let o = smash(&[
            "synth",
            "--config",
            s(&path),
            "--out",
            s(&shots),
            "--seed",
            &seed_arg,
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let d = diagnose_json(&shots, &["--instrument", "camera"]);
        let found = findings(&d);
        println!("face twist only, seed {seed}: findings {found:?}");
        assert_eq!(found, ["face_curvature.d_bulge_mm"], "seed {seed}");
        let bulge = d["estimates"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["param"] == "d_bulge_mm")
            .unwrap()["value"]
            .as_f64()
            .unwrap();
        assert!(
            (-70.0..=-45.0).contains(&bulge),
            "seed {seed}: d_bulge {bulge}"
        );
    }
}
