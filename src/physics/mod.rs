//! Pure impact physics: face geometry, frames, the impulse–momentum solve and launch conditions.
//!
//! No I/O, no threads, no logging. Inputs are validated at construction ([`ImpactModel::new`]),
//! so [`ImpactModel::solve`] only fails for per-shot reasons (off the face, not approaching).
//! The model is the paper's (Danaei, McNally, Henrikson, McPhee: *Adjusting a momentum-based
//! golf clubhead-ball impact model to improve accuracy*), with the conventions of
//! `docs/conventions.md`.

pub mod delivery;
pub mod delivery_vars;
pub mod expr;
pub mod face;
pub mod impact;
pub mod launch;
pub mod laws;
mod params;
pub mod real;
pub mod user_terms;

pub use delivery::{face_orientation, Delivery, FrameTrig};
pub use face::{ContactFrame, ContactFrameOf, FaceError, FaceGeometry};
pub use impact::{
    solve_spd3, validate_inertia, DeliveryFrame, ImpactError, ImpactModel, ImpactOutcome,
    ModelParams, ParamError,
};
pub use launch::{Launch, LaunchComponent};
