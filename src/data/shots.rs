//! Shots files (CSV): one row a shot, header required, column order free.
//!
//! | column | unit | required | meaning |
//! |---|---|---|---|
//! | `shot_id` | text | yes | unique id |
//! | `group` | text | no (`all`) | e.g. the shaft: parameters may be fitted per group |
//! | `golfer` | text | no | groups cross-validation folds |
//! | `shaft_mass_g` | g | no | relates added mass to shaft mass |
//! | `club_speed_mph` | mph | yes | clubhead CoM speed |
//! | `attack_angle_deg`, `club_path_deg`, `dynamic_loft_deg`, `face_angle_deg` | deg | yes | |
//! | `lie_tilt_deg` | deg | no (0) | |
//! | `club_omega_{x,y,z}_rad_s` | rad/s | no (0) | clubhead angular velocity in G |
//! | `impact_y_mm`, `impact_z_mm` | mm | yes | impact location from CoF |
//! | `ball_speed_mph`, `launch_angle_deg`, `azimuth_deg`, `backspin_rpm`, `sidespin_rpm` | | all or none | measured launch |
//!
//! Other columns are carried through to outputs untouched.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use nalgebra::Vector3;

use super::DataError;
use crate::limits::{self, PhysicalRange};
/// The shot itself is a domain type (it lives in [`crate::model`]); re-exported here for
/// callers of the reader.
pub use crate::model::Shot;
use crate::physics::{Delivery, Launch, LaunchComponent};
use crate::units::{deg, mm, mph, rpm};

/// Columns a shots file must have.
pub const REQUIRED_COLUMNS: [&str; 8] = [
    "shot_id",
    "club_speed_mph",
    "attack_angle_deg",
    "club_path_deg",
    "dynamic_loft_deg",
    "face_angle_deg",
    "impact_y_mm",
    "impact_z_mm",
];

/// Optional input columns the engine reads.
pub const OPTIONAL_COLUMNS: [&str; 7] = [
    "group",
    "golfer",
    "shaft_mass_g",
    "lie_tilt_deg",
    "club_omega_x_rad_s",
    "club_omega_y_rad_s",
    "club_omega_z_rad_s",
];

/// Group of shots without a `group` column.
pub const DEFAULT_GROUP: &str = "all";

/// A shots file: parsed shots plus the raw table, so outputs can carry every input column.
#[derive(Debug, Clone, PartialEq)]
pub struct ShotTable {
    /// Where it came from.
    pub path: PathBuf,
    /// Header, as in the file.
    pub headers: Vec<String>,
    /// Raw cells, one record per shot, in file order.
    pub records: Vec<Vec<String>>,
    /// Parsed shots, in file order.
    pub shots: Vec<Shot>,
    /// 1-based line of the file where each shot's record starts (parallel to `shots`).
    pub lines: Vec<usize>,
}

impl ShotTable {
    /// Do the shots carry measured launch conditions?
    pub fn has_measurements(&self) -> bool {
        self.shots.first().is_some_and(|s| s.measured.is_some())
    }

    /// Distinct groups, sorted.
    pub fn groups(&self) -> Vec<String> {
        let mut g: Vec<String> = self.shots.iter().map(|s| s.group.clone()).collect();
        g.sort();
        g.dedup();
        g
    }
}

/// The physical range of a measured launch component (file units).
pub fn measured_range(c: LaunchComponent) -> PhysicalRange {
    match c {
        LaunchComponent::BallSpeed => limits::BALL_SPEED_MPH,
        LaunchComponent::LaunchAngle | LaunchComponent::Azimuth => limits::LAUNCH_DIRECTION_DEG,
        LaunchComponent::Backspin | LaunchComponent::Sidespin => limits::BALL_SPIN_RPM,
    }
}

/// Read a shots file.
pub fn read_shots(path: &Path) -> Result<ShotTable, DataError> {
    let file = std::fs::File::open(path)
        .map_err(|e| DataError::file(path, format!("cannot read: {e}")))?;
    parse_shots(path, file)
}

