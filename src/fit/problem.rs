//! The least-squares problem: shots and a club in, residuals of the model out, as an argmin
//! [`Operator`] (residual vector) and [`Jacobian`] (central finite differences).
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
//! The Jacobian is by central differences, `∂r/∂θ_j ≈ (r(θ + h_j e_j) − r(θ − h_j e_j)) /
//! (2 h_j)`, with `h_j = 1e-4 · (upper_j − lower_j)` (for example 0.03 g of added mass,
//! 2 µm of ball offset, 3 mdeg of loft bias); at a bound the difference is taken one-sided
//! inside the bounds. The model for each group is built once per evaluation; the per-shot
//! loop does not allocate. A column of a per-group parameter is evaluated on that group's
//! shots only (the others' differences are exactly zero).
//!
//! Everything that does not depend on the fitted parameters is computed once per data set
//! ([`FitData`] keeps it): each shot's face orientation and clubhead velocities in the face
//! frame ([`ImpactModel::delivery_frame`], reused while the loft and face biases are those of
//! the club), and the face's contact frame at every impact location or quadrature node. An
//! evaluation then runs only the second half of [`ImpactModel::solve`], on [`W`] shots of one
//! group at a time: [`ImpactModel::solve_contact`] (the contact mechanics the scalar solve
//! itself runs, generic over the lane type) on the lanes, the rotation to `G`, and the launch
//! angles by the branch-free [`atan2_v`] and [`hypot_v`] instead of libm's. The residuals agree
//! with solving each shot afresh to rounding (`tests/fit_batched.rs` holds them to 1e-9
//! relative; in practice a few ulp), and a shot's result does not depend on its lane or
//! neighbours. Large data sets are evaluated in parallel chunks of shots; when any shot of a
//! chunk cannot be computed the chunk is evaluated one shot at a time by the scalar solve, so
//! the first failing shot in file order is reported.

use argmin::core::{Error as ArgminError, Jacobian, Operator};
use nalgebra::{DMatrix, DVector, Vector3};
use std::sync::{Arc, OnceLock};

use rayon::prelude::*;

use super::spec::ParamLayout;
use super::FitError;
use crate::club::ClubSpec;
use crate::lanes::{V, W};
use crate::measurement::{expected_over, ImpactNoise, LocationNode, NODES_PER_SHOT};
use crate::model::Shot;
use crate::physics::impact::ContactInputs;
use crate::physics::{
    ContactFrame, Delivery, DeliveryFrame, FaceError, FaceGeometry, ImpactError, ImpactModel,
    Launch, LaunchComponent, ModelParams, ParamError,
};
use crate::sweep::fastmath::{atan2_v, hypot_v};

/// Relative finite-difference step: `h_j = FD_STEP_OF_RANGE · (upper_j − lower_j)`.
pub const FD_STEP_OF_RANGE: f64 = 1e-4;

/// The shots a fit uses, flattened for the inner loop.
#[derive(Debug, Clone, PartialEq)]
pub struct FitData {
    /// Shot ids, for messages.
    pub ids: Vec<String>,
    /// Distinct groups, sorted.
    pub groups: Vec<String>,
    /// Index into `groups` of each shot.
    pub group_of: Vec<usize>,
    /// Golfer of each shot, when known.
    pub golfers: Vec<Option<String>>,
    /// Shaft mass of each shot, g, when known.
    pub shaft_mass_g: Vec<Option<f64>>,
    /// Deliveries, SI.
    pub deliveries: Vec<Delivery>,
    /// Measured launch in file units (mph, deg, deg, rpm, rpm), one array a shot.
    pub measured: Vec<[f64; 5]>,
    /// Measured ball velocity in G, m/s.
    pub measured_velocity_m_s: Vec<Vector3<f64>>,
    /// Measured spin about G's `y` and `z` axes, rad/s (`ω_y = −sidespin`, `ω_z = backspin`).
    pub measured_spin_yz_rad_s: Vec<[f64; 2]>,
    /// Posterior quadrature nodes of each shot's true impact location when the measured
    /// locations are noisy (see [`crate::measurement`]); `None`: locations taken as measured.
    pub impact_nodes: Option<Vec<[LocationNode; NODES_PER_SHOT]>>,
    /// Parameter-independent parts of every evaluation, built on first use (see the module
    /// docs). Built from the fields above: change them only through the methods here.
    cache: OnceLock<Option<Arc<SiteCache>>>,
}

