//! Limits, in one place: the physical range of every input quantity, and the caps on how much
//! work one command may be asked to do.
//!
//! Every reader (club, shots, study, synth files and the command line) checks its inputs against
//! the ranges here, so a value that is not a golf club, a golf ball or a golf swing is refused at
//! the edge, with the file, key or column, the value and the allowed range. The ranges are wide
//! (every real club and swing lies well inside), but finite: inside them no derived quantity of
//! the impact model can overflow to infinity or lose all precision, which is what keeps `inf`
//! and `NaN` out of every output.
//!
//! Every product of counts (design axes, grid points × variants, groups × shots, …) goes
//! through [`count_product`]: checked arithmetic, one cap, and a message that states the
//! factors, the product and the limit.

use std::fmt;

/// The physically meaningful values of one quantity, in its file unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicalRange {
    /// What the quantity is, for messages (`club speed`).
    pub quantity: &'static str,
    /// File unit (`mph`).
    pub unit: &'static str,
    /// Lowest value.
    pub min: f64,
    /// Highest value (inclusive).
    pub max: f64,
    /// Whether `min` itself is allowed (`false`: values must exceed it).
    pub min_inclusive: bool,
}

impl PhysicalRange {
    const fn closed(quantity: &'static str, unit: &'static str, min: f64, max: f64) -> Self {
        Self {
            quantity,
            unit,
            min,
            max,
            min_inclusive: true,
        }
    }

    const fn above(quantity: &'static str, unit: &'static str, min: f64, max: f64) -> Self {
        Self {
            quantity,
            unit,
            min,
            max,
            min_inclusive: false,
        }
    }

    /// Whether `x` is finite and in the range.
    pub fn contains(&self, x: f64) -> bool {
        let low_ok = if self.min_inclusive {
            x >= self.min
        } else {
            x > self.min
        };
        x.is_finite() && low_ok && x <= self.max
    }

    /// `x`, or an error stating the value and the allowed range (no location: the caller
    /// names the file, key or column).
    pub fn check(&self, x: f64) -> Result<f64, LimitError> {
        if self.contains(x) {
            Ok(x)
        } else {
            Err(LimitError::OutOfRange {
                range: *self,
                value: x,
            })
        }
    }

    /// The message for a value outside the range.
    pub fn refusal(&self, x: f64) -> String {
        LimitError::OutOfRange {
            range: *self,
            value: x,
        }
        .to_string()
    }
}

/// A value refused by a limit: the message states the value and what is allowed (no location:
/// the caller names the file, key or column).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LimitError {
    /// Outside a [`PhysicalRange`].
    #[error("{} {} is outside the physical range {range}", range.quantity, fmt_value(*value))]
    OutOfRange {
        /// The range.
        range: PhysicalRange,
        /// The value, in the range's unit.
        value: f64,
    },
    /// A part of the head at or in front of the face plane ([`check_behind_face_mm`]).
    #[error(
        "{what} x = {} mm is at or in front of the face (x_F points out of the face, the face \
         is at x = 0); it must be behind the face, in [-500, 0) mm",
        fmt_value(*x_mm)
    )]
    NotBehindFace {
        /// What is placed (`club centre of mass`, …).
        what: String,
        /// Its position along the face normal, mm.
        x_mm: f64,
    },
    /// A part of the head that weighs nothing or as much as the head
    /// ([`check_head_part_mass_g`]).
    #[error(
        "{what} {} g is not part of the head: it must be above 0 g and below the head mass, {} g \
         (the rest of the head holds the face)",
        fmt_value(*mass_g),
        fmt_value(*head_g)
    )]
    NotPartOfHead {
        /// What is placed (`discretionary mass`, …).
        what: String,
        /// Its mass, g.
        mass_g: f64,
        /// The head's mass, g, to the microgram.
        head_g: f64,
    },
}

impl fmt::Display for PhysicalRange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let open = if self.min_inclusive { '[' } else { '(' };
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        write!(
            f,
            "{open}{}, {}]{unit}",
            fmt_value(self.min),
            fmt_value(self.max)
        )
    }
}

