//! A compliant-contact world: the clubhead–ball impact integrated in time, so the engine can be
//! tested against physics richer than its own impulse–momentum model.
//!
//! Size: one simulator — its parameters, validation, state layout, force law and integrator
//! share private constants and types; about half the file is the derivation and literature the
//! tests and configs refer to.
//!
//! ## Bodies
//!
//! * **Clubhead**: a free rigid body with the club's mass, centre of mass and full inertia tensor
//!   (F axes, rotated with the head as it turns), and the torus face of
//!   [`crate::physics::face`]. The contact point is found at every instant as the point of the
//!   torus nearest the ball centre, so it travels over the face as the bodies move and rotate.
//!   No grip or gravity acts during the ~0.5 ms contact (as in the momentum model).
//! * **Ball**: a rigid sphere (mass, radius, isotropic inertia) whose contact with the face is
//!   compliant. With overlap `δ`, the contact plane is the face surface, so the lever arm of the
//!   contact force about the ball centre is `R − δ`, not `R`: the flattened ball turns less per
//!   unit tangential impulse, as the library's `ball_offset` effect tries to mimic.
//! * **Shaft tip** (optional): a point mass joined to the hosel by an isotropic spring–damper of
//!   zero rest length, moving with the hosel before impact. A stiff joint makes it act as mass
//!   added at the hosel; a soft one lets the head leave it behind during the contact. It acts
//!   only through a contact of finite duration: with a rigid contact (`hertz_k_n_per_m1_5` ≈
//!   1e15, contact ≈ microseconds) no joint of finite stiffness passes any impulse to it.
//!
//! ## How heavy a shaft tip, on how stiff a joint
//!
//! The shaft's tip is glued into the hosel bore over a few centimetres: that part, with its
//! epoxy and the ferrule, moves with the head (≈ 2 g: ≈ 38 mm of a tip section of ≈ 50 g/m).
//! Above it the shaft is a beam, and the contact lasts only `T` ≈ 0.46 ms, during which a
//! bending disturbance travels a few centimetres (bending waves are dispersive:
//! `c_B = sqrt(ω)·(EI/ρA)^¼`). A semi-infinite Euler–Bernoulli beam whose end is driven with its
//! slope held (the bond clamps it to the head, which turns little) answers a velocity `v(t)` of
//! its end with the force `F = Γ·D^½ v`, `Γ = √2·(ρA)^¾·EI^¼` (its driving-point impedance
//! `ρA·c_B·(1 + i)`); over a contact whose impulse rises as a half sine, the impulse it takes
//! equals that of a rigid mass `0.78·Γ·sqrt(T)` moving with the hosel. With a graphite driver
//! tip, `EI` ≈ 20 N·m² (an 8.5 mm tube of 1.2 mm wall, laminate modulus ≈ 100 GPa; a steel tip
//! is similar) and `ρA` ≈ 0.05 kg/m (the paper's 60–75 g shafts over 1.105 m), `Γ` ≈ 0.32
//! kg/s^½ and the beam adds ≈ 5.3 g (2.6 g if the end were free to turn). With the bonded part:
//! **≈ 6 g at the hosel** (range 4.5–7 g), the default. The lumped tip stands for that impulse,
//! so its joint must let it follow the hosel within the contact: 10 kHz (half period 0.05 ms, a
//! ninth of the contact; the tests show 5–100 kHz give the same launch). The paper's fitted
//! added masses (0.9–2.5 g at the CoM; Shaft C's lead tape 350–640 mm up the shaft, beyond any
//! wave's reach in 0.46 ms, changed it by no more than its fitting noise) are smaller than this
//! estimate; `docs/compliant-worlds.md` gives the figures and what diagnose makes of the tip.
//!
//! ## Contact laws
//!
//! ```text
//! normal      F_n = k·δ^1.5·(1 + χ·δ̇)        (Hertz stiffness, Hunt–Crossley damping; F_n ≥ 0)
//! tangential  F_t = k_t·ξ + c_t·u_t           (ξ = ∫ u_t dt, kept in the tangent plane)
//!             k_t = κ·dF_n/dδ = κ·1.5·k·δ^0.5 (Mindlin: the tangential stiffness follows the
//!                                              contact radius; κ = 2(1−ν)/(2−ν))
//!             c_t = 2·ζ_t·sqrt(m_t·k_t)
//!             |F_t| ≤ μ·F_n                   (Coulomb: beyond it the contact slides and ξ is cut
//!                                              back to the limit)
//! ```
//!
//! `u` is the velocity of the club's contact point minus the ball's, `δ̇ = u·n` and `u_t` its
//! tangential part.
//!
//! **Why the COR falls with speed.** For one degree of freedom, `m·ẍ = −k·x^1.5·(1 + χ·ẋ)`
//! scaled by the impact speed `v` and the Hertz length shows that the COR depends on the single
//! group `χ·v` — not on `m` or `k` (Hunt & Crossley 1975). For small `χ·v` the energy lost over
//! the elastic path gives `1 − e ≈ (2/3)·χ·v` (checked in the tests). We choose `χ` so that the
//! COR at the reference normal speed 48.77 m/s is `cor_ref` (default: the club's `cor`), by
//! bisection on the dimensionless one-body problem ([`hunt_crossley_cor`]); the COR at any other
//! speed then follows from the same law. The damping force is clamped so the contact never pulls.
//!
//! **Tangential compliance.** A ball gripping the face stores energy in tangential shear; when
//! the tangential spring's period is comparable to the contact time it gives it back, the
//! contact point's tangential velocity reverses before release, and the spin overshoots the
//! "rolling" value that the momentum model's no-slip condition (`e_t = 0`) yields (Maw, Barber
//! & Fawcett 1976, 1981; Cross 2002, 2005 measured the resulting tangential restitution for
//! balls of several sports). If the spring force would exceed `μ·F_n`, the contact slides.
//! The stiffness ratio κ = 2(1−ν)/(2−ν) of tangential to normal contact stiffness is Mindlin's
//! result for equal elastic bodies (Johnson, *Contact Mechanics*, 1985, §7.2); ν = 0.45 for a
//! golf ball's rubber gives κ ≈ 0.71.
//!
//! ## Parameters and defaults
//!
//! | key | default | meaning |
//! |---|---|---|
//! | `hertz_k_n_per_m1_5` | 2.4e7 N/m^1.5 | normal stiffness `k`. With the paper's driver and ball it gives a contact time of ≈ 0.45 ms at 45–50 m/s normal speed (measured by the tests; ≈ 0.45 ms is what high-speed films of driver impacts show) and a maximum overlap ≈ 7 mm |
//! | `cor_ref` | club `cor` | COR at 48.77 m/s normal speed, sets `χ` |
//! | `mu` | 0.35 | Coulomb friction, ball cover on a titanium face (0.3–0.4 in published oblique-impact measurements) |
//! | `tangential_stiffness_ratio` | 0.71 | κ, Mindlin with ν = 0.45 |
//! | `tangential_damping_ratio` | 0.1 | ζ_t of the tangential spring (a small loss in the shear) |
//! | `steps_per_contact` | 1000 | RK4 steps per estimated contact time |
//! | `shaft_tip.mass_g` | 6.0 g | tip mass: the bonded tip and the beam's share over the contact (above) |
//! | `shaft_tip.frequency_hz` | 10 000 Hz | `sqrt(k_s/m_s)/2π`: stiff enough that the tip follows the hosel within the contact |
//! | `shaft_tip.damping_ratio` | 0.2 | of the joint |
//! | `shaft_tip.hosel_mm` | the club's `hosel_mm` | hosel point in the face frame F (behind the face, up, toward the heel); the club file's default is [`crate::physics::impact::DRIVER_HOSEL_MM`] = [−20, 25, −55] mm, the point where the library's `hosel_mass` puts its mass |
//!
//! The shaft-tip values are the estimate above (from the shaft's bending stiffness and mass per
//! length), not measurements.
//!
//! ## Integration
//!
//! Classic fixed-step RK4 on a 31-number state (head position, orientation quaternion, velocity
//! and angular velocity; ball position, velocity and spin; tangential spring ξ; shaft-tip
//! position and velocity), in the face frame at first contact (an inertial frame). The step is
//! the Hertz contact time of the one-body problem with the normal effective mass `1/(n·K·n)`,
//! `3.2146·(m/k)^0.4·u1n^−0.2`, divided by `steps_per_contact`. After each step the Coulomb limit
//! is enforced on ξ; the impact ends at the first step after which the overlap is negative.
//! With the defaults one impact takes ~5000 evaluations of the forces (about a millisecond).
//!
//! ## The rigid limit and which COR the momentum model must be given
//!
//! With a very stiff contact, a gripping tangential law (very stiff, critically damped spring,
//! large μ) and no shaft tip, the bodies barely move during the contact, and the result should
//! match [`ImpactModel::solve`] with `e_t = 0` and a suitable `e`. Which `e`? The contact's
//! restitution acts on the *normal motion it sees*, and off the centre that is not `u1n`. The
//! stiff tangential spring stops the tangential slip at first touch, before any appreciable
//! normal impulse; the tangential impulse that does so, `K_tt⁻¹·u1t`, also changes the normal
//! velocity through the coupling terms of the collision matrix `K`. From then on the contact
//! grips (`u_t = 0`) and the normal motion is a one-body Hunt–Crossley impact of effective mass
//! `1/(K⁻¹)_nn`, starting from
//!
//! ```text
//! v* = u1n − K_nt·K_tt⁻¹·u1t = (K⁻¹·u1)·n / (n·K⁻¹·n)
//! ```
//!
//! and leaving at `u2n = −e_HC(χ·v*)·v*` (Poisson's and the energetic restitution hypotheses
//! agree here: one normal motion, one effective mass). Newton's kinematic law of the momentum
//! model, `u2n = −e·u1n`, reproduces it with `e = e_HC(χ·v*)·v*/u1n`
//! ([`ContactWorld::rigid_limit_cor`]). At the centre `K` barely couples (`v*` ≈ `u1n`); off the
//! centre `v*` differs from `u1n` by up to ≈ 0.6 % and so does the COR. The tests
//! (`tests/contact_world.rs`, `k = 1e15`, κ = 50 critically damped, μ = 100, 2000 steps per
//! contact, 40 random deliveries) measure, against the momentum model given this COR, ball
//! speed and spin within 0.2 % on- and off-centre; given instead the one-body COR at `u1n`,
//! 0.25 % off the centre. So "the same COR" means the same restitution of the normal motion
//! after the grip: a fixed Newton COR on `u1n` is not what a compliant contact has when the
//! grip couples into the normal direction (`docs/compliant-worlds.md`).
//!
//! ## Literature
//!
//! * K. H. Hunt, F. R. E. Crossley, "Coefficient of restitution interpreted as damping in
//!   vibroimpact", J. Appl. Mech. 42 (1975) 440–445.
//! * N. Maw, J. R. Barber, J. N. Fawcett, "The oblique impact of elastic spheres", Wear 38
//!   (1976) 101–114; "The role of elastic tangential compliance in oblique impact", J. Lubr.
//!   Technol. 103 (1981) 74–80.
//! * K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985 (Hertz: ch. 4;
//!   Mindlin tangential compliance: ch. 7).
//! * R. Cross, "Grip-slip behavior of a bouncing ball", Am. J. Phys. 70 (2002) 1093–1102;
//!   "Bounce of a spinning ball near normal incidence", Am. J. Phys. 73 (2005) 914–920.
//! * W. McNally, "Development of a golf ball–clubface impact model using volumetric contact",
//!   MASc thesis, University of Waterloo, 2018 (a volumetric alternative to the point Hertz
//!   law used here, with the same ingredients: compliance, damping, friction, face curvature).

