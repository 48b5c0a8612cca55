//! Tests of [`super`]: the folds' start from the all-shots rows, the candidates' start from
//! the base's evaluation, and the launch errors against the scalar solve.

use std::path::Path;

use super::*;
use crate::fit::spec::parse_effect_list;

/// The paper world with `golfers` golfers per shaft, as shots.
fn world(golfers: usize) -> (ClubSpec, Vec<crate::model::Shot>) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut cfg = crate::synth::read_config(&root.join("configs/synth/paper_world.toml"))
        .expect("paper world reads");
    cfg.golfers = golfers;
    let club = crate::data::club_file::read_club(&root.join("configs/clubs/paper_driver.toml"))
        .expect("club reads");
    let run = crate::synth::generate(&cfg, &club).expect("world generates");
    (club, run.shots.iter().map(|s| s.to_shot()).collect())
}

/// A fold's fit given the rows of the all-shots fit's residuals and Jacobian is the same
/// fit, bit for bit, as one that evaluates its own start; cross-validation, which keeps
/// those rows' Jacobian for the folds' steps ([`run_lm_point_near`]), gives the
/// cross-validated χ² of the folds' own fits to 1e-5 relative (7e-7 measured: 0.001 of a
/// χ² of 1541, where a candidate's penalty is about 12): with exact locations (one
/// site a shot, serial evaluation) and with impact-location noise (nine sites a shot,
/// evaluated in parallel chunks), from the all-shots solution and from a base point
/// evaluated afresh.
#[test]
fn folds_started_from_the_all_shots_rows_give_the_same_cv() {
    let (club, shots) = world(10);
    let fold_of: Vec<usize> = (0..shots.len()).map(|i| (i / 10) % 5).collect();
    let layout = ParamLayout::from_requests(
        &parse_effect_list("added_mass@group,ball_offset").unwrap(),
        &FitData::from_shots(&shots).unwrap().groups,
    )
    .unwrap();
    for noise in [None, Some(ImpactNoise::from_mm(2.0, 2.0).unwrap())] {
        let data = FitData::from_shots(&shots)
            .unwrap()
            .with_impact_noise(noise)
            .unwrap();
        let folds = make_folds(&data, &fold_of, 5);
        let w = Weighting::launch(&[1.4, 1.0, 0.7, 400.0, 190.0]);
        let run = fit(&club, &layout, &data, w, &layout.defaults(), 100).unwrap();
        let cv = |start: &DVector<f64>, at: Option<AllShots>| {
            cv_chi2(&club, &layout, &folds, w, start, at, 100, None).unwrap()
        };
        // The first fold's fit with and without its rows given: the same point, one
        // residual and one Jacobian evaluation (2 per parameter) fewer.
        let pr = || FitProblem::new(&club, layout.clone(), &folds.train[0], w);
        let rows = fold_rows(
            (&run.residuals, &run.jacobian),
            &folds.train_idx[0],
            w.rows_per_shot(),
        );
        let own = crate::fit::run::execute(pr(), &run.theta, 100, None, false, None).unwrap();
        let given =
            crate::fit::run::execute(pr(), &run.theta, 100, None, false, Some(rows)).unwrap();
        assert_eq!(given.theta, own.theta);
        assert_eq!(given.cost.to_bits(), own.cost.to_bits());
        assert_eq!(given.iterations, own.iterations);
        assert_eq!(
            given.evaluations + 1 + 2 * layout.len() as u64,
            own.evaluations
        );
        let close = |own: f64, near: f64| {
            assert!(
                (near - own).abs() <= 1e-5 * own,
                "noise {noise:?}: {near} against {own}"
            );
        };
        let plain = cv(&run.theta, None);
        close(plain, cv(&run.theta, Some((&run.residuals, &run.jacobian))));
        // A point that is not a fit's solution, evaluated on all shots.
        let start = layout.defaults();
        let at = all_shots_at(&club, &layout, &data, w, &start).unwrap();
        close(cv(&start, None), cv(&start, Some((&at.0, &at.1))));
    }
}

