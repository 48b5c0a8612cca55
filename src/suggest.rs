//! Suggestions for a name typed wrong: the nearest allowed one, shared by every message that
//! refuses a name (TOML keys, effect names).

/// The candidate nearest to `given`, when it is near enough to be a typing slip: a
/// Jaro–Winkler similarity of at least 0.8 (the threshold cargo and clap use for their
/// suggestions).
pub fn did_you_mean<'c>(given: &str, candidates: impl Iterator<Item = &'c str>) -> Option<&'c str> {
    candidates
        .map(|c| (strsim::jaro_winkler(given, c), c))
        .filter(|(s, _)| *s >= 0.8)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, c)| c)
}