use nalgebra::{Matrix3, Quaternion, SVector, UnitQuaternion, Vector3};

use crate::physics::impact::COR_SPEED_REFERENCE_M_S;
use crate::physics::{Delivery, ImpactModel, Launch};

/// Default Hertz stiffness, N/m^1.5 (contact time ≈ 0.45 ms at driver speeds, see module docs).
pub const DEFAULT_HERTZ_K_N_PER_M1_5: f64 = 2.4e7;
/// Default Coulomb friction coefficient (0.3–0.4 measured for balls on clubfaces).
pub const DEFAULT_MU: f64 = 0.35;
/// Default tangential-to-normal stiffness ratio: Mindlin's 2(1−ν)/(2−ν) with ν = 0.45.
pub const DEFAULT_TANGENTIAL_STIFFNESS_RATIO: f64 = 2.0 * (1.0 - 0.45) / (2.0 - 0.45);
/// Default damping ratio of the tangential spring.
pub const DEFAULT_TANGENTIAL_DAMPING_RATIO: f64 = 0.1;
/// Default RK4 steps per estimated contact time.
pub const DEFAULT_STEPS_PER_CONTACT: u32 = 1000;
/// Default shaft-tip mass, g: the bonded tip (≈ 2 g) and the share of the shaft a bending
/// wave reaches during the contact (≈ 5.3 g for `EI` ≈ 20 N·m², `ρA` ≈ 0.05 kg/m, 0.46 ms),
/// rounded within the 4.5–7 g range of that estimate (module docs).
pub const DEFAULT_TIP_MASS_G: f64 = 6.0;
/// Default shaft-tip joint natural frequency, Hz: stiff against the ≈ 0.46 ms contact (module
/// docs), so the lumped tip moves with the hosel.
pub const DEFAULT_TIP_FREQUENCY_HZ: f64 = 10_000.0;
/// Default shaft-tip joint damping ratio.
pub const DEFAULT_TIP_DAMPING_RATIO: f64 = 0.2;

