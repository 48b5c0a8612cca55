//! The import's summary: the rows of an export counted by what became of them (summary rows,
//! rows the monitor flagged, rows left out by reason, shots kept without part of their
//! delivery, flagged shots, disagreements of values given twice), one note per kind.

use super::cell::list_lines;
use super::checks::Redundancy;
use crate::data::DataError;

/// Rows left out for one reason: the reason, their lines, and the first one's full message.
pub(super) struct LeftOut {
    pub reason: String,
    pub lines: Vec<usize>,
    pub first: String,
    /// Left out by a rule `docs/import.md` states (a row a spreadsheet's formula computed, a
    /// launch the monitor did not measure: lost spin, a vendor's "no value"), not for a value
    /// that cannot be read: no sign that the file is read wrongly.
    pub by_rule: bool,
}

/// What the rows of an export came to, for the summary.
#[derive(Default)]
pub(super) struct Tally {
    pub summary: Vec<(String, Vec<usize>)>,
    pub flagged: Vec<(usize, String)>,
    pub left_out: Vec<LeftOut>,
    /// Cells read as not measured, by reason (the `first` is the first cell's line and text).
    pub blanked: Vec<LeftOut>,
    pub lacking: Vec<(&'static str, Vec<usize>)>,
    pub flags: Vec<(&'static str, Vec<usize>)>,
    pub redundancy: Redundancy,
    /// Lines of shots written with back spin below 0 (topspin).
    pub topspin: Vec<usize>,
}

impl Tally {
    pub(super) fn push_to(
        list: &mut Vec<(&'static str, Vec<usize>)>,
        what: &'static str,
        line: usize,
    ) {
        match list.iter_mut().find(|(w, _)| *w == what) {
            Some((_, v)) => v.push(line),
            None => list.push((what, vec![line])),
        }
    }

    /// A row skipped as `label` (never a shot: a summary row, a repeated units row).
    pub(super) fn skip(&mut self, label: String, line: usize) {
        match self.summary.iter_mut().find(|(l, _)| *l == label) {
            Some((_, v)) => v.push(line),
            None => self.summary.push((label, vec![line])),
        }
    }

    pub(super) fn blank(&mut self, reason: String, line: usize, first: &str) {
        match self.blanked.iter_mut().find(|l| l.reason == reason) {
            Some(l) if l.lines.last() == Some(&line) => {}
            Some(l) => l.lines.push(line),
            None => self.blanked.push(LeftOut {
                reason,
                lines: vec![line],
                first: first.to_owned(),
                by_rule: true,
            }),
        }
    }

    /// Leave the row at `line` out for `reason` (`by_rule`: a reason the import documents as
    /// skipped and counted, [`LeftOut::by_rule`]).
    pub(super) fn leave_out(&mut self, reason: String, line: usize, e: &DataError, by_rule: bool) {
        match self.left_out.iter_mut().find(|l| l.reason == reason) {
            Some(l) => l.lines.push(line),
            None => self.left_out.push(LeftOut {
                reason,
                lines: vec![line],
                first: e.to_string(),
                by_rule,
            }),
        }
    }
}

/// Refuse an export more than half of whose rows hold values that cannot be used, as every
/// reader of shots and launches refuses such a file
/// ([`crate::data::left_out::refuse_when_unusable`]): it is read wrongly (another layout, unit or
/// separator), and the shots written would be the few rows that happen to parse. A file with no
/// shot at all is refused by its own message ([`no_shots`]). Rows left out by a documented rule
/// ([`LeftOut::by_rule`]: formula rows, lost spin) say nothing of how the file is read, so they
/// count on neither side.
pub(super) fn refuse_mostly_bad(
    path: &std::path::Path,
    vendor: &str,
    t: &Tally,
    written: usize,
) -> Result<(), DataError> {
    let unreadable = t.left_out.iter().filter(|l| !l.by_rule);
    let bad: usize = unreadable.clone().map(|l| l.lines.len()).sum();
    let total = written + bad;
    // The earliest bad row's message, whatever its reason.
    let first = unreadable.min_by_key(|l| l.lines[0]);
    match first {
        Some(first) if written > 0 && crate::data::left_out::mostly_bad(bad, total) => {
            Err(DataError::file(
                path,
                format!(
                "{bad} of {total} rows of the {vendor} export hold values that cannot be used, \
                 more than half: the file is likely read wrongly, so none of it is used (the \
                 first, {}; fix the file or read it with the right --format)",
                first.first
            ),
            ))
        }
        _ => Ok(()),
    }
}

/// The refusal of an export none of whose rows became a shot: what the rows left out were,
/// by reason. Only when some of them hold values that cannot be read is the file likely read
/// wrongly; rows left out by documented rules alone (formula rows, lost spin) are said to be
/// such, without sending the user to another `--format`.
pub(super) fn no_shots(path: &std::path::Path, vendor: &str, t: &Tally) -> DataError {
    let Some(first) = t.left_out.iter().min_by_key(|l| l.lines[0]) else {
        return DataError::file(
            path,
            format!("no shots: the {vendor} export has no usable rows"),
        );
    };
    if t.left_out.iter().all(|l| l.by_rule) {
        let n: usize = t.left_out.iter().map(|l| l.lines.len()).sum();
        let kinds: Vec<String> = t
            .left_out
            .iter()
            .map(|l| format!("{} {}", l.lines.len(), l.reason))
            .collect();
        return DataError::file(
            path,
            format!(
                "no shots: all {n} rows of the {vendor} export are left out by the import's \
                 rules for rows that are not shots or lack a measured launch ({}; the first, \
                 {}); there is nothing to import",
                kinds.join("; "),
                first.first
            ),
        );
    }
    DataError::file(
        path,
        format!(
            "no shots: the {vendor} export has no usable rows (the first left out: {})",
            first.first
        ),
    )
}

/// The import's summary, one note per kind of row.
pub(super) fn summarise(t: &Tally, written: usize, notes: &mut Vec<String>) {
    for (label, lines) in &t.summary {
        notes.push(format!(
            "skipped {} {label} row(s), never shots (line(s) {})",
            lines.len(),
            list_lines(lines)
        ));
    }
    if !t.flagged.is_empty() {
        let lines: Vec<usize> = t.flagged.iter().map(|(l, _)| *l).collect();
        notes.push(format!(
            "skipped {} shot(s) the monitor flagged ({}; line(s) {}): not used",
            t.flagged.len(),
            t.flagged[0].1,
            list_lines(&lines)
        ));
    }
    for l in &t.left_out {
        notes.push(format!(
            "left out {} row(s): {} (line(s) {}; the first: {})",
            l.lines.len(),
            l.reason,
            list_lines(&l.lines),
            l.first
        ));
    }
    for l in &t.blanked {
        notes.push(format!(
            "read cells of {} row(s) as not measured: {} (line(s) {}; the first: {})",
            l.lines.len(),
            l.reason,
            list_lines(&l.lines),
            l.first
        ));
    }
    for (what, lines) in &t.lacking {
        notes.push(format!(
            "{} of {written} shot(s) have no {what} (line(s) {}): written with those cells \
             empty; smash flight uses their launch, and predict, compare, calibrate and diagnose \
             leave them out",
            lines.len(),
            list_lines(lines)
        ));
    }
    for (flag, lines) in &t.flags {
        let what = match *flag {
            "spin_estimated" => "spin the monitor estimated (spin_estimated = 1)",
            "club_estimated" => "club data the monitor estimated (club_estimated = 1)",
            _ => "a carry from the vendor's flight model, not tracked to landing (flight_modelled = 1)",
        };
        let then = if *flag == "flight_modelled" {
            "comparing a flight model with them compares two models"
        } else {
            "predict, compare, calibrate and diagnose leave them out unless --include-estimated"
        };
        notes.push(format!(
            "{} of {written} shot(s) have {what} (line(s) {}); {then}",
            lines.len(),
            list_lines(lines)
        ));
    }
    if !t.topspin.is_empty() {
        notes.push(format!(
            "{} of {written} shot(s) have topspin, back spin below 0 (line(s) {}): a topped \
             ball; if the export's spin axis runs past ±90° by another convention, or its back \
             spin has the other sign, they are read wrongly",
            t.topspin.len(),
            list_lines(&t.topspin)
        ));
    }
    t.redundancy.notes(notes);
}
