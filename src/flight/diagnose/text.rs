//! The text form of a flight diagnosis (every line under 100 columns).

use std::fmt::Write as _;

use super::{FlightDiagnosis, Value};
use crate::flight::calibrate::uncertainty_text;

/// A value as the report prints it: `drag x1.0612 ± 0.0041`, `drag_crisis ΔCd +0.0120 ±
/// 0.0040`, `spin_decay x3.0000 (at its upper bound)`.
pub fn value_text(v: &Value) -> String {
    let u = uncertainty_text(v.se, v.at_bound);
    if v.name == "drag_crisis" {
        format!("{} ΔCd {:+.4} {u}", v.name, v.value)
    } else {
        format!("{} x{:.4} {u}", v.name, v.value)
    }
}

/// Values joined by `, `, wrapped so that no line (after `indent`) passes 99 columns.
fn wrapped(values: &[String], first: usize, indent: usize) -> String {
    let mut out = String::new();
    let mut col = first;
    for (i, v) in values.iter().enumerate() {
        let sep = if i == 0 { "" } else { ", " };
        if i > 0 && col + sep.len() + v.chars().count() > 99 {
            out.push_str(",\n");
            out.push_str(&" ".repeat(indent));
            col = indent;
        } else {
            out.push_str(sep);
            col += sep.len();
        }
        out.push_str(v);
        col += v.chars().count();
    }
    out
}

pub(super) fn render(d: &FlightDiagnosis) -> String {
    let mut s = String::new();
    let balls = if d.balls.is_empty() {
        String::new()
    } else {
        format!(", {} ball types", d.balls.len())
    };
    let _ = writeln!(
        s,
        "flight diagnose: {} shots, model {}, folds by {} ({}){balls}",
        d.shots, d.model, d.folds_by, d.folds
    );
    for (i, st) in d.steps.iter().enumerate() {
        let _ = writeln!(
            s,
            "step {}: noise carry {:.2} yd, apex {:.2} yd, land {:.2} deg; base CV chi2 {:.1}",
            i + 1,
            st.sigma[0],
            st.sigma[1],
            st.sigma[2],
            st.base_cv_chi2
        );
        let _ = writeln!(
            s,
            "  {:<12} {:>2} {:>9} {:>8} {:>9}  fitted on all shots",
            "term", "k", "CV gain", "penalty", "margin"
        );
        for c in &st.candidates {
            let head = match &c.failure {
                Some(_) => format!(
                    "  {:<12} {:>2} {:>9} {:>8.1} {:>9}",
                    c.term, c.n_params, "-", c.penalty, "-"
                ),
                None => format!(
                    "  {:<12} {:>2} {:>9.1} {:>8.1} {:>+9.1}",
                    c.term,
                    c.n_params,
                    c.gain,
                    c.penalty,
                    c.margin()
                ),
            };
            let own: Vec<String> = match &c.failure {
                Some(e) => vec![format!("not fitted: {e}")],
                None => {
                    let mut v: Vec<String> = c.values
                        [c.values.len() - c.n_params.min(c.values.len())..]
                        .iter()
                        .map(value_text)
                        .collect();
                    if !c.identified && !v.iter().any(|t| t.ends_with("(not determined)")) {
                        v.push("not determined".into());
                    }
                    v
                }
            };
            let first = head.chars().count() + 2;
            let _ = writeln!(s, "{head}  {}", wrapped(&own, first, 8));
        }
        let _ = match st.selected {
            Some(t) => writeln!(s, "  -> {t} selected"),
            None => writeln!(
                s,
                "  -> no term gains more than its penalty: selection stops"
            ),
        };
    }
    if d.selected.is_empty() {
        let _ = writeln!(
            s,
            "selected: none (the model as given is not beaten out of sample)"
        );
    } else {
        let v: Vec<String> = d.values.iter().map(value_text).collect();
        let _ = writeln!(s, "selected: {}", wrapped(&v, 10, 10));
    }
    let (b, a) = (d.rmse_before, d.rmse_after);
    // A quantity the file does not measure has no RMSE: `-`, never NaN.
    let f = |x: f64| {
        if x.is_finite() {
            format!("{x:.2}")
        } else {
            "-".to_string()
        }
    };
    let _ = writeln!(
        s,
        "RMSE on all shots: carry {} -> {} yd, apex {} -> {} yd, land {} -> {} deg",
        f(b[0]),
        f(a[0]),
        f(b[1]),
        f(a[1]),
        f(b[2]),
        f(a[2])
    );
    s
}
