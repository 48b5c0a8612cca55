//! A shot the model cannot solve, located in its shots file like the reader's own errors.

use super::shots::ShotTable;
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
}
