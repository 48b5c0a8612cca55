//! Which library effects produce which error pattern: a small table, used to hint at the
//! missing physics behind a finding. Each row was read off the model (an effect's derivative of
//! the launch over typical driver shots); `smash diagnose` tests them quantitatively.

use std::fmt;

use serde::Serialize;

use crate::effects::user::UserEffect;
use crate::effects::EffectKind;
use crate::physics::LaunchComponent;

/// What a signature points at: a library effect (checked by the compiler), the effect per group
/// of shots, noise in the measured impact location, or a user-defined effect whose measured
/// signature matches ([`super::user_hints`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Hint {
    /// A library effect, for all shots.
    Effect(EffectKind),
    /// A library effect fitted per group (`name@group`).
    PerGroup(EffectKind),
    /// Impact-location measurement noise (`--impact-noise-mm`).
    ImpactNoise,
    /// A user-defined effect, for all shots.
    User(&'static UserEffect),
    /// A user-defined effect fitted per group (`name@group`).
    UserPerGroup(&'static UserEffect),
}

impl fmt::Display for Hint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Effect(k) => f.write_str(k.name()),
            Self::PerGroup(k) => write!(f, "{}@group", k.name()),
            Self::ImpactNoise => f.write_str("impact_noise"),
            Self::User(u) => f.write_str(u.name),
            Self::UserPerGroup(u) => write!(f, "{}@group", u.name),
        }
    }
}

/// The shape of an error pattern.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Pattern {
    /// A uniform bias: the mean error is not zero.
    Bias,
    /// The mean error differs between groups (shafts).
    GroupBias,
    /// The error changes with a delivery variable.
    Trend(&'static str),
}

/// One row of the table.
#[derive(Debug, Clone, Copy)]
pub struct Signature {
    /// Error component.
    pub component: LaunchComponent,
    /// Pattern.
    pub pattern: Pattern,
    /// Effects (or measurement noise) that produce it.
    pub effects: &'static [Hint],
    /// Why, in a few words.
    pub why: &'static str,
}

use Hint::{Effect, ImpactNoise, PerGroup};
use LaunchComponent::{Azimuth, Backspin, BallSpeed, LaunchAngle, Sidespin};
use Pattern::{Bias, GroupBias, Trend};

const fn sig(
    component: LaunchComponent,
    pattern: Pattern,
    effects: &'static [Hint],
    why: &'static str,
) -> Signature {
    Signature {
        component,
        pattern,
        effects,
        why,
    }
}

