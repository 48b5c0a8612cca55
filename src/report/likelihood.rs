//! How the models of `calibrate` and `diagnose` were scored, as text and JSON: the likelihood
//! table, the scales and how they were set ([`crate::fit::likelihood`]).

use crate::fit::{Likelihood, ScaleSource};
use crate::physics::LaunchComponent;
use crate::report::TextTable;

/// `head` then per component `name value unit`, comma-separated, wrapped with `indent` and two
/// spaces so that no line passes 99 columns; ends with a newline.
pub fn scales_text(head: &str, indent: &str, scales: &[f64; 5]) -> String {
    let mut s = format!("{indent}{head}");
    let mut line = s.chars().count();
    for (i, c) in LaunchComponent::ALL.iter().enumerate() {
        let mut piece = format!("{} {:.4} {}", c.column(), scales[c.index()], c.unit());
        if i + 1 < LaunchComponent::ALL.len() {
            piece.push(',');
        }
        let width = piece.chars().count() + 1;
        if line + width > 99 {
            s.push_str(&format!("\n{indent} "));
            line = indent.len() + 1;
        }
        s.push(' ');
        s.push_str(&piece);
        line += width;
    }
    s.push('\n');
    s
}

/// The likelihood table of the models `rows` (name, score), all on the first one's scale, with
/// a header saying how the scales were set and the scales (given: once; profiled: the first
/// and the last model's); `indent` before every line.
pub fn text(rows: &[(&str, &Likelihood)], indent: &str) -> String {
    let Some((_, first)) = rows.first() else {
        return String::new();
    };
    let how = match &first.source {
        ScaleSource::Profiled => {
            "PROFILED (estimated in each fit, sigma_c^2 = RSS_c/n; k counts the 5 scales)"
                .to_owned()
        }
        ScaleSource::Given(name) => format!(
            "GIVEN ({name} noise through the nominal model; k counts fitted parameters only)"
        ),
    };
    let mut s = format!(
        "\n{indent}Model comparison: -2 ln L of the errors, AIC = -2 ln L + 2k, BIC = -2 ln L + \
         k ln N (N = {}),\n",
        first.n_residuals
    );
    s.push_str(&crate::report::wrap::wrap(
        &format!("{indent}noise scales {how}:"),
        99,
        2,
    ));
    let mut t = TextTable::new(["model", "k", "-2 ln L", "AIC", "BIC"]);
    for (name, l) in rows {
        t.row([
            (*name).to_owned(),
            l.k.to_string(),
            format!("{:.2}", l.minus_2_ln_l),
            format!("{:.2}", l.aic()),
            format!("{:.2}", l.bic()),
        ]);
    }
    for line in t.render().lines() {
        s.push_str(&format!("{indent}{line}\n"));
    }
    if first.source == ScaleSource::Profiled {
        // The first and the last model's (every model's in a two-row table).
        let ends = [rows.first(), rows.get(1).and(rows.last())];
        for (name, l) in ends.into_iter().flatten() {
            s.push_str(&scales_text(
                &format!("scales ({name}):"),
                indent,
                &l.scales,
            ));
        }
    } else {
        let head = "scales (given; root mean of each shot's expected variance):";
        s.push_str(&scales_text(head, indent, &first.scales));
    }
    s
}
