//! Calibration recovers hidden parameters from synthetic experiments.

mod common;

use common::{paper_truth, shots, Experiment};
use smash::fit::{calibrate, parse_effect_list, CalibrateOptions, Method};

#[test]
fn paper_world_recovers_added_mass_per_shaft_and_ball_offset() {
    let truth = paper_truth();
    let shots = shots(&truth, &Experiment::default());
    let club = common::paper_club();
    let req = parse_effect_list("added_mass@group,ball_offset").unwrap();
    let t = std::time::Instant::now();
    let cal = calibrate(&club, &shots, &req, &CalibrateOptions::default(), None).unwrap();
    eprintln!("calibrate: {:?}", t.elapsed());
    let truth_values = [2.54, 0.88, 1.18, 0.48, -0.07];
    for (p, want) in cal.params.iter().zip(truth_values) {
        let se = p.stderr.expect("identifiable");
        eprintln!("{} = {:.4} ± {:.4} (truth {want})", p.label(), p.value, se);
        assert!(
            (p.value - want).abs() < 3.5 * se,
            "{}: {} ± {} vs {}",
            p.label(),
            p.value,
            se,
            want
        );
    }
    eprintln!("chi2 {} red {} evals {} iters {} {}", cal.chi2, cal.reduced_chi2, cal.evaluations, cal.iterations, cal.termination);
}
