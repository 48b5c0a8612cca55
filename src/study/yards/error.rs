//! Why yard metrics, a carry map or a mass optimisation cannot be computed.

/// Why yard metrics, a carry map or a mass optimisation cannot be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum YardsError {
    /// A flight that cannot be flown.
    #[error("flight: {0}")]
    Flight(crate::flight::FlightError),
    /// A confidence level outside (0, 1).
    #[error("confidence {0}: must be within (0, 1)")]
    Confidence(f64),
    /// Impacts of the distribution off the face.
    #[error("{0} impact(s) of the distribution are off the face or miss the ball")]
    OffFace(usize),
    /// Most of the distribution's weight never leaves the ground ([`super::MAX_GROUNDED_SHARE`]).
    #[error(
        "{grounded} of {impacts} impacts ({:.1} % of the distribution's weight) launch below \
         horizontal from the ground and never fly (mean launch angle {mean_launch_deg:.1} deg); \
         carry and dispersion are not reported when more than {:.0} % of the weight never \
         flies: give the head and swing more loft, or more attack angle",
        100.0 * share,
        100.0 * super::MAX_GROUNDED_SHARE
    )]
    Grounded {
        /// Impacts that never fly.
        grounded: usize,
        /// Impacts.
        impacts: usize,
        /// Their share of the weight, in [0, 1].
        share: f64,
        /// Mean launch angle, deg.
        mean_launch_deg: f64,
    },
    /// Landing points that are not finite.
    #[error("the landing points are not finite")]
    NotFinite,
    /// A design that is not physical.
    #[error(transparent)]
    Design(#[from] crate::study::design::DesignError),
    /// A head the model refuses.
    #[error(transparent)]
    Model(#[from] crate::physics::ParamError),
    /// The base design of a mass optimisation breaks a constraint.
    #[error("the base design breaks a constraint: {name} = {value:.3} (limit {limit})")]
    BaseBreaksConstraint {
        /// The constraint.
        name: String,
        /// The base design's value.
        value: f64,
        /// The limit.
        limit: f64,
    },
    /// The optimiser's words.
    #[error("{0}")]
    Solver(String),
}

impl YardsError {
    pub(super) fn solver(e: impl std::fmt::Display) -> Self {
        Self::Solver(e.to_string())
    }
}
