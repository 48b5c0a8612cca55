//! Calibration recovers hidden parameters from synthetic experiments (truth hidden from the fit).

use crate::common;

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
    // Information criteria from the likelihood with profiled scales: 5 parameters + 5 scales,
    // and the calibrated model far more likely than the nominal one on the same scale.
    let l = &cal.likelihood;
    assert_eq!((l.k, cal.likelihood_nominal.k), (10, 5));
    assert_eq!(cal.aic, l.minus_2_ln_l + 20.0);
    assert_eq!(
        cal.bic,
        l.minus_2_ln_l + 10.0 * (cal.n_residuals as f64).ln()
    );
    assert!(cal.likelihood_nominal.aic() > cal.aic + 100.0);
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

/// The whitened Levenberg–Marquardt calibration hands each stage what it knows already (the
/// nominal errors whitened as the first fit's start, the first fit's final Jacobian re-weighted
/// as the second's, the second's as the covariance's). An independent reference evaluates
/// everything afresh, as the procedure is defined: the same estimates, standard errors, χ² and
/// noise scales to 1e-9 (relative; estimates relative to their ranges), with and without
/// impact-location noise.
#[test]
fn lm_calibration_matches_the_procedure_evaluated_afresh() {
    use smash::fit::{covariance, noise_scales, run_lm, FitData, FitProblem, ParamLayout};
    use smash::fit::{Progress, Weighting};
    use smash::measurement::ImpactNoise;
    let club = paper_club();
    let shots = shots(&paper_truth(), &Experiment::default());
    let req = parse_effect_list("added_mass@group,ball_offset").unwrap();
    for noise in [None, Some(ImpactNoise::from_mm(2.0, 2.0).unwrap())] {
        let opts = CalibrateOptions {
            impact_noise: noise,
            ..CalibrateOptions::default()
        };
        let cal = calibrate(&club, &shots, &req, &opts, None).unwrap();

        let data = FitData::from_shots(&shots)
            .unwrap()
            .with_impact_noise(noise)
            .unwrap();
        let layout = ParamLayout::from_requests(&req, &data.groups).unwrap();
        let unit = FitProblem::new(&club, layout.clone(), &data, Weighting::launch(&[1.0; 5]));
        let start = layout.defaults();
        let quiet = None::<(&std::sync::Arc<dyn Progress>, &str)>;
        let fit = |theta: &nalgebra::DVector<f64>| {
            let sigma = noise_scales(&unit.launch_errors(theta.as_slice()).unwrap());
            let pr = unit.clone().with_weighting(Weighting::launch(&sigma));
            run_lm(pr, theta, 100, quiet).unwrap().theta
        };
        let theta = fit(&fit(&start));
        let sigma = noise_scales(&unit.launch_errors(theta.as_slice()).unwrap());
        let whitened = unit.clone().with_weighting(Weighting::launch(&sigma));
        let r = whitened.residuals(theta.as_slice()).unwrap();
        let chi2 = r.norm_squared();
        let dof = (r.len() - layout.len()) as f64;
        let ranges: Vec<f64> = (0..layout.len())
            .map(|j| layout.upper()[j] - layout.lower()[j])
            .collect();
        let cov = covariance(
            &whitened.jacobian_full(&theta).unwrap(),
            chi2 / dof,
            &ranges,
        );
        let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-9 * scale;
        for (j, p) in cal.params.iter().enumerate() {
            assert!(
                close(p.value, theta[j], ranges[j]),
                "{}: {} vs {}",
                p.label(),
                p.value,
                theta[j]
            );
            let (a, b) = (p.stderr.unwrap(), cov.stderr[j].unwrap());
            assert!(close(a, b, b), "{} stderr: {a} vs {b}", p.label());
        }
        assert!(close(cal.chi2, chi2, chi2), "{} vs {chi2}", cal.chi2);
        let before = whitened.residuals(start.as_slice()).unwrap().norm_squared();
        assert!(close(cal.chi2_before, before, before));
        for (a, b) in cal.noise_scales.iter().zip(&sigma) {
            assert!(close(*a, *b, *b), "{a} vs {b}");
        }
        eprintln!(
            "noise {noise:?}: {} iterations, {} evaluations; {}",
            cal.iterations, cal.evaluations, cal.termination
        );
    }
}
