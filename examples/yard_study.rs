//! Run a study in yards (`configs/studies/yards_driver.toml`): carry/offline maps over the face,
//! robust carry and dispersion over a swing/impact distribution, and a discretionary-mass
//! optimisation for expected carry (or dispersion) under head-mass, Rules-MOI and CoM-box
//! constraints. Writes `carry_map.csv`, `metrics.csv` and `optimise.txt` into the output folder.
//!
//! `cargo run --release --example yard_study -- STUDY.toml OUT_DIR`

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use smash::data::club_file::read_club;
use smash::data::write_atomic;
use smash::flight::{Atmosphere, FlightConfig};
use smash::physics::ImpactModel;
use smash::study::design::DiscretionaryMass;
use smash::study::distribution::{Distribution, Method, SwingSpec};
use smash::study::yards::{
    carry_map, optimise_mass, yard_metrics, HeadConstraints, MassProblem, YardGoal,
};
use smash::units::{g, mm};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    study: StudyT,
    delivery: DeliveryT,
    distribution: DistT,
    grid: GridT,
    atmosphere: Option<Atmosphere>,
    design: DesignT,
    optimise: OptT,
    constraints: ConsT,
}
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StudyT {
    name: String,
    club: PathBuf,
    static_loft_deg: f64,
    confidence: f64,
}
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DeliveryT {
    club_speed_mph: f64,
    dynamic_loft_deg: f64,
    #[serde(default)]
    attack_angle_deg: f64,
    #[serde(default)]
    club_path_deg: f64,
    #[serde(default)]
    face_angle_deg: f64,
}
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DistT {
    nodes: usize,
    impact_centre_mm: [f64; 2],
    #[serde(default)]
    sigma_y_mm: f64,
    #[serde(default)]
    sigma_z_mm: f64,
    #[serde(default)]
    sigma_club_speed_mph: f64,
    #[serde(default)]
    sigma_attack_angle_deg: f64,
    #[serde(default)]
    sigma_club_path_deg: f64,
    #[serde(default)]
    sigma_dynamic_loft_deg: f64,
    #[serde(default)]
    sigma_face_angle_deg: f64,
}
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GridT {
    y_mm: (f64, f64, usize),
    z_mm: (f64, f64, usize),
}
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DesignT {
    mass_g: f64,
    at_mm: [f64; 3],
    bounds_mm: [[f64; 2]; 3],
}
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct OptT {
    goal: String,
    max_iters: u64,
}
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ConsT {
    mass_g: Option<[f64; 2]>,
    moi_vertical_max_gcm2: Option<f64>,
    com_box_mm: Option<[[f64; 2]; 3]>,
}

