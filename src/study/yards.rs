//! Studies in yards: the impact model followed by ball flight, so that designs are judged by
//! carry and dispersion.
//!
//! - [`carry_map`]: carry and offline over a grid of impact locations on the face;
//! - [`yard_metrics`]: robust metrics over a distribution of swings and impact locations:
//!   mean carry, carry spread, mean and spread of offline, and the area of the dispersion
//!   ellipse of the landing points at a confidence level ([`super::landing`]);
//! - [`HeadConstraints`]: what a designer must respect, checked and reported (never clipped):
//!   total head mass, the Rules of Golf moment-of-inertia limit for woods, a box for the CoM;
//! - [`optimise_mass`]: move a discretionary mass to maximise expected carry or minimise the
//!   dispersion area, rejecting designs that break a constraint, and report every constraint's
//!   value and margin at the base and the best design.
//!
//! Pure: no I/O.

use argmin::core::{CostFunction, Executor, State};
use argmin::solver::neldermead::NelderMead;
use nalgebra::Vector3;

use super::design::{Design, DesignVar, DiscretionaryMass};
use super::distribution::{Distribution, SwingSpec};
use super::landing::Landing;
use crate::flight::{fly, FlightConfig, FlightLaunch};
use crate::physics::{ImpactModel, ModelParams};
use crate::sweep::kernel::{face_map, FaceMapKernel, LaunchGrid};
use crate::units::mm;

mod error;
pub use error::YardsError;

/// Rules of Golf limit on the moment of inertia of a wood's head about the vertical axis
/// through its CoM, g·cm² (Equipment Rules, Part 2, 4.1d(i) "Moment of inertia"; USGA/R&A
/// Procedure for Measuring the Moment of Inertia of Golf Clubheads).
pub const RULES_MOI_LIMIT_GCM2: f64 = 5900.0;
/// Test tolerance added to that limit in the measurement procedure, g·cm².
pub const RULES_MOI_TOLERANCE_GCM2: f64 = 100.0;

/// Carry and offline over a grid (row-major, rows are `ys_mm`), yd; `None` where the impact is
/// off the face or the club does not reach the ball.
#[derive(Debug, Clone, PartialEq)]
pub struct CarryMap {
    /// Heights up the face, mm.
    pub ys_mm: Vec<f64>,
    /// Heel–toe locations, mm.
    pub zs_mm: Vec<f64>,
    /// Carry, yd.
    pub carry_yd: Vec<Option<f64>>,
    /// Offline, yd (+ right).
    pub offline_yd: Vec<Option<f64>>,
}

fn launches_of(grid: &LaunchGrid) -> Vec<Option<FlightLaunch>> {
    (0..grid.len())
        .map(|k| {
            grid.valid[k].then(|| FlightLaunch {
                ball_speed_m_s: grid.ball_speed_m_s[k],
                launch_angle_rad: grid.launch_angle_rad[k],
                azimuth_rad: grid.azimuth_rad[k],
                backspin_rad_s: grid.backspin_rad_s[k],
                sidespin_rad_s: grid.sidespin_rad_s[k],
            })
        })
        .collect()
}

/// Carry and offline over the face for one swing.
pub fn carry_map(
    model: &ImpactModel,
    swing: &SwingSpec,
    ys_mm: &[f64],
    zs_mm: &[f64],
    flight: &FlightConfig,
) -> Result<CarryMap, YardsError> {
    let ys: Vec<f64> = ys_mm.iter().map(|&y| mm(y)).collect();
    let zs: Vec<f64> = zs_mm.iter().map(|&z| mm(z)).collect();
    let grid = face_map(model, &swing.delivery(0.0, 0.0), &ys, &zs);
    let launches = launches_of(&grid);
    let valid: Vec<FlightLaunch> = launches.iter().flatten().copied().collect();
    let mut flights = fly(flight, &valid).into_iter();
    let mut carry = Vec::with_capacity(launches.len());
    let mut off = Vec::with_capacity(launches.len());
    for l in &launches {
        match l {
            None => {
                carry.push(None);
                off.push(None);
            }
            Some(_) => {
                let f = flights
                    .next()
                    .expect("one flight per valid launch")
                    .map_err(YardsError::Flight)?;
                carry.push(Some(f.carry_yd()));
                off.push(Some(f.offline_yd()));
            }
        }
    }
    Ok(CarryMap {
        ys_mm: ys_mm.to_vec(),
        zs_mm: zs_mm.to_vec(),
        carry_yd: carry,
        offline_yd: off,
    })
}

