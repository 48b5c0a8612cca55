//! One impact: the closed-form 3 × 3 reduction (`ImpactModel::solve` + launch) against the
//! paper's 15 equations solved directly with a 15 × 15 LU (`tests/common/fifteen.rs`), for
//! the paper's driver without and with effects.

#[path = "../tests/common/fifteen.rs"]
mod fifteen;

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::{Matrix3, Vector3};
use smash::physics::ModelParams;
use smash::{Delivery, ImpactModel};

fn paper_params() -> ModelParams {
    ModelParams {
        club_mass_kg: 0.204,
        club_com_m: Vector3::new(-0.0423, 0.0029, 0.001),
        club_inertia_kgm2: Matrix3::new(
            2843.0, -733.0, 530.2, -733.0, 5679.0, 0.5, 530.2, 0.5, 4085.0,
        ) * 1e-7,
        cor: 0.83,
        bulge_m: 0.305,
        roll_m: 0.305,
        ball_mass_kg: 0.0459,
        ball_radius_m: 0.0213,
        ball_inertia_kgm2: 83.63e-7,
        ball_offset_y_m: 0.0,
        ball_offset_z_m: 0.0,
        tangential_restitution: 0.0,
        friction_mu: None,
        cor_speed_k_s_per_m: 0.0,
        cor_radial_c_per_m2: 0.0,
        loft_bias_rad: 0.0,
        face_bias_rad: 0.0,
    }
}

fn impact(c: &mut Criterion) {
    let d = Delivery {
        club_speed_m_s: 47.0,
        attack_angle_rad: (-1.0f64).to_radians(),
        club_path_rad: 1.5f64.to_radians(),
        dynamic_loft_rad: 12.5f64.to_radians(),
        face_angle_rad: 0.5f64.to_radians(),
        lie_tilt_rad: 0.5f64.to_radians(),
        club_omega_rad_s: Vector3::new(-2.0, 5.0, -10.0),
        impact_y_m: 0.008,
        impact_z_m: -0.012,
    };
    let nominal = paper_params();
    let mut effects = paper_params();
    effects.club_mass_kg += 2.54e-3;
    effects.ball_offset_y_m = 0.48e-3;
    effects.ball_offset_z_m = -0.07e-3;
    effects.tangential_restitution = 0.1;
    effects.cor_speed_k_s_per_m = 0.004;
    effects.cor_radial_c_per_m2 = 50.0;
    let mut group = c.benchmark_group("impact");
    for (name, p) in [("nominal", nominal), ("effects", effects)] {
        let model = ImpactModel::new(p).unwrap();
        group.bench_with_input(BenchmarkId::new("closed_form_3x3", name), &model, |b, m| {
            b.iter(|| black_box(m).solve(black_box(&d)).map(|o| o.launch()))
        });
        group.bench_with_input(BenchmarkId::new("direct_15x15_lu", name), &model, |b, m| {
            b.iter(|| fifteen::solve_fifteen(black_box(m), black_box(&d)))
        });
    }
    group.finish();
}

criterion_group!(benches, impact);
criterion_main!(benches);
