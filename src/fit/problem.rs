//! The least-squares problem: shots and a club in, residuals of the model out, as an argmin
//! [`Operator`] (residual vector) and [`Jacobian`] (forward finite differences).
//!
//! Residuals come in three forms ([`Weighting`]):
//!
//! - **Whitened launch** (the default fit): `r_{i,c} = (ŷ_{i,c}(θ) − y_{i,c}) / σ_c` for each
//!   shot `i` and launch component `c` in file units (mph, deg, rpm), with `σ_c` the noise scale
//!   of the component. Then `χ² = Σ r²`.
//! - **Paper, linear** (`W = ∞` in the paper's Eq. 11): `r_i = v_b,sim − v_b,exp`, the ball
//!   velocity vector in G, m/s (3 rows a shot).
//! - **Paper, angular** (`W = 0`): `r_i = ω_b,sim − ω_b,exp` restricted to the measured spin
//!   axes `(ω_y, ω_z)` in G, rad/s (2 rows a shot; a launch monitor does not measure rifle spin).
//!
//! The Jacobian is by forward differences, `∂r/∂θ_j ≈ (r(θ + h_j e_j) − r(θ)) / h_j`, with
//! `h_j = 1e-4 · (upper_j − lower_j)` (for example 0.03 g of added mass, 2 µm of ball offset,
//! 3 mdeg of loft bias); where `θ_j + h_j` would leave the upper bound the step is taken
//! downwards. The friction coefficient keeps central differences, `(r(θ + h_j e_j) −
//! r(θ − h_j e_j)) / (2 h_j)` within the bounds: its χ² has a corner where shots change
//! between sticking and slipping ([`difference_points`]). A forward difference's truncation
//! error, `h_j/2 · ∂²r/∂θ_j²`, is about 1e-4 of a column's largest entry for a parameter whose
//! effect bends over its range, far inside what the data determine (a standard error moves in
//! its fourth or fifth figure), and it costs `p + 1` models a site where central differences
//! cost `2p`: at real scale the Jacobians are most of a diagnosis's work. On the
//! lanes the model at `θ` and the `p` shifted models are solved in one pass over the shots,
//! each site's inputs read once for all of them (`problem/jacobian.rs`; the same bits as two
//! evaluations a column). The model for each group is built once per evaluation; the per-shot
//! loop does not allocate. A column of a per-group parameter is evaluated on that group's
//! shots only (the others' differences are exactly zero).
//!
//! Everything that does not depend on the fitted parameters is computed once per data set
//! ([`FitData`] keeps it): each shot's face orientation and clubhead velocities in the face frame
//! ([`ImpactModel::delivery_frame`], reused while the loft and face biases are those of the club).
//! An evaluation then runs only the second half of [`ImpactModel::solve`], on a lane vector of
//! shots of one group at a time (8 with AVX-512, 4 otherwise): the contact frame at each impact location or quadrature node
//! ([`crate::physics::FaceGeometry::contact_on`], the face equations of the scalar solve, generic
//! over the lane type: computing it costs less than reading a stored one from memory),
//! [`ImpactModel::solve_contact`] (the contact mechanics the scalar solve itself runs, generic
//! over the lane type) on the lanes, the rotation to `G`, and the launch angles by the
//! branch-free [`crate::sweep::fastmath::atan2_v`] and [`crate::sweep::fastmath::hypot_v`] instead
//! of libm's. That evaluation (`problem/lanes.rs`) is written once over
//! [`crate::lanes::Lanes`] and compiled for AVX-512 (`__m512d`), AVX2 (`__m256d`) and the portable
//! lanes, the widest this machine runs picked at run time; all give the same bits. The
//! residuals agree with solving each shot afresh to rounding (`tests/fit_batched.rs` holds them to
//! 1e-9 relative; in practice a few ulp), and a shot's result does not depend on its lane or
//! neighbours. Large data sets are evaluated in parallel chunks of shots; when any shot of a chunk
//! cannot be computed the chunk is evaluated one shot at a time by the scalar solve, so the first
//! failing shot in file order is reported.

use argmin::core::{Error as ArgminError, Jacobian, Operator};
use nalgebra::{DMatrix, DVector, Vector3};

use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

