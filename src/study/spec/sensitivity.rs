//! The `[sensitivity]` table: which design variables to differentiate, and their steps.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use toml::Spanned;

use super::design::{design_var, DesignSpace};
use crate::data::{DataError, TomlDoc};
use crate::limits;
use crate::study::design::DesignVar;

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSensitivity {
    pub variables: Option<Vec<Spanned<String>>>,
    pub steps: Option<BTreeMap<Spanned<String>, Spanned<f64>>>,
}

pub(super) fn parse_sensitivity(
    doc: &TomlDoc<'_>,
    s: &Spanned<RawSensitivity>,
    design: &DesignSpace,
) -> Result<Vec<(DesignVar, f64)>, DataError> {
    let r = s.get_ref();
    let mut vars: Vec<DesignVar> = match &r.variables {
        Some(list) => list
            .iter()
            .map(|n| design_var(doc, n, "sensitivity.variables", false))
            .collect::<Result<_, _>>()?,
        None => design.axes.iter().map(|(v, _)| *v).collect(),
    };
    vars.sort();
    vars.dedup();
    if vars.is_empty() {
        return Err(doc.err(
            s.span(),
            "sensitivity.variables",
            format!(
                "no variables: list some, or give [design] axes; allowed: {}",
                DesignVar::all_keys()
            ),
        ));
    }
    let mut steps: Vec<(DesignVar, f64)> = vars.iter().map(|v| (*v, v.default_step())).collect();
    for (k, v) in r.steps.iter().flatten() {
        let key = format!("sensitivity.steps.{}", k.get_ref());
        let slot = steps
            .iter_mut()
            .find(|(var, _)| var.key() == k.get_ref())
            .ok_or_else(|| {
                let names: Vec<&str> = vars.iter().map(|v| v.key()).collect();
                doc.err(
                    k.span(),
                    &key,
                    format!(
                        "not one of the sensitivity variables; allowed: {}",
                        names.join(", ")
                    ),
                )
            })?;
        slot.1 = step(doc, v, &key, slot.0)?;
    }
    if design.discretionary_mass.is_none() {
        if let Some((v, _)) = steps.iter().find(|(v, _)| v.needs_discretionary_mass()) {
            return Err(doc.err(
                s.span(),
                "sensitivity.variables",
                format!("{} needs design.discretionary_mass", v.key()),
            ));
        }
    }
    Ok(steps)
}

/// Smallest central-difference step, as a fraction of the variable's reference change
/// (`DesignVar::reference_change`: 1 mm, 0.1, 100 g·cm²). A step `h` moves the launch by about
/// `h·f'`, which must stand well clear of the launch's rounding (~1e-16 of it) for the
/// difference quotient to mean anything. Its rounding error is about `1e-16·|f|/h`: with a
/// millionth of the reference change (1e-6 mm) and a ball speed of 150 mph that is 1.5e-8 mph
/// per mm, under a millionth of a typical 0.05 mph/mm; a step of, say, 1e-300 mm changes no
/// bit of the club at all and gives exact-zero derivatives.
const MIN_STEP_OF_REFERENCE: f64 = 1e-6;

/// A central-difference step of `var`: not below [`MIN_STEP_OF_REFERENCE`] of its reference
/// change, and both evaluations physical.
fn step(doc: &TomlDoc<'_>, v: &Spanned<f64>, key: &str, var: DesignVar) -> Result<f64, DataError> {
    let h = doc.positive(v, key, var.unit())?;
    let min = var.reference_change() * MIN_STEP_OF_REFERENCE;
    if h < min {
        return Err(doc.err(
            v.span(),
            key,
            format!(
                "{} {} is below the smallest meaningful step {} {} (the difference it makes is \
                 lost in the numbers' precision); the default is {}",
                limits::fmt_value(h),
                var.unit(),
                limits::fmt_value(min),
                var.unit(),
                limits::fmt_value(var.default_step())
            ),
        ));
    }
    let r = var.range();
    let n = var.neutral();
    if !(r.contains(n - h) && r.contains(n + h)) {
        return Err(doc.err(
            v.span(),
            key,
            format!(
                "the central difference evaluates {} ± {}, outside the physical range {r}",
                limits::fmt_value(n),
                limits::fmt_value(h)
            ),
        ));
    }
    let is_scale = matches!(
        var,
        DesignVar::InertiaScale | DesignVar::IxxScale | DesignVar::IyyScale | DesignVar::IzzScale
    );
    if is_scale && h >= 0.5 {
        return Err(doc.err(
            v.span(),
            key,
            format!(
                "a scale's central difference evaluates 1 ± step; the step must be below 0.5 \
                 (typically 0.01), got {}",
                limits::fmt_value(h)
            ),
        ));
    }
    Ok(h)
}

/// The sensitivities as a `[sensitivity]` table.
pub(super) fn raw_sensitivity(sens: &[(DesignVar, f64)]) -> RawSensitivity {
    let name = |v: &DesignVar| Spanned::new(0..0, v.key().to_owned());
    RawSensitivity {
        variables: Some(sens.iter().map(|(v, _)| name(v)).collect()),
        steps: Some(
            sens.iter()
                .map(|(v, h)| (name(v), Spanned::new(0..0, *h)))
                .collect(),
        ),
    }
}
