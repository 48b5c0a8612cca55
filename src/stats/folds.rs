//! Deterministic fold assignment for cross-validation, grouped by a key (the golfer) or not.

/// Fold of each item for k-fold cross-validation where items sharing a key (a golfer) always
/// fall in the same fold. Distinct keys are sorted and dealt round-robin, so the assignment is
/// deterministic and the folds hold as equal a number of keys as possible.
///
/// Returns one fold index in `0..k` per item. `k` is capped at the number of distinct keys.
pub fn grouped_folds<S: AsRef<str>>(keys: &[S], k: usize) -> Vec<usize> {
    let mut distinct: Vec<&str> = keys.iter().map(AsRef::as_ref).collect();
    distinct.sort_unstable();
    distinct.dedup();
    let k = k.clamp(1, distinct.len().max(1));
    keys.iter()
        .map(|key| {
            let pos = distinct
                .binary_search(&key.as_ref())
                .expect("key is in the list");
            pos % k
        })
        .collect()
}

/// What per-shot keys of [`FoldKeys`] stand for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KeyKind {
    /// A session: the shots of one date.
    Session,
    /// A block of consecutive shots of one session, by time of day.
    TimeBlock,
    /// The club named in the shots' group.
    Club,
}

/// Keys that group shots into folds when there are no golfers: one key per shot, with what they
/// are and the column they come from.
#[derive(Debug, Clone, PartialEq)]
pub struct FoldKeys {
    /// What the keys stand for.
    pub kind: KeyKind,
    /// The input column they were read from.
    pub column: String,
    /// One key per shot, in shot order.
    pub keys: Vec<String>,
}

/// Shot-level fold assignment (no grouping): item `i` goes to fold `i mod k`.
pub fn item_folds(n: usize, k: usize) -> Vec<usize> {
    let k = k.clamp(1, n.max(1));
    (0..n).map(|i| i % k).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grouped_folds_keep_keys_together() {
        let keys: Vec<String> = (0..60).map(|i| format!("g{:02}", i % 20)).collect();
        let folds = grouped_folds(&keys, 5);
        for (i, a) in keys.iter().enumerate() {
            for (j, b) in keys.iter().enumerate() {
                if a == b {
                    assert_eq!(folds[i], folds[j]);
                }
            }
        }
        let mut counts = [0; 5];
        for f in &folds {
            counts[*f] += 1;
        }
        assert_eq!(counts, [12; 5]);
        // Deterministic.
        assert_eq!(folds, grouped_folds(&keys, 5));
        // More folds than keys: capped.
        assert!(grouped_folds(&["a", "b"], 5).iter().all(|&f| f < 2));
        assert_eq!(item_folds(7, 3), vec![0, 1, 2, 0, 1, 2, 0]);
    }
}