pub use super::data::FitData;
use super::data::SiteCache;
use super::spec::ParamLayout;
use crate::club::ClubSpec;
use crate::lanes::{simd_level, SimdLevel};
use crate::measurement::{expected_over, NODES_PER_SHOT};
use crate::physics::{ImpactError, ImpactModel, Launch, LaunchComponent, ModelParams, ParamError};

mod jacobian;
pub(crate) use jacobian::difference_points;
mod lanes;

/// Relative finite-difference step: `h_j = FD_STEP_OF_RANGE · (upper_j − lower_j)`.
pub const FD_STEP_OF_RANGE: f64 = 1e-4;

/// Fewest evaluation sites (shots × location nodes) for which a residual evaluation is split
/// over threads.
const PARALLEL_MIN_SITES: usize = 2048;

/// Shots per parallel task of a residual evaluation.
pub(crate) const SHOTS_PER_TASK: usize = 128;

/// Residual evaluations the lanes refused by design (a model whose law has no lane form: a
/// user-defined loft or face-angle term), whose shots then went one at a time through the scalar
/// solve, since the process started.
pub(crate) static LANE_REFUSALS: AtomicU64 = AtomicU64::new(0);
/// Shots evaluated one at a time by the scalar solve for any reason: a refusal above, or a lane
/// vector holding a shot that cannot be computed (off the face, not approaching; the scalar
/// solve then names the first such shot).
static SCALAR_SHOTS: AtomicU64 = AtomicU64::new(0);

/// How often the fits left the lanes since the process started: the guard that every library
/// effect (and every user-defined one but a loft or face-angle term) is evaluated on the lanes
/// (`tests/lane_path.rs` runs a diagnose over every library effect and asserts no refusal).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ScalarPathCounts {
    /// Residual evaluations the lanes refused because a law has no lane form.
    pub refusals: u64,
    /// Shots evaluated one at a time by the scalar solve (refusals, and shots the lanes could
    /// not compute).
    pub shots: u64,
}

/// The counts so far ([`ScalarPathCounts`]).
pub fn scalar_path_counts() -> ScalarPathCounts {
    ScalarPathCounts {
        refusals: LANE_REFUSALS.load(Ordering::Relaxed),
        shots: SCALAR_SHOTS.load(Ordering::Relaxed),
    }
}

/// How model − measured becomes residual rows (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Weighting {
    /// `(ŷ − y)/σ_c` for the five launch components; holds `1/σ_c` in 1/file unit.
    Launch {
        /// Inverse noise scale per component.
        inv_scale: [f64; 5],
    },
    /// Ball velocity error vector, m/s (the paper's `W = ∞` stage).
    PaperLinear,
    /// Ball spin error about G's `y` and `z`, rad/s (the paper's `W = 0` stage).
    PaperAngular,
}

impl Weighting {
    /// Whitened launch residuals with noise scales `sigma` (file units).
    pub fn launch(sigma: &[f64; 5]) -> Self {
        Self::Launch {
            inv_scale: sigma.map(|s| 1.0 / s),
        }
    }

    /// Residual rows per shot.
    pub fn rows_per_shot(&self) -> usize {
        match self {
            Self::Launch { .. } => 5,
            Self::PaperLinear => 3,
            Self::PaperAngular => 2,
        }
    }
}

/// Why the model cannot be evaluated at some parameter values.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EvalError {
    /// The parameters of a group are not physical.
    #[error("group '{group}': {source}")]
    Model {
        /// Group.
        group: String,
        /// Problem.
        source: ParamError,
    },
    /// One shot cannot be computed.
    #[error("shot '{shot_id}': {source}")]
    Shot {
        /// Shot id.
        shot_id: String,
        /// Problem.
        source: ImpactError,
    },
}

/// The residual problem handed to the solver: club, free effects, shots and weighting.
///
/// The solver's vector is the subset `active` of the full parameter vector `θ` (physical file
/// units); the other entries stay at `theta_fixed`. By default every parameter is active.
#[derive(Debug, Clone)]
pub struct FitProblem<'a> {
    data: &'a FitData,
    layout: ParamLayout,
    /// Per group: nominal parameters with the club's own effects applied.
    base_params: Vec<ModelParams>,
    /// Per group: indices of the free effects that apply.
    applies: Vec<Vec<usize>>,
    weighting: Weighting,
    active: Vec<usize>,
    theta_fixed: DVector<f64>,
    lower: DVector<f64>,
    upper: DVector<f64>,
    /// Effect index of each parameter of `θ`.
    owner: Vec<usize>,
    parallel_jacobian: bool,
    /// The lane code path of the batched evaluations ([`crate::lanes::simd_level`] unless a
    /// test chose another; every path gives the same bits).
    level: SimdLevel,
}

