//! Shots files (CSV): one row a shot, header required, column order free.
//!
//! | column | unit | required | meaning |
//! |---|---|---|---|
//! | `shot_id` | text | yes | unique id |
//! | `group` | text | no (`all`) | e.g. the shaft: parameters may be fitted per group |
//! | `golfer` | text | no | groups cross-validation folds |
//! | `shaft_mass_g` | g | no (an empty cell: none) | relates added mass to shaft mass |
//! | `club_speed_mph` | mph | yes | clubhead CoM speed |
//! | `attack_angle_deg`, `club_path_deg`, `dynamic_loft_deg`, `face_angle_deg` | deg | yes | |
//! | `lie_tilt_deg` | deg | no (0, an empty cell too) | |
//! | `club_omega_{x,y,z}_rad_s` | rad/s | no (0, an empty cell too) | clubhead angular velocity in G |
//! | `impact_y_mm`, `impact_z_mm` | mm | yes | impact location from CoF |
//! | `ball_speed_mph`, `launch_angle_deg`, `azimuth_deg`, `backspin_rpm`, `sidespin_rpm` | | all or none | measured launch |
//! | `face_at`, `velocity_at`, `face_angle_from` | text | no (the model's own) | the delivery's convention ([`crate::conventions`]) |
//!
//! Other columns are carried through to outputs untouched.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

pub use super::columns::{optional_columns, required_columns, ESTIMATED_FLAGS};
use super::{csv_error_at, DataError};
use crate::limits::{self, PhysicalRange};
use crate::line_index::LineIndex;
use crate::model::convention::{
    names, parse_name, DeliveryConvention, FaceAngleSource, FacePoint, VelocityPoint,
    FACE_ANGLE_FROM_COLUMN, FACE_AT_COLUMN, VELOCITY_AT_COLUMN,
};
/// The shot itself is a domain type (it lives in [`crate::model`]); re-exported here for
/// callers of the reader.
pub use crate::model::Shot;
use crate::model::{delivery_from_file_units, DeliveryVar, N_DELIVERY};
use crate::physics::{Delivery, Launch, LaunchComponent};
use crate::units::{deg, mph, rpm};

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
    /// Rows left out (a delivery cell empty, estimated values, a value that cannot be used),
    /// by reason, in file order.
    pub left_out: Vec<LeftOut>,
    /// Where and how each shot's delivery is defined (parallel to `shots`): the
    /// `face_at`, `velocity_at` and `face_angle_from` columns, the model's own convention
    /// where absent. [`crate::conventions::to_model`] brings the shots to the model's.
    pub conventions: Vec<DeliveryConvention>,
    /// Read with [`ReadOptions::strict`]: a shot a later step cannot use refuses the file
    /// instead of being left out and counted.
    pub strict: bool,
}

pub use super::left_out::{list_lines, LeftOut};

/// How to read a shots file.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ReadOptions {
    /// Refuse the file at the first row with an empty delivery cell or a value that cannot be
    /// used (the default leaves such rows out and counts them in [`ShotTable::left_out`],
    /// refusing the file only when no row is left or more than half hold bad values:
    /// [`super::left_out::refuse_when_unusable`]).
    pub strict: bool,
    /// Use shots whose spin or club data the monitor estimated (`spin_estimated = 1`,
    /// `club_estimated = 1`); by default they are left out and counted.
    pub include_estimated: bool,
}