/// Parse shots from any reader (`path` is used in messages only).
pub fn parse_shots<R: std::io::Read>(path: &Path, mut reader: R) -> Result<ShotTable, DataError> {
    let mut bytes = Vec::new();
    reader
        .read_to_end(&mut bytes)
        .map_err(|e| DataError::file(path, format!("cannot read: {e}")))?;
    // Lines from byte offsets: the csv crate's own line count is off for CRLF files (as written
    // by Excel and Python's csv module).
    let newlines: Vec<usize> = bytes
        .iter()
        .enumerate()
        .filter(|(_, &b)| b == b'\n')
        .map(|(i, _)| i)
        .collect();
    // With CRLF the reported byte is the previous line's `\n` itself, hence `<=`.
    let line_of = |p: &csv::Position| newlines.partition_point(|&nl| (nl as u64) <= p.byte()) + 1;
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(true)
        .trim(csv::Trim::All)
        .from_reader(bytes.as_slice());
    let csv_err = |e: csv::Error| {
        let line = e.position().map(line_of);
        let msg = match e.kind() {
            csv::ErrorKind::UnequalLengths {
                expected_len, len, ..
            } => {
                format!("row has {len} fields but the header has {expected_len}")
            }
            _ => e.to_string(),
        };
        DataError::at(path, line, None, msg)
    };
    let headers: Vec<String> = rdr
        .headers()
        .map_err(csv_err)?
        .iter()
        .map(str::to_owned)
        .collect();
    if headers.iter().all(|h| h.is_empty()) {
        return Err(DataError::file(
            path,
            "empty file: a header row is required",
        ));
    }
    let mut seen = HashSet::new();
    for h in &headers {
        if !seen.insert(h.as_str()) {
            return Err(DataError::at(
                path,
                Some(1),
                None,
                format!("column '{h}' appears twice in the header"),
            ));
        }
    }
    let col = |name: &str| headers.iter().position(|h| h == name);
    let missing: Vec<&str> = REQUIRED_COLUMNS
        .iter()
        .copied()
        .filter(|c| col(c).is_none())
        .collect();
    if !missing.is_empty() {
        return Err(DataError::at(
            path,
            Some(1),
            None,
            format!(
                "missing required column(s): {} (required: {})",
                missing.join(", "),
                REQUIRED_COLUMNS.join(", ")
            ),
        ));
    }
    let req = |name: &str| col(name).expect("checked above");
    let launch_cols: Vec<Option<usize>> = LaunchComponent::ALL
        .iter()
        .map(|c| col(c.column()))
        .collect();
    let n_launch = launch_cols.iter().flatten().count();
    if n_launch != 0 && n_launch != launch_cols.len() {
        let absent: Vec<&str> = LaunchComponent::ALL
            .iter()
            .zip(&launch_cols)
            .filter(|(_, c)| c.is_none())
            .map(|(c, _)| c.column())
            .collect();
        return Err(DataError::at(
            path,
            Some(1),
            None,
            format!(
                "measured launch columns must be all present or all absent; missing: {}",
                absent.join(", ")
            ),
        ));
    }

    let i_id = req("shot_id");
    let i_speed = req("club_speed_mph");
    let i_attack = req("attack_angle_deg");
    let i_path = req("club_path_deg");
    let i_loft = req("dynamic_loft_deg");
    let i_face = req("face_angle_deg");
    let i_y = req("impact_y_mm");
    let i_z = req("impact_z_mm");
    let i_group = col("group");
    let i_golfer = col("golfer");
    let i_shaft = col("shaft_mass_g");
    let i_lie = col("lie_tilt_deg");
    let i_w = [
        col("club_omega_x_rad_s"),
        col("club_omega_y_rad_s"),
        col("club_omega_z_rad_s"),
    ];

    let mut records = Vec::new();
    let mut shots = Vec::new();
    let mut lines = Vec::new();
    let mut ids = HashSet::new();
    for rec in rdr.records() {
        let rec = rec.map_err(csv_err)?;
        let line = rec.position().map_or(records.len() + 2, line_of);
        lines.push(line);
        let cells: Vec<String> = rec.iter().map(str::to_owned).collect();
        let num = |i: usize| -> Result<f64, DataError> {
            let s = cells[i].as_str();
            let here = |m: String| {
                DataError::at(
                    path,
                    Some(line),
                    Some(format!("column '{}'", headers[i])),
                    m,
                )
            };
            match s.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                Ok(v) => Err(here(format!(
                    "value {v} is not finite; a finite number is required"
                ))),
                Err(_) if s.is_empty() => Err(here("empty cell; a number is required".into())),
                Err(_) => Err(here(format!("'{s}' is not a number"))),
            }
        };
        // A number in its physical range (see `crate::limits`).
        let ranged = |i: usize, range: PhysicalRange| -> Result<f64, DataError> {
            let v = num(i)?;
            range.check(v).map_err(|m| {
                DataError::at(
                    path,
                    Some(line),
                    Some(format!("column '{}'", headers[i])),
                    m,
                )
            })
        };
        let opt_ranged =
            |i: Option<usize>, range: PhysicalRange| i.map_or(Ok(0.0), |i| ranged(i, range));
        let id = cells[i_id].clone();
        if id.is_empty() {
            return Err(DataError::at(
                path,
                Some(line),
                Some("column 'shot_id'".into()),
                "empty shot id",
            ));
        }
        if !ids.insert(id.clone()) {
            return Err(DataError::at(
                path,
                Some(line),
                Some("column 'shot_id'".into()),
                format!("shot id '{id}' is used twice; ids must be unique"),
            ));
        }
        let group = match i_group {
            Some(i) if cells[i].is_empty() => {
                return Err(DataError::at(
                    path,
                    Some(line),
                    Some("column 'group'".into()),
                    "empty group name",
                ));
            }
            Some(i) => cells[i].clone(),
            None => DEFAULT_GROUP.to_owned(),
        };
        let golfer = i_golfer.map(|i| cells[i].clone()).filter(|g| !g.is_empty());
        let shaft_mass_g = match i_shaft {
            Some(i) => Some(ranged(i, limits::SHAFT_MASS_G)?),
            None => None,
        };
        let angle = limits::DELIVERY_ANGLE_DEG;
        let omega = limits::CLUB_OMEGA_RAD_S;
        let delivery = Delivery {
            club_speed_m_s: mph(ranged(i_speed, limits::CLUB_SPEED_MPH)?),
            attack_angle_rad: deg(ranged(i_attack, angle)?),
            club_path_rad: deg(ranged(i_path, angle)?),
            dynamic_loft_rad: deg(ranged(i_loft, limits::DYNAMIC_LOFT_DEG)?),
            face_angle_rad: deg(ranged(i_face, angle)?),
            lie_tilt_rad: deg(opt_ranged(i_lie, angle)?),
            club_omega_rad_s: Vector3::new(
                opt_ranged(i_w[0], omega)?,
                opt_ranged(i_w[1], omega)?,
                opt_ranged(i_w[2], omega)?,
            ),
            impact_y_m: mm(ranged(i_y, limits::IMPACT_LOCATION_MM)?),
            impact_z_m: mm(ranged(i_z, limits::IMPACT_LOCATION_MM)?),
        };
        let measured = if n_launch > 0 {
            let v: Vec<f64> = launch_cols
                .iter()
                .zip(LaunchComponent::ALL)
                .map(|(c, comp)| ranged(c.expect("all present"), measured_range(comp)))
                .collect::<Result<_, _>>()?;
            Some(Launch {
                ball_speed_m_s: mph(v[0]),
                launch_angle_rad: deg(v[1]),
                azimuth_rad: deg(v[2]),
                backspin_rad_s: rpm(v[3]),
                sidespin_rad_s: rpm(v[4]),
            })
        } else {
            None
        };
        shots.push(Shot {
            id,
            group,
            golfer,
            shaft_mass_g,
            delivery,
            measured,
        });
        records.push(cells);
    }
    if shots.is_empty() {
        return Err(DataError::file(
            path,
            "no shots: the file has a header but no rows",
        ));
    }
    Ok(ShotTable {
        path: path.to_owned(),
        headers,
        records,
        shots,
        lines,
    })
}