/// Hertz contact-time constant: `T = 3.2146·(m/k)^0.4·v^−0.2` for `F = k·δ^1.5`
/// (Johnson 1985, §11.1: `T = 2.94·δ_max/v` with `δ_max = (5mv²/4k)^0.4`).
const HERTZ_TIME_CONSTANT: f64 = 3.2146;

/// A shaft tip joined to the hosel by a spring–damper.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShaftTip {
    /// Tip mass, g (> 0).
    pub mass_g: f64,
    /// Natural frequency of the tip on its joint, `sqrt(k_s/m_s)/2π`, Hz (> 0).
    pub frequency_hz: f64,
    /// Damping ratio of the joint (≥ 0).
    pub damping_ratio: f64,
    /// Hosel point in the face frame F, mm; `None`: the club's `hosel_mm` (the point where the
    /// library's `hosel_mass` effect puts its mass).
    pub hosel_mm: Option<[f64; 3]>,
}

impl Default for ShaftTip {
    fn default() -> Self {
        Self {
            mass_g: DEFAULT_TIP_MASS_G,
            frequency_hz: DEFAULT_TIP_FREQUENCY_HZ,
            damping_ratio: DEFAULT_TIP_DAMPING_RATIO,
            hosel_mm: None,
        }
    }
}

/// Parameters of the compliant contact (file units where named).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactParams {
    /// Hertz stiffness `k`, N/m^1.5 (> 0).
    pub hertz_k_n_per_m1_5: f64,
    /// COR at the reference normal speed 48.77 m/s; `None` takes the club's `cor`.
    pub cor_ref: Option<f64>,
    /// Coulomb friction coefficient (> 0).
    pub mu: f64,
    /// Tangential-to-normal contact stiffness ratio κ (> 0).
    pub tangential_stiffness_ratio: f64,
    /// Damping ratio of the tangential spring (≥ 0).
    pub tangential_damping_ratio: f64,
    /// RK4 steps per estimated contact time (≥ 20).
    pub steps_per_contact: u32,
    /// Optional shaft tip at the hosel.
    pub shaft_tip: Option<ShaftTip>,
}

