//! The Jacobian (`problem.rs`'s module docs say how it is differenced): the two points of a
//! parameter's difference ([`difference_points`]), the Jacobian a column at a time from two
//! evaluations, and the same on the lanes in one pass over the shots: for each vector of
//! [`Lanes::N`](crate::lanes::Lanes::N) shots of one group, each evaluation site's inputs (the
//! location nodes and the contact frames there, the delivery frames) are gathered once and
//! solved by the model at `θ` and the `p` shifted models (`θ + h_j e_j`, or `θ − h_j e_j` at the
//! upper bound) before the next site is read. Each model's solution is the same operations on
//! the same inputs as its own evaluation ([`FitProblem::residuals_into`]), so every column is
//! the same bits as from two separate evaluations; what is saved is solving the model at `θ`
//! once for all columns, and reading, arranging and computing the inputs `p` times more per
//! site.

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use super::lanes::{padded, FrameLanes, LanePrediction};
use super::{EvalError, FitProblem, FD_STEP_OF_RANGE, SHOTS_PER_TASK};
use crate::fit::data::SiteCache;
#[cfg(target_arch = "x86_64")]
use crate::lanes::{F64x4, F64x8};
use crate::lanes::{Lanes, SimdLevel, V};
use crate::physics::{FaceGeometry, ImpactModel};

/// The most lanes of any lane type (AVX-512's eight).
const MAX_LANES: usize = 8;

/// The shifted models of one Jacobian column per group it touches (`None` for the others):
/// the upper point's, and the lower point's (`None`: the model at `θ`), and the groups it
/// touches.
struct Column {
    plus: Vec<Option<ImpactModel>>,
    minus: Option<Vec<Option<ImpactModel>>>,
    /// The distance between the two points.
    span: f64,
    /// Per group: does the parameter change the group's model? (The other groups' rows are 0.)
    touched: Vec<bool>,
}

