//! A full design-study variant sweep: 5 clubhead CoM offsets × 5 inertia scales, each a
//! 101 × 101 face map (±25 mm crown–sole, ±40 mm heel–toe) for the paper's driver, through
//! `face_map_into` with one reused output grid (rows in parallel), and for comparison the same
//! sweep parallel over the variants with each map on one thread.

use std::path::Path;

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use nalgebra::Vector3;
use rayon::prelude::*;
use smash::data::club_file::read_club;
use smash::physics::ModelParams;
use smash::sweep::{face_map_into, FaceMapKernel, LaunchGrid};
use smash::units::{deg, mm, mph};
use smash::{Delivery, ImpactModel};

fn paper_params() -> ModelParams {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/clubs/paper_driver.toml");
    read_club(&path).expect("paper driver club file").nominal
}

fn linspace(half: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| -half + 2.0 * half * i as f64 / (n - 1) as f64)
        .collect()
}

/// The 25 variants: CoM shifted back/forward along the face normal by −4…+4 mm and the
/// inertia tensor scaled by 0.8…1.2.
fn variants(base: &ModelParams) -> Vec<ImpactModel> {
    let mut out = Vec::new();
    for dx_mm in [-4.0, -2.0, 0.0, 2.0, 4.0] {
        for s in [0.8, 0.9, 1.0, 1.1, 1.2] {
            let mut p = base.clone();
            p.club_com_m.x += mm(dx_mm);
            p.club_inertia_kgm2 *= s;
            out.push(ImpactModel::new(p).expect("valid variant"));
        }
    }
    out
}

fn sweep(c: &mut Criterion) {
    let models = variants(&paper_params());
    let d = Delivery {
        club_speed_m_s: mph(105.0),
        attack_angle_rad: deg(-1.0),
        club_path_rad: deg(1.5),
        dynamic_loft_rad: deg(12.5),
        face_angle_rad: deg(0.5),
        lie_tilt_rad: deg(0.5),
        club_omega_rad_s: Vector3::new(-2.0, 5.0, -10.0),
        impact_y_m: 0.0,
        impact_z_m: 0.0,
        shaft_mass_g: None,
    };
    let n = 101;
    let ys = linspace(mm(25.0), n);
    let zs = linspace(mm(40.0), n);
    let mut grid = LaunchGrid::with_len(n * n);
    let mut group = c.benchmark_group("sweep_5com_x_5inertia_101x101");
    group.throughput(Throughput::Elements((models.len() * n * n) as u64));
    group.bench_function("face_map_into", |b| {
        b.iter(|| {
            let mut checksum = 0.0;
            for m in black_box(&models) {
                face_map_into(m, black_box(&d), black_box(&ys), black_box(&zs), &mut grid);
                // Reduce each map so the work is not optimised away (as a study would).
                checksum += grid.ball_speed_m_s[n * n / 2];
            }
            black_box(checksum)
        })
    });
    // For comparison: the same sweep parallel over the variants instead of over rows, each
    // map on one thread (`FaceMapKernel::eval_grid`), one reused grid per variant.
    let mut grids: Vec<LaunchGrid> = models.iter().map(|_| LaunchGrid::with_len(n * n)).collect();
    group.bench_function("par_over_variants_eval_grid", |b| {
        b.iter(|| {
            models
                .par_iter()
                .zip(grids.par_iter_mut())
                .map(|(m, g)| {
                    FaceMapKernel::new(m, black_box(&d)).eval_grid(
                        black_box(&ys),
                        black_box(&zs),
                        g,
                    );
                    g.ball_speed_m_s[n * n / 2]
                })
                .sum::<f64>()
        })
    });
    group.finish();
}

criterion_group!(benches, sweep);
criterion_main!(benches);
