//! An effect candidate's fit started from the step base's evaluation on all shots.

use nalgebra::{DMatrix, DVector};

use super::{CandidateLayout, StepBase};
use crate::fit::FitProblem;

/// The residuals and Jacobian of a candidate's fit at its start, made from the base's on all
/// shots ([`StepBase::at`]) and the candidate's own columns, or `None` unless that is exactly
/// what the fit would evaluate itself: the candidate keeps every base effect in order (no
/// refinement) and, at its start and at each shifted point of a base column, builds the same
/// models as the base (its own effects at their defaults change nothing, bit for bit). The
/// fit is then the same, bit for bit, and saves the `2p` shifted models of the base columns
/// (one Jacobian of `p` columns becomes one of the candidate's `k`).
pub(super) fn start_evaluation(
    b: &StepBase,
    l: &CandidateLayout,
) -> Option<(DVector<f64>, DMatrix<f64>)> {
    let (r0, j0) = b.at?;
    let kept = l.kept;
    if kept != b.theta.len() || j0.ncols() != kept || kept == 0 {
        return None;
    }
    let cand = FitProblem::new(b.club, l.layout.clone(), b.data, b.w);
    let base = FitProblem::new(b.club, b.layout.clone(), b.data, b.w);
    let same = |t: &DVector<f64>, tb: &DVector<f64>| match (
        cand.models(t.as_slice()),
        base.models(tb.as_slice()),
    ) {
        (Ok(a), Ok(m)) => a == m,
        _ => false,
    };
    if !same(&l.start, b.theta) {
        return None;
    }
    // The shifted points of the base columns, as the Jacobian makes them.
    let (lo, hi) = (b.layout.lower(), b.layout.upper());
    let central: Vec<bool> = b
        .layout
        .params()
        .map(|(i, _)| b.layout.effects()[i].is_nonsmooth())
        .collect();
    for j in 0..kept {
        let (to, from) =
            crate::fit::problem::difference_points(central[j], b.theta[j], lo[j], hi[j]);
        for v in [Some(to), from].into_iter().flatten() {
            let (mut t, mut tb) = (l.start.clone(), b.theta.clone());
            t[j] = v;
            tb[j] = v;
            if !same(&t, &tb) {
                return None;
            }
        }
    }
    let own = cand
        .clone()
        .with_active((kept..l.layout.len()).collect(), l.start.clone())
        .jacobian_full(&l.start)
        .ok()?;
    let mut jac = DMatrix::zeros(j0.nrows(), l.layout.len());
    jac.columns_mut(0, kept).copy_from(j0);
    jac.columns_mut(kept, own.ncols()).copy_from(&own);
    Some((r0.clone(), jac))
}

#[cfg(test)]
mod tests {
    use super::super::tests::world;
    use super::super::{all_shots_at, candidate_layout, make_folds, StepBase};
    use super::start_evaluation;
    use crate::fit::spec::parse_effect_list;
    use crate::fit::{
        fit_quietly as fit, fit_quietly_from as fit_from, FitData, FitProblem, ParamLayout,
        Weighting,
    };

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
            cancel: None,
            spread: None,
        };
        let mut taken = Vec::new();
        for cand in crate::diagnose::default_candidates(&data.groups) {
            // A candidate of a kind the base has already is not offered (its layout fails).
            let Ok(l) = candidate_layout(&layout, &theta, &cand, &data.groups) else {
                continue;
            };
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
                let given =
                    fit_from(&club, &l.layout, &data, w, &l.start, 100, Some((r, j))).unwrap();
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
}
