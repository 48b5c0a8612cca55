//! What the shots file gets from the resolved columns: which columns it has, how spin and the
//! heel–toe offset are derived, and the checks that the mapping feeds what a shots file needs:
//! a complete delivery, a complete measured launch, or both (a launch-only export, from a
//! monitor that measures no dynamic loft or impact location, imports for `smash flight`).

use std::path::Path;

use super::columns::Resolved;
use super::table::Table;
use super::target::{numeric, Target, LAUNCH};
use super::{ExportSpec, ImportOptions, Mapping, OffsetSide};
use crate::data::DataError;
use crate::model::convention::DeliveryConvention;
use crate::model::DeliveryVar;

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
    /// Side spin is derived from back spin and spin axis (`side = back · tan a`), for an
    /// export that gives back spin and axis but no side spin or total.
    pub use_back_axis: bool,
    /// Back and side spin and spin rate and axis are all given: they are checked against each
    /// other.
    pub check_spin: bool,
    /// The export measures the launch (every row written has it).
    pub launch_all: bool,
    /// The export gives every required delivery column (a row may still leave cells empty).
    pub delivery_all: bool,
    /// Numeric shots columns written, in order.
    pub numeric: Vec<&'static str>,
    /// Text and flag columns written after the numeric ones (`ball_type`, `spin_estimated`,
    /// `club_estimated`, `flight_modelled`).
    pub extra: Vec<&'static str>,
    /// Every shot's flight figures are the vendor's model (the mapping says so).
    pub all_modelled: bool,
    /// The delivery's convention, as the mapping states it, when it maps delivery angles or
    /// velocity (written as the `face_at`, `velocity_at`, `face_angle_from` columns).
    pub convention: Option<DeliveryConvention>,
    /// The text columns, when mapped.
    pub id: Option<&'r Resolved<'a>>,
    pub group: Option<&'r Resolved<'a>>,
    pub golfer: Option<&'r Resolved<'a>>,
    pub status: Option<&'r Resolved<'a>>,
}

impl<'r, 'a> Layout<'r, 'a> {
    /// Check that `resolved` feeds a shots file (a complete delivery or a complete measured
    /// launch, the heel–toe sign when the file holds offsets, a launch all there or absent)
    /// and lay it out. Messages point at the header line.
    pub(super) fn plan(
        path: &Path,
        table: &Table,
        resolved: &'r [Resolved<'a>],
        mapping: &Mapping,
        opts: &ImportOptions,
    ) -> Result<Self, DataError> {
        let header_line = table.header_line;
        let has = |name: &str| resolved.iter().any(|r| r.spec.target == name);
        let offset_side = offset_side(path, header_line, resolved, opts, mapping)?;
        let launch_all = check_launch(path, header_line, &has)?;
        let delivery_all = check_delivery(
            path,
            table,
            resolved,
            offset_side,
            &mapping.export,
            launch_all,
        )?;
        let spin_pair = has("backspin_rpm") && has("sidespin_rpm");
        let back_axis = has("backspin_rpm") && has("spin_axis_deg") && !has("sidespin_rpm");
        let use_rate_axis = launch_all && !spin_pair && has("spin_rate_rpm");
        let use_back_axis = launch_all && !spin_pair && !use_rate_axis && back_axis;
        let check_spin = launch_all && spin_pair && has("spin_rate_rpm") && has("spin_axis_deg");
        let from_offset = has("impact_offset_mm");
        let condition = has("condition");
        let mut out_numeric: Vec<&str> = numeric()
            .into_iter()
            .map(|(c, _)| c)
            .filter(|c| {
                has(c)
                    || (*c == "impact_z_mm" && from_offset)
                    || ((use_rate_axis || use_back_axis)
                        && (*c == "backspin_rpm" || *c == "sidespin_rpm"))
                    || (condition && matches!(*c, "altitude_m" | "air_temperature_c"))
            })
            .collect();
        if !launch_all {
            out_numeric
                .retain(|c| !LAUNCH.contains(c) && !matches!(*c, "backspin_rpm" | "sidespin_rpm"));
        }
        let mut extra = Vec::new();
        if has("datetime") {
            extra.push("datetime");
        }
        if has("ball_type") || condition {
            extra.push("ball_type");
        }
        for flag in ["spin_estimated", "club_estimated"] {
            if has(flag) {
                extra.push(flag);
            }
        }
        let all_modelled = mapping.export.flight_modelled;
        if condition || all_modelled || (has("tracked_length_yd") && has("carry_yd")) {
            extra.push("flight_modelled");
        }
        let delivery_mapped = ["dynamic_loft_deg", "face_angle_deg", "club_speed_mph"]
            .iter()
            .chain(&["attack_angle_deg", "club_path_deg"])
            .any(|c| has(c));
        let convention = delivery_mapped.then(|| super::conventions::of_mapping(mapping, &has));
        if let Some(c) = convention {
            extra.extend(super::conventions::cells(c).map(|(col, _)| col));
        }
        let text_col = |name: &str| resolved.iter().find(|r| r.spec.target == name);
        Ok(Layout {
            resolved,
            offset_side,
            from_offset,
            use_rate_axis,
            use_back_axis,
            check_spin,
            launch_all,
            delivery_all,
            numeric: out_numeric,
            extra,
            all_modelled,
            convention,
            id: text_col("shot_id"),
            group: text_col("group"),
            golfer: text_col("golfer"),
            status: text_col("status"),
        })
    }

    /// The resolved column feeding `target`, when mapped.
    pub(super) fn column(&self, target: &str) -> Option<&'r Resolved<'a>> {
        self.resolved.iter().find(|r| r.spec.target == target)
    }

    /// The resolved columns of one kind of target.
    pub(super) fn of(&self, target: Target) -> Option<&'r Resolved<'a>> {
        self.resolved.iter().find(|r| r.target == target)
    }

    /// The units the speeds and the carry were read in, for messages
    /// (`ball speed in m/s, club speed in mph, carry in yd`).
    pub(super) fn units_read(&self) -> String {
        ["ball_speed_mph", "club_speed_mph", "carry_yd"]
            .iter()
            .filter_map(|t| {
                let r = self.column(t)?;
                let what = t.rsplit_once('_').map_or(*t, |(w, _)| w).replace('_', " ");
                Some(format!("{what} in {}", r.unit?.name))
            })
            .collect::<Vec<_>>()
            .join(", ")
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
        head.extend(&self.extra);
        head
    }
}

