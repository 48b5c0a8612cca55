//! False discoveries of `diagnose` in null worlds (nothing hidden: the nominal club is the
//! truth, only measurement noise separates data from model).
//!
//! Three null worlds, each over its own seeds:
//!
//! - `engine`: the fitting tests' own experiment (20 golfers × 3 shafts × 10 swings, launch
//!   noise only, exact deliveries and impact locations);
//! - `synth`: `configs/synth/null_world.toml` (motion-capture delivery noise, 1.5 mm impact
//!   location noise, camera-class launch monitor), seed replaced;
//! - `quiet`: the same design with a quieter launch monitor and delivery and exact impact
//!   locations;
//! - `located`: `null_world.toml` with a poorer impact-location estimate, 2.5 mm (a face-tape
//!   or launch-monitor estimate of the strike point).
//!
//! A *false discovery* is a seed where diagnose selects any physical effect (measurement
//! candidates, impact-location noise, are not physics). The promise (docs/diagnose-selection.md):
//! at most 4 % of null seeds, with and without the instruments' noise given; the noise floor
//! must call the errors noise in as many. Location noise must be detected in `synth` (1.5 mm)
//! and `located` (2.5 mm) and must not be invented in `engine` and `quiet` (exact locations).
//!
//! Seeds: world `engine` 1000–1019, `synth` 2000–2019, `quiet` 3000–3019, `located`
//! 4000–4019 (`seed_of`), fixed before the first run and never changed to pass.

use crate::common;

use std::path::Path;

use common::{paper_club, shots, Experiment};
use smash::diagnose::noise_floor::{noise_floor, InstrumentNoise};
use smash::diagnose::{diagnose, DiagnoseOptions, Diagnosis};
use smash::model::DeliveryVar;
use smash::model::Shot;
use smash::synth::{generate, read_config, SynthConfig};

/// The null worlds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum World {
    Engine,
    Synth,
    Quiet,
    Located,
}

impl World {
    const ALL: [World; 4] = [World::Engine, World::Synth, World::Quiet, World::Located];

    fn name(self) -> &'static str {
        match self {
            World::Engine => "engine",
            World::Synth => "synth",
            World::Quiet => "quiet",
            World::Located => "located",
        }
    }

    fn has_location_noise(self) -> bool {
        matches!(self, World::Synth | World::Located)
    }
}

fn synth_null(seed: u64) -> SynthConfig {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/synth/null_world.toml");
    let mut c = read_config(&p).expect("null world reads");
    c.seed = seed;
    c
}

fn quiet(mut c: SynthConfig) -> SynthConfig {
    // A radar/camera unit at its best and a marker-based delivery at half the default noise;
    // impact locations exact.
    c.launch_noise = [0.3, 0.15, 0.3, 60.0, 80.0].into();
    for v in DeliveryVar::ALL {
        c.delivery_noise[v.index()] = 0.5 * v.default_noise();
    }
    c.delivery_noise[DeliveryVar::ImpactY.index()] = 0.0;
    c.delivery_noise[DeliveryVar::ImpactZ.index()] = 0.0;
    c
}

fn located(mut c: SynthConfig) -> SynthConfig {
    c.delivery_noise[DeliveryVar::ImpactY.index()] = 2.5;
    c.delivery_noise[DeliveryVar::ImpactZ.index()] = 2.5;
    c
}

/// The synth-based world `w` (not `engine`) at `seed`.
fn synth_world(w: World, seed: u64) -> SynthConfig {
    let c = synth_null(seed);
    match w {
        World::Quiet => quiet(c),
        World::Located => located(c),
        World::Engine | World::Synth => c,
    }
}

/// The instruments' true noise in world `w`.
fn instrument(w: World) -> InstrumentNoise {
    match w {
        World::Engine => InstrumentNoise {
            name: "engine".into(),
            launch_sd: common::NOISE,
            delivery_sd: [0.0; 11],
        },
        World::Synth | World::Quiet | World::Located => {
            let c = synth_world(w, 0);
            InstrumentNoise {
                name: w.name().into(),
                launch_sd: c.launch_noise.0,
                delivery_sd: c.delivery_noise,
            }
        }
    }
}

fn world_shots(w: World, seed: u64) -> Vec<Shot> {
    match w {
        World::Engine => shots(
            &paper_club(),
            &Experiment {
                seed,
                ..Experiment::default()
            },
        ),
        World::Synth | World::Quiet | World::Located => {
            generate(&synth_world(w, seed), &paper_club())
                .expect("null world generates")
                .shots
                .iter()
                .map(|s| s.to_shot())
                .collect()
        }
    }
}

/// The documented seed list: world `w`, index `i` → seed.
fn seed_of(w: World, i: u64) -> u64 {
    1000 * (1 + w as u64) + i
}

struct Outcome {
    world: World,
    seed: u64,
    physical: Vec<String>,
    /// Selected with the instruments' noise known (the noise-floor stopping rule).
    physical_known: Vec<String>,
    location_noise: bool,
    location_noise_known: bool,
    /// Best margin of a physical candidate at the first step.
    best_margin: f64,
    /// Components where the noise floor claims structure.
    structure: Vec<&'static str>,
}