impl Default for ContactParams {
    fn default() -> Self {
        Self {
            hertz_k_n_per_m1_5: DEFAULT_HERTZ_K_N_PER_M1_5,
            cor_ref: None,
            mu: DEFAULT_MU,
            tangential_stiffness_ratio: DEFAULT_TANGENTIAL_STIFFNESS_RATIO,
            tangential_damping_ratio: DEFAULT_TANGENTIAL_DAMPING_RATIO,
            steps_per_contact: DEFAULT_STEPS_PER_CONTACT,
            shaft_tip: None,
        }
    }
}

/// What one integrated impact produced. Vectors in the ground frame G, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactOutcome {
    /// Ball CoM velocity after separation, m/s.
    pub ball_velocity_m_s: Vector3<f64>,
    /// Ball spin after separation, rad/s.
    pub ball_spin_rad_s: Vector3<f64>,
    /// Normal approach speed `u1n` at first contact, m/s.
    pub normal_approach_speed_m_s: f64,
    /// Normal COR achieved: `−u_n(end)/u1n` at the contact point.
    pub cor_measured: f64,
    /// Tangential relative velocity of the contact points at first contact, F0 frame, m/s.
    pub tangential_before_m_s: Vector3<f64>,
    /// Tangential relative velocity at separation, F0 frame, m/s.
    pub tangential_after_m_s: Vector3<f64>,
    /// Contact duration, s.
    pub contact_time_s: f64,
    /// Largest overlap (ball compression), m.
    pub max_compression_m: f64,
    /// Integration steps taken.
    pub steps: usize,
    /// Whether the Coulomb limit was reached at any step.
    pub slipped: bool,
    /// Normal impulse on the ball, N·s.
    pub normal_impulse_n_s: f64,
}

impl ContactOutcome {
    /// Launch conditions of the ball.
    pub fn launch(&self) -> Launch {
        Launch::from_ball_state(&self.ball_velocity_m_s, &self.ball_spin_rad_s)
    }
}

/// COR of the one-body Hunt–Crossley impact `ẍ = −x^1.5·(1 + c·ẋ)`, `x(0) = 0`, `ẋ(0) = 1`
/// (dimensionless; `c = χ·v`). It depends on `c` alone, whatever the mass and stiffness.
pub fn hunt_crossley_cor(c: f64) -> f64 {
    // Dimensionless contact time ≈ 3.2 (Hertz); 4000 RK4 steps give ~1e-10 accuracy.
    let dt = 1e-3;
    let acc = |x: f64, v: f64| -> f64 {
        if x <= 0.0 {
            0.0
        } else {
            -(x * x.sqrt() * (1.0 + c * v)).max(0.0)
        }
    };
    let (mut x, mut v) = (0.0_f64, 1.0_f64);
    for _ in 0..1_000_000 {
        let (k1x, k1v) = (v, acc(x, v));
        let (k2x, k2v) = (
            v + 0.5 * dt * k1v,
            acc(x + 0.5 * dt * k1x, v + 0.5 * dt * k1v),
        );
        let (k3x, k3v) = (
            v + 0.5 * dt * k2v,
            acc(x + 0.5 * dt * k2x, v + 0.5 * dt * k2v),
        );
        let (k4x, k4v) = (v + dt * k3v, acc(x + dt * k3x, v + dt * k3v));
        x += dt / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        v += dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if x < 0.0 {
            return -v;
        }
    }
    0.0
}

/// Why a contact world cannot be built or cannot integrate an impact.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ContactError {
    /// A target COR outside (0, 1].
    #[error("the target COR must be in (0, 1], got {cor}")]
    TargetCor {
        /// The COR asked for.
        cor: f64,
    },
    /// A COR no damping reaches.
    #[error("no Hunt–Crossley damping gives a COR as low as {cor}")]
    CorTooLow {
        /// The COR asked for.
        cor: f64,
    },
    /// Hidden effects whose physics the contact world makes itself.
    #[error(
        "the contact world makes its own restitution, friction and ball deformation: hidden \
         effects tangential_restitution, friction, cor_speed, cor_power, cor_radial and \
         ball_offset cannot be combined with it"
    )]
    RestitutionEffects,
    /// User-defined effects, which the contact world does not evaluate.
    #[error(
        "the contact world integrates its own physics and does not evaluate user-defined \
         effects: hide them in a momentum-model world (no [world] contact)"
    )]
    UserEffects,
    /// A contact setting outside what it allows (the message says which and what).
    #[error("{0}")]
    Setting(&'static str),
    /// The impact point is not on the face.
    #[error(transparent)]
    Face(#[from] crate::physics::FaceError),
    /// The momentum model's refusal of the delivery.
    #[error(transparent)]
    Impact(#[from] crate::physics::ImpactError),
    /// The collision matrix has no inverse.
    #[error("the collision matrix is singular")]
    SingularCollision,
    /// The club does not approach the ball, before or after the grip.
    #[error(
        "the club does not approach the ball: normal approach {} m/s, after the grip {} m/s \
         (both must exceed {} m/s)",
        crate::limits::fmt_value(*u1n_m_s),
        crate::limits::fmt_value(*after_grip_m_s),
        crate::limits::fmt_value(crate::limits::MIN_NORMAL_APPROACH_M_S)
    )]
    NoGripApproach {
        /// Normal approach speed, m/s.
        u1n_m_s: f64,
        /// Normal approach left once the grip stopped the slip, m/s.
        after_grip_m_s: f64,
    },
    /// The integration gave a non-finite state.
    #[error("the contact integration produced a non-finite result")]
    NonFinite,
    /// The ball stayed on the face.
    #[error("the ball did not separate within {max_steps} steps (50 estimated contact times)")]
    NoSeparation {
        /// Steps integrated.
        max_steps: usize,
    },
}