/// The side a positive heel–toe offset points to: the user's `--impact-offset-positive`, the
/// mapping's, or the header's sign legend (`Face Impact Horizontal (mm toe-/heel+)`); a side
/// stated that the legend contradicts refuses the file.
fn offset_side(
    path: &Path,
    header_line: usize,
    resolved: &[Resolved],
    opts: &ImportOptions,
    mapping: &Mapping,
) -> Result<Option<OffsetSide>, DataError> {
    let stated = opts
        .impact_offset_positive
        .or(mapping.export.impact_offset_positive);
    let Some((r, side)) = resolved
        .iter()
        .find_map(|r| r.legend_offset.map(|s| (r, s)))
    else {
        return Ok(stated);
    };
    match stated {
        Some(s) if s != side => Err(DataError::at(
            path,
            Some(header_line),
            Some(format!("column '{}'", r.header)),
            format!(
                "the header's sign legend says a positive offset points to the {}, but the \
                 {} says the {}; drop the option or the mapping's impact_offset_positive",
                side.word(),
                if opts.impact_offset_positive.is_some() {
                    "--impact-offset-positive option"
                } else {
                    "mapping"
                },
                s.word()
            ),
        )),
        _ => Ok(Some(side)),
    }
}

/// The delivery columns: every required one fed (unless the export measures the launch:
/// then the delivery is optional, and a launch-only file imports for flight), the heel–toe
/// location fed at most once, and the sign of a heel–toe offset stated when any row holds one
/// (the import does not guess). Returns whether the whole delivery is fed.
fn check_delivery(
    path: &Path,
    table: &Table,
    resolved: &[Resolved],
    offset_side: Option<OffsetSide>,
    export: &ExportSpec,
    launch_all: bool,
) -> Result<bool, DataError> {
    let vendor = &export.name;
    let has = |name: &str| resolved.iter().any(|r| r.spec.target == name);
    let offset_held = |r: &&Resolved| {
        table.rows.iter().any(|(_, cells)| {
            cells.get(r.index).is_some_and(|c| {
                !super::missing::not_measured(c.trim(), &r.spec.missing, &export.missing)
            })
        })
    };
    if let Some(r) = resolved
        .iter()
        .find(|r| r.spec.target == "impact_offset_mm")
        .filter(offset_held)
        .filter(|_| offset_side.is_none())
    {
        return Err(DataError::at(
            path,
            Some(table.header_line),
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
    let missing: Vec<&str> = DeliveryVar::ALL
        .into_iter()
        .filter(|v| v.required())
        .map(DeliveryVar::column)
        .filter(|c| !(has(c) || (*c == "impact_z_mm" && has("impact_offset_mm"))))
        .collect();
    if !missing.is_empty() && !launch_all {
        return Err(DataError::file(
            path,
            format!(
                "the mapping feeds neither a measured launch nor the whole delivery (missing: {}); \
                 a shots file needs one of them",
                missing.join(", ")
            ),
        ));
    }
    Ok(missing.is_empty())
}

/// The measured launch is all there (ball speed, launch angle and direction, and back and side
/// spin or spin rate and axis: returns `true`) or absent (`false`); anything between is refused.
fn check_launch(
    path: &Path,
    header_line: usize,
    has: &dyn Fn(&str) -> bool,
) -> Result<bool, DataError> {
    let spin_pair = has("backspin_rpm") && has("sidespin_rpm");
    let rate_axis = (has("spin_rate_rpm") || has("backspin_rpm")) && has("spin_axis_deg");
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
            "measured launch is incomplete: ball speed, launch angle, launch direction and back and side spin, \
             spin rate and spin axis, or back spin and spin axis are all needed (or none of them)",
        ));
    }
    Ok(launch_all)
}