/// Robust metrics of a design over a distribution of swings and impacts, yd.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct YardMetrics {
    /// Weighted mean carry, yd.
    pub mean_carry_yd: f64,
    /// Weighted standard deviation of carry, yd.
    pub std_carry_yd: f64,
    /// Weighted mean offline, yd.
    pub mean_offline_yd: f64,
    /// Weighted standard deviation of offline, yd.
    pub std_offline_yd: f64,
    /// Area of the dispersion ellipse of the landing points at [`Self::confidence`], yd².
    pub ellipse_area_yd2: f64,
    /// Confidence level of the ellipse, in (0, 1).
    pub confidence: f64,
    /// Weighted mean ball speed at launch, mph.
    pub mean_ball_speed_mph: f64,
    /// Weighted mean backspin at launch, rpm.
    pub mean_backspin_rpm: f64,
    /// Weighted mean sidespin at launch, rpm (+ curves right).
    pub mean_sidespin_rpm: f64,
    /// Impacts of the distribution (its points, every one on the face).
    pub impacts: usize,
    /// Impacts whose ball never left the ground (a launch below horizontal from the ground
    /// lands at once: `Flight::flight_time_s` 0); they are in the means with 0 yd of carry.
    pub grounded: usize,
    /// Their share of the distribution's weight, in [0, 1].
    pub grounded_share: f64,
}

/// Largest share of a distribution's weight whose balls may never leave the ground (launched
/// below horizontal from the ground: 0 yd carry) for its carry and dispersion to be reported.
/// Such a ball is a topped shot, and a few among many are part of a real pattern (counted, with
/// 0 yd, and named beside the figures); but when most of the weight never flies, mean carry is
/// mostly zeros, the ellipse shrinks toward the tee, and a change reads as "−100 %": figures
/// about balls that did not fly. Half is where the median shot is one of them.
pub const MAX_GROUNDED_SHARE: f64 = 0.5;

impl YardMetrics {
    /// `Some("3 of 25 impacts (4.2 % of the weight) …")` when some balls never left the ground.
    pub fn grounded_note(&self) -> Option<String> {
        (self.grounded > 0).then(|| {
            format!(
                "{} of {} impacts ({:.1} % of the weight) launch into the ground and never fly \
                 (counted as 0 yd carry)",
                self.grounded,
                self.impacts,
                100.0 * self.grounded_share
            )
        })
    }
}

/// Robust metrics over `dist` around `base` (see the module documentation). Every impact of
/// the distribution must be on the face and every ball must land; otherwise the error says
/// how many did not.
pub fn yard_metrics(
    model: &ImpactModel,
    base: &SwingSpec,
    dist: &Distribution,
    flight: &FlightConfig,
    confidence: f64,
) -> Result<YardMetrics, YardsError> {
    yard_landing(model, base, dist, flight, confidence).map(|(m, _)| m)
}

