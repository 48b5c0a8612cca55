use super::*;

#[test]
fn a_mass_moved_keeps_the_head_mass_and_moves_the_com_by_its_share() {
    let p = ModelParams::paper_driver();
    let c = HeadChange {
        mass_move: Some(MassMove {
            mass_g: 5.0,
            from_mm: [-70.0, -10.0, 0.0],
            to_mm: [-80.0, -10.0, -10.0],
        }),
        ..HeadChange::default()
    };
    let q = c.apply(&p).unwrap();
    assert_eq!(q.club_mass_kg, p.club_mass_kg);
    let shift = (q.club_com_m - p.club_com_m) / crate::units::M_PER_MM;
    let share = 5.0 / (p.club_mass_kg * 1e3);
    assert!((shift.x + 10.0 * share).abs() < 1e-12);
    assert!(shift.y.abs() < 1e-12);
    assert!((shift.z + 10.0 * share).abs() < 1e-12);
    // Moving a mass back and to the heel, away from the CoM, raises the vertical-axis MOI.
    assert!(q.club_inertia_kgm2[(1, 1)] > p.club_inertia_kgm2[(1, 1)]);
    // Nothing else changes.
    assert_eq!(q.bulge_m, p.bulge_m);
    assert!(HeadChange::default().is_empty() && !c.is_empty());
}

#[test]
fn the_carry_change_map_of_a_loft_change_and_its_grid() {
    let [ys, zs] = carry_change_grid([0.0, 5.0], [4.0, 2.0], 5);
    assert_eq!(ys, [-10.0, -5.0, 0.0, 5.0, 10.0]);
    assert_eq!(zs, [-15.0, -5.0, 5.0, 15.0, 25.0]);
    let p = ModelParams::paper_driver();
    let swing = SwingSpec {
        club_speed_mph: 95.0,
        dynamic_loft_deg: 13.0,
        attack_angle_deg: 0.0,
        club_path_deg: 0.0,
        face_angle_deg: 0.0,
        lie_tilt_deg: 0.0,
        club_omega_rad_s: [0.0; 3],
    };
    let flight = crate::flight::FlightConfig::default();
    let none = HeadChange::default();
    let m = carry_change_map(&p, &p, &none, &swing, &flight, &[ys.clone(), zs.clone()]);
    let m = m.unwrap();
    assert_eq!(m.d_carry_yd.len(), 25);
    assert!(m.d_carry_yd.iter().all(|d| d == &Some(0.0)), "{m:?}");
    // Two degrees more loft at 95 mph: the centre strike carries differently, and every
    // change is finite.
    let loft = HeadChange {
        loft_change_deg: Some(2.0),
        ..HeadChange::default()
    };
    let m = carry_change_map(&p, &p, &loft, &swing, &flight, &[ys, zs]).unwrap();
    let centre = m.d_carry_yd[2 * 5 + 1].unwrap();
    assert!(centre.abs() > 0.1 && centre.is_finite(), "{centre}");
}

#[test]
fn a_mass_heavier_than_the_head_is_refused() {
    let p = ModelParams::paper_driver();
    let c = HeadChange {
        mass_move: Some(MassMove {
            mass_g: 500.0,
            from_mm: [-70.0, 0.0, 0.0],
            to_mm: [-60.0, 0.0, 0.0],
        }),
        ..HeadChange::default()
    };
    let e = c.apply(&p).unwrap_err();
    assert!(
        matches!(
            e,
            WhatIfError::Part {
                part: ChangePart::MassMove,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(e.to_string().contains("below the head mass, 204 g"), "{e}");
}

#[test]
fn bulge_roll_and_loft_are_replaced_or_added() {
    let p = ModelParams::paper_driver();
    let c = HeadChange {
        bulge_mm: Some(280.0),
        roll_mm: Some(250.0),
        loft_change_deg: Some(1.5),
        ..HeadChange::default()
    };
    let q = c.apply(&p).unwrap();
    assert!((q.bulge_m - 0.28).abs() < 1e-15 && (q.roll_m - 0.25).abs() < 1e-15);
    let swing = SwingSpec {
        club_speed_mph: 95.0,
        dynamic_loft_deg: 12.0,
        attack_angle_deg: 0.0,
        club_path_deg: 0.0,
        face_angle_deg: 0.0,
        lie_tilt_deg: 0.0,
        club_omega_rad_s: [0.0; 3],
    };
    assert_eq!(c.swing(&swing).dynamic_loft_deg, 13.5);
    assert_eq!(c.describe().len(), 3);
}
