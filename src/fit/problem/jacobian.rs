//! The central-difference Jacobian on the lanes in one pass over the shots: for each vector of
//! [`Lanes::N`](crate::lanes::Lanes::N) shots of one group, each evaluation site's inputs (the location nodes and the contact
//! frames there, the delivery frames) are gathered once and solved by all `2p` shifted models
//! (`θ ± h_j e_j`) before the next site is read. Each model's solution is the same operations on
//! the same inputs as its own evaluation ([`FitProblem::residuals_into`]), so every column is
//! the same bits as from two separate evaluations; what is saved is reading, arranging and
//! computing the inputs `2p − 1` times more per site.

use nalgebra::DMatrix;
use rayon::prelude::*;

use super::lanes::{padded, FrameLanes, LanePrediction};
use super::{FitProblem, SHOTS_PER_TASK};
use crate::fit::data::SiteCache;
#[cfg(target_arch = "x86_64")]
use crate::lanes::{F64x4, F64x8};
use crate::lanes::{Lanes, SimdLevel, V};
use crate::physics::{FaceGeometry, ImpactModel};

/// The two shifted models of one Jacobian column, per group it touches (`None` for the
/// others), and the groups it touches.
struct Column {
    plus: Vec<Option<ImpactModel>>,
    minus: Vec<Option<ImpactModel>>,
    /// `θ_j⁺ − θ_j⁻`.
    span: f64,
    /// Per group: does the parameter change the group's model? (The other groups' rows are 0.)
    touched: Vec<bool>,
}

impl FitProblem<'_> {
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
        for &j in &self.active {
            let (plus, minus, touched) = self.shifted(theta, j);
            let column = Column {
                span: plus[j] - minus[j],
                plus: self.models_of(&plus, &touched).ok()?,
                minus: self.models_of(&minus, &touched).ok()?,
                touched,
            };
            let lane = column
                .plus
                .iter()
                .chain(&column.minus)
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
            self.jacobian_block(&columns, (cache, face), t * SHOTS_PER_TASK, &mut out)
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
        for (k, col) in apart {
            self.jacobian_column(theta, k, col).ok()?;
        }
        Some(jac)
    }

    /// The Jacobian rows of the shots `start..` (at most [`SHOTS_PER_TASK`]) into `out` (one
    /// slice a column, zero on entry); `false` if a shot cannot be computed. Runs the lane type
    /// of the problem's [`SimdLevel`], as the residuals do (the same bits on every path).
    fn jacobian_block(
        &self,
        columns: &[Column],
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
        columns: &[Column],
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
        columns: &[Column],
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
        columns: &[Column],
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
        columns: &[Column],
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
        let mut models: Vec<&ImpactModel> = Vec::with_capacity(2 * columns.len());
        let mut which = Vec::with_capacity(columns.len());
        let mut frames: Vec<FrameLanes<L>> = Vec::with_capacity(2 * columns.len());
        let mut outs = vec![LanePrediction::<L>::zero(); 2 * columns.len()];
        for run in order.chunk_by(|&a, &b| group_of[a] == group_of[b]) {
            let g = group_of[run[0]];
            models.clear();
            which.clear();
            for (k, c) in columns.iter().enumerate().filter(|(_, c)| c.touched[g]) {
                which.push(k);
                models.push(c.plus[g].as_ref()?);
                models.push(c.minus[g].as_ref()?);
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
                let at = (cache, face);
                if !self.predict_lanes_multi(&models, at, &idx[..n], &mut frames, outs) {
                    return None;
                }
                for (q, &k) in which.iter().enumerate() {
                    let (p, m) = (outs[2 * q].lanewise(), outs[2 * q + 1].lanewise());
                    for (l, &i) in shots.iter().enumerate() {
                        let (mut r_plus, mut r_minus) = ([0.0; 5], [0.0; 5]);
                        let rp = &mut r_plus[..rows];
                        self.write_rows(i, &p.launch(l), &p.ball(l, false), &p.ball(l, true), rp);
                        let rm = &mut r_minus[..rows];
                        self.write_rows(i, &m.launch(l), &m.ball(l, false), &m.ball(l, true), rm);
                        let span = columns[k].span;
                        let out = &mut block[k][(i - start) * rows..][..rows];
                        for ((o, a), b) in out.iter_mut().zip(rp.iter()).zip(rm.iter()) {
                            *o = (a - b) / span;
                        }
                    }
                }
            }
        }
        Some(())
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

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