/// A number for a message: short, and in scientific notation when huge or tiny (never 300
/// digits); the one rule is [`crate::units::Num`].
pub fn fmt_value(x: f64) -> String {
    crate::units::Num(x).to_string()
}

/// Clubhead CoM speed at impact, mph. The fastest long-drive swings measured are near 150 mph
/// and the slowest putts a few mph; 250 leaves room for any real club while keeping ball speed,
/// spin and energy far from overflow, and below 1 mph the head's rotation would dominate the
/// contact velocity and ratios such as the smash factor lose their meaning.
pub const CLUB_SPEED_MPH: PhysicalRange = PhysicalRange::closed("club speed", "mph", 1.0, 250.0);

/// Delivery angles (attack angle, club path, face angle, lie tilt), deg. Beyond ±90° the club
/// moves away from the target or the face points backwards: no golf stroke.
pub const DELIVERY_ANGLE_DEG: PhysicalRange =
    PhysicalRange::closed("delivery angle", "deg", -90.0, 90.0);

/// Dynamic loft at impact, deg: from a strongly delofted putter (−90 is a face pointing at the
/// ground) to a face pointing straight up (90).
pub const DYNAMIC_LOFT_DEG: PhysicalRange =
    PhysicalRange::closed("dynamic loft", "deg", -90.0, 90.0);

/// Smallest spacing of a study's `{ from, to, count }` or `{ from, to, step }` range, in the
/// axis's unit (mm for impact locations and CoM moves, g for masses, 1 for scale factors): a
/// micrometre or a microgram is far below what any face map or design can resolve, and closer
/// values only repeat each other's result (or print as hundreds of digits).
pub const MIN_AXIS_SPACING: f64 = 1e-6;

/// Smallest normal approach speed `u1·n` at which the club counts as approaching the ball,
/// m/s: 0.1 mm/s. The one threshold of the scalar solve (`ImpactModel::solve`), the face-map
/// kernel's lanes (`sweep::kernel`) and the fits' lanes (`fit::problem`), so that all three
/// decide validity alike. Why not 0: a face turned exactly along the club's path (a loft of
/// 90° on a level swing) has `u1·n` of rounding size (≈3e-15 m/s), whose sign is noise. At the
/// largest allowed speeds (club speed 250 mph, head rotation 200 rad/s about a point 0.5 m
/// away: |u1| ≲ 250 m/s) that rounding is below 1e-12 m/s, eight orders under the threshold;
/// and an approach of 0.1 mm/s launches the ball at under 0.2 mm/s, far below what any launch
/// monitor or golf shot has, so no real impact is refused.
pub const MIN_NORMAL_APPROACH_M_S: f64 = 1e-4;

/// One component of the clubhead's angular velocity, rad/s. Measured values at impact are a few
/// tens of rad/s (the face closes at up to about 50 rad/s); 200 leaves a factor of four.
pub const CLUB_OMEGA_RAD_S: PhysicalRange =
    PhysicalRange::closed("clubhead angular velocity", "rad/s", -200.0, 200.0);

/// Impact location from the centre of face in either direction, mm (shots, grids, probe lines,
/// distributions). The largest driver faces span about 60 mm by 110 mm; 100 mm from the centre
/// is off every club face.
pub const IMPACT_LOCATION_MM: PhysicalRange =
    PhysicalRange::closed("impact location", "mm", -100.0, 100.0);

/// Values of a study's face grid, mm. A grid may reach past the face's edge to show where the
/// face ends (those points are marked invalid); no club face is a metre from its centre.
pub const GRID_LOCATION_MM: PhysicalRange =
    PhysicalRange::closed("grid location", "mm", -1000.0, 1000.0);

/// Standard deviation of an impact location, mm (a study's distribution): wider than a face.
pub const SIGMA_LOCATION_MM: PhysicalRange =
    PhysicalRange::closed("impact-location spread", "mm", 0.0, 100.0);

/// Standard deviation of the club speed, mph (a study's distribution).
pub const SIGMA_CLUB_SPEED_MPH: PhysicalRange =
    PhysicalRange::closed("club-speed spread", "mph", 0.0, 50.0);

