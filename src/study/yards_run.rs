//! The `[yards]` part of a study run: maps in yards over the face, robust metrics over the
//! study's distribution, the constraint report and the discretionary-mass optimisation
//! ([`run_yards`]), and their output files ([`yards_files`], written under `yards/` beside the
//! study's other outputs).
//!
//! | file | content |
//! |---|---|
//! | `yards/carry_yd.csv` / `.svg`, `yards/offline_yd.csv` / `.svg` | carry and offline of the study's swing at each grid point |
//! | `yards/mean_carry_yd`, `yards/std_carry_yd`, `yards/ellipse_area_yd2` (`.csv` / `.svg`) | robust metrics of the distribution centred at each grid point (empty where part of it is off the face, or most of its balls never leave the ground) |
//! | `yards/metrics.csv` | base (and optimum) design: mean and spread of carry and offline, dispersion-ellipse area and its confidence |
//! | `yards/constraints.csv` | every constraint at the base (and optimum): value, limit, margin, holds |
//! | `yards/optimise.csv` | goal, evaluations, rejected designs, mass move, active bounds (or why it did not run) |
//! | `yards/variants.csv` | every head against the base, keyed by `variant_id` (the ids of `variants.csv`; empty for the base and the optima): each `[design]` variant, the `[yards.optimise]` optimum and the `[optimise]` optimum, with the changes of mean carry, carry spread, ellipse area, offline, ball speed and spin and their quadrature uncertainty ([`super::yards_variants`]) |
//!
//! The impact model is the study's base club (nominal parameters; the group's effects are not
//! applied to the yard part). Pure: the CLI writes the files.

use std::fmt::Write as _;
use std::path::PathBuf;

use rayon::prelude::*;

use super::design::{Design, DesignVar, DiscretionaryMass};
use super::output::{cell, Files};
use super::spec::Study;
use super::yards::{
    carry_map, check_constraints, optimise_mass, yard_metrics, CarryMap, ConstraintCheck,
    MassProblem, YardGoal, YardMetrics, YardOptimum, YardsError,
};
use super::yards_spec::YardsSpec;
use super::yards_variants::{head_yards, rows_csv, HeadYards, YardRow, YardSetting};
use crate::flight::FlightConfig;
use crate::physics::ImpactModel;
use crate::report::heatmap::{heatmap_svg, matrix_csv, Heatmap, Scale};

/// Most flights the robust-metric maps may take (grid points × distribution points): about a
/// second per million here.
pub const MAX_MAP_FLIGHTS: usize = 20_000_000;

/// Everything the yard part computes.
#[derive(Debug, Clone)]
pub struct YardsResult {
    /// The base head's metrics with the companion rule's (for the uncertainties).
    pub base_head: HeadYards,
    /// Every head against the base, the base first (see [`super::yards_variants`]).
    pub rows: Vec<YardRow>,
    /// Carry and offline of the study's swing over the grid.
    pub map: CarryMap,
    /// Robust metrics of the distribution centred at each grid point (row-major), `None` where
    /// part of it is off the face.
    pub robust_map: Vec<Option<YardMetrics>>,
    /// Robust metrics of the base design (distribution as given).
    pub base: YardMetrics,
    /// Constraints at the base design.
    pub base_constraints: Vec<ConstraintCheck>,
    /// The optimisation, when asked for: its result, or why it could not run.
    pub optimum: Option<Result<YardOptimum, YardsError>>,
}