/// What every evaluation of a [`FitData`] shares: per shot the delivery frame for one pair of
/// loft and face biases, per evaluation site (shot, or shot × location node) the face's contact
/// frame for one face geometry.
#[derive(Debug, PartialEq)]
struct SiteCache {
    face: FaceGeometry,
    loft_bias_rad: f64,
    face_bias_rad: f64,
    frames: Vec<DeliveryFrame>,
    /// `sites_per_shot` entries a shot.
    contacts: Vec<Result<ContactFrame, FaceError>>,
    sites_per_shot: usize,
}

impl SiteCache {
    fn build(model: &ImpactModel, data: &FitData) -> Self {
        let frames = data
            .deliveries
            .iter()
            .map(|d| model.delivery_frame(d))
            .collect();
        let face = *model.face();
        let (contacts, sites_per_shot) = match &data.impact_nodes {
            None => (
                data.deliveries
                    .iter()
                    .map(|d| face.contact(d.impact_y_m, d.impact_z_m))
                    .collect(),
                1,
            ),
            Some(nodes) => (
                nodes
                    .iter()
                    .flat_map(|ns| ns.iter().map(move |n| face.contact(n.y_m, n.z_m)))
                    .collect(),
                NODES_PER_SHOT,
            ),
        };
        let p = model.params();
        Self {
            face,
            loft_bias_rad: p.loft_bias_rad,
            face_bias_rad: p.face_bias_rad,
            frames,
            contacts,
            sites_per_shot,
        }
    }

    /// Are the frames valid for `model` (same biases)?
    fn frames_fit(&self, model: &ImpactModel) -> bool {
        let p = model.params();
        p.loft_bias_rad == self.loft_bias_rad && p.face_bias_rad == self.face_bias_rad
    }
}

/// Fewest evaluation sites (shots × location nodes) for which a residual evaluation is split
/// over threads.
const PARALLEL_MIN_SITES: usize = 2048;

/// Shots per parallel task of a residual evaluation.
const SHOTS_PER_TASK: usize = 128;

impl FitData {
    /// Flatten shots that carry measured launch conditions.
    pub fn from_shots(shots: &[Shot]) -> Result<Self, FitError> {
        if shots.is_empty() {
            return Err(FitError::TooFewShots {
                shots: 0,
                params: 0,
            });
        }
        let mut groups: Vec<String> = shots.iter().map(|s| s.group.clone()).collect();
        groups.sort();
        groups.dedup();
        let mut d = Self {
            ids: Vec::with_capacity(shots.len()),
            groups,
            group_of: Vec::with_capacity(shots.len()),
            golfers: Vec::with_capacity(shots.len()),
            shaft_mass_g: Vec::with_capacity(shots.len()),
            deliveries: Vec::with_capacity(shots.len()),
            measured: Vec::with_capacity(shots.len()),
            measured_velocity_m_s: Vec::with_capacity(shots.len()),
            measured_spin_yz_rad_s: Vec::with_capacity(shots.len()),
            impact_nodes: None,
            cache: OnceLock::new(),
        };
        for s in shots {
            let m = s.measured.ok_or(FitError::NoMeasurements)?;
            d.ids.push(s.id.clone());
            d.group_of
                .push(d.groups.binary_search(&s.group).expect("group listed"));
            d.golfers.push(s.golfer.clone());
            d.shaft_mass_g.push(s.delivery.shaft_mass_g);
            d.deliveries.push(s.delivery);
            d.measured.push(m.to_file_units());
            let (sl, cl) = m.launch_angle_rad.sin_cos();
            let (sa, ca) = m.azimuth_rad.sin_cos();
            d.measured_velocity_m_s
                .push(m.ball_speed_m_s * Vector3::new(cl * ca, sl, cl * sa));
            d.measured_spin_yz_rad_s
                .push([-m.sidespin_rad_s, m.backspin_rad_s]);
        }
        Ok(d)
    }

    /// Correct for noise in the measured impact locations (`None`: none). The prior of the true
    /// locations comes from all these shots' measured locations.
    pub fn with_impact_noise(mut self, noise: Option<ImpactNoise>) -> Result<Self, FitError> {
        self.impact_nodes = noise.map(|n| n.nodes_for(&self.deliveries)).transpose()?;
        self.cache = OnceLock::new();
        Ok(self)
    }

    /// Number of shots.
    pub fn len(&self) -> usize {
        self.ids.len()
    }

