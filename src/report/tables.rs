//! Plain-text tables: a small aligned-column builder and the paper's Table-2 layout of launch
//! errors (mean and STD of model − measured, per launch component, per group).

use crate::physics::LaunchComponent;
use crate::stats::ErrorTable;

/// A table of text cells with right-aligned columns (the first column left-aligned).
#[derive(Debug, Clone, Default)]
pub struct TextTable {
    rows: Vec<Vec<String>>,
}

impl TextTable {
    /// A table with a header row.
    pub fn new<S: Into<String>>(header: impl IntoIterator<Item = S>) -> Self {
        Self {
            rows: vec![header.into_iter().map(Into::into).collect()],
        }
    }

    /// Append a row.
    pub fn row<S: Into<String>>(&mut self, cells: impl IntoIterator<Item = S>) -> &mut Self {
        self.rows.push(cells.into_iter().map(Into::into).collect());
        self
    }

    /// Render, one line per row, a rule under the header.
    pub fn render(&self) -> String {
        let ncol = self.rows.iter().map(Vec::len).max().unwrap_or(0);
        let width: Vec<usize> = (0..ncol)
            .map(|c| {
                self.rows
                    .iter()
                    .filter_map(|r| r.get(c))
                    .map(|s| s.chars().count())
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        let mut out = String::new();
        for (i, r) in self.rows.iter().enumerate() {
            let mut line = String::new();
            for (c, w) in width.iter().enumerate() {
                let cell = r.get(c).map_or("", String::as_str);
                if c == 0 {
                    line.push_str(&format!("{cell:<w$}"));
                } else {
                    line.push_str(&format!("  {cell:>w$}"));
                }
            }
            out.push_str(line.trim_end());
            out.push('\n');
            if i == 0 {
                let total: usize = width.iter().sum::<usize>() + 2 * width.len().saturating_sub(1);
                out.push_str(&"-".repeat(total));
                out.push('\n');
            }
        }
        out
    }
}

/// A launch-component value with the precision its unit deserves (rpm: integer).
pub fn fmt_value(c: LaunchComponent, v: f64) -> String {
    if !v.is_finite() {
        // Undefined (the spread of a single shot): shown as a dash, `null` in JSON.
        return "–".to_owned();
    }
    match c {
        LaunchComponent::Backspin | LaunchComponent::Sidespin => format!("{v:.0}"),
        _ => format!("{v:.2}"),
    }
}

/// The paper's Table-2 layout for one error table.
pub fn error_table_text(t: &ErrorTable) -> String {
    let mut header = vec!["component".to_owned()];
    for g in &t.groups {
        header.push(format!("{} mean", g.group));
        header.push("std".to_owned());
    }
    let mut tt = TextTable::new(header);
    for c in LaunchComponent::ALL {
        let mut row = vec![format!("{} ({})", c.label(), c.unit())];
        for g in &t.groups {
            let ms = g.components[c.index()];
            row.push(fmt_value(c, ms.mean));
            row.push(fmt_value(c, ms.std));
        }
        tt.row(row);
    }
    tt.render()
}

/// Two Table-2 tables side by side (`before` and `after`, same groups), with titles.
pub fn error_tables_side_by_side(
    before: &ErrorTable,
    after: &ErrorTable,
    titles: (&str, &str),
) -> String {
    let left = error_table_text(before);
    let right = error_table_text(after);
    let lw = left.lines().map(|l| l.chars().count()).max().unwrap_or(0);
    let mut out = format!("{:<lw$}   | {}\n", titles.0, titles.1);
    for (l, r) in left.lines().zip(right.lines()) {
        out.push_str(&format!("{l:<lw$}   | {r}\n"));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::launch_error_table;

    #[test]
    fn a_single_shot_groups_undefined_spread_is_a_dash() {
        // The spread of a one-shot group is undefined (NaN in the table, null in JSON): text
        // shows a dash, never "NaN".
        let t = launch_error_table(&["A", "A", "B"], &[[1.0; 5], [3.0; 5], [2.0; 5]]);
        let std = t.groups[1].components[0].std;
        assert!(std.is_nan());
        assert!(fmt_value(LaunchComponent::BallSpeed, std) == "–");
        assert!(fmt_value(LaunchComponent::BallSpeed, f64::NAN) == "–");
    }

    #[test]
    fn renders_aligned() {
        let mut t = TextTable::new(["a", "bb"]);
        t.row(["xyz", "1"]);
        let s = t.render();
        assert_eq!(s, "a    bb\n-------\nxyz   1\n");
        let e = launch_error_table(&["A", "B"], &[[1.0, 2.0, 3.0, 400.0, 5.0]; 2]);
        let s = error_tables_side_by_side(&e, &e, ("before", "after"));
        assert!(s.contains("Ball speed (mph)") && s.contains("A mean") && s.contains("| "));
        assert!(s.lines().next().unwrap().starts_with("before"));
    }
}
