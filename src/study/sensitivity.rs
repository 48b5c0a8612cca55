//! Sensitivities of the maps and metrics to the design variables, at the base design.
//!
//! Central differences: `d f / d x ≈ (f(x₀ + h) − f(x₀ − h)) / (2h)` with `x₀` the variable's
//! neutral value (the base club) and `h` its step (defaults: 0.5 mm for mass moves and CoM
//! offsets, 0.01 for scales, 10 g·cm² for principal-moment changes; `[sensitivity] steps`
//! overrides). The truncation error is `O(h²)`; every output is smooth in every variable.
//!
//! The ranked table orders, within each metric, the variables by the size of the change a
//! *reference change* of the variable makes (1 mm, 0.1 in scale, 100 g·cm²), so variables of
//! different units can be compared.

use rayon::prelude::*;

use crate::sweep::kernel::face_map;
use crate::units::{mm, mph};

use super::design::{Design, DesignVar};
use super::metrics::{evaluate, Output};
use super::sweep::{design_model, Prepared};
use super::StudyError;

/// The sensitivities to one design variable.
#[derive(Debug, Clone, PartialEq)]
pub struct Sensitivity {
    /// The variable.
    pub var: DesignVar,
    /// Central-difference step, in the variable's unit.
    pub step: f64,
    /// d metric / d variable, in `metric_names` order (metric unit per variable unit).
    pub metrics: Vec<f64>,
    /// d output / d variable over the grid, per [`Output::ALL`], file units per variable unit;
    /// NaN where either side is off the face.
    pub maps: Vec<Vec<f64>>,
}

/// Sensitivities to every variable of `[sensitivity]` (empty if the study has none).
pub fn sensitivities(p: &Prepared) -> Result<Vec<Sensitivity>, StudyError> {
    let Some(vars) = &p.study.sensitivity else {
        return Ok(Vec::new());
    };
    let ys: Vec<f64> = p.ys_mm.iter().map(|v| mm(*v)).collect();
    let zs: Vec<f64> = p.zs_mm.iter().map(|v| mm(*v)).collect();
    let delivery = p.study.swing.delivery(0.0, 0.0);
    let club_speed = mph(p.study.swing.club_speed_mph);
    vars.iter()
        .map(|&(var, h)| {
            let base = Design::default();
            let x0 = var.neutral();
            let plus = design_model(&p.study, &base.with(var, x0 + h))?;
            let minus = design_model(&p.study, &base.with(var, x0 - h))?;
            let (mp, mm_) = rayon::join(
                || evaluate(&plus, &p.study, &p.groups),
                || evaluate(&minus, &p.study, &p.groups),
            );
            let metrics = mp
                .iter()
                .zip(&mm_)
                .map(|(a, b)| (a - b) / (2.0 * h))
                .collect();
            let gp = face_map(&plus, &delivery, &ys, &zs);
            let gm = face_map(&minus, &delivery, &ys, &zs);
            let maps = Output::ALL
                .iter()
                .map(|o| {
                    (0..gp.len())
                        .into_par_iter()
                        .map(|i| {
                            (o.file_value(&gp, i, club_speed) - o.file_value(&gm, i, club_speed))
                                / (2.0 * h)
                        })
                        .collect()
                })
                .collect();
            Ok(Sensitivity {
                var,
                step: h,
                metrics,
                maps,
            })
        })
        .collect()
}
