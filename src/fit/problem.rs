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
//! loop does not allocate.

use argmin::core::{Error as ArgminError, Jacobian, Operator};
use nalgebra::{DMatrix, DVector, Vector3};
use rayon::prelude::*;

use super::spec::ParamLayout;
use super::FitError;
use crate::club::ClubSpec;
use crate::measurement::{expected_outcome, ImpactNoise, LocationNode, NODES_PER_SHOT};
use crate::model::Shot;
use crate::physics::{
    Delivery, ImpactError, ImpactModel, Launch, LaunchComponent, ModelParams, ParamError,
};

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
}

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
        };
        for s in shots {
            let m = s.measured.ok_or(FitError::NoMeasurements)?;
            d.ids.push(s.id.clone());
            d.group_of
                .push(d.groups.binary_search(&s.group).expect("group listed"));
            d.golfers.push(s.golfer.clone());
            d.shaft_mass_g.push(s.shaft_mass_g);
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
        }
    }

    /// Do all shots name a golfer?
    pub fn has_golfers(&self) -> bool {
        self.golfers.iter().all(Option::is_some)
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
        (0..self.data.len())
            .map(|i| {
                let (launch, _, _) = self.predict(&models, i)?;
                let m = &self.data.measured[i];
                Ok(std::array::from_fn(|c| {
                    launch.get_file(LaunchComponent::ALL[c]) - m[c]
                }))
            })
            .collect()
    }

    /// Predicted launch (SI), ball velocity and spin (G) of shot `i`: the model at the measured
    /// delivery, or its average over the posterior of the true impact location.
    #[inline]
    fn predict(
        &self,
        models: &[ImpactModel],
        i: usize,
    ) -> Result<(Launch, Vector3<f64>, Vector3<f64>), EvalError> {
        let nodes = self.data.impact_nodes.as_ref().map(|n| &n[i]);
        expected_outcome(
            &models[self.data.group_of[i]],
            &self.data.deliveries[i],
            nodes,
        )
        .map_err(|source| EvalError::Shot {
            shot_id: self.data.ids[i].clone(),
            source,
        })
    }

    /// Residuals at full `theta` into `out` (length [`FitProblem::rows`]).
    pub fn residuals_into(&self, theta: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        let models = self.models(theta)?;
        let rows = self.weighting.rows_per_shot();
        debug_assert_eq!(out.len(), self.rows());
        for (i, r) in out.chunks_exact_mut(rows).enumerate() {
            let (launch, ball_v, ball_w) = self.predict(&models, i)?;
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
        Ok(())
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
            let mut r_minus = vec![0.0; m];
            self.residuals_into(plus.as_slice(), col)?;
            self.residuals_into(minus.as_slice(), &mut r_minus)?;
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
