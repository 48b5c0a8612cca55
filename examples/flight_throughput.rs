//! Fly N deterministic drives (as in `benches/flight.rs`) and print the rate; time the whole
//! process with `/usr/bin/time` to get its CPU time.
//!
//! `cargo run --release --example flight_throughput -- [N]`

use smash::flight::{fly, FlightConfig, FlightLaunch};

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse().expect("a count"))
        .unwrap_or(1_000_000);
    let frac = |k: usize, a: f64| (k as f64 * a).fract();
    let ls: Vec<FlightLaunch> = (0..n)
        .map(|k| {
            FlightLaunch::from_file_units(
                150.0 + 30.0 * frac(k, 0.618_033_988_7),
                8.0 + 6.0 * frac(k, 0.754_877_666_2),
                -3.0 + 6.0 * frac(k, 0.569_840_290_9),
                2000.0 + 1200.0 * frac(k, 0.438_846_845_8),
                -600.0 + 1200.0 * frac(k, 0.352_201_997_2),
            )
        })
        .collect();
    let cfg = FlightConfig::default();
    let t0 = std::time::Instant::now();
    let out = fly(&cfg, &ls);
    let s = t0.elapsed().as_secs_f64();
    let ok = out.iter().filter(|r| r.is_ok()).count();
    let mean = out.iter().flatten().map(|f| f.carry_yd()).sum::<f64>() / ok as f64;
    println!(
        "{n} drives ({ok} landed, mean carry {mean:.1} yd) in {s:.3} s wall: {:.0} drives/s",
        n as f64 / s
    );
}