    /// No shots?
    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    /// The shots at `idx` (same group list, so group indices stay valid).
    pub fn subset(&self, idx: &[usize]) -> Self {
        Self {
            ids: idx.iter().map(|&i| self.ids[i].clone()).collect(),
            groups: self.groups.clone(),
            group_of: idx.iter().map(|&i| self.group_of[i]).collect(),
            golfers: idx.iter().map(|&i| self.golfers[i].clone()).collect(),
            shaft_mass_g: idx.iter().map(|&i| self.shaft_mass_g[i]).collect(),
            deliveries: idx.iter().map(|&i| self.deliveries[i]).collect(),
            measured: idx.iter().map(|&i| self.measured[i]).collect(),
            measured_velocity_m_s: idx.iter().map(|&i| self.measured_velocity_m_s[i]).collect(),
            measured_spin_yz_rad_s: idx
                .iter()
                .map(|&i| self.measured_spin_yz_rad_s[i])
                .collect(),
            impact_nodes: self
                .impact_nodes
                .as_ref()
                .map(|n| idx.iter().map(|&i| n[i]).collect()),
            cache: OnceLock::new(),
        }
    }

    /// The shared evaluation parts, built on first use with `model`'s face and biases (`None`
    /// when `model` is `None`: no valid club model to build them with).
    fn site_cache(&self, model: impl FnOnce() -> Option<ImpactModel>) -> Option<&SiteCache> {
        self.cache
            .get_or_init(|| model().map(|m| Arc::new(SiteCache::build(&m, self))))
            .as_deref()
    }

    /// Do all shots name a golfer?
    pub fn has_golfers(&self) -> bool {
        self.golfers.iter().all(Option::is_some)
    }
}

/// Predicted launch (SI), ball velocity and spin (G) of [`W`] shots, one lane a shot.
struct LanePrediction {
    launch: [V; 5],
    ball_v: [V; 3],
    ball_w: [V; 3],
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

