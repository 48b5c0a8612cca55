//! One impact: the closed-form 3 × 3 reduction (`ImpactModel::solve` + launch) against the
//! paper's 15 equations solved directly with a 15 × 15 LU (`tests/common/fifteen.rs`), for
//! the paper's driver without and with effects.

#[path = "../tests/common/fifteen.rs"]
mod fifteen;

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::Vector3;
use smash::physics::ModelParams;
use smash::{Delivery, ImpactModel};

fn paper_params() -> ModelParams {
    ModelParams::paper_driver()
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
        shaft_mass_g: None,
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
