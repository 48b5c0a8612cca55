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
