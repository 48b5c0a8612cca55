//! The `[summary]` table: the probe lines of the speed-retention and gear-effect summaries.

use std::path::Path;

use serde::{Deserialize, Serialize};
use toml::Spanned;

use super::defaults;
use crate::club::ClubSpec;
use crate::data::{DataError, TomlDoc};
use crate::limits;
use crate::units::mm;

/// Probe lines for the speed-retention and gear-effect summaries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Probe {
    /// Half-length of each cross-section through the CoF, mm (> 0).
    pub half_width_mm: f64,
    /// Spacing of the probe points, mm (> 0, at most the half-width).
    pub step_mm: f64,
}

impl Probe {
    /// Points on one probe line.
    pub(super) fn points(&self) -> usize {
        (self.half_width_mm / self.step_mm + 1e-9).floor() as usize + 1
    }
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSummary {
    pub half_width_mm: Option<Spanned<f64>>,
    pub step_mm: Option<Spanned<f64>>,
}

pub(super) fn parse_summary(
    doc: &TomlDoc<'_>,
    s: Option<&RawSummary>,
    club: &ClubSpec,
    club_path: &Path,
) -> Result<Probe, DataError> {
    let half_width_mm = match s.and_then(|s| s.half_width_mm.as_ref()) {
        None => defaults::HALF_WIDTH_MM,
        Some(v) => doc.ranged(v, "summary.half_width_mm", limits::PROBE_HALF_WIDTH_MM)?,
    };
    let step_mm = match s.and_then(|s| s.step_mm.as_ref()) {
        None => defaults::STEP_MM.min(half_width_mm),
        Some(v) => parse_step(doc, v, half_width_mm)?,
    };
    let probe = Probe {
        half_width_mm,
        step_mm,
    };
    check_on_face(doc, &probe, club, club_path)?;
    Ok(probe)
}

fn parse_step(doc: &TomlDoc<'_>, v: &Spanned<f64>, half_width_mm: f64) -> Result<f64, DataError> {
    let st = doc.positive(v, "summary.step_mm", "mm")?;
    if st > half_width_mm {
        return Err(doc.err(
            v.span(),
            "summary.step_mm",
            format!("must not exceed half_width_mm ({half_width_mm})"),
        ));
    }
    let points = (half_width_mm / st).floor() + 1.0;
    if points > limits::MAX_PROBE_POINTS as f64 {
        return Err(doc.err(
            v.span(),
            "summary.step_mm",
            format!(
                "half_width_mm / step_mm gives {} points a probe line, more than the limit of \
                 {}; use a larger step",
                limits::fmt_value(points),
                limits::MAX_PROBE_POINTS
            ),
        ));
    }
    Ok(st)
}

/// The probe lines must lie on the face, or the speed-retention and gear-effect summaries
/// cannot be computed.
fn check_on_face(
    doc: &TomlDoc<'_>,
    probe: &Probe,
    club: &ClubSpec,
    club_path: &Path,
) -> Result<(), DataError> {
    let face = crate::physics::FaceGeometry::new(club.nominal.bulge_m, club.nominal.roll_m)
        .map_err(|m| DataError::file(club_path, m))?;
    let hw = mm(probe.half_width_mm);
    if [(hw, 0.0), (-hw, 0.0), (0.0, hw), (0.0, -hw)]
        .iter()
        .all(|&(y, z)| face.contact(y, z).is_ok())
    {
        return Ok(());
    }
    Err(doc.whole(
        "summary.half_width_mm",
        format!(
            "the probe lines reach {} mm from the centre, off the face of {} (bulge {:.1} mm, \
             roll {:.1} mm); use a smaller half_width_mm",
            probe.half_width_mm,
            club_path.display(),
            club.nominal.bulge_m * 1e3,
            club.nominal.roll_m * 1e3
        ),
    ))
}

/// The probe as a `[summary]` table.
pub(super) fn raw_summary(p: &Probe) -> RawSummary {
    RawSummary {
        half_width_mm: Some(Spanned::new(0..0, p.half_width_mm)),
        step_mm: Some(Spanned::new(0..0, p.step_mm)),
    }
}