/// Standard deviation of a delivery angle, deg (a study's distribution).
pub const SIGMA_ANGLE_DEG: PhysicalRange =
    PhysicalRange::closed("delivery-angle spread", "deg", 0.0, 30.0);

/// Half-length of a study's summary probe lines through the centre of face, mm (the lines
/// must also lie on the club's face, which is checked against the club).
pub const PROBE_HALF_WIDTH_MM: PhysicalRange =
    PhysicalRange::above("probe half-width", "mm", 0.0, 100.0);

/// Shaft mass, g. Real shafts weigh 40–130 g.
pub const SHAFT_MASS_G: PhysicalRange = PhysicalRange::above("shaft mass", "g", 0.0, 1000.0);

/// Measured ball speed, mph. The fastest measured drives launch near 230 mph. A ball speed of
/// 0 is no launch (TrackMan and GSPro write 0 for a shot they did not measure): above 0.
pub const BALL_SPEED_MPH: PhysicalRange =
    PhysicalRange::above("measured ball speed", "mph", 0.0, 400.0);

/// Measured launch angle or azimuth, deg: a ball leaving the face goes forward.
pub const LAUNCH_DIRECTION_DEG: PhysicalRange =
    PhysicalRange::closed("measured launch direction", "deg", -90.0, 90.0);

/// Measured backspin or sidespin, rpm. Wedges spin near 12,000 rpm; launch monitors stop far
/// below 30,000.
pub const BALL_SPIN_RPM: PhysicalRange =
    PhysicalRange::closed("measured spin", "rpm", -30_000.0, 30_000.0);

/// Total spin rate of a launch-monitor export, rpm: a magnitude (never negative), with the same
/// ceiling as [`BALL_SPIN_RPM`].
pub const SPIN_RATE_RPM: PhysicalRange = PhysicalRange::closed("spin rate", "rpm", 0.0, 30_000.0);

/// Spin axis tilt of a launch-monitor export, deg (+ tilted right): a direction, so within a
/// half turn either way. Past ±90° the ball carries topspin, as a topped shot does (the shots
/// file's backspin may be negative, and the model predicts it for strikes low on the face).
pub const SPIN_AXIS_DEG: PhysicalRange = PhysicalRange::closed("spin axis", "deg", -180.0, 180.0);

/// Clubhead mass, g: from a toy head to a sledgehammer (drivers weigh about 200 g).
pub const CLUB_MASS_G: PhysicalRange = PhysicalRange::closed("club mass", "g", 1.0, 10_000.0);

/// One component of the clubhead CoM's position from the centre of face, mm. A driver's CoM
/// sits about 40 mm behind the face; no head is half a metre long.
pub const CLUB_COM_MM: PhysicalRange =
    PhysicalRange::closed("club centre of mass", "mm", -500.0, 500.0);

/// `Err` with the value and the allowed range when a clubhead CoM at `x_mm` along the face
/// normal `x_F` is not behind the face. `x_F` points out of the face at the ball
/// (`docs/conventions.md`); the centre of mass of a real head lies inside it, behind the face
/// (a driver's about 40 mm): at or in front of the face plane (`x ≥ 0`) it is not a clubhead.
/// The far end is [`CLUB_COM_MM`]'s.
pub fn check_club_com_x_mm(x_mm: f64) -> Result<f64, LimitError> {
    check_behind_face_mm("club centre of mass", x_mm)
}

/// [`check_club_com_x_mm`] for any part of the head (`what`: a discretionary mass, …): the
/// head's mass lies behind its face.
pub fn check_behind_face_mm(what: &str, x_mm: f64) -> Result<f64, LimitError> {
    if x_mm < 0.0 && CLUB_COM_MM.contains(x_mm) {
        Ok(x_mm)
    } else {
        Err(LimitError::NotBehindFace {
            what: what.to_owned(),
            x_mm,
        })
    }
}

