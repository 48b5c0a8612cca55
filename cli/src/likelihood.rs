//! The scales the models of `calibrate` and `diagnose` are scored by, and the instrument class
//! argument that gives them; the likelihood table is the library's
//! [`smash::report::likelihood`].

use std::path::Path;

use smash::data::noise_file::read_noise_file;
use smash::diagnose::noise_floor::{self, InstrumentClass};
use smash::fit::GivenScales;
use smash::measurement::ImpactNoise;
use smash::model::Shot;
use smash::physics::LaunchComponent;
use smash::ClubSpec;

/// The scales the models are scored by when the instruments' noise is given (`--noise FILE`,
/// else `--instrument CLASS`): each shot's expected error variance through the nominal model
/// `club` with the location correction `impact_noise`; `None` (profiled scales) when neither is
/// given. A zero scale is refused: it would make any error infinitely unlikely.
pub fn given_scales(
    (noise, instrument): (Option<&Path>, Option<InstrumentClass>),
    club: &ClubSpec,
    shots: &[Shot],
    impact_noise: Option<ImpactNoise>,
) -> anyhow::Result<Option<GivenScales>> {
    let inst = match (noise, instrument) {
        (Some(p), _) => read_noise_file(p)?,
        (None, Some(c)) => c.noise(),
        (None, None) => return Ok(None),
    };
    let given = noise_floor::given_scales(club, shots, &inst, impact_noise)?;
    let scales = given.scales();
    if let Some(c) = LaunchComponent::ALL
        .iter()
        .find(|c| !(scales[c.index()] > 1e-9 && scales[c.index()].is_finite()))
    {
        anyhow::bail!(
            "{}: the noise of {} is {}; scoring needs a positive noise for every launch \
             component (give it in [noise.launch])",
            inst.name,
            c.column(),
            scales[c.index()]
        );
    }
    Ok(Some(given))
}

/// `--instrument CLASS`.
pub fn parse_instrument(s: &str) -> Result<InstrumentClass, String> {
    InstrumentClass::from_name(s).ok_or_else(|| {
        format!(
            "unknown instrument class '{s}'; allowed: {}",
            InstrumentClass::ALL.map(|c| c.name()).join(", ")
        )
    })
}
