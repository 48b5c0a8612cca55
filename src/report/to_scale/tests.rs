use super::*;

fn pattern<'a>(class: &'a str, points: &'a [(f64, f64, f64)], major_deg: f64) -> Pattern<'a> {
    Pattern {
        label: class,
        class,
        colour: BASE_COLOUR,
        points,
        ellipse: PatternEllipse {
            centre_offline_yd: 2.0,
            centre_carry_yd: 240.0,
            semi_major_yd: 12.0,
            semi_minor_yd: 5.0,
            major_from_carry_deg: major_deg,
        },
    }
}

/// The numbers of attribute `name` on the elements whose tag starts with `start`.
fn attrs(svg: &str, start: &str, name: &str) -> Vec<f64> {
    svg.match_indices(start)
        .map(|(i, _)| {
            let tag = &svg[i..i + svg[i..].find('>').unwrap()];
            let key = format!(" {name}=\"");
            let v = &tag[tag.find(&key).unwrap() + key.len()..];
            v[..v.find('"').unwrap()].parse().unwrap()
        })
        .collect()
}

#[test]
fn landing_patterns_draw_their_points_and_ellipses_to_one_scale() {
    let pts = [(0.0, 240.0, 0.5), (8.0, 250.0, 0.25), (-6.0, 232.0, 0.25)];
    let svg = landing_svg(
        "Landings",
        0.95,
        &[pattern("base", &pts, 20.0), pattern("changed", &pts, -90.0)],
    );
    assert_eq!(svg.matches("<ellipse class=\"ellipse ").count(), 2);
    let rx = attrs(&svg, "<ellipse class=\"ellipse", "rx");
    let ry = attrs(&svg, "<ellipse class=\"ellipse", "ry");
    // Semi-axes 12 and 5 yd at one scale: the radii keep their ratio.
    for (a, b) in rx.iter().zip(&ry) {
        assert!(
            *a > 0.0 && *b > 0.0 && ((a / b) - 12.0 / 5.0).abs() < 0.01,
            "{a} {b}"
        );
    }
    assert_eq!(svg.matches("<g class=\"landing base\"").count(), 1);
    // Every point of both patterns, and the legend's two swatches.
    assert_eq!(svg.matches("<circle cx=").count(), 2 * pts.len() + 2);
    assert!(svg.contains("offline, yd") && svg.contains("carry, yd"));
    assert!(svg.contains("rotate(-70.000") && svg.contains("rotate(-180.000"));
}

#[test]
fn bad_numbers_draw_nothing_not_a_number() {
    let pts = [(f64::NAN, f64::INFINITY, 1.0), (0.0, 200.0, f64::NAN)];
    let mut p = pattern("base", &pts, f64::NAN);
    p.ellipse.semi_major_yd = f64::INFINITY;
    let svg = landing_svg("Landings", f64::NAN, &[p]);
    assert!(!svg.contains("NaN") && !svg.contains("inf"), "{svg}");
    let h = HeadPoints {
        com_before_mm: [f64::NAN, 0.0, 0.0],
        com_after_mm: [0.0, f64::INFINITY, 0.0],
        hosel_mm: [-20.0, 25.0, -55.0],
        mass: None,
    };
    for v in [View::Above, View::Behind] {
        let svg = head_view_svg(&h, v);
        assert!(!svg.contains("NaN") && !svg.contains("inf"), "{svg}");
    }
}

#[test]
fn head_views_show_the_com_and_the_mass_before_and_after() {
    let h = HeadPoints {
        com_before_mm: [-42.3, 2.9, 1.0],
        com_after_mm: [-42.545, 2.9, 0.755],
        hosel_mm: [-20.0, 25.0, -55.0],
        mass: Some(MovedMass {
            mass_g: 5.0,
            from_mm: [-70.0, -10.0, 0.0],
            to_mm: [-80.0, -10.0, -10.0],
        }),
    };
    for v in [View::Above, View::Behind] {
        let svg = head_view_svg(&h, v);
        for class in ["com before", "com after", "mass from", "mass to"] {
            assert_eq!(
                svg.matches(&format!("<circle class=\"{class}\"")).count(),
                1,
                "{v:?}: {class}"
            );
        }
        // A quarter-millimetre shift is magnified, and says so.
        assert!(
            svg.contains("com-shift-magnified") && svg.contains("shift ×"),
            "{v:?}"
        );
        assert!(svg.contains("z, mm (toward the toe)"));
    }
    // To scale: from above the mass moves 10 mm back and 10 mm heelward, as far across as up.
    let svg = head_view_svg(&h, View::Above);
    let (cx, cy) = (
        attrs(&svg, "<circle class=\"mass", "cx"),
        attrs(&svg, "<circle class=\"mass", "cy"),
    );
    assert!(
        ((cx[1] - cx[0]) + (cy[1] - cy[0])).abs() < 0.02,
        "{cx:?} {cy:?}"
    );
    assert!(cx[1] < cx[0], "heelward is to the left");
}
