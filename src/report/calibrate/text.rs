//! The text report of `smash calibrate`: the measurement model, the parameter table, the
//! correlations, what the values mean, the fit's statistics, the shaft relation and the errors
//! before and after, in [`crate::report::text::WIDTH`] columns (`--wide`: the tables side by side).

use super::CalibrateReport;
use crate::diagnose::honest;
use crate::fit::Calibration;
use crate::report::TextTable;
use crate::stats::t_statistic;

/// The "Measurement model:" line: what the fit took as noisy, and how much.
pub fn measurement_line(cal: &Calibration) -> String {
    let mut parts = Vec::new();
    if let Some(n) = cal.impact_noise {
        parts.push(format!(
            "impact locations with 1σ noise {} mm (vertical), {} mm (heel-toe)",
            crate::report::location_mm(n.sigma_y_m),
            crate::report::location_mm(n.sigma_z_m)
        ));
    }
    if let Some(n) = &cal.delivery_noise {
        parts.push(format!(
            "delivery with 1σ noise {} (model at the expected true delivery)",
            crate::report::delivery_noise::describe(n)
        ));
    }
    if parts.is_empty() {
        "Measurement model: delivery and impact locations as measured (exact)\n".into()
    } else {
        format!("Measurement model: {}\n", parts.join("; "))
    }
}

/// The human-readable report of `r`: the parameter table, correlations, warnings (stand-ins,
/// aliases, unidentifiable parameters), the fit's statistics, the shaft relation and the error
/// tables; `wide`: the tables side by side. Headed by a NO FINDINGS line when the shots are
/// another club's.
pub fn render(r: &CalibrateReport, wide: bool) -> String {
    let mut s = match &r.club_mismatch {
        Some(why) => crate::report::text::wrap_long(&format!(
            "NO FINDINGS: the shots do not match the club ({why}); the fitted values describe \
             another club's shots, not this head\n"
        )),
        None => String::new(),
    };
    s.push_str(&body(&r.calibration, r.n_shots, wide));
    s
}

fn body(cal: &Calibration, n_shots: usize, wide: bool) -> String {
    let labels: Vec<String> = cal.params.iter().map(|p| p.label()).collect();
    let unidentified = cal.identifiability.unidentified();
    let mut s = format!(
        "Calibration ({}) of {} parameter(s) on {} shots\n\n",
        cal.method.name(),
        cal.params.len(),
        n_shots
    );
    s.push_str(&crate::report::text::wrap_long(&measurement_line(cal)));
    s.push('\n');
    s.push_str(&parameter_table(cal, &labels, &unidentified));
    s.push_str(&correlation_table(cal, &labels));
    s.push_str(&crate::report::text::wrap_long(&warnings(
        cal,
        &labels,
        &unidentified,
    )));
    s.push_str(&fit_statistics(cal, &labels));
    s.push_str(&shaft_relation_text(cal));
    s.push_str("\nErrors (model − measured), per group:\n");
    s.push_str(&crate::report::text::before_after(
        &cal.before,
        &cal.after,
        ("before (nominal)", "after (calibrated)"),
        wide,
    ));
    s
}

/// One row per parameter: value, standard error, t, unit, plausible range and notes (at a
/// bound, not identifiable, implausible).
fn parameter_table(cal: &Calibration, labels: &[String], unidentified: &[usize]) -> String {
    let mut t = TextTable::new([
        "parameter",
        "value",
        "± stderr",
        "t",
        "unit",
        "plausible",
        "note",
    ]);
    for (j, p) in cal.params.iter().enumerate() {
        let mut note = Vec::new();
        if p.at_bound {
            note.push("at bound");
        }
        if unidentified.contains(&j) {
            note.push("not identifiable");
        }
        if honest::implausible_within_noise(p) {
            note.push("outside the plausible range by less than 2 SE");
        } else if honest::is_plausible(p) == Some(false) {
            note.push("IMPLAUSIBLE: a stand-in, not a finding");
        }
        t.row([
            labels[j].clone(),
            format!("{:.5}", p.value),
            p.stderr
                .filter(|e| e.is_finite())
                .map_or("n/a".into(), |e| format!("{e:.5}")),
            p.stderr
                .map(|e| t_statistic(p.value, e))
                .filter(|t| t.is_finite())
                .map_or("n/a".into(), |t| format!("{t:.1}")),
            p.unit.to_owned(),
            honest::plausible_range_text(p),
            note.join(", "),
        ]);
    }
    t.render()
}

