//! The study sweep: design variants × face grid, split into a flat work list.
//!
//! The work list has, per variant in order, one *metrics* item (the variant's summary metrics)
//! then one item per grid row. A shard `k/N` takes the contiguous items
//! `[k·T/N, (k+1)·T/N)` of the `T` items; every item is computed the same way whichever run
//! computes it, so merged shards equal the unsharded run bit for bit.

use rayon::prelude::*;

use crate::physics::ImpactModel;
use crate::sweep::kernel::{FaceMapKernel, LaunchGrid};
use crate::units::mm;

use super::design::Design;
use super::distribution::SwingGroup;
use super::evaluate::{evaluate, impacts_per_design};
use super::spec::Study;
use super::StudyError;

/// A study ready to run: variants validated into models, grid in metres.
#[derive(Debug, Clone)]
pub struct Prepared {
    /// The resolved study.
    pub study: Study,
    /// The variants, in order.
    pub variants: Vec<Design>,
    /// One validated model per variant.
    pub models: Vec<ImpactModel>,
    /// Grid rows (heights), mm.
    pub ys_mm: Vec<f64>,
    /// Grid columns (toward the toe), mm.
    pub zs_mm: Vec<f64>,
    /// Distribution impacts (empty without a distribution).
    pub groups: Vec<SwingGroup>,
}

/// The model of `design` for the study's club and group.
pub fn design_model(study: &Study, design: &Design) -> Result<ImpactModel, StudyError> {
    let nominal = design
        .apply(
            &study.club.nominal,
            study.design.discretionary_mass.as_ref(),
        )
        .map_err(|e| StudyError::Design {
            values: e.values.clone(),
            problem: e.problem.clone(),
        })?;
    let mut club = study.club.clone();
    club.nominal = nominal;
    club.model_for_group(&study.group)
        .map_err(|e| StudyError::Design {
            values: design.describe(),
            problem: e.to_string(),
        })
}