impl ShotTable {
    /// One note per reason rows were left out: how many of all the rows, why, and their first
    /// file lines (`left out 2 of 40 rows: no impact location (line(s) 5, 9; …)`).
    pub fn left_out_notes(&self) -> Vec<String> {
        super::left_out::notes(&self.left_out, self.rows_read())
    }

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

/// Why [`ShotTable::leave_out_derived`] leaves shots out (a [`LeftOut`] reason).
pub const DERIVED_LEFT_OUT: &str = "face angle derived from the launch (face_angle_from)";

impl ShotTable {
    /// Leave out the shots whose face angle the monitor derived from the launch, and count them in
    /// `left_out` under [`DERIVED_LEFT_OUT`]: what `diagnose` and `calibrate` do, so that no
    /// effect is fitted to a formula. Returns how many were left out.
    pub fn leave_out_derived(&mut self) -> usize {
        let table = self;
        let derived = |c: &DeliveryConvention| c.face_angle_from == FaceAngleSource::Launch;
        let lines: Vec<usize> = table
            .conventions
            .iter()
            .zip(&table.lines)
            .filter(|(c, _)| derived(c))
            .map(|(_, l)| *l)
            .collect();
        if lines.is_empty() {
            return 0;
        }
        let keep: Vec<bool> = table.conventions.iter().map(|c| !derived(c)).collect();
        let n = lines.len();
        table.leave_out(
            &keep,
            vec![LeftOut {
                reason: DERIVED_LEFT_OUT.to_owned(),
                lines,
                first: None,
                cut_by_limit: false,
            }],
        );
        n
    }
}

/// The physical range of a measured launch component (file units).
pub fn measured_range(c: LaunchComponent) -> PhysicalRange {
    match c {
        LaunchComponent::BallSpeed => limits::BALL_SPEED_MPH,
        LaunchComponent::LaunchAngle => PhysicalRange {
            quantity: "measured launch angle",
            ..limits::LAUNCH_DIRECTION_DEG
        },
        LaunchComponent::Azimuth => PhysicalRange {
            quantity: "measured azimuth",
            ..limits::LAUNCH_DIRECTION_DEG
        },
        LaunchComponent::Backspin | LaunchComponent::Sidespin => limits::BALL_SPIN_RPM,
    }
}

/// Read a shots file.
pub fn read_shots(path: &Path) -> Result<ShotTable, DataError> {
    read_shots_with(path, ReadOptions::default())
}

/// Read a shots file with `opts`.
pub fn read_shots_with(path: &Path, opts: ReadOptions) -> Result<ShotTable, DataError> {
    crate::data::safe_write::note_input(path);
    let file = std::fs::File::open(path)
        .map_err(|e| DataError::file(path, format!("cannot read: {e}")))?;
    parse_shots_with(path, file, opts)
}

/// Parse shots from any reader (`path` is used in messages only).
pub fn parse_shots<R: std::io::Read>(path: &Path, reader: R) -> Result<ShotTable, DataError> {
    parse_shots_with(path, reader, ReadOptions::default())
}

/// Parse shots from any reader with `opts` (`path` is used in messages only).
pub fn parse_shots_with<R: std::io::Read>(
    path: &Path,
    mut reader: R,
    opts: ReadOptions,
) -> Result<ShotTable, DataError> {
    let mut bytes = Vec::new();
    reader
        .read_to_end(&mut bytes)
        .map_err(|e| DataError::file(path, format!("cannot read: {e}")))?;
    if let Some(u) = crate::line_index::utf16(&bytes) {
        return Err(DataError::at(path, Some(1), None, u.refusal()));
    }
    let lines = LineIndex::new(&bytes);
    // Flexible: a row of the wrong width is one bad row (left out and counted below), not the
    // end of the file.
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(true)
        .flexible(true)
        .trim(csv::Trim::All)
        .from_reader(bytes.as_slice());
    let csv_err = |e: csv::Error| csv_error_at(&lines, path, &e);
    let headers: Vec<String> = rdr
        .headers()
        .map_err(csv_err)?
        .iter()
        .map(str::to_owned)
        .collect();
    let cols = Columns::locate(path, &headers)?;

    let mut table = ShotTable {
        path: path.to_owned(),
        headers,
        records: Vec::new(),
        shots: Vec::new(),
        lines: Vec::new(),
        left_out: Vec::new(),
        conventions: Vec::new(),
        strict: opts.strict,
    };
    let mut ids = HashSet::new();
    for (row_index, rec) in rdr.records().enumerate() {
        let rec = rec.map_err(csv_err)?;
        let line = rec.position().map_or(row_index + 2, |p| lines.line_of(p));
        if rec.len() != table.headers.len() {
            // Its cells cannot be told apart: an unquoted decimal comma, a cell lost.
            let e = DataError::at(
                path,
                Some(line),
                None,
                crate::line_index::field_count_message(
                    rec.len() as u64,
                    table.headers.len() as u64,
                ),
            );
            if opts.strict {
                return Err(e);
            }
            super::left_out::push_bad(&mut table.left_out, line, e);
            continue;
        }
        let cells: Vec<String> = rec.iter().map(str::to_owned).collect();
        let row = Row {
            path,
            line,
            headers: &table.headers,
            cells: &cells,
        };
        // A row with a value that cannot be used is left out and counted (under `strict`, the
        // file is refused at it): one bad row of a real export does not sink the others.
        let parsed = row.left_out(&cols, opts).and_then(|why| match why {
            Some(reason) => Ok(Err(reason)),
            None => Ok(Ok((row.shot(&cols, &ids)?, row.convention(&cols)?))),
        });
        match parsed {
            Ok(Ok((shot, convention))) => {
                ids.insert(shot.id.clone());
                table.lines.push(line);
                table.shots.push(shot);
                table.conventions.push(convention);
                table.records.push(cells);
            }
            Ok(Err(reason)) => super::left_out::push_reason(&mut table.left_out, line, reason),
            Err(e) if opts.strict => return Err(e),
            Err(e) => super::left_out::push_bad(&mut table.left_out, line, e),
        }
    }
    super::left_out::refuse_when_unusable(path, &table.left_out, table.shots.len())?;
    Ok(table)
}

/// Where each column the engine reads sits in the header.
struct Columns {
    id: usize,
    group: Option<usize>,
    golfer: Option<usize>,
    shaft: Option<usize>,
    /// Per [`DeliveryVar`]; `None` only for optional variables.
    delivery: [Option<usize>; N_DELIVERY],
    /// Per [`LaunchComponent`]; all or none present.
    launch: Option<[usize; 5]>,
    /// The [`ESTIMATED_FLAGS`] columns present.
    estimated: Vec<(usize, &'static str)>,
    /// The `face_at`, `velocity_at` and `face_angle_from` columns, when present.
    convention: [Option<usize>; 3],
}

impl Columns {
    /// Checks the header (non-empty, no duplicates, required columns, launch all-or-none).
    fn locate(path: &Path, headers: &[String]) -> Result<Self, DataError> {
        if headers.iter().all(|h| h.is_empty()) {
            return Err(DataError::file(
                path,
                "empty file: a header row is required",
            ));
        }
        let header_err = |m: String| DataError::at(path, Some(1), None, m);
        let mut seen = HashSet::new();
        for h in headers {
            if !seen.insert(h.as_str()) {
                return Err(header_err(format!(
                    "column '{h}' appears twice in the header"
                )));
            }
        }
        super::columns::check_known_case(path, headers)?;
        let col = |name: &str| headers.iter().position(|h| h == name);
        let required = required_columns();
        let missing: Vec<&str> = required
            .iter()
            .copied()
            .filter(|c| col(c).is_none())
            .collect();
        if !missing.is_empty() {
            return Err(header_err(format!(
                "missing required column(s): {} (required: {})",
                missing.join(", "),
                required.join(", ")
            )));
        }
        let launch_cols = LaunchComponent::ALL.map(|c| col(c.column()));
        let n_launch = launch_cols.iter().flatten().count();
        if n_launch != 0 && n_launch != launch_cols.len() {
            let absent: Vec<&str> = LaunchComponent::ALL
                .iter()
                .zip(&launch_cols)
                .filter(|(_, c)| c.is_none())
                .map(|(c, _)| c.column())
                .collect();
            return Err(header_err(format!(
                "measured launch columns must be all present or all absent; missing: {}",
                absent.join(", ")
            )));
        }
        Ok(Self {
            id: col("shot_id").expect("checked above"),
            group: col("group"),
            golfer: col("golfer"),
            shaft: col("shaft_mass_g"),
            delivery: DeliveryVar::ALL.map(|v| col(v.column())),
            launch: (n_launch > 0).then(|| launch_cols.map(|c| c.expect("all present"))),
            estimated: ESTIMATED_FLAGS
                .iter()
                .filter_map(|(c, what)| col(c).map(|i| (i, *what)))
                .collect(),
            convention: [FACE_AT_COLUMN, VELOCITY_AT_COLUMN, FACE_ANGLE_FROM_COLUMN].map(col),
        })
    }
}

/// One record of the file, with what messages about it need.
struct Row<'a> {
    path: &'a Path,
    line: usize,
    headers: &'a [String],
    cells: &'a [String],
}

impl Row<'_> {
    fn error(&self, column: &str, m: impl std::fmt::Display) -> DataError {
        DataError::at(
            self.path,
            Some(self.line),
            Some(format!("column '{column}'")),
            m,
        )
    }

