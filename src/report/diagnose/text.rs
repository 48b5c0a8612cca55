//! The text report of `smash diagnose`: its steps' candidate tables, the selection, the
//! strata, the model comparison, the noise floor and the errors before and after, in
//! [`crate::report::text::WIDTH`] columns (`--wide`: the full candidate and noise-floor tables).

use super::{calibrate_flag_pairs, conclusion, DiagnoseReport};
use crate::diagnose::honest;
use crate::diagnose::noise_floor::NoiseFloor;
use crate::diagnose::{Diagnosis, Step};
use crate::fit::ParamEstimate;
use crate::physics::LaunchComponent;
use crate::report::location_mm;
use crate::report::text::{shell_command, shell_word, wrap_long};
use crate::report::{error_table_text, TextTable};

/// How the text report is laid out, and the command that runs `smash calibrate` on the same
/// club and shots.
#[derive(Debug, Clone, Default)]
pub struct Layout {
    /// The full tables (`--wide`).
    pub wide: bool,
    /// `smash calibrate --club … --shots …` with the shots' format flags, as shell words; the
    /// model's flags follow it.
    pub calibrate: Vec<String>,
}

fn fmt_params(ps: &[ParamEstimate]) -> String {
    ps.iter()
        .map(|p| {
            let name = match &p.group {
                Some(g) => format!("{}@{g}", p.param),
                None => p.param.to_owned(),
            };
            // Small values (COR falloff per mm², say) in scientific notation.
            let num = |x: f64| {
                if x != 0.0 && x.abs() < 1e-3 {
                    format!("{x:.3e}")
                } else {
                    format!("{x:.4}")
                }
            };
            match p.stderr {
                Some(se) => format!("{name} = {} ± {}{}", num(p.value), num(se), honest::mark(p)),
                None => format!("{name} = {}{}", num(p.value), honest::mark(p)),
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The human-readable report of `r`.
pub fn render(r: &DiagnoseReport, layout: &Layout) -> String {
    let (d, floor) = (&r.diagnosis, &r.floor);
    let mut s = format!(
        "Diagnosis of {} shots: {}-fold cross-validation by {}, penalty ln(n) = {:.2} per parameter \
         (+ 2·ln m for a physical effect picked from m candidates)\n",
        d.n_shots,
        d.folds,
        d.fold_by.name(),
        (d.n_shots as f64).ln()
    );
    if let Some(why) = &d.club_mismatch {
        s = format!(
            "NO FINDINGS: the shots do not match the club ({why}); what is selected below \
             describes another club's shots, not this head\n{s}"
        );
    }
    if !layout.wide {
        s.push_str(
            "Candidates: gain (cross-validated) − penalty = margin; speed … side: change of each \
             launch component's RMS error, %; their parameters with --wide\n",
        );
    }
    let mut s = wrap_long(&s);
    for (i, st) in d.steps.iter().enumerate() {
        s.push_str(&step_text(i, st, layout.wide));
    }
    s.push_str(&wrap_long(&summary_text(d)));
    s.push_str(&next_command(d, layout));
    s.push_str(&crate::report::strata::text(d, layout.wide));
    s.push_str(&likelihood_text(d));
    s.push_str(&floor_text(d, floor, layout.wide));
    s.push('\n');
    s.push_str(&crate::report::text::before_after(
        &d.before,
        &d.after,
        ("before (club as given)", "after (selected effects)"),
        layout.wide,
    ));
    s
}

fn short_name(c: &LaunchComponent) -> &'static str {
    match c {
        LaunchComponent::BallSpeed => "speed",
        LaunchComponent::LaunchAngle => "launch",
        LaunchComponent::Azimuth => "azim",
        LaunchComponent::Backspin => "back",
        LaunchComponent::Sidespin => "side",
    }
}

/// The notes on candidate `c` of step `st`: short tags for the narrow table and the full notes.
fn candidate_notes(
    st: &Step,
    c: &crate::diagnose::CandidateResult,
) -> (Vec<&'static str>, Vec<String>) {
    let (mut tags, mut notes) = (Vec::new(), Vec::new());
    if c.spread_gain.is_some() {
        tags.push("spread");
        notes.push("gain: −2 ln L of the spread".to_owned());
    }
    if let Some(f) = &c.failure {
        tags.push("see below");
        notes.push(format!("failed: {f}"));
    } else if !c.converged {
        tags.push("see below");
        notes.push("fit did not converge".to_owned());
    }
    if !c.unidentified.is_empty() {
        if !tags.contains(&"see below") {
            tags.push("see below");
        }
        notes.push(format!("not identifiable: {}", c.unidentified.join(", ")));
    }
    if st.selected.as_deref() == Some(c.label.as_str()) {
        tags.push("SELECTED");
        notes.push("SELECTED".to_owned());
    } else if st.rivals.iter().any(|r| r.label == c.label) {
        tags.push("rival");
        notes.push("rival of the selected".to_owned());
    }
    (tags, notes)
}

/// The candidate table of one step: wide, every column with the parameters and full notes;
/// narrow, the scores and the RMS changes with short notes, the long notes under the table.
fn candidates_table(st: &Step, wide: bool) -> String {
    let mut header: Vec<String> = if wide {
        ["candidate", "k", "CV gain", "penalty", "margin"]
            .map(String::from)
            .to_vec()
    } else {
        ["candidate", "k", "gain", "penalty", "margin"]
            .map(String::from)
            .to_vec()
    };
    header.extend(LaunchComponent::ALL.iter().map(|c| match wide {
        true => format!("Δrms {}", short_name(c)),
        false => short_name(c).to_owned(),
    }));
    if wide {
        header.push("parameters".to_owned());
    }
    header.push("note".to_owned());
    let mut t = TextTable::new(header);
    let mut below = String::new();
    for c in &st.candidates {
        // A candidate whose fit failed has no gain (NaN in the report's types): a dash, never
        // `NaN`, and no change of the errors.
        let failed = !c.gain.is_finite();
        let one = |v: f64| {
            if v.is_finite() {
                format!("{v:.1}")
            } else {
                "—".to_owned()
            }
        };
        let mut row = vec![
            c.label.clone(),
            c.n_params.to_string(),
            one(c.gain),
            one(c.penalty),
            one(c.margin()),
        ];
        let pct = if wide { "%" } else { "" };
        row.extend(c.rms_reduction.iter().map(|r| match failed {
            true => "—".to_owned(),
            false => format!("{:+.1}{pct}", -100.0 * r),
        }));
        let (tags, notes) = candidate_notes(st, c);
        if wide {
            row.push(fmt_params(&c.params));
            row.push(notes.join("; "));
        } else {
            if tags.contains(&"see below") {
                let detail: Vec<&str> = notes
                    .iter()
                    .map(String::as_str)
                    .filter(|n| *n != "SELECTED")
                    .collect();
                below.push_str(&format!("  {}: {}\n", c.label, detail.join("; ")));
            }
            row.push(tags.join(", "));
        }
        t.row(row);
    }
    if st.candidates.iter().any(|c| c.spread_gain.is_some()) && !wide {
        below.push_str("  spread: the gain is −2 ln L of the errors' spread, not CV chi2\n");
    }
    format!("{}{}", t.render(), wrap_long(&below))
}

/// One step: its base, candidates, choice and the errors after it.
fn step_text(i: usize, st: &Step, wide: bool) -> String {
    let mut s = String::new();
    // Prose is wrapped; the tables are laid out to fit.
    let mut say = |line: String| s.push_str(&wrap_long(&line));
    say(format!(
        "\nStep {}: base = {}; {}\n",
        i + 1,
        if st.base.is_empty() {
            "nominal".to_owned()
        } else {
            st.base.join(" + ")
        },
        st.base_cv_chi2
            .map_or("not scored (nothing to offer)".to_owned(), |c| {
                format!("CV chi2 of the base = {c:.1}")
            })
    ));
    if st.at_noise_floor {
        say(
            "  (errors at the instruments' noise floor: only measurement candidates offered)\n"
                .to_owned(),
        );
    }
    let mut s = s + &candidates_table(st, wide);
    let mut say = |line: String| s.push_str(&wrap_long(&line));
    if let Some(a) = &st.alias {
        say(format!("-> aliases: {}\n", a.text()));
    }
    if let Some(w) = &st.swap {
        say(format!(
            "-> step {}: {} (forward selection had stopped; errors after:)\n",
            i + 1,
            w.text()
        ));
        return s + &error_table_text(&st.after);
    }
    match &st.selected {
        Some(l) => {
            if !st.rivals.is_empty() {
                let names: Vec<&str> = st.rivals.iter().map(|r| r.label.as_str()).collect();
                say(format!(
                    "-> rivals of {l} (margin within {} and the same change to the predictions, \
                     r > 0.9): {}\n",
                    crate::diagnose::select::RIVAL_MARGIN,
                    names.join(", ")
                ));
            }
            say(format!(
                "-> add {l}; errors (model − measured) after this step:\n"
            ));
            s.push_str(&error_table_text(&st.after));
        }
        None if st.at_noise_floor && st.candidates.is_empty() => say(
            "-> the errors are at the instruments' noise floor: no physical effect offered; stop\n"
                .to_owned(),
        ),
        None => say("-> no candidate beats its penalty: stop\n".to_owned()),
    }
    s
}

/// The models of the steps that changed the model, with the nominal and the final model, on
/// the diagnosis's one likelihood scale.
fn likelihood_text(d: &Diagnosis) -> String {
    let mut rows: Vec<(String, &crate::fit::Likelihood)> = vec![("nominal".into(), &d.nominal_fit)];
    for (i, st) in d.steps.iter().enumerate() {
        let what = match (&st.selected, &st.swap) {
            (Some(l), _) => format!("+ {l}"),
            (None, Some(w)) => match &w.inn {
                Some(inn) => format!("{} -> {inn}", w.out),
                None => format!("- {}", w.out),
            },
            (None, None) => continue,
        };
        rows.push((format!("after step {}: {what}", i + 1), &st.fit));
    }
    rows.push(("final".into(), &d.final_fit));
    let rows: Vec<(&str, &crate::fit::Likelihood)> =
        rows.iter().map(|(n, l)| (n.as_str(), *l)).collect();
    crate::report::likelihood::text(&rows, "")
}

/// Selected effects, final values, findings, stand-ins, ambiguities, aliases and the
/// measurement model.
fn summary_text(d: &Diagnosis) -> String {
    let mut s = format!(
        "\nSelected (in order): {}\n",
        if d.selected.is_empty() {
            "none".to_owned()
        } else {
            d.selected.join(", ")
        }
    );
    if !d.estimates.is_empty() {
        s.push_str(&format!("Final values: {}\n", fmt_params(&d.estimates)));
        let findings: Vec<String> = d
            .estimates
            .iter()
            .filter(|p| d.is_finding(p))
            .map(|p| p.label())
            .collect();
        s.push_str(&format!(
            "Findings (values inside their plausible ranges, no plausible rival, not aliased with \
             another effect, the same in every stratum): {}\n",
            if findings.is_empty() {
                "none".to_owned()
            } else {
                findings.join(", ")
            }
        ));
        for p in d.estimates.iter().filter(|p| honest::is_absent(p)) {
            s.push_str(&wrap_long(&format!(
                "  absent, not a finding: {} = {:.4} {} sits on its no-effect bound (the fit \
                 found none of what it adds)\n",
                p.label(),
                p.value,
                p.unit
            )));
        }
        let n = d.estimates.len();
        for p in d.estimates.iter().filter(|p| honest::is_unchanged(p, n)) {
            s.push_str(&wrap_long(&format!(
                "  unchanged, not a finding: {} = {:.4} ± {:.4} {} does not differ from its \
                 no-effect value (p >= {} / {n} parameters)\n",
                p.label(),
                p.value,
                p.stderr.unwrap_or(0.0),
                p.unit,
                honest::UNCHANGED_ALPHA
            )));
        }
        for p in &d.estimates {
            if let Some(w) = honest::stand_in(p) {
                let alike: Vec<String> = d
                    .alike(p)
                    .iter()
                    .map(|(l, r)| format!("{l} (r = {r:.2})"))
                    .collect();
                let measured = if alike.is_empty() {
                    String::new()
                } else {
                    format!(
                        "; on these shots its change to the predictions was most like {}",
                        alike.join(", ")
                    )
                };
                s.push_str(&wrap_long(&format!(
                    "  stand-in, not a finding: {} = {:.4} {} is outside its plausible range {}; \
                     it behaves like {w}{measured}\n",
                    p.label(),
                    p.value,
                    p.unit,
                    honest::plausible_range_text(p)
                )));
            }
        }
    }
    for a in &d.ambiguities {
        s.push_str(&format!("  rivals: {}\n", a.text()));
    }
    for a in &d.aliases {
        s.push_str(&format!("  alias: {}\n", a.text()));
    }
    if let Some(u) = &d.unresolved {
        s.push_str(&wrap_long(&format!("  {}\n", u.text())));
    }
    s.push_str(&measurement_model_line(d));
    s
}

/// The `smash calibrate` command that fits the diagnosis's final model, on lines of its own
/// (none when nothing was selected and the measurements were taken as exact).
fn next_command(d: &Diagnosis, layout: &Layout) -> String {
    let flags = calibrate_flag_pairs(d);
    if flags.is_empty() {
        return String::new();
    }
    let mut words = layout.calibrate.clone();
    for (flag, value) in flags {
        words.extend([flag.to_owned(), shell_word(&value)]);
    }
    format!("Fit the same model with:\n{}", shell_command("  ", &words))
}

/// The measurement model's line, when it has noise: what was taken as noisy and how much.
fn measurement_model_line(d: &Diagnosis) -> String {
    let how = |estimated: bool| {
        if estimated {
            ", selected from the data"
        } else {
            ", as given"
        }
    };
    let mut parts = Vec::new();
    if let Some(n) = d.impact_noise {
        parts.push(format!(
            "impact locations with 1σ noise {} mm (vertical), {} mm (heel-toe){}",
            location_mm(n.sigma_y_m),
            location_mm(n.sigma_z_m),
            how(d.impact_noise_estimated)
        ));
    }
    if let Some(n) = d.delivery_noise.filter(|n| n.is_active()) {
        parts.push(format!(
            "delivery with 1σ noise {}{}",
            crate::report::delivery_noise::describe(&n),
            how(d.delivery_noise_estimated)
        ));
    }
    if parts.is_empty() {
        return String::new();
    }
    format!("Measurement model: {}\n", parts.join("; "))
}

/// The noise-floor table and the conclusion.
fn floor_text(d: &Diagnosis, floor: &NoiseFloor, wide: bool) -> String {
    let mut s = wrap_long(&format!(
        "\nNoise floor ({} instrument noise; spread of model − measured if the model were right):\n",
        floor.instrument.name
    ));
    if floor.assumed {
        s.push_str("(that noise is ASSUMED: no --noise or --instrument was given)\n");
    }
    let mut header = vec![
        "component",
        "mean",
        "mean/σ",
        "expected sd",
        "observed sd",
        "ratio",
        "p",
    ];
    if wide {
        header.push("verdict");
    }
    let mut t = TextTable::new(header);
    let mut verdicts = String::new();
    for c in &floor.components {
        if !wide {
            verdicts.push_str(&format!("  {}\n", c.verdict()));
        }
        let cells = [
            c.component.column().to_owned(),
            format!("{:+.3}", c.mean),
            format!("{:+.2}", c.mean_in_sd),
            format!("{:.3}", c.expected_sd),
            format!("{:.3}", c.observed_sd),
            format!("{:.2}", c.ratio),
            format!("{:.2e}", c.p_value),
            c.verdict(),
        ];
        t.row(cells.into_iter().take(if wide { 8 } else { 7 }));
    }
    s.push_str(&t.render());
    s.push_str(&wrap_long(&verdicts));
    for map in floor
        .components
        .iter()
        .filter_map(super::face_map::face_map_text)
    {
        s.push_str(&map);
    }
    s.push_str(&crate::report::wrap::wrap(
        &format!("Conclusion: {}", conclusion(d, floor)),
        99,
        2,
    ));
    s
}