/// The correlation matrix of the estimates, when more than one parameter was fitted.
fn correlation_table(cal: &Calibration, labels: &[String]) -> String {
    let Some(c) = cal.correlation.as_ref().filter(|c| c.nrows() > 1) else {
        return String::new();
    };
    let mut s = String::from("\nCorrelation of the estimates:\n");
    let mut header = vec![String::new()];
    header.extend((0..c.ncols()).map(|j| format!("[{j}]")));
    let mut t = TextTable::new(header);
    for i in 0..c.nrows() {
        let mut row = vec![format!("[{i}] {}", labels[i])];
        row.extend((0..c.ncols()).map(|j| format!("{:+.3}", c[(i, j)])));
        t.row(row);
    }
    s.push_str(&t.render());
    s
}

/// Warnings about what the estimates mean: stand-ins outside their plausible range, aliased
/// parameters, parameters these shots cannot identify.
fn warnings(cal: &Calibration, labels: &[String], unidentified: &[usize]) -> String {
    let mut s = String::new();
    for p in &cal.params {
        if let (true, Some(se)) = (honest::implausible_within_noise(p), p.stderr) {
            s.push_str(&format!(
                "  within noise of its plausible range: {} = {:.4} ± {se:.4} {} is outside {} by \
                 less than 2 SE, so the fit does not tell it from a plausible value (no reading \
                 as a stand-in)\n",
                p.label(),
                p.value,
                p.unit,
                honest::plausible_range_text(p)
            ));
            continue;
        }
        if let Some(w) = honest::stand_in(p) {
            s.push_str(&format!(
                "  stand-in, not a finding: {} = {:.4} {} is outside its plausible range {}; it \
                 behaves like {w}\n",
                p.label(),
                p.value,
                p.unit,
                honest::plausible_range_text(p)
            ));
        }
    }
    for a in honest::aliases(&cal.params, cal.correlation.as_ref()) {
        s.push_str(&format!("  alias: {}\n", a.text()));
    }
    if !unidentified.is_empty() {
        s.push_str(&format!(
            "  not identifiable from these shots: {}\n",
            unidentified
                .iter()
                .map(|&j| labels[j].as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    s
}

/// The fit's statistics: the models' likelihood scores on one scale, the fit's own chi2 and
/// whitening scales, the solver's work and the paper's stage of each parameter.
fn fit_statistics(cal: &Calibration, labels: &[String]) -> String {
    let mut s = crate::report::likelihood::text(
        &[
            ("nominal", &cal.likelihood_nominal),
            ("calibrated", &cal.likelihood),
        ],
        "",
    );
    s.push_str(&format!(
        "chi2 = {:.2} over N = {} residuals, p = {}: reduced chi2 = {:.4} (whitened by this \
         fit's own\n  robust scales, for the standard errors: not comparable between fits)\n",
        cal.chi2,
        cal.n_residuals,
        cal.params.len(),
        cal.reduced_chi2,
    ));
    s.push_str(&crate::report::likelihood::scales_text(
        "whitening scales:",
        "",
        &cal.noise_scales,
    ));
    s.push_str(&format!(
        "solver: {} iteration(s), {} residual evaluations; {}\n",
        cal.iterations, cal.evaluations, cal.termination
    ));
    if !cal.paper_stages.is_empty() {
        s.push_str("paper stages (relative sensitivity velocity / spin):\n");
        for a in &cal.paper_stages {
            s.push_str(&format!(
                "  {:<28} {:.3e} / {:.3e} -> {}\n",
                labels[a.param],
                a.linear_sensitivity,
                a.angular_sensitivity,
                match a.stage {
                    crate::fit::Stage::Linear => "W = inf (velocity)",
                    crate::fit::Stage::Angular => "W = 0 (spin)",
                }
            ));
        }
    }
    s
}

/// Added mass against shaft mass per group with its fitted line (the paper's Figure 3), when
/// the calibration has one.
fn shaft_relation_text(cal: &Calibration) -> String {
    let Some(r) = &cal.shaft_relation else {
        return String::new();
    };
    let mut s = String::from("\nAdded mass against shaft mass (the paper's Figure 3):\n");
    for (g, m, dm, se) in &r.points {
        s.push_str(&format!(
            "  group {g}: shaft {m:.1} g, added mass {dm:.3} ± {} g\n",
            se.map_or("n/a".into(), |e| format!("{e:.3}"))
        ));
    }
    s.push_str(&format!(
        "  dm = {:.4} g/g × shaft mass {:+.3} g, r = {:.3} ({})\n",
        r.line.slope,
        r.line.intercept,
        r.line.r,
        crate::report::text::counted(r.line.n, "group")
    ));
    s
}
