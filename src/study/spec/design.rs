//! The `[grid]` and `[design]` tables: the face grid and the design variants.

use std::collections::BTreeMap;

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use toml::Spanned;

use super::axis::{parse_axis, Axis};
use crate::club::ClubSpec;
use crate::data::{DataError, TomlDoc};
use crate::limits;
use crate::study::design::{Design, DesignVar, DiscretionaryMass};
use crate::units::{g, mm};

/// The grid of impact locations, mm in the CoF tangent plane.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Heights up the face (rows), strictly ascending.
    pub y_mm: Axis,
    /// Positions toward the toe (columns), strictly ascending.
    pub z_mm: Axis,
}

/// The design variants: the cartesian product of the listed variable axes.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignSpace {
    /// Variable axes, in [`DesignVar::ALL`] order (the first is the outermost loop).
    pub axes: Vec<(DesignVar, Axis)>,
    /// The movable mass, when any `mass_*` variable is used.
    pub discretionary_mass: Option<DiscretionaryMass>,
}

impl DesignSpace {
    /// All variants, in order: the last axis varies fastest.
    pub fn variants(&self) -> Vec<Design> {
        let mut out = vec![Design::default()];
        for (var, axis) in &self.axes {
            let vals = axis.values();
            out = out
                .into_iter()
                .flat_map(|d| vals.iter().map(move |&x| d.with(*var, x)))
                .collect();
        }
        out
    }
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawGrid {
    pub y_mm: Spanned<toml::Value>,
    pub z_mm: Spanned<toml::Value>,
}

/// `[design]`: variable name → axis, and `discretionary_mass`.
pub(super) type RawDesign = BTreeMap<Spanned<String>, Spanned<toml::Value>>;

pub(super) fn parse_grid(doc: &TomlDoc<'_>, raw: &RawGrid) -> Result<Grid, DataError> {
    let grid = Grid {
        y_mm: parse_axis(doc, &raw.y_mm, "grid.y_mm", limits::GRID_LOCATION_MM)?,
        z_mm: parse_axis(doc, &raw.z_mm, "grid.z_mm", limits::GRID_LOCATION_MM)?,
    };
    for (axis, v, key) in [
        (&grid.y_mm, &raw.y_mm, "grid.y_mm"),
        (&grid.z_mm, &raw.z_mm, "grid.z_mm"),
    ] {
        let vals = axis.values();
        if vals.windows(2).any(|w| !(w[1] > w[0])) {
            return Err(doc.err(v.span(), key, "values must be strictly ascending"));
        }
    }
    Ok(grid)
}

pub(super) fn parse_design(
    doc: &TomlDoc<'_>,
    table: Option<&RawDesign>,
    club: &ClubSpec,
) -> Result<DesignSpace, DataError> {
    let mut axes = Vec::new();
    let mut discretionary_mass = None;
    for (k, v) in table.into_iter().flatten() {
        let key = k.get_ref().as_str();
        if key == "discretionary_mass" {
            discretionary_mass = Some(parse_mass(doc, v, club)?);
            continue;
        }
        let full = format!("design.{key}");
        let var = design_var(doc, k, &full, true)?;
        axes.push((var, parse_axis(doc, v, &full, var.range())?));
    }
    axes.sort_by_key(|(v, _)| *v);
    if discretionary_mass.is_none() {
        if let Some((var, _)) = axes.iter().find(|(v, _)| v.needs_discretionary_mass()) {
            return Err(doc.whole(
                &format!("design.{}", var.key()),
                "moving the discretionary mass needs design.discretionary_mass = { mass_g = …, \
                 at_mm = [x, y, z] }",
            ));
        }
    }
    Ok(DesignSpace {
        axes,
        discretionary_mass,
    })
}

/// The design variable named by `name` (`with_mass`: `discretionary_mass` is allowed too).
pub(super) fn design_var(
    doc: &TomlDoc<'_>,
    name: &Spanned<String>,
    key: &str,
    with_mass: bool,
) -> Result<DesignVar, DataError> {
    let mut allowed: Vec<(&str, Option<DesignVar>)> =
        DesignVar::ALL.iter().map(|v| (v.key(), Some(*v))).collect();
    if with_mass {
        allowed.push(("discretionary_mass", None));
    }
    doc.one_of(
        name.span(),
        key,
        "design variable",
        name.get_ref(),
        &allowed,
    )?
    .ok_or_else(|| doc.err(name.span(), key, "is not a design variable"))
}

const MASS_FORM: &str =
    "{ mass_g = …, at_mm = [x, y, z] } (at_mm: the mass's base position from the CoF, in F)";

fn parse_mass(
    doc: &TomlDoc<'_>,
    v: &Spanned<toml::Value>,
    club: &ClubSpec,
) -> Result<DiscretionaryMass, DataError> {
    let key = "design.discretionary_mass";
    let toml::Value::Table(t) = v.get_ref() else {
        return Err(doc.err(v.span(), key, format!("must be a table {MASS_FORM}")));
    };
    if let Some(k) = t.keys().find(|k| *k != "mass_g" && *k != "at_mm") {
        let m = crate::data::toml_check::unknown_message("key", k, &["mass_g", "at_mm"]);
        return Err(doc.err(v.span(), key, m));
    }
    let m = t
        .get("mass_g")
        .ok_or_else(|| doc.err(v.span(), key, format!("missing `mass_g`; {MASS_FORM}")))
        .and_then(|x| doc.number(x, v.span(), "design.discretionary_mass.mass_g"))?;
    limits::check_head_part_mass_g("the discretionary mass", m, club.nominal.club_mass_kg)
        .map_err(|e| doc.err(v.span(), "design.discretionary_mass.mass_g", e))?;
    let at_key = "design.discretionary_mass.at_mm";
    let at = match t.get("at_mm") {
        Some(toml::Value::Array(a)) if a.len() == 3 => a
            .iter()
            .map(|x| {
                doc.number(x, v.span(), at_key).and_then(|x| {
                    limits::CLUB_COM_MM
                        .check(x)
                        .map_err(|m| doc.err(v.span(), at_key, m))
                })
            })
            .collect::<Result<Vec<_>, _>>()?,
        _ => {
            return Err(doc.err(
                v.span(),
                at_key,
                format!("must be [x, y, z] in mm; {MASS_FORM}"),
            ))
        }
    };
    limits::check_behind_face_mm("the discretionary mass", at[0])
        .map_err(|m| doc.err(v.span(), at_key, m))?;
    Ok(DiscretionaryMass {
        mass_kg: g(m),
        at_m: Vector3::new(mm(at[0]), mm(at[1]), mm(at[2])),
    })
}

/// The grid as a `[grid]` table.
pub(super) fn raw_grid(grid: &Grid) -> RawGrid {
    RawGrid {
        y_mm: Spanned::new(0..0, grid.y_mm.to_value()),
        z_mm: Spanned::new(0..0, grid.z_mm.to_value()),
    }
}

/// The design space as a `[design]` table (`None` when it has no axes and no mass).
pub(super) fn raw_design(d: &DesignSpace) -> Option<RawDesign> {
    let key = |k: &str| Spanned::new(0..0, k.to_owned());
    let mut t: RawDesign = d
        .axes
        .iter()
        .map(|(v, a)| (key(v.key()), Spanned::new(0..0, a.to_value())))
        .collect();
    if let Some(m) = &d.discretionary_mass {
        let a = m.at_m * 1e3;
        let mut mass = toml::Table::new();
        mass.insert("mass_g".into(), toml::Value::Float(m.mass_kg * 1e3));
        let at = [a.x, a.y, a.z].map(toml::Value::Float).to_vec();
        mass.insert("at_mm".into(), toml::Value::Array(at));
        t.insert(
            key("discretionary_mass"),
            Spanned::new(0..0, toml::Value::Table(mass)),
        );
    }
    (!t.is_empty()).then_some(t)
}
