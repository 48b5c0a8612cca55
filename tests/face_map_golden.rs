//! The face-map kernel on the golden deliveries (`tests/data/golden/*.csv`, one effect per file),
//! each delivery as a one-point `eval_points`, against the golden launch values to 1e-6 relative
//! or absolute. The reference values come from an independent implementation
//! (`tests/data/golden/generate.py`, see its README).

use std::path::PathBuf;

use nalgebra::Vector3;
use smash::data::club_file::read_club;
use smash::effects::EffectKind;
use smash::sweep::{FaceMapKernel, LaunchGrid};
use smash::units::{deg, mm, mph};
use smash::{Delivery, ImpactModel, LaunchComponent};

/// A golden file and the effect (name, parameter values) it switches on.
type GoldenFile = (&'static str, Option<(&'static str, &'static [f64])>);

const FILES: [GoldenFile; 11] = [
    ("nominal", None),
    ("added_mass", Some(("added_mass", &[2.54]))),
    ("ball_offset", Some(("ball_offset", &[0.48, -0.07]))),
    (
        "tangential_restitution",
        Some(("tangential_restitution", &[-0.2])),
    ),
    ("friction", Some(("friction", &[0.05]))),
    ("cor_speed", Some(("cor_speed", &[0.002]))),
    ("cor_radial", Some(("cor_radial", &[0.0002]))),
    ("loft_bias", Some(("loft_bias", &[1.0]))),
    ("face_bias", Some(("face_bias", &[-1.5]))),
    ("com_offset", Some(("com_offset", &[-3.0, -2.0, 1.5]))),
    ("inertia_scale", Some(("inertia_scale", &[1.2]))),
];

#[test]
fn kernel_reproduces_golden_files() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/golden");
    let club_path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("configs/clubs/paper_driver.toml");
    let nominal = read_club(&club_path).unwrap().nominal;
    let mut rows = 0;
    for (file, effect) in FILES {
        let mut p = nominal.clone();
        if let Some((name, values)) = effect {
            EffectKind::from_name(name).unwrap().apply(values, &mut p);
        }
        let model = ImpactModel::new(p).unwrap();
        let mut rdr = csv::Reader::from_path(dir.join(format!("{file}.csv"))).unwrap();
        let headers = rdr.headers().unwrap().clone();
        for rec in rdr.records() {
            let rec = rec.unwrap();
            let col = |name: &str| -> f64 {
                let i = headers.iter().position(|h| h == name).unwrap();
                rec[i].parse().unwrap()
            };
            let d = Delivery {
                club_speed_m_s: mph(col("club_speed_mph")),
                attack_angle_rad: deg(col("attack_angle_deg")),
                club_path_rad: deg(col("club_path_deg")),
                dynamic_loft_rad: deg(col("dynamic_loft_deg")),
                face_angle_rad: deg(col("face_angle_deg")),
                lie_tilt_rad: deg(col("lie_tilt_deg")),
                club_omega_rad_s: Vector3::new(
                    col("club_omega_x_rad_s"),
                    col("club_omega_y_rad_s"),
                    col("club_omega_z_rad_s"),
                ),
                impact_y_m: 0.0,
                impact_z_m: 0.0,
                shaft_mass_g: None,
            };
            let mut out = LaunchGrid::with_len(1);
            FaceMapKernel::new(&model, &d).eval_points(
                &[mm(col("impact_y_mm"))],
                &[mm(col("impact_z_mm"))],
                out.all_out(),
            );
            assert!(out.valid[0], "{file}: row {rows} invalid");
            for c in LaunchComponent::ALL {
                let got = out.component(c)[0] * c.file_units_per_si();
                let want = col(&format!("pred_{}", c.column()));
                let diff = (got - want).abs();
                assert!(
                    diff <= 1e-6 * want.abs().max(1.0),
                    "{file} row {rows} {c:?}: kernel {got}, golden {want}"
                );
            }
            rows += 1;
        }
    }
    assert_eq!(rows, 11 * 40, "every golden row of every file");
    eprintln!("{rows} golden rows reproduced");
}
