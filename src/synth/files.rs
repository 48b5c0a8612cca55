//! Files of a synthetic experiment: the shots CSV (the shots-file format of docs/conventions.md,
//! readable by [`crate::data::shots::read_shots`]) and the truth TOML. Builds bytes only.

use std::fmt::Write as _;

use super::{config_toml, csv_header, SynthConfig, SynthRun};
use crate::data::fmt_f64;

/// Shots CSV: `shot_id, group, golfer, shaft_mass_g`, the measured delivery, the measured launch.
/// Floats are written in shortest round-trip form, so reading the file gives the generator's
/// values bit for bit.
pub fn synth_shots_csv(run: &SynthRun) -> Vec<u8> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(csv_header()).expect("writing to memory");
    let mut row: Vec<String> = Vec::with_capacity(20);
    for s in &run.shots {
        row.clear();
        row.push(s.id.clone());
        row.push(s.group.clone());
        row.push(s.golfer.clone());
        row.push(fmt_f64(s.shaft_mass_g));
        row.extend(s.delivery.iter().map(|&v| fmt_f64(v)));
        row.extend(s.launch.iter().map(|&v| fmt_f64(v)));
        w.write_record(&row).expect("writing to memory");
    }
    w.into_inner().expect("flushing memory")
}

/// Truth TOML: a header, the resolved configuration (itself a valid synth config that
/// regenerates the same shots) and a `[truth]` table with what the run produced.
pub fn truth_toml(cfg: &SynthConfig, run: &SynthRun, source: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# Truth of a synthetic experiment written by smash {} from {source}.",
        env!("CARGO_PKG_VERSION")
    );
    let _ = writeln!(
        s,
        "# Everything below is the resolved configuration: `smash synth --config` on this file"
    );
    let _ = writeln!(
        s,
        "# regenerates the same shots. [[hidden]] tables have the shape of club [[effect]] tables."
    );
    s.push_str(&config_toml(cfg));
    let cors: Vec<f64> = run.shots.iter().map(|x| x.cor_effective).collect();
    let (lo, hi) = cors
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &c| {
            (a.min(c), b.max(c))
        });
    let _ = writeln!(s, "\n[truth]  # what the run produced (ignored on input)");
    let _ = writeln!(s, "shots = {}", run.shots.len());
    let _ = writeln!(s, "redrawn = {}", run.redrawn);
    if lo.is_finite() {
        let _ = writeln!(s, "cor_effective_min = {lo:?}");
        let _ = writeln!(s, "cor_effective_max = {hi:?}");
    }
    s
}
