//! One cell of an export: a number with an optional L/R direction letter or unit suffix.

use super::units::Unit;

pub(super) use crate::data::shots::list_lines;

/// Parse one cell: a number, optionally with an L/R letter before or after it (when the column
/// takes directions) or the column's own unit after it. Returns the value in the column's unit.
pub(super) fn parse_cell(raw: &str, unit: Unit, direction: Option<&str>) -> Result<f64, String> {
    let s = raw.trim();
    let mut letter: Option<char> = None;
    let mut rest = s;
    if let Some(c) = s.chars().next() {
        if matches!(c, 'L' | 'R' | 'l' | 'r')
            && s[1..]
                .trim_start()
                .starts_with(|d: char| d.is_ascii_digit() || d == '.')
        {
            letter = Some(c.to_ascii_uppercase());
            rest = s[1..].trim_start();
        }
    }
    // The numeric prefix.
    let bytes = rest.as_bytes();
    let mut end = 0;
    while end < bytes.len() {
        let b = bytes[end];
        let ok = b.is_ascii_digit()
            || b == b'.'
            || ((b == b'-' || b == b'+') && (end == 0 || matches!(bytes[end - 1], b'e' | b'E')))
            || ((b == b'e' || b == b'E')
                && end > 0
                && bytes
                    .get(end + 1)
                    .is_some_and(|n| n.is_ascii_digit() || *n == b'-' || *n == b'+'));
        if !ok {
            break;
        }
        end += 1;
    }
    let number = &rest[..end];
    let v: f64 = number
        .parse()
        .map_err(|_| format!("{} is not a number", crate::data::quote_cell(raw)))?;
    let tail = rest[end..].trim();
    if !tail.is_empty() {
        if letter.is_none() && matches!(tail, "L" | "R" | "l" | "r") {
            letter = Some(tail.chars().next().expect("one").to_ascii_uppercase());
        } else {
            match Unit::parse(tail) {
                Some(u) if u.name == unit.name => {}
                Some(u) => {
                    return Err(format!(
                        "mixed units: '{raw}' is in {} but the column is in {}",
                        u.name, unit.name
                    ))
                }
                None => return Err(format!("{} is not a number", crate::data::quote_cell(raw))),
            }
        }
    }
    match (letter, direction) {
        (None, _) => Ok(v),
        (Some(_), None) => Err(format!("'{raw}': this column does not take L/R directions")),
        (Some(_), Some(_)) if number.starts_with(['-', '+']) => {
            Err(format!("'{raw}': both a sign and an L/R letter; write one"))
        }
        (Some(l), Some(d)) => {
            let positive = if d == "R+" { 'R' } else { 'L' };
            Ok(if l == positive { v } else { -v })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn deg() -> Unit {
        Unit::parse("deg").unwrap()
    }

    #[test]
    fn directions_and_units_in_cells() {
        assert_eq!(parse_cell("5.4 L", deg(), Some("R+")), Ok(-5.4));
        assert_eq!(parse_cell("5.4R", deg(), Some("R+")), Ok(5.4));
        assert_eq!(parse_cell("L5.4", deg(), Some("R+")), Ok(-5.4));
        assert_eq!(parse_cell("R 5.4", deg(), Some("L+")), Ok(-5.4));
        assert_eq!(parse_cell("-2.5", deg(), Some("R+")), Ok(-2.5));
        assert_eq!(parse_cell("1e-3", deg(), None), Ok(1e-3));
        assert!(parse_cell("-5.4 L", deg(), Some("R+")).is_err());
        assert!(parse_cell("5.4 L", deg(), None).is_err());
        let mph = Unit::parse("mph").unwrap();
        assert_eq!(parse_cell("152.5 mph", mph, None), Ok(152.5));
        let e = parse_cell("245 km/h", mph, None).unwrap_err();
        assert!(e.contains("mixed units"), "{e}");
        assert!(parse_cell("fast", mph, None).is_err());
    }
}
