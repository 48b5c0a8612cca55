//! The module map in `src/lib.rs`'s doc comment names every module the library declares, so
//! that a newcomer reading it finds every room (issue 42).

#[test]
fn lib_map_names_every_module() {
    let lib = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/src/lib.rs"))
        .expect("src/lib.rs");
    let map: Vec<&str> = lib.lines().filter(|l| l.starts_with("//!")).collect();
    let declared: Vec<&str> = lib
        .lines()
        .filter_map(|l| l.strip_prefix("pub mod ")?.strip_suffix(';'))
        .collect();
    assert!(declared.len() > 20, "{declared:?}");
    let missing: Vec<&&str> = declared
        .iter()
        .filter(|m| {
            let link = format!("- [`{m}`]");
            !map.iter().any(|l| l.contains(&link))
        })
        .collect();
    assert!(missing.is_empty(), "src/lib.rs's map omits {missing:?}");
}