/// A club's static (address) loft, deg, as a club file's `loft_deg` states it. Real clubs run
/// from putters' 2–4° (the Equipment Rules allow a putter at most 10°) through drivers' 8–12°
/// to lob wedges' 60–64°, the most lofted clubs the makers sell (a few novelty wedges reach
/// 70–72°); 80° leaves room for any of them. Below 0 the face points down at the ground, which
/// no club does; 1000° is not an angle a face can have.
pub const STATIC_LOFT_DEG: PhysicalRange = PhysicalRange::closed("static loft", "deg", 0.0, 80.0);

/// `Err` with the value and the allowed range when a part of the head of `m_g` grams (a
/// discretionary mass, a mass moved within the head) is not a part of a head of `head_kg`
/// kilograms: it must weigh more than nothing and less than the whole head. Compared in the
/// head's own unit, so that a 204 g part of a 204 g head (0.204 kg read back as
/// 204.00000000000003 g) is refused, not let through by rounding.
pub fn check_head_part_mass_g(what: &str, m_g: f64, head_kg: f64) -> Result<f64, LimitError> {
    if m_g.is_finite() && m_g > 0.0 && crate::units::g(m_g) < head_kg {
        Ok(m_g)
    } else {
        Err(LimitError::NotPartOfHead {
            what: what.to_owned(),
            mass_g: m_g,
            // To the microgram: the head's 0.204 kg is shown as 204, not 204.00000000000003.
            head_g: (head_kg / crate::units::KG_PER_G * 1e6).round() / 1e6,
        })
    }
}

/// One component of the hosel's position (where the shaft joins the head) from the centre of
/// face, mm: like the CoM, somewhere on a head that is nowhere near half a metre long.
pub const HOSEL_MM: PhysicalRange = PhysicalRange::closed("hosel position", "mm", -500.0, 500.0);

/// One entry of the clubhead inertia tensor, g·cm². Drivers are near 5000 g·cm² (the USGA MOI
/// limit is 5900); 10⁶ allows any club while keeping the tensor's inverse well conditioned.
pub const CLUB_INERTIA_GCM2: PhysicalRange =
    PhysicalRange::closed("club inertia entry", "g·cm²", -1e6, 1e6);

/// The farthest any point of a clubhead lies from another, mm: the diagonal of the largest box
/// the Rules of Golf let a head fill (Equipment Rules, Part 2, 4b): a putter's head at most 7 in
/// (177.8 mm) heel to toe, less than that face to back, at most 2.5 in (63.5 mm) sole to top; a
/// wood's at most 5 in (127 mm) and 2.8 in (71.12 mm), within the same box when its height is
/// taken as 71.12 mm. √(177.8² + 177.8² + 71.12²) = 261.3 mm, rounded up. (Irons, which those
/// rules do not bound, are about 80 mm heel to toe.) A point farther than this from the centre
/// of face, which lies on the head, is outside any head.
pub const HEAD_REACH_MM: f64 = 262.0;

/// The density of the densest material, g/cm³: osmium, 22.59 (CRC Handbook of Chemistry and
/// Physics, "Physical constants of inorganic compounds"); tungsten, the densest metal a head is
/// weighted with, is 19.3.
pub const DENSEST_G_CM3: f64 = 22.59;

/// The least principal moment of inertia about its centre of mass a clubhead of `mass_g` grams
/// can have, g·cm². About any axis, the moment `∫ r⊥² dm` of a body of mass `M` that spans at
/// most a length `L` along the axis and is nowhere denser than `ρ` is least when each slice
/// across the axis is a full disc of density `ρ` about it, and the slices hold equal masses:
/// a rod of radius `R` with `M = ρ π R² L`, whose moment is `M R² / 2 = M² / (2 π ρ L)`. With
/// `L` = [`HEAD_REACH_MM`] (26.2 cm) and `ρ` = [`DENSEST_G_CM3`] that is `M² / 3719` g·cm²:
/// 11.2 g·cm² for a 204 g driver head, whose real moments are 2800–5700 g·cm² (a 1 g toy head:
/// 0.00027). A tensor with a smaller principal moment is no head of that mass: its mass would
/// have to sit closer to the axis than any matter can be packed.
pub fn min_head_moment_gcm2(mass_g: f64) -> f64 {
    mass_g * mass_g / (2.0 * std::f64::consts::PI * DENSEST_G_CM3 * HEAD_REACH_MM / 10.0)
}