/// [`yard_metrics`] and the landing pattern they are computed from (its points, mean and
/// covariance: what a picture of the pattern and its ellipse needs).
pub fn yard_landing(
    model: &ImpactModel,
    base: &SwingSpec,
    dist: &Distribution,
    flight: &FlightConfig,
    confidence: f64,
) -> Result<(YardMetrics, Landing), YardsError> {
    if !(confidence > 0.0 && confidence < 1.0) {
        return Err(YardsError::Confidence(confidence));
    }
    let mut launches = Vec::new();
    let mut weights = Vec::new();
    let mut off_face = 0usize;
    for g in dist.groups(base) {
        let mut grid = LaunchGrid::with_len(g.ys_m.len());
        FaceMapKernel::new(model, &g.swing.delivery(0.0, 0.0)).eval_points(
            &g.ys_m,
            &g.zs_m,
            grid.all_out(),
        );
        for (l, &w) in launches_of(&grid).into_iter().zip(&g.weights) {
            match l {
                Some(l) => {
                    launches.push(l);
                    weights.push(w);
                }
                None => off_face += 1,
            }
        }
    }
    if off_face > 0 {
        return Err(YardsError::OffFace(off_face));
    }
    let flights = fly(flight, &launches);
    let launch_mean = |f: fn(&FlightLaunch) -> f64| -> f64 {
        let sw: f64 = weights.iter().sum();
        launches
            .iter()
            .zip(&weights)
            .map(|(l, w)| w * f(l))
            .sum::<f64>()
            / sw
    };
    let mean_ball_speed_mph = launch_mean(|l| l.ball_speed_m_s) / crate::units::M_S_PER_MPH;
    let mean_backspin_rpm = launch_mean(|l| l.backspin_rad_s) / crate::units::RAD_S_PER_RPM;
    let mean_sidespin_rpm = launch_mean(|l| l.sidespin_rad_s) / crate::units::RAD_S_PER_RPM;
    // Carry is the landing's signed coordinate along the target line (`Flight::carry_m`), so
    // the mean and spread of carry are those of the landing points' `x`.
    let (mut sw, mut grounded, mut grounded_w) = (0.0, 0usize, 0.0);
    let mut pts = Vec::with_capacity(flights.len());
    for (f, &w) in flights.iter().zip(&weights) {
        let f = f.as_ref().map_err(|e| YardsError::Flight(*e))?;
        if f.flight_time_s <= 0.0 {
            grounded += 1;
            grounded_w += w;
        }
        pts.push((f.carry_yd(), f.offline_yd(), w));
        sw += w;
    }
    let grounded_share = grounded_w / sw;
    if grounded == pts.len() || grounded_share > MAX_GROUNDED_SHARE {
        return Err(YardsError::Grounded {
            grounded,
            impacts: pts.len(),
            share: grounded_share,
            mean_launch_deg: launch_mean(|l| l.launch_angle_rad).to_degrees(),
        });
    }
    let landing = Landing::of(pts.iter().copied()).ok_or(YardsError::NotFinite)?;
    let metrics = YardMetrics {
        mean_carry_yd: landing.mean_carry_yd,
        std_carry_yd: landing.std_carry_yd(),
        mean_offline_yd: landing.mean_offline_yd,
        std_offline_yd: landing.std_offline_yd(),
        ellipse_area_yd2: landing.ellipse_area_yd2(confidence),
        confidence,
        mean_ball_speed_mph,
        mean_backspin_rpm,
        mean_sidespin_rpm,
        impacts: pts.len(),
        grounded,
        grounded_share,
    };
    Ok((metrics, landing))
}

/// Constraints on a clubhead design.
#[derive(Debug, Clone, PartialEq)]
pub struct HeadConstraints {
    /// Allowed total head mass, g (min, max).
    pub mass_g: Option<[f64; 2]>,
    /// Largest moment of inertia about the vertical axis through the CoM at address, g·cm²
    /// (woods: [`RULES_MOI_LIMIT_GCM2`] + [`RULES_MOI_TOLERANCE_GCM2`]).
    pub moi_vertical_max_gcm2: Option<f64>,
    /// Static loft, degrees: tilts the face frame at address, to find the vertical axis.
    pub loft_deg: f64,
    /// Box for the CoM in the face frame F, mm: `[[x_min, x_max], [y_min, y_max], [z_min, z_max]]`.
    pub com_box_mm: Option<[[f64; 2]; 3]>,
}

impl HeadConstraints {
    /// The Rules of Golf MOI limit for a wood (with the test tolerance) at this static loft.
    pub fn rules_wood(loft_deg: f64) -> Self {
        Self {
            mass_g: None,
            moi_vertical_max_gcm2: Some(RULES_MOI_LIMIT_GCM2 + RULES_MOI_TOLERANCE_GCM2),
            loft_deg,
            com_box_mm: None,
        }
    }
}

