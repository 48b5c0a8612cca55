//! The effect library: named physics beyond the nominal model.
//!
//! Every effect has a name, named parameters with units, defaults and physical bounds, and is off
//! unless listed. The names, parameter names and forms are fixed by `docs/conventions.md` (data and
//! configs depend on them). An effect applies to every shot, or only to the shots of one `group`.
//!
//! | name | parameters | what it does |
//! |---|---|---|
//! | `added_mass` | `dm_g` | `m_c → m_c + dm` (the paper's shaft effect) |
//! | `ball_offset` | `dy_mm`, `dz_mm` | `^I r_b = (−radius, dy, dz)` (the paper's ball deformation) |
//! | `tangential_restitution` | `et` | `e_t` in `K P = u1 + e·u1n·n + e_t·(u1 − u1n·n)` |
//! | `friction` | `mu` | gross slip when the no-slip tangential impulse exceeds `mu·P_n` |
//! | `cor_speed` | `k_per_m_s` | `e = cor − k·(u1n − 48.77 m/s)` |
//! | `cor_radial` | `c_per_mm2` | `e = cor − c·(y² + z²)`, y and z in mm |
//! | `loft_bias` | `deg` | delivered dynamic loft + deg |
//! | `face_bias` | `deg` | delivered face angle + deg |
//! | `com_offset` | `dx_mm`, `dy_mm`, `dz_mm` | clubhead CoM + offset, in F |
//! | `inertia_scale` | `s` | `I_c → s·I_c` |
//!
//! When several listed effects of one name apply to the same shot (a global one and a per-group
//! one, say), they compose: additive parameters add, `inertia_scale` multiplies, and `friction`
//! takes the smallest `mu`.

use std::fmt;

use crate::physics::ModelParams;
use crate::units::{deg, mm};

/// Most parameters any effect has.
pub const MAX_EFFECT_PARAMS: usize = 3;

/// One parameter of an effect: its key, unit, neutral/default value and physical bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamSpec {
    /// Key in TOML tables and reports (`dm_g`, `dy_mm`, …). The unit is part of the key.
    pub key: &'static str,
    /// Unit, for reports (`g`, `mm`, `1`, …).
    pub unit: &'static str,
    /// The value at which the effect does nothing; also the starting value of a fit
    /// (for `friction`, whose neutral value is infinite, a typical value).
    pub default: f64,
    /// Smallest physical value (inclusive).
    pub lower: f64,
    /// Largest physical value (inclusive).
    pub upper: f64,
    /// Range of values a real driver impact plausibly shows (inside `[lower, upper]`): a fitted
    /// value outside it is a stand-in for some other physics, not a finding. Sources and
    /// reasons: `docs/plausible-ranges.md`.
    pub plausible: (f64, f64),
    /// What the parameter means.
    pub doc: &'static str,
}

/// The kinds of effect in the library.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum EffectKind {
    /// Added clubhead mass (the paper's shaft effect).
    AddedMass,
    /// Shifted ball centre of mass relative to the contact point (the paper's ball deformation).
    BallOffset,
    /// Tangential restitution `e_t`.
    TangentialRestitution,
    /// Coulomb friction limit on the tangential impulse.
    Friction,
    /// COR falling linearly with normal approach speed.
    CorSpeed,
    /// COR falling with squared distance from the face centre.
    CorRadial,
    /// Bias on delivered dynamic loft.
    LoftBias,
    /// Bias on delivered face angle.
    FaceBias,
    /// Offset of the clubhead centre of mass.
    ComOffset,
    /// Scaling of the clubhead inertia tensor.
    InertiaScale,
}

const fn spec(
    key: &'static str,
    unit: &'static str,
    default: f64,
    lower: f64,
    upper: f64,
    plausible: (f64, f64),
    doc: &'static str,
) -> ParamSpec {
    ParamSpec {
        key,
        unit,
        default,
        lower,
        upper,
        plausible,
        doc,
    }
}