/// `x` to 6 significant digits, or as many more as keep it outside `range` (for a refused value
/// computed by the program, `2.8429999999999995e9` printed as `2.843e9`; never rounded back
/// inside the range it was refused by).
pub fn shown_outside(x: f64, range: &PhysicalRange) -> f64 {
    (6..=17)
        .filter_map(|d| format!("{:.*e}", d - 1, x).parse::<f64>().ok())
        .find(|r| !range.contains(*r))
        .unwrap_or(x)
}

/// Face bulge and roll radii, mm. Driver faces have 250–330 mm; a radius below the ball's 21 mm
/// cannot meet a ball, and 10⁶ mm is a flat face for every purpose.
pub const FACE_RADIUS_MM: PhysicalRange = PhysicalRange::closed("face radius", "mm", 20.0, 1e6);

/// Ball mass, g (the rules cap a golf ball at 45.93 g).
pub const BALL_MASS_G: PhysicalRange = PhysicalRange::closed("ball mass", "g", 1.0, 1000.0);

/// Ball radius, mm (a golf ball is at least 21.335 mm).
pub const BALL_RADIUS_MM: PhysicalRange = PhysicalRange::closed("ball radius", "mm", 1.0, 200.0);

/// Ball moment of inertia, g·cm² (a golf ball is near 80).
pub const BALL_INERTIA_GCM2: PhysicalRange =
    PhysicalRange::closed("ball inertia", "g·cm²", 0.01, 1e6);

/// A design study's CoM offset or discretionary-mass move, mm: within the head (see
/// [`IMPACT_LOCATION_MM`] for the face's size).
pub const DESIGN_OFFSET_MM: PhysicalRange =
    PhysicalRange::closed("design offset", "mm", -100.0, 100.0);

/// A design study's inertia scale (whole tensor or one axis), 1: from a tenth to ten times the
/// base club.
pub const DESIGN_INERTIA_SCALE: PhysicalRange =
    PhysicalRange::closed("inertia scale", "", 0.1, 10.0);

/// A design study's change of a principal moment, g·cm² (the base moments are a few thousand).
pub const DESIGN_MOMENT_CHANGE_GCM2: PhysicalRange =
    PhysicalRange::closed("principal-moment change", "g·cm²", -1e5, 1e5);

// ---------------------------------------------------------------------------------------------
// Caps on counts. The cap on grid points per run (variants × rows × columns) is
// `crate::study::MAX_SWEEP_POINTS`, beside the sweep whose memory it bounds.

/// Most design variants (the product of the `[design]` axes' counts) one study may list.
pub const MAX_DESIGN_VARIANTS: usize = 1_000_000;

/// Most values on one axis (grid or design).
pub const MAX_AXIS_VALUES: usize = 100_000;

/// Most points on one summary probe line (half-width / step + 1).
pub const MAX_PROBE_POINTS: usize = 10_001;

/// Most impacts of one quadrature distribution (nodes^dimensions).
pub const MAX_QUADRATURE_POINTS: usize = 200_000;

/// Most impact evaluations of one study run (variants × (grid + summary + distribution)): about
/// an hour at the measured sweep rate of a few million impacts per second.
pub const MAX_STUDY_IMPACTS: usize = 10_000_000_000;

/// Most shots one synthetic experiment makes (groups × golfers × swings): each shot is held in
/// memory with its CSV row (under 1 kB), so the cap is a few GB.
pub const MAX_SYNTH_SHOTS: usize = 2_000_000;

/// Most face bins of a comparison (rows × columns).
pub const MAX_FACE_BINS: usize = 1_000_000;

/// A library option outside what it allows (from a validating constructor or `validate`).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("option {option} = {value}: allowed {allowed}")]
pub struct OptionError {
    /// The option (field) name.
    pub option: &'static str,
    /// The value given.
    pub value: String,
    /// What is allowed.
    pub allowed: &'static str,
}

