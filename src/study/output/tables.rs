//! The small tables of a study's outputs: `variants.csv`, `sensitivity.csv` and the optimiser's
//! files, built in memory (a few rows per variant, variable or iteration).

use std::fmt::Write as _;

use crate::data::club_file::club_toml;

use super::super::design::DesignVar;
use super::super::metrics::metric_unit;
use super::super::optimise::OptimiseResult;
use super::super::sensitivity::Sensitivity;
use super::super::sweep::Prepared;
use super::{cell, Files};

/// `variants.csv`: per variant its id, design variables and summary metrics.
pub(super) fn variants_table(
    p: &Prepared,
    axes: &[DesignVar],
    names: &[String],
    metrics: &[Vec<f64>],
) -> String {
    let mut t = String::from("variant_id");
    for v in axes {
        let _ = write!(t, ",{}", v.key());
    }
    for n in names {
        let _ = write!(t, ",{n}");
    }
    t.push('\n');
    for (i, (d, m)) in p.variants.iter().zip(metrics).enumerate() {
        let _ = write!(t, "{i}");
        for v in axes {
            let _ = write!(t, ",{}", cell(d.get(*v)));
        }
        for x in m {
            let _ = write!(t, ",{}", cell(*x));
        }
        t.push('\n');
    }
    t
}

pub(super) fn sensitivity_table(sens: &[Sensitivity], names: &[String]) -> String {
    let mut t = String::from(
        "metric,variable,derivative,unit,step,reference_change,change_per_reference,rank\n",
    );
    for (mi, name) in names.iter().enumerate() {
        let mut rows: Vec<(&Sensitivity, f64)> = sens
            .iter()
            .map(|x| (x, x.metrics[mi] * x.var.reference_change()))
            .collect();
        // Largest |change| first; NaN last; ties keep variable order.
        rows.sort_by(|a, b| {
            let (x, y) = (a.1.abs(), b.1.abs());
            match (x.is_nan(), y.is_nan()) {
                (true, true) => std::cmp::Ordering::Equal,
                (true, false) => std::cmp::Ordering::Greater,
                (false, true) => std::cmp::Ordering::Less,
                _ => y.total_cmp(&x),
            }
        });
        for (rank, (x, change)) in rows.iter().enumerate() {
            let _ = writeln!(
                t,
                "{name},{},{},{} per {},{},{},{},{}",
                x.var.key(),
                cell(x.metrics[mi]),
                metric_unit(name),
                x.var.unit(),
                cell(x.step),
                cell(x.var.reference_change()),
                cell(*change),
                rank + 1
            );
        }
    }
    t
}

pub(super) fn optimise_files(p: &Prepared, o: &OptimiseResult, names: &[String]) -> Files {
    let s = &p.study;
    let spec = s.optimise.as_ref().expect("optimise result without spec");
    let mut files = Files::new();
    let mut t = String::from("iteration,objective");
    for (v, _, _) in &spec.bounds {
        let _ = write!(t, ",{}", v.key());
    }
    t.push('\n');
    for pt in &o.path {
        let _ = write!(t, "{},{}", pt.iteration, cell(pt.objective));
        for (v, _, _) in &spec.bounds {
            let _ = write!(t, ",{}", cell(pt.design.get(*v)));
        }
        t.push('\n');
    }
    files.push(("optimise/path.csv".into(), t.into_bytes()));

    let base = s.club.nominal.clone();
    let best = o
        .best
        .apply(&s.club.nominal, s.design.discretionary_mass.as_ref())
        .expect("the optimum was evaluated");
    let mut t = String::from("quantity,unit,base,optimum,change\n");
    let mut row = |q: &str, unit: &str, a: f64, b: f64| {
        let _ = writeln!(t, "{q},{unit},{},{},{}", cell(a), cell(b), cell(b - a));
    };
    row("objective", "", o.base_objective, o.best_objective);
    for (v, _, _) in &spec.bounds {
        row(v.key(), v.unit(), v.neutral(), o.best.get(*v));
    }
    row(
        "club_mass_g",
        "g",
        base.club_mass_kg * 1e3,
        best.club_mass_kg * 1e3,
    );
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        row(
            &format!("com_{axis}_mm"),
            "mm",
            base.club_com_m[k] * 1e3,
            best.club_com_m[k] * 1e3,
        );
    }
    for (k, axis) in ["xx", "yy", "zz"].iter().enumerate() {
        row(
            &format!("i{axis}_gcm2"),
            "gcm2",
            base.club_inertia_kgm2[(k, k)] * 1e7,
            best.club_inertia_kgm2[(k, k)] * 1e7,
        );
    }
    for (i, n) in names.iter().enumerate() {
        row(n, &metric_unit(n), o.base_metrics[i], o.best_metrics[i]);
    }
    files.push(("optimise/result.csv".into(), t.into_bytes()));

    let mut club = s.club.clone();
    club.nominal = best;
    club.name = format!("{} (optimised by study {})", s.club.name, s.name);
    let comment = format!(
        "Optimum of study '{}': {}\nobjective {} -> {} ({} iterations' path in path.csv)",
        s.name,
        o.best.describe(),
        cell(o.base_objective),
        cell(o.best_objective),
        o.path.len()
    );
    files.push((
        "optimise/optimum_club.toml".into(),
        club_toml(&club, &comment).into_bytes(),
    ));
    files
}