impl<'a> FitProblem<'a> {
    /// A problem over every parameter of `layout`, starting values at their defaults.
    pub fn new(
        club: &ClubSpec,
        layout: ParamLayout,
        data: &'a FitData,
        weighting: Weighting,
    ) -> Self {
        let base_params: Vec<ModelParams> = data
            .groups
            .iter()
            .map(|g| club.params_for_group(g))
            .collect();
        let applies = data
            .groups
            .iter()
            .map(|g| {
                (0..layout.effects().len())
                    .filter(|&i| layout.effects()[i].applies_to(g))
                    .collect()
            })
            .collect();
        let theta_fixed = layout.defaults();
        let (lower, upper) = (layout.lower(), layout.upper());
        let owner = layout.params().map(|(i, _)| i).collect();
        Self {
            data,
            active: (0..layout.len()).collect(),
            layout,
            base_params,
            applies,
            weighting,
            theta_fixed,
            lower,
            upper,
            owner,
            parallel_jacobian: false,
            level: simd_level(),
        }
    }

    /// Free only the parameters `active` (indices into `θ`); the rest stay at `theta_fixed`.
    pub fn with_active(mut self, active: Vec<usize>, theta_fixed: DVector<f64>) -> Self {
        assert!(active.iter().all(|&j| j < self.layout.len()));
        assert_eq!(theta_fixed.len(), self.layout.len());
        self.active = active;
        self.theta_fixed = theta_fixed;
        self
    }

    /// Compute the column-by-column Jacobian's columns in parallel (worth it when the fit is
    /// not itself one of many parallel jobs: each column's evaluations are scalar solves). The
    /// one-pass Jacobian on the lanes splits by size alone, as a residual evaluation does.
    pub fn with_parallel_jacobian(mut self, on: bool) -> Self {
        self.parallel_jacobian = on;
        self
    }

    /// Evaluate on the lanes of `level` (or the widest level below it this machine runs):
    /// every level gives the same bits, which tests check by running each.
    pub fn with_simd_level(mut self, level: SimdLevel) -> Self {
        self.level = level.or_supported();
        self
    }

    /// Change the weighting.
    pub fn with_weighting(mut self, weighting: Weighting) -> Self {
        self.weighting = weighting;
        self
    }

    /// The layout.
    pub fn layout(&self) -> &ParamLayout {
        &self.layout
    }

    /// The shots.
    pub fn data(&self) -> &FitData {
        self.data
    }

    /// Active parameter indices.
    pub fn active(&self) -> &[usize] {
        &self.active
    }

    /// Lower bounds of the active parameters.
    pub fn active_lower(&self) -> DVector<f64> {
        DVector::from_iterator(
            self.active.len(),
            self.active.iter().map(|&j| self.lower[j]),
        )
    }

    /// Upper bounds of the active parameters.
    pub fn active_upper(&self) -> DVector<f64> {
        DVector::from_iterator(
            self.active.len(),
            self.active.iter().map(|&j| self.upper[j]),
        )
    }

    /// Full `θ` from the active sub-vector.
    pub fn full_theta(&self, active_values: &[f64]) -> DVector<f64> {
        let mut theta = self.theta_fixed.clone();
        for (&j, &v) in self.active.iter().zip(active_values) {
            theta[j] = v;
        }
        theta
    }

    /// Active sub-vector of a full `θ`.
    pub fn active_part(&self, theta: &DVector<f64>) -> DVector<f64> {
        DVector::from_iterator(self.active.len(), self.active.iter().map(|&j| theta[j]))
    }

    /// Evaluation sites of one residual evaluation: shots × impact-location nodes.
    fn sites(&self) -> usize {
        self.data.len()
            * if self.data.impact_nodes.is_some() {
                NODES_PER_SHOT
            } else {
                1
            }
    }

