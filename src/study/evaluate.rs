//! The summary metrics of one design: the impacts [`evaluate`] computes and how they reduce to
//! the metrics defined in [`super::metrics`] (names, units, [`Output`]s).

use crate::physics::{ImpactModel, LaunchComponent};
use crate::sweep::kernel::{FaceMapKernel, LaunchGrid};
use crate::units::{mm, mph};

use super::distribution::SwingGroup;
use super::metrics::{ls_slope, Output};
use super::spec::Study;

/// Probe offsets `0, s, 2s, …` up to `L` (inclusive when `L` is a multiple of `s`), mm.
fn probe_offsets(study: &Study) -> Vec<f64> {
    let p = study.probe;
    let n = (p.half_width_mm / p.step_mm + 1e-9).floor() as usize;
    (0..=n).map(|i| i as f64 * p.step_mm).collect()
}

/// Number of impacts [`evaluate`] computes for one design.
pub fn impacts_per_design(study: &Study, groups: &[SwingGroup]) -> usize {
    let n = probe_offsets(study).len();
    // CoF, then the horizontal line (2n − 1 points) and the vertical line (2n − 1 points).
    1 + 2 * (2 * n - 1) + groups.iter().map(|g| g.weights.len()).sum::<usize>()
}

/// All metrics of one model, in [`metric_names`] order. `groups` is the study distribution's
/// impacts (empty without a distribution).
pub fn evaluate(model: &ImpactModel, study: &Study, groups: &[SwingGroup]) -> Vec<f64> {
    let offs = probe_offsets(study);
    let n = offs.len();
    // Line coordinates from −L to L.
    let line: Vec<f64> = offs
        .iter()
        .rev()
        .map(|o| -o)
        .chain(offs.iter().skip(1).copied())
        .collect();
    let mut ys = vec![0.0];
    let mut zs = vec![0.0];
    for &c in &line {
        ys.push(0.0);
        zs.push(mm(c));
    }
    for &c in &line {
        ys.push(mm(c));
        zs.push(0.0);
    }
    let swing = study.swing;
    let club_speed = mph(swing.club_speed_mph);
    let kernel = FaceMapKernel::new(model, &swing.delivery(0.0, 0.0));
    let mut g = LaunchGrid::with_len(ys.len());
    kernel.eval_points(&ys, &zs, g.row_out(0, ys.len()));

    let mut out: Vec<f64> = Output::ALL
        .iter()
        .map(|o| o.file_value(&g, 0, club_speed))
        .collect();
    let m = line.len();
    let val = |o: Output, start: usize, k: usize| o.file_value(&g, start + k, club_speed);
    let speed = Output::Launch(LaunchComponent::BallSpeed);
    let h0 = 1; // first point of the horizontal line (z = −L)
    let v0 = 1 + m; // first point of the vertical line (y = −L)
    let centre = n - 1; // index of 0 within the line
    let side = |start: usize, range: std::ops::Range<usize>, sign: f64| {
        let x: Vec<f64> = range.clone().map(|k| line[k]).collect();
        let v: Vec<f64> = range.map(|k| val(speed, start, k)).collect();
        -sign * ls_slope(&x, &v)
    };
    out.push(side(h0, centre..m, 1.0)); // toe: +z
    out.push(side(h0, 0..centre + 1, -1.0)); // heel: −z
    out.push(side(v0, centre..m, 1.0)); // crown: +y
    out.push(side(v0, 0..centre + 1, -1.0)); // sole: −y
    let side_spin: Vec<f64> = (0..m)
        .map(|k| val(Output::Launch(LaunchComponent::Sidespin), h0, k))
        .collect();
    out.push(ls_slope(&line, &side_spin));
    let back_spin: Vec<f64> = (0..m)
        .map(|k| val(Output::Launch(LaunchComponent::Backspin), v0, k))
        .collect();
    out.push(ls_slope(&line, &back_spin));

    if !groups.is_empty() {
        let mut sum = [0.0; 6];
        let mut sum2 = [0.0; 6];
        let mut samples: Vec<([f64; 6], f64)> = Vec::new();
        for grp in groups {
            let k = FaceMapKernel::new(model, &grp.swing.delivery(0.0, 0.0));
            let mut lg = LaunchGrid::with_len(grp.ys_m.len());
            k.eval_points(&grp.ys_m, &grp.zs_m, lg.row_out(0, grp.ys_m.len()));
            let cs = mph(grp.swing.club_speed_mph);
            for (i, w) in grp.weights.iter().enumerate() {
                let v = Output::ALL.map(|o| o.file_value(&lg, i, cs));
                for j in 0..6 {
                    sum[j] += w * v[j];
                }
                samples.push((v, *w));
            }
        }
        for (v, w) in &samples {
            for j in 0..6 {
                sum2[j] += w * (v[j] - sum[j]).powi(2);
            }
        }
        out.extend(sum);
        out.extend(sum2.map(f64::sqrt));
    }
    out
}
