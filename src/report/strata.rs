//! Diagnose's strata table: every selected value refitted on independent parts of the shots, and
//! which would-be findings are provisional because the parts disagree
//! ([`crate::diagnose::strata`]).

use crate::diagnose::strata::StrataCheck;
use crate::diagnose::Diagnosis;
use crate::report::TextTable;

/// A value in 4 significant figures (scientific when small), with its standard error.
pub(crate) fn value_text(v: Option<(f64, f64)>) -> String {
    let num = |x: f64| {
        if x != 0.0 && x.abs() < 1e-3 {
            format!("{x:.2e}")
        } else {
            format!("{x:.4}")
        }
    };
    v.map_or("n/a".into(), |(v, se)| format!("{} ± {}", num(v), num(se)))
}

/// The strata table (one block of rows per family, its p-values last) and the provisional
/// values with the check each failed; empty when nothing was checked. The parameters' columns
/// are split into tables of at most [`crate::report::text::WIDTH`] columns (family, stratum and
/// n repeated in each) unless `wide`, which prints one table as wide as it needs.
pub fn text(d: &Diagnosis, wide: bool) -> String {
    let Some(c) = &d.strata else {
        return String::new();
    };
    let mut s = format!(
        "\nStability across strata (the final model refitted on each part of the shots; a \
         value whose\nparts disagree, p < {:.1e} = {} / checks made, is provisional, not a \
         finding):\n",
        c.alpha_each,
        crate::diagnose::strata::STRATA_ALPHA
    );
    let fits = |t: &String| {
        t.lines()
            .all(|l| l.chars().count() <= crate::report::text::WIDTH)
    };
    // Blocks of parameters whose tables fit (at least one parameter each).
    let mut blocks: Vec<Vec<usize>> = Vec::new();
    for j in 0..c.params.len() {
        match blocks.last_mut() {
            Some(b) if wide || fits(&table(c, &[b.as_slice(), &[j]].concat())) => b.push(j),
            _ => blocks.push(vec![j]),
        }
    }
    let tables: Vec<String> = blocks.iter().map(|b| table(c, b)).collect();
    s.push_str(&tables.join("\n"));
    for p in &d.estimates {
        if let Some(why) = d.provisional(p) {
            let line = format!("  provisional, not a finding: {why}");
            s.push_str(&crate::report::wrap::wrap(&line, 99, 2));
        }
    }
    s
}

/// The strata table of the parameters `cols` (indices into the check's parameters).
fn table(c: &StrataCheck, cols: &[usize]) -> String {
    let mut header = vec!["family".to_owned(), "stratum".into(), "n".into()];
    header.extend(cols.iter().map(|&j| c.params[j].clone()));
    let mut t = TextTable::new(header);
    for f in &c.families {
        for (i, st) in f.strata.iter().enumerate() {
            let mut row = vec![
                if i == 0 {
                    f.name.clone()
                } else {
                    String::new()
                },
                st.label.clone(),
                st.n.to_string(),
            ];
            row.extend(cols.iter().map(|&j| value_text(st.values[j])));
            t.row(row);
        }
        if f.checks.iter().all(Option::is_none) {
            continue;
        }
        let mut row = vec![String::new(), "p (one value?)".into(), String::new()];
        row.extend(cols.iter().map(|&j| {
            f.checks[j].as_ref().map_or("-".into(), |k| {
                let p = if k.p_value < 1e-15 {
                    "< 1e-15".to_owned()
                } else {
                    format!("{:.2e}", k.p_value)
                };
                format!("{p}{}", if k.stable { "" } else { " DIFFERS" })
            })
        }));
        t.row(row);
    }
    t.render()
}
