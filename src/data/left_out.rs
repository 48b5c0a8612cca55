//! Rows of an input file a command cannot use (a cell that is not a number, a value outside
//! its physical range, a launch the flight model does not accept), left out and counted: one
//! note per kind of reason with its first file line and message, never a refusal of the other
//! rows. The shots reader ([`crate::data::shots`]) and the launch reader
//! ([`crate::data::flight_files`], and the streamed flight of
//! [`crate::app::flight::stream`]) both keep their rows left out here, so `predict`,
//! `compare`, `calibrate`, `diagnose` and `flight` say the same thing the same way. Under
//! `--strict` the readers refuse the file at the first such row instead.

use std::path::Path;

use super::DataError;

/// Rows of a file left out for one reason.
#[derive(Debug, Clone, PartialEq)]
pub struct LeftOut {
    /// Why (`no impact location`, `a value outside its physical range in column
    /// 'ball_speed_mph'`).
    pub reason: String,
    /// Their file lines, in file order.
    pub lines: Vec<usize>,
    /// For a row whose values cannot be used: the first such row's full message (file, line,
    /// column, what was wrong, what is allowed). `None` for rows left out by choice (no impact
    /// location, estimated values), which hold nothing wrong.
    pub first: Option<DataError>,
    /// Rows of flights cut off by the time limit the user gave (`--max-time-s` below the
    /// default, [`crate::flight::cut_by_given_limit`]): nothing wrong in the file, so they
    /// never count toward a refusal that blames it.
    pub cut_by_limit: bool,
}

/// Why rows whose flight the user's `--max-time-s` cut off are left out.
const CUT_BY_LIMIT: &str = "not landed within the --max-time-s given (raise it to fly them)";

/// The kind of what is wrong with a cell, from the reader's message: the reasons a note
/// groups rows by (with the column).
fn kind(message: &str) -> &'static str {
    if message.contains("outside") {
        "a value outside its physical range"
    } else if message.contains("not a number")
        || message.contains("not a finite number")
        || message.contains("not finite")
    {
        "a cell that is not a number"
    } else if message.starts_with("empty") {
        "an empty cell"
    } else if message.contains("has not landed") {
        "a launch that does not land within the time limit"
    } else if message.starts_with("found a row with") {
        "a row whose cells do not match the header's columns"
    } else if message.contains("is used twice") {
        "a shot id used before"
    } else if message.contains("must be") {
        "a launch value the flight model does not take"
    } else {
        "a bad value"
    }
}

/// Keep the items of `items` whose entry in `keep` (parallel to it) is true: the rows of one
/// table held in several parallel vectors are left out of each alike.
pub fn retain_kept<T>(items: &mut Vec<T>, keep: &[bool]) {
    let mut k = keep.iter();
    items.retain(|_| *k.next().expect("parallel"));
}

/// Add the row at `line` that `e` says cannot be used to `list`, under the reason of its kind
/// and column (`a cell that is not a number in column 'backspin_rpm'`).
pub fn push_bad(list: &mut Vec<LeftOut>, line: usize, e: DataError) {
    if crate::flight::cut_by_given_limit(&e.message) {
        return push_entry(list, line, CUT_BY_LIMIT.to_owned(), Some(e), true);
    }
    let reason = match &e.place {
        Some(place) => format!("{} in {place}", kind(&e.message)),
        None => kind(&e.message).to_owned(),
    };
    push(list, line, reason, Some(e));
}

/// Add a row at `line` left out for `reason` (nothing wrong in it: a choice of the reader).
pub fn push_reason(list: &mut Vec<LeftOut>, line: usize, reason: String) {
    push(list, line, reason, None);
}

/// Add the row at `line` to `list` under `reason`: to its entry when there is one, else to a
/// new entry whose first row's message is `first`.
pub fn push(list: &mut Vec<LeftOut>, line: usize, reason: String, first: Option<DataError>) {
    push_entry(list, line, reason, first, false);
}

fn push_entry(
    list: &mut Vec<LeftOut>,
    line: usize,
    reason: String,
    first: Option<DataError>,
    cut_by_limit: bool,
) {
    match list.iter_mut().find(|l| l.reason == reason) {
        Some(l) => l.lines.push(line),
        None => list.push(LeftOut {
            reason,
            lines: vec![line],
            first,
            cut_by_limit,
        }),
    }
}

/// File lines for a note: the first ten, then `…` when there are more.
pub fn list_lines(lines: &[usize]) -> String {
    let shown: Vec<String> = lines.iter().take(10).map(usize::to_string).collect();
    if lines.len() > 10 {
        format!("{}, …", shown.join(", "))
    } else {
        shown.join(", ")
    }
}

/// One note per reason: how many of the file's `total` rows, why, their first lines and, for
/// bad values, the first one's message (`left out 2 of 40 rows: a value outside its physical
/// range in column 'ball_speed_mph' (line(s) 5, 9; the first: s.csv:5: column
/// 'ball_speed_mph': measured ball speed 900 is outside the physical range (0, 400] mph;
/// --strict refuses the file)`).
pub fn notes(list: &[LeftOut], total: usize) -> Vec<String> {
    list.iter()
        .map(|l| {
            let first = l
                .first
                .as_ref()
                .map_or(String::new(), |e| format!("; the first: {e}"));
            format!(
                "left out {} of {total} rows: {} (line(s) {}{first}; --strict refuses the file)",
                l.lines.len(),
                l.reason,
                list_lines(&l.lines)
            )
        })
        .collect()
}