fn run(w: World, seed: u64) -> Outcome {
    let shots = world_shots(w, seed);
    let d: Diagnosis =
        diagnose(&paper_club(), &shots, &DiagnoseOptions::default(), None).expect("diagnose runs");
    let floor = noise_floor(&d, &shots, &instrument(w)).expect("noise floor");
    let known = diagnose(
        &paper_club(),
        &shots,
        &DiagnoseOptions {
            noise_floor: Some(instrument(w)),
            ..DiagnoseOptions::default()
        },
        None,
    )
    .expect("diagnose runs");
    Outcome {
        world: w,
        seed,
        physical: d.selected.clone(),
        physical_known: known.selected.clone(),
        location_noise: d.impact_noise_estimated,
        location_noise_known: known.impact_noise_estimated,
        best_margin: d.steps[0]
            .candidates
            .iter()
            .filter(|c| !c.label.starts_with("impact_noise"))
            .map(|c| c.margin())
            .filter(|m| m.is_finite())
            .fold(f64::NEG_INFINITY, f64::max),
        structure: floor
            .components
            .iter()
            .filter(|c| c.structure)
            .map(|c| c.component.column())
            .collect(),
    }
}

fn check(per_world: u64) {
    let mut outcomes = Vec::new();
    for w in World::ALL {
        for i in 0..per_world {
            outcomes.push(run(w, seed_of(w, i)));
        }
    }
    let n = outcomes.len();
    let false_hits: Vec<&Outcome> = outcomes.iter().filter(|o| !o.physical.is_empty()).collect();
    for o in &outcomes {
        eprintln!(
            "{:<6} seed {:>5}: selected {:?} (noise known: {:?}), location noise {} ({}), best \
             physical margin at step 1 {:+.1}, noise floor: {}",
            o.world.name(),
            o.seed,
            o.physical,
            o.physical_known,
            if o.location_noise { "found" } else { "none" },
            if o.location_noise_known {
                "found"
            } else {
                "none"
            },
            o.best_margin,
            if o.structure.is_empty() {
                "noise".to_owned()
            } else {
                format!("structure in {:?}", o.structure)
            }
        );
    }
    let rate = false_hits.len() as f64 / n as f64;
    eprintln!(
        "false discoveries: {} of {n} null seeds ({:.1} %)",
        false_hits.len(),
        100.0 * rate
    );
    // Issue 29's promise: at most 2 of the 80 null seeds (measured 26 Nov 2026, with
    // face_curvature, cor_spot, shaft_fraction and hosel_mass@group among the candidates: 1,
    // synth seed 2003, cor_radial).
    assert!(
        false_hits.len() <= 2 && rate <= 0.04,
        "false discoveries in {} of {n} seeds: {:?}",
        false_hits.len(),
        false_hits
            .iter()
            .map(|o| format!("{} {}: {:?}", o.world.name(), o.seed, o.physical))
            .collect::<Vec<_>>()
    );
    let known_hits = outcomes
        .iter()
        .filter(|o| !o.physical_known.is_empty())
        .count();
    eprintln!(
        "with the instruments' noise known: {known_hits} of {n} null seeds ({:.1} %)",
        100.0 * known_hits as f64 / n as f64
    );
    assert!(
        known_hits as f64 <= 0.04 * n as f64,
        "false discoveries with known noise in {known_hits} of {n} seeds"
    );
    // Location noise: found where present, not invented where absent (same 4 % allowance).
    for present in [true, false] {
        let of: Vec<&Outcome> = outcomes
            .iter()
            .filter(|o| o.world.has_location_noise() == present)
            .collect();
        let count = |f: fn(&Outcome) -> bool| of.iter().filter(|o| f(o)).count();
        eprintln!(
            "location noise {} in {} (penalty only) and {} (noise known) of {} seeds {} it",
            if present { "found" } else { "invented" },
            count(|o| o.location_noise),
            count(|o| o.location_noise_known),
            of.len(),
            if present { "with" } else { "without" },
        );
    }
    let missed = outcomes
        .iter()
        .filter(|o| {
            o.world.has_location_noise() != o.location_noise
                || o.world.has_location_noise() != o.location_noise_known
        })
        .count();
    assert!(
        missed as f64 <= 0.04 * n as f64,
        "impact-location noise misjudged in {missed} of {n} seeds"
    );
    // The noise floor, given the instruments' true noise, calls a null world's errors noise
    // (its test has a 1 % family-wise level; the linearisation gets the same 4 % allowance).
    let structured = outcomes.iter().filter(|o| !o.structure.is_empty()).count();
    eprintln!("noise floor claims structure in {structured} of {n} null seeds");
    assert!(
        structured as f64 <= 0.04 * n as f64,
        "noise floor claims structure in {structured} of {n} null seeds"
    );
}

/// 20 seeds in each of the four null worlds (80 seeds), each diagnosed twice: as a user without
/// noise figures would (penalty only) and with the instruments' noise known (noise-floor stop).
/// About a minute on two cores; measured rates are in docs/diagnose-selection.md.
#[test]
fn false_discovery_rate_is_at_most_4_percent() {
    check(20);
}
