//! Impact-location noise detected when present and not invented when absent, measured over
//! seeds (bench-style: `#[ignore]`d, run with
//! `cargo test -p smash --test library location_noise:: -- --ignored --nocapture`; the rates are in
//! docs/diagnose-selection.md). The always-run checks are in `tests/diagnose_fdr.rs`.
//!
//! Worlds: `configs/synth/null_world.toml` (nothing hidden; camera-class launch monitor and
//! motion-capture delivery noise) with its impact-location noise set to 0, 2, 2.5 or 3 mm, and
//! the compliant-contact world `configs/synth/compliant_driver.toml` (physics the library
//! lacks) with 0 or 2.5 mm. Each is diagnosed with the instruments' true noise given (the
//! location figure of the instrument set to the world's, which the spread score does not
//! use) and without it. Seeds 5000 + i, fixed before the first run.

use crate::common;

use std::path::Path;

use common::paper_club;
use smash::diagnose::noise_floor::InstrumentNoise;
use smash::diagnose::{diagnose, DiagnoseOptions};
use smash::model::{DeliveryVar, Shot};
use smash::synth::{generate, read_config, SynthConfig};

fn world(config: &str, location_mm: f64, seed: u64) -> (SynthConfig, Vec<Shot>) {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join(config);
    let mut c = read_config(&p).expect("world reads");
    c.seed = seed;
    // 600 shots, as the rates were measured (the shipped compliant worlds have 3000).
    c.swings_per_golfer = 10;
    c.delivery_noise[DeliveryVar::ImpactY.index()] = location_mm;
    c.delivery_noise[DeliveryVar::ImpactZ.index()] = location_mm;
    let shots = generate(&c, &paper_club())
        .expect("world generates")
        .shots
        .iter()
        .map(|s| s.to_shot())
        .collect();
    (c, shots)
}

/// Diagnose one world and seed; returns (location noise selected with noise known, its size
/// in mm, physical effects selected; the same without noise known).
fn run(config: &str, location_mm: f64, seed: u64, max_steps: usize) -> String {
    let (c, shots) = world(config, location_mm, seed);
    let inst = InstrumentNoise {
        name: "true".into(),
        launch_sd: c.launch_noise.0,
        delivery_sd: c.delivery_noise,
    };
    let opts = DiagnoseOptions {
        max_steps,
        ..DiagnoseOptions::default()
    };
    let known = match diagnose(
        &paper_club(),
        &shots,
        &DiagnoseOptions {
            noise_floor: Some(inst),
            ..opts.clone()
        },
        None,
    ) {
        Ok(d) => d,
        Err(e) => {
            let line = format!("{config} loc {location_mm} mm seed {seed}: diagnose failed: {e}");
            eprintln!("{line}");
            return line;
        }
    };
    let step_of = |d: &smash::diagnose::Diagnosis| {
        d.steps
            .iter()
            .position(|s| {
                s.selected
                    .as_deref()
                    .is_some_and(|l| l.starts_with("impact_noise"))
            })
            .map_or(0, |i| i + 1)
    };
    // Per step: the best impact-noise margin and the best physical margin.
    let first_gains = |d: &smash::diagnose::Diagnosis| -> String {
        let best = |s: &smash::diagnose::Step, noise: bool| {
            s.candidates
                .iter()
                .filter(|c| c.label.starts_with("impact_noise") == noise)
                .map(|c| c.margin())
                .filter(|m| m.is_finite())
                .fold(f64::NEG_INFINITY, f64::max)
        };
        d.steps
            .iter()
            .map(|s| format!("{:.0}|{:.0}", best(s, true), best(s, false)))
            .collect::<Vec<_>>()
            .join(" ")
    };
    let mm = |d: &smash::diagnose::Diagnosis| {
        d.impact_noise
            .filter(|_| d.impact_noise_estimated)
            .map_or(0.0, |n| n.sigma_z_m * 1e3)
    };
    let line = format!(
        "{config} loc {location_mm} mm seed {seed}: known: location {} mm (step {}; margins \
         noise|physics {}), physics {:?}",
        mm(&known),
        step_of(&known),
        first_gains(&known),
        known.selected,
    );
    eprintln!("{line}");
    line
}

fn first_seed() -> u64 {
    std::env::var("LOC_FIRST_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(5000)
}

fn seeds() -> u64 {
    std::env::var("LOC_SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20)
}

#[test]
#[ignore = "bench-style measurement; minutes"]
fn location_noise_rates_in_null_worlds() {
    let mms: Vec<f64> = std::env::var("LOC_MM")
        .ok()
        .map(|s| s.split(',').map(|x| x.parse().unwrap()).collect())
        .unwrap_or(vec![0.0, 2.0, 2.5, 3.0]);
    for mm in mms {
        for i in 0..seeds() {
            run("configs/synth/null_world.toml", mm, first_seed() + i, 10);
        }
    }
}

#[test]
#[ignore = "bench-style measurement; long"]
fn location_noise_rates_in_compliant_worlds() {
    let mms: Vec<f64> = std::env::var("LOC_MM")
        .ok()
        .map(|s| s.split(',').map(|x| x.parse().unwrap()).collect())
        .unwrap_or(vec![0.0, 2.5]);
    for mm in mms {
        for i in 0..seeds() {
            run(
                "configs/synth/compliant_driver.toml",
                mm,
                first_seed() + i,
                10,
            );
        }
    }
}