const ADDED_MASS: [ParamSpec; 1] = [spec(
    "dm_g",
    "g",
    0.0,
    -100.0,
    200.0,
    (0.0, 10.0),
    "mass added to the clubhead",
)];
const BALL_OFFSET: [ParamSpec; 2] = [
    spec(
        "dy_mm",
        "mm",
        0.0,
        -10.0,
        10.0,
        (-2.0, 2.0),
        "contact point relative to ball CoM, along y_I",
    ),
    spec(
        "dz_mm",
        "mm",
        0.0,
        -10.0,
        10.0,
        (-2.0, 2.0),
        "contact point relative to ball CoM, along z_I",
    ),
];
const TANGENTIAL_RESTITUTION: [ParamSpec; 1] = [spec(
    "et",
    "1",
    0.0,
    -1.0,
    1.0,
    (-0.3, 0.3),
    "tangential restitution (0 = no slip, the paper's model)",
)];
const FRICTION: [ParamSpec; 1] = [spec(
    "mu",
    "1",
    0.4,
    1e-3,
    2.0,
    (0.1, 0.6),
    "Coulomb friction coefficient face-ball",
)];
const COR_SPEED: [ParamSpec; 1] = [spec(
    "k_per_m_s",
    "s/m",
    0.0,
    0.0,
    0.02, (0.0, 0.005),
    "COR drop per m/s of normal approach speed above 48.77 m/s (a ball's COR falls with speed: k >= 0)",
)];
const COR_RADIAL: [ParamSpec; 1] = [spec(
    "c_per_mm2",
    "1/mm²",
    0.0,
    0.0,
    2e-3,
    (0.0, 3e-4),
    "COR drop per mm² of squared distance from the face centre (COR peaks at the centre: c >= 0)",
)];
const LOFT_BIAS: [ParamSpec; 1] = [spec(
    "deg",
    "deg",
    0.0,
    -15.0,
    15.0,
    (-3.0, 3.0),
    "added to the delivered dynamic loft",
)];
const FACE_BIAS: [ParamSpec; 1] = [spec(
    "deg",
    "deg",
    0.0,
    -15.0,
    15.0,
    (-3.0, 3.0),
    "added to the delivered face angle",
)];
const COM_OFFSET: [ParamSpec; 3] = [
    spec(
        "dx_mm",
        "mm",
        0.0,
        -30.0,
        30.0,
        (-3.0, 3.0),
        "clubhead CoM shift along x_F (face normal)",
    ),
    spec(
        "dy_mm",
        "mm",
        0.0,
        -30.0,
        30.0,
        (-3.0, 3.0),
        "clubhead CoM shift along y_F (up)",
    ),
    spec(
        "dz_mm",
        "mm",
        0.0,
        -30.0,
        30.0,
        (-3.0, 3.0),
        "clubhead CoM shift along z_F (toe)",
    ),
];
const INERTIA_SCALE: [ParamSpec; 1] = [spec(
    "s",
    "1",
    1.0,
    0.1,
    10.0,
    (0.85, 1.15),
    "factor on the clubhead inertia tensor",
)];

impl EffectKind {
    /// Every effect in the library, in the order of `docs/conventions.md`.
    pub const ALL: [EffectKind; 10] = [
        Self::AddedMass,
        Self::BallOffset,
        Self::TangentialRestitution,
        Self::Friction,
        Self::CorSpeed,
        Self::CorRadial,
        Self::LoftBias,
        Self::FaceBias,
        Self::ComOffset,
        Self::InertiaScale,
    ];

    /// The effect's name in files and on the command line.
    pub const fn name(self) -> &'static str {
        match self {
            Self::AddedMass => "added_mass",
            Self::BallOffset => "ball_offset",
            Self::TangentialRestitution => "tangential_restitution",
            Self::Friction => "friction",
            Self::CorSpeed => "cor_speed",
            Self::CorRadial => "cor_radial",
            Self::LoftBias => "loft_bias",
            Self::FaceBias => "face_bias",
            Self::ComOffset => "com_offset",
            Self::InertiaScale => "inertia_scale",
        }
    }

    /// One-line description.
    pub const fn description(self) -> &'static str {
        match self {
            Self::AddedMass => "m_c -> m_c + dm (shaft mass taking part in the impact)",
            Self::BallOffset => "ball CoM shifted from the contact normal (ball deformation)",
            Self::TangentialRestitution => "tangential rebound e_t instead of no slip",
            Self::Friction => "Coulomb limit mu on the tangential impulse (gross slip)",
            Self::CorSpeed => "COR falls linearly with normal approach speed",
            Self::CorRadial => "COR falls with squared distance from the face centre",
            Self::LoftBias => "bias on the measured dynamic loft",
            Self::FaceBias => "bias on the measured face angle",
            Self::ComOffset => "clubhead centre of mass offset, in F",
            Self::InertiaScale => "clubhead inertia tensor scaled",
        }
    }

    /// Parameter specifications, in file order.
    pub const fn params(self) -> &'static [ParamSpec] {
        match self {
            Self::AddedMass => &ADDED_MASS,
            Self::BallOffset => &BALL_OFFSET,
            Self::TangentialRestitution => &TANGENTIAL_RESTITUTION,
            Self::Friction => &FRICTION,
            Self::CorSpeed => &COR_SPEED,
            Self::CorRadial => &COR_RADIAL,
            Self::LoftBias => &LOFT_BIAS,
            Self::FaceBias => &FACE_BIAS,
            Self::ComOffset => &COM_OFFSET,
            Self::InertiaScale => &INERTIA_SCALE,
        }
    }

    /// Look an effect up by name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Comma-separated list of all effect names, for error messages.
    pub fn all_names() -> String {
        Self::ALL.map(|k| k.name()).join(", ")
    }

    /// Apply the effect with parameter values `v` (in the units of [`EffectKind::params`]).
    pub fn apply(self, v: &[f64], p: &mut ModelParams) {
        match self {
            Self::AddedMass => p.club_mass_kg += v[0] * 1e-3,
            Self::BallOffset => {
                p.ball_offset_y_m += mm(v[0]);
                p.ball_offset_z_m += mm(v[1]);
            }
            Self::TangentialRestitution => p.tangential_restitution += v[0],
            Self::Friction => p.friction_mu = Some(p.friction_mu.map_or(v[0], |mu| mu.min(v[0]))),
            Self::CorSpeed => p.cor_speed_k_s_per_m += v[0],
            Self::CorRadial => p.cor_radial_c_per_m2 += v[0] * 1e6,
            Self::LoftBias => p.loft_bias_rad += deg(v[0]),
            Self::FaceBias => p.face_bias_rad += deg(v[0]),
            Self::ComOffset => {
                p.club_com_m.x += mm(v[0]);
                p.club_com_m.y += mm(v[1]);
                p.club_com_m.z += mm(v[2]);
            }
            Self::InertiaScale => p.club_inertia_kgm2 *= v[0],
        }
    }
}

