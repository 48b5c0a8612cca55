//! The kernel's outputs: [`LaunchGrid`] (structure of arrays over impact points) and the
//! mutable [`RowOut`] slices one row or point set is written into.

use crate::physics::LaunchComponent;

/// Launch outputs over a set of impact points, structure of arrays, SI units, row-major for
/// grids. Invalid points (off the face torus, or club not approaching the ball) have
/// `valid = false` and NaN outputs.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LaunchGrid {
    /// Ball speed, m/s.
    pub ball_speed_m_s: Vec<f64>,
    /// Launch angle, rad (+ up).
    pub launch_angle_rad: Vec<f64>,
    /// Azimuth, rad (+ right of target).
    pub azimuth_rad: Vec<f64>,
    /// Backspin, rad/s.
    pub backspin_rad_s: Vec<f64>,
    /// Sidespin, rad/s (+ slice for a right-hander).
    pub sidespin_rad_s: Vec<f64>,
    /// Whether the impact at this point is physical (on the face, club approaching the ball).
    pub valid: Vec<bool>,
}

/// Mutable output slices for one row or point set (same fields as [`LaunchGrid`], equal
/// lengths).
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
    /// Validity flags.
    pub valid: &'a mut [bool],
}

impl RowOut<'_> {
    /// Number of points (the length of every slice).
    pub fn len(&self) -> usize {
        self.valid.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.valid.is_empty()
    }

    pub(super) fn assert_len(&self, n: usize) {
        for (name, len) in [
            ("ball_speed_m_s", self.ball_speed_m_s.len()),
            ("launch_angle_rad", self.launch_angle_rad.len()),
            ("azimuth_rad", self.azimuth_rad.len()),
            ("backspin_rad_s", self.backspin_rad_s.len()),
            ("sidespin_rad_s", self.sidespin_rad_s.len()),
            ("valid", self.valid.len()),
        ] {
            assert_eq!(len, n, "RowOut.{name} has {len} entries for {n} points");
        }
    }
}

impl LaunchGrid {
    /// A grid of `n` points, all NaN and invalid.
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

    /// Whether the grid has no points.
    pub fn is_empty(&self) -> bool {
        self.valid.is_empty()
    }

    /// One launch component, SI units (m/s, rad, rad/s).
    pub fn component(&self, c: LaunchComponent) -> &[f64] {
        match c {
            LaunchComponent::BallSpeed => &self.ball_speed_m_s,
            LaunchComponent::LaunchAngle => &self.launch_angle_rad,
            LaunchComponent::Azimuth => &self.azimuth_rad,
            LaunchComponent::Backspin => &self.backspin_rad_s,
            LaunchComponent::Sidespin => &self.sidespin_rad_s,
        }
    }

    /// Output slices for the points `start..start + len`.
    ///
    /// # Panics
    /// If the range is outside the grid.
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

    /// Resize to `n` points (allocates only if the capacity is too small).
    pub fn resize(&mut self, n: usize) {
        self.ball_speed_m_s.resize(n, f64::NAN);
        self.launch_angle_rad.resize(n, f64::NAN);
        self.azimuth_rad.resize(n, f64::NAN);
        self.backspin_rad_s.resize(n, f64::NAN);
        self.sidespin_rad_s.resize(n, f64::NAN);
        self.valid.resize(n, false);
    }

    /// Output slices for the whole grid.
    pub fn all_out(&mut self) -> RowOut<'_> {
        let n = self.len();
        self.row_out(0, n)
    }
}

/// Mark every point of `out` invalid (NaN outputs).
pub(super) fn fill_invalid(out: RowOut<'_>) {
    out.ball_speed_m_s.fill(f64::NAN);
    out.launch_angle_rad.fill(f64::NAN);
    out.azimuth_rad.fill(f64::NAN);
    out.backspin_rad_s.fill(f64::NAN);
    out.sidespin_rad_s.fill(f64::NAN);
    out.valid.fill(false);
}
