//! A sixth hostile pass (29 Nov 2026): hand-made files read differently from imported ones: a
//! column name in another case dropped without a word, a 0 that means "not measured" used as a
//! measurement, and `1.0` not read as a flag.

use crate::cli_support;

use cli_support::{club, measured_shots, s, smash, unwrapped as stderr, write};

/// A copy of `path` with column `from` of its header renamed `to`.
fn renamed(path: &std::path::Path, from: &str, to: &str) -> std::path::PathBuf {
    let text = std::fs::read_to_string(path).unwrap();
    let (head, rest) = text.split_once('\n').unwrap();
    let head: Vec<&str> = head
        .split(',')
        .map(|h| if h == from { to } else { h })
        .collect();
    let out = path.with_file_name(format!("renamed_{to}.csv"));
    std::fs::write(&out, format!("{}\n{rest}", head.join(","))).unwrap();
    out
}

/// `Group`, `Carry_yd` or `Flight_Modelled` would be carried through unread (the shots in one
/// group, no carry compared, modelled flights taken as tracked): each is refused on line 1,
/// naming the column to write, in the commands that read shots and in `flight`.
#[test]
fn a_known_column_in_another_case_is_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let shots = measured_shots(dir.path());
    let text = std::fs::read_to_string(&shots).unwrap();
    let mut grouped = String::new();
    for (i, l) in text.lines().enumerate() {
        let g = match i {
            0 => "Group",
            _ if i % 2 == 0 => "A",
            _ => "B",
        };
        grouped.push_str(&format!("{g},{l}\n"));
    }
    let g = write(dir.path(), "g.csv", &grouped);
    let c = club();
    for cmd in ["compare", "predict"] {
        let out = dir.path().join("p.csv");
        let mut args = vec![cmd, "--club", &c, "--shots", s(&g)];
        if cmd == "predict" {
            args.extend(["--out", s(&out)]);
        }
        let o = smash(&args);
        let e = stderr(&o);
        assert!(!o.status.success(), "{cmd}: {e}");
        assert!(
            e.contains("g.csv:1: column 'Group': is smash's 'group' written in another case")
                && e.contains("rename it 'group'"),
            "{cmd}: {e}"
        );
    }
    let flights = write(
        dir.path(),
        "f.csv",
        "shot_id,group,ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,sidespin_rpm,\
         Carry_yd,Flight_Modelled\na,7i,110,18,0,6000,0,160,1\nb,7i,112,17,1,6200,100,158,1\n",
    );
    let out = dir.path().join("o.csv");
    let o = smash(&["flight", "--shots", s(&flights), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(!o.status.success(), "{e}");
    assert!(
        e.contains("column 'Carry_yd'") && e.contains("rename it 'carry_yd'"),
        "{e}"
    );
    assert!(!out.exists());
    // Renamed as asked, the file flies and compares.
    let fixed = renamed(
        &renamed(&flights, "Carry_yd", "carry_yd"),
        "Flight_Modelled",
        "flight_modelled",
    );
    let o = smash(&["flight", "--shots", s(&fixed), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(e.contains("carry error"), "{e}");
}

/// A measured carry (apex, landing) of 0 is a monitor's "not tracked", as `smash import` reads
/// it: not compared (its error cell empty, the yd and % columns over the same shots), and said.
#[test]
fn a_zero_carry_is_not_compared_and_is_said() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(
        dir.path(),
        "f.csv",
        "shot_id,group,ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,sidespin_rpm,\
         carry_yd,offline_yd\na,7i,110,18,0,6000,0,160,0\nb,7i,112,17,1,6200,100,0,3\n",
    );
    let out = dir.path().join("o.csv");
    let o = smash(&["flight", "--shots", s(&f), "--out", s(&out), "--json"]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    let rows = cli_support::csv_rows(&out);
    assert!(!rows[0]["err_carry_yd"].is_empty(), "{rows:?}");
    assert_eq!(rows[1]["err_carry_yd"], "", "{rows:?}");
    // An offline of 0 is a straight shot: compared.
    assert!(!rows[0]["err_offline_yd"].is_empty(), "{rows:?}");
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let all = j["errors"]["rows"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["group"] == "all")
        .unwrap();
    let carry = all["errors"]
        .as_array()
        .unwrap()
        .iter()
        .find(|q| q[0] == "carry_yd")
        .unwrap();
    assert_eq!(carry[1]["n"], 1, "{all}");
    let warnings = j["warnings"].to_string();
    assert!(
        warnings.contains("1 shot(s) have a carry_yd of 0, read as not measured"),
        "{warnings}"
    );
}

/// Back and side spin both 0 is a monitor that lost the spin: the shot is left out of the
/// comparison and counted, as `smash import` leaves it out, not compared as a spinless ball.
#[test]
fn a_lost_spin_is_left_out_and_counted() {
    let dir = tempfile::tempdir().unwrap();
    let shots = measured_shots(dir.path());
    let text = std::fs::read_to_string(&shots).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let head: Vec<&str> = lines[0].split(',').collect();
    let (b, sd) = (
        head.iter().position(|h| *h == "backspin_rpm").unwrap(),
        head.iter().position(|h| *h == "sidespin_rpm").unwrap(),
    );
    let mut cells: Vec<String> = lines[3].split(',').map(str::to_owned).collect();
    cells[b] = "0".into();
    cells[sd] = "0".into();
    lines[3] = cells.join(",");
    let f = write(dir.path(), "z.csv", &(lines.join("\n") + "\n"));
    let o = smash(&["compare", "--club", &club(), "--shots", s(&f)]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("left out 1 of 40 rows: back and side spin both 0 (a monitor that lost the spin writes zeros)"),
        "{e}"
    );
    assert!(
        String::from_utf8_lossy(&o.stdout).contains("39 shots"),
        "{e}"
    );
    let o = smash(&["compare", "--club", &club(), "--shots", s(&f), "--strict"]);
    let e = stderr(&o);
    assert!(!o.status.success(), "{e}");
    assert!(
        e.contains("z.csv:4")
            && e.contains("backspin_rpm")
            && e.contains("back and side spin both 0"),
        "{e}"
    );
}

/// A flag written `1.0`/`0.0` (pandas writes a 0/1 column with gaps so) is a flag.
#[test]
fn a_flag_written_as_a_decimal_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(
        dir.path(),
        "f.csv",
        "shot_id,group,ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,sidespin_rpm,\
         carry_yd,flight_modelled\na,7i,110,18,0,6000,0,160,1.0\nb,7i,112,17,1,6200,100,158,0.0\n",
    );
    let out = dir.path().join("o.csv");
    let o = smash(&["flight", "--shots", s(&f), "--out", s(&out)]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("1 of the 2 shots compared have the vendor's flight model"),
        "{e}"
    );
    assert!(!e.contains("not a flag"), "{e}");
}

/// `infer-club` names a parameter held at a physical bound as such in its "determined" list
/// (60 shots of the paper world hold `cor_radial` at 0): the data push it against the bound.
#[test]
fn infer_club_says_a_determined_parameter_sits_at_its_bound() {
    let dir = tempfile::tempdir().unwrap();
    let world = cli_support::synth_world(dir.path(), "paper_world", 1);
    let text = std::fs::read_to_string(&world).unwrap();
    let first: Vec<&str> = text.lines().take(61).collect();
    let shots = write(dir.path(), "s60.csv", &(first.join("\n") + "\n"));
    let out = dir.path().join("h.toml");
    let o = smash(&[
        "infer-club",
        "--shots",
        s(&shots),
        "--start",
        &club(),
        "--out-club",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let e = String::from_utf8(o.stdout).unwrap();
    let at_bound: Vec<&str> = e
        .lines()
        .filter(|l| l.ends_with("(at a physical bound)") && !l.starts_with(' '))
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    assert!(!at_bound.is_empty(), "{e}");
    let after = e.split("At the estimate:").nth(1).unwrap();
    let determined = after
        .split("not determined:")
        .next()
        .unwrap()
        .replace('\n', " ");
    for p in at_bound {
        assert!(
            !determined.contains(&format!("{p},")) && !determined.trim_end().ends_with(p),
            "{p} listed as determined without its bound: {determined}"
        );
    }
}