    /// Compute Jacobian columns in parallel (worth it when the fit is not itself one of many
    /// parallel jobs).
    pub fn with_parallel_jacobian(mut self, on: bool) -> Self {
        self.parallel_jacobian = on;
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

    /// Number of residual rows.
    pub fn rows(&self) -> usize {
        self.data.len() * self.weighting.rows_per_shot()
    }

    /// One validated model per group for full parameters `theta`.
    pub fn models(&self, theta: &[f64]) -> Result<Vec<ImpactModel>, EvalError> {
        self.base_params
            .iter()
            .zip(&self.applies)
            .zip(&self.data.groups)
            .map(|((base, applies), group)| {
                let mut p = base.clone();
                for &i in applies {
                    self.layout.effects()[i]
                        .kind
                        .apply(&theta[self.layout.range(i)], &mut p);
                }
                ImpactModel::new(p).map_err(|source| EvalError::Model {
                    group: group.clone(),
                    source,
                })
            })
            .collect()
    }

    /// Model − measured for every shot in file units (mph, deg, deg, rpm, rpm), full `theta`.
    pub fn launch_errors(&self, theta: &[f64]) -> Result<Vec<[f64; 5]>, EvalError> {
        let models = self.models(theta)?;
        let cache = self.cache();
        (0..self.data.len())
            .map(|i| {
                let (launch, _, _) = self.predict(&models, cache, i)?;
                let m = &self.data.measured[i];
                Ok(std::array::from_fn(|c| {
                    launch.get_file(LaunchComponent::ALL[c]) - m[c]
                }))
            })
            .collect()
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
        let (frame, contacts) = match cache {
            Some(c) => {
                let frame = if c.frames_fit(model) {
                    &c.frames[i]
                } else {
                    fresh = model.delivery_frame(d);
                    &fresh
                };
                let per = c.sites_per_shot;
                let contacts = (*model.face() == c.face).then(|| &c.contacts[i * per..][..per]);
                (frame, contacts)
            }
            None => {
                fresh = model.delivery_frame(d);
                (&fresh, None)
            }
        };
        expected_over(nodes, |k| {
            let (y, z) = at(k);
            let cf = match contacts {
                Some(c) => c[k]?,
                None => model.face().contact(y, z)?,
            };
            model.solve_in(frame, &cf, y, z)
        })
        .map_err(|source| EvalError::Shot {
            shot_id: self.data.ids[i].clone(),
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
                self.residual_rows(&models, cache, i, r)?;
            }
            Ok(())
        };
        let sites = self.data.len()
            * if self.data.impact_nodes.is_some() {
                NODES_PER_SHOT
            } else {
                1
            };
        if sites >= PARALLEL_MIN_SITES {
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

    /// Residual rows of the shots `start..` of `chunk` (those of the groups flagged in `groups`)
    /// evaluated [`W`] shots at a time on the lanes ([`FitProblem::predict_lanes`]). Shots are
    /// taken group by group (a lane vector shares one model), the last vector of a group padded
    /// with copies of its last shot. Returns `false`, with `chunk` partly written, when a shot
    /// cannot be computed (off the face, not approaching, not finite) or a model has
    /// user-defined effects: the caller then evaluates the chunk one shot at a time.
    fn residuals_on_lanes(
        &self,
        models: &[ImpactModel],
        cache: &SiteCache,
        start: usize,
        chunk: &mut [f64],
        groups: Option<&[bool]>,
    ) -> bool {
        // User-defined effects are evaluated per shot by the scalar solve.
        if models.iter().any(|m| !m.laws().user.is_empty()) {
            return false;
        }
        let rows = self.weighting.rows_per_shot();
        let group_of = &self.data.group_of;
        let mut order = [0usize; SHOTS_PER_TASK];
        let mut len = 0;
        for i in start..start + chunk.len() / rows {
            if groups.is_none_or(|g| g[group_of[i]]) {
                order[len] = i;
                len += 1;
            }
        }
        let order = &mut order[..len];
        // Keys are distinct, so the unstable sort (which does not allocate) keeps file order
        // within a group.
        order.sort_unstable_by_key(|&i| (group_of[i], i));
        for run in order.chunk_by(|&a, &b| group_of[a] == group_of[b]) {
            let model = &models[group_of[run[0]]];
            for shots in run.chunks(W) {
                let mut idx = [shots[shots.len() - 1]; W];
                idx[..shots.len()].copy_from_slice(shots);
                let Some(p) = self.predict_lanes(model, cache, &idx) else {
                    return false;
                };
                for (l, &i) in shots.iter().enumerate() {
                    let launch = Launch {
                        ball_speed_m_s: p.launch[0].0[l],
                        launch_angle_rad: p.launch[1].0[l],
                        azimuth_rad: p.launch[2].0[l],
                        backspin_rad_s: p.launch[3].0[l],
                        sidespin_rad_s: p.launch[4].0[l],
                    };
                    let lane = |v: &[V; 3]| Vector3::new(v[0].0[l], v[1].0[l], v[2].0[l]);
                    let r = &mut chunk[(i - start) * rows..][..rows];
                    self.write_rows(i, &launch, &lane(&p.ball_v), &lane(&p.ball_w), r);
                }
            }
        }
        true
    }

    /// [`FitProblem::predict`] for the [`W`] shots `idx` of one group (model `model`) at once:
    /// [`ImpactModel::solve_contact`] on the lanes (the scalar solve's own contact mechanics),
    /// rotated to `G`, the launch angles by [`atan2_v`] and [`hypot_v`], averaged over the
    /// impact-location nodes as [`crate::measurement::expected_over`] does. Agrees with the
    /// scalar path to rounding (a few ulp). `None` if any lane cannot be computed.
    #[inline]
    fn predict_lanes(
        &self,
        model: &ImpactModel,
        cache: &SiteCache,
        idx: &[usize; W],
    ) -> Option<LanePrediction> {
        let data = self.data;
        let frames: [DeliveryFrame; W] = if cache.frames_fit(model) {
            idx.map(|i| cache.frames[i])
        } else {
            idx.map(|i| model.delivery_frame(&data.deliveries[i]))
        };
        let lanes = |f: &dyn Fn(&DeliveryFrame) -> f64| V(frames.each_ref().map(f));
        let v_c: [V; 3] = std::array::from_fn(|a| lanes(&|fr| fr.club_velocity_f_m_s[a]));
        let w_c: [V; 3] = std::array::from_fn(|a| lanes(&|fr| fr.club_omega_f_rad_s[a]));
        let r_gf: [[V; 3]; 3] =
            std::array::from_fn(|a| std::array::from_fn(|b| lanes(&|fr| fr.r_gf[(a, b)])));
        let rotate = |v: &[V; 3]| -> [V; 3] {
            std::array::from_fn(|a| r_gf[a][0] * v[0] + r_gf[a][1] * v[1] + r_gf[a][2] * v[2])
        };
        let nodes = data.impact_nodes.as_ref();
        let per = cache.sites_per_shot;
        let same_face = *model.face() == cache.face;
        let zero = V::splat(0.0);
        let mut out = LanePrediction {
            launch: [zero; 5],
            ball_v: [zero; 3],
            ball_w: [zero; 3],
        };
        for k in 0..per {
            let mut x = ContactInputs {
                club_velocity_f_m_s: v_c,
                club_omega_f_rad_s: w_c,
                point_m: [zero; 3],
                normal: [zero; 3],
                tangent_y: [zero; 3],
                tangent_z_xz: [zero; 2],
                y_m: zero,
                z_m: zero,
            };
            let mut weight = zero;
            for (l, &i) in idx.iter().enumerate() {
                let (y, z, w) = match nodes {
                    Some(n) => (n[i][k].y_m, n[i][k].z_m, n[i][k].weight),
                    None => {
                        let d = &data.deliveries[i];
                        (d.impact_y_m, d.impact_z_m, 1.0)
                    }
                };
                let cf = if same_face {
                    cache.contacts[i * per + k].ok()?
                } else {
                    model.face().contact(y, z).ok()?
                };
                for a in 0..3 {
                    x.point_m[a].0[l] = cf.point_m[a];
                    x.normal[a].0[l] = cf.normal[a];
                    x.tangent_y[a].0[l] = cf.tangent_y[a];
                }
                x.tangent_z_xz[0].0[l] = cf.tangent_z.x;
                x.tangent_z_xz[1].0[l] = cf.tangent_z.z;
                x.y_m.0[l] = y;
                x.z_m.0[l] = z;
                weight.0[l] = w;
            }
            let s = model.solve_contact(&x);
            // The scalar solve's checks: the club approaches the ball, and the ball's and the
            // club's states after impact are finite.
            let finite = |v: &[V; 3]| v.iter().all(|c| c.0.iter().all(|x| x.is_finite()));
            let p = &s.impulse_n_s;
            let club_dv = p.map(|c| c / model.params().club_mass_kg);
            let r_c = &s.contact_from_club_com_m;
            let moment = [
                r_c[1] * p[2] - r_c[2] * p[1],
                r_c[2] * p[0] - r_c[0] * p[2],
                r_c[0] * p[1] - r_c[1] * p[0],
            ];
            if (!s.normal_approach_speed_m_s.gt(zero)).any()
                || !(finite(&s.ball_velocity_f_m_s)
                    && finite(&s.ball_spin_f_rad_s)
                    && finite(&club_dv)
                    && finite(&moment))
            {
                return None;
            }
            let v = rotate(&s.ball_velocity_f_m_s);
            let w = rotate(&s.ball_spin_f_rad_s);
            let launch = [
                (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt(),
                atan2_v(v[1], hypot_v(v[0], v[2])),
                atan2_v(v[2], v[0]),
                w[2],
                -w[1],
            ];
            if nodes.is_none() {
                out = LanePrediction {
                    launch,
                    ball_v: v,
                    ball_w: w,
                };
            } else {
                for (a, c) in out.launch.iter_mut().zip(launch) {
                    *a = *a + weight * c;
                }
                for a in 0..3 {
                    out.ball_v[a] = out.ball_v[a] + weight * v[a];
                    out.ball_w[a] = out.ball_w[a] + weight * w[a];
                }
            }
        }
        Some(out)
    }

    /// Residuals at full `theta`.
    pub fn residuals(&self, theta: &[f64]) -> Result<DVector<f64>, EvalError> {
        let mut out = DVector::zeros(self.rows());
        self.residuals_into(theta, out.as_mut_slice())?;
        Ok(out)
    }

    /// Central-difference Jacobian of the residuals with respect to the active parameters,
    /// at full `theta`. Columns in the order of `active`.
    pub fn jacobian_full(&self, theta: &DVector<f64>) -> Result<DMatrix<f64>, EvalError> {
        let m = self.rows();
        let mut jac = DMatrix::zeros(m, self.active.len());
        let column = |(k, col): (usize, &mut [f64])| -> Result<(), EvalError> {
            let j = self.active[k];
            let h = FD_STEP_OF_RANGE * (self.upper[j] - self.lower[j]);
            let mut plus = theta.clone();
            let mut minus = theta.clone();
            plus[j] = (theta[j] + h).min(self.upper[j]);
            minus[j] = (theta[j] - h).max(self.lower[j]);
            let span = plus[j] - minus[j];
            // Groups whose model the parameter changes: the other shots' residuals are the same
            // at both points, so their rows stay 0 (what (r − r)/span gives).
            let touched: Vec<bool> = self
                .applies
                .iter()
                .map(|a| a.contains(&self.owner[j]))
                .collect();
            let groups = (!touched.iter().all(|&t| t)).then_some(touched.as_slice());
            let mut r_minus = vec![0.0; m];
            self.residuals_of_groups(plus.as_slice(), col, groups)?;
            self.residuals_of_groups(minus.as_slice(), &mut r_minus, groups)?;
            for (c, rm) in col.iter_mut().zip(&r_minus) {
                *c = (*c - rm) / span;
            }
            Ok(())
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