/// One constraint at one design: its value, limit and whether it holds.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstraintCheck {
    /// What is constrained (with unit).
    pub name: String,
    /// The design's value.
    pub value: f64,
    /// The limit (`≤` for maxima, `≥` for minima).
    pub limit: f64,
    /// `limit − value` for a maximum, `value − limit` for a minimum: ≥ 0 when it holds.
    pub margin: f64,
}

impl ConstraintCheck {
    fn max(name: String, value: f64, limit: f64) -> Self {
        Self {
            name,
            value,
            limit,
            margin: limit - value,
        }
    }
    fn min(name: String, value: f64, limit: f64) -> Self {
        Self {
            name,
            value,
            limit,
            margin: value - limit,
        }
    }
    /// Whether it holds.
    pub fn holds(&self) -> bool {
        self.margin >= 0.0
    }
}

/// Moment of inertia about the vertical axis through the CoM at address, g·cm². At address
/// with the face square and the sole flat, the vertical is `(sin loft, cos loft, 0)` in F
/// (from the CONVENTIONS orientation with `δ` = loft, `φ = λ = 0`).
pub fn vertical_moi_gcm2(p: &ModelParams, loft_deg: f64) -> f64 {
    let (s, c) = loft_deg.to_radians().sin_cos();
    let n = Vector3::new(s, c, 0.0);
    (n.transpose() * p.club_inertia_kgm2 * n)[(0, 0)] / crate::units::KGM2_PER_GCM2
}

/// Every constraint at the design `p`.
pub fn check_constraints(p: &ModelParams, c: &HeadConstraints) -> Vec<ConstraintCheck> {
    let mut out = Vec::new();
    if let Some([lo, hi]) = c.mass_g {
        let m = p.club_mass_kg / crate::units::KG_PER_G;
        out.push(ConstraintCheck::min("head mass g (min)".into(), m, lo));
        out.push(ConstraintCheck::max("head mass g (max)".into(), m, hi));
    }
    if let Some(lim) = c.moi_vertical_max_gcm2 {
        out.push(ConstraintCheck::max(
            "MOI about the vertical axis g·cm²".into(),
            vertical_moi_gcm2(p, c.loft_deg),
            lim,
        ));
    }
    if let Some(b) = c.com_box_mm {
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            let v = p.club_com_m[k] / crate::units::M_PER_MM;
            out.push(ConstraintCheck::min(
                format!("CoM {axis} mm (min)"),
                v,
                b[k][0],
            ));
            out.push(ConstraintCheck::max(
                format!("CoM {axis} mm (max)"),
                v,
                b[k][1],
            ));
        }
    }
    out
}

/// What [`optimise_mass`] optimises.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum YardGoal {
    /// Maximise the expected (mean) carry.
    MaxMeanCarry,
    /// Minimise the dispersion-ellipse area.
    MinDispersion,
}

/// Result of [`optimise_mass`].
#[derive(Debug, Clone, PartialEq)]
pub struct YardOptimum {
    /// Mass move at the optimum, mm (F frame).
    pub move_mm: [f64; 3],
    /// Metrics at the base design.
    pub base: YardMetrics,
    /// Metrics at the optimum.
    pub best: YardMetrics,
    /// Constraints at the base design.
    pub base_constraints: Vec<ConstraintCheck>,
    /// Constraints at the optimum.
    pub best_constraints: Vec<ConstraintCheck>,
    /// Designs the optimiser proposed that broke a constraint (rejected, not clipped).
    pub rejected: usize,
    /// Objective evaluations.
    pub evaluations: usize,
}

