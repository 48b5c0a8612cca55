//! Face maps of a model whose user-defined mass or geometry reads the impact location
//! (`loft_deg = "loft_deg + k * impact_y_mm"`, a CoM or ball offset that varies over the face):
//! what [`FaceMapKernel::new`] would precompute once per delivery then differs from point to
//! point. Each point gets its own kernel, built at its location with the same code
//! ([`FaceMapKernel::at_location`], which evaluates the user-defined terms as the scalar solve
//! does), and is evaluated by the same vector code as every other point. No allocation per
//! point; roughly the cost of one kernel construction per point, so only models that need it
//! take this path.

use std::sync::Arc;

use super::jobs::{Job, PointsJob};
use super::{FaceMapKernel, RowOut, SimdLevel};
use crate::physics::{Delivery, ImpactModel};

/// The model and delivery a location-dependent face map rebuilds its kernel from.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Located {
    model: ImpactModel,
    delivery: Delivery,
}

impl Located {
    pub(super) fn new(model: &ImpactModel, delivery: &Delivery) -> Arc<Self> {
        Arc::new(Self {
            model: model.clone(),
            delivery: *delivery,
        })
    }

    /// Evaluate the points of `job` one at a time, each on the kernel of its own location.
    pub(super) fn run(&self, level: SimdLevel, job: &impl Job, out: RowOut<'_>) {
        for i in 0..job.len() {
            let (y, z) = job.at(i);
            let d = Delivery {
                impact_y_m: y,
                impact_z_m: z,
                ..self.delivery
            };
            let k = FaceMapKernel::at_location(&self.model, &d);
            let one = RowOut {
                ball_speed_m_s: &mut out.ball_speed_m_s[i..=i],
                launch_angle_rad: &mut out.launch_angle_rad[i..=i],
                azimuth_rad: &mut out.azimuth_rad[i..=i],
                backspin_rad_s: &mut out.backspin_rad_s[i..=i],
                sidespin_rad_s: &mut out.sidespin_rad_s[i..=i],
                valid: &mut out.valid[i..=i],
            };
            k.dispatch(level, &PointsJob { ys: &[y], zs: &[z] }, one);
        }
    }
}