/// Why the yard part of a study cannot run ([`run_yards`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RunYardsError {
    /// No `[yards]` table.
    #[error("the study has no [yards] table")]
    NoYards,
    /// No `[distribution]`.
    #[error("[yards] needs the study's [distribution]")]
    NoDistribution,
    /// The atmosphere is not air.
    #[error(transparent)]
    Atmosphere(#[from] crate::flight::AtmosphereError),
    /// More map flights than [`MAX_MAP_FLIGHTS`].
    #[error(
        "the robust-metric maps of [yards] need {flights} flights (grid {}×{} × {points} \
         distribution points), more than {MAX_MAP_FLIGHTS}: use a coarser [grid] or fewer \
         distribution nodes",
        grid[0],
        grid[1]
    )]
    TooManyFlights {
        /// Flights the maps need.
        flights: usize,
        /// Grid points up the face and heel–toe.
        grid: [usize; 2],
        /// Distribution points.
        points: usize,
    },
    /// A head's yard metrics, named (`base design`, a variant's label).
    #[error("[yards] {head}: {source}")]
    Head {
        /// Which head.
        head: String,
        /// Why.
        source: YardsError,
    },
    /// Yard metrics or a model without a head to name.
    #[error(transparent)]
    Yards(#[from] YardsError),
}

impl RunYardsError {
    fn of(head: &str, source: YardsError) -> Self {
        Self::Head {
            head: head.to_owned(),
            source,
        }
    }
}

/// The flight configuration of a `[yards]` table.
pub fn flight_config(y: &YardsSpec) -> Result<FlightConfig, crate::flight::AtmosphereError> {
    Ok(FlightConfig {
        aero: y.aero(),
        air: y.atmosphere.air()?,
        ..FlightConfig::default()
    })
}

/// Run the yard part of `study` (which must have a `[yards]` table). `study_optimum`: the
/// best design of the study's `[optimise]`, when it has one (its row joins the table).
pub fn run_yards(
    study: &Study,
    study_optimum: Option<&Design>,
) -> Result<YardsResult, RunYardsError> {
    let y = study.yards.as_ref().ok_or(RunYardsError::NoYards)?;
    let dist = study
        .distribution
        .as_ref()
        .ok_or(RunYardsError::NoDistribution)?;
    let flight = flight_config(y)?;
    let nominal = &study.club.nominal;
    let model = ImpactModel::new(nominal.clone()).map_err(YardsError::from)?;
    let ys = study.grid.y_mm.values();
    let zs = study.grid.z_mm.values();
    let flights = ys.len() * zs.len() * dist.point_count();
    if flights > MAX_MAP_FLIGHTS {
        return Err(RunYardsError::TooManyFlights {
            flights,
            grid: [ys.len(), zs.len()],
            points: dist.point_count(),
        });
    }
    let map = carry_map(&model, &study.swing, &ys, &zs, &flight)?;
    let robust_map: Vec<Option<YardMetrics>> = (0..ys.len() * zs.len())
        .into_par_iter()
        .map(|k| {
            let mut d = *dist;
            d.impact_centre_mm = [ys[k / zs.len()], zs[k % zs.len()]];
            yard_metrics(&model, &study.swing, &d, &flight, y.confidence).ok()
        })
        .collect();
    let base = yard_metrics(&model, &study.swing, dist, &flight, y.confidence)
        .map_err(|e| RunYardsError::of("base design", e))?;
    let base_constraints = check_constraints(nominal, &y.constraints);
    let optimum = match (&y.optimise, &y.mass) {
        (Some((goal, iters)), Some((mass, bounds))) => {
            let problem = MassProblem {
                nominal,
                mass,
                bounds_mm: *bounds,
                base: &study.swing,
                dist,
                flight: &flight,
                confidence: y.confidence,
                constraints: &y.constraints,
                goal: *goal,
            };
            Some(optimise_mass(&problem, *iters))
        }
        _ => None,
    };
    let setting = YardSetting {
        swing: &study.swing,
        dist,
        flight: &flight,
        confidence: y.confidence,
    };
    let base_head =
        head_yards(nominal, &setting).map_err(|e| RunYardsError::of("base design", e))?;
    let mut heads = design_heads(study, study_optimum);
    if let (Some(Ok(o)), Some((mass, _))) = (&optimum, &y.mass) {
        let d = Design::default()
            .with(DesignVar::MassDx, o.move_mm[0])
            .with(DesignVar::MassDy, o.move_mm[1])
            .with(DesignVar::MassDz, o.move_mm[2]);
        heads.push((None, "optimum [yards.optimise]".into(), d, Some(*mass)));
    }
    let rows = heads
        .into_par_iter()
        .map(|(variant_id, label, d, mass)| {
            let p = d.apply(nominal, mass.as_ref()).map_err(YardsError::from)?;
            let head = head_yards(&p, &setting).map_err(|e| RunYardsError::of(&label, e))?;
            Ok(YardRow {
                variant_id,
                label,
                design: d.describe(),
                head,
            })
        })
        .collect::<Result<Vec<_>, RunYardsError>>()?;
    Ok(YardsResult {
        base_head,
        rows,
        map,
        robust_map,
        base,
        base_constraints,
        optimum,
    })
}

