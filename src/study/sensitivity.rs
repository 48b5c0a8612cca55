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

use crate::sweep::kernel::{FaceMapKernel, LaunchGrid};
use crate::units::{mm, mph};

use super::design::{Design, DesignVar};
use super::evaluate::evaluate;
use super::metrics::Output;
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
    /// The face-map kernels of the designs at `x₀ + h` and `x₀ − h` (the maps are computed a
    /// band of rows at a time when written: see [`Sensitivity::map_rows`]).
    pub kernels: [FaceMapKernel; 2],
}

impl Sensitivity {
    /// d output / d variable on the grid rows `ys_m` (row-major over `zs_m`), file units per
    /// variable unit, for each output of `outputs` (into `out`, one vector each); NaN where
    /// either side is off the face.
    pub fn map_rows(
        &self,
        ys_m: &[f64],
        zs_m: &[f64],
        club_speed_m_s: f64,
        outputs: &[Output],
        out: &mut [Vec<f64>],
    ) {
        let n = ys_m.len() * zs_m.len();
        let (mut gp, mut gm) = (LaunchGrid::with_len(n), LaunchGrid::with_len(n));
        rayon::join(
            || self.kernels[0].par_eval_grid(ys_m, zs_m, &mut gp),
            || self.kernels[1].par_eval_grid(ys_m, zs_m, &mut gm),
        );
        let h2 = 2.0 * self.step;
        for (o, dst) in outputs.iter().zip(out.iter_mut()) {
            dst.clear();
            dst.par_extend((0..n).into_par_iter().map(|i| {
                (o.file_value(&gp, i, club_speed_m_s) - o.file_value(&gm, i, club_speed_m_s)) / h2
            }));
        }
    }

    /// The whole sensitivity maps of the study `p`, per [`Output::ALL`] (for small grids and
    /// checks; the outputs are written band by band).
    pub fn maps(&self, p: &Prepared) -> Vec<Vec<f64>> {
        let ys: Vec<f64> = p.ys_mm.iter().map(|v| mm(*v)).collect();
        let zs: Vec<f64> = p.zs_mm.iter().map(|v| mm(*v)).collect();
        let mut out = vec![Vec::new(); Output::ALL.len()];
        self.map_rows(
            &ys,
            &zs,
            mph(p.study.swing.club_speed_mph),
            &Output::ALL,
            &mut out,
        );
        out
    }
}

/// Sensitivities to every variable of `[sensitivity]` (empty if the study has none).
pub fn sensitivities(p: &Prepared) -> Result<Vec<Sensitivity>, StudyError> {
    let Some(vars) = &p.study.sensitivity else {
        return Ok(Vec::new());
    };
    let delivery = p.study.swing.delivery(0.0, 0.0);
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
            let kernels = [
                FaceMapKernel::new(&plus, &delivery),
                FaceMapKernel::new(&minus, &delivery),
            ];
            Ok(Sensitivity {
                var,
                step: h,
                metrics,
                kernels,
            })
        })
        .collect()
}
