//! Face-map kernel: launch conditions over many impact locations for one model and one swing.
//!
//! This is the simple reference implementation: every point is one call of
//! [`ImpactModel::solve`], rows in parallel with rayon. It is bit-deterministic per point and
//! independent of the thread count. Points that cannot be computed (off the face torus, or the
//! club not approaching the ball there) are marked `valid = false` with NaN values; callers turn
//! them into empty cells.

use rayon::prelude::*;

use crate::physics::{Delivery, ImpactModel, LaunchComponent};

/// Launch conditions over a set of impact locations, structure of arrays, SI units, row-major.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LaunchGrid {
    /// Ball speed, m/s.
    pub ball_speed_m_s: Vec<f64>,
    /// Launch angle, rad.
    pub launch_angle_rad: Vec<f64>,
    /// Azimuth, rad (+ right of target).
    pub azimuth_rad: Vec<f64>,
    /// Backspin, rad/s.
    pub backspin_rad_s: Vec<f64>,
    /// Sidespin, rad/s (+ slice for a right-hander).
    pub sidespin_rad_s: Vec<f64>,
    /// Whether the point could be computed (on the face, club approaching).
    pub valid: Vec<bool>,
}

/// Mutable views of a contiguous run of points of a [`LaunchGrid`].
#[derive(Debug)]
pub struct RowOut<'a> {
    /// Ball speed, m/s.
    pub ball_speed_m_s: &'a mut [f64],
    /// Launch angle, rad.
    pub launch_angle_rad: &'a mut [f64],
    /// Azimuth, rad.
    pub azimuth_rad: &'a mut [f64],
    /// Backspin, rad/s.
    pub backspin_rad_s: &'a mut [f64],
    /// Sidespin, rad/s.
    pub sidespin_rad_s: &'a mut [f64],
    /// Validity.
    pub valid: &'a mut [bool],
}

impl LaunchGrid {
    /// `n` points, all invalid (NaN).
    pub fn with_len(n: usize) -> Self {
        Self {
            ball_speed_m_s: vec![f64::NAN; n],
            launch_angle_rad: vec![f64::NAN; n],
            azimuth_rad: vec![f64::NAN; n],
            backspin_rad_s: vec![f64::NAN; n],
            sidespin_rad_s: vec![f64::NAN; n],
            valid: vec![false; n],
        }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.valid.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.valid.is_empty()
    }

    /// One component, SI units.
    pub fn component(&self, c: LaunchComponent) -> &[f64] {
        match c {
            LaunchComponent::BallSpeed => &self.ball_speed_m_s,
            LaunchComponent::LaunchAngle => &self.launch_angle_rad,
            LaunchComponent::Azimuth => &self.azimuth_rad,
            LaunchComponent::Backspin => &self.backspin_rad_s,
            LaunchComponent::Sidespin => &self.sidespin_rad_s,
        }
    }

    /// Views of points `start .. start + len`.
    pub fn row_out(&mut self, start: usize, len: usize) -> RowOut<'_> {
        let r = start..start + len;
        RowOut {
            ball_speed_m_s: &mut self.ball_speed_m_s[r.clone()],
            launch_angle_rad: &mut self.launch_angle_rad[r.clone()],
            azimuth_rad: &mut self.azimuth_rad[r.clone()],
            backspin_rad_s: &mut self.backspin_rad_s[r.clone()],
            sidespin_rad_s: &mut self.sidespin_rad_s[r.clone()],
            valid: &mut self.valid[r],
        }
    }
}

impl RowOut<'_> {
    fn len(&self) -> usize {
        self.valid.len()
    }

    #[inline]
    fn set(&mut self, i: usize, model: &ImpactModel, d: &Delivery) {
        match model.solve(d) {
            Ok(o) => {
                let l = o.launch();
                self.ball_speed_m_s[i] = l.ball_speed_m_s;
                self.launch_angle_rad[i] = l.launch_angle_rad;
                self.azimuth_rad[i] = l.azimuth_rad;
                self.backspin_rad_s[i] = l.backspin_rad_s;
                self.sidespin_rad_s[i] = l.sidespin_rad_s;
                self.valid[i] = true;
            }
            Err(_) => {
                self.ball_speed_m_s[i] = f64::NAN;
                self.launch_angle_rad[i] = f64::NAN;
                self.azimuth_rad[i] = f64::NAN;
                self.backspin_rad_s[i] = f64::NAN;
                self.sidespin_rad_s[i] = f64::NAN;
                self.valid[i] = false;
            }
        }
    }
}

/// One model and one swing, ready to evaluate many impact locations.
#[derive(Debug, Clone)]
pub struct FaceMapKernel {
    model: ImpactModel,
    delivery: Delivery,
}