    /// Whether an evaluation of this size is worth splitting over threads
    /// ([`PARALLEL_MIN_SITES`]).
    fn worth_splitting(&self) -> bool {
        self.sites() >= PARALLEL_MIN_SITES
    }

    /// Number of residual rows.
    pub fn rows(&self) -> usize {
        self.data.len() * self.weighting.rows_per_shot()
    }

    /// One validated model per group for full parameters `theta`.
    pub fn models(&self, theta: &[f64]) -> Result<Vec<ImpactModel>, EvalError> {
        (0..self.data.groups.len())
            .map(|g| self.model_of(theta, g))
            .collect()
    }

    /// The validated model of group `g` for full parameters `theta`.
    fn model_of(&self, theta: &[f64], g: usize) -> Result<ImpactModel, EvalError> {
        let mut p = self.base_params[g].clone();
        for &i in &self.applies[g] {
            self.layout.effects()[i]
                .kind
                .apply(&theta[self.layout.range(i)], &mut p);
        }
        ImpactModel::new(p).map_err(|source| EvalError::Model {
            group: self.data.groups[g].clone(),
            source,
        })
    }

    /// [`FitProblem::models`] for the groups flagged in `groups` only (`None` for the others):
    /// a Jacobian column of a per-group parameter needs its group's models alone.
    fn models_of(
        &self,
        theta: &[f64],
        groups: &[bool],
    ) -> Result<Vec<Option<ImpactModel>>, EvalError> {
        groups
            .iter()
            .enumerate()
            .map(|(g, &on)| on.then(|| self.model_of(theta, g)).transpose())
            .collect()
    }

    /// Model − measured for every shot in file units (mph, deg, deg, rpm, rpm), full `theta`:
    /// the launch residuals with unit noise scales (`(ŷ − y)·1` is `ŷ − y` exactly), so
    /// evaluated on the lanes like every residual.
    pub fn launch_errors(&self, theta: &[f64]) -> Result<Vec<[f64; 5]>, EvalError> {
        let unit = Self {
            weighting: Weighting::Launch {
                inv_scale: [1.0; 5],
            },
            ..self.clone()
        };
        let mut rows = vec![0.0; self.data.len() * 5];
        unit.residuals_into(theta, &mut rows)?;
        Ok(rows
            .chunks_exact(5)
            .map(|r| std::array::from_fn(|c| r[c]))
            .collect())
    }

    /// The data's shared evaluation parts, built with the club's own model of the first group.
    fn cache(&self) -> Option<&SiteCache> {
        self.data
            .site_cache(|| ImpactModel::new(self.base_params.first()?.clone()).ok())
    }

    /// Predicted launch (SI), ball velocity and spin (G) of shot `i`: the model at the measured
    /// delivery, or its average over the posterior of the true impact location. The same bits
    /// as [`crate::measurement::expected_outcome`], from the cached frames where they apply.
    #[inline]
    fn predict(
        &self,
        models: &[ImpactModel],
        cache: Option<&SiteCache>,
        i: usize,
    ) -> Result<(Launch, Vector3<f64>, Vector3<f64>), EvalError> {
        let model = &models[self.data.group_of[i]];
        let d = &self.data.deliveries[i];
        let nodes = self.data.impact_nodes.as_ref().map(|n| &n[i]);
        let at = |k: usize| match nodes {
            Some(n) => (n[k].y_m, n[k].z_m),
            None => (d.impact_y_m, d.impact_z_m),
        };
        let fresh;
        let frame = match cache {
            Some(c) if c.frames_fit(model) => &c.frames[i],
            Some(c) => {
                fresh = model.delivery_frame_from(d, &c.trig[i]);
                &fresh
            }
            None => {
                fresh = model.delivery_frame(d);
                &fresh
            }
        };
        expected_over(nodes, |k| {
            let (y, z) = at(k);
            let cf = model.face().contact(y, z)?;
            model.solve_in(frame, &cf, y, z)
        })
        .map_err(|source| EvalError::Shot {
            shot_id: self.data.ids[i].to_string(),
            source,
        })
    }

    /// Residuals at full `theta` into `out` (length [`FitProblem::rows`]).
    pub fn residuals_into(&self, theta: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        self.residuals_of_groups(theta, out, None)
    }

