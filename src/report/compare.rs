//! Rendering of a comparison: the printed diagnosis, and the files (CSV tables, face SVGs, JSON).
//! Builds text and bytes only.

use std::fmt::Write as _;

use crate::compare::{sig3, CompareReport};
use crate::data::fmt_f64;
use crate::physics::LaunchComponent;
use crate::report::heatmap::{heatmap_svg, Heatmap, Scale};
use crate::report::wrap::wrap;

fn opt(v: Option<f64>) -> String {
    v.map(fmt_f64).unwrap_or_default()
}

fn cell(v: Option<f64>) -> String {
    v.map(sig3).unwrap_or_else(|| "–".into())
}

/// The widest line of [`compare_text`]'s default layout, in columns.
pub const TEXT_WIDTH: usize = 100;

/// Table 2 (mean and STD per group and component, `*` where the mean differs from 0) for the
/// groups `groups` (indices into `r.table2`, whose last is all shots), with `t(all)` after the
/// last group.
fn table2_block(r: &CompareReport, groups: &[usize]) -> String {
    let mut s = String::new();
    let last = r.table2.len() - 1;
    let _ = write!(s, "{:<14}{:<5}", "Component", "unit");
    for &g in groups {
        let w = mean_width(&r.table2[g].group);
        let _ = write!(
            s,
            "{:>w$}{:>8}",
            format!("{} mean", r.table2[g].group),
            "STD"
        );
    }
    if groups.contains(&last) {
        let _ = write!(s, "{:>9}", "t(all)");
    }
    let _ = writeln!(s);
    for c in LaunchComponent::ALL {
        let _ = write!(s, "{:<14}{:<5}", c.label(), c.unit());
        for &g in groups {
            let e = &r.table2[g].components[c.index()];
            let mark = if e.significant { "*" } else { " " };
            let w = mean_width(&r.table2[g].group) - 1;
            let _ = write!(
                s,
                "{:>w$}{mark}{:>8}",
                cell(e.summary.mean),
                cell(e.summary.std)
            );
        }
        if groups.contains(&last) {
            let all = &r.table2[last].components[c.index()];
            let t = all.summary.t.map(|t| format!("{t:.1}")).unwrap_or_default();
            let _ = write!(s, "{t:>9}");
        }
        let _ = writeln!(s);
    }
    s
}

/// The width of a group's mean column: 10, or its heading (`NAME mean`) and a space before it
/// when that is wider, so that a long group name does not run into the column before.
fn mean_width(group: &str) -> usize {
    (group.chars().count() + " mean".len() + 1).max(10)
}

/// The groups of Table 2 in blocks that fit [`TEXT_WIDTH`] (one block when `wide`): as many
/// groups a block as their columns allow, at least one.
fn table2_blocks(r: &CompareReport, wide: bool) -> Vec<Vec<usize>> {
    let n = r.table2.len();
    if wide {
        return vec![(0..n).collect()];
    }
    // Component and unit, each group's mean and STD, `t(all)` with the last block.
    let mut blocks: Vec<Vec<usize>> = Vec::new();
    let mut width = 0;
    for g in 0..n {
        let w = mean_width(&r.table2[g].group) + 8 + if g + 1 == n { 9 } else { 0 };
        match blocks.last_mut() {
            Some(b) if width + w <= TEXT_WIDTH => b.push(g),
            _ => {
                blocks.push(vec![g]);
                width = 19;
            }
        }
        width += w;
    }
    blocks
}

/// The printed diagnosis: Table 2 layout (in blocks of groups that fit [`TEXT_WIDTH`] unless
/// `wide`), ranked findings with hints (wrapped), and the flag count.
pub fn compare_text(r: &CompareReport, title: &str, wide: bool) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "{title}");
    let _ = writeln!(
        s,
        "{} shots; errors are model − measured (the paper's Table 2 layout). * = mean ≠ 0 at {}%",
        r.n_shots,
        r.alpha * 100.0
    );
    for block in table2_blocks(r, wide) {
        let _ = writeln!(s);
        s.push_str(&table2_block(r, &block));
    }
    let _ = writeln!(s);
    if r.findings.is_empty() {
        let _ = writeln!(
            s,
            "Findings: none. No bias or strong trend is significant at {}%.",
            r.alpha * 100.0
        );
    } else {
        let _ = writeln!(s, "Findings, strongest first:");
        for (i, f) in r.findings.iter().enumerate() {
            // Continuation lines start under the finding's text, in column 4.
            let line = format!("{:>2}. {}", i + 1, f.text);
            let lead = line.len() - line.trim_start().len();
            s.push_str(&wrap(&line, TEXT_WIDTH, 4 - lead));
            if f.hints.is_empty() {
                let _ = writeln!(s, "    no library effect has this signature");
            } else {
                let hints = format!("    try: {}", f.hints.join("; "));
                s.push_str(&wrap(&hints, TEXT_WIDTH, 5));
            }
        }
    }
    let _ = writeln!(
        s,
        "\n{} of {} tests flagged at {}% ({:.1} expected by chance if the model were right).",
        r.flags,
        r.tests,
        r.alpha * 100.0,
        r.expected_false_flags
    );
    s
}

/// `table2.csv`: group, component, unit, n, mean, std, sem, t, p, significant.
pub fn table2_csv(r: &CompareReport) -> Vec<u8> {
    let mut s = String::from("group,component,unit,n,mean,std,sem,t,p,significant\n");
    for b in &r.table2 {
        for e in &b.components {
            let m = &e.summary;
            let _ = writeln!(
                s,
                "{},{},{},{},{},{},{},{},{},{}",
                csv_cell(&b.group),
                e.component,
                e.unit,
                m.n,
                opt(m.mean),
                opt(m.std),
                opt(m.sem),
                opt(m.t),
                opt(m.p),
                e.significant
            );
        }
    }
    s.into_bytes()
}