fn lin((a, b, n): (f64, f64, usize)) -> Vec<f64> {
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n.max(2) - 1) as f64)
        .collect()
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(study), Some(out)) = (args.first(), args.get(1)) else {
        anyhow::bail!("usage: yard_study STUDY.toml OUT_DIR");
    };
    let study = Path::new(study);
    let out = Path::new(out);
    let f: File = toml::from_str(&std::fs::read_to_string(study)?)
        .map_err(|e| anyhow::anyhow!("{}: {}", study.display(), e.message()))?;
    let club_path = study.parent().unwrap_or(Path::new(".")).join(&f.study.club);
    let club = read_club(&club_path)?;
    let nominal = club.nominal.clone();
    let model = ImpactModel::new(nominal.clone())?;
    let swing = SwingSpec {
        club_speed_mph: f.delivery.club_speed_mph,
        dynamic_loft_deg: f.delivery.dynamic_loft_deg,
        attack_angle_deg: f.delivery.attack_angle_deg,
        club_path_deg: f.delivery.club_path_deg,
        face_angle_deg: f.delivery.face_angle_deg,
        lie_tilt_deg: 0.0,
        club_omega_rad_s: [0.0; 3],
    };
    let d = &f.distribution;
    let dist = Distribution {
        method: Method::Quadrature { nodes: d.nodes },
        impact_centre_mm: d.impact_centre_mm,
        sigma_y_mm: d.sigma_y_mm,
        sigma_z_mm: d.sigma_z_mm,
        sigma_club_speed_mph: d.sigma_club_speed_mph,
        sigma_attack_angle_deg: d.sigma_attack_angle_deg,
        sigma_club_path_deg: d.sigma_club_path_deg,
        sigma_dynamic_loft_deg: d.sigma_dynamic_loft_deg,
        sigma_face_angle_deg: d.sigma_face_angle_deg,
    };
    let atm = f.atmosphere.unwrap_or_default();
    let flight = FlightConfig {
        air: atm.air()?,
        ..FlightConfig::default()
    };
    let t0 = std::time::Instant::now();

    // Maps over the face (base design, central swing).
    let (ys, zs) = (lin(f.grid.y_mm), lin(f.grid.z_mm));
    let map = carry_map(&model, &swing, &ys, &zs, &flight).map_err(anyhow::Error::msg)?;
    let mut csv = String::from("y_mm,z_mm,carry_yd,offline_yd\n");
    for (i, y) in ys.iter().enumerate() {
        for (j, z) in zs.iter().enumerate() {
            let k = i * zs.len() + j;
            let cell = |v: Option<f64>| v.map(|v| format!("{v:.3}")).unwrap_or_default();
            writeln!(
                csv,
                "{y},{z},{},{}",
                cell(map.carry_yd[k]),
                cell(map.offline_yd[k])
            )?;
        }
    }

    // Optimisation (includes the base design's robust metrics).
    let mass = DiscretionaryMass {
        mass_kg: g(f.design.mass_g),
        at_m: nalgebra::Vector3::new(
            mm(f.design.at_mm[0]),
            mm(f.design.at_mm[1]),
            mm(f.design.at_mm[2]),
        ),
    };
    let cons = HeadConstraints {
        mass_g: f.constraints.mass_g,
        moi_vertical_max_gcm2: f.constraints.moi_vertical_max_gcm2,
        loft_deg: f.study.static_loft_deg,
        com_box_mm: f.constraints.com_box_mm,
    };
    let goal = match f.optimise.goal.as_str() {
        "max_mean_carry" => YardGoal::MaxMeanCarry,
        "min_dispersion" => YardGoal::MinDispersion,
        other => anyhow::bail!(
            "{}: optimise.goal '{other}': allowed are max_mean_carry, min_dispersion",
            study.display()
        ),
    };
    let problem = MassProblem {
        nominal: &nominal,
        mass: &mass,
        bounds_mm: f.design.bounds_mm,
        base: &swing,
        dist: &dist,
        flight: &flight,
        confidence: f.study.confidence,
        constraints: &cons,
        goal,
    };
    let base_metrics = yard_metrics(&model, &swing, &dist, &flight, f.study.confidence)
        .map_err(anyhow::Error::msg)?;
    let opt = optimise_mass(&problem, f.optimise.max_iters).map_err(anyhow::Error::msg)?;

    let mut metrics = String::from(
        "design,mean_carry_yd,std_carry_yd,mean_offline_yd,std_offline_yd,ellipse_area_yd2,confidence\n",
    );
    for (name, m) in [("base", base_metrics), ("optimum", opt.best)] {
        writeln!(
            metrics,
            "{name},{:.3},{:.3},{:.3},{:.3},{:.2},{}",
            m.mean_carry_yd,
            m.std_carry_yd,
            m.mean_offline_yd,
            m.std_offline_yd,
            m.ellipse_area_yd2,
            m.confidence
        )?;
    }
    let mut rep = String::new();
    writeln!(
        rep,
        "study {} ({}), club {}",
        f.study.name,
        study.display(),
        club.name
    )?;
    writeln!(
        rep,
        "goal {}, {} evaluations, {} proposed designs rejected (outside bounds or breaking a constraint)",
        f.optimise.goal, opt.evaluations, opt.rejected
    )?;
    writeln!(
        rep,
        "mass move at the optimum: dx {:+.2} mm, dy {:+.2} mm, dz {:+.2} mm (face frame F)",
        opt.move_mm[0], opt.move_mm[1], opt.move_mm[2]
    )?;
    let active: Vec<String> = (0..3)
        .flat_map(|k| {
            let b = f.design.bounds_mm[k];
            let axis = ["dx", "dy", "dz"][k];
            let v = opt.move_mm[k];
            [(b[0], "lower"), (b[1], "upper")]
                .into_iter()
                .filter(move |(x, _)| (v - x).abs() < 0.1)
                .map(move |(x, side)| format!("{axis} at its {side} bound {x} mm"))
        })
        .collect();
    writeln!(
        rep,
        "bounds active at the optimum (within 0.1 mm): {}",
        if active.is_empty() {
            "none".to_string()
        } else {
            active.join(", ")
        }
    )?;
    writeln!(
        rep,
        "mean carry {:.2} -> {:.2} yd, carry std {:.2} -> {:.2} yd, {:.0} % ellipse {:.1} -> {:.1} yd²",
        opt.base.mean_carry_yd,
        opt.best.mean_carry_yd,
        opt.base.std_carry_yd,
        opt.best.std_carry_yd,
        100.0 * f.study.confidence,
        opt.base.ellipse_area_yd2,
        opt.best.ellipse_area_yd2
    )?;
    writeln!(
        rep,
        "\nconstraint | base | optimum | limit | margin at optimum | holds"
    )?;
    for (b, o) in opt.base_constraints.iter().zip(&opt.best_constraints) {
        writeln!(
            rep,
            "{} | {:.2} | {:.2} | {} | {:.2} | {}",
            o.name,
            b.value,
            o.value,
            o.limit,
            o.margin,
            if o.holds() { "yes" } else { "NO" }
        )?;
    }
    writeln!(rep, "\nrun time {:.2} s", t0.elapsed().as_secs_f64())?;
    write_atomic(&out.join("carry_map.csv"), csv.as_bytes())?;
    write_atomic(&out.join("metrics.csv"), metrics.as_bytes())?;
    write_atomic(&out.join("optimise.txt"), rep.as_bytes())?;
    print!("{rep}");
    Ok(())
}