/// The table.
pub const SIGNATURES: &[Signature] = &[
    sig(
        BallSpeed,
        Bias,
        &[
            Effect(EffectKind::AddedMass),
            Effect(EffectKind::CorLevel),
            Effect(EffectKind::HoselMass),
        ],
        "effective clubhead mass (shaft taking part) or the club's COR",
    ),
    sig(
        BallSpeed,
        GroupBias,
        &[PerGroup(EffectKind::AddedMass)],
        "shaft mass taking part in the impact",
    ),
    sig(
        BallSpeed,
        Trend("club_speed_mph"),
        &[Effect(EffectKind::CorSpeed), Effect(EffectKind::CorPower)],
        "COR falling with impact speed",
    ),
    sig(
        BallSpeed,
        Trend("impact_r_mm"),
        &[Effect(EffectKind::CorRadial), ImpactNoise],
        "COR falling off-centre, or noisy impact locations (falling with r: the model is charged \
         for strikes measured farther out than they were; try --impact-noise-mm)",
    ),
    sig(
        BallSpeed,
        Trend("impact_y_mm"),
        &[Effect(EffectKind::CorRadial), Effect(EffectKind::ComOffset)],
        "COR or effective mass varying up the face",
    ),
    sig(
        BallSpeed,
        Trend("impact_z_mm"),
        &[
            Effect(EffectKind::ComOffset),
            Effect(EffectKind::InertiaScale),
        ],
        "heel-toe energy loss: CoM position, inertia",
    ),
    sig(
        LaunchAngle,
        Bias,
        &[Effect(EffectKind::LoftBias)],
        "delivered loft measured with an offset",
    ),
    sig(
        LaunchAngle,
        Trend("dynamic_loft_deg"),
        &[
            Effect(EffectKind::LoftBias),
            Effect(EffectKind::TangentialRestitution),
            Effect(EffectKind::Friction),
        ],
        "how far the ball follows the face normal",
    ),
    sig(
        LaunchAngle,
        Trend("impact_y_mm"),
        &[Effect(EffectKind::ComOffset)],
        "vertical gear effect",
    ),
    sig(
        Azimuth,
        Bias,
        &[Effect(EffectKind::FaceBias)],
        "delivered face angle measured with an offset",
    ),
    sig(
        Azimuth,
        Trend("face_angle_deg"),
        &[
            Effect(EffectKind::TangentialRestitution),
            Effect(EffectKind::Friction),
            Effect(EffectKind::FaceBias),
        ],
        "how far the ball follows the face vs the path",
    ),
    sig(
        Azimuth,
        Trend("club_path_deg"),
        &[
            Effect(EffectKind::TangentialRestitution),
            Effect(EffectKind::Friction),
        ],
        "how far the ball follows the path",
    ),
    sig(
        Azimuth,
        Trend("impact_z_mm"),
        &[
            Effect(EffectKind::ComOffset),
            Effect(EffectKind::InertiaScale),
        ],
        "horizontal gear effect",
    ),
    sig(
        Backspin,
        Bias,
        &[Effect(EffectKind::BallOffset), Effect(EffectKind::LoftBias)],
        "ball deformation: CoM off the contact normal (dy)",
    ),
    sig(
        Backspin,
        GroupBias,
        &[
            PerGroup(EffectKind::BallOffset),
            PerGroup(EffectKind::AddedMass),
        ],
        "shaft-dependent spin",
    ),
    sig(
        Backspin,
        Trend("dynamic_loft_deg"),
        &[
            Effect(EffectKind::LoftBias),
            Effect(EffectKind::Friction),
            Effect(EffectKind::TangentialRestitution),
        ],
        "spin loft: grip and loft reading",
    ),
    sig(
        Backspin,
        Trend("club_speed_mph"),
        &[Effect(EffectKind::BallOffset), Effect(EffectKind::Friction)],
        "spin growing with speed: deformation, slip",
    ),
    sig(
        Backspin,
        Trend("impact_y_mm"),
        &[
            Effect(EffectKind::ComOffset),
            Effect(EffectKind::InertiaScale),
        ],
        "vertical gear effect: CoM height/depth, inertia",
    ),
    sig(
        Sidespin,
        Bias,
        &[Effect(EffectKind::BallOffset), Effect(EffectKind::FaceBias)],
        "ball deformation sideways (dz), face reading",
    ),
    sig(
        Sidespin,
        Trend("impact_z_mm"),
        &[
            Effect(EffectKind::ComOffset),
            Effect(EffectKind::InertiaScale),
        ],
        "horizontal gear effect: CoM, inertia",
    ),
    sig(
        Sidespin,
        Trend("face_angle_deg"),
        &[
            Effect(EffectKind::FaceBias),
            Effect(EffectKind::Friction),
            Effect(EffectKind::TangentialRestitution),
        ],
        "face-to-path spin axis",
    ),
    sig(
        Sidespin,
        Trend("club_path_deg"),
        &[
            Effect(EffectKind::Friction),
            Effect(EffectKind::TangentialRestitution),
        ],
        "face-to-path spin axis",
    ),
];

/// Hints for a pattern of one component: `effect, effect (why)` for every matching row.
pub fn hints_for(component: LaunchComponent, pattern: &Pattern) -> Vec<String> {
    SIGNATURES
        .iter()
        .filter(|s| s.component == component && s.pattern == *pattern)
        .map(|s| {
            let names: Vec<String> = s.effects.iter().map(Hint::to_string).collect();
            format!("{} ({})", names.join(" or "), s.why)
        })
        .collect()
}

/// The hint text of a user-defined effect: its name and its own description.
pub fn user_hint_text(h: &Hint) -> String {
    match h {
        Hint::User(u) | Hint::UserPerGroup(u) if !u.doc.is_empty() => {
            format!("{h} (user-defined: {})", u.doc)
        }
        _ => format!("{h} (user-defined)"),
    }
}