/// One head of the yards table: its id in `variants.csv` (a `[design]` variant's only), label,
/// design and the discretionary mass it moves.
type DesignHead = (Option<usize>, String, Design, Option<DiscretionaryMass>);

/// The heads the table compares: the base, each `[design]` variant (with its id in
/// `variants.csv`), and the `[optimise]` optimum.
fn design_heads(study: &Study, study_optimum: Option<&Design>) -> Vec<DesignHead> {
    let mass = study.design.discretionary_mass;
    let mut heads = vec![(None, "base".to_owned(), Design::default(), None)];
    let variants = study.design.variants();
    if variants.len() > 1 || variants.first().is_some_and(|d| *d != Design::default()) {
        for (i, d) in variants.into_iter().enumerate() {
            heads.push((Some(i), format!("variant {i}"), d, mass));
        }
    }
    if let Some(d) = study_optimum {
        heads.push((None, "optimum [optimise]".into(), *d, mass));
    }
    heads
}

fn map_files(
    out: &mut Files,
    study: &Study,
    stem: &str,
    title: &str,
    value_label: &str,
    values: &[f64],
    scale: Scale,
) {
    let ys = study.grid.y_mm.values();
    let zs = study.grid.z_mm.values();
    let title = format!("{}: {title}", study.name);
    let h = Heatmap {
        title: &title,
        x_label: "impact z (toward toe), mm",
        y_label: "impact y (up), mm",
        value_label,
        xs: &zs,
        ys: &ys,
        values,
        marker: Some((0.0, 0.0)),
        scale,
    };
    out.push((PathBuf::from(format!("yards/{stem}.csv")), matrix_csv(&h)));
    out.push((
        PathBuf::from(format!("yards/{stem}.svg")),
        heatmap_svg(&h).into_bytes(),
    ));
}

fn goal_name(g: YardGoal) -> &'static str {
    match g {
        YardGoal::MaxMeanCarry => "max_mean_carry",
        YardGoal::MinDispersion => "min_dispersion",
    }
}

/// The output files of the yard part (paths under `yards/`).
pub fn yards_files(study: &Study, r: &YardsResult) -> Files {
    let mut out = yard_maps(study, r);
    let opt = r.optimum.as_ref().and_then(|o| o.as_ref().ok());
    out.push((PathBuf::from("yards/metrics.csv"), metrics_csv(r, opt)));
    out.push((
        PathBuf::from("yards/constraints.csv"),
        constraints_csv(r, opt),
    ));
    out.extend(optimise_csv(study, r));
    out.push((
        PathBuf::from("yards/variants.csv"),
        rows_csv(&r.base_head, &r.rows),
    ));
    out
}

