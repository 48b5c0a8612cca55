//! What a command leaves out of a shots table after reading it: the rows dropped from every
//! parallel vector alike and counted, and a shot the model cannot solve, located in its shots
//! file like the reader's own errors.

use super::shots::{LeftOut, ShotTable};
use super::DataError;

impl ShotTable {
    /// The error of shot `shot_id` (1-based `row`) that the model cannot solve, at its file
    /// line with the columns that decide it (`FILE:LINE: columns …: shot 'ID': …`, the form of
    /// the reader's own errors).
    pub fn shot_error(
        &self,
        row: usize,
        shot_id: &str,
        source: crate::physics::ImpactError,
    ) -> DataError {
        use crate::physics::ImpactError;
        let line = row.checked_sub(1).and_then(|i| self.lines.get(i)).copied();
        let place = match source {
            ImpactError::OffFace(_) => Some("columns impact_y_mm, impact_z_mm".to_owned()),
            ImpactError::NotApproaching { .. } => Some(
                "columns club_speed_mph, attack_angle_deg, club_path_deg, dynamic_loft_deg, \
                 face_angle_deg, club_omega_*_rad_s"
                    .to_owned(),
            ),
            _ => None,
        };
        DataError::at(
            &self.path,
            line,
            place,
            format!("shot '{shot_id}': {source}"),
        )
    }

    /// Keep the shots whose entry in `keep` is true (every parallel vector alike) and count
    /// the others under `left` (their reasons and lines).
    pub fn leave_out(&mut self, keep: &[bool], left: Vec<LeftOut>) {
        super::left_out::retain_kept(&mut self.shots, keep);
        super::left_out::retain_kept(&mut self.records, keep);
        super::left_out::retain_kept(&mut self.lines, keep);
        super::left_out::retain_kept(&mut self.conventions, keep);
        self.left_out.extend(left);
    }

    /// Rows read: the shots kept and the rows left out.
    pub fn rows_read(&self) -> usize {
        self.shots.len() + self.left_out.iter().map(|l| l.lines.len()).sum::<usize>()
    }
}
