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

/// A SkyTrak export's header and one shot row (`id` first).
const SKYTRAK_HEAD: &str = "Shot,Club,Ball Speed,Launch Angle,Side Angle,Back Spin,Side Spin,\
Total Spin,Spin Axis,Carry,Roll,Total,Offline,Descent Angle,Peak Height,Club Speed\n";

fn skytrak_row(id: usize, ball_speed: &str, back: &str, side: &str) -> String {
    format!(
        "{id},7 Iron,{ball_speed},18.1,R1.0,{back},{side},5786,R0.7,169.4,6.0,175.4,R3.5,47.3,\
         31.9,87.8\n"
    )
}

#[test]
fn rows_the_import_leaves_out_by_its_rules_are_no_sign_of_a_wrong_format() {
    let dir = tempfile::tempdir().unwrap();
    let import = |name: &str, rows: &[String]| {
        let file = write(
            dir.path(),
            name,
            &(SKYTRAK_HEAD.to_owned() + &rows.concat()),
        );
        let out = dir.path().join(format!("{name}.shots.csv"));
        let o = smash(&["import", "--format", "skytrak", s(&file), "--out", s(&out)]);
        (o.status.success(), stderr(&o), out)
    };
    let good = [
        skytrak_row(1, "122.1", "5785", "R68"),
        skytrak_row(2, "122.1", "5785", "R68"),
    ];
    // Two shots and three formula rows (an average row and its like).
    let formula: Vec<String> = (3..=5)
        .map(|i| skytrak_row(i, if i == 5 { "#N/A" } else { "#DIV/0!" }, "5983", "R457"))
        .collect();
    // Two shots and three rows whose monitor lost the spin.
    let lost: Vec<String> = (3..=5).map(|i| skytrak_row(i, "122.1", "0", "0")).collect();
    for (name, extra, why) in [
        (
            "div.csv",
            &formula,
            "a cell holds a spreadsheet's error value",
        ),
        ("spin0.csv", &lost, "back and side spin both exactly 0"),
    ] {
        let rows: Vec<String> = good.iter().chain(extra.iter()).cloned().collect();
        let (ok, e, out) = import(name, &rows);
        assert!(ok, "{name}: {e}");
        assert!(
            e.contains("left out 3 row(s)") && e.contains(why),
            "{name}: {e}"
        );
        assert!(!e.contains("--format"), "{name}: {e}");
        assert_eq!(cli_support::csv_rows(&out).len(), 2, "{name}");
        // Only such rows: refused, saying what they were, not sending to another --format.
        let (ok, e, out) = import(&format!("only_{name}"), extra);
        assert!(!ok, "{name}: {e}");
        assert_eq!(e.trim_end().lines().count(), 1, "{name}: {e}");
        assert!(
            e.contains(
                "no shots: all 3 rows of the SkyTrak export are left out by the import's rules"
            ) && e.contains(why),
            "{name}: {e}"
        );
        assert!(!e.contains("--format"), "{name}: {e}");
        assert!(!out.exists());
    }
}

/// `smash whatif` on the paper driver with `change` (flag and value pairs): success and
/// stderr.
fn whatif(change: &[&str]) -> (bool, String) {
    let club = cli_support::repo("configs/clubs/paper_driver.toml");
    let mut args = vec!["whatif", "--club", s(&club), "--speed", "95"];
    args.extend(change);
    let o = smash(&args);
    (o.status.success(), stderr(&o))
}

#[test]
fn whatif_refusals_name_the_flag_that_gave_the_value() {
    for (change, starts, says) in [
        (
            ["--bulge-mm", "0"],
            "error: --bulge-mm 0: face radius 0 is outside the physical range [20, 1000000] mm",
            "",
        ),
        (
            ["--roll-mm", "1e9"],
            "error: --roll-mm 1e9: face radius",
            "",
        ),
        (
            ["--loft-change-deg", "80"],
            "error: --loft-change-deg 80: the changed head's dynamic loft 93 is outside",
            "with a base dynamic loft of 13 deg the loft change must be within [-103, 77] deg",
        ),
    ] {
        let (ok, e) = whatif(&change);
        assert!(!ok, "{change:?}: {e}");
        assert_eq!(e.trim_end().lines().count(), 1, "{e}");
        assert!(e.starts_with(starts), "{change:?}: {e}");
        assert!(e.contains(says), "{change:?}: {e}");
        assert!(
            !e.contains("paper_driver.toml") && !e.contains("club."),
            "{e}"
        );
    }
}

#[test]
fn a_mass_moved_from_outside_the_head_is_named_as_such() {
    for (mv, says) in [
        // 50 g 208 mm behind the CoM: its own moment would exceed the head's.
        (
            "50g:-250,0,0:-80,0,0",
            "the FROM point (-250, 0, 0) mm is 207.7 mm from the head's centre of mass",
        ),
        (
            "5g:-700,-10,0:-80,-10,-10",
            "the FROM point (-700, -10, 0) mm lies outside any clubhead",
        ),
        (
            "5g:-70,-10,0:-70,0,600",
            "the TO point (-70, 0, 600) mm lies outside any clubhead",
        ),
        (
            "5g:10,0,0:-80,0,0",
            "the FROM point (10, 0, 0) mm is at or in front of the face",
        ),
    ] {
        let (ok, e) = whatif(&["--move-mass", mv]);
        assert!(!ok, "{mv}: {e}");
        assert_eq!(e.trim_end().lines().count(), 1, "{e}");
        assert!(e.starts_with(&format!("error: --move-mass {mv}: ")), "{e}");
        assert!(e.contains(says), "{mv}: {e}");
        assert!(!e.contains("positive definite"), "{mv}: {e}");
    }
}

#[test]
fn a_head_has_at_least_the_moment_its_mass_allows() {
    let (ok, e) = whatif(&["--moi-scale", "1e-9"]);
    assert!(!ok, "{e}");
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(
        e.starts_with("error: --moi-scale 1e-9: the changed head's principal moment")
            && e.contains("below the least a 204 g head can have, 11.2 g·cm²")
            && e.contains("the scale must be within [0.00449, 176]"),
        "{e}"
    );
    // A value computed by the program is stated to a sensible number of digits.
    let (ok, e) = whatif(&["--moi-scale", "1e6"]);
    assert!(!ok, "{e}");
    assert!(e.contains("club inertia entry 2.843e9 is outside"), "{e}");
    // A club file with such a tensor is refused at its key.
    let dir = tempfile::tempdir().unwrap();
    let text =
        std::fs::read_to_string(cli_support::repo("configs/clubs/paper_driver.toml")).unwrap();
    let at = text.find("inertia_gcm2").unwrap();
    let end = at + text[at..].find('\n').unwrap();
    let tiny = format!(
        "{}inertia_gcm2 = [[0.001, 0, 0], [0, 0.001, 0], [0, 0, 0.001]]{}",
        &text[..at],
        &text[end..]
    );
    let club = write(dir.path(), "tiny.toml", &tiny);
    let o = smash(&[
        "predict",
        "--club",
        s(&club),
        "--speed",
        "100",
        "--loft",
        "12",
    ]);
    let e = stderr(&o);
    assert!(!o.status.success(), "{e}");
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(
        e.contains("club.inertia_gcm2")
            && e.contains("principal moment 0.001 g·cm² is below the least a 204 g head can have"),
        "{e}"
    );
}
