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
    /// How far the ball curved off its launch line (offline − carry·tan(azimuth)), yd, + right,
    /// when the export gives the offline distance: the evidence that settles which of side spin
    /// and spin axis has the wrong sign.
    curve_yd: Option<f64>,
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
            curve_yd: get("offline_yd")
                .zip(get("carry_yd"))
                .zip(get("azimuth_deg"))
                .map(|((off, carry), az)| off - carry * az.to_radians().tan()),
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

/// [`SMASH_TOLERANCE`], or more for speeds written in whole mph (SkyTrak: `106` and `76`),
/// whose ratio may be off by `0.5/club·(1 + ball/club)` by their rounding alone (0.016 at 76 mph),
/// plus the factor's own ±0.005.
fn smash_tolerance(ball: f64, club: f64) -> f64 {
    if ball.fract() != 0.0 || club.fract() != 0.0 {
        return SMASH_TOLERANCE;
    }
    SMASH_TOLERANCE.max(0.005 + 0.5 / club * (1.0 + ball / club))
}

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
    /// Ball speed / club speed over the smash factor of each disagreeing shot.
    smash_ratio: Vec<f64>,
    /// Of the shots whose spins disagree in sign and that curved clearly (more than 2 yd): how
    /// many, and how many curved the way the side spin (as read) or the spin axis says.
    curved: usize,
    side_agrees: usize,
    axis_agrees: usize,
    /// Ball speed over club speed, and carry over the carry the launch would reach in a vacuum,
    /// of every shot that gives them: the units checked by physics.
    speed_ratios: Vec<f64>,
    carry_ratios: Vec<f64>,
    /// Each shot's launch and carry, for the check of the carry's unit against the flight
    /// model ([`super::carry_units`]).
    carries: Vec<super::carry_units::CarryShot>,
}

