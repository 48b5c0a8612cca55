//! Unit tests of the noise floor.

use super::*;

#[test]
fn chi2_tail_is_a_half_near_the_mean_and_small_far_above() {
    let p = chi2_upper_tail(599.0, 599.0);
    assert!((p - 0.5).abs() < 0.02, "{p}");
    // 1.2² × ν is far in the tail for ν = 599.
    assert!(chi2_upper_tail(1.44 * 599.0, 599.0) < 1e-6);
    // Known value: χ²(10) upper 5 % point is 18.307.
    assert!((chi2_upper_tail(18.307, 10.0) - 0.05).abs() < 0.003);
}

#[test]
fn delivery_file_units_round_trip() {
    let x = [101.0, 2.0, -1.5, 12.0, 0.7, 1.0, 0.3, -0.4, 0.5, 3.0, -7.0];
    let back = delivery_to_file_units(&delivery_from_file_units(&x));
    for (a, b) in x.iter().zip(back) {
        assert!((a - b).abs() < 1e-9, "{a} vs {b}");
    }
}

/// The linearised expected variance agrees with sampling the delivery noise through the
/// full model (an independent check of the Jacobian propagation).
#[test]
fn linearised_variance_matches_sampling() {
    use rand::{Rng, SeedableRng};
    use rand_distr::StandardNormal;

    let club = ClubSpec::new(
        "paper".into(),
        None,
        crate::physics::ModelParams::paper_driver(),
        Vec::new(),
    )
    .unwrap();
    let inst = InstrumentClass::Radar.noise();
    let clean = [105.0, 1.0, 0.5, 12.0, 0.5, 0.0, 0.0, 0.0, 0.0, 4.0, -6.0];
    let shot = Shot {
        id: "s".into(),
        group: "all".into(),
        golfer: None,
        delivery: delivery_from_file_units(&clean),
        measured: None,
    };
    let v = expected_variances(&club, std::slice::from_ref(&shot), &inst, None).unwrap()[0];
    let model = club.model_for_group("all").unwrap();
    let f0 = model
        .solve(&shot.delivery)
        .unwrap()
        .launch()
        .to_file_units();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let n = 4000;
    let mut sum2 = [0.0; 5];
    for _ in 0..n {
        let x: [f64; N_DELIVERY] = std::array::from_fn(|j| {
            clean[j] + inst.delivery_sd[j] * rng.sample::<f64, _>(StandardNormal)
        });
        let f = model
            .solve(&delivery_from_file_units(&x))
            .unwrap()
            .launch()
            .to_file_units();
        for c in 0..5 {
            sum2[c] += (f[c] - f0[c]).powi(2);
        }
    }
    for c in 0..5 {
        let sampled = sum2[c] / n as f64 + inst.launch_sd[c].powi(2);
        let rel = (v[c] / sampled).sqrt();
        // Sampling error of an SD from 4000 draws is ~1.1 %; curvature adds a little.
        assert!(
            (0.93..1.07).contains(&rel),
            "component {c}: linearised/sampled SD {rel}"
        );
    }
}