/// Everything one evaluation needs.
pub struct MassProblem<'a> {
    /// The club.
    pub nominal: &'a ModelParams,
    /// The movable mass.
    pub mass: &'a DiscretionaryMass,
    /// Bounds of the move along x, y, z of F, mm.
    pub bounds_mm: [[f64; 2]; 3],
    /// Swing and distribution.
    pub base: &'a SwingSpec,
    /// Distribution of swings and impacts.
    pub dist: &'a Distribution,
    /// Flight.
    pub flight: &'a FlightConfig,
    /// Ellipse confidence.
    pub confidence: f64,
    /// Constraints.
    pub constraints: &'a HeadConstraints,
    /// Goal.
    pub goal: YardGoal,
}

impl MassProblem<'_> {
    fn params(&self, mv: &[f64]) -> Result<ModelParams, YardsError> {
        let d = Design::default()
            .with(DesignVar::MassDx, mv[0])
            .with(DesignVar::MassDy, mv[1])
            .with(DesignVar::MassDz, mv[2]);
        Ok(d.apply(self.nominal, Some(self.mass))?)
    }

    /// Metrics and constraints of a mass move (mm).
    pub fn evaluate(&self, mv: &[f64]) -> Result<(YardMetrics, Vec<ConstraintCheck>), YardsError> {
        let p = self.params(mv)?;
        let model = ImpactModel::new(p.clone())?;
        let m = yard_metrics(&model, self.base, self.dist, self.flight, self.confidence)?;
        Ok((m, check_constraints(&p, self.constraints)))
    }

    fn score(&self, m: &YardMetrics) -> f64 {
        match self.goal {
            YardGoal::MaxMeanCarry => -m.mean_carry_yd,
            YardGoal::MinDispersion => m.ellipse_area_yd2,
        }
    }
}

struct Cost<'a, 'b> {
    p: &'b MassProblem<'a>,
    rejected: &'b std::cell::Cell<usize>,
    evals: &'b std::cell::Cell<usize>,
}

impl CostFunction for Cost<'_, '_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, u: &Vec<f64>) -> Result<f64, argmin::core::Error> {
        self.evals.set(self.evals.get() + 1);
        let b = &self.p.bounds_mm;
        if (0..3).any(|k| !(u[k] >= b[k][0] && u[k] <= b[k][1])) {
            self.rejected.set(self.rejected.get() + 1);
            return Ok(f64::INFINITY);
        }
        match self.p.evaluate(u) {
            Ok((m, cons)) if cons.iter().all(ConstraintCheck::holds) => Ok(self.p.score(&m)),
            _ => {
                self.rejected.set(self.rejected.get() + 1);
                Ok(f64::INFINITY)
            }
        }
    }
}

