//! Which library effects produce which error pattern: a small table, used to hint at the
//! missing physics behind a finding. Each row was read off the model (an effect's derivative of
//! the launch over typical driver shots); `smash diagnose` tests them quantitatively.

use serde::Serialize;

use crate::physics::LaunchComponent;

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
    /// Effects that produce it (`name` or `name@group`).
    pub effects: &'static [&'static str],
    /// Why, in a few words.
    pub why: &'static str,
}

use LaunchComponent::{Azimuth, Backspin, BallSpeed, LaunchAngle, Sidespin};
use Pattern::{Bias, GroupBias, Trend};

const fn sig(
    component: LaunchComponent,
    pattern: Pattern,
    effects: &'static [&'static str],
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
        &["added_mass"],
        "effective clubhead mass (shaft taking part) or the club's COR",
    ),
    sig(
        BallSpeed,
        GroupBias,
        &["added_mass@group"],
        "shaft mass taking part in the impact",
    ),
    sig(
        BallSpeed,
        Trend("club_speed_mph"),
        &["cor_speed"],
        "COR falling with impact speed",
    ),
    sig(
        BallSpeed,
        Trend("impact_r_mm"),
        &["cor_radial", "impact_noise"],
        "COR falling off-centre, or noisy impact locations (falling with r: the model is charged \
         for strikes measured farther out than they were; try --impact-noise-mm)",
    ),
    sig(
        BallSpeed,
        Trend("impact_y_mm"),
        &["cor_radial", "com_offset"],
        "COR or effective mass varying up the face",
    ),
    sig(
        BallSpeed,
        Trend("impact_z_mm"),
        &["com_offset", "inertia_scale"],
        "heel-toe energy loss: CoM position, inertia",
    ),
    sig(
        LaunchAngle,
        Bias,
        &["loft_bias"],
        "delivered loft measured with an offset",
    ),
    sig(
        LaunchAngle,
        Trend("dynamic_loft_deg"),
        &["loft_bias", "tangential_restitution", "friction"],
        "how far the ball follows the face normal",
    ),
    sig(
        LaunchAngle,
        Trend("impact_y_mm"),
        &["com_offset"],
        "vertical gear effect",
    ),
    sig(
        Azimuth,
        Bias,
        &["face_bias"],
        "delivered face angle measured with an offset",
    ),
    sig(
        Azimuth,
        Trend("face_angle_deg"),
        &["tangential_restitution", "friction", "face_bias"],
        "how far the ball follows the face vs the path",
    ),
    sig(
        Azimuth,
        Trend("club_path_deg"),
        &["tangential_restitution", "friction"],
        "how far the ball follows the path",
    ),
    sig(
        Azimuth,
        Trend("impact_z_mm"),
        &["com_offset", "inertia_scale"],
        "horizontal gear effect",
    ),
    sig(
        Backspin,
        Bias,
        &["ball_offset", "loft_bias"],
        "ball deformation: CoM off the contact normal (dy)",
    ),
    sig(
        Backspin,
        GroupBias,
        &["ball_offset@group", "added_mass@group"],
        "shaft-dependent spin",
    ),
    sig(
        Backspin,
        Trend("dynamic_loft_deg"),
        &["loft_bias", "friction", "tangential_restitution"],
        "spin loft: grip and loft reading",
    ),
    sig(
        Backspin,
        Trend("club_speed_mph"),
        &["ball_offset", "friction"],
        "spin growing with speed: deformation, slip",
    ),
    sig(
        Backspin,
        Trend("impact_y_mm"),
        &["com_offset", "inertia_scale"],
        "vertical gear effect: CoM height/depth, inertia",
    ),
    sig(
        Sidespin,
        Bias,
        &["ball_offset", "face_bias"],
        "ball deformation sideways (dz), face reading",
    ),
    sig(
        Sidespin,
        Trend("impact_z_mm"),
        &["com_offset", "inertia_scale"],
        "horizontal gear effect: CoM, inertia",
    ),
    sig(
        Sidespin,
        Trend("face_angle_deg"),
        &["face_bias", "friction", "tangential_restitution"],
        "face-to-path spin axis",
    ),
    sig(
        Sidespin,
        Trend("club_path_deg"),
        &["friction", "tangential_restitution"],
        "face-to-path spin axis",
    ),
];

/// Hints for a pattern of one component: `effect, effect (why)` for every matching row.
pub fn hints_for(component: LaunchComponent, pattern: &Pattern) -> Vec<String> {
    SIGNATURES
        .iter()
        .filter(|s| s.component == component && s.pattern == *pattern)
        .map(|s| format!("{} ({})", s.effects.join(" or "), s.why))
        .collect()
}
