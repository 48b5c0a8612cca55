//! Sessions, time blocks and clubs of a shots file: what cross-validation folds are grouped by
//! when the shots name no golfer.
//!
//! Shots of one session share a day's swing, warm-up, ball and conditions; folds that put some
//! in training and the others in the test would reward an effect that fits that day. So,
//! without golfers, the folds hold whole sessions (the date of a `date`, `datetime` or
//! `timestamp` column), or, in a single session, blocks of consecutive shots (by the time of
//! day of such a column or a `time` column), or the clubs named in `group`; by shot only when
//! none of these exists.

use super::shots::ShotTable;
use super::DataError;
use crate::club_match::ClubKind;
use crate::stats::{FoldKeys, KeyKind};

/// Column names (compared without case) that carry a date, a time or both: a shots file's own,
/// and those a launch-monitor export writes (`Date` in TrackMan's and Garmin's exports, which
/// hold the date and time of day in one cell).
const TIME_COLUMNS: [&str; 6] = [
    "date",
    "datetime",
    "date_time",
    "timestamp",
    "time",
    "session",
];

/// A cell's date and time of day: `2026-05-06 19:03:21`, `2026-05-06T19:03:21`,
/// `5/6/2026 7:03:21 PM`, `19:03`, or a date alone.
fn split_date_time(cell: &str) -> (Option<&str>, Option<&str>) {
    let cell = cell.trim();
    if cell.is_empty() {
        return (None, None);
    }
    let (date, time) = match cell.split_once([' ', 'T']) {
        Some((d, t)) => (d, Some(t.trim())),
        None if cell.contains(':') => return (None, Some(cell)),
        None => (cell, None),
    };
    (Some(date), time)
}

use super::datetime::seconds_of_day;

/// The keys to group `table`'s folds by when it names no golfer, for `folds` folds: sessions
/// (two or more dates), else time blocks (`folds` runs of consecutive shots of equal size by
/// time of day), else the clubs named in `group` (two or more), else `None` (by shot). A time
/// column whose cells are not all times of day is refused, naming the first such cell: folds
/// by shot would mix a session's shots, which the column is there to prevent.
pub fn fold_keys(table: &ShotTable, folds: usize) -> Result<Option<FoldKeys>, DataError> {
    let col = table
        .headers
        .iter()
        .position(|h| TIME_COLUMNS.iter().any(|c| h.eq_ignore_ascii_case(c)));
    if let Some(i) = col {
        let column = table.headers[i].clone();
        // One day written two ways (`5/1/2026`, `2026-05-01`) is one session; an Excel serial
        // (`46143.79`) is a day and a time, not a session of its own.
        let raw: Vec<&str> = table
            .records
            .iter()
            .map(|r| r.get(i).map_or("", String::as_str))
            .collect();
        let day_first = super::datetime::day_first(raw.iter().copied());
        let normal: Vec<String> = raw
            .iter()
            .map(|c| {
                super::datetime::parse(c, day_first).map_or_else(|| (*c).to_owned(), |d| d.format())
            })
            .collect();
        let cells: Vec<(Option<&str>, Option<&str>)> =
            normal.iter().map(|c| split_date_time(c)).collect();
        let mut dates: Vec<&str> = cells.iter().filter_map(|c| c.0).collect();
        dates.sort_unstable();
        dates.dedup();
        if dates.len() >= 2 && cells.iter().all(|c| c.0.is_some()) {
            let keys = cells.iter().map(|c| c.0.unwrap_or("").to_owned()).collect();
            return Ok(Some(FoldKeys {
                kind: KeyKind::Session,
                column,
                keys,
            }));
        }
        if cells.iter().any(|c| c.1.is_some()) {
            return time_blocks(table, i, &cells, folds).map(Some);
        }
    }
    let clubs: Vec<Option<ClubKind>> = table
        .shots
        .iter()
        .map(|s| ClubKind::parse(&s.group))
        .collect();
    let mut distinct: Vec<ClubKind> = clubs.iter().flatten().copied().collect();
    distinct.sort_unstable();
    distinct.dedup();
    if distinct.len() >= 2 && clubs.iter().all(Option::is_some) {
        return Ok(Some(FoldKeys {
            kind: KeyKind::Club,
            column: "group".into(),
            keys: table.shots.iter().map(|s| s.group.clone()).collect(),
        }));
    }
    Ok(None)
}

