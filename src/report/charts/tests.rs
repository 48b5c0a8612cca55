//! Tests of the charts (`super`).

use super::*;

#[test]
fn charts_are_svg_with_titles_and_legends() {
    let svg = grouped_bars_svg(
        "Ball speed",
        "error, mph",
        &["A".into(), "B".into()],
        &[
            BarSeries {
                label: "before".into(),
                colour: BLUE_C,
                values: vec![Some(Bar::of(-2.0, 1.0, 10)), Some(Bar::of(-1.5, 0.5, 10))],
            },
            BarSeries {
                label: "after".into(),
                colour: ORANGE_C,
                values: vec![Some(Bar::of(0.1, 1.0, 10)), None],
            },
        ],
    )
    .unwrap();
    assert!(svg.starts_with("<svg"), "{}", &svg[..50]);
    for t in [
        "Ball speed",
        "error, mph",
        "before",
        "after",
        "\nA\n</text>",
        "\nB\n</text>",
    ] {
        assert!(svg.contains(t), "missing {t}");
    }
    let pts: Vec<(f64, f64)> = (0..50).map(|i| (i as f64, 2.0 * i as f64 + 1.0)).collect();
    let (s, c) = fit_line(&pts).unwrap();
    assert!((s - 2.0).abs() < 1e-12 && (c - 1.0).abs() < 1e-9);
    let t = Trend {
        slope: s,
        intercept: c,
        label: "trend".into(),
    };
    let svg = scatter_trend_svg("t", "x, mph", "y, rpm", &pts, Some(&t), &[(1.0, 3.0)]).unwrap();
    assert!(svg.contains("x, mph") && svg.contains("trend") && svg.contains("<circle"));
    let svg = estimates_svg(
        "dm",
        "g",
        &[Estimate {
            label: "added_mass.dm_g".into(),
            value: 2.0,
            interval: Some((1.0, 3.0)),
            plausible: (0.0, 15.0),
        }],
    )
    .unwrap();
    assert!(svg.contains("plausible range") && svg.contains("added_mass.dm_g"));
    let svg = bars_with_line_svg(
        "g",
        "gain",
        &["a".into()],
        &[3.0],
        Some((&[2.0][..], "penalty")),
    )
    .unwrap();
    assert!(svg.contains("penalty"));
}

/// The ticks plotters places on an axis (up to ten labels, and twice as many) get labels that
/// differ from each other, and only a tick at zero reads as zero, on axes from 1e-9 to 1e9
/// wide, centred on zero or offset from it (the diagnose page's `cor_spot.c_per_mm2` axis,
/// 0.0001 to 0.0002, printed `0.0001 0.0001 0.0002 0.0002` before).
#[test]
fn tick_labels_are_distinct_and_zero_only_at_zero() {
    use plotters::coord::ranged1d::Ranged;
    use plotters::coord::types::RangedCoordf64;
    let mut axes = vec![
        (0.0001, 0.0002),
        (-3.2e-4, 1.1e-4),
        (12.0, 13.0),
        (0.0, 1.0),
    ];
    for e in -9..=9 {
        let w = 10f64.powi(e);
        for (a, b) in [(0.0, w), (-w, w), (w, 1.7 * w), (100.0 * w, 100.0 * w + w)] {
            axes.push((a, b));
        }
    }
    for (lo, hi) in axes {
        let label = super::tick_for(lo..hi);
        for n in [10usize, 20] {
            let points = RangedCoordf64::from(lo..hi).key_points(n);
            let labels: Vec<String> = points.iter().map(&label).collect();
            let mut distinct = labels.clone();
            distinct.sort();
            distinct.dedup();
            assert_eq!(distinct.len(), labels.len(), "{lo}..{hi}: {labels:?}");
            for (p, l) in points.iter().zip(&labels) {
                let zero = l.parse::<f64>().map(|v| v == 0.0).unwrap_or(false);
                assert_eq!(zero, p.abs() <= 1e-6 * (hi - lo), "{lo}..{hi}: {p} as {l}");
            }
        }
    }
}

/// Three significant figures never print a non-zero value as zero.
#[test]
fn sig3_keeps_small_values_off_zero() {
    use crate::compare::sig3;
    assert_eq!(sig3(2.5e-4), "2.50e-4");
    assert_eq!(sig3(-0.0004), "-4.00e-4");
    assert_eq!(sig3(-0.004), "-0.004");
    assert_eq!(sig3(0.0), "0");
    assert_eq!(sig3(0.25), "0.250");
    assert_eq!(sig3(41.26), "41.3");
    for e in -12..6 {
        let v = 1.234 * 10f64.powi(e);
        assert_ne!(sig3(v).parse::<f64>().unwrap(), 0.0, "{v}");
        assert_ne!(sig3(-v).parse::<f64>().unwrap(), 0.0, "{v}");
    }
}
