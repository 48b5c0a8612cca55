//! The scales the models of `calibrate` and `diagnose` are scored by, and the instrument class
//! argument that gives them; the likelihood table is the library's
//! [`smash::report::likelihood`].

use smash::diagnose::noise_floor::InstrumentClass;

pub use smash::app::calibrate::given_scales;

/// `--instrument CLASS`.
pub fn parse_instrument(s: &str) -> Result<InstrumentClass, String> {
    InstrumentClass::from_name(s).ok_or_else(|| {
        format!(
            "unknown instrument class '{s}'; allowed: {}",
            InstrumentClass::ALL.map(|c| c.name()).join(", ")
        )
    })
}
