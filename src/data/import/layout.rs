//! What the shots file gets from the resolved columns: which columns it has, how spin and the
//! heel–toe offset are derived, and the checks that the mapping feeds what a shots file needs.

use std::path::Path;

use super::columns::Resolved;
use super::target::numeric;
use super::{ImportOptions, Mapping, OffsetSide};
use crate::data::DataError;
use crate::model::DeliveryVar;

/// The measured-launch columns written only when the whole launch is measured.
const LAUNCH: [&str; 3] = ["ball_speed_mph", "launch_angle_deg", "azimuth_deg"];

/// The shots file's layout.
pub(super) struct Layout<'r, 'a> {
    /// The resolved export columns.
    pub resolved: &'r [Resolved<'a>],
    /// Which way a positive heel–toe offset points, when the user or the mapping states it.
    pub offset_side: Option<OffsetSide>,
    /// `impact_z_mm` is derived from a mapped `impact_offset_mm`.
    pub from_offset: bool,
    /// Back and side spin are derived from spin rate and axis.
    pub use_rate_axis: bool,
    /// Numeric shots columns written, in order.
    pub numeric: Vec<&'static str>,
    /// The text columns, when mapped.
    pub id: Option<&'r Resolved<'a>>,
    pub group: Option<&'r Resolved<'a>>,
    pub golfer: Option<&'r Resolved<'a>>,
    pub status: Option<&'r Resolved<'a>>,
}

impl<'r, 'a> Layout<'r, 'a> {
    /// Check that `resolved` feeds a shots file (required delivery, the heel–toe sign, a
    /// complete measured launch or none) and lay it out. `header_line` is where messages point.
    pub(super) fn plan(
        path: &Path,
        header_line: usize,
        resolved: &'r [Resolved<'a>],
        mapping: &Mapping,
        opts: &ImportOptions,
    ) -> Result<Self, DataError> {
        let vendor = &mapping.export.name;
        let has = |name: &str| resolved.iter().any(|r| r.spec.target == name);
        let offset_side = opts
            .impact_offset_positive
            .or(mapping.export.impact_offset_positive);
        check_delivery(path, header_line, resolved, offset_side, vendor)?;
        let launch_all = check_launch(path, header_line, &has)?;
        let use_rate_axis = launch_all && !(has("backspin_rpm") && has("sidespin_rpm"));
        let from_offset = has("impact_offset_mm");
        let mut out_numeric: Vec<&str> = numeric()
            .into_iter()
            .map(|(c, _)| c)
            .filter(|c| {
                has(c)
                    || (*c == "impact_z_mm" && from_offset)
                    || (use_rate_axis && (*c == "backspin_rpm" || *c == "sidespin_rpm"))
            })
            .collect();
        if !launch_all {
            out_numeric
                .retain(|c| !LAUNCH.contains(c) && !matches!(*c, "backspin_rpm" | "sidespin_rpm"));
        }
        let text_col = |name: &str| resolved.iter().find(|r| r.spec.target == name);
        Ok(Layout {
            resolved,
            offset_side,
            from_offset,
            use_rate_axis,
            numeric: out_numeric,
            id: text_col("shot_id"),
            group: text_col("group"),
            golfer: text_col("golfer"),
            status: text_col("status"),
        })
    }

    /// The shots file's header row.
    pub(super) fn header(&self) -> Vec<&'static str> {
        let mut head: Vec<&str> = vec!["shot_id"];
        if self.group.is_some() {
            head.push("group");
        }
        if self.golfer.is_some() {
            head.push("golfer");
        }
        head.extend(&self.numeric);
        head
    }
}

/// The delivery columns: every required one fed, the heel–toe location fed exactly once, and
/// the sign of a heel–toe offset stated (the import does not guess).
fn check_delivery(
    path: &Path,
    header_line: usize,
    resolved: &[Resolved],
    offset_side: Option<OffsetSide>,
    vendor: &str,
) -> Result<(), DataError> {
    let has = |name: &str| resolved.iter().any(|r| r.spec.target == name);
    if let Some(r) = resolved
        .iter()
        .find(|r| r.spec.target == "impact_offset_mm")
        .filter(|_| offset_side.is_none())
    {
        return Err(DataError::at(
            path,
            Some(header_line),
            Some(format!("column '{}'", r.header)),
            format!(
                "{vendor} does not document which way a positive heel–toe impact offset points; \
                 state it with --impact-offset-positive toe|heel (the import does not guess)"
            ),
        ));
    }
    if has("impact_offset_mm") && has("impact_z_mm") {
        return Err(DataError::file(
            path,
            "both impact_offset_mm and impact_z_mm are mapped; map one",
        ));
    }
    // The required delivery columns; impact_z_mm may come from impact_offset_mm.
    for need in DeliveryVar::ALL
        .into_iter()
        .filter(|v| v.required() && *v != DeliveryVar::ImpactZ)
        .map(DeliveryVar::column)
    {
        if !has(need) {
            return Err(DataError::file(
                path,
                format!("the mapping does not feed the required shots column {need}"),
            ));
        }
    }
    if !has("impact_offset_mm") && !has("impact_z_mm") {
        return Err(DataError::file(
            path,
            "the mapping feeds neither impact_z_mm nor impact_offset_mm (the heel–toe impact location)",
        ));
    }
    Ok(())
}

/// The measured launch is all there (ball speed, launch angle and direction, and back and side
/// spin or spin rate and axis: returns `true`) or absent (`false`); anything between is refused.
fn check_launch(
    path: &Path,
    header_line: usize,
    has: &dyn Fn(&str) -> bool,
) -> Result<bool, DataError> {
    let spin_pair = has("backspin_rpm") && has("sidespin_rpm");
    let rate_axis = has("spin_rate_rpm") && has("spin_axis_deg");
    let launch_any = LAUNCH.iter().any(|c| has(c))
        || [
            "backspin_rpm",
            "sidespin_rpm",
            "spin_rate_rpm",
            "spin_axis_deg",
        ]
        .iter()
        .any(|c| has(c));
    let launch_all = LAUNCH.iter().all(|c| has(c)) && (spin_pair || rate_axis);
    if launch_any && !launch_all {
        return Err(DataError::at(
            path,
            Some(header_line),
            None,
            "measured launch is incomplete: ball speed, launch angle, launch direction and either back and side spin \
             or spin rate and spin axis are all needed (or none of them)",
        ));
    }
    Ok(launch_all)
}
