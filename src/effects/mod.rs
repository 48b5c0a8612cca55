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
//! | `cor_level` | `dcor` | `cor → cor + dcor` (the face's own COR, fitted) |
//! | `hosel_mass` | `dm_g` | point mass at the club's `hosel_mm`: mass, CoM and inertia (parallel axis) |
//! | `cor_power` | `q` | `e = cor·(u1n/48.77 m/s)^(−q)` |
//! | `contact_time` | `tau_ms` | finite contact: the impulse delivered by the face turned by `τ·(ω₀/2 + Δω/9)`, at the point the ball has travelled to, `−τ·(u1/2 − g/9)_t` |
//! | `tangential_compliance` | `et0`, `k_tan`, `eg` | `e_t = et0 + k_tan·|u1t|/u1n` on the approach, `e_g = eg` on the gear-effect drive: `K P = u1 + e·u1n·n + e_t·u1t − e_g·(K·n)_t·P_n0` |
//! | `compression_lever` | `delta_mm` | spin lever `R − δ̄` of the compressed ball: `I_b → I_b·R/(R − δ̄)` |
//! | `face_curvature` | `d_bulge_mm`, `d_roll_mm` | bulge and roll radii + the changes |
//! | `cor_spot` | `y0_mm`, `z0_mm`, `c_per_mm2` | `e = cor − c·((y − y0)² + (z − z0)²)`, y and z in mm |
//! | `shaft_fraction` | `f` | `m_c → m_c + f·m_shaft`, per shot (the paper's Figure 3 relation) |
//! | `inertia_axes` | `sy`, `sz` | `I_yy → s_y·I_yy`, `I_zz → s_z·I_zz` by moving mass (`I_xx` follows) |
//!
//! Each effect is one file in this folder plus one line in the `library!` registration below
//! (`docs/adding-an-effect.md`). An effect only changes [`ModelParams`]; the laws that read
//! them are written once in [`crate::physics::laws`], for the scalar solve and the kernel alike.
//!
//! When several listed effects of one name apply to the same shot (a global one and a per-group
//! one, say), they compose: additive parameters add, `inertia_scale` and `inertia_axes` multiply, and `friction`
//! takes the smallest `mu`.

use std::fmt;

use crate::physics::ModelParams;

pub mod knowledge;
pub mod user;

pub use knowledge::{Needs, Pattern, SignatureRow, StandIn};
pub use user::UserEffect;

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

/// Build a parameter specification (for the effect files).
pub(crate) const fn spec(
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

/// Declares the library: one line per effect, `module => Variant,`. The module is the file
/// `src/effects/<module>.rs`, which defines `NAME`, `DESCRIPTION`, `PARAMS`,
/// `apply(values, &mut ModelParams)` and what the library knows of the effect beyond its law:
/// `SIGNATURE`, `STAND_IN`, `SEPARATE_BY` and `NEEDS` ([`knowledge`]; see
/// `docs/adding-an-effect.md`).
macro_rules! library {
    ($($module:ident => $variant:ident,)*) => {
        $(pub mod $module;)*

        /// The kinds of effect in the library (one per file in `src/effects/`).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum EffectKind {
            $(
                #[doc = concat!("The `", stringify!($module), "` effect (see [`", stringify!($module), "`]).")]
                $variant,
            )*
        }

        impl EffectKind {
            /// Every effect in the library, in registration order.
            pub const ALL: [EffectKind; [$(stringify!($variant)),*].len()] =
                [$(EffectKind::$variant),*];

            /// The effect's name in files and on the command line.
            pub const fn name(self) -> &'static str {
                match self {
                    $(Self::$variant => $module::NAME,)*
                }
            }

            /// One-line description.
            pub const fn description(self) -> &'static str {
                match self {
                    $(Self::$variant => $module::DESCRIPTION,)*
                }
            }

            /// Parameter specifications, in file order.
            pub const fn params(self) -> &'static [ParamSpec] {
                match self {
                    $(Self::$variant => $module::PARAMS,)*
                }
            }

            /// Launch patterns the effect leaves when the model lacks it (compare's hints).
            pub const fn signature(self) -> &'static [knowledge::SignatureRow] {
                match self {
                    $(Self::$variant => $module::SIGNATURE,)*
                }
            }

            /// What a fitted value outside the plausible range behaves like.
            pub const fn stand_in(self) -> knowledge::StandIn {
                match self {
                    $(Self::$variant => $module::STAND_IN,)*
                }
            }

            /// The measurement that pins the effect down independently of launch data.
            pub const fn separate_by(self) -> &'static str {
                match self {
                    $(Self::$variant => $module::SEPARATE_BY,)*
                }
            }

            /// Which delivery variables must vary for shots to identify the effect.
            pub const fn needs(self) -> knowledge::Needs {
                match self {
                    $(Self::$variant => $module::NEEDS,)*
                }
            }

            /// Apply the effect with parameter values `v` (in the units of
            /// [`EffectKind::params`]).
            pub fn apply(self, v: &[f64], p: &mut ModelParams) {
                match self {
                    $(Self::$variant => $module::apply(v, p),)*
                }
            }
        }
    };
}

