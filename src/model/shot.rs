//! One shot: the unit every room above the physics works on (predict, compare, fit, diagnose,
//! synth). Read from and written to files by [`crate::data`].

use crate::physics::{Delivery, Launch};

/// One shot: who, how the club was delivered and, if measured, how the ball launched.
#[derive(Debug, Clone, PartialEq)]
pub struct Shot {
    /// Unique id.
    pub id: String,
    /// Group (e.g. shaft); `all` when the file has none.
    pub group: String,
    /// Golfer, when known.
    pub golfer: Option<String>,
    /// Clubhead delivery, SI, with the shaft mass when the file gives it
    /// ([`Delivery::shaft_mass_g`]).
    pub delivery: Delivery,
    /// Measured launch, SI, when the file has launch columns.
    pub measured: Option<Launch>,
}
