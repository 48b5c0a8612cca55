//! Calibration recovers hidden parameters from synthetic experiments (truth hidden from the fit).

mod common;

use common::{paper_club, paper_truth, shots, Experiment};
use smash::data::club_file::{club_toml, parse_club};
use smash::fit::{calibrate, parse_effect_list, CalibrateOptions, FitError, Method, Stage};
use smash::predict::predict_shots;

const PAPER_TRUTH: [(&str, f64); 5] = [
    ("added_mass@A.dm_g", 2.54),
    ("added_mass@B.dm_g", 0.88),
    ("added_mass@C.dm_g", 1.18),
    ("ball_offset.dy_mm", 0.48),
    ("ball_offset.dz_mm", -0.07),
];

#[test]
fn paper_world_recovers_added_mass_per_shaft_and_ball_offset() {
    let shots = shots(&paper_truth(), &Experiment::default());
    let req = parse_effect_list("added_mass@group,ball_offset").unwrap();
    let cal = calibrate(
        &paper_club(),
        &shots,
        &req,
        &CalibrateOptions::default(),
        None,
    )
    .unwrap();
    for (p, (label, want)) in cal.params.iter().zip(PAPER_TRUTH) {
        assert_eq!(p.label(), label);
        let se = p.stderr.expect("identifiable");
        eprintln!("{label} = {:.4} ± {:.4} (truth {want})", p.value, se);
        assert!(
            (p.value - want).abs() < 3.0 * se,
            "{label}: {} ± {se} vs truth {want}",
            p.value
        );
    }
    // Standard errors of the right size: 200 shots a shaft at 0.8 mph noise.
    assert!(cal.params[0].stderr.unwrap() < 0.6 && cal.params[3].stderr.unwrap() < 0.01);
    // Ordered like the shaft masses (74.5 g A > 70.9 g C > 60.3 g B).
    let dm = |i: usize| cal.params[i].value;
    assert!(
        dm(0) > dm(2) && dm(2) > dm(1),
        "A {} C {} B {}",
        dm(0),
        dm(2),
        dm(1)
    );
    let rel = cal.shaft_relation.as_ref().expect("shaft masses known");
    assert_eq!(rel.points.len(), 3);
    assert!(rel.line.slope > 0.0 && rel.line.r > 0.8, "{:?}", rel.line);
    // A good fit: reduced chi2 near one, far below the nominal model's.
    assert!((cal.reduced_chi2 - 1.0).abs() < 0.1, "{}", cal.reduced_chi2);
    assert!(cal.chi2_before > 5.0 * cal.chi2);
    assert!(cal.bic > cal.aic && cal.aic > cal.chi2);
    assert!(cal.evaluations > cal.iterations && cal.termination.contains("converged"));
    // The mean backspin error collapses (paper: 741 → ~100 rpm; here the truth is reachable).
    for (b, a) in cal.before.groups.iter().zip(&cal.after.groups) {
        assert!(
            b.components[3].mean > 300.0,
            "nominal backspin error {}",
            b.components[3].mean
        );
        assert!(a.components[3].mean.abs() < 30.0);
        assert!(a.components[0].mean.abs() < 0.2);
    }
}

#[test]
fn calibrated_club_reads_back_and_predicts_the_same() {
    let shots = shots(&paper_truth(), &Experiment::default());
    let req = parse_effect_list("added_mass@group,ball_offset").unwrap();
    let cal = calibrate(
        &paper_club(),
        &shots,
        &req,
        &CalibrateOptions::default(),
        None,
    )
    .unwrap();
    let text = club_toml(&cal.club, "test");
    let back = parse_club(std::path::Path::new("x.toml"), &text).unwrap();
    assert_eq!(back.effects.len(), 4);
    let a = predict_shots(&cal.club, &shots).unwrap();
    let b = predict_shots(&back, &shots).unwrap();
    for (x, y) in a.iter().zip(&b) {
        assert!((x.launch().ball_speed_m_s - y.launch().ball_speed_m_s).abs() < 1e-12);
    }
}

#[test]
fn paper_method_assigns_stages_like_the_paper_and_recovers_the_truth() {
    let shots = shots(&paper_truth(), &Experiment::default());
    let req = parse_effect_list("added_mass@group,ball_offset").unwrap();
    let opts = CalibrateOptions {
        method: Method::Paper,
        ..CalibrateOptions::default()
    };
    let cal = calibrate(&paper_club(), &shots, &req, &opts, None).unwrap();
    let stages: Vec<Stage> = cal.paper_stages.iter().map(|a| a.stage).collect();
    assert_eq!(
        stages,
        [
            Stage::Linear,
            Stage::Linear,
            Stage::Linear,
            Stage::Angular,
            Stage::Angular
        ]
    );
    for (p, (label, want)) in cal.params.iter().zip(PAPER_TRUTH) {
        let se = p.stderr.unwrap();
        eprintln!("paper method {label} = {:.4} ± {:.4}", p.value, se);
        assert!(
            (p.value - want).abs() < 4.0 * se,
            "{label}: {} vs {want}",
            p.value
        );
    }
}

#[test]
fn refuses_what_it_cannot_fit() {
    let club = paper_club();
    let all = shots(&paper_truth(), &Experiment::default());
    let req = parse_effect_list("com_offset,ball_offset").unwrap();
    let e = calibrate(&club, &all[..5], &req, &CalibrateOptions::default(), None).unwrap_err();
    assert_eq!(
        e,
        FitError::TooFewShots {
            shots: 5,
            params: 5
        }
    );
    let mut one_group = all[..50].to_vec();
    one_group.iter_mut().for_each(|s| s.group = "all".into());
    let req = parse_effect_list("added_mass@group").unwrap();
    let e = calibrate(&club, &one_group, &req, &CalibrateOptions::default(), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("only one group") && e.contains("use the global form 'added_mass'"));
    let mut unmeasured = all[..50].to_vec();
    unmeasured.iter_mut().for_each(|s| s.measured = None);
    let req = parse_effect_list("added_mass").unwrap();
    let e = calibrate(&club, &unmeasured, &req, &CalibrateOptions::default(), None).unwrap_err();
    assert_eq!(e, FitError::NoMeasurements);
    let opts = CalibrateOptions {
        max_iters: 1,
        ..CalibrateOptions::default()
    };
    let req = parse_effect_list("ball_offset").unwrap();
    let e = calibrate(&club, &all, &req, &opts, None).unwrap_err();
    assert!(matches!(e, FitError::NotConverged { .. }), "{e}");
}
