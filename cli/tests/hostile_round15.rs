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

/// Launches of which two fly longer than 4 s (110 mph at 18° with 6000 rpm, 160 mph at 12°)
/// and two land within it (60 mph wedges).
const FOUR_SECONDS: &str = "shot_id,ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,\
sidespin_rpm\na,110,18,0,6000,0\nb,160,12,0,2500,0\nc,60,30,0,8000,0\nd,60,20,0,8000,0\n";

#[test]
fn flights_cut_off_by_the_users_max_time_are_not_blamed_on_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o.csv");
    let fly = |name: &str, text: &str| {
        let shots = write(dir.path(), name, text);
        let o = smash(&[
            "flight",
            "--shots",
            s(&shots),
            "--out",
            s(&out),
            "--max-time-s",
            "4",
        ]);
        (o.status.success(), stderr(&o))
    };
    // Two of four cut off: the note names the flag, not a time limit of the file's.
    let (ok, e) = fly("four.csv", FOUR_SECONDS);
    assert!(ok, "{e}");
    assert!(
        e.contains("left out 2 of 4 rows: not landed within the --max-time-s given")
            && e.contains("4 s: raise --max-time-s to fly it"),
        "{e}"
    );
    // Two of three cut off: not "more than half bad", the run goes on.
    let three: String = FOUR_SECONDS
        .lines()
        .take(4)
        .map(|l| format!("{l}\n"))
        .collect();
    let (ok, e) = fly("three.csv", &three);
    assert!(ok, "{e}");
    assert!(
        !e.contains("--format") && !e.contains("fix the file"),
        "{e}"
    );
    // All cut off: refused, naming the flag, not the file's format.
    let two: String = FOUR_SECONDS
        .lines()
        .take(3)
        .map(|l| format!("{l}\n"))
        .collect();
    let (ok, e) = fly("two.csv", &two);
    assert!(!ok, "{e}");
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(
        e.contains("2 of 2 rows have not landed within the --max-time-s given")
            && e.contains("raise --max-time-s"),
        "{e}"
    );
    assert!(
        !e.contains("--format") && !e.contains("fix the file"),
        "{e}"
    );
}