/// Move the discretionary mass within its bounds to reach the goal (Nelder–Mead from the base
/// design; designs outside the bounds or breaking a constraint are rejected, never clipped).
/// The base design must itself be feasible.
pub fn optimise_mass(p: &MassProblem<'_>, max_iters: u64) -> Result<YardOptimum, YardsError> {
    let (base, base_cons) = p.evaluate(&[0.0; 3])?;
    if let Some(c) = base_cons.iter().find(|c| !c.holds()) {
        return Err(YardsError::BaseBreaksConstraint {
            name: c.name.clone(),
            value: c.value,
            limit: c.limit,
        });
    }
    let span = |k: usize| 0.25 * (p.bounds_mm[k][1] - p.bounds_mm[k][0]);
    let start: Vec<f64> = (0..3)
        .map(|k| 0.0f64.clamp(p.bounds_mm[k][0], p.bounds_mm[k][1]))
        .collect();
    let mut simplex = vec![start.clone()];
    for k in 0..3 {
        let mut v = start.clone();
        v[k] += if v[k] + span(k) <= p.bounds_mm[k][1] {
            span(k)
        } else {
            -span(k)
        };
        simplex.push(v);
    }
    let (rejected, evals) = (std::cell::Cell::new(0), std::cell::Cell::new(0));
    let cost = Cost {
        p,
        rejected: &rejected,
        evals: &evals,
    };
    let solver = NelderMead::new(simplex)
        .with_sd_tolerance(1e-6)
        .map_err(YardsError::solver)?;
    let res = Executor::new(cost, solver)
        .configure(|s| s.max_iters(max_iters))
        .run()
        .map_err(YardsError::solver)?;
    let u = res
        .state()
        .get_best_param()
        .cloned()
        .unwrap_or(start.clone());
    let (best, best_cons) = p.evaluate(&u)?;
    Ok(YardOptimum {
        move_mm: [u[0], u[1], u[2]],
        base,
        best,
        base_constraints: base_cons,
        best_constraints: best_cons,
        rejected: rejected.get(),
        evaluations: evals.get(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::distribution::Method;

    #[test]
    fn ellipse_area_of_a_known_cloud() {
        // Area formula: for Σ = diag(a², b²) the p-ellipse has semi-axes a·k, b·k, k² = χ²₂(p).
        let (a, b, p) = (3.0f64, 2.0f64, 0.95f64);
        let k2 = -2.0 * (1.0 - p).ln();
        let area = std::f64::consts::PI * k2 * (a * a * b * b).sqrt();
        assert!((area - std::f64::consts::PI * (a * k2.sqrt()) * (b * k2.sqrt())).abs() < 1e-9);
        assert!((k2 - 5.991_464_547).abs() < 1e-8);
    }

    #[test]
    fn vertical_moi_of_a_diagonal_tensor() {
        let mut p = crate::physics::ModelParams::paper_driver();
        p.club_inertia_kgm2 = nalgebra::Matrix3::from_diagonal(&Vector3::new(3e-4, 5e-4, 4e-4));
        // Loft 0: the vertical is y_F.
        assert!((vertical_moi_gcm2(&p, 0.0) - 5000.0).abs() < 1e-9);
        // Loft 90: the vertical is x_F.
        assert!((vertical_moi_gcm2(&p, 90.0) - 3000.0).abs() < 1e-6);
        let c = check_constraints(&p, &HeadConstraints::rules_wood(0.0));
        assert_eq!(c.len(), 1);
        assert!(c[0].holds() && (c[0].margin - 1000.0).abs() < 1e-9);
    }

    #[test]
    fn metrics_of_a_centre_strike_distribution() {
        let model = ImpactModel::new(crate::physics::ModelParams::paper_driver()).unwrap();
        let swing = SwingSpec {
            club_speed_mph: 105.0,
            dynamic_loft_deg: 12.0,
            attack_angle_deg: 2.0,
            club_path_deg: 0.0,
            face_angle_deg: 0.0,
            lie_tilt_deg: 0.0,
            club_omega_rad_s: [0.0; 3],
        };
        let dist = Distribution {
            method: Method::Quadrature { nodes: 3 },
            impact_centre_mm: [0.0, 0.0],
            sigma_y_mm: 0.0,
            sigma_z_mm: 8.0,
            sigma_club_speed_mph: 0.0,
            sigma_attack_angle_deg: 0.0,
            sigma_club_path_deg: 0.0,
            sigma_dynamic_loft_deg: 0.0,
            sigma_face_angle_deg: 0.0,
        };
        let cfg = FlightConfig::default();
        let m = yard_metrics(&model, &swing, &dist, &cfg, 0.95).unwrap();
        // Heel–toe scatter: gear effect sends toe and heel strikes to opposite sides.
        assert!(m.std_offline_yd > 1.0, "{m:?}");
        assert!(m.mean_carry_yd > 200.0 && m.mean_carry_yd < 320.0, "{m:?}");
        // A one-point distribution has no spread.
        let one = Distribution {
            sigma_z_mm: 0.0,
            ..dist
        };
        let m1 = yard_metrics(&model, &swing, &one, &cfg, 0.95).unwrap();
        assert_eq!(m1.std_carry_yd, 0.0);
        assert_eq!(m1.ellipse_area_yd2, 0.0);
        let map = carry_map(
            &model,
            &swing,
            &[-10.0, 0.0, 10.0],
            &[-20.0, 0.0, 20.0],
            &cfg,
        )
        .unwrap();
        assert!((map.carry_yd[4].unwrap() - m1.mean_carry_yd).abs() < 1e-9);
    }
}
