//! `contact_time`: a finite contact of duration `τ`, to first order in `τ`.
//!
//! The paper's impact is instantaneous. During a real driver impact (about half a
//! millisecond) the head turns under the growing impulse, so the face that delivers the impulse
//! is not the face at first contact. The law is [`crate::physics::laws::FiniteContact`], derived
//! there from the one-body Hertz impact: the impulse is delivered, on average, by the face
//! turned by `θ̄ = τ·(ω₀/2 + Δω/9)`.

use super::{spec, ParamSpec};
use crate::physics::ModelParams;

/// Name in files and on the command line.
pub const NAME: &str = "contact_time";

/// One-line description.
pub const DESCRIPTION: &str =
    "finite contact of tau_ms: the head turns while the impulse is delivered (face turned by tau*(w0/2 + dw/9))";

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
