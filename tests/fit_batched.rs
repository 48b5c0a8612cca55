//! The fits' evaluation machinery (frames and contact frames computed once per data set, shots
//! evaluated four at a time on the lanes with the branch-free `atan2`, in parallel chunks,
//! Jacobian columns of per-group parameters evaluated on their group only) agrees to 1e-9
//! relative with solving every shot afresh with `ImpactModel::solve` (through
//! `measurement::expected_outcome`, libm's `atan2` and `hypot`), with every library effect free
//! at random values, friction on, with and without impact-location noise, and with the shots in
//! a random order and a count that leaves a short last chunk, so a shot evaluated in another
//! shot's lane shows as an error of the size of the shot-to-shot spread.

use crate::common;

use nalgebra::{DMatrix, DVector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use common::{fx, paper_truth, shots, truth, Experiment};
use smash::effects::EffectKind;
use smash::fit::{EffectRequest, FitData, FitProblem, ParamLayout, Weighting, FD_STEP_OF_RANGE};
use smash::measurement::{expected_outcome, ImpactNoise};
use smash::physics::LaunchComponent;

/// Residuals the slow way: each shot solved from its delivery by the scalar solve.
fn reference_residuals(pr: &FitProblem<'_>, theta: &[f64], inv_scale: &[f64; 5]) -> Vec<f64> {
    let models = pr.models(theta).expect("physical parameters");
    let data = pr.data();
    let mut out = Vec::with_capacity(pr.rows());
    for i in 0..data.len() {
        let nodes = data.impact_nodes.as_ref().map(|n| &n[i]);
        let (launch, _, _) =
            expected_outcome(&models[data.group_of[i]], &data.deliveries[i], nodes).unwrap();
        for (c, (m, inv)) in data.measured[i].iter().zip(inv_scale).enumerate() {
            out.push((launch.get_file(LaunchComponent::ALL[c]) - m) * inv);
        }
    }
    out
}

/// The documented difference (forward, downwards where the step would leave the upper bound;
/// central for the friction coefficient), from reference residuals.
fn reference_jacobian(pr: &FitProblem<'_>, theta: &DVector<f64>, inv: &[f64; 5]) -> DMatrix<f64> {
    let layout = pr.layout();
    let (lo, hi) = (layout.lower(), layout.upper());
    let friction: Vec<bool> = layout
        .params()
        .map(|(i, _)| layout.effects()[i].kind == EffectKind::Friction)
        .collect();
    let mut jac = DMatrix::zeros(pr.rows(), pr.active().len());
    for (k, &j) in pr.active().iter().enumerate() {
        let h = FD_STEP_OF_RANGE * (hi[j] - lo[j]);
        let (mut a, mut b) = (theta.clone(), theta.clone());
        if friction[j] {
            a[j] = (theta[j] + h).min(hi[j]);
            b[j] = (theta[j] - h).max(lo[j]);
        } else if theta[j] + h <= hi[j] {
            a[j] = theta[j] + h;
        } else {
            b[j] = theta[j] - h;
        }
        let span = a[j] - b[j];
        let ra = reference_residuals(pr, a.as_slice(), inv);
        let rb = reference_residuals(pr, b.as_slice(), inv);
        for r in 0..pr.rows() {
            jac[(r, k)] = (ra[r] - rb[r]) / span;
        }
    }
    jac
}

/// Model − measured per row agrees to 1e-9 relative to the magnitudes subtracted (the model's
/// and the measurement's, whitened).
fn close_residuals(what: &str, got: &[f64], want: &[f64], pr: &FitProblem<'_>, inv: &[f64; 5]) {
    assert_eq!(got.len(), want.len(), "{what}: lengths");
    let data = pr.data();
    let mut worst = 0.0f64;
    for (r, (g, w)) in got.iter().zip(want).enumerate() {
        let measured = (data.measured[r / 5][r % 5] * inv[r % 5]).abs();
        let scale = w.abs().max(measured).max(f64::MIN_POSITIVE);
        let rel = (g - w).abs() / scale;
        worst = worst.max(rel);
        assert!(
            rel <= 1e-9,
            "{what}: row {r}: {g} vs {w} (relative {rel:e})"
        );
    }
    eprintln!("{what}: worst relative difference {worst:e}");
}

/// Each Jacobian column agrees to 1e-9 relative to its largest entry.
fn close_jacobian(got: &DMatrix<f64>, want: &DMatrix<f64>) {
    assert_eq!(got.shape(), want.shape());
    let mut worst = 0.0f64;
    for k in 0..want.ncols() {
        let scale = want.column(k).amax();
        for r in 0..want.nrows() {
            let (g, w) = (got[(r, k)], want[(r, k)]);
            let diff = (g - w).abs();
            if scale == 0.0 {
                assert_eq!(g, 0.0, "jacobian ({r}, {k}): {g} where the column is 0");
                continue;
            }
            worst = worst.max(diff / scale);
            assert!(
                diff <= 1e-9 * scale,
                "jacobian ({r}, {k}): {g} vs {w} (column scale {scale:e})"
            );
        }
    }
    eprintln!("jacobian: worst column-relative difference {worst:e}");
}

#[test]
fn lane_residuals_and_jacobian_agree_with_the_scalar_solve() {
    // A club that carries its own biases and friction (so cached frames are made with non-zero
    // biases), shots from the paper world, and every library effect free on top of it, plus the
    // added mass per shaft.
    let club = truth(vec![
        fx("loft_bias", &[0.4], None),
        fx("face_bias", &[-0.3], None),
        fx("friction", &[0.3], None),
    ]);
    let shots = shots(&paper_truth(), &Experiment::default());
    let mut requests: Vec<EffectRequest> = EffectKind::ALL
        .iter()
        .map(|&k| EffectRequest::Global(k.into()))
        .collect();
    requests.push(EffectRequest::PerGroup(EffectKind::AddedMass.into()));
    let sigma = [1.4, 0.9, 0.7, 420.0, 180.0];
    let inv = sigma.map(|s| 1.0 / s);
    let mut rng = ChaCha8Rng::seed_from_u64(10);
    // The shots in a random order, 133 of them: a full chunk of 128 and a last chunk of 5, so
    // groups are cut into runs of every length and the lane vectors have padded tails.
    let mut order: Vec<usize> = (0..shots.len()).collect();
    for i in (1..order.len()).rev() {
        order.swap(i, rng.random_range(0..=i));
    }
    let shots: Vec<_> = order[..133].iter().map(|&i| shots[i].clone()).collect();
    let plain = FitData::from_shots(&shots).unwrap();
    assert!(plain.groups.len() >= 2, "the test needs several groups");
    let noisy = plain
        .clone()
        .with_impact_noise(Some(ImpactNoise::from_mm(2.0, 2.5).unwrap()))
        .unwrap();
    let mut checked = 0;
    for data in [&plain, &noisy] {
        let layout = ParamLayout::from_requests(&requests, &data.groups).unwrap();
        let pr = FitProblem::new(&club, layout.clone(), data, Weighting::launch(&sigma));
        let (lo, hi) = (layout.lower(), layout.upper());
        // At the defaults (the cached frames apply) and at random points around them (every
        // effect on; loft and face biases moved, so frames are made afresh).
        for trial in 0..4 {
            let theta = if trial == 0 {
                layout.defaults()
            } else {
                let mut t = layout.defaults();
                for j in 0..t.len() {
                    let r = 0.04 * (hi[j] - lo[j]);
                    t[j] = (t[j] + rng.random_range(-r..r)).clamp(lo[j], hi[j]);
                }
                t
            };
            let Ok(got) = pr.residuals(theta.as_slice()) else {
                continue;
            };
            let want = reference_residuals(&pr, theta.as_slice(), &inv);
            close_residuals("residuals", got.as_slice(), &want, &pr, &inv);
            // A Jacobian over a few columns, among them a per-group one.
            let active: Vec<usize> = layout
                .labels()
                .iter()
                .enumerate()
                .filter(|(_, l)| {
                    [
                        "loft_bias",
                        "friction",
                        "ball_offset.dy",
                        "added_mass@B",
                        "cor_power",
                    ]
                    .iter()
                    .any(|p| l.starts_with(p))
                })
                .map(|(j, _)| j)
                .collect();
            assert!(active.len() >= 5, "{:?}", layout.labels());
            let sub = pr.clone().with_active(active, theta.clone());
            let jac = sub.jacobian_full(&theta).unwrap();
            let want_jac = reference_jacobian(&sub, &theta, &inv);
            close_jacobian(&jac, &want_jac);
            checked += 1;
        }
    }
    assert!(checked >= 6, "only {checked} points could be evaluated");
}
