//! `smash diagnose --club configs/clubs/paper_driver.toml --shots <world>.csv` with every default
//! (`DiagnoseOptions::default()`, which the CLI's defaults build: the default candidates and
//! impact-noise levels, 5-fold CV grouped by golfer, up to 10 steps, 100 iterations a fit, then
//! the noise floor the report prints), in process: the library calls the CLI makes, on the
//! 600-shot paper world and on the same world with 10,020 shots (334 golfers per shaft), and
//! on the real-format season (`benches/support/real_format.rs`: 2,200 drives of 22 sessions as
//! a TrackMan export read with the `trackman` preset, folded by session as the CLI folds it,
//! with structure everywhere so that the selection walks 13 steps, swap rounds and removals
//! among them).
//! Reading the files and printing the report are left out (a few ms).

#[path = "support/real_format.rs"]
mod real_format;
#[path = "support/trackman.rs"]
mod trackman;
#[path = "support/worlds.rs"]
mod worlds;

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};

use smash::data::shots::Shot;
use smash::diagnose::noise_floor::{noise_floor, InstrumentClass};
use smash::diagnose::{default_candidates_without, diagnose, DiagnoseOptions};
use smash::effects::{EffectId, EffectKind};
use smash::fit::EffectRequest;
use smash::ClubSpec;

fn bench_one(
    g: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>,
    name: &str,
    (club, shots, opts): (&ClubSpec, &[Shot], &DiagnoseOptions),
) {
    g.bench_function(name, |b| {
        b.iter(|| {
            let d = diagnose(black_box(club), black_box(shots), opts, None).unwrap();
            noise_floor(&d, shots, &InstrumentClass::Camera.noise()).unwrap()
        })
    });
}

fn bench(c: &mut Criterion) {
    let club = worlds::paper_club();
    let mut g = c.benchmark_group("diagnose");
    g.sample_size(10);
    let defaults = DiagnoseOptions::default();
    for (label, golfers) in [("600 shots", 20), ("10k shots", 334)] {
        let shots = worlds::paper_world(golfers);
        if golfers > 20 {
            g.measurement_time(Duration::from_secs(60));
        }
        let name = format!("paper world, {label}, default options");
        bench_one(&mut g, &name, (&club, &shots, &defaults));
    }
    // The CLI's options on an export without golfers: folds by session (the `Date` column).
    let (shots, fold_keys) = real_format::real_format_season(&club, defaults.folds);
    assert!(fold_keys.is_some(), "the season's sessions fold it");
    let opts = DiagnoseOptions {
        fold_keys,
        ..DiagnoseOptions::default()
    };
    g.measurement_time(Duration::from_secs(100));
    let name = "real-format TrackMan season, 2,200 shots, default options";
    bench_one(&mut g, name, (&club, &shots, &opts));
    // The same without `added_mass`: `shaft_fraction` (the added mass as a share of the shot's
    // shaft mass; the export has no shaft column, so every shot has the default shaft's) is
    // offered at every step and fitted on the lanes, the path that once sent every later fit
    // one shot at a time through the scalar solve. It is not selected on this season (measured
    // 28 Nov 2026: `cor_speed` and `cor_power` take the ball-speed level first); a fixture on
    // which it is selected needs shafts that differ (`docs/performance-history.md`).
    let without = [EffectRequest::Global(EffectKind::AddedMass.into())];
    let opts = DiagnoseOptions {
        candidates: Some(default_candidates_without(&shots, &without).expect("candidates")),
        ..opts
    };
    let name = "real-format TrackMan season, 2,200 shots, without added_mass";
    bench_one(&mut g, name, (&club, &shots, &opts));
    g.finish();
}

/// The shaft-fitting season (`real_format::shaft_season`): 2,244 real-format drives with three
/// shafts, on which `shaft_fraction` and nine other effects are selected (20 steps, swap rounds
/// and a re-selection among them): the fixture issue 45 names. About half a minute a run on
/// two cores, so ten samples (criterion's least) in flat sampling.
fn bench_shaft(c: &mut Criterion) {
    let club = worlds::paper_club();
    let (shots, fold_keys) = real_format::shaft_season(&club, DiagnoseOptions::default().folds);
    let opts = DiagnoseOptions {
        fold_keys,
        ..DiagnoseOptions::default()
    };
    let mut g = c.benchmark_group("diagnose shaft season");
    g.sample_size(10);
    g.sampling_mode(criterion::SamplingMode::Flat);
    g.measurement_time(Duration::from_secs(300));
    let d = diagnose(&club, &shots, &opts, None).expect("diagnose runs");
    assert!(
        d.selected.iter().any(|s| s == "shaft_fraction") && d.selected.len() >= 7,
        "the bench's claim: shaft_fraction and six more selected, got {:?}",
        d.selected
    );
    bench_one(
        &mut g,
        "2,244 shots, three shafts, default options",
        (&club, &shots, &opts),
    );
    g.finish();
}

/// A user-defined law against its library twin: the power-law COR world
/// (`configs/synth/cor_power_world.toml`) diagnosed with `cor_power`, and with `my_cor_power`
/// (the same law as an expression, `tests/data/my_cor_power.toml`) offered in its place.
fn bench_user(c: &mut Criterion) {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let club = worlds::paper_club();
    let shots = worlds::world(&root.join("configs/synth/cor_power_world.toml"));
    smash::data::effect_defs::read_effect_defs(&root.join("tests/data/my_cor_power.toml"))
        .expect("definitions read");
    let mut g = c.benchmark_group("diagnose user law");
    g.sample_size(10);
    let all = default_candidates_without(&shots, &[]).expect("candidates");
    let user = |e: &EffectRequest| matches!(e, EffectRequest::Global(EffectId::User(_)));
    let library: Vec<EffectRequest> = all.iter().filter(|e| !user(e)).cloned().collect();
    let twin: Vec<EffectRequest> = all
        .iter()
        .filter(|e| {
            !matches!(
                e,
                EffectRequest::Global(EffectId::Library(EffectKind::CorPower))
            ) && (!user(e) || e.label() == "my_cor_power")
        })
        .cloned()
        .collect();
    for (name, candidates) in [("cor_power", library), ("my_cor_power", twin)] {
        let opts = DiagnoseOptions {
            candidates: Some(candidates),
            ..DiagnoseOptions::default()
        };
        bench_one(&mut g, name, (&club, &shots, &opts));
    }
    g.finish();
}

criterion_group!(benches, bench, bench_user, bench_shaft);
criterion_main!(benches);