/// The Hunt–Crossley `χ` (s/m) whose COR at normal speed `v_ref_m_s` is `cor` (in (0, 1]).
pub fn hunt_crossley_chi(cor: f64, v_ref_m_s: f64) -> Result<f64, ContactError> {
    if !(cor > 0.0 && cor <= 1.0) {
        return Err(ContactError::TargetCor { cor });
    }
    if cor >= 1.0 {
        return Ok(0.0);
    }
    // hunt_crossley_cor falls monotonically from 1 at c = 0; bracket, then bisect.
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    while hunt_crossley_cor(hi) > cor {
        hi *= 2.0;
        if hi > 1e6 {
            return Err(ContactError::CorTooLow { cor });
        }
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if hunt_crossley_cor(mid) > cor {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-12 * hi {
            break;
        }
    }
    Ok(0.5 * (lo + hi) / v_ref_m_s)
}

// State layout (F0 frame: the face frame at first contact, origin at the face centre).
const XC: usize = 0; // club CoM position
const Q: usize = 3; // club orientation quaternion (w, i, j, k)
const VC: usize = 7; // club CoM velocity
const WC: usize = 10; // club angular velocity
const XB: usize = 13; // ball centre
const VB: usize = 16; // ball velocity
const WB: usize = 19; // ball spin
const XI: usize = 22; // tangential spring displacement
const XT: usize = 25; // shaft-tip position
const VT: usize = 28; // shaft-tip velocity
const N: usize = 31;

type State = SVector<f64, N>;

fn v3(s: &State, i: usize) -> Vector3<f64> {
    Vector3::new(s[i], s[i + 1], s[i + 2])
}

fn set3(s: &mut State, i: usize, v: &Vector3<f64>) {
    s[i] = v.x;
    s[i + 1] = v.y;
    s[i + 2] = v.z;
}

/// The compliant-contact world for one club and ball (one group's model), with `χ` and the
/// per-club constants precomputed.
#[derive(Debug, Clone)]
pub struct ContactWorld {
    model: ImpactModel,
    params: ContactParams,
    chi_s_per_m: f64,
    tip: Option<TipConsts>,
}

#[derive(Debug, Clone, Copy)]
struct TipConsts {
    mass_kg: f64,
    k_n_per_m: f64,
    c_n_s_per_m: f64,
    /// Hosel relative to the club CoM, body (F) axes, m.
    hosel_from_com_m: Vector3<f64>,
}

/// Per-impact constants used by the force evaluation.
struct Consts {
    m_c: f64,
    inertia_body: Matrix3<f64>,
    inv_inertia_body: Matrix3<f64>,
    com: Vector3<f64>,
    bulge: f64,
    roll: f64,
    major: f64,
    m_b: f64,
    r_b: f64,
    i_b: f64,
    k: f64,
    chi: f64,
    kappa: f64,
    zeta_t: f64,
    m_t: f64,
    mu: f64,
}

/// What [`ContactWorld::impact`] starts from.
struct Start {
    c: Consts,
    s: State,
    dt: f64,
    /// Normal approach speed, m/s.
    u1n: f64,
    /// Face frame at first contact to ground.
    r_gf: Matrix3<f64>,
}

/// Keep the tangential spring in the tangent plane and within the Coulomb limit (after a
/// step); returns whether it had to be cut back (the contact slid).
fn limit_spring(c: &Consts, e: &Eval, s: &mut State) -> bool {
    let xi = v3(s, XI);
    let mut xi_t = xi - xi.dot(&e.normal) * e.normal;
    let mut slid = false;
    if e.overlap_m > 0.0 {
        let kt = c.kappa * 1.5 * c.k * e.overlap_m.sqrt();
        let limit = c.mu * e.normal_force_n;
        if kt * xi_t.norm() > limit {
            xi_t *= limit / (kt * xi_t.norm());
            slid = true;
        }
    }
    set3(s, XI, &xi_t);
    slid
}

/// Contact geometry and forces at one state.
struct Eval {
    deriv: State,
    overlap_m: f64,
    normal: Vector3<f64>,
    u: Vector3<f64>,
    normal_force_n: f64,
    slipping: bool,
}

impl ContactWorld {
    /// Build the world for `model` (a group's club with its hidden effects). The contact laws
    /// replace the model's restitution laws, so a model with a tangential restitution, friction,
    /// `cor_speed`, `cor_radial` or a ball offset is refused rather than silently ignored.
    pub fn new(model: &ImpactModel, params: ContactParams) -> Result<Self, ContactError> {
        let p = model.params();
        if p.tangential_restitution != 0.0
            || p.friction_mu.is_some()
            || p.cor_speed_k_s_per_m != 0.0
            || p.cor_power_q != 0.0
            || p.cor_radial_c_per_m2 != 0.0
            || p.cor_radial_moment_per_m != [0.0; 2]
            || p.cor_radial_offset != 0.0
            || p.ball_offset_y_m != 0.0
            || p.ball_offset_z_m != 0.0
        {
            return Err(ContactError::RestitutionEffects);
        }
        if !p.user.is_empty() {
            return Err(ContactError::UserEffects);
        }
        let pos = |v: f64| v.is_finite() && v > 0.0;
        if !pos(params.hertz_k_n_per_m1_5) {
            return Err(ContactError::Setting(
                "hertz_k_n_per_m1_5 must be finite and > 0",
            ));
        }
        if !pos(params.mu) || !pos(params.tangential_stiffness_ratio) {
            return Err(ContactError::Setting(
                "mu and tangential_stiffness_ratio must be finite and > 0",
            ));
        }
        if !(params.tangential_damping_ratio.is_finite() && params.tangential_damping_ratio >= 0.0)
        {
            return Err(ContactError::Setting(
                "tangential_damping_ratio must be finite and ≥ 0",
            ));
        }
        if params.steps_per_contact < 20 {
            return Err(ContactError::Setting(
                "steps_per_contact must be at least 20",
            ));
        }
        let cor = params.cor_ref.unwrap_or(p.cor);
        let chi_s_per_m = hunt_crossley_chi(cor, COR_SPEED_REFERENCE_M_S)?;
        let tip = params.shaft_tip.map(|t| {
            let m = t.mass_g * 1e-3;
            let w = 2.0 * std::f64::consts::PI * t.frequency_hz;
            TipConsts {
                mass_kg: m,
                k_n_per_m: m * w * w,
                c_n_s_per_m: 2.0 * t.damping_ratio * m * w,
                hosel_from_com_m: t.hosel_mm.map_or(p.hosel_m, |h| Vector3::from(h) * 1e-3)
                    - p.club_com_m,
            }
        });
        if let Some(t) = params.shaft_tip {
            let ok = pos(t.mass_g)
                && pos(t.frequency_hz)
                && t.damping_ratio.is_finite()
                && t.damping_ratio >= 0.0
                && t.hosel_mm.iter().flatten().all(|v| v.is_finite());
            if !ok {
                return Err(ContactError::Setting(
                    "shaft_tip: mass_g and frequency_hz must be > 0, damping_ratio ≥ 0, hosel_mm \
                     finite",
                ));
            }
        }
        Ok(Self {
            model: model.clone(),
            params,
            chi_s_per_m,
            tip,
        })
    }

    /// Hunt–Crossley `χ`, s/m.
    pub fn chi_s_per_m(&self) -> f64 {
        self.chi_s_per_m
    }

    /// The COR this world's normal law gives at normal approach speed `u1n_m_s` for a
    /// one-degree-of-freedom impact (what a centre strike on a rigid head would show).
    pub fn cor_at(&self, u1n_m_s: f64) -> f64 {
        hunt_crossley_cor(self.chi_s_per_m * u1n_m_s)
    }

    /// The Newton COR (on `u1n`) with which the momentum model reproduces this world's impact of
    /// `d` in the rigid, gripping limit: `e_HC(χ·v*)·v*/u1n`, with `v*` the normal approach left
    /// once the grip has stopped the tangential slip (module docs, "The rigid limit").
    pub fn rigid_limit_cor(&self, d: &Delivery) -> Result<f64, ContactError> {
        let p = self.model.params();
        let r_fg = self.model.face_orientation(d).transpose();
        let cf = self.model.face().contact(d.impact_y_m, d.impact_z_m)?;
        let r_c = cf.point_m - p.club_com_m;
        let u1 = r_fg * d.club_velocity_m_s() + (r_fg * d.club_omega_rad_s).cross(&r_c);
        let n = cf.normal;
        let kinv = self
            .model
            .k_matrix(&r_c, &(-p.ball_radius_m * n))
            .try_inverse()
            .ok_or(ContactError::SingularCollision)?;
        let (u1n, v_star) = (u1.dot(&n), (kinv * u1).dot(&n) / n.dot(&(kinv * n)));
        let min = crate::limits::MIN_NORMAL_APPROACH_M_S;
        if !(u1n > min && v_star > min) {
            return Err(ContactError::NoGripApproach {
                u1n_m_s: u1n,
                after_grip_m_s: v_star,
            });
        }
        Ok(self.cor_at(v_star) * v_star / u1n)
    }

    /// Integrate one impact from the delivery `d` (loft and face biases of the model applied).
    pub fn impact(&self, d: &Delivery) -> Result<ContactOutcome, ContactError> {
        let Start {
            c,
            mut s,
            dt,
            u1n,
            r_gf,
        } = self.start(d)?;
        let first = self.eval(&c, &s);
        let u1t = first.u - first.u.dot(&first.normal) * first.normal;
        let max_steps = 50 * self.params.steps_per_contact as usize;
        let mut max_overlap: f64 = 0.0;
        let mut slipped = false;
        let mut normal_impulse = 0.0;
        for step in 1..=max_steps {
            normal_impulse += self.rk4_step(&c, &mut s, dt);
            let e = self.eval(&c, &s);
            slipped |= e.slipping;
            slipped |= limit_spring(&c, &e, &mut s);
            max_overlap = max_overlap.max(e.overlap_m);
            if e.overlap_m < 0.0 {
                let un = e.u.dot(&e.normal);
                let out = ContactOutcome {
                    ball_velocity_m_s: r_gf * v3(&s, VB),
                    ball_spin_rad_s: r_gf * v3(&s, WB),
                    normal_approach_speed_m_s: u1n,
                    cor_measured: -un / u1n,
                    tangential_before_m_s: u1t,
                    tangential_after_m_s: e.u - un * e.normal,
                    contact_time_s: step as f64 * dt,
                    max_compression_m: max_overlap,
                    steps: step,
                    slipped,
                    normal_impulse_n_s: normal_impulse,
                };
                let finite = |v: &Vector3<f64>| v.iter().all(|x| x.is_finite());
                if !(finite(&out.ball_velocity_m_s) && finite(&out.ball_spin_rad_s)) {
                    return Err(ContactError::NonFinite);
                }
                return Ok(out);
            }
        }
        Err(ContactError::NoSeparation { max_steps })
    }

    /// One classic RK4 step of `dt`, then the quaternion renormalised; returns the normal
    /// impulse over the step (N·s).
    fn rk4_step(&self, c: &Consts, s: &mut State, dt: f64) -> f64 {
        let k1 = self.eval(c, s);
        let k2 = self.eval(c, &(*s + 0.5 * dt * k1.deriv));
        let k3 = self.eval(c, &(*s + 0.5 * dt * k2.deriv));
        let k4 = self.eval(c, &(*s + dt * k3.deriv));
        *s += dt / 6.0 * (k1.deriv + 2.0 * (k2.deriv + k3.deriv) + k4.deriv);
        let qn =
            (s[Q] * s[Q] + s[Q + 1] * s[Q + 1] + s[Q + 2] * s[Q + 2] + s[Q + 3] * s[Q + 3]).sqrt();
        for i in Q..Q + 4 {
            s[i] /= qn;
        }
        dt / 6.0
            * (k1.normal_force_n
                + 2.0 * k2.normal_force_n
                + 2.0 * k3.normal_force_n
                + k4.normal_force_n)
    }

    /// The initial state at first contact, the per-impact constants and the step.
    fn start(&self, d: &Delivery) -> Result<Start, ContactError> {
        let p = self.model.params();
        let r_gf = self.model.face_orientation(d);
        let r_fg = r_gf.transpose();
        let v_c = r_fg * d.club_velocity_m_s();
        let w_c = r_fg * d.club_omega_rad_s;
        let cf = self.model.face().contact(d.impact_y_m, d.impact_z_m)?;
        let n0 = cf.normal;
        let r_c = cf.point_m - p.club_com_m;
        let u1 = v_c + w_c.cross(&r_c);
        let u1n = u1.dot(&n0);
        // The momentum solve's threshold and words: the two worlds refuse the same deliveries.
        if !(u1n > crate::limits::MIN_NORMAL_APPROACH_M_S) {
            return Err(ContactError::Impact(
                crate::physics::ImpactError::NotApproaching {
                    normal_speed_m_s: u1n,
                },
            ));
        }
        let r_b0 = -p.ball_radius_m * n0;
        let kmat = self.model.k_matrix(&r_c, &r_b0);
        let m_eff = 1.0 / n0.dot(&(kmat * n0));
        let kt_mean = 0.5
            * (cf.tangent_y.dot(&(kmat * cf.tangent_y)) + cf.tangent_z.dot(&(kmat * cf.tangent_z)));
        let k = self.params.hertz_k_n_per_m1_5;
        let t_est = HERTZ_TIME_CONSTANT * (m_eff / k).powf(0.4) * u1n.powf(-0.2);
        let dt = t_est / f64::from(self.params.steps_per_contact);

        let major = p.bulge_m - p.roll_m;
        let c = Consts {
            m_c: p.club_mass_kg,
            inertia_body: p.club_inertia_kgm2,
            inv_inertia_body: *self.model.club_inv_inertia(),
            com: p.club_com_m,
            bulge: p.bulge_m,
            roll: p.roll_m,
            major,
            m_b: p.ball_mass_kg,
            r_b: p.ball_radius_m,
            i_b: p.ball_inertia_kgm2,
            k,
            chi: self.chi_s_per_m,
            kappa: self.params.tangential_stiffness_ratio,
            zeta_t: self.params.tangential_damping_ratio,
            m_t: 1.0 / kt_mean,
            mu: self.params.mu,
        };

        let mut s = State::zeros();
        set3(&mut s, XC, &p.club_com_m);
        s[Q] = 1.0;
        set3(&mut s, VC, &v_c);
        set3(&mut s, WC, &w_c);
        set3(&mut s, XB, &(cf.point_m + p.ball_radius_m * n0));
        if let Some(t) = &self.tip {
            let h = p.club_com_m + t.hosel_from_com_m;
            set3(&mut s, XT, &h);
            set3(&mut s, VT, &(v_c + w_c.cross(&t.hosel_from_com_m)));
        }

        Ok(Start {
            c,
            s,
            dt,
            u1n,
            r_gf,
        })
    }

    /// Forces and state derivative.
    #[inline]
    fn eval(&self, c: &Consts, s: &State) -> Eval {
        let x_c = v3(s, XC);
        let v_c = v3(s, VC);
        let w_c = v3(s, WC);
        let x_b = v3(s, XB);
        let v_b = v3(s, VB);
        let w_b = v3(s, WB);
        let xi = v3(s, XI);
        let rot =
            UnitQuaternion::from_quaternion(Quaternion::new(s[Q], s[Q + 1], s[Q + 2], s[Q + 3]))
                .to_rotation_matrix()
                .into_inner();
        let rot_t = rot.transpose();

        // Ball centre in face coordinates (origin CoF), then the nearest torus point.
        let p_f = rot_t * (x_b - x_c) + c.com;
        let qx = p_f.x + c.bulge;
        let h = qx.hypot(p_f.z);
        let ring = Vector3::new(qx, 0.0, p_f.z) * (c.major / h);
        let dvec = Vector3::new(qx, p_f.y, p_f.z) - ring;
        let dlen = dvec.norm();
        let n_f = dvec / dlen;
        let surf_f = ring + c.roll * n_f - Vector3::new(c.bulge, 0.0, 0.0);
        let overlap = c.r_b - (dlen - c.roll);

        let n = rot * n_f;
        let r_cw = rot * (surf_f - c.com);
        let r_bw = -(c.r_b - overlap) * n;
        let u = v_c + w_c.cross(&r_cw) - (v_b + w_b.cross(&r_bw));
        let un = u.dot(&n);
        let u_t = u - un * n;

        let mut force = Vector3::zeros();
        let mut fn_mag = 0.0;
        let mut dxi = Vector3::zeros();
        let mut slipping = false;
        if overlap > 0.0 {
            let sq = overlap.sqrt();
            fn_mag = (c.k * overlap * sq * (1.0 + c.chi * un)).max(0.0);
            let kt = c.kappa * 1.5 * c.k * sq;
            let ct = 2.0 * c.zeta_t * (c.m_t * kt).sqrt();
            let xi_t = xi - xi.dot(&n) * n;
            let mut ft = kt * xi_t + ct * u_t;
            let ftn = ft.norm();
            let limit = c.mu * fn_mag;
            if ftn > limit {
                ft *= limit / ftn;
                slipping = true;
            } else {
                dxi = u_t;
            }
            force = fn_mag * n + ft;
        }

        // Shaft tip on the hosel.
        let mut tip_force_on_head = Vector3::zeros();
        let mut torque_tip = Vector3::zeros();
        let mut a_tip = Vector3::zeros();
        if let Some(t) = &self.tip {
            let r_hw = rot * t.hosel_from_com_m;
            let x_h = x_c + r_hw;
            let v_h = v_c + w_c.cross(&r_hw);
            let f = -t.k_n_per_m * (x_h - v3(s, XT)) - t.c_n_s_per_m * (v_h - v3(s, VT));
            tip_force_on_head = f;
            torque_tip = r_hw.cross(&f);
            a_tip = -f / t.mass_kg;
        }

        let f_head = -force + tip_force_on_head;
        let torque_head = r_cw.cross(&(-force)) + torque_tip;
        let i_w = rot * c.inertia_body * rot_t;
        let i_w_inv = rot * c.inv_inertia_body * rot_t;
        let dw_c = i_w_inv * (torque_head - w_c.cross(&(i_w * w_c)));

        let mut d = State::zeros();
        set3(&mut d, XC, &v_c);
        let (qw, qi, qj, qk) = (s[Q], s[Q + 1], s[Q + 2], s[Q + 3]);
        d[Q] = -0.5 * (w_c.x * qi + w_c.y * qj + w_c.z * qk);
        d[Q + 1] = 0.5 * (w_c.x * qw + w_c.y * qk - w_c.z * qj);
        d[Q + 2] = 0.5 * (w_c.y * qw + w_c.z * qi - w_c.x * qk);
        d[Q + 3] = 0.5 * (w_c.z * qw + w_c.x * qj - w_c.y * qi);
        set3(&mut d, VC, &(f_head / c.m_c));
        set3(&mut d, WC, &dw_c);
        set3(&mut d, XB, &v_b);
        set3(&mut d, VB, &(force / c.m_b));
        set3(&mut d, WB, &(r_bw.cross(&force) / c.i_b));
        set3(&mut d, XI, &dxi);
        if self.tip.is_some() {
            set3(&mut d, XT, &v3(s, VT));
            set3(&mut d, VT, &a_tip);
        }
        Eval {
            deriv: d,
            overlap_m: overlap,
            normal: n,
            u,
            normal_force_n: fn_mag,
            slipping,
        }
    }
}
