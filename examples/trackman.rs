//! Fly TrackMan's PGA Tour averages and print the per-club errors (the table of
//! docs/flight-models.md).
//!
//! `cargo run --release --example trackman -- [MODEL] [TEMPERATURE_C] [ELEVATION_M] [RH_PCT]`
//! (defaults: fmm2022-tour, the model calibrated on these tables, and the default atmosphere).

use smash::flight::trackman::PGA_TOUR;
use smash::flight::{fly, AeroModel, Atmosphere, FlightConfig};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let num = |i: usize| args.get(i).map(|s| s.parse::<f64>().expect("a number"));
    let mut atm = Atmosphere::default();
    if let Some(t) = num(1) {
        atm.temperature_c = t;
    }
    if let Some(h) = num(2) {
        atm.elevation_m = Some(h);
    }
    if let Some(rh) = num(3) {
        atm.humidity_pct = rh;
    }
    let mut cfg = FlightConfig {
        aero: AeroModel::from_name(args.first().map(String::as_str).unwrap_or("fmm2022-tour"))
            .expect("a model name"),
        air: atm.air().expect("a valid atmosphere"),
        ..FlightConfig::default()
    };
    if let Some(tau) = num(4) {
        cfg.spin_decay = if tau > 0.0 {
            smash::flight::SpinDecay::Exponential {
                time_constant_s: tau,
            }
        } else {
            smash::flight::SpinDecay::Moment
        };
    }
    if let Some(k) = num(5) {
        cfg.ball.inertia_kg_m2 /= k;
    }
    println!(
        "model {}, air {:.4} kg/m³, viscosity {:.4e} Pa·s",
        cfg.aero.name(),
        cfg.air.density_kg_m3,
        cfg.air.viscosity_pa_s
    );
    let launches: Vec<_> = PGA_TOUR.iter().map(|r| r.launch()).collect();
    let flights = fly(&cfg, &launches);
    println!("| club | ball speed mph | launch ° | spin rpm | carry yd (TrackMan) | carry yd (model) | error % | apex yd (TM / model) | land ° (TM / model) |");
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut errs = Vec::new();
    let mut land = Vec::new();
    for (r, f) in PGA_TOUR.iter().zip(&flights) {
        let f = f.as_ref().expect("flies");
        let e = 100.0 * (f.carry_yd() / r.carry_yd - 1.0);
        errs.push(e.abs());
        land.push((f.land_angle_deg() - r.land_angle_deg).abs());
        println!(
            "| {} | {} | {} | {} | {} | {:.1} | {:+.1} | {} / {:.1} | {} / {:.1} |",
            r.club,
            r.ball_speed_mph,
            r.launch_angle_deg,
            r.spin_rpm,
            r.carry_yd,
            f.carry_yd(),
            e,
            r.max_height_yd,
            f.apex_yd(),
            r.land_angle_deg,
            f.land_angle_deg()
        );
    }
    errs.sort_by(f64::total_cmp);
    let med = 0.5 * (errs[5] + errs[6]);
    println!(
        "median |carry error| {med:.2} %, worst {:.2} %, worst |land-angle error| {:.1}°",
        errs[11],
        land.iter().cloned().fold(0.0, f64::max)
    );
}
