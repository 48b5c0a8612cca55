//! Study outputs as bytes: CSV tables, CSV matrices and SVG heatmaps. Nothing here writes files;
//! the CLI hands the list to [`crate::data::write_atomic`]. No NaN reaches a file: values that
//! cannot be computed are empty cells.
//!
//! | file | content |
//! |---|---|
//! | `study.toml` | the resolved study (every default filled in) |
//! | `variants.csv` | one row per variant: id, design variables, summary metrics |
//! | `maps_long.csv` | one row per variant × grid point: id, variables, `y_mm`, `z_mm`, `valid`, outputs |
//! | `maps/v<id>_<output>.csv` / `.svg` | matrix (rows top to bottom) and heatmap per variant and output |
//! | `sensitivity.csv` | d metric / d variable at the base design, ranked within each metric |
//! | `sensitivity/d_<output>__d_<variable>.csv` / `.svg` | sensitivity maps |
//! | `optimise/path.csv` | best objective and design per optimiser iteration |
//! | `optimise/result.csv` | base vs optimum: objective, design variables, mass properties, metrics |
//! | `optimise/optimum_club.toml` | the optimum as a club file |

use std::fmt::Write as _;
use std::path::PathBuf;

use crate::data::club_file::club_toml;
use crate::data::fmt_f64;
use crate::report::heatmap::{heatmap_svg, matrix_csv, Heatmap, Scale};
use crate::units::mph;

use super::design::DesignVar;
use super::metrics::{metric_names, metric_unit, Output};
use super::optimise::OptimiseResult;
use super::sensitivity::Sensitivity;
use super::spec::resolved_toml;
use super::sweep::{Prepared, VariantResult};

/// Files to write: path relative to the output folder, bytes.
pub type Files = Vec<(PathBuf, Vec<u8>)>;

/// A CSV cell: shortest round-trip form, empty for NaN.
pub fn cell(v: f64) -> String {
    if v.is_finite() {
        fmt_f64(v)
    } else {
        String::new()
    }
}

const X_LABEL: &str = "impact z (toward toe), mm";
const Y_LABEL: &str = "impact y (up the face), mm";

fn id_width(n: usize) -> usize {
    (n.saturating_sub(1)).to_string().len().max(3)
}

/// Every output file of a complete (unsharded or merged) run.
pub fn study_files(
    p: &Prepared,
    results: &[VariantResult],
    sens: &[Sensitivity],
    opt: Option<&OptimiseResult>,
) -> Files {
    let s = &p.study;
    let mut files: Files = vec![("study.toml".into(), resolved_toml(s).into_bytes())];
    let axes: Vec<DesignVar> = s.design.axes.iter().map(|(v, _)| *v).collect();
    let names = metric_names(s.distribution.is_some());
    let club_speed = mph(s.swing.club_speed_mph);

    // variants.csv
    let mut t = String::from("variant_id");
    for v in &axes {
        let _ = write!(t, ",{}", v.key());
    }
    for n in &names {
        let _ = write!(t, ",{n}");
    }
    t.push('\n');
    for (i, (d, r)) in p.variants.iter().zip(results).enumerate() {
        let _ = write!(t, "{i}");
        for v in &axes {
            let _ = write!(t, ",{}", cell(d.get(*v)));
        }
        for m in &r.metrics {
            let _ = write!(t, ",{}", cell(*m));
        }
        t.push('\n');
    }
    files.push(("variants.csv".into(), t.into_bytes()));

    // maps_long.csv
    let nz = p.zs_mm.len();
    let mut t = String::from("variant_id");
    for v in &axes {
        let _ = write!(t, ",{}", v.key());
    }
    t.push_str(",y_mm,z_mm,valid");
    for o in &s.outputs {
        let _ = write!(t, ",{}", o.column());
    }
    t.push('\n');
    for (i, (d, r)) in p.variants.iter().zip(results).enumerate() {
        let mut prefix = i.to_string();
        for v in &axes {
            let _ = write!(prefix, ",{}", cell(d.get(*v)));
        }
        for (iy, y) in p.ys_mm.iter().enumerate() {
            for (iz, z) in p.zs_mm.iter().enumerate() {
                let k = iy * nz + iz;
                let _ = write!(
                    t,
                    "{prefix},{},{},{}",
                    cell(*y),
                    cell(*z),
                    u8::from(r.grid.valid[k])
                );
                for o in &s.outputs {
                    let _ = write!(t, ",{}", cell(o.file_value(&r.grid, k, club_speed)));
                }
                t.push('\n');
            }
        }
    }
    files.push(("maps_long.csv".into(), t.into_bytes()));

    // Per-variant maps.
    let w = id_width(p.variants.len());
    for (i, (d, r)) in p.variants.iter().zip(results).enumerate() {
        for o in &s.outputs {
            let values: Vec<f64> = (0..r.grid.len())
                .map(|k| o.file_value(&r.grid, k, club_speed))
                .collect();
            let title = format!("{}: variant {i} ({}): {}", s.name, d.describe(), o.label());
            let value_label = format!("{}, {}", o.label().to_lowercase(), o.unit());
            let map = Heatmap {
                title: &title,
                x_label: X_LABEL,
                y_label: Y_LABEL,
                value_label: &value_label,
                xs: &p.zs_mm,
                ys: &p.ys_mm,
                values: &values,
                marker: Some((0.0, 0.0)),
                scale: if o.signed() {
                    Scale::Diverging
                } else {
                    Scale::Sequential
                },
            };
            let stem = format!("maps/v{i:0w$}_{}", o.column());
            files.push((format!("{stem}.csv").into(), matrix_csv(&map)));
            files.push((format!("{stem}.svg").into(), heatmap_svg(&map).into_bytes()));
        }
    }

    if !sens.is_empty() {
        files.extend(sensitivity_files(p, sens, &names));
    }
    if let Some(o) = opt {
        files.extend(optimise_files(p, o, &names));
    }
    files
}

fn sensitivity_files(p: &Prepared, sens: &[Sensitivity], names: &[String]) -> Files {
    let s = &p.study;
    let mut files = Files::new();
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
    files.push(("sensitivity.csv".into(), t.into_bytes()));
    for x in sens {
        for (oi, o) in Output::ALL.iter().enumerate() {
            if !s.outputs.contains(o) {
                continue;
            }
            let title = format!(
                "{}: d({}) / d({}) at the base design (step {})",
                s.name,
                o.label().to_lowercase(),
                x.var.key(),
                x.step
            );
            let value_label = format!(
                "{} per {}, {}/{}",
                o.label().to_lowercase(),
                x.var.key(),
                o.unit(),
                x.var.unit()
            );
            let map = Heatmap {
                title: &title,
                x_label: X_LABEL,
                y_label: Y_LABEL,
                value_label: &value_label,
                xs: &p.zs_mm,
                ys: &p.ys_mm,
                values: &x.maps[oi],
                marker: Some((0.0, 0.0)),
                scale: Scale::Diverging,
            };
            let stem = format!("sensitivity/d_{}__d_{}", o.column(), x.var.key());
            files.push((format!("{stem}.csv").into(), matrix_csv(&map)));
            files.push((format!("{stem}.svg").into(), heatmap_svg(&map).into_bytes()));
        }
    }
    files
}

fn optimise_files(p: &Prepared, o: &OptimiseResult, names: &[String]) -> Files {
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
