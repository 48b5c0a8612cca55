//! Values an export gives twice, checked against each other: back and side spin against spin
//! rate and axis (`back = S cos a`, `side = S sin a`), and the smash factor against ball speed
//! over club speed. A few disagreements are reported; disagreement on most shots means the
//! mapping reads a column with the wrong sign or meaning, and the file is refused.

use std::path::Path;

use super::cell::list_lines;
use super::layout::Layout;
use crate::data::DataError;

/// Spin given both ways for one shot, rpm and deg.
pub(super) struct SpinCheck {
    back_rpm: f64,
    side_rpm: f64,
    rate_rpm: f64,
    axis_deg: f64,
}

impl SpinCheck {
    /// The shot's spin given both ways, when the export gives both and the cells hold them.
    pub(super) fn of(layout: &Layout, get: &dyn Fn(&str) -> Option<f64>) -> Option<Self> {
        if !layout.check_spin {
            return None;
        }
        Some(Self {
            back_rpm: get("backspin_rpm")?,
            side_rpm: get("sidespin_rpm")?,
            rate_rpm: get("spin_rate_rpm")?,
            axis_deg: get("spin_axis_deg")?,
        })
    }

    /// How far apart the two may be: 2 % of the rate plus 15 rpm covers the rounding of the
    /// axis to 0.1° (0.2 % of the rate) and of each spin to 1 rpm, and the vendors' own
    /// rounding of the rate to tens of rpm, with margin.
    fn tolerance_rpm(&self) -> f64 {
        0.02 * self.rate_rpm + 15.0
    }

    /// `None` when they agree, else what disagrees, and whether flipping the side spin's sign
    /// would make them agree.
    fn disagreement(&self) -> Option<(String, bool)> {
        let a = self.axis_deg.to_radians();
        let (back, side) = (self.rate_rpm * a.cos(), self.rate_rpm * a.sin());
        let tol = self.tolerance_rpm();
        if (self.back_rpm - back).abs() <= tol && (self.side_rpm - side).abs() <= tol {
            return None;
        }
        let flipped = (self.back_rpm - back).abs() <= tol && (self.side_rpm + side).abs() <= tol;
        Some((
            format!(
                "backspin {:.0} and sidespin {:.0} rpm where spin rate {:.0} rpm and axis {:.1}° \
                 give {back:.0} and {side:.0}",
                self.back_rpm, self.side_rpm, self.rate_rpm, self.axis_deg
            ),
            flipped,
        ))
    }
}

/// Smash factors more than this from ball speed over club speed disagree: the factor is
/// written to 0.01 (±0.005) and the speeds to 0.1 mph (±0.001 on the ratio).
const SMASH_TOLERANCE: f64 = 0.01;

/// The redundant values of the shots written.
#[derive(Default)]
pub(super) struct Redundancy {
    spin_checked: usize,
    spin_bad: Vec<usize>,
    spin_flipped: usize,
    spin_first: Option<String>,
    smash_checked: usize,
    smash_bad: Vec<usize>,
    smash_first: Option<String>,
}

impl Redundancy {
    /// Check one shot (its export line, spin both ways, smash factor, ball and club speed).
    pub(super) fn add(
        &mut self,
        line: usize,
        spin: &Option<SpinCheck>,
        smash: Option<(f64, f64, f64)>,
    ) {
        if let Some(s) = spin {
            self.spin_checked += 1;
            if let Some((what, flipped)) = s.disagreement() {
                self.spin_bad.push(line);
                self.spin_flipped += usize::from(flipped);
                self.spin_first
                    .get_or_insert(format!("line {line}: {what}"));
            }
        }
        if let Some((factor, ball, club)) = smash {
            self.smash_checked += 1;
            if club > 0.0 && (factor - ball / club).abs() > SMASH_TOLERANCE {
                self.smash_bad.push(line);
                self.smash_first.get_or_insert(format!(
                    "line {line}: smash factor {factor} where ball speed / club speed = {:.3}",
                    ball / club
                ));
            }
        }
    }

    /// Refuse the export when the spin disagrees on most of at least three shots.
    pub(super) fn refuse_systematic(&self, path: &Path, vendor: &str) -> Result<(), DataError> {
        let bad = self.spin_bad.len();
        if self.spin_checked >= 3 && 2 * bad > self.spin_checked {
            let hint = if 2 * self.spin_flipped > bad {
                "with the sign of sidespin flipped they agree: the mapping reads sidespin (or the \
                 spin axis) with the wrong sign"
            } else {
                "the mapping reads a spin column with the wrong meaning or unit"
            };
            return Err(DataError::file(
                path,
                format!(
                    "back and side spin disagree with spin rate and axis on {bad} of {} {vendor} \
                     shots ({}); {hint}",
                    self.spin_checked,
                    self.spin_first.as_deref().unwrap_or_default()
                ),
            ));
        }
        Ok(())
    }

    /// Notes on disagreements that did not refuse the file.
    pub(super) fn notes(&self, notes: &mut Vec<String>) {
        if !self.spin_bad.is_empty() {
            notes.push(format!(
                "back and side spin disagree with spin rate and axis on {} of {} shots (line(s) \
                 {}; the first, {}): back and side spin were used",
                self.spin_bad.len(),
                self.spin_checked,
                list_lines(&self.spin_bad),
                self.spin_first.as_deref().unwrap_or_default()
            ));
        }
        if !self.smash_bad.is_empty() {
            notes.push(format!(
                "the smash factor disagrees with ball speed / club speed on {} of {} shots (line(s) \
                 {}; the first, {})",
                self.smash_bad.len(),
                self.smash_checked,
                list_lines(&self.smash_bad),
                self.smash_first.as_deref().unwrap_or_default()
            ));
        }
    }
}