/// A text cell (a group name) for a CSV row: quoted, its quotes doubled, when it holds a comma,
/// a quote, a line break, or spaces at either end (which a reader that trims cells would lose).
fn csv_cell(text: &str) -> std::borrow::Cow<'_, str> {
    let needs = text.contains([',', '"', '\n', '\r']) || text.trim() != text;
    if needs {
        format!("\"{}\"", text.replace('"', "\"\"")).into()
    } else {
        text.into()
    }
}

/// `face_residuals.csv`, long form: one row per non-empty face bin and component;
/// `mean` and `std` empty for bins with fewer than `min_count` shots.
pub fn face_csv(r: &CompareReport) -> Vec<u8> {
    let mut s = String::from("y_mm,z_mm,component,unit,count,mean,std\n");
    for b in r.face.bins.iter().filter(|b| b.count > 0) {
        for c in LaunchComponent::ALL {
            let _ = writeln!(
                s,
                "{},{},{},{},{},{},{}",
                fmt_f64(b.y_mm),
                fmt_f64(b.z_mm),
                c.column(),
                c.unit(),
                b.count,
                opt(b.mean[c.index()]),
                opt(b.std[c.index()])
            );
        }
    }
    s.into_bytes()
}

/// Face picture of the mean error of one component (diverging scale, centre marked).
pub fn face_svg(r: &CompareReport, c: LaunchComponent) -> Vec<u8> {
    let title = format!(
        "{} error (model − measured), mean per {} mm bin, ≥ {} shots",
        c.label(),
        r.face.bin_mm,
        r.face.min_count
    );
    let value_label = format!("{} error, {}", c.label().to_lowercase(), c.unit());
    let values = r.face.grid(c);
    heatmap_svg(&Heatmap {
        title: &title,
        x_label: "impact z (toward toe), mm",
        y_label: "impact y (up), mm",
        value_label: &value_label,
        xs: &r.face.zs_mm,
        ys: &r.face.ys_mm,
        values: &values,
        marker: Some((0.0, 0.0)),
        scale: Scale::Diverging,
    })
    .into_bytes()
}

/// `residuals_by_<variable>.csv`: quantile bins with the mean error per component.
pub fn binned_csv(r: &CompareReport, index: usize) -> Vec<u8> {
    let t = &r.binned[index];
    let mut s = format!("{0}_lo,{0}_hi,count", t.variable);
    for c in LaunchComponent::ALL {
        let _ = write!(s, ",mean_err_{}", c.column());
    }
    s.push('\n');
    for row in &t.rows {
        let _ = write!(s, "{},{},{}", fmt_f64(row.lo), fmt_f64(row.hi), row.count);
        for m in &row.mean {
            let _ = write!(s, ",{}", opt(*m));
        }
        s.push('\n');
    }
    s.into_bytes()
}

/// `correlations.csv`: component, variable, n, r, t, p, significant, strong.
pub fn correlations_csv(r: &CompareReport) -> Vec<u8> {
    let mut s = String::from("component,variable,n,r,t,p,significant,strong\n");
    for k in &r.correlations {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{}",
            k.component,
            k.variable,
            k.n,
            fmt_f64(k.r),
            fmt_f64(k.t),
            fmt_f64(k.p),
            k.significant,
            k.strong
        );
    }
    s.into_bytes()
}

/// The version of compare's JSON schema (`schema_version`); raised when a key changes meaning
/// or goes away (a new key does not raise it).
pub const SCHEMA_VERSION: u32 = 1;

/// The report as JSON: its own fields after `schema_version` and `command`.
#[derive(serde::Serialize)]
pub struct Versioned<'a> {
    schema_version: u32,
    command: &'static str,
    #[serde(flatten)]
    report: &'a CompareReport,
}

/// The text report, headed by `NO FINDINGS` when the shots do not match the club; `wide`:
/// Table 2 in one block however many groups.
pub fn report_text(report: &CompareReport, title: &str, wide: bool) -> String {
    use crate::report::text::wrap_long;
    let title = wrap_long(title);
    let text = compare_text(report, title.trim_end(), wide);
    match &report.club_mismatch {
        Some(why) => {
            wrap_long(&format!(
                "NO FINDINGS: the shots do not match the club ({why}); the tables below \
                 describe errors of another club's shots, not of this head\n"
            )) + &text
        }
        None => text,
    }
}

/// The serde form of `r` that its JSON prints (the schema: `docs/json.md`).
pub fn versioned(r: &CompareReport) -> Versioned<'_> {
    Versioned {
        schema_version: SCHEMA_VERSION,
        command: "compare",
        report: r,
    }
}

/// The whole report as one JSON object (the schema: `docs/json.md`).
pub fn compare_json(r: &CompareReport) -> String {
    serde_json::to_string_pretty(&versioned(r)).expect("report serializes")
}

/// Every output file of a comparison: (file name, bytes).
pub fn compare_files(r: &CompareReport, text: &str) -> Vec<(String, Vec<u8>)> {
    let mut files = vec![
        ("table2.csv".to_string(), table2_csv(r)),
        ("face_residuals.csv".to_string(), face_csv(r)),
        ("correlations.csv".to_string(), correlations_csv(r)),
        ("compare.json".to_string(), compare_json(r).into_bytes()),
        ("findings.txt".to_string(), text.as_bytes().to_vec()),
    ];
    for (i, t) in r.binned.iter().enumerate() {
        files.push((format!("residuals_by_{}.csv", t.variable), binned_csv(r, i)));
    }
    for c in LaunchComponent::ALL {
        files.push((format!("face_{}.svg", c.column()), face_svg(r, c)));
    }
    files
}
