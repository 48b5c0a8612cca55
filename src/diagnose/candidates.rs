//! The candidates diagnose offers by default, and the same without some of them.

use crate::effects::{EffectId, EffectKind};
use crate::fit::{EffectRequest, FitError};
use crate::model::Shot;

/// Library effects that are searched only when named with `--candidates`: `inertia_axes`, the
/// two moments of `smash infer-club` (`docs/infer-club.md`). At equal factors it is
/// `inertia_scale` exactly, so as a default candidate it only doubles that one's chance to
/// stand in: offered by default it was selected in six of six seeds of the curved-face world
/// outside the library (`cli/tests/library_forms.rs`), with a false finding in one, and moved
/// the paper world's `ball_offset.dy` outside 2 SE in three of twenty seeds
/// (`cli/tests/world_seeds.rs`). (`cor_level`, `hosel_mass` and `cor_power` were once here
/// because they alias `added_mass` and `cor_speed` on launch data alone; alias arbitration
/// made them default candidates.)
pub const OPT_IN_CANDIDATES: [EffectKind; 1] = [EffectKind::InertiaAxes];

/// Every library effect as a global candidate (except [`OPT_IN_CANDIDATES`]), plus
/// `added_mass@group` and `hosel_mass@group` with several groups, plus every offered
/// user-defined effect (`crate::effects::user::offered`: those of an effects file or club file
/// read, not a synth world's hidden ones) as a global candidate beside them.
pub fn default_candidates(groups: &[String]) -> Vec<EffectRequest> {
    let mut c: Vec<EffectRequest> = EffectKind::ALL
        .iter()
        .filter(|k| !OPT_IN_CANDIDATES.contains(k))
        .map(|&k| EffectRequest::Global(k.into()))
        .collect();
    if groups.len() > 1 {
        c.push(EffectRequest::PerGroup(EffectKind::AddedMass.into()));
        c.push(EffectRequest::PerGroup(EffectKind::HoselMass.into()));
    }
    c.extend(
        crate::effects::user::offered()
            .into_iter()
            .map(|u| EffectRequest::Global(EffectId::User(u))),
    );
    c
}

/// The default candidates for `shots` ([`default_candidates`] of their groups) without those
/// in `without`: what diagnose would conclude if the library lacked them. Each of `without`
/// must be a default candidate (a name or `name@group`), or the list is refused.
pub fn default_candidates_without(
    shots: &[Shot],
    without: &[EffectRequest],
) -> Result<Vec<EffectRequest>, FitError> {
    let all = default_candidates(&crate::fit::distinct_groups(shots));
    if let Some(w) = without.iter().find(|w| !all.contains(w)) {
        return Err(FitError::BadEffectList(format!(
            "'{}' is not a default candidate of these shots; they are: {}",
            w.label(),
            all.iter()
                .map(EffectRequest::label)
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    Ok(all.into_iter().filter(|c| !without.contains(c)).collect())
}
