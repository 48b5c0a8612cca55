//! `smash calibrate` as the CLI runs it (Levenberg–Marquardt, 100 iterations, parallel
//! Jacobian), in process on the paper world as `smash synth` writes it:
//!
//! - `--effects added_mass@group,ball_offset` (5 parameters) on the 600-shot world;
//! - the same with `--impact-noise-mm 3,3` on 100,020 shots (3334 golfers per shaft);
//! - `--effects added_mass,ball_offset,loft_bias` on 600 shots (a fit through the loft bias,
//!   where each evaluation re-makes the face frames).

#[path = "support/worlds.rs"]
mod worlds;

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};

use smash::fit::{calibrate, parse_effect_list, CalibrateOptions, Method};
use smash::measurement::ImpactNoise;

/// The options `smash calibrate` builds from its default arguments.
fn cli_options(impact_noise: Option<ImpactNoise>) -> CalibrateOptions {
    CalibrateOptions {
        method: Method::Lm,
        max_iters: 100,
        parallel: true,
        impact_noise,
        delivery_noise: None,
    }
}

fn bench(c: &mut Criterion) {
    let club = worlds::paper_club();
    let mut g = c.benchmark_group("calibrate");
    let paper = worlds::paper_world(20);
    for list in [
        "added_mass@group,ball_offset",
        "added_mass,ball_offset,loft_bias",
    ] {
        let req = parse_effect_list(list).unwrap();
        g.bench_function(format!("600 shots, {list}"), |b| {
            b.iter(|| {
                calibrate(
                    black_box(&club),
                    black_box(&paper),
                    &req,
                    &cli_options(None),
                    None,
                )
                .unwrap()
            })
        });
    }
    let big = worlds::paper_world(3334);
    let req = parse_effect_list("added_mass@group,ball_offset").unwrap();
    let noise = ImpactNoise::from_mm(3.0, 3.0).unwrap();
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(30));
    g.bench_function(
        "100k shots, added_mass@group,ball_offset, impact noise 3,3 mm",
        |b| {
            b.iter(|| {
                calibrate(
                    black_box(&club),
                    black_box(&big),
                    &req,
                    &cli_options(Some(noise)),
                    None,
                )
                .unwrap()
            })
        },
    );
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
