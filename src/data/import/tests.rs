//! Tests of the mapping files' checks (`super`).
use super::*;

/// A mapping's conventions: each value allowed for its target, one point per quantity.
#[test]
fn conventions_are_checked() {
    let map = |cols: &str| {
        parse_mapping(
            Path::new("m.toml"),
            &format!("[export]\nname = \"M\"\n{cols}"),
        )
    };
    let col = |t: &str, extra: &str| {
        format!("[[column]]\ntarget = \"{t}\"\nsource = [\"{t}\"]\n{extra}\n")
    };
    let err = |cols: String| map(&cols).unwrap_err().to_string();
    let e = err(col("dynamic_loft_deg", "at = \"geometric_centre\""));
    assert!(e.contains("allowed: face_centre, contact_point"), "{e}");
    let e = err(col("club_speed_mph", "at = \"contact_point\""));
    assert!(
        e.contains("allowed: com, geometric_centre, face_centre"),
        "{e}"
    );
    let e = err(col("ball_speed_mph", "at = \"com\""));
    assert!(e.contains("`at` is for the delivery"), "{e}");
    let e = err(col("dynamic_loft_deg", "how = \"derived_from_launch\""));
    assert!(
        e.contains("only face_angle_deg may be derived_from_launch"),
        "{e}"
    );
    let e = err(col("dynamic_loft_deg", "at = \"contact_point\"")
        + &col("face_angle_deg", "at = \"face_centre\""));
    assert!(e.contains("must state the same point"), "{e}");
    let ok = col("dynamic_loft_deg", "at = \"contact_point\"")
        + &col(
            "face_angle_deg",
            "at = \"contact_point\"\nhow = \"derived_from_launch\"",
        );
    assert!(map(&ok).is_ok());
}

#[test]
fn presets_parse() {
    for (name, _) in PRESETS {
        load_mapping(name).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    assert!(load_mapping("gcquad").is_ok());
    // Every preset records, per delivery column, where and how the vendor defines it.
    for (name, _) in PRESETS {
        let m = load_mapping(name).unwrap();
        for c in m.column.iter().filter(|c| {
            crate::model::DeliveryVar::from_column(&c.target).is_some_and(|v| {
                !matches!(
                    v,
                    crate::model::DeliveryVar::ImpactY | crate::model::DeliveryVar::ImpactZ
                ) && v.required()
            })
        }) {
            assert!(c.at.is_some() && c.how.is_some(), "{name}: {}", c.target);
        }
    }
    let e = load_mapping("nosuch").unwrap_err().to_string();
    assert!(e.contains("unknown format"), "{e}");
}
