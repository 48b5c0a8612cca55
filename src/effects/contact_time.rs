//! `contact_time`: a finite contact of duration `τ`, to first order in `τ`.
//!
//! The paper's impact is instantaneous. During a real driver impact (about half a
//! millisecond) two things move while the impulse is delivered: the head turns under the
//! growing impulse, so the face that delivers it is not the face at first contact; and the
//! ball travels over the face (the face slides beneath the ball with the tangential approach
//! `u1t` while the ball gathers speed), so the impulse acts on average away from the first
//! contact point, where the curved face's normal is tilted. The law is
//! [`crate::physics::laws::FiniteContact`], derived there from the one-body Hertz impact: the
//! impulse is delivered, on average, by the face turned by `θ̄ = τ·(ω₀/2 + Δω/9)` at the point
//! `d̄ = −τ·(u1/2 − g/9)_t` from the first contact (`≈ −0.47·τ·u1t` for a gripping ball). One
//! parameter, `τ`, sets both.

use super::{spec, ParamSpec};
use super::knowledge::{row, Needs, Pattern, SignatureRow, StandIn};
use crate::physics::LaunchComponent;
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "contact_time";

/// One-line description.
pub const DESCRIPTION: &str =
    "finite contact of tau_ms: the head turns (by tau*(w0/2 + dw/9)) and the ball travels over the face (by -tau*(u1/2 - g/9)_t, about -0.47*tau*u1t) while the impulse is delivered";

/// Parameters, in file order. Physical: a duration is not negative; 2 ms is four times a
/// driver's. Plausible: high-speed films of driver impacts show 0.4–0.5 ms (Cochran & Stobbs,
/// *The Search for the Perfect Swing*, 1968; the Hertz estimate for a ball on a driver face at
/// 45–50 m/s agrees), softer balls and lower speeds somewhat longer: up to 0.7 ms
/// (`docs/plausible-ranges.md`).
pub const PARAMS: &[ParamSpec] = &[spec(
    "tau_ms",
    "ms",
    0.0,
    0.0,
    2.0,
    (0.0, 0.7),
    "duration of the clubhead–ball contact (0 = the paper's instantaneous impact)",
)];

/// Apply with parameter values `v` (units of [`PARAMS`]). Several apply as one contact of the
/// summed duration.
pub fn apply(v: &[f64], p: &mut ModelParams) {
    p.contact_time_s += v[0] * 1e-3;
}

/// Launch patterns it leaves when present and missing from the model (compare's hints).
pub const SIGNATURE: &[SignatureRow] = &[
    row(LaunchComponent::LaunchAngle, Pattern::Bias, "the face turning while the ball is on it"),
    row(LaunchComponent::Backspin, Pattern::Trend("impact_y_mm"), "vertical gear effect changed by a finite contact"),
    row(LaunchComponent::Sidespin, Pattern::Trend("impact_z_mm"), "horizontal gear effect changed by a finite contact"),
];

/// What a fitted value outside the plausible range behaves like.
pub const STAND_IN: StandIn = StandIn::either(
    "a contact longer than a driver impact lasts: behaves like a spin lever or head rotation the file's geometry does not give (ball offset, CoM or inertia error)",
);

/// The measurement that pins it down independently of launch data.
pub const SEPARATE_BY: &str = "a measured contact time (high-speed video or a force-instrumented face) and off-centre shots";

/// Which delivery variables must vary for shots to identify it.
pub const NEEDS: Needs = Needs::Nothing("the head's own rotation and the ball's travel turn the impulse of every shot");
