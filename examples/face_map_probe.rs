//! Quick timing probe for the face-map kernel (best of many repetitions, robust to a loaded
//! machine): `cargo run --release --example face_map_probe`.

use std::time::Instant;

use nalgebra::Vector3;
use smash::physics::ModelParams;
use smash::sweep::{FaceMapKernel, LaunchGrid};
use smash::units::{deg, mm, mph};
use smash::{Delivery, ImpactModel};

fn main() {
    let p = ModelParams {
        friction_mu: std::env::args().nth(1).map(|s| s.parse().unwrap()),
        ..ModelParams::paper_driver()
    };
    let model = ImpactModel::new(p).unwrap();
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
    let n = 401;
    let lin = |h: f64| -> Vec<f64> {
        (0..n)
            .map(|i| -h + 2.0 * h * i as f64 / (n - 1) as f64)
            .collect()
    };
    let (ys, zs) = (lin(mm(25.0)), lin(mm(40.0)));
    let mut out = LaunchGrid::with_len(n * n);
    let mut best = f64::INFINITY;
    for _ in 0..300 {
        let t = Instant::now();
        let k = FaceMapKernel::new(&model, &d);
        k.eval_grid(&ys, &zs, &mut out);
        std::hint::black_box(&out);
        best = best.min(t.elapsed().as_secs_f64());
    }
    let mut best_par = f64::INFINITY;
    for _ in 0..300 {
        let t = Instant::now();
        smash::sweep::face_map_into(&model, &d, &ys, &zs, &mut out);
        std::hint::black_box(&out);
        best_par = best_par.min(t.elapsed().as_secs_f64());
    }
    println!(
        "face_map_into on {} rayon threads: best {:.3} ms = {:.1} M impacts/s",
        rayon::current_num_threads(),
        best_par * 1e3,
        (n * n) as f64 / best_par / 1e6
    );
    println!(
        "{:?}: best {:.3} ms per {n}x{n} grid = {:.1} M impacts/s on one thread ({:.1} ns/impact)",
        smash::sweep::simd_level(),
        best * 1e3,
        (n * n) as f64 / best / 1e6,
        best * 1e9 / (n * n) as f64
    );
}
