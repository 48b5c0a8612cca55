//! Fly N deterministic drives (`smash::flight::workload`, as `benches/flight.rs` does) and
//! print the rate; time the whole process with `/usr/bin/time` to get its CPU time.
//!
//! `cargo run --release --example flight_throughput -- [N]`

use smash::flight::{fly, FlightConfig};

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse().expect("a count"))
        .unwrap_or(1_000_000);
    let ls = smash::flight::workload::drives(n);
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
