//! The tables of a comparison: the errors, the Table 2 blocks, the face bins, the quantile bins
//! and the correlations with the delivery variables.

use super::{
    BinnedRow, BinnedTable, CompareError, CompareOptions, ComponentError, CorrelationEntry,
    FaceBin, FaceResiduals, GroupBias, Variable, VARIABLES,
};
use crate::model::Shot;
use crate::physics::{Launch, LaunchComponent};
use crate::stats::{pearson, student_t_two_sided_p, Summary};

pub(super) fn errors_of(
    shots: &[Shot],
    predicted: &[Launch],
) -> Result<Vec<[f64; 5]>, CompareError> {
    if shots.len() != predicted.len() {
        return Err(CompareError::Length {
            shots: shots.len(),
            predictions: predicted.len(),
        });
    }
    if shots.is_empty() {
        return Err(CompareError::Empty);
    }
    shots
        .iter()
        .zip(predicted)
        .map(|(s, p)| {
            let m = s
                .measured
                .as_ref()
                .ok_or_else(|| CompareError::NoMeasurement {
                    shot_id: s.id.clone(),
                })?;
            Ok(LaunchComponent::ALL.map(|c| p.get_file(c) - m.get_file(c)))
        })
        .collect()
}

pub(super) fn group_errors(group: &str, errs: &[&[f64; 5]], alpha: f64) -> GroupBias {
    GroupBias {
        group: group.to_owned(),
        n: errs.len(),
        components: LaunchComponent::ALL
            .iter()
            .map(|&c| {
                let xs: Vec<f64> = errs.iter().map(|e| e[c.index()]).collect();
                let summary = Summary::of(&xs);
                ComponentError {
                    component: c.column(),
                    unit: c.unit(),
                    significant: summary.significant(alpha),
                    summary,
                }
            })
            .collect(),
    }
}

pub(super) fn face_residuals(
    shots: &[Shot],
    errs: &[[f64; 5]],
    o: &CompareOptions,
) -> Result<FaceResiduals, CompareError> {
    let b = o.face_bin_mm;
    let idx = |v_m: f64| (v_m * 1e3 / b).floor() as i64;
    let iy: Vec<i64> = shots.iter().map(|s| idx(s.delivery.impact_y_m)).collect();
    let iz: Vec<i64> = shots.iter().map(|s| idx(s.delivery.impact_z_m)).collect();
    let range = |v: &[i64]| (*v.iter().min().unwrap(), *v.iter().max().unwrap());
    let ((y0, y1), (z0, z1)) = (range(&iy), range(&iz));
    let span = |lo: i64, hi: i64| {
        usize::try_from(hi.saturating_sub(lo)).map_or(usize::MAX, |d| d.saturating_add(1))
    };
    crate::limits::count_product(
        "face bins",
        &[("rows", span(y0, y1)), ("columns", span(z0, z1))],
        crate::limits::MAX_FACE_BINS,
        "use a larger --bin-mm",
    )?;
    let ys_mm: Vec<f64> = (y0..=y1).map(|i| (i as f64 + 0.5) * b).collect();
    let zs_mm: Vec<f64> = (z0..=z1).map(|i| (i as f64 + 0.5) * b).collect();
    let mut cells: Vec<Vec<usize>> = vec![Vec::new(); ys_mm.len() * zs_mm.len()];
    for (k, (y, z)) in iy.iter().zip(&iz).enumerate() {
        cells[(y - y0) as usize * zs_mm.len() + (z - z0) as usize].push(k);
    }
    let bins = cells
        .iter()
        .enumerate()
        .map(|(cell, members)| {
            let enough = members.len() >= o.min_bin_count;
            let per: Vec<Summary> = LaunchComponent::ALL
                .iter()
                .map(|c| {
                    let xs: Vec<f64> = members.iter().map(|&k| errs[k][c.index()]).collect();
                    Summary::of(&xs)
                })
                .collect();
            FaceBin {
                y_mm: ys_mm[cell / zs_mm.len()],
                z_mm: zs_mm[cell % zs_mm.len()],
                count: members.len(),
                mean: per.iter().map(|s| s.mean.filter(|_| enough)).collect(),
                std: per.iter().map(|s| s.std.filter(|_| enough)).collect(),
            }
        })
        .collect();
    Ok(FaceResiduals {
        bin_mm: b,
        min_count: o.min_bin_count,
        ys_mm,
        zs_mm,
        bins,
    })
}

pub(super) fn binned(v: &Variable, shots: &[Shot], errs: &[[f64; 5]], nbins: usize) -> BinnedTable {
    let mut order: Vec<usize> = (0..shots.len()).collect();
    let x: Vec<f64> = shots.iter().map(|s| v.get(s)).collect();
    order.sort_by(|&a, &b| x[a].total_cmp(&x[b]));
    let nbins = nbins.clamp(1, shots.len());
    let rows = (0..nbins)
        .map(|i| {
            let part = &order[i * order.len() / nbins..(i + 1) * order.len() / nbins];
            BinnedRow {
                lo: x[part[0]],
                hi: x[*part.last().expect("non-empty bin")],
                count: part.len(),
                mean: LaunchComponent::ALL
                    .iter()
                    .map(|c| {
                        let xs: Vec<f64> = part.iter().map(|&k| errs[k][c.index()]).collect();
                        Summary::of(&xs).mean
                    })
                    .collect(),
            }
        })
        .collect();
    BinnedTable {
        variable: v.name(),
        rows,
    }
}

/// Welch's t between two samples' means; `None` when undefined.
pub(super) fn welch_t(a: &[f64], b: &[f64]) -> Option<(f64, f64)> {
    let (sa, sb) = (Summary::of(a), Summary::of(b));
    let (ma, mb, ea, eb) = (sa.mean?, sb.mean?, sa.sem?, sb.sem?);
    let se2 = ea * ea + eb * eb;
    if !(se2 > 0.0) {
        return None;
    }
    let t = (ma - mb) / se2.sqrt();
    let df = se2 * se2 / (ea.powi(4) / (a.len() - 1) as f64 + eb.powi(4) / (b.len() - 1) as f64);
    Some((t, student_t_two_sided_p(t, df)))
}

/// Every component × variable correlation of the errors.
pub(super) fn correlations(
    shots: &[Shot],
    errs: &[[f64; 5]],
    o: &CompareOptions,
) -> Vec<CorrelationEntry> {
    let mut out = Vec::new();
    for c in LaunchComponent::ALL {
        let y: Vec<f64> = errs.iter().map(|e| e[c.index()]).collect();
        for v in &VARIABLES {
            let x: Vec<f64> = shots.iter().map(|s| v.get(s)).collect();
            if let Some(k) = pearson(&x, &y) {
                let significant = k.p < o.alpha;
                out.push(CorrelationEntry {
                    component: c.column(),
                    variable: v.name(),
                    n: k.n,
                    r: k.r,
                    t: k.t,
                    p: k.p,
                    significant,
                    strong: significant && k.r.abs() >= o.strong_r,
                });
            }
        }
    }
    out
}
