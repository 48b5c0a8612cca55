//! Axes of values (`[grid]` and `[design]`): a number, a list, or a range with a count or step.

use std::ops::Range;

use toml::Spanned;

use crate::data::{DataError, TomlDoc};
use crate::limits::{self, fmt_value, PhysicalRange};

/// Values of one axis: an explicit list, or `count` evenly spaced values from `from` to `to`.
#[derive(Debug, Clone, PartialEq)]
pub enum Axis {
    /// Explicit values.
    List(Vec<f64>),
    /// `count` values from `from` to `to` inclusive (`count = 1` gives `from`).
    Range {
        /// First value.
        from: f64,
        /// Last value.
        to: f64,
        /// Number of values (≥ 1).
        count: usize,
    },
}

/// `v` as the decimal of at most nine significant figures it misses by rounding alone (within
/// 12 significant figures), else `v`: `{ from = 0, to = 0.3, step = 0.1 }` gives 0.1 and 0.2,
/// not 0.09999999999999999 and 0.19999999999999998, while a third stays a third.
fn short_decimal(v: f64) -> f64 {
    let Ok(r) = format!("{v:.11e}").parse::<f64>() else {
        return v;
    };
    let text = format!("{r:e}");
    let mantissa = text.split('e').next().unwrap_or("");
    let digits = mantissa.chars().filter(char::is_ascii_digit).count();
    if digits <= 9 {
        r
    } else {
        v
    }
}

impl Axis {
    /// The values.
    pub fn values(&self) -> Vec<f64> {
        match self {
            Axis::List(v) => v.clone(),
            Axis::Range { from, to, count } => {
                if *count == 1 {
                    return vec![*from];
                }
                let n = (*count - 1) as f64;
                (0..*count)
                    .map(|i| {
                        if i + 1 == *count {
                            *to
                        } else {
                            short_decimal(from + (to - from) * (i as f64 / n))
                        }
                    })
                    .collect()
            }
        }
    }

    /// Number of values, without building them.
    pub fn len(&self) -> usize {
        match self {
            Axis::List(v) => v.len(),
            Axis::Range { count, .. } => *count,
        }
    }

    /// Whether the axis has no values (never, once parsed).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The axis as a study-file value (a list, or `{ from, to, count }`).
    pub(super) fn to_value(&self) -> toml::Value {
        match self {
            Axis::List(v) => toml::Value::Array(v.iter().map(|x| toml::Value::Float(*x)).collect()),
            Axis::Range { from, to, count } => {
                let mut t = toml::Table::new();
                t.insert("from".into(), toml::Value::Float(*from));
                t.insert("to".into(), toml::Value::Float(*to));
                t.insert("count".into(), toml::Value::Integer(*count as i64));
                toml::Value::Table(t)
            }
        }
    }
}

const AXIS_FORMS: &str =
    "a number, a list of numbers, or a range { from, to, count } or { from, to, step }";

/// An axis whose every value lies in `range`: a number, a list of numbers, or
/// `{ from, to, count }` / `{ from, to, step }`.
pub(super) fn parse_axis(
    doc: &TomlDoc<'_>,
    v: &Spanned<toml::Value>,
    key: &str,
    range: PhysicalRange,
) -> Result<Axis, DataError> {
    let axis = axis_values(doc, v, key)?;
    let span = v.span();
    match &axis {
        Axis::List(vals) => {
            if vals.len() > limits::MAX_AXIS_VALUES {
                return Err(doc.err(
                    span,
                    key,
                    format!(
                        "{} values; at most {} an axis",
                        vals.len(),
                        limits::MAX_AXIS_VALUES
                    ),
                ));
            }
            if let Some(x) = vals.iter().find(|x| !range.contains(**x)) {
                return Err(doc.err(span, key, range.refusal(*x)));
            }
        }
        Axis::Range { from, to, .. } => {
            for (x, k) in [(*from, "from"), (*to, "to")] {
                if !range.contains(x) {
                    return Err(doc.err(span.clone(), &format!("{key}.{k}"), range.refusal(x)));
                }
            }
        }
    }
    Ok(axis)
}

fn axis_values(doc: &TomlDoc<'_>, v: &Spanned<toml::Value>, key: &str) -> Result<Axis, DataError> {
    let span = v.span();
    match v.get_ref() {
        toml::Value::Float(_) | toml::Value::Integer(_) => {
            Ok(Axis::List(vec![doc.number(v.get_ref(), span, key)?]))
        }
        toml::Value::Array(items) => {
            if items.is_empty() {
                return Err(doc.err(span, key, format!("the list is empty; give {AXIS_FORMS}")));
            }
            let vals = items
                .iter()
                .map(|x| doc.number(x, span.clone(), key))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(Axis::List(vals))
        }
        toml::Value::Table(t) => range_axis(doc, t, span, key),
        other => Err(doc.err(
            span,
            key,
            format!("got {}; give {AXIS_FORMS}", other.type_str()),
        )),
    }
}