/// Rows with values that cannot be used, among those left out (not those of flights the
/// user's `--max-time-s` cut off).
pub fn bad_rows(list: &[LeftOut]) -> usize {
    list.iter()
        .filter(|l| l.first.is_some() && !l.cut_by_limit)
        .map(|l| l.lines.len())
        .sum()
}

/// Rows of flights the user's `--max-time-s` cut off, among those left out.
fn cut_rows(list: &[LeftOut]) -> usize {
    list.iter()
        .filter(|l| l.cut_by_limit)
        .map(|l| l.lines.len())
        .sum()
}

/// Whether `bad` of `total` rows is more than half: the limit at which a file is taken to be
/// read wrongly (every reader of shots and launches, and the import).
pub fn mostly_bad(bad: usize, total: usize) -> bool {
    2 * bad > total
}

/// Refuse the file in one line when no row is left to use (`kept` = 0), or when more than
/// half of its rows (the `kept` and those in `list`) hold values that cannot be used: the limit at which the import's
/// checks of values given twice refuse a file (`import::checks`, "disagreement on most
/// shots"), for the same reason: a file most of whose rows are wrong is read wrongly (another
/// layout, unit or separator), and what is left would describe the few rows that happen to
/// parse.
///
/// Flights cut off by the user's own `--max-time-s` are no sign of a file read wrongly: they
/// count in neither refusal, and a run they leave without a row is refused naming the flag.
pub fn refuse_when_unusable(path: &Path, list: &[LeftOut], kept: usize) -> Result<(), DataError> {
    let all = kept + list.iter().map(|l| l.lines.len()).sum::<usize>();
    let cut = cut_rows(list);
    let total = all - cut;
    let bad = bad_rows(list);
    let first = list
        .iter()
        .filter(|l| !l.cut_by_limit)
        .filter_map(|l| l.first.as_ref())
        .min_by_key(|e| e.line);
    if kept == 0 && cut > 0 {
        let first_cut = list
            .iter()
            .filter(|l| l.cut_by_limit)
            .filter_map(|l| l.first.as_ref())
            .min_by_key(|e| e.line)
            .expect("a cut flight has its message");
        let others = if cut < all {
            format!(", the other {} for other reasons", all - cut)
        } else {
            String::new()
        };
        return Err(DataError::file(
            path,
            format!(
                "no shot left: {cut} of {all} rows have not landed within the --max-time-s \
                 given{others} (the first, {first_cut}); raise --max-time-s"
            ),
        ));
    }
    if kept == 0 {
        let why = match (first, list.first()) {
            (Some(e), _) => format!(
                "no usable row: all {total} rows are left out (the first bad one, {e}; fix the \
                 file or read it with the right --format)"
            ),
            (None, Some(l)) => format!(
                "no shots: every row is left out (the first, line {}: {}; --strict names the \
                 cell)",
                l.lines[0], l.reason
            ),
            (None, None) => "no shots: the file has a header but no rows".into(),
        };
        return Err(DataError::file(path, why));
    }
    if let Some(e) = first.filter(|_| mostly_bad(bad, total)) {
        return Err(DataError::file(
            path,
            format!(
                "{bad} of {total} rows hold values that cannot be used, more than half: the file \
                 is likely read wrongly, so none of it is used (the first, {e}; fix the file or \
                 read it with the right --format)"
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_grouped_by_kind_and_column_and_refused_past_half() {
        let p = Path::new("s.csv");
        let at = |line, col: &str, m: &str| {
            DataError::at(p, Some(line), Some(format!("column '{col}'")), m)
        };
        let mut list = Vec::new();
        push_bad(
            &mut list,
            3,
            at(
                3,
                "ball_speed_mph",
                "measured ball speed 900 is outside the physical range (0, 400] mph",
            ),
        );
        push_bad(&mut list, 5, at(5, "backspin_rpm", "'abc' is not a number"));
        push_bad(
            &mut list,
            8,
            at(
                8,
                "ball_speed_mph",
                "measured ball speed 0 is outside the physical range (0, 400] mph",
            ),
        );
        push_reason(&mut list, 9, "no impact location".into());
        assert_eq!(list.len(), 3);
        assert_eq!(list[0].lines, [3, 8]);
        assert_eq!(bad_rows(&list), 3);
        let n = notes(&list, 10);
        assert!(n[0].starts_with("left out 2 of 10 rows: a value outside its physical range in column 'ball_speed_mph' (line(s) 3, 8; the first: s.csv:3: column 'ball_speed_mph': measured ball speed 900"), "{}", n[0]);
        assert!(
            n[1].contains("a cell that is not a number in column 'backspin_rpm'"),
            "{}",
            n[1]
        );
        assert_eq!(
            n[2],
            "left out 1 of 10 rows: no impact location (line(s) 9; --strict refuses the file)"
        );
        assert!(refuse_when_unusable(p, &list, 6).is_ok());
        // 3 bad of 5: more than half.
        let e = refuse_when_unusable(p, &list, 1).unwrap_err().to_string();
        assert!(
            e.starts_with("s.csv: 3 of 5 rows hold values that cannot be used"),
            "{e}"
        );
        let e = refuse_when_unusable(p, &list, 0).unwrap_err().to_string();
        assert!(e.contains("no usable row"), "{e}");
        // A repeated id is named as such, not as a launch value (its message says "must be").
        assert_eq!(
            kind("shot id 'A-1' is used twice; ids must be unique"),
            "a shot id used before"
        );
        assert_eq!(
            list_lines(&(1..=12).collect::<Vec<_>>()),
            "1, 2, 3, 4, 5, 6, 7, 8, 9, 10, …"
        );
    }
}