impl FaceMapKernel {
    /// Kernel for `model` and the swing of `delivery` (its impact location is ignored).
    pub fn new(model: &ImpactModel, delivery: &Delivery) -> Self {
        Self {
            model: model.clone(),
            delivery: *delivery,
        }
    }

    /// Points `(y_m, zs_m[j])` into `out` (`out` has `zs_m.len()` points).
    pub fn eval_row(&self, y_m: f64, zs_m: &[f64], mut out: RowOut<'_>) {
        assert_eq!(out.len(), zs_m.len(), "eval_row: output length");
        let mut d = self.delivery;
        d.impact_y_m = y_m;
        for (j, &z) in zs_m.iter().enumerate() {
            d.impact_z_m = z;
            out.set(j, &self.model, &d);
        }
    }

    /// Points `(ys_m[i], zs_m[i])` into `out`.
    pub fn eval_points(&self, ys_m: &[f64], zs_m: &[f64], mut out: RowOut<'_>) {
        assert_eq!(ys_m.len(), zs_m.len(), "eval_points: ys and zs lengths");
        assert_eq!(out.len(), zs_m.len(), "eval_points: output length");
        let mut d = self.delivery;
        for (i, (&y, &z)) in ys_m.iter().zip(zs_m).enumerate() {
            d.impact_y_m = y;
            d.impact_z_m = z;
            out.set(i, &self.model, &d);
        }
    }
}

/// Launch over the grid `ys_m × zs_m` (row `i` is `ys_m[i]`), rows in parallel.
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

/// As [`face_map`], into an existing grid of `ys_m.len() × zs_m.len()` points.
pub fn face_map_into(
    model: &ImpactModel,
    delivery: &Delivery,
    ys_m: &[f64],
    zs_m: &[f64],
    out: &mut LaunchGrid,
) {
    let nz = zs_m.len();
    assert_eq!(out.len(), ys_m.len() * nz, "face_map_into: grid size");
    if nz == 0 {
        return;
    }
    let kernel = FaceMapKernel::new(model, delivery);
    let rows = out
        .ball_speed_m_s
        .par_chunks_mut(nz)
        .zip(out.launch_angle_rad.par_chunks_mut(nz))
        .zip(out.azimuth_rad.par_chunks_mut(nz))
        .zip(out.backspin_rad_s.par_chunks_mut(nz))
        .zip(out.sidespin_rad_s.par_chunks_mut(nz))
        .zip(out.valid.par_chunks_mut(nz));
    rows.zip(ys_m.par_iter())
        .for_each(|((((((bs, la), az), bk), sd), v), &y)| {
            kernel.eval_row(
                y,
                zs_m,
                RowOut {
                    ball_speed_m_s: bs,
                    launch_angle_rad: la,
                    azimuth_rad: az,
                    backspin_rad_s: bk,
                    sidespin_rad_s: sd,
                    valid: v,
                },
            );
        });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::club_file::parse_club;
    use std::path::Path;

    #[test]
    fn face_map_matches_solve_and_marks_off_face_points() {
        let club = parse_club(
            Path::new("club.toml"),
            include_str!("../../configs/clubs/paper_driver.toml"),
        )
        .unwrap();
        let model = club.model_for_group("all").unwrap();
        let d = Delivery {
            club_speed_m_s: 45.0,
            attack_angle_rad: 0.0,
            club_path_rad: 0.0,
            dynamic_loft_rad: 0.2,
            face_angle_rad: 0.0,
            lie_tilt_rad: 0.0,
            club_omega_rad_s: nalgebra::Vector3::zeros(),
            impact_y_m: 0.0,
            impact_z_m: 0.0,
        };
        let ys = [-0.4, -0.01, 0.0, 0.02];
        let zs = [-0.03, 0.0, 0.015];
        let g = face_map(&model, &d, &ys, &zs);
        for (i, &y) in ys.iter().enumerate() {
            for (j, &z) in zs.iter().enumerate() {
                let k = i * zs.len() + j;
                let r = model.solve(&Delivery {
                    impact_y_m: y,
                    impact_z_m: z,
                    ..d
                });
                match r {
                    Ok(o) => {
                        assert!(g.valid[k]);
                        assert_eq!(g.ball_speed_m_s[k], o.launch().ball_speed_m_s);
                        assert_eq!(g.sidespin_rad_s[k], o.launch().sidespin_rad_s);
                    }
                    Err(_) => {
                        assert!(!g.valid[k] && g.backspin_rad_s[k].is_nan());
                    }
                }
            }
        }
        assert!(!g.valid[0], "y = -400 mm is off a 305 mm roll torus");
    }
}