/// `{ from, to, count }` or `{ from, to, step }`.
fn range_axis(
    doc: &TomlDoc<'_>,
    t: &toml::Table,
    span: Range<usize>,
    key: &str,
) -> Result<Axis, DataError> {
    const KEYS: [&str; 4] = ["from", "to", "count", "step"];
    if let Some(k) = t.keys().find(|k| !KEYS.contains(&k.as_str())) {
        return Err(doc.err(
            span,
            key,
            format!(
                "{}; a range has from, to and count or step",
                crate::data::toml_check::unknown_message("range key", k, &KEYS)
            ),
        ));
    }
    let get = |k: &str| {
        t.get(k)
            .ok_or_else(|| doc.err(span.clone(), key, format!("range: missing `{k}`")))
            .and_then(|x| doc.number(x, span.clone(), &format!("{key}.{k}")))
    };
    let (from, to) = (get("from")?, get("to")?);
    let count = match (t.get("count"), t.get("step")) {
        (Some(_), Some(_)) | (None, None) => {
            return Err(doc.err(span, key, "range: give exactly one of `count` or `step`"))
        }
        (Some(toml::Value::Integer(c)), None)
            if *c >= 1 && *c <= limits::MAX_AXIS_VALUES as i64 =>
        {
            *c as usize
        }
        (Some(c), None) => {
            return Err(doc.err(
                span,
                &format!("{key}.count"),
                format!(
                    "must be an integer from 1 to {}, got {c}",
                    limits::MAX_AXIS_VALUES
                ),
            ))
        }
        (None, Some(_)) => step_count(doc, span.clone(), key, from, to, get("step")?)?,
    };
    if count == 1 && to != from {
        return Err(doc.err(
            span,
            &format!("{key}.count"),
            format!(
                "count = 1 needs from = to (got from = {}, to = {})",
                fmt_value(from),
                fmt_value(to)
            ),
        ));
    }
    if count > 1 && !(to > from) {
        return Err(doc.err(
            span,
            key,
            format!(
                "range: `to` ({}) must exceed `from` ({})",
                fmt_value(to),
                fmt_value(from)
            ),
        ));
    }
    if count > 1 {
        let spacing = (to - from) / (count - 1) as f64;
        if !(spacing >= limits::MIN_AXIS_SPACING) {
            return Err(doc.err(
                span,
                key,
                format!(
                    "range: its values are {} apart; they must be at least {} apart (in the \
                     axis's unit)",
                    fmt_value(spacing),
                    fmt_value(limits::MIN_AXIS_SPACING)
                ),
            ));
        }
    }
    Ok(Axis::Range { from, to, count })
}

/// The number of points `{ from, to, step }` gives.
fn step_count(
    doc: &TomlDoc<'_>,
    span: Range<usize>,
    key: &str,
    from: f64,
    to: f64,
    step: f64,
) -> Result<usize, DataError> {
    let n = (to - from) / step;
    if !(step > 0.0) || !(n >= 0.0) || (n - n.round()).abs() > 1e-9 * n.max(1.0) {
        return Err(doc.err(
            span,
            &format!("{key}.step"),
            format!(
                "must be > 0 and divide to − from = {} into whole steps, got {}",
                fmt_value(to - from),
                fmt_value(step)
            ),
        ));
    }
    if n.round() + 1.0 > limits::MAX_AXIS_VALUES as f64 {
        return Err(doc.err(
            span,
            &format!("{key}.step"),
            format!(
                "{} gives {} points; at most {} points an axis",
                fmt_value(step),
                fmt_value(n.round() + 1.0),
                limits::MAX_AXIS_VALUES
            ),
        ));
    }
    Ok(n.round() as usize + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn range_values_are_the_decimals_the_user_wrote() {
        let a = Axis::Range {
            from: 0.0,
            to: 0.3,
            count: 4,
        };
        assert_eq!(a.values(), [0.0, 0.1, 0.2, 0.3]);
        let a = Axis::Range {
            from: -20.0,
            to: 20.0,
            count: 401,
        };
        assert!(
            a.values().iter().all(|v| format!("{v}").len() <= 5),
            "{:?}",
            a.values()
        );
        // Thirds stay thirds (no short decimal is near them).
        let a = Axis::Range {
            from: 0.0,
            to: 1.0,
            count: 4,
        };
        assert_eq!(a.values()[1], 1.0 / 3.0);
    }
}
