//! The shots of a fit, flattened for the inner loop ([`FitData`]), and what every evaluation
//! of them shares ([`SiteCache`]: per-shot delivery frames, built once per data set).

use std::sync::{Arc, OnceLock};

use nalgebra::Vector3;

use super::FitError;
use crate::measurement::{DeliveryNoise, ImpactNoise, LocationNode, NODES_PER_SHOT};
use crate::model::Shot;
use crate::physics::{Delivery, DeliveryFrame, FaceGeometry, FrameTrig, ImpactModel};

/// The shots a fit uses, flattened for the inner loop.
#[derive(Debug, Clone, PartialEq)]
pub struct FitData {
    /// Shot ids, for messages (shared: the folds' and noise levels' copies of the data take
    /// a reference each, not a new string).
    pub ids: Vec<Arc<str>>,
    /// Distinct groups, sorted.
    pub groups: Vec<String>,
    /// Index into `groups` of each shot.
    pub group_of: Vec<usize>,
    /// Golfer of each shot, when known.
    pub golfers: Vec<Option<Arc<str>>>,
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
/// loft and face biases, and the face geometry the evaluations compute each site's contact
/// frame on (an evaluation site is a shot, or shot × location node). The contact frames are not
/// stored: computing one on the lanes costs less than reading it from memory.
#[derive(Debug, PartialEq)]
pub(crate) struct SiteCache {
    pub(crate) face: FaceGeometry,
    pub(crate) loft_bias_rad: f64,
    pub(crate) face_bias_rad: f64,
    pub(crate) frames: Vec<DeliveryFrame>,
    /// Per shot, the trigonometry of `frames` ([`Delivery::frame_trig`]): a model with other
    /// biases makes its frames from it, computing only the angles its biases change.
    pub(crate) trig: Vec<FrameTrig>,
    pub(crate) sites_per_shot: usize,
}

impl SiteCache {
    fn build(model: &ImpactModel, data: &FitData) -> Self {
        let p = model.params();
        let trig: Vec<FrameTrig> = data
            .deliveries
            .iter()
            .map(|d| d.frame_trig(p.loft_bias_rad, p.face_bias_rad))
            .collect();
        let frames = data
            .deliveries
            .iter()
            .zip(&trig)
            .map(|(d, t)| model.delivery_frame_from(d, t))
            .collect();
        Self {
            face: *model.face(),
            loft_bias_rad: p.loft_bias_rad,
            face_bias_rad: p.face_bias_rad,
            frames,
            trig,
            sites_per_shot: if data.impact_nodes.is_some() {
                NODES_PER_SHOT
            } else {
                1
            },
        }
    }

    /// Are the frames valid for `model` (same biases)?
    pub(crate) fn frames_fit(&self, model: &ImpactModel) -> bool {
        let p = model.params();
        p.loft_bias_rad == self.loft_bias_rad && p.face_bias_rad == self.face_bias_rad
    }
}

/// The distinct group names of `shots`, sorted (without a copy of every shot's name).
pub(crate) fn distinct_groups(shots: &[Shot]) -> Vec<String> {
    shots
        .iter()
        .map(|s| s.group.as_str())
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .map(str::to_owned)
        .collect()
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
        let groups = distinct_groups(shots);

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
            d.ids.push(Arc::from(s.id.as_str()));
            d.group_of
                .push(d.groups.binary_search(&s.group).expect("group listed"));
            d.golfers.push(s.golfer.as_deref().map(Arc::from));
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

    /// Correct for noise in the measured delivery variables other than the impact location
    /// (`None`: none): every delivery is replaced by the conditional mean of its true values
    /// given all these shots' measured deliveries and golfers ([`DeliveryNoise::calibrate`]).
    /// Apply before [`Self::with_impact_noise`] or after: the location is left as measured.
    pub fn with_delivery_noise(mut self, noise: Option<DeliveryNoise>) -> Self {
        if let Some(n) = noise.filter(DeliveryNoise::is_active) {
            self.deliveries = n.calibrate(&self.deliveries, &self.golfers);
            self.cache = OnceLock::new();
        }
        self
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
    pub(crate) fn site_cache(
        &self,
        model: impl FnOnce() -> Option<ImpactModel>,
    ) -> Option<&SiteCache> {
        self.cache
            .get_or_init(|| model().map(|m| Arc::new(SiteCache::build(&m, self))))
            .as_deref()
    }

    /// Do all shots name a golfer?
    pub fn has_golfers(&self) -> bool {
        self.golfers.iter().all(Option::is_some)
    }
}
