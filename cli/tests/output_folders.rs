//! Output folders are written as a unit: a re-run leaves exactly the new outputs (no stale
//! files), a folder holding anything else is never overwritten, and merge refuses to write into
//! one of its shards.

use crate::cli_support;

use std::path::Path;

use cli_support::smash;

fn files_under(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_owned()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.push(p.strip_prefix(dir).unwrap().display().to_string());
            }
        }
    }
    out.sort();
    out
}

#[test]
fn rerunning_a_study_leaves_no_stale_files_and_foreign_folders_are_kept() {
    let tmp = tempfile::tempdir().unwrap();
    let repo = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    let club = repo.join("configs/clubs/paper_driver.toml");
    let study = |outputs: &str| {
        format!(
            "[study]\nname = \"t\"\nclub = {:?}\noutputs = [{outputs}]\n\n[delivery]\nclub_speed_mph = 100.0\n\
             dynamic_loft_deg = 12.0\n\n[grid]\ny_mm = {{ from = -10.0, to = 10.0, count = 5 }}\n\
             z_mm = {{ from = -10.0, to = 10.0, count = 5 }}\n",
            club.to_str().unwrap()
        )
    };
    let s1 = tmp.path().join("s1.toml");
    std::fs::write(&s1, study("\"ball_speed_mph\", \"backspin_rpm\"")).unwrap();
    let s2 = tmp.path().join("s2.toml");
    std::fs::write(&s2, study("\"ball_speed_mph\"")).unwrap();
    let out = tmp.path().join("out");
    let o = smash(&["run", s1.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let first = files_under(&out);
    assert!(first.iter().any(|f| f.contains("backspin")));
    let o = smash(&["run", s2.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let second = files_under(&out);
    assert!(
        !second.iter().any(|f| f.contains("backspin")),
        "stale files: {second:?}"
    );
    assert!(second.len() < first.len());

    // A folder with someone else's files is not replaced.
    let foreign = tmp.path().join("mine");
    std::fs::create_dir_all(&foreign).unwrap();
    std::fs::write(foreign.join("thesis.tex"), "precious").unwrap();
    let o = smash(&[
        "run",
        s2.to_str().unwrap(),
        "--out",
        foreign.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("choose a new or empty folder"));
    assert_eq!(files_under(&foreign), vec!["thesis.tex".to_string()]);

    // Merge into one of its own shards is refused.
    let sh0 = tmp.path().join("sh0");
    let sh1 = tmp.path().join("sh1");
    for (k, d) in [("0/2", &sh0), ("1/2", &sh1)] {
        let o = smash(&[
            "run",
            s2.to_str().unwrap(),
            "--shard",
            k,
            "--out",
            d.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let o = smash(&[
        "merge",
        sh0.to_str().unwrap(),
        sh1.to_str().unwrap(),
        "--out",
        sh0.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("one of the shard folders"));
}