impl FitProblem<'_> {
    /// Forward-difference Jacobian of the residuals with respect to the active parameters,
    /// at full `theta` (module docs). Columns in the order of `active`.
    pub fn jacobian_full(&self, theta: &DVector<f64>) -> Result<DMatrix<f64>, EvalError> {
        // All columns in one pass over the shots where the lanes can take them (the same bits).
        match self.jacobian_on_lanes(theta.as_slice()) {
            Some(jac) => Ok(jac),
            None => self.jacobian_by_columns(theta),
        }
    }

    /// [`FitProblem::jacobian_full`] one column at a time, each from its shifted point's
    /// evaluation and the one at `theta` (made once for every column) or at its lower point.
    pub(super) fn jacobian_by_columns(
        &self,
        theta: &DVector<f64>,
    ) -> Result<DMatrix<f64>, EvalError> {
        let m = self.rows();
        let mut jac = DMatrix::zeros(m, self.active.len());
        let here = self.residuals_here(theta.as_slice(), 0..self.active.len())?;
        let column = |(k, col): (usize, &mut [f64])| {
            self.jacobian_column(theta.as_slice(), k, col, here.as_deref())
        };
        if self.parallel_jacobian {
            jac.as_mut_slice()
                .par_chunks_mut(m)
                .enumerate()
                .try_for_each(column)?;
        } else {
            jac.as_mut_slice()
                .chunks_mut(m)
                .enumerate()
                .try_for_each(column)?;
        }
        Ok(jac)
    }

    /// The points of parameter `j`'s difference at `theta` ([`difference_points`]): the
    /// shifted point, the lower one (`None`: `theta` itself), the span between them, and per
    /// group whether the parameter changes its model: the other groups' residuals are the same
    /// at both points, so their rows stay 0 (what (r − r)/span gives).
    #[allow(clippy::type_complexity)]
    pub(super) fn shifted(
        &self,
        theta: &[f64],
        j: usize,
    ) -> (Vec<f64>, Option<Vec<f64>>, f64, Vec<bool>) {
        let central = self.layout.effects()[self.owner[j]].is_nonsmooth();
        let (to, from) = difference_points(central, theta[j], self.lower[j], self.upper[j]);
        let mut point = theta.to_vec();
        point[j] = to;
        let lower = from.map(|v| {
            let mut p = theta.to_vec();
            p[j] = v;
            p
        });
        let touched = self
            .applies
            .iter()
            .map(|a| a.contains(&self.owner[j]))
            .collect();
        (point, lower, to - from.unwrap_or(theta[j]), touched)
    }

    /// The residuals at `theta` when any of the active columns `ks` is a one-sided difference
    /// (which differences from `theta` itself): evaluated once for all of them, not once a
    /// column. `None` when every one is central.
    fn residuals_here(
        &self,
        theta: &[f64],
        mut ks: impl Iterator<Item = usize>,
    ) -> Result<Option<Vec<f64>>, EvalError> {
        let one_sided =
            |k: usize| !self.layout.effects()[self.owner[self.active[k]]].is_nonsmooth();
        if !ks.any(one_sided) {
            return Ok(None);
        }
        let mut here = vec![0.0; self.rows()];
        self.residuals_into(theta, &mut here)?;
        Ok(Some(here))
    }

    /// Column `k` of the Jacobian (of active parameter `k`) at `theta` into `col` (zero on
    /// entry), from the residuals at its difference's two points; `here`, the residuals at
    /// `theta` when they are already made ([`FitProblem::residuals_here`]). The rows of groups
    /// the parameter does not touch stay 0.
    pub(super) fn jacobian_column(
        &self,
        theta: &[f64],
        k: usize,
        col: &mut [f64],
        here: Option<&[f64]>,
    ) -> Result<(), EvalError> {
        let j = self.active[k];
        let (point, lower, span, touched) = self.shifted(theta, j);
        let groups = (!touched.iter().all(|&t| t)).then_some(touched.as_slice());
        self.residuals_of_groups(&point, col, groups)?;
        let made;
        let r_from = match (&lower, here) {
            (None, Some(h)) => h,
            _ => {
                let mut r = vec![0.0; col.len()];
                self.residuals_of_groups(lower.as_deref().unwrap_or(theta), &mut r, groups)?;
                made = r;
                &made[..]
            }
        };
        let rows = self.weighting.rows_per_shot();
        let shots = col.chunks_mut(rows).zip(r_from.chunks(rows));
        for ((c, r0), &g) in shots.zip(&self.data.group_of) {
            if touched[g] {
                for (c, r0) in c.iter_mut().zip(r0) {
                    *c = (*c - r0) / span;
                }
            }
        }
        Ok(())
    }

    /// [`FitProblem::jacobian_full`] in one pass (see the module docs), the columns whose shifted
    /// models have another face than the cache's (or user-defined loft or face terms) taken one
    /// at a time after it; or `None` when it cannot be done that way: no site cache, a shifted
    /// model that cannot be built, no column for the pass, or a shot that cannot be computed.
    /// The caller then takes every column one at a time, which gives the same bits or reports
    /// the error.
    pub(super) fn jacobian_on_lanes(&self, theta: &[f64]) -> Option<DMatrix<f64>> {
        let cache = self.cache()?;
        if self.active.is_empty() {
            return Some(DMatrix::zeros(self.rows(), 0));
        }
        // Every group's model at `theta` must exist, as the column-by-column Jacobian needs.
        let base = self.models(theta).ok()?;
        // The face the pass solves on: the models' at `theta` when they share one (with face
        // radii fitted it is not the club's, whose contact frames the cache holds: each site's
        // frame is then made on this face, as the residuals make it), else the cache's.
        let shared = match base.first() {
            Some(m) if base.iter().all(|o| o.face() == m.face()) => m.face(),
            _ => &cache.face,
        };
        let face = (*shared != cache.face).then_some(shared);
        let mut columns = Vec::with_capacity(self.active.len());
        let usable = |m: &ImpactModel| !m.laws().user.sets_orientation() && m.face() == shared;
        // Active parameters whose column is taken on the lanes in the one pass (`true`), or one
        // column at a time (a shifted model with another face than the cache's, e.g. a
        // `face_curvature` parameter: the same bits either way, the residuals re-make the
        // contact frames on that face).
        let mut on_lanes = Vec::with_capacity(self.active.len());
        // The model at `theta` is solved beside every column's.
        if !base.iter().all(usable) {
            return None;
        }
        for &j in &self.active {
            let (point, lower, span, touched) = self.shifted(theta, j);
            let minus = match lower {
                Some(l) => Some(self.models_of(&l, &touched).ok()?),
                None => None,
            };
            let column = Column {
                span,
                plus: self.models_of(&point, &touched).ok()?,
                minus,
                touched,
            };
            let lane = column
                .plus
                .iter()
                .chain(column.minus.iter().flatten())
                .flatten()
                .all(usable);
            on_lanes.push(lane);
            if lane {
                columns.push(column);
            }
        }
        if columns.is_empty() {
            return None;
        }
        let n = self.data.len();
        // Each task writes its shots' rows of every lane column in place: lane column k's rows
        // of task t are `parts[t][k]`; the other columns are made after the pass.
        let (m, seg) = (self.rows(), SHOTS_PER_TASK * self.weighting.rows_per_shot());
        let mut jac = DMatrix::zeros(m, self.active.len());
        let mut parts: Vec<Vec<&mut [f64]>> = (0..n.div_ceil(SHOTS_PER_TASK))
            .map(|_| Vec::with_capacity(columns.len()))
            .collect();
        let mut apart = Vec::new();
        for (k, col) in jac.as_mut_slice().chunks_mut(m).enumerate() {
            if !on_lanes[k] {
                apart.push((k, col));
                continue;
            }
            for (t, rows) in col.chunks_mut(seg).enumerate() {
                parts[t].push(rows);
            }
        }
        let task = |(t, mut out): (usize, Vec<&mut [f64]>)| {
            let at = (&base[..], &columns[..]);
            self.jacobian_block(at, (cache, face), t * SHOTS_PER_TASK, &mut out)
        };
        // Split by size alone: below it the lane vectors of a task finish sooner than waking,
        // stealing and joining threads takes (a 600-shot, 5-parameter calibration: 2.01 ms
        // with its Jacobian split, 1.52 ms on one thread, `cargo bench --bench calibrate`,
        // 26 Nov 2026); the same bits either way.
        let done = if self.worth_splitting() {
            parts.into_par_iter().enumerate().all(task)
        } else {
            parts.into_iter().enumerate().all(task)
        };
        if !done {
            return None;
        }
        let here = self
            .residuals_here(theta, apart.iter().map(|(k, _)| *k))
            .ok()?;
        for (k, col) in apart {
            self.jacobian_column(theta, k, col, here.as_deref()).ok()?;
        }
        Some(jac)
    }

    /// The Jacobian rows of the shots `start..` (at most [`SHOTS_PER_TASK`]) into `out` (one
    /// slice a column, zero on entry); `false` if a shot cannot be computed. Runs the lane type
    /// of the problem's [`SimdLevel`], as the residuals do (the same bits on every path).
    fn jacobian_block(
        &self,
        columns: (&[ImpactModel], &[Column]),
        cache: (&SiteCache, Option<&FaceGeometry>),
        start: usize,
        out: &mut [&mut [f64]],
    ) -> bool {
        match self.level {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: `self.level` is at most `simd_level()`, which reports AVX-512F only when
            // the CPU (and operating system) have it.
            SimdLevel::Avx512 => unsafe { self.jacobian_block_avx512(columns, cache, start, out) },
            #[cfg(target_arch = "x86_64")]
            // SAFETY: as above, AVX2.
            SimdLevel::Avx2 => unsafe { self.jacobian_block_avx2(columns, cache, start, out) },
            _ => self.jacobian_block_portable(columns, cache, start, out),
        }
    }

    /// [`FitProblem::jacobian_block_impl`] on the portable lanes [`V`], a function of its own
    /// (see [`FitProblem::lanes_portable`]).
    #[inline(never)]
    fn jacobian_block_portable(
        &self,
        columns: (&[ImpactModel], &[Column]),
        cache: (&SiteCache, Option<&FaceGeometry>),
        start: usize,
        out: &mut [&mut [f64]],
    ) -> bool {
        self.jacobian_block_impl::<V>(columns, cache, start, out)
            .is_some()
    }

    /// [`FitProblem::jacobian_block_impl`] on [`F64x8`], compiled for AVX-512F.
    ///
    /// # Safety
    /// The CPU must have AVX-512F.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f")]
    unsafe fn jacobian_block_avx512(
        &self,
        columns: (&[ImpactModel], &[Column]),
        cache: (&SiteCache, Option<&FaceGeometry>),
        start: usize,
        out: &mut [&mut [f64]],
    ) -> bool {
        self.jacobian_block_impl::<F64x8>(columns, cache, start, out)
            .is_some()
    }

    /// [`FitProblem::jacobian_block_impl`] on [`F64x4`], compiled for AVX2.
    ///
    /// # Safety
    /// The CPU must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn jacobian_block_avx2(
        &self,
        columns: (&[ImpactModel], &[Column]),
        cache: (&SiteCache, Option<&FaceGeometry>),
        start: usize,
        out: &mut [&mut [f64]],
    ) -> bool {
        self.jacobian_block_impl::<F64x4>(columns, cache, start, out)
            .is_some()
    }

    /// The body of [`FitProblem::jacobian_block`]: shots taken group by group as the residuals
    /// take them, each vector of [`Lanes::N`] shots solved by the shifted models of the columns that
    /// touch its group, then `(r⁺ − r⁻) / span` per row.
    #[inline(always)]
    fn jacobian_block_impl<L: Lanes>(
        &self,
        (base, columns): (&[ImpactModel], &[Column]),
        (cache, face): (&SiteCache, Option<&FaceGeometry>),
        start: usize,
        block: &mut [&mut [f64]],
    ) -> Option<()> {
        let rows = self.weighting.rows_per_shot();
        let end = (start + SHOTS_PER_TASK).min(self.data.len());
        let group_of = &self.data.group_of;
        let mut order = [0usize; SHOTS_PER_TASK];
        let order = &mut order[..end - start];
        for (o, i) in order.iter_mut().zip(start..end) {
            *o = i;
        }
        // Keys are distinct, so the unstable sort (which does not allocate) keeps file order
        // within a group.
        order.sort_unstable_by_key(|&i| (group_of[i], i));
        // Per group run: the model at `θ` first, then each touching column's upper point's
        // model and, for a central difference, its lower point's; `at[q]` the positions of
        // column `which[q]`'s two models (0: the model at `θ`).
        let mut models: Vec<&ImpactModel> = Vec::with_capacity(1 + 2 * columns.len());
        let mut which = Vec::with_capacity(columns.len());
        let mut at = Vec::with_capacity(columns.len());
        let mut frames: Vec<FrameLanes<L>> = Vec::with_capacity(1 + 2 * columns.len());
        let mut outs = vec![LanePrediction::<L>::zero(); 1 + 2 * columns.len()];
        let mut rows_of = vec![[[0.0; 5]; MAX_LANES]; 1 + 2 * columns.len()];
        for run in order.chunk_by(|&a, &b| group_of[a] == group_of[b]) {
            let g = group_of[run[0]];
            models.clear();
            which.clear();
            at.clear();
            models.push(&base[g]);
            for (k, c) in columns.iter().enumerate().filter(|(_, c)| c.touched[g]) {
                which.push(k);
                models.push(c.plus[g].as_ref()?);
                let upper = models.len() - 1;
                let lower = match &c.minus {
                    Some(m) => {
                        models.push(m[g].as_ref()?);
                        models.len() - 1
                    }
                    None => 0,
                };
                at.push((upper, lower));
            }
            if which.is_empty() {
                continue;
            }
            let outs = &mut outs[..models.len()];
            let n = L::N;
            self.prefetch_shots(cache, &run[..run.len().min(n)]);
            for (v, shots) in run.chunks(n).enumerate() {
                let next = run
                    .get((v + 1) * n..)
                    .map_or(&[][..], |r| &r[..r.len().min(n)]);
                self.prefetch_shots(cache, next);
                let idx = padded(shots);
                let sites = (cache, face);
                if !self.predict_lanes_multi(&models, sites, &idx[..n], &mut frames, outs) {
                    return None;
                }
                // Every model's rows of the vector's shots, then each column's difference.
                for (m, out) in outs.iter().enumerate() {
                    let p = out.lanewise();
                    for (l, &i) in shots.iter().enumerate() {
                        let r = &mut rows_of[m][l][..rows];
                        self.write_rows(i, &p.launch(l), &p.ball(l, false), &p.ball(l, true), r);
                    }
                }
                for (&k, &(upper, lower)) in which.iter().zip(at.iter()) {
                    let span = columns[k].span;
                    for (l, &i) in shots.iter().enumerate() {
                        let (a, b) = (&rows_of[upper][l][..rows], &rows_of[lower][l][..rows]);
                        let out = &mut block[k][(i - start) * rows..][..rows];
                        for ((o, a), b) in out.iter_mut().zip(a).zip(b) {
                            *o = (a - b) / span;
                        }
                    }
                }
            }
        }
        Some(())
    }
}

