//! The kernel's entry points: a row, a set of points, a grid (on the calling thread or rows in
//! parallel), and [`face_map`] / [`face_map_into`] for one (model, delivery).

use rayon::prelude::*;

use super::jobs::{PointsJob, RowJob};
use super::{simd_level, FaceMapKernel, LaunchGrid, RowOut, SimdLevel, ROWS_PER_TASK};
use crate::lanes::V;
use crate::physics::{Delivery, ImpactModel};

impl FaceMapKernel {
    /// Evaluate one row: the points `(y_m, zs_m[j])` into `out` (each slice of `zs_m.len()`).
    ///
    /// # Panics
    /// If an output slice has another length than `zs_m`.
    pub fn eval_row(&self, y_m: f64, zs_m: &[f64], out: RowOut<'_>) {
        self.eval_row_on(simd_level(), y_m, zs_m, out)
    }

    /// [`FaceMapKernel::eval_row`] on a given code path (to check that all paths give the same
    /// bits). A path this machine does not support falls back to [`SimdLevel::Portable`].
    ///
    /// # Panics
    /// If an output slice has another length than `zs_m`.
    pub fn eval_row_on(&self, level: SimdLevel, y_m: f64, zs_m: &[f64], out: RowOut<'_>) {
        out.assert_len(zs_m.len());
        let row = self.row(V::splat(y_m));
        let level = level.or_supported();
        self.dispatch(
            level,
            &RowJob {
                row: &row,
                zs: zs_m,
            },
            out,
        );
    }

    /// Evaluate arbitrary points `(ys_m[i], zs_m[i])` into `out`.
    ///
    /// # Panics
    /// If `ys_m` and `zs_m` differ in length, or an output slice has another length.
    pub fn eval_points(&self, ys_m: &[f64], zs_m: &[f64], out: RowOut<'_>) {
        self.eval_points_on(simd_level(), ys_m, zs_m, out)
    }

    /// [`FaceMapKernel::eval_points`] on a given code path (see
    /// [`FaceMapKernel::eval_row_on`]).
    ///
    /// # Panics
    /// As [`FaceMapKernel::eval_points`].
    pub fn eval_points_on(&self, level: SimdLevel, ys_m: &[f64], zs_m: &[f64], out: RowOut<'_>) {
        assert_eq!(
            ys_m.len(),
            zs_m.len(),
            "eval_points: {} heights for {} heel-toe locations",
            ys_m.len(),
            zs_m.len()
        );
        out.assert_len(zs_m.len());
        let level = level.or_supported();
        self.dispatch(level, &PointsJob { ys: ys_m, zs: zs_m }, out);
    }

    /// Evaluate the grid `ys_m × zs_m` (row-major) on the calling thread.
    ///
    /// # Panics
    /// If `out` does not have `ys_m.len() · zs_m.len()` points.
    pub fn eval_grid(&self, ys_m: &[f64], zs_m: &[f64], out: &mut LaunchGrid) {
        let nz = zs_m.len();
        assert_eq!(out.len(), ys_m.len() * nz, "grid size");
        for (i, &y) in ys_m.iter().enumerate() {
            self.eval_row(y, zs_m, out.row_out(i * nz, nz));
        }
    }

    /// Evaluate the grid `ys_m × zs_m` (row-major), rows in parallel on the rayon pool.
    /// Bit-identical to [`FaceMapKernel::eval_grid`] for any number of threads.
    ///
    /// # Panics
    /// If `out` does not have `ys_m.len() · zs_m.len()` points.
    pub fn par_eval_grid(&self, ys_m: &[f64], zs_m: &[f64], out: &mut LaunchGrid) {
        let nz = zs_m.len();
        assert_eq!(out.len(), ys_m.len() * nz, "grid size");
        if nz == 0 || ys_m.is_empty() {
            return;
        }
        (
            ys_m.par_iter(),
            out.ball_speed_m_s.par_chunks_mut(nz),
            out.launch_angle_rad.par_chunks_mut(nz),
            out.azimuth_rad.par_chunks_mut(nz),
            out.backspin_rad_s.par_chunks_mut(nz),
            out.sidespin_rad_s.par_chunks_mut(nz),
            out.valid.par_chunks_mut(nz),
        )
            .into_par_iter()
            .with_min_len(ROWS_PER_TASK)
            .for_each(
                |(
                    &y,
                    ball_speed_m_s,
                    launch_angle_rad,
                    azimuth_rad,
                    backspin_rad_s,
                    sidespin_rad_s,
                    valid,
                )| {
                    self.eval_row(
                        y,
                        zs_m,
                        RowOut {
                            ball_speed_m_s,
                            launch_angle_rad,
                            azimuth_rad,
                            backspin_rad_s,
                            sidespin_rad_s,
                            valid,
                        },
                    )
                },
            );
    }
}

/// Face map over the grid `ys_m × zs_m` (row-major: row `i` is `ys_m[i]`), rows in parallel
/// with rayon. Deterministic: the result does not depend on the number of threads.
pub fn face_map(
    model: &ImpactModel,
    delivery: &Delivery,
    ys_m: &[f64],
    zs_m: &[f64],
) -> LaunchGrid {
    let mut out = LaunchGrid::with_len(ys_m.len() * zs_m.len());
    face_map_into(model, delivery, ys_m, zs_m, &mut out);
    out
}

/// Same as [`face_map`], into a caller-provided grid, for repeated sweeps. `out` is resized to
/// `ys_m.len() · zs_m.len()` points if needed (no allocation when it already has that size).
pub fn face_map_into(
    model: &ImpactModel,
    delivery: &Delivery,
    ys_m: &[f64],
    zs_m: &[f64],
    out: &mut LaunchGrid,
) {
    out.resize(ys_m.len() * zs_m.len());
    FaceMapKernel::new(model, delivery).par_eval_grid(ys_m, zs_m, out);
}
