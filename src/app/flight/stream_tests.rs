//! Tests of [`super`]: the streamed flight equals the one-piece flight, bad rows and all.

use super::*;

fn launch_file(n: usize, extra: &str) -> String {
    let mut t = String::from(
        "shot_id, ball_speed_mph,launch_angle_deg,azimuth_deg,backspin_rpm,sidespin_rpm,carry_yd\n",
    );
    for k in 0..n {
        let f = |a: f64| (k as f64 * a).fract();
        t.push_str(&format!(
            "s{k}, {} ,{},{},{},{},{}\n",
            150.0 + 30.0 * f(0.618),
            8.0 + 6.0 * f(0.755),
            -3.0 + 6.0 * f(0.57),
            2000.0 + 1200.0 * f(0.439),
            -600.0 + 1200.0 * f(0.352),
            if k % 7 == 0 {
                String::new()
            } else {
                format!("{}", 250 + k % 40)
            }
        ));
        if k % 500 == 0 {
            t.push('\n');
        }
    }
    t.push_str(extra);
    t
}

#[test]
fn streamed_output_equals_the_one_piece_output() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("l.csv");
    // No final newline, blank lines, padded cells, an empty measured cell.
    std::fs::write(&input, launch_file(3000, "last,160,11,0,2500,0,270")).unwrap();
    let cfg = FlightConfig {
        ground: Some(crate::flight::Ground::default()),
        ..FlightConfig::default()
    };
    let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
    let fa = fly_csv_file(&input, &a, &cfg, LaunchRead::default(), 10_000).unwrap();
    let fb = in_memory(&input, &b, &cfg, LaunchRead::default()).unwrap();
    assert_eq!(fa, fb);
    assert_eq!(fa.shots, 3001);
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    // One chunk or many: the same bytes.
    let c = dir.path().join("c.csv");
    fly_csv_file(&input, &c, &cfg, LaunchRead::default(), CHUNK_BYTES).unwrap();
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&c).unwrap());
}

#[test]
fn the_first_bad_row_is_reported_and_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o.csv");
    std::fs::write(&out, "keep me").unwrap();
    let cfg = FlightConfig::default();
    let text = launch_file(2000, "");
    let lines: Vec<&str> = text.lines().collect();
    // Line 1500 of the file gets a bad speed, line 1800 a short row: under --strict the
    // first is named; without, the short row refuses the file (its cells are not known).
    let mut bad = String::new();
    for (i, l) in lines.iter().enumerate() {
        let l = match i + 1 {
            1500 => "bad, abc ,10,0,2500,0,".to_string(),
            1800 => "x,1".to_string(),
            _ => l.to_string(),
        };
        bad.push_str(&l);
        bad.push('\n');
    }
    let input = dir.path().join("bad.csv");
    std::fs::write(&input, &bad).unwrap();
    let strict = LaunchRead {
        strict: true,
        ..LaunchRead::default()
    };
    let one = in_memory(&input, &out, &cfg, strict)
        .unwrap_err()
        .to_string();
    for chunk in [4096, CHUNK_BYTES] {
        let e = fly_csv_file(&input, &out, &cfg, strict, chunk)
            .unwrap_err()
            .to_string();
        assert!(e.contains("bad.csv:1500"), "{e}");
        assert!(
            one.contains("bad.csv:1500") || one.contains("bad.csv:1800"),
            "{one}"
        );
        let e = fly_csv_file(&input, &out, &cfg, LaunchRead::default(), chunk)
            .unwrap_err()
            .to_string();
        assert!(e.contains("bad.csv:1800"), "{e}");
    }
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "keep me");
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(left.len(), 2, "no temporary left");
}

#[test]
fn bad_rows_are_left_out_and_counted_the_same_streamed_or_not() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = FlightConfig::default();
    let text = launch_file(2000, "");
    let mut bad = String::new();
    let mut good = String::new();
    for (i, l) in text.lines().enumerate() {
        let row = match i + 1 {
            700 => Some("s_a, abc ,10,0,2500,0,"),
            1200 => Some("s_b,900,10,0,2500,0,250"),
            1500 => Some("s_c,150,95,0,2500,0,250"),
            1900 => Some("s_d,150,10,0,2500,0,9999"),
            _ => None,
        };
        bad.push_str(row.unwrap_or(l));
        bad.push('\n');
        if row.is_none() {
            good.push_str(l);
            good.push('\n');
        }
    }
    let (input, clean) = (dir.path().join("bad.csv"), dir.path().join("good.csv"));
    std::fs::write(&input, &bad).unwrap();
    std::fs::write(&clean, &good).unwrap();
    let read = LaunchRead::default();
    let want = dir.path().join("want.csv");
    fly_csv_file(&clean, &want, &cfg, read, CHUNK_BYTES).unwrap();
    for chunk in [4096, CHUNK_BYTES] {
        let o = dir.path().join(format!("o{chunk}.csv"));
        let flown = fly_csv_file(&input, &o, &cfg, read, chunk).unwrap();
        assert_eq!(flown.shots, 1996);
        let lines: Vec<Vec<usize>> = flown.left_out.iter().map(|l| l.lines.clone()).collect();
        assert_eq!(
            lines,
            [[700], [1200], [1500], [1900]],
            "{:?}",
            flown.notes()
        );
        assert_eq!(std::fs::read(&o).unwrap(), std::fs::read(&want).unwrap());
    }
    let m = dir.path().join("m.csv");
    let flown = in_memory(&input, &m, &cfg, read).unwrap();
    assert_eq!(flown.shots, 1996);
    assert_eq!(std::fs::read(&m).unwrap(), std::fs::read(&want).unwrap());
}

#[test]
fn quoted_files_take_the_one_piece_path() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("q.csv");
    let mut text = launch_file(200, "");
    text.push_str("\"a, quoted\",150,10,0,2500,0,\n");
    std::fs::write(&input, &text).unwrap();
    let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
    let cfg = FlightConfig::default();
    fly_csv_file(&input, &a, &cfg, LaunchRead::default(), 1000).unwrap();
    in_memory(&input, &b, &cfg, LaunchRead::default()).unwrap();
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    assert!(std::fs::read_to_string(&a)
        .unwrap()
        .contains("\"a, quoted\""));
}