/// The two points of a parameter's difference at `value` within `[lower, upper]`, with
/// `h = FD_STEP_OF_RANGE · (upper − lower)`: the shifted value and the one it is differenced
/// from (`None`: `value` itself). A forward difference, `value + h` (or `value − h` where that
/// would leave the upper bound, then differenced upwards from it); a central one, `value ± h`
/// kept within the bounds (`central`), for the friction coefficient, whose χ² has a corner
/// where shots change between sticking and slipping (a one-sided difference there is the slope
/// of one side only, and the fits near it did not converge). Where neither step fits within
/// the bounds (an unbounded range), the farther bound.
pub(crate) fn difference_points(
    central: bool,
    value: f64,
    lower: f64,
    upper: f64,
) -> (f64, Option<f64>) {
    let h = FD_STEP_OF_RANGE * (upper - lower);
    if central {
        return ((value + h).min(upper), Some((value - h).max(lower)));
    }
    if value + h <= upper {
        (value + h, None)
    } else if value - h >= lower {
        (value, Some(value - h))
    } else if upper - value >= value - lower {
        (upper, None)
    } else {
        (value, Some(lower))
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    /// A forward difference inside the bounds, downwards at the upper bound, central (kept
    /// within the bounds) for the friction coefficient, and the farther bound where the range
    /// is too wide for a finite step.
    #[test]
    fn difference_points_follow_the_documented_rule() {
        use super::difference_points;
        let h = super::FD_STEP_OF_RANGE * 10.0;
        assert_eq!(difference_points(false, 2.0, 0.0, 10.0), (2.0 + h, None));
        assert_eq!(
            difference_points(false, 10.0, 0.0, 10.0),
            (10.0, Some(10.0 - h))
        );
        assert_eq!(
            difference_points(true, 2.0, 0.0, 10.0),
            (2.0 + h, Some(2.0 - h))
        );
        assert_eq!(difference_points(true, 0.0, 0.0, 10.0), (h, Some(0.0)));
        let (to, from) = difference_points(false, 1.0, -f64::MAX, f64::MAX);
        assert!(to.is_finite() && from.is_none_or(f64::is_finite));
        assert_eq!((to, from), (f64::MAX, None));
    }

    use nalgebra::DVector;

    use crate::fit::{parse_effect_list, FitData, FitProblem, ParamLayout, Weighting};
    use crate::measurement::ImpactNoise;

    /// The one-pass Jacobian is the column-by-column one bit for bit: per-group and global
    /// parameters, a loft bias (whose shifted models make their own delivery frames), face
    /// radii (whose shifted models have another face: those columns are taken apart), with and
    /// without impact-location noise (split over threads with it: 240 shots × 9 nodes is above
    /// the split size), the columns serial and parallel.
    #[test]
    fn one_pass_is_the_columns_bit_for_bit() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut cfg = crate::synth::read_config(&root.join("configs/synth/paper_world.toml"))
            .expect("paper world reads");
        cfg.golfers = 8;
        let club = crate::data::club_file::read_club(&root.join("configs/clubs/paper_driver.toml"))
            .expect("club reads");
        let run = crate::synth::generate(&cfg, &club).expect("world generates");
        let shots: Vec<_> = run.shots.iter().map(|s| s.to_shot()).collect();
        let list =
            parse_effect_list("added_mass@group,ball_offset,loft_bias,cor_level,face_curvature")
                .unwrap();
        for noise in [None, Some(ImpactNoise::from_mm(2.0, 2.0).unwrap())] {
            let data = FitData::from_shots(&shots)
                .unwrap()
                .with_impact_noise(noise)
                .unwrap();
            let layout = ParamLayout::from_requests(&list, &data.groups).unwrap();
            // Away from the defaults, with the loft bias off the club's (no cached frames).
            let theta = DVector::from_fn(layout.len(), |j, _| {
                let (lo, hi) = (layout.lower()[j], layout.upper()[j]);
                layout.defaults()[j] + 0.01 * (j as f64 + 1.0) * (hi - lo) / 7.0
            });
            for parallel in [false, true] {
                let w = Weighting::launch(&[1.4, 1.0, 0.7, 400.0, 190.0]);
                let pr = FitProblem::new(&club, layout.clone(), &data, w)
                    .with_parallel_jacobian(parallel);
                // Both of the one-pass Jacobian's paths are taken: on one thread without noise,
                // split over threads with it.
                assert_eq!(pr.worth_splitting(), noise.is_some());
                let one = pr
                    .jacobian_on_lanes(theta.as_slice())
                    .expect("lanes take it");
                let cols = pr.jacobian_by_columns(&theta).unwrap();
                assert_eq!(one.shape(), cols.shape());
                assert!(one.iter().any(|v| *v != 0.0));
                for (a, b) in one.iter().zip(cols.iter()) {
                    assert_eq!(a.to_bits(), b.to_bits(), "noise {noise:?}");
                }
            }
        }
    }

    /// Every lane type this machine runs (portable, AVX2, AVX-512) gives the same residuals and
    /// Jacobians, bit for bit, with the laws' optional branches switched on (friction slip, the
    /// power-law COR, the tangential compliance, a finite contact), with and without location
    /// noise, away from the defaults.
    #[test]
    fn every_lane_type_gives_the_same_bits() {
        use crate::lanes::{simd_level, SimdLevel};
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut cfg = crate::synth::read_config(&root.join("configs/synth/paper_world.toml"))
            .expect("paper world reads");
        cfg.golfers = 5;
        let club = crate::data::club_file::read_club(&root.join("configs/clubs/paper_driver.toml"))
            .expect("club reads");
        let run = crate::synth::generate(&cfg, &club).expect("world generates");
        let shots: Vec<_> = run.shots.iter().map(|s| s.to_shot()).collect();
        eprintln!("this machine runs {:?}", simd_level());
        for effects in [
            "added_mass@group,ball_offset,face_bias",
            "friction,cor_power,tangential_compliance,contact_time,com_offset",
        ] {
            let list = parse_effect_list(effects).unwrap();
            for noise in [None, Some(ImpactNoise::from_mm(2.0, 2.0).unwrap())] {
                let data = FitData::from_shots(&shots)
                    .unwrap()
                    .with_impact_noise(noise)
                    .unwrap();
                let layout = ParamLayout::from_requests(&list, &data.groups).unwrap();
                let theta = DVector::from_fn(layout.len(), |j, _| {
                    let (lo, hi) = (layout.lower()[j], layout.upper()[j]);
                    layout.defaults()[j] + 0.013 * (j as f64 + 1.0) * (hi - lo) / 7.0
                });
                let w = Weighting::launch(&[1.4, 1.0, 0.7, 400.0, 190.0]);
                let at = |level: SimdLevel| {
                    let pr =
                        FitProblem::new(&club, layout.clone(), &data, w).with_simd_level(level);
                    let r = pr.residuals(theta.as_slice()).expect("residuals");
                    let j = pr
                        .jacobian_on_lanes(theta.as_slice())
                        .expect("lanes take it");
                    (r, j)
                };
                let (r0, j0) = at(SimdLevel::Portable);
                assert!(j0.iter().any(|v| *v != 0.0));
                for level in SimdLevel::ALL {
                    let (r, j) = at(level);
                    let same = |a: &[f64], b: &[f64]| {
                        a.len() == b.len()
                            && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
                    };
                    assert!(
                        same(r.as_slice(), r0.as_slice()),
                        "{effects} {noise:?} {level:?}"
                    );
                    assert!(
                        same(j.as_slice(), j0.as_slice()),
                        "{effects} {noise:?} {level:?}"
                    );
                }
            }
        }
    }
}
