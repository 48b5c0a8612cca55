//! Ball flight throughput: 100,000 drives (ball speed 150–180 mph, launch 8–14°, spin
//! 2000–3200 rpm, sidespin ±600 rpm, azimuth ±3°) to landing with the default model and
//! atmosphere, all threads (rayon), and the same on one thread; and what `smash flight` does
//! with them: the same drives as a launch CSV (cells as a launch monitor writes them, 2
//! decimals, spins in whole rpm), read, parsed, flown, formatted and written to a flight CSV.

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use smash::app::flight::stream::{fly_csv_file, CHUNK_BYTES};
use smash::flight::integrate::fly_serial;
use smash::flight::workload::{drive_file_units, drives};
use smash::flight::{fly, Flight, FlightConfig, FlightError};

/// The drives of [`drives`] as a launch CSV, as `smash flight --shots` reads it.
fn drives_csv(n: usize) -> String {
    let mut t = String::from(
        "shot_id,ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,sidespin_rpm\n",
    );
    for k in 0..n {
        let [v, a, az, back, side] = drive_file_units(k);
        t.push_str(&format!("s{k},{v:.2},{a:.2},{az:.2},{back:.0},{side:.0}\n"));
    }
    t
}

fn bench(c: &mut Criterion) {
    let cfg = FlightConfig::default();
    let n = 100_000;
    let ls = drives(n);
    let mut g = c.benchmark_group("flight");
    g.throughput(Throughput::Elements(n as u64));
    g.sample_size(10);
    g.bench_function("drives_100k_all_threads", |b| {
        b.iter(|| black_box(fly(&cfg, black_box(&ls))))
    });
    let mut out: Vec<Result<Flight, FlightError>> =
        vec![Err(FlightError::NeverLands { time_limit_s: 0.0 }); n];
    g.bench_function("drives_100k_one_thread", |b| {
        b.iter(|| fly_serial(&cfg, black_box(&ls), &mut out))
    });
    let dir = tempfile::tempdir().expect("a temporary folder");
    let (shots, out) = (dir.path().join("drives.csv"), dir.path().join("f.csv"));
    std::fs::write(&shots, drives_csv(n)).expect("writing the launch file");
    g.bench_function("smash_flight_csv_100k", |b| {
        b.iter(|| fly_csv_file(&shots, &out, &cfg, Default::default(), CHUNK_BYTES).expect("flies"))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
