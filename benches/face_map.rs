//! Face-map throughput: launch conditions over a heel–toe × crown–sole grid of impact points
//! for the paper's driver (configs/clubs/paper_driver.toml), reported as impacts/s.
//!
//! Variants: the vectorised kernel on one thread, the kernel with rows in parallel on the
//! rayon pool (`face_map_into`), and for scale the generic `ImpactModel::solve` + `launch()`
//! per point on one thread.

use std::path::Path;

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use nalgebra::Vector3;
use smash::data::club_file::read_club;
use smash::sweep::{face_map_into, FaceMapKernel, LaunchGrid};
use smash::units::{deg, mm, mph};
use smash::{Delivery, ImpactModel};

fn paper_model() -> ImpactModel {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/clubs/paper_driver.toml");
    let club = read_club(&path).expect("paper driver club file");
    ImpactModel::new(club.nominal).expect("valid model")
}

fn delivery() -> Delivery {
    Delivery {
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
    }
}

/// `n` points evenly spaced over `[-half, half]`.
fn linspace(half: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| -half + 2.0 * half * i as f64 / (n - 1) as f64)
        .collect()
}

fn face_map(c: &mut Criterion) {
    let model = paper_model();
    let d = delivery();
    for n in [101usize, 401] {
        // ±25 mm crown–sole, ±40 mm heel–toe.
        let ys = linspace(mm(25.0), n);
        let zs = linspace(mm(40.0), n);
        let mut out = LaunchGrid::with_len(n * n);
        let mut group = c.benchmark_group(format!("face_map_{n}x{n}"));
        group.throughput(Throughput::Elements((n * n) as u64));
        group.bench_function(BenchmarkId::new("kernel", "1_thread"), |b| {
            b.iter(|| {
                let k = FaceMapKernel::new(black_box(&model), black_box(&d));
                k.eval_grid(black_box(&ys), black_box(&zs), &mut out);
                black_box(&out);
            })
        });
        group.bench_function(BenchmarkId::new("kernel", "rayon"), |b| {
            b.iter(|| {
                face_map_into(
                    black_box(&model),
                    black_box(&d),
                    black_box(&ys),
                    black_box(&zs),
                    &mut out,
                );
                black_box(&out);
            })
        });
        if n <= 101 {
            group.bench_function(BenchmarkId::new("generic_solve", "1_thread"), |b| {
                b.iter(|| {
                    let mut sum = 0.0;
                    for &y in black_box(&ys) {
                        for &z in black_box(&zs) {
                            let mut dd = d;
                            dd.impact_y_m = y;
                            dd.impact_z_m = z;
                            if let Ok(o) = model.solve(&dd) {
                                let l = o.launch();
                                sum += l.ball_speed_m_s
                                    + l.launch_angle_rad
                                    + l.azimuth_rad
                                    + l.backspin_rad_s
                                    + l.sidespin_rad_s;
                            }
                        }
                    }
                    black_box(sum)
                })
            });
        }
        group.finish();
    }
}

criterion_group!(benches, face_map);
criterion_main!(benches);