    /// The text cells (id, group, golfer) hold no control character: they are printed in tables
    /// and terminals, where an escape or a line break would act or break the layout.
    fn printable(&self, cols: &Columns) -> Result<(), DataError> {
        for i in [Some(cols.id), cols.group, cols.golfer]
            .into_iter()
            .flatten()
        {
            let t = &self.cells[i];
            if t.chars().any(char::is_control) {
                return Err(self.error(
                    &self.headers[i],
                    format!(
                        "{} holds a control character (an escape, a line break, a tab); use \
                         printable text",
                        super::quote_cell(t)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Why the row is left out, if it is: a delivery cell empty (a session without
    /// impact-location hardware; under `strict` that is refused, naming the cell), or values
    /// the monitor estimated.
    fn left_out(&self, cols: &Columns, opts: ReadOptions) -> Result<Option<String>, DataError> {
        // An empty optional cell (`lie_tilt_deg`, `club_omega_*`) takes its default, as an
        // absent column does: only a required one leaves the row out.
        let empty: Vec<DeliveryVar> = DeliveryVar::ALL
            .into_iter()
            .filter(|v| v.required())
            .filter(|v| cols.delivery[v.index()].is_some_and(|i| self.cells[i].is_empty()))
            .collect();
        if let Some(first) = empty.first() {
            if opts.strict {
                let i = cols.delivery[first.index()].expect("present");
                return Err(self.error(
                    &self.headers[i],
                    "empty cell; a number is required (without --strict such a row is left out \
                     and counted)",
                ));
            }
            return Ok(Some(
                if empty
                    .iter()
                    .all(|v| matches!(v, DeliveryVar::ImpactY | DeliveryVar::ImpactZ))
                {
                    "no impact location".into()
                } else {
                    format!("no complete delivery ({} empty)", first.column())
                },
            ));
        }
        // A struck ball spins: back and side spin both exactly 0 is a monitor that lost the
        // spin, as `smash import` reads it (`docs/import.md`, "Not measured").
        if let Some(launch) = cols.launch {
            let zero = |c: LaunchComponent| {
                crate::data::number::parse_f64(self.cells[launch[c.index()]].trim()) == Some(0.0)
            };
            if zero(LaunchComponent::Backspin) && zero(LaunchComponent::Sidespin) {
                let why = "back and side spin both 0 (a monitor that lost the spin writes zeros)";
                if opts.strict {
                    let i = launch[LaunchComponent::Backspin.index()];
                    return Err(self.error(
                        &self.headers[i],
                        format!(
                            "{why}; a measured spin is required (without --strict such a row is \
                             left out and counted)"
                        ),
                    ));
                }
                return Ok(Some(why.into()));
            }
        }
        if !opts.include_estimated {
            for (i, what) in &cols.estimated {
                let v = self.cells[*i].as_str();
                let Ok(estimated) = super::columns::flag(v) else {
                    return Err(self.error(
                        &self.headers[*i],
                        format!(
                            "{} is not a flag: write 1 (estimated) or 0 (measured)",
                            super::quote_cell(v)
                        ),
                    ));
                };
                if estimated == Some(true) {
                    return Ok(Some(format!(
                        "{what} ({} = 1; --include-estimated uses them)",
                        self.headers[*i]
                    )));
                }
            }
        }
        Ok(None)
    }

    /// The row's delivery convention: each of the three columns names a value, or is absent
    /// or empty (the model's own).
    fn convention(&self, cols: &Columns) -> Result<DeliveryConvention, DataError> {
        fn cell<T: Copy + Default>(
            row: &Row,
            at: Option<usize>,
            all: &[(T, &'static str)],
        ) -> Result<T, DataError> {
            let Some(i) = at else {
                return Ok(T::default());
            };
            let v = row.cells[i].as_str();
            if v.is_empty() {
                return Ok(T::default());
            }
            parse_name(all, v).ok_or_else(|| {
                row.error(
                    &row.headers[i],
                    format!(
                        "{} is not known here (allowed: {}, or empty for {})",
                        super::quote_cell(v),
                        names(all),
                        all[0].1
                    ),
                )
            })
        }
        let [f, v, d] = cols.convention;
        Ok(DeliveryConvention {
            face_at: cell(self, f, &FacePoint::ALL)?,
            velocity_at: cell(self, v, &VelocityPoint::ALL)?,
            face_angle_from: cell(self, d, &FaceAngleSource::ALL)?,
        })
    }

    /// A finite number.
    fn num(&self, i: usize) -> Result<f64, DataError> {
        let s = self.cells[i].as_str();
        let here = |m: String| self.error(&self.headers[i], m);
        match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(v) => Err(here(format!(
                "value {v} is not finite; a finite number is required"
            ))),
            Err(_) if s.is_empty() => Err(here("empty cell; a number is required".into())),
            Err(_) => Err(here(format!("{} is not a number", super::quote_cell(s)))),
        }
    }

    /// A number in its physical range (see `crate::limits`).
    fn ranged(&self, i: usize, range: PhysicalRange) -> Result<f64, DataError> {
        let v = self.num(i)?;
        range.check(v).map_err(|m| self.error(&self.headers[i], m))
    }

    /// The shot of this row; `ids` are those of the rows kept before (ids must be unique).
    fn shot(&self, cols: &Columns, ids: &HashSet<String>) -> Result<Shot, DataError> {
        self.printable(cols)?;
        let id = self.cells[cols.id].clone();
        if id.is_empty() {
            return Err(self.error("shot_id", "empty shot id"));
        }
        if ids.contains(&id) {
            return Err(self.error(
                "shot_id",
                format!("shot id '{id}' is used twice; ids must be unique"),
            ));
        }
        let group = match cols.group {
            Some(i) if self.cells[i].is_empty() => {
                return Err(self.error("group", "empty group name"));
            }
            Some(i) => self.cells[i].clone(),
            None => DEFAULT_GROUP.to_owned(),
        };
        let golfer = cols
            .golfer
            .map(|i| self.cells[i].clone())
            .filter(|g| !g.is_empty());
        // Empty optional cells are what an absent column gives: no shaft mass, a delivery
        // variable's default (0).
        let shaft_mass_g = match cols.shaft {
            Some(i) if self.cells[i].is_empty() => None,
            Some(i) => Some(self.ranged(i, limits::SHAFT_MASS_G)?),
            None => None,
        };
        let mut values = [0.0; N_DELIVERY];
        for v in DeliveryVar::ALL {
            if let Some(i) = cols.delivery[v.index()] {
                if !v.required() && self.cells[i].is_empty() {
                    continue;
                }
                values[v.index()] = self.ranged(i, v.range())?;
            }
        }
        let delivery = Delivery {
            shaft_mass_g,
            ..delivery_from_file_units(&values)
        };
        let measured = match cols.launch {
            Some(idx) => {
                let mut v = [0.0; 5];
                for (c, i) in LaunchComponent::ALL.into_iter().zip(idx) {
                    v[c.index()] = self.ranged(i, measured_range(c))?;
                }
                Some(Launch {
                    ball_speed_m_s: mph(v[0]),
                    launch_angle_rad: deg(v[1]),
                    azimuth_rad: deg(v[2]),
                    backspin_rad_s: rpm(v[3]),
                    sidespin_rad_s: rpm(v[4]),
                })
            }
            None => None,
        };
        Ok(Shot {
            id,
            group,
            golfer,
            delivery,
            measured,
        })
    }
}
