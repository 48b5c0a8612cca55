//! Calibrate 5 parameters (added_mass@group + ball_offset) and 4 parameters
//! (added_mass + ball_offset + loft_bias) on 600 shots, and a full diagnose (all library
//! effects, 5-fold CV grouped by golfer) on 600 shots.

#[path = "../tests/common/mod.rs"]
mod common;

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};

use smash::diagnose::{diagnose, DiagnoseOptions};
use smash::fit::{calibrate, parse_effect_list, CalibrateOptions};

fn bench(c: &mut Criterion) {
    let club = common::paper_club();
    let shots = common::shots(&common::paper_truth(), &common::Experiment::default());
    let mut g = c.benchmark_group("600_shots");
    g.sample_size(10);
    for list in [
        "added_mass,ball_offset,loft_bias",
        "added_mass@group,ball_offset",
    ] {
        let req = parse_effect_list(list).unwrap();
        g.bench_function(format!("calibrate {list}"), |b| {
            b.iter(|| {
                calibrate(
                    black_box(&club),
                    black_box(&shots),
                    &req,
                    &CalibrateOptions::default(),
                    None,
                )
                .unwrap()
            })
        });
    }
    g.bench_function("diagnose all effects, 5-fold grouped CV", |b| {
        b.iter(|| {
            diagnose(
                black_box(&club),
                black_box(&shots),
                &DiagnoseOptions::default(),
                None,
            )
            .unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