/// The yard maps (carry, offline and the robust metrics over the face): matrices and pictures.
fn yard_maps(study: &Study, r: &YardsResult) -> Files {
    let y = study.yards.as_ref().expect("a study with [yards]");
    let mut out = Files::new();
    let nan = |v: &Option<f64>| v.unwrap_or(f64::NAN);
    let carry: Vec<f64> = r.map.carry_yd.iter().map(nan).collect();
    let off: Vec<f64> = r.map.offline_yd.iter().map(nan).collect();
    map_files(
        &mut out,
        study,
        "carry_yd",
        "carry (study swing)",
        "carry, yd",
        &carry,
        Scale::Sequential,
    );
    map_files(
        &mut out,
        study,
        "offline_yd",
        "offline (study swing; + right)",
        "offline, yd",
        &off,
        Scale::Diverging,
    );
    let robust = |f: fn(&YardMetrics) -> f64| -> Vec<f64> {
        r.robust_map
            .iter()
            .map(|m| m.as_ref().map_or(f64::NAN, f))
            .collect()
    };
    map_files(
        &mut out,
        study,
        "mean_carry_yd",
        "mean carry over the distribution centred here",
        "mean carry, yd",
        &robust(|m| m.mean_carry_yd),
        Scale::Sequential,
    );
    map_files(
        &mut out,
        study,
        "std_carry_yd",
        "carry spread over the distribution centred here",
        "carry standard deviation, yd",
        &robust(|m| m.std_carry_yd),
        Scale::Sequential,
    );
    let pct = 100.0 * y.confidence;
    map_files(
        &mut out,
        study,
        "ellipse_area_yd2",
        &format!("{pct}% dispersion ellipse over the distribution centred here"),
        "ellipse area, yd²",
        &robust(|m| m.ellipse_area_yd2),
        Scale::Sequential,
    );
    out
}

/// `yards/metrics.csv`: the base design's yard metrics and the optimum's.
fn metrics_csv(r: &YardsResult, opt: Option<&YardOptimum>) -> Vec<u8> {
    let mut t = String::from(
        "design,mass_dx_mm,mass_dy_mm,mass_dz_mm,mean_carry_yd,std_carry_yd,mean_offline_yd,\
         std_offline_yd,ellipse_area_yd2,confidence,grounded_pct\n",
    );
    let mut row = |name: &str, mv: [f64; 3], m: &YardMetrics| {
        let _ = writeln!(
            t,
            "{name},{},{},{},{},{},{},{},{},{},{}",
            cell(mv[0]),
            cell(mv[1]),
            cell(mv[2]),
            cell(m.mean_carry_yd),
            cell(m.std_carry_yd),
            cell(m.mean_offline_yd),
            cell(m.std_offline_yd),
            cell(m.ellipse_area_yd2),
            cell(m.confidence),
            cell(100.0 * m.grounded_share)
        );
    };
    row("base", [0.0; 3], &r.base);
    if let Some(o) = opt {
        row("optimum", o.move_mm, &o.best);
    }
    t.into_bytes()
}

/// `yards/constraints.csv`: each head constraint at the base and the optimum.
fn constraints_csv(r: &YardsResult, opt: Option<&YardOptimum>) -> Vec<u8> {
    let mut t = String::from("constraint,limit,base,base_margin,base_holds");
    if opt.is_some() {
        t.push_str(",optimum,optimum_margin,optimum_holds");
    }
    t.push('\n');
    for (k, b) in r.base_constraints.iter().enumerate() {
        let _ = write!(
            t,
            "{},{},{},{},{}",
            b.name,
            cell(b.limit),
            cell(b.value),
            cell(b.margin),
            b.holds()
        );
        if let Some(o) = opt {
            let c = &o.best_constraints[k];
            let _ = write!(t, ",{},{},{}", cell(c.value), cell(c.margin), c.holds());
        }
        t.push('\n');
    }
    t.into_bytes()
}

