//! The spread of drives the flight benchmarks, the throughput example and the batching tests
//! fly: a deterministic low-discrepancy walk (golden-ratio-like increments, one per variable)
//! through 150–180 mph of ball speed, 8–14° of launch, ±3° of azimuth, 2000–3200 rpm of
//! backspin and ±600 rpm of sidespin, so that the launches arrive in no particular order of
//! hang time. One definition, so that a figure of the bench and of a test are of the same
//! drives.

use super::FlightLaunch;

/// Drive `k` of the spread in file units: ball speed mph, launch angle deg, azimuth deg,
/// backspin rpm, sidespin rpm (the order of [`FlightLaunch::from_file_units`]).
pub fn drive_file_units(k: usize) -> [f64; 5] {
    let frac = |a: f64| (k as f64 * a).fract();
    [
        150.0 + 30.0 * frac(0.618_033_988_7),
        8.0 + 6.0 * frac(0.754_877_666_2),
        -3.0 + 6.0 * frac(0.569_840_290_9),
        2000.0 + 1200.0 * frac(0.438_846_845_8),
        -600.0 + 1200.0 * frac(0.352_201_997_2),
    ]
}

/// The first `n` drives of the spread.
pub fn drives(n: usize) -> Vec<FlightLaunch> {
    (0..n)
        .map(|k| {
            let [v, a, az, back, side] = drive_file_units(k);
            FlightLaunch::from_file_units(v, a, az, back, side)
        })
        .collect()
}