    /// Residuals at full `theta` into `out` for the shots of the groups flagged in `groups`
    /// (all shots when `None`); the rows of other shots are left as they are.
    fn residuals_of_groups(
        &self,
        theta: &[f64],
        out: &mut [f64],
        groups: Option<&[bool]>,
    ) -> Result<(), EvalError> {
        let models = self.models(theta)?;
        let cache = self.cache();
        let rows = self.weighting.rows_per_shot();
        debug_assert_eq!(out.len(), self.rows());
        let task = |(t, chunk): (usize, &mut [f64])| -> Result<(), EvalError> {
            let start = t * SHOTS_PER_TASK;
            if let Some(c) = cache {
                if self.residuals_on_lanes(&models, c, start, chunk, groups) {
                    return Ok(());
                }
            }
            // No cache (no valid club model to build it with), or a shot of the chunk cannot be
            // computed: one shot at a time, in file order, so the error is the first failing
            // shot's.
            for (k, r) in chunk.chunks_exact_mut(rows).enumerate() {
                let i = start + k;
                if groups.is_some_and(|g| !g[self.data.group_of[i]]) {
                    continue;
                }
                SCALAR_SHOTS.fetch_add(1, Ordering::Relaxed);
                self.residual_rows(&models, cache, i, r)?;
            }
            Ok(())
        };
        if self.worth_splitting() {
            // Collected in order, so the error reported is the first failing shot's.
            let done: Vec<Result<(), EvalError>> = out
                .par_chunks_mut(SHOTS_PER_TASK * rows)
                .enumerate()
                .map(task)
                .collect();
            done.into_iter().collect()
        } else {
            out.chunks_mut(SHOTS_PER_TASK * rows)
                .enumerate()
                .try_for_each(task)
        }
    }

    /// The residual rows of shot `i`.
    #[inline]
    fn residual_rows(
        &self,
        models: &[ImpactModel],
        cache: Option<&SiteCache>,
        i: usize,
        r: &mut [f64],
    ) -> Result<(), EvalError> {
        let (launch, ball_v, ball_w) = self.predict(models, cache, i)?;
        self.write_rows(i, &launch, &ball_v, &ball_w, r);
        Ok(())
    }

    /// The residual rows of shot `i` from its predicted launch (SI), ball velocity and spin (G).
    #[inline]
    fn write_rows(
        &self,
        i: usize,
        launch: &Launch,
        ball_v: &Vector3<f64>,
        ball_w: &Vector3<f64>,
        r: &mut [f64],
    ) {
        match self.weighting {
            Weighting::Launch { inv_scale } => {
                let m = &self.data.measured[i];
                for c in 0..5 {
                    r[c] = (launch.get_file(LaunchComponent::ALL[c]) - m[c]) * inv_scale[c];
                }
            }
            Weighting::PaperLinear => {
                let d = ball_v - self.data.measured_velocity_m_s[i];
                r.copy_from_slice(d.as_slice());
            }
            Weighting::PaperAngular => {
                let m = &self.data.measured_spin_yz_rad_s[i];
                r[0] = ball_w.y - m[0];
                r[1] = ball_w.z - m[1];
            }
        }
    }

    /// Residuals at full `theta`.
    pub fn residuals(&self, theta: &[f64]) -> Result<DVector<f64>, EvalError> {
        let mut out = DVector::zeros(self.rows());
        self.residuals_into(theta, out.as_mut_slice())?;
        Ok(out)
    }
}

impl Operator for FitProblem<'_> {
    type Param = DVector<f64>;
    type Output = DVector<f64>;

    fn apply(&self, active_values: &Self::Param) -> Result<Self::Output, ArgminError> {
        let theta = self.full_theta(active_values.as_slice());
        Ok(self.residuals(theta.as_slice())?)
    }
}

impl Jacobian for FitProblem<'_> {
    type Param = DVector<f64>;
    type Jacobian = DMatrix<f64>;

    fn jacobian(&self, active_values: &Self::Param) -> Result<Self::Jacobian, ArgminError> {
        let theta = self.full_theta(active_values.as_slice());
        Ok(self.jacobian_full(&theta)?)
    }
}
