mod common;
use common::*;
use smash::diagnose::{diagnose, DiagnoseOptions};

#[test]
#[ignore]
fn explore() {
    let worlds: Vec<(&str, Vec<smash::Effect>)> = vec![
        ("null", vec![]),
        ("paper", paper_truth().effects),
        ("added_mass", vec![fx("added_mass", &[2.0], None)]),
        ("ball_offset", vec![fx("ball_offset", &[0.4, -0.1], None)]),
        ("cor_speed", vec![fx("cor_speed", &[0.003], None)]),
        ("cor_radial", vec![fx("cor_radial", &[1e-4], None)]),
        ("loft_bias", vec![fx("loft_bias", &[0.5], None)]),
        ("face_bias", vec![fx("face_bias", &[0.5], None)]),
        ("com_offset", vec![fx("com_offset", &[0.0, 1.5, -2.0], None)]),
        ("inertia_scale", vec![fx("inertia_scale", &[1.3], None)]),
        ("friction", vec![fx("friction", &[0.1], None)]),
        ("tangential_restitution", vec![fx("tangential_restitution", &[0.1], None)]),
    ];
    let only = std::env::var("WORLD").ok();
    for (name, eff) in worlds {
        if only.as_deref().is_some_and(|o| o != name) { continue; }
        let t = truth(eff);
        let s = shots(&t, &Experiment::default());
        let t0 = std::time::Instant::now();
        let d = diagnose(&paper_club(), &s, &DiagnoseOptions::default(), None).unwrap();
        eprintln!("== {name}: selected {:?} in {:?}", d.selected, t0.elapsed());
        for (i, st) in d.steps.iter().enumerate() {
            for c in st.candidates.iter().take(4) {
                eprintln!("   step {} {:<24} gain {:>10.1} pen {:>5.1} elig {} unid {:?} {:?} {}", i+1, c.label, c.gain, c.penalty, c.eligible(), c.unidentified, c.failure, c.params.iter().map(|p| format!("{}={:.4}±{:.4}", p.param, p.value, p.stderr.unwrap_or(f64::NAN))).collect::<Vec<_>>().join(" "));
            }
        }
    }
}