/// `folds` blocks of consecutive shots by time of day (ties kept in file order).
fn time_blocks(
    table: &ShotTable,
    col: usize,
    cells: &[(Option<&str>, Option<&str>)],
    folds: usize,
) -> Result<FoldKeys, DataError> {
    let mut secs = Vec::with_capacity(cells.len());
    for (n, c) in cells.iter().enumerate() {
        match c.1.and_then(seconds_of_day) {
            Some(s) => secs.push(s),
            None => {
                return Err(DataError::at(
                    &table.path,
                    table.lines.get(n).copied(),
                    Some(format!("column '{}'", table.headers[col])),
                    format!(
                        "{} is not a time of day (h:mm, h:mm:ss, with AM/PM or not, after a date \
                         or alone); diagnose groups its folds by this column's sessions and times",
                        super::quote_cell(table.records[n].get(col).map_or("", String::as_str))
                    ),
                ))
            }
        }
    }
    let mut order: Vec<usize> = (0..secs.len()).collect();
    order.sort_by(|&a, &b| secs[a].total_cmp(&secs[b]));
    let n = secs.len();
    let k = folds.clamp(1, n.max(1));
    let mut keys = vec![String::new(); n];
    for (rank, &i) in order.iter().enumerate() {
        keys[i] = format!("block {}", rank * k / n + 1);
    }
    Ok(FoldKeys {
        kind: KeyKind::TimeBlock,
        column: table.headers[col].clone(),
        keys,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_of_day_are_read_in_both_clocks() {
        assert_eq!(seconds_of_day("7:03:21 PM"), Some(19.0 * 3600.0 + 201.0));
        assert_eq!(seconds_of_day("12:00 AM"), Some(0.0));
        assert_eq!(
            seconds_of_day("18:45:04"),
            Some(18.0 * 3600.0 + 45.0 * 60.0 + 4.0)
        );
        assert_eq!(seconds_of_day("25:00"), None);
        assert_eq!(seconds_of_day("fast"), None);
        assert_eq!(
            split_date_time("5/6/2026 7:03:21 PM"),
            (Some("5/6/2026"), Some("7:03:21 PM"))
        );
        assert_eq!(
            split_date_time("2026-05-06T19:03:21"),
            (Some("2026-05-06"), Some("19:03:21"))
        );
        assert_eq!(split_date_time("2026-05-06"), (Some("2026-05-06"), None));
        assert_eq!(split_date_time("19:03"), (None, Some("19:03")));
    }

    fn table(head: &str, cells: &[&str], groups: &[&str]) -> ShotTable {
        let shots = groups
            .iter()
            .enumerate()
            .map(|(i, g)| crate::model::Shot {
                id: i.to_string(),
                group: (*g).to_owned(),
                golfer: None,
                delivery: crate::model::delivery_from_file_units(&[0.0; crate::model::N_DELIVERY]),
                measured: None,
            })
            .collect();
        ShotTable {
            path: "s.csv".into(),
            headers: vec!["shot_id".into(), head.into()],
            records: cells
                .iter()
                .enumerate()
                .map(|(i, c)| vec![i.to_string(), (*c).to_owned()])
                .collect(),
            shots,
            lines: (2..2 + cells.len()).collect(),
            left_out: Vec::new(),
            conventions: Vec::new(),
            strict: false,
        }
    }

    #[test]
    fn dates_make_sessions_and_one_days_times_make_blocks() {
        let t = table(
            "Date",
            &["5/6/2026 7:03 PM", "5/7/2026 9:00 AM", "5/6/2026 7:05 PM"],
            &["all"; 3],
        );
        let k = fold_keys(&t, 5).unwrap().unwrap();
        assert_eq!(k.kind, KeyKind::Session);
        assert_eq!(k.keys, ["2026-05-06", "2026-05-07", "2026-05-06"]);
        // One day: 6 shots out of order in 3 blocks of 2 consecutive shots.
        let t = table(
            "time",
            &["10:05", "10:00", "10:20", "10:10", "10:25", "10:15"],
            &["all"; 6],
        );
        let k = fold_keys(&t, 3).unwrap().unwrap();
        assert_eq!(k.kind, KeyKind::TimeBlock);
        assert_eq!(
            k.keys,
            ["block 1", "block 1", "block 3", "block 2", "block 3", "block 2"]
        );
        let t = table("time", &["10:05", "later"], &["all"; 2]);
        let e = fold_keys(&t, 3).unwrap_err().to_string();
        assert!(
            e.contains("s.csv:3: column 'time'") && e.contains("'later' is not a time of day"),
            "{e}"
        );
    }

    #[test]
    fn clubs_group_when_there_is_no_time_and_nothing_else_is_by_shot() {
        let t = table("note", &["", "", ""], &["Driver", "7 Iron", "7i"]);
        let k = fold_keys(&t, 5).unwrap().unwrap();
        assert_eq!(k.kind, KeyKind::Club);
        let t = table("note", &["", "", ""], &["A", "B", "C"]);
        assert_eq!(fold_keys(&t, 5).unwrap(), None);
    }
}