/// `yards/optimise.csv` when the study optimises: goal, status, the move and the bounds it
/// reached.
fn optimise_csv(study: &Study, r: &YardsResult) -> Option<(PathBuf, Vec<u8>)> {
    let y = study.yards.as_ref().expect("a study with [yards]");
    let (Some(o), Some((goal, iters)), Some((_, bounds))) = (&r.optimum, &y.optimise, &y.mass)
    else {
        return None;
    };
    {
        let mut t = String::from("key,value\n");
        let _ = writeln!(t, "goal,{}", goal_name(*goal));
        let _ = writeln!(t, "max_iters,{iters}");
        match o {
            Err(e) => {
                let _ = writeln!(t, "status,\"not run: {}\"", e.to_string().replace('"', "'"));
            }
            Ok(o) => {
                let _ = writeln!(t, "status,done");
                let _ = writeln!(t, "evaluations,{}", o.evaluations);
                let _ = writeln!(t, "rejected_designs,{}", o.rejected);
                for (k, axis) in ["dx", "dy", "dz"].iter().enumerate() {
                    let _ = writeln!(t, "mass_{axis}_mm,{}", cell(o.move_mm[k]));
                }
                let active: Vec<String> = (0..3)
                    .flat_map(|k| {
                        let v = o.move_mm[k];
                        let axis = ["dx", "dy", "dz"][k];
                        [(bounds[k][0], "lower"), (bounds[k][1], "upper")]
                            .into_iter()
                            .filter(move |(x, _)| (v - x).abs() < 0.1)
                            .map(move |(_, side)| format!("{axis} {side}"))
                    })
                    .collect();
                let _ = writeln!(
                    t,
                    "bounds_active_within_0.1_mm,{}",
                    if active.is_empty() {
                        "none".into()
                    } else {
                        active.join(" ")
                    }
                );
            }
        }
        Some((PathBuf::from("yards/optimise.csv"), t.into_bytes()))
    }
}

/// A few lines for the terminal: base and optimum metrics and any broken constraint, the lines
/// wrapped and the table split to fit 100 columns unless `wide`.
pub fn yards_summary(study: &Study, r: &YardsResult, wide: bool) -> String {
    let y = study.yards.as_ref().expect("a study with [yards]");
    let pct = 100.0 * y.confidence;
    let mut t = String::new();
    let m = &r.base;
    let _ = writeln!(
        t,
        "yards: base design mean carry {:.2} yd (sd {:.2}), offline {:+.2} yd (sd {:.2}), {pct}% ellipse {:.1} yd²",
        m.mean_carry_yd, m.std_carry_yd, m.mean_offline_yd, m.std_offline_yd, m.ellipse_area_yd2
    );
    if let Some(note) = m.grounded_note() {
        let _ = writeln!(t, "yards: base design: {note}");
    }
    for c in r.base_constraints.iter().filter(|c| !c.holds()) {
        let _ = writeln!(
            t,
            "yards: the base design breaks {}: {:.2} against {} (margin {:.2})",
            c.name, c.value, c.limit, c.margin
        );
    }
    match &r.optimum {
        None => {}
        Some(Err(e)) => {
            let _ = writeln!(t, "yards: optimisation not run: {e}");
        }
        Some(Ok(o)) => {
            let _ = writeln!(
                t,
                "yards: optimum (mass moved {:+.1}, {:+.1}, {:+.1} mm) mean carry {:.2} yd (sd {:.2}), {pct}% ellipse {:.1} yd²; {} evaluations, {} designs rejected for breaking a bound or constraint",
                o.move_mm[0], o.move_mm[1], o.move_mm[2],
                o.best.mean_carry_yd, o.best.std_carry_yd, o.best.ellipse_area_yd2,
                o.evaluations, o.rejected
            );
        }
    }
    if r.rows.len() > 1 {
        let _ = writeln!(
            t,
            "yards per design against the base (changes; ± the quadrature's error estimate):"
        );
        let width = (!wide).then_some(crate::report::compare::TEXT_WIDTH);
        t.push_str(&super::yards_variants::rows_text(
            &r.base_head,
            &r.rows,
            12,
            width,
        ));
    }
    if !study.club.effects.is_empty() {
        let _ = writeln!(
            t,
            "yards: the club's {} [[effect]] entries are not applied in yards (the nominal head, \
             as documented in configs/README.md); the face maps apply group '{}'",
            study.club.effects.len(),
            study.group
        );
    }
    if study.sensitivity.is_some() {
        let _ = writeln!(
            t,
            "yards: [sensitivity] differentiates the face-map metrics (sensitivities.csv), not yards"
        );
    }
    if wide {
        return t;
    }
    // Prose wrapped; the table's lines are at most the width already.
    let width = crate::report::compare::TEXT_WIDTH;
    t.split_inclusive('\n')
        .map(|l| match l.trim_end().chars().count() > width {
            true => crate::report::wrap::wrap(l.trim_end(), width, 2),
            false => l.to_owned(),
        })
        .collect()
}
