//! Ctrl-C (SIGINT) or SIGTERM in the middle of writing leaves no hidden temporary (issue 32,
//! item 12: 24–550 MB for `run`, 53–106 MB for `flight` stayed until the next run into the same
//! place) and no partial output; the process ends with the shell's status for the signal.

use crate::cli_support;

use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use cli_support::{repo, s, SMASH};

fn hidden_in(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect()
}

/// Wait until a name starting with `prefix` appears in `dir` (the command's temporary), then
/// send `signal`; returns the exit code. Panics if the command ends first.
fn signal_while_writing(mut child: Child, dir: &Path, prefix: &str, signal: &str) -> Option<i32> {
    let start = Instant::now();
    loop {
        if hidden_in(dir).iter().any(|n| n.starts_with(prefix)) {
            break;
        }
        if let Some(status) = child.try_wait().unwrap() {
            panic!("the command ended ({status}) before its temporary {prefix}* appeared");
        }
        assert!(start.elapsed() < Duration::from_secs(120), "no temporary");
        std::thread::sleep(Duration::from_millis(2));
    }
    let kill = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let out = child.wait_with_output().unwrap();
    assert!(
        !String::from_utf8_lossy(&out.stderr).contains("panicked"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.status.code()
}

#[test]
fn a_signal_during_a_study_removes_its_temporary_folder() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let study = d.join("big.toml");
    std::fs::write(
        &study,
        format!(
            "[study]\nname = \"big\"\nclub = {:?}\n\n[delivery]\nclub_speed_mph = 100.0\n\
             dynamic_loft_deg = 12.0\n\n[grid]\ny_mm = {{ from = -20.0, to = 20.0, count = 800 }}\n\
             z_mm = {{ from = -30.0, to = 30.0, count = 800 }}\n",
            s(&repo("configs/clubs/paper_driver.toml"))
        ),
    )
    .unwrap();
    for (signal, code) in [("-TERM", 143), ("-INT", 130)] {
        let out = d.join("out");
        let child = Command::new(SMASH)
            .args(["run", s(&study), "--out", s(&out)])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        assert_eq!(
            signal_while_writing(child, d, ".out.tmp-", signal),
            Some(code)
        );
        assert_eq!(hidden_in(d), Vec::<String>::new(), "after {signal}");
        assert!(!out.exists());
    }
}

#[test]
fn a_signal_during_a_flight_removes_its_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut text = String::from("shot_id,ball_speed_mph,launch_angle_deg,backspin_rpm\n");
    for i in 0..200_000 {
        text.push_str(&format!(
            "d{i},{},{},{}\n",
            120 + i % 50,
            8 + i % 12,
            2000 + i % 3000
        ));
    }
    let launch = d.join("launch.csv");
    std::fs::write(&launch, text).unwrap();
    let out = d.join("f.csv");
    let child = Command::new(SMASH)
        .args(["flight", "--shots", s(&launch), "--out", s(&out)])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    assert_eq!(
        signal_while_writing(child, d, ".f.csv.", "-TERM"),
        Some(143)
    );
    assert_eq!(hidden_in(d), Vec::<String>::new());
    assert!(!out.exists());
}