// The library: one registration line per effect file.
library! {
    added_mass => AddedMass,
    ball_offset => BallOffset,
    tangential_restitution => TangentialRestitution,
    friction => Friction,
    cor_speed => CorSpeed,
    cor_radial => CorRadial,
    loft_bias => LoftBias,
    face_bias => FaceBias,
    com_offset => ComOffset,
    inertia_scale => InertiaScale,
    cor_level => CorLevel,
    hosel_mass => HoselMass,
    cor_power => CorPower,
    contact_time => ContactTime,
    tangential_compliance => TangentialCompliance,
    compression_lever => CompressionLever,
    face_curvature => FaceCurvature,
    cor_spot => CorSpot,
    shaft_fraction => ShaftFraction,
    inertia_axes => InertiaAxes,
}

impl EffectKind {
    /// Look an effect up by name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Comma-separated list of all effect names, for error messages.
    pub fn all_names() -> String {
        Self::ALL.map(|k| k.name()).join(", ")
    }
}

impl fmt::Display for EffectKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Any effect: one of the library ([`EffectKind`], typed, so compare's hints stay checked by
/// the compiler) or one defined by the user at run time ([`user`]).
#[derive(Debug, Clone, Copy)]
pub enum EffectId {
    /// A library effect.
    Library(EffectKind),
    /// A user-defined effect (registered for the life of the process).
    User(&'static UserEffect),
}

impl From<EffectKind> for EffectId {
    fn from(k: EffectKind) -> Self {
        EffectId::Library(k)
    }
}

impl PartialEq for EffectId {
    fn eq(&self, o: &Self) -> bool {
        match (self, o) {
            (EffectId::Library(a), EffectId::Library(b)) => a == b,
            (EffectId::User(a), EffectId::User(b)) => a.name == b.name,
            _ => false,
        }
    }
}

impl Eq for EffectId {}

impl PartialEq<EffectKind> for EffectId {
    fn eq(&self, o: &EffectKind) -> bool {
        matches!(self, EffectId::Library(k) if k == o)
    }
}

impl std::hash::Hash for EffectId {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        self.name().hash(h)
    }
}

impl PartialOrd for EffectId {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for EffectId {
    /// Library effects first, in registration order, then user-defined ones by name.
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        match (self, o) {
            (EffectId::Library(a), EffectId::Library(b)) => a.cmp(b),
            (EffectId::Library(_), EffectId::User(_)) => std::cmp::Ordering::Less,
            (EffectId::User(_), EffectId::Library(_)) => std::cmp::Ordering::Greater,
            (EffectId::User(a), EffectId::User(b)) => a.name.cmp(b.name),
        }
    }
}

impl EffectId {
    /// Look an effect up by name: the library, then the registered user-defined effects.
    pub fn from_name(name: &str) -> Option<Self> {
        EffectKind::from_name(name)
            .map(EffectId::Library)
            .or_else(|| user::lookup(name).map(EffectId::User))
    }

    /// Comma-separated names of the library and the registered user-defined effects.
    pub fn all_names() -> String {
        let mut names = EffectKind::all_names();
        for u in user::registered() {
            names.push_str(", ");
            names.push_str(u.name);
        }
        names
    }

    /// The library kind, if it is one.
    pub fn library(self) -> Option<EffectKind> {
        match self {
            EffectId::Library(k) => Some(k),
            EffectId::User(_) => None,
        }
    }

    /// The user-defined effect, if it is one.
    pub fn user(self) -> Option<&'static UserEffect> {
        match self {
            EffectId::Library(_) => None,
            EffectId::User(u) => Some(u),
        }
    }

    /// The effect's name in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            EffectId::Library(k) => k.name(),
            EffectId::User(u) => u.name,
        }
    }

    /// One-line description.
    pub fn description(self) -> &'static str {
        match self {
            EffectId::Library(k) => k.description(),
            EffectId::User(u) => u.doc,
        }
    }

    /// Parameter specifications, in file order.
    pub fn params(self) -> &'static [ParamSpec] {
        match self {
            EffectId::Library(k) => k.params(),
            EffectId::User(u) => u.params,
        }
    }

    /// Apply with parameter values `v` (units of [`EffectId::params`]).
    pub fn apply(self, v: &[f64], p: &mut ModelParams) {
        match self {
            EffectId::Library(k) => k.apply(v, p),
            EffectId::User(u) => u.apply(v, p),
        }
    }
}

impl fmt::Display for EffectId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Why an effect cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EffectError {
    /// No effect has this name.
    #[error(
        "unknown effect '{name}'{}; the library has: {}",
        crate::suggest::did_you_mean(name, EffectId::all_names().split(", "))
            .map_or_else(String::new, |m| format!(" (did you mean '{m}'?)")),
        EffectId::all_names()
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
    kind: EffectId,
    values: [f64; MAX_EFFECT_PARAMS],
    group: Option<String>,
}

impl Effect {
    /// Build an effect; `values` in the order and units of `kind.params()`, each within bounds.
    pub fn new(
        kind: impl Into<EffectId>,
        values: &[f64],
        group: Option<String>,
    ) -> Result<Self, EffectError> {
        let kind = kind.into();
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
    pub fn with_defaults(kind: impl Into<EffectId>, group: Option<String>) -> Self {
        let kind = kind.into();
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
    pub fn kind(&self) -> EffectId {
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
