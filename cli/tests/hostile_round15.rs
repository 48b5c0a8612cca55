//! The fifteenth hostile pass: rows the import leaves out by its own documented rules counted
//! as signs of a wrong `--format`, flights cut off by the user's own `--max-time-s` blamed on
//! the file, refusals giving the other side's reason, and `whatif`'s flag values named as
//! club-file keys.

use crate::cli_support;

use cli_support::{s, smash, unwrapped as stderr, write};

/// One launch row that flies within any step (`--dt-s` is what is wrong).
const LAUNCH: &str = "shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\nd1,150,10,2500\n";

#[test]
fn each_side_of_the_dt_range_gives_its_own_reason() {
    let dir = tempfile::tempdir().unwrap();
    let shots = write(dir.path(), "l.csv", LAUNCH);
    let out = dir.path().join("o.csv");
    let run = |dt: &str| {
        let o = smash(&[
            "flight",
            "--shots",
            s(&shots),
            "--out",
            s(&out),
            "--dt-s",
            dt,
        ]);
        assert!(!o.status.success());
        let e = stderr(&o);
        assert_eq!(e.trim_end().lines().count(), 1, "{e}");
        e
    };
    let big = run("5");
    assert!(
        big.contains("--dt-s 5: must be within [0.0001, 0.5] s (a longer step loses accuracy"),
        "{big}"
    );
    assert!(!big.contains("smaller step"), "{big}");
    let small = run("1e-9");
    assert!(
        small.contains("a smaller step only adds rounding"),
        "{small}"
    );
    assert!(!small.contains("longer step"), "{small}");
    assert!(!out.exists());
}