impl OptionError {
    /// `Ok(())` when `ok`, else the error for `option = value`.
    pub fn check(
        ok: bool,
        option: &'static str,
        value: impl std::fmt::Display,
        allowed: &'static str,
    ) -> Result<(), OptionError> {
        if ok {
            Ok(())
        } else {
            Err(OptionError {
                option,
                value: value.to_string(),
                allowed,
            })
        }
    }
}

/// Why a count is refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{what}: {factors} = {product}, above the limit of {limit}{reason}")]
pub struct CapError {
    /// What is counted.
    pub what: String,
    /// The factors with their names, `a (name) × b (name)`.
    pub factors: String,
    /// The product, or "over 2^64" when it overflows.
    pub product: String,
    /// The cap.
    pub limit: usize,
    /// Why the cap exists and what to do (starts with `; ` when given).
    pub reason: String,
}

/// The product of named counts, checked: overflow and values above `limit` are errors that
/// state every factor, the product and the limit. `what` names the product (`design variants`);
/// `advice` says what to do (may be empty).
pub fn count_product(
    what: &str,
    factors: &[(&str, usize)],
    limit: usize,
    advice: &str,
) -> Result<usize, CapError> {
    let product = factors
        .iter()
        .try_fold(1usize, |acc, (_, n)| acc.checked_mul(*n));
    match product {
        Some(p) if p <= limit => Ok(p),
        _ => Err(CapError {
            what: what.to_owned(),
            factors: factors
                .iter()
                .map(|(name, n)| format!("{n} ({name})"))
                .collect::<Vec<_>>()
                .join(" × "),
            product: product.map_or_else(|| "over 2^64".to_owned(), |p| p.to_string()),
            limit,
            reason: if advice.is_empty() {
                String::new()
            } else {
                format!("; {advice}")
            },
        }),
    }
}

/// The sum of counts, checked against `limit` like [`count_product`].
pub fn count_sum(
    what: &str,
    terms: &[(&str, usize)],
    limit: usize,
    advice: &str,
) -> Result<usize, CapError> {
    let sum = terms
        .iter()
        .try_fold(0usize, |acc, (_, n)| acc.checked_add(*n));
    match sum {
        Some(s) if s <= limit => Ok(s),
        _ => Err(CapError {
            what: what.to_owned(),
            factors: terms
                .iter()
                .map(|(name, n)| format!("{n} ({name})"))
                .collect::<Vec<_>>()
                .join(" + "),
            product: sum.map_or_else(|| "over 2^64".to_owned(), |s| s.to_string()),
            limit,
            reason: if advice.is_empty() {
                String::new()
            } else {
                format!("; {advice}")
            },
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overflowing_products_are_refused_not_wrapped() {
        let f = [("a", 65536), ("b", 65536), ("c", 65536), ("d", 65536)];
        let e = count_product("design variants", &f, MAX_DESIGN_VARIANTS, "").unwrap_err();
        let m = e.to_string();
        assert!(m.contains("over 2^64"), "{m}");
        assert!(m.contains("1000000"), "{m}");
        assert_eq!(count_product("x", &[("a", 3), ("b", 4)], 12, ""), Ok(12));
        assert!(count_product("x", &[("a", 3), ("b", 5)], 12, "").is_err());
        assert_eq!(count_product("x", &[], 1, ""), Ok(1));
    }

    #[test]
    fn ranges_reject_non_finite_and_name_the_value() {
        assert!(CLUB_SPEED_MPH.check(f64::NAN).is_err());
        assert!(CLUB_SPEED_MPH.check(f64::INFINITY).is_err());
        assert!(CLUB_SPEED_MPH.check(0.0).is_err());
        assert!(CLUB_SPEED_MPH.check(1e-300).is_err());
        assert_eq!(CLUB_SPEED_MPH.check(100.0), Ok(100.0));
        let m = CLUB_SPEED_MPH.check(1e155).unwrap_err().to_string();
        assert!(m.contains("1e155") && m.contains("[1, 250] mph"), "{m}");
        assert!(DELIVERY_ANGLE_DEG.check(-90.0).is_ok());
    }
}