impl Prepared {
    /// Validate every variant and the swing. Errors name the first bad variant with its values.
    pub fn new(study: Study) -> Result<Self, StudyError> {
        let variants = study.design.variants();
        let (ny, nz) = (
            study.grid.y_mm.values().len(),
            study.grid.z_mm.values().len(),
        );
        let points = variants.len() as u128 * ny as u128 * nz as u128;
        if points > super::MAX_SWEEP_POINTS {
            return Err(StudyError::TooLarge {
                points,
                variants: variants.len(),
                ny,
                nz,
            });
        }
        let models = variants
            .par_iter()
            .enumerate()
            .map(|(i, d)| {
                design_model(&study, d).map_err(|e| match e {
                    StudyError::Design { values, problem } => StudyError::Variant {
                        id: i,
                        values,
                        problem,
                    },
                    other => other,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let delivery = study.swing.delivery(0.0, 0.0);
        models[0].solve(&delivery).map_err(|e| StudyError::Swing {
            problem: e.to_string(),
        })?;
        let groups = study
            .distribution
            .as_ref()
            .map_or_else(Vec::new, |d| d.groups(&study.swing));
        Ok(Self {
            ys_mm: study.grid.y_mm.values(),
            zs_mm: study.grid.z_mm.values(),
            groups,
            variants,
            models,
            study,
        })
    }

    /// Items per variant: the metrics item and one per row.
    pub fn items_per_variant(&self) -> usize {
        self.ys_mm.len() + 1
    }

    /// Length of the work list.
    pub fn work_len(&self) -> usize {
        self.variants.len() * self.items_per_variant()
    }

    /// Items of shard `k` of `n` (0-based `k`).
    pub fn shard_range(&self, k: usize, n: usize) -> std::ops::Range<usize> {
        // In 128 bits: k·t overflows usize for large shard counts.
        let (k, n, t) = (k as u128, n.max(1) as u128, self.work_len() as u128);
        ((k * t / n) as usize)..(((k + 1).min(n) * t / n) as usize)
    }

    /// Impacts computed by `items`.
    pub fn impacts_in(&self, items: std::ops::Range<usize>) -> usize {
        let per = impacts_per_design(&self.study, &self.groups);
        items
            .map(|i| {
                if i % self.items_per_variant() == 0 {
                    per
                } else {
                    self.zs_mm.len()
                }
            })
            .sum()
    }

    /// Compute the work items `items` in parallel; `tick` is called once per finished item.
    pub fn compute(
        &self,
        items: std::ops::Range<usize>,
        tick: &(dyn Fn() + Sync),
    ) -> Vec<ItemResult> {
        let mut out = self.allocate(items);
        self.compute_into(&mut out, tick);
        out
    }

    /// Output slots for the work items `items`, with every grid page written once (so the
    /// sweep itself does not pay for first-touch page faults).
    pub fn allocate(&self, items: std::ops::Range<usize>) -> Vec<ItemResult> {
        let per = self.items_per_variant();
        let nz = self.zs_mm.len();
        items
            .map(|i| {
                let (v, k) = (i / per, i % per);
                if k == 0 {
                    ItemResult::Metrics {
                        variant: v,
                        values: Vec::new(),
                    }
                } else {
                    let mut grid = LaunchGrid::with_len(nz);
                    for c in [
                        &mut grid.ball_speed_m_s,
                        &mut grid.launch_angle_rad,
                        &mut grid.azimuth_rad,
                        &mut grid.backspin_rad_s,
                        &mut grid.sidespin_rad_s,
                    ] {
                        c.fill(f64::NAN);
                    }
                    grid.valid.fill(false);
                    ItemResult::Row {
                        variant: v,
                        row: k - 1,
                        grid,
                    }
                }
            })
            .collect()
    }

    /// Compute every slot of `slots` (from [`Prepared::allocate`]) in parallel; `tick` is called
    /// once per finished item.
    pub fn compute_into(&self, slots: &mut [ItemResult], tick: &(dyn Fn() + Sync)) {
        let zs_m: Vec<f64> = self.zs_mm.iter().map(|z| mm(*z)).collect();
        let delivery = self.study.swing.delivery(0.0, 0.0);
        let kernels: Vec<FaceMapKernel> = self
            .models
            .iter()
            .map(|m| FaceMapKernel::new(m, &delivery))
            .collect();
        slots.par_iter_mut().for_each(|slot| {
            match slot {
                ItemResult::Metrics { variant, values } => {
                    *values = evaluate(&self.models[*variant], &self.study, &self.groups);
                }
                ItemResult::Row { variant, row, grid } => {
                    let n = zs_m.len();
                    kernels[*variant].eval_row(mm(self.ys_mm[*row]), &zs_m, grid.row_out(0, n));
                }
            }
            tick();
        });
    }

    /// Every variant's summary metrics, in parallel.
    pub fn all_metrics(&self) -> Vec<Vec<f64>> {
        self.models
            .par_iter()
            .map(|m| evaluate(m, &self.study, &self.groups))
            .collect()
    }

    /// The face maps computed on demand, a band of rows at a time, by one kernel per variant.
    pub fn kernels(&self) -> Kernels {
        let delivery = self.study.swing.delivery(0.0, 0.0);
        Kernels {
            kernels: self
                .models
                .iter()
                .map(|m| FaceMapKernel::new(m, &delivery))
                .collect(),
            ys_m: self.ys_mm.iter().map(|y| mm(*y)).collect(),
            zs_m: self.zs_mm.iter().map(|z| mm(*z)).collect(),
            seconds: std::sync::Mutex::new(0.0),
            points: std::sync::atomic::AtomicUsize::new(0),
        }
    }

    /// Assemble complete per-variant results from item results covering the whole work list.
    pub fn assemble(&self, items: Vec<ItemResult>) -> Result<Vec<VariantResult>, StudyError> {
        let (ny, nz) = (self.ys_mm.len(), self.zs_mm.len());
        let mut out: Vec<VariantResult> = (0..self.variants.len())
            .map(|_| VariantResult {
                grid: LaunchGrid::with_len(ny * nz),
                metrics: Vec::new(),
            })
            .collect();
        let mut seen = vec![false; self.work_len()];
        let per = self.items_per_variant();
        for it in items {
            let (v, row) = match &it {
                ItemResult::Metrics { variant, .. } => (*variant, None),
                ItemResult::Row { variant, row, .. } => (*variant, Some(*row)),
            };
            if v >= self.variants.len() || row.is_some_and(|r| r >= ny) {
                return Err(StudyError::Merge(format!(
                    "variant {v}{} is outside the study ({} variant(s) of {ny} grid rows)",
                    row.map_or(String::new(), |r| format!(" row {r}")),
                    self.variants.len()
                )));
            }
            let idx = v * per + row.map_or(0, |r| r + 1);
            if idx >= seen.len() {
                return Err(StudyError::Merge(format!(
                    "work item {idx} is outside the study"
                )));
            }
            if seen[idx] {
                return Err(StudyError::Merge(format!("work item {idx} appears twice")));
            }
            seen[idx] = true;
            match it {
                ItemResult::Metrics { values, .. } => out[v].metrics = values,
                ItemResult::Row { row, grid, .. } => {
                    if grid.len() != nz {
                        return Err(StudyError::Merge(format!(
                            "variant {v} row {row} has {} points, the grid has {nz} columns",
                            grid.len()
                        )));
                    }
                    let dst = &mut out[v].grid;
                    let s = row * nz;
                    dst.ball_speed_m_s[s..s + nz].copy_from_slice(&grid.ball_speed_m_s);
                    dst.launch_angle_rad[s..s + nz].copy_from_slice(&grid.launch_angle_rad);
                    dst.azimuth_rad[s..s + nz].copy_from_slice(&grid.azimuth_rad);
                    dst.backspin_rad_s[s..s + nz].copy_from_slice(&grid.backspin_rad_s);
                    dst.sidespin_rad_s[s..s + nz].copy_from_slice(&grid.sidespin_rad_s);
                    dst.valid[s..s + nz].copy_from_slice(&grid.valid);
                }
            }
        }
        if let Some(missing) = seen.iter().position(|s| !s) {
            return Err(StudyError::Merge(format!(
                "work item {missing} (variant {}) is missing: are all shards given?",
                missing / per
            )));
        }
        Ok(out)
    }
}

/// The result of one work item.
#[derive(Debug, Clone, PartialEq)]
pub enum ItemResult {
    /// A variant's summary metrics.
    Metrics {
        /// Variant id.
        variant: usize,
        /// Values in `metric_names` order.
        values: Vec<f64>,
    },
    /// One grid row of a variant.
    Row {
        /// Variant id.
        variant: usize,
        /// Row index (ascending y).
        row: usize,
        /// The row's points.
        grid: LaunchGrid,
    },
}

/// Everything swept for one variant.
#[derive(Debug, Clone, PartialEq)]
pub struct VariantResult {
    /// The face map, `ys × zs`, row-major.
    pub grid: LaunchGrid,
    /// Summary metrics.
    pub metrics: Vec<f64>,
}

/// Where the face maps come from: computed on demand (a run) or read back from the shards (a
/// merge).
pub trait GridSource: Sync {
    /// Rows `rows` of variant `variant` into `out` (resized to `rows.len() · nz` points).
    fn grid_rows(
        &self,
        variant: usize,
        rows: std::ops::Range<usize>,
        out: &mut LaunchGrid,
    ) -> std::io::Result<()>;
}

/// One face-map kernel per variant: the study's maps computed on demand (a [`GridSource`]).
/// Bit-identical to [`Prepared::compute`] row by row.
#[derive(Debug)]
pub struct Kernels {
    kernels: Vec<FaceMapKernel>,
    ys_m: Vec<f64>,
    zs_m: Vec<f64>,
    seconds: std::sync::Mutex<f64>,
    points: std::sync::atomic::AtomicUsize,
}

impl Kernels {
    /// Wall-clock seconds spent in the kernel so far.
    pub fn seconds(&self) -> f64 {
        *self.seconds.lock().expect("not poisoned")
    }

    /// Grid points computed so far.
    pub fn points(&self) -> usize {
        self.points.load(std::sync::atomic::Ordering::Relaxed)
    }
}

impl GridSource for Kernels {
    fn grid_rows(
        &self,
        variant: usize,
        rows: std::ops::Range<usize>,
        out: &mut LaunchGrid,
    ) -> std::io::Result<()> {
        let start = std::time::Instant::now();
        out.resize(rows.len() * self.zs_m.len());
        self.kernels[variant].par_eval_grid(&self.ys_m[rows], &self.zs_m, out);
        *self.seconds.lock().expect("not poisoned") += start.elapsed().as_secs_f64();
        self.points
            .fetch_add(out.len(), std::sync::atomic::Ordering::Relaxed);
        Ok(())
    }
}