/// The median of `v` (not empty).
fn median(v: &[f64]) -> f64 {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// What the offline distances say about a sign disagreement between side spin and axis.
enum Verdict {
    /// Too few curved shots, or they do not agree enough: nothing is recommended.
    Unsettled,
    /// The side spin as read is right (the axis is what disagrees): the shots use it.
    SideRight,
    /// The spin axis is right: the side spin is read with the wrong sign.
    AxisRight,
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
                if let Some(c) = s.curve_yd.filter(|c| flipped && c.abs() > 2.0) {
                    self.curved += 1;
                    self.side_agrees += usize::from(c * s.side_rpm > 0.0);
                    self.axis_agrees += usize::from(c * s.axis_deg > 0.0);
                }
                self.spin_first
                    .get_or_insert(format!("line {line}: {what}"));
            }
        }
        if let Some((factor, ball, club)) = smash {
            self.smash_checked += 1;
            if club > 0.0 && (factor - ball / club).abs() > smash_tolerance(ball, club) {
                self.smash_bad.push(line);
                self.smash_ratio.push(ball / club / factor);
                self.smash_first.get_or_insert(format!(
                    "line {line}: smash factor {factor} where ball speed / club speed = {:.3}",
                    ball / club
                ));
            }
        }
    }

    /// Record a shot's speeds, launch angle, carry and backspin (shots-file units) for the
    /// unit checks.
    pub(super) fn add_physics(
        &mut self,
        ball_mph: Option<f64>,
        club_mph: Option<f64>,
        launch_deg: Option<f64>,
        carry_yd: Option<f64>,
        backspin_rpm: Option<f64>,
    ) {
        if let (Some(b), Some(l), Some(c), Some(s)) = (ball_mph, launch_deg, carry_yd, backspin_rpm)
        {
            self.carries.push(super::carry_units::CarryShot {
                ball_mph: b,
                launch_deg: l,
                backspin_rpm: s,
                carry_yd: c,
            });
        }
        if let (Some(b), Some(c)) = (ball_mph, club_mph) {
            if b > 0.0 && c > 0.0 {
                self.speed_ratios.push(b / c);
            }
        }
        if let (Some(b), Some(l), Some(carry)) = (ball_mph, launch_deg, carry_yd) {
            let v = b * 0.44704;
            let vacuum_yd = v * v * (2.0 * l.to_radians()).sin() / 9.80665 / 0.9144;
            if vacuum_yd > 1.0 && carry > 0.0 {
                self.carry_ratios.push(carry / vacuum_yd);
            }
        }
    }

    /// Refuse an export whose speeds or carries no golf shot could give, in the median of at
    /// least three shots: ball speed over club speed outside 0.7–1.75 (a smash factor; m/s read
    /// as mph or km/h as mph in one of the two), or carries longer than the launch would reach
    /// in a vacuum three times over (the ball speed in too small a unit: m/s read as mph gives
    /// five times). `units` names the
    /// units the speeds and carry were read in.
    pub(super) fn refuse_units(&self, path: &Path, units: &str) -> Result<(), DataError> {
        if self.speed_ratios.len() >= 3 {
            let m = median(&self.speed_ratios);
            if !(0.7..=1.75).contains(&m) {
                return Err(DataError::file(
                    path,
                    format!(
                        "ball speed / club speed is {m:.2} in the median of {} shots, where a golf \
                         shot's smash factor is 0.7–1.75: one of the two is read in the wrong unit \
                         ({units}); state the right one with unit = \"…\" in a mapping file",
                        self.speed_ratios.len()
                    ),
                ));
            }
        }
        if self.carry_ratios.len() >= 3 {
            let m = median(&self.carry_ratios);
            // Lift carries a low, spinning launch past its vacuum range (a driver by up to
            // about 1.5 times); m/s read as mph shrinks the vacuum range five times.
            if m > 3.0 {
                return Err(DataError::file(
                    path,
                    format!(
                        "the median of {} carries is {m:.1} times what the launch would carry in a \
                         vacuum: the ball speed is read in too small a unit (m/s as mph?) or the \
                         carry in too large a one ({units}); state the right one with unit = \"…\" \
                         in a mapping file",
                        self.carry_ratios.len()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The carries' units checked against the flight model ([`super::carry_units::check`]):
    /// the refusal of carries far shorter than their launches fly when a reading of the units
    /// explains it, else the note, if any.
    pub(super) fn carry_units(
        &self,
        path: &Path,
        read: &super::carry_units::AsRead,
    ) -> Result<Option<String>, DataError> {
        use super::carry_units::CarryUnits;
        match super::carry_units::check(&self.carries, read) {
            Some(CarryUnits::Refuse(why)) => Err(DataError::file(path, why)),
            Some(CarryUnits::Note(note)) => Ok(Some(note)),
            None => Ok(None),
        }
    }

    /// The offline distances' verdict on the sign disagreements: settled only when at least
    /// three shots curved clearly and 80 % of them agree with one reading and at most 20 % with
    /// the other.
    fn verdict(&self) -> Verdict {
        let (n, side, axis) = (self.curved, self.side_agrees, self.axis_agrees);
        if n < 3 {
            Verdict::Unsettled
        } else if 5 * side >= 4 * n && 5 * axis <= n {
            Verdict::SideRight
        } else if 5 * axis >= 4 * n && 5 * side <= n {
            Verdict::AxisRight
        } else {
            Verdict::Unsettled
        }
    }

    /// Refuse the export when the spin disagrees on most of at least three shots, unless the
    /// offline distances show the side spin as read is right (then it is used, and a note
    /// says so).
    pub(super) fn refuse_systematic(&self, path: &Path, vendor: &str) -> Result<(), DataError> {
        let bad = self.spin_bad.len();
        if self.spin_checked >= 3 && 2 * bad > self.spin_checked {
            let sign = 2 * self.spin_flipped > bad;
            let hint = match (sign, self.verdict()) {
                (true, Verdict::SideRight) => return Ok(()),
                (true, Verdict::AxisRight) => format!(
                    "with the sign of sidespin flipped they agree, and the offline distances side \
                     with the spin axis ({} of {} clearly curved shots): the mapping reads sidespin \
                     with the wrong sign",
                    self.axis_agrees, self.curved
                ),
                (true, Verdict::Unsettled) => format!(
                    "they agree with the sign of sidespin or of the spin axis flipped, and {}: \
                     check which of the two the mapping reads with the wrong sign",
                    if self.curved >= 3 {
                        format!(
                            "the offline distances do not settle which ({} of {} clearly curved \
                             shots curve the way the sidespin says, {} the way the axis says)",
                            self.side_agrees, self.curved, self.axis_agrees
                        )
                    } else {
                        "the file gives too few offline distances to tell which".to_owned()
                    }
                ),
                (false, _) => {
                    "the mapping reads a spin column with the wrong meaning or unit".to_owned()
                }
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

    /// Refuse a file whose smash factor disagrees with ball speed / club speed on most of at
    /// least three shots, by more than 10 % on the median such shot, as the spin checks refuse
    /// theirs: a speed (or the factor) is read in the wrong unit (km/h as mph is 38 % off, m/s
    /// 55 %) or from the wrong column, and every club speed written would be wrong. A smaller
    /// disagreement is a vendor's definition (FlightScope's Mevo+ factor is 1 % above its
    /// speeds' ratio on most shots), noted, not refused.
    pub(super) fn refuse_smash(&self, path: &Path, vendor: &str) -> Result<(), DataError> {
        let bad = self.smash_bad.len();
        if self.smash_checked < 3 || 2 * bad <= self.smash_checked {
            return Ok(());
        }
        let mut r = self.smash_ratio.clone();
        r.sort_by(f64::total_cmp);
        let median = r[r.len() / 2];
        if (median - 1.0).abs() <= 0.1 {
            return Ok(());
        }
        Err(DataError::file(
            path,
            format!(
                "the smash factor disagrees with ball speed / club speed on {bad} of {} {vendor} \
                 shots ({}); on the median such shot the speeds' ratio is {median:.3} times the \
                 factor (0.621 if a club speed in km/h is read as mph, 0.447 for m/s; 1.609 or \
                 2.237 the other way round): a speed is read in the wrong unit or from the wrong \
                 column; state its unit in the units row or in a mapping file",
                self.smash_checked,
                self.smash_first.as_deref().unwrap_or_default()
            ),
        ))
    }

    /// Notes on disagreements that did not refuse the file.
    pub(super) fn notes(&self, notes: &mut Vec<String>) {
        if !self.spin_bad.is_empty() && matches!(self.verdict(), Verdict::SideRight) {
            notes.push(format!(
                "back and side spin disagree in sign with spin rate and axis on {} of {} shots \
                 (the first, {}); the offline distances side with the sidespin as read ({} of {} \
                 clearly curved shots), so back and side spin were used: the spin axis column is \
                 what disagrees",
                self.spin_bad.len(),
                self.spin_checked,
                self.spin_first.as_deref().unwrap_or_default(),
                self.side_agrees,
                self.curved
            ));
        } else if !self.spin_bad.is_empty() {
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