/// An effect candidate's start evaluation made from the base's on all shots and its own
/// columns ([`start_evaluation`]) is the one its fit would make, bit for bit, and the fit
/// started from it is the same fit; it is made for the candidates whose defaults leave the
/// model as it is, not for a refinement of a selected global effect.
#[test]
fn candidate_fits_start_from_the_base_evaluation() {
    let (club, shots) = world(4);
    let data = FitData::from_shots(&shots).unwrap();
    let fold_of: Vec<usize> = (0..shots.len()).map(|i| i % 5).collect();
    let folds = make_folds(&data, &fold_of, 5);
    let layout = ParamLayout::from_requests(
        &parse_effect_list("ball_offset,added_mass").unwrap(),
        &data.groups,
    )
    .unwrap();
    let w = Weighting::launch(&[1.4, 1.0, 0.7, 400.0, 190.0]);
    let theta = fit(&club, &layout, &data, w, &layout.defaults(), 100)
        .unwrap()
        .theta;
    let at = all_shots_at(&club, &layout, &data, w, &theta).unwrap();
    let errors = vec![[0.0; 5]; data.len()];
    let b = StepBase {
        club: &club,
        data: &data,
        folds: &folds,
        layout: &layout,
        theta: &theta,
        errors: &errors,
        sigma: [1.4, 1.0, 0.7, 400.0, 190.0],
        w,
        rms: [1.0; 5],
        cv: f64::NAN,
        at: Some((&at.0, &at.1)),
        max_iters: 100,
        progress: None,
        spread: None,
    };
    let mut taken = Vec::new();
    for cand in crate::diagnose::default_candidates(&data.groups) {
        let l = candidate_layout(&layout, &theta, &cand, &data.groups).unwrap();
        let Some((r, j)) = start_evaluation(&b, &l) else {
            continue;
        };
        taken.push(cand.label());
        let pr = FitProblem::new(&club, l.layout.clone(), &data, w);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(
            bits(r.as_slice()),
            bits(pr.residuals(l.start.as_slice()).unwrap().as_slice())
        );
        assert_eq!(
            bits(j.as_slice()),
            bits(pr.jacobian_full(&l.start).unwrap().as_slice()),
            "{}",
            cand.label()
        );
        if taken.len() <= 2 {
            let own = fit(&club, &l.layout, &data, w, &l.start, 100).unwrap();
            let given = fit_from(&club, &l.layout, &data, w, &l.start, 100, Some((r, j))).unwrap();
            assert_eq!(bits(given.theta.as_slice()), bits(own.theta.as_slice()));
            assert_eq!(given.cost.to_bits(), own.cost.to_bits());
            assert_eq!(given.iterations, own.iterations);
            assert!(given.evaluations < own.evaluations);
        }
    }
    eprintln!("start evaluations taken for {taken:?}");
    assert!(taken.len() >= 3, "{taken:?}");
    // A refinement of the selected global added mass replaces it: no start evaluation.
    let refine = parse_effect_list("added_mass@group").unwrap().remove(0);
    let l = candidate_layout(&layout, &theta, &refine, &data.groups).unwrap();
    assert!(start_evaluation(&b, &l).is_none());
}

/// The launch errors, now evaluated on the lanes, agree with solving each shot afresh by
/// the scalar solve to 1e-9 relative (of the component's scale).
#[test]
fn launch_errors_agree_with_the_scalar_solve() {
    let (club, shots) = world(4);
    let data = FitData::from_shots(&shots).unwrap();
    let layout = ParamLayout::new(Vec::new()).unwrap();
    let errors = FitProblem::new(&club, layout, &data, Weighting::launch(&[1.0; 5]))
        .launch_errors(&[])
        .unwrap();
    assert_eq!(errors.len(), shots.len());
    for (s, e) in shots.iter().zip(&errors) {
        let model = club.model_for_group(&s.group).unwrap();
        let launch = model.solve(&s.delivery).unwrap().launch().to_file_units();
        let measured = s.measured.unwrap().to_file_units();
        for c in 0..5 {
            let want = launch[c] - measured[c];
            let tol = 1e-9 * launch[c].abs().max(1.0);
            assert!(
                (e[c] - want).abs() <= tol,
                "shot {}: {} vs {want}",
                s.id,
                e[c]
            );
        }
    }
}