impl fmt::Display for EffectKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Why an effect cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EffectError {
    /// No effect has this name.
    #[error(
        "unknown effect '{name}'; the library has: {}",
        EffectKind::all_names()
    )]
    UnknownName {
        /// The name given.
        name: String,
    },
    /// A parameter value is missing, not finite or outside its physical bounds.
    #[error(
        "{effect}.{key} = {} is outside its physical range [{lower}, {upper}] {unit}",
        crate::units::Num(*.value)
    )]
    OutOfBounds {
        /// Effect name.
        effect: &'static str,
        /// Parameter key.
        key: &'static str,
        /// Value given.
        value: f64,
        /// Lower bound.
        lower: f64,
        /// Upper bound.
        upper: f64,
        /// Unit.
        unit: &'static str,
    },
    /// Wrong number of parameter values.
    #[error("{effect} takes {expected} parameter(s) ({keys}), got {got}")]
    Arity {
        /// Effect name.
        effect: &'static str,
        /// Expected count.
        expected: usize,
        /// Keys expected.
        keys: String,
        /// Count given.
        got: usize,
    },
}

/// An effect with its parameter values, global or restricted to one group of shots.
#[derive(Debug, Clone, PartialEq)]
pub struct Effect {
    kind: EffectKind,
    values: [f64; MAX_EFFECT_PARAMS],
    group: Option<String>,
}

impl Effect {
    /// Build an effect; `values` in the order and units of `kind.params()`, each within bounds.
    pub fn new(
        kind: EffectKind,
        values: &[f64],
        group: Option<String>,
    ) -> Result<Self, EffectError> {
        let specs = kind.params();
        if values.len() != specs.len() {
            return Err(EffectError::Arity {
                effect: kind.name(),
                expected: specs.len(),
                keys: specs.iter().map(|s| s.key).collect::<Vec<_>>().join(", "),
                got: values.len(),
            });
        }
        let mut stored = [0.0; MAX_EFFECT_PARAMS];
        for ((slot, &value), s) in stored.iter_mut().zip(values).zip(specs) {
            if !(value.is_finite() && value >= s.lower && value <= s.upper) {
                return Err(EffectError::OutOfBounds {
                    effect: kind.name(),
                    key: s.key,
                    value,
                    lower: s.lower,
                    upper: s.upper,
                    unit: s.unit,
                });
            }
            *slot = value;
        }
        Ok(Self {
            kind,
            values: stored,
            group,
        })
    }

    /// The effect at its default parameter values.
    pub fn with_defaults(kind: EffectKind, group: Option<String>) -> Self {
        let mut values = [0.0; MAX_EFFECT_PARAMS];
        for (slot, s) in values.iter_mut().zip(kind.params()) {
            *slot = s.default;
        }
        Self {
            kind,
            values,
            group,
        }
    }

    /// Kind of effect.
    pub fn kind(&self) -> EffectKind {
        self.kind
    }

    /// Parameter values in the order and units of `kind().params()`.
    pub fn values(&self) -> &[f64] {
        &self.values[..self.kind.params().len()]
    }

    /// Group this effect is restricted to, or `None` for all shots.
    pub fn group(&self) -> Option<&str> {
        self.group.as_deref()
    }

    /// Does the effect apply to shots of `group`?
    pub fn applies_to(&self, group: &str) -> bool {
        self.group.as_deref().is_none_or(|g| g == group)
    }

    /// Apply to model parameters.
    pub fn apply(&self, p: &mut ModelParams) {
        self.kind.apply(self.values(), p);
    }

    /// `name` or `name@group`, as on the command line.
    pub fn label(&self) -> String {
        match &self.group {
            Some(g) => format!("{}@{}", self.kind.name(), g),
            None => self.kind.name().to_string(),
        }
    }
}

impl fmt::Display for Effect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}(", self.label())?;
        for (i, (s, v)) in self.kind.params().iter().zip(self.values()).enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{} = {}", s.key, v)?;
        }
        f.write_str(")")
    }
}
