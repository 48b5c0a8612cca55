//! `smash diagnose --club configs/clubs/paper_driver.toml --shots <world>.csv` with every default
//! (`DiagnoseOptions::default()`, which the CLI's defaults build: the default candidates and
//! impact-noise levels, 5-fold CV grouped by golfer, up to 10 steps, 100 iterations a fit, then
//! the noise floor the report prints), in process: the library calls the CLI makes, on the
//! 600-shot paper world and on the same world with 10,020 shots (334 golfers per shaft).
//! Reading the files and printing the report are left out (a few ms).

#[path = "support/worlds.rs"]
mod worlds;

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};

use smash::diagnose::noise_floor::{noise_floor, InstrumentClass};
use smash::diagnose::{diagnose, DiagnoseOptions};

fn bench(c: &mut Criterion) {
    let club = worlds::paper_club();
    let mut g = c.benchmark_group("diagnose");
    g.sample_size(10);
    for (label, golfers) in [("600 shots", 20), ("10k shots", 334)] {
        let shots = worlds::paper_world(golfers);
        if golfers > 20 {
            g.measurement_time(Duration::from_secs(60));
        }
        g.bench_function(format!("paper world, {label}, default options"), |b| {
            b.iter(|| {
                let d = diagnose(
                    black_box(&club),
                    black_box(&shots),
                    &DiagnoseOptions::default(),
                    None,
                )
                .unwrap();
                noise_floor(&d, &shots, &InstrumentClass::Camera.noise()).unwrap()
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
