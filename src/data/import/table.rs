//! Reading an export into rows of cells: text decoded by [`super::text::decode`], Excel's
//! `sep=` delimiter hint or a semicolon-separated file (European spreadsheets, whose cells write
//! decimal commas), title lines before the header (found by its column names), the header row
//! and an optional units row under it. Every row keeps the file line it came from, for messages.

use std::path::Path;

use super::cell::{split_header, Row};
use super::text::decode;
use super::units::Unit;
use crate::data::DataError;

/// An export read into cells.
pub(super) struct Table {
    /// File line of the header row.
    pub header_line: usize,
    /// The header cells as written (for messages).
    pub header: Vec<String>,
    /// The header cells split into a normalised name and the bracketed unit text, if any.
    pub headers: Vec<(String, Option<String>)>,
    /// The units row under the header, when there is one.
    pub unit_row: Option<Row>,
    /// The data rows; rows with no text in any cell are dropped.
    pub rows: Vec<Row>,
    /// Cells write decimal commas (`3,5`): the file is separated by semicolons or tabs.
    pub decimal_comma: bool,
    /// What was read differently from a plain UTF-8 CSV (encoding, separator, title lines).
    pub notes: Vec<String>,
    /// The file line of the last row when the file ends inside a quoted cell of it (the row
    /// was cut short).
    pub cut_last: Option<usize>,
    /// Lines that could not be read as a row at all (JSON Lines that are not JSON), each with
    /// why: bad rows, left out and counted.
    pub broken: Vec<(usize, DataError)>,
    /// Columns added after the header's own ([`Table::sections_as_column`]): not the file's,
    /// so a row's width is checked against the header's own columns.
    pub added: usize,
}

/// How many rows the header may be preceded by (title lines, a date, a place): an export whose
/// header is further down is read from its first row, and its columns are reported missing.
const HEADER_SEARCH_ROWS: usize = 30;

/// Read an export (`bytes`, from `path`): drop `skip_lines` lines after any BOM and `sep=` line,
/// then find the header (the first row naming at least two columns `known` recognises, among
/// the first rows; else the first row) and split the units row and the data rows. `vendor`
/// names the export in messages.
pub(super) fn read_table(
    path: &Path,
    bytes: &[u8],
    skip_lines: usize,
    vendor: &str,
    known: &dyn Fn(&str) -> bool,
) -> Result<Table, DataError> {
    let (text, encoding_note) = decode(path, bytes)?;
    let mut notes: Vec<String> = encoding_note.into_iter().collect();
    if super::json::is_json(&text) {
        let json = super::json::read_json(path, &text, known, &mut notes)?;
        let headers = json.header.iter().map(|h| split_header(h)).collect();
        return Ok(Table {
            header_line: 1,
            header: json.header,
            headers,
            unit_row: None,
            rows: json.rows,
            decimal_comma: false,
            notes,
            cut_last: None,
            broken: json.broken,
            added: 0,
        });
    }
    let (body, offset_lines, sep) = strip_preamble(path, &text, skip_lines)?;
    let delimiter = sep.unwrap_or_else(|| sniff_delimiter(body));
    let (mut rows, last_start) = read_rows(path, body, offset_lines, delimiter)?;
    // A file separated by semicolons or tabs writes decimal commas when some cell is one
    // (`3,5`); then a dot groups thousands (`3.083`). Without such a cell, dots are decimal.
    let decimal_comma = delimiter != b','
        && rows
            .iter()
            .any(|(_, cells)| cells.iter().any(|c| is_decimal_comma(c)));
    if sep.is_none() && delimiter != b',' {
        notes.push(format!(
            "separated by {}, with decimal {} in numbers",
            if delimiter == b';' {
                "semicolons"
            } else {
                "tabs"
            },
            if decimal_comma {
                "commas (a dot groups thousands)"
            } else {
                "points"
            }
        ));
    }
    let header_at = rows
        .iter()
        .take(HEADER_SEARCH_ROWS)
        .position(|(_, cells)| cells.iter().filter(|c| known(&split_header(c).0)).count() >= 2)
        .unwrap_or(0);
    if header_at > 0 {
        let lines: Vec<usize> = rows[..header_at].iter().map(|(l, _)| *l).collect();
        notes.push(format!(
            "{} line(s) before the header skipped (title: line(s) {})",
            lines.len(),
            super::cell::list_lines(&lines)
        ));
    }
    // A units row among the title lines above the header counts as one under it.
    let mut found: Vec<Row> = rows[..header_at]
        .iter()
        .filter(|(_, cells)| is_unit_row(cells))
        .cloned()
        .collect();
    let mut rows = rows.split_off(header_at).into_iter();
    let (header_line, header) = rows.next().ok_or_else(|| {
        DataError::file(
            path,
            format!("empty file: a {vendor} export has a header row"),
        )
    })?;
    let headers = header.iter().map(|h| split_header(h)).collect();
    let mut rows: Vec<Row> = rows.collect();
    found.extend(take_unit_row(&mut rows));
    for (line, _) in found.iter().filter(|(l, _)| *l != header_line + 1) {
        notes.push(format!(
            "the units row is line {line}, not the line under the header: read as the units row"
        ));
    }
    let unit_row = merge_unit_rows(path, found)?;
    let headers = units_of_twins(headers, unit_row.as_ref());
    let cut_last = cut_in_quotes(body, &rows, last_start, delimiter);
    Ok(Table {
        header_line,
        header,
        headers,
        unit_row,
        rows,
        decimal_comma,
        notes,
        cut_last,
        broken: Vec::new(),
        added: 0,
    })
}

impl Table {
    /// Rows whose only text is in their first cell, not a number (SkyTrak writes the club this
    /// way, `PW` or `"9 IRON"`, above its shots), taken out and read as a column `name` of the
    /// rows under them, added after the header's last column; a row above the first such row
    /// gets an empty cell. A row with fewer cells than the header is left as it is (its cut is
    /// found as any cut row's). A file with a column of that name keeps its own. Returns how
    /// many such rows name rows under them (notes at the end of a file name none); with no such
    /// row, nothing changes.
    pub(super) fn sections_as_column(&mut self, name: &str) -> usize {
        let section = |cells: &[String]| match cells.split_first() {
            Some((first, rest)) => {
                !first.is_empty()
                    && first.parse::<f64>().is_err()
                    && rest.iter().all(|c| c.is_empty())
            }
            None => false,
        };
        let found = self.rows.iter().filter(|(_, c)| section(c)).count();
        // A file with a column of that name names its clubs itself.
        let own = split_header(name).0;
        if found == 0 || self.headers.iter().any(|(h, _)| *h == own) {
            return 0;
        }
        let width = self.header.len();
        let (mut current, mut fresh, mut named) = (String::new(), false, 0);
        self.rows.retain_mut(|(_, cells)| {
            if section(cells) {
                current = cells[0].clone();
                fresh = true;
                return false;
            }
            if cells.len() >= width {
                cells.insert(width, current.clone());
            }
            named += usize::from(std::mem::take(&mut fresh));
            true
        });
        self.header.push(name.to_owned());
        self.headers.push(split_header(name));
        self.added += 1;
        named
    }
}

/// The header's names with the units row's unit given to each name the header writes twice
/// without one: SkyTrak writes `SIDE` for its side spin and its side angle, told apart only by
/// `RPM` and `DEG` in the units row under them. Other names keep their header unit (or none).
fn units_of_twins(
    mut headers: Vec<(String, Option<String>)>,
    unit_row: Option<&Row>,
) -> Vec<(String, Option<String>)> {
    let Some((_, units)) = unit_row else {
        return headers;
    };
    let twice: Vec<bool> = headers
        .iter()
        .map(|(n, u)| {
            u.is_none() && !n.is_empty() && headers.iter().filter(|(m, _)| m == n).count() > 1
        })
        .collect();
    for (i, (_, u)) in headers.iter_mut().enumerate() {
        match units.get(i) {
            Some(cell) if twice[i] && Unit::parse(cell).is_some() => *u = Some(cell.clone()),
            _ => {}
        }
    }
    headers
}

/// The units rows found (above the header, under it, under the first shot) as one: each
/// column's unit from the row that states one. Two rows that state different units for one
/// column are refused: which one holds is not clear.
fn merge_unit_rows(path: &Path, found: Vec<Row>) -> Result<Option<Row>, DataError> {
    let mut found = found.into_iter();
    let Some((line, mut cells)) = found.next() else {
        return Ok(None);
    };
    for (other, more) in found {
        if let Some(i) = unit_conflict(&cells, &more) {
            return Err(DataError::at(
                path,
                Some(other),
                Some(format!("column {}", i + 1)),
                format!(
                    "a second units row: line {line} says '{}' and line {other} says '{}' for \
                     this column; which one holds is not clear: keep one units row, under the \
                     header",
                    cells[i], more[i]
                ),
            ));
        }
        if more.len() > cells.len() {
            cells.resize(more.len(), String::new());
        }
        for (c, m) in cells.iter_mut().zip(more) {
            if c.is_empty() {
                *c = m;
            }
        }
    }
    Ok(Some((line, cells)))
}

/// The first column for which two units rows state different units (units compared by what
/// they are, so `[yds]` and `[yd]` agree).
pub(super) fn unit_conflict(a: &[String], b: &[String]) -> Option<usize> {
    let unit = |c: &String| Unit::parse(c).map(|u| u.name);
    (0..a.len().min(b.len()))
        .find(|&i| matches!((unit(&a[i]), unit(&b[i])), (Some(x), Some(y)) if x != y))
}

/// The line of the last row when the file ends inside a quoted cell that row opened (a
/// truncated file whose last line was cut in a quoted cell: the CSV reader closes the cell at
/// the end of the file, and the row would be read whole). `last_start` is the byte where the
/// reader started that row.
fn cut_in_quotes(body: &str, rows: &[Row], last_start: usize, delimiter: u8) -> Option<usize> {
    let (last_line, _) = rows.last()?;
    ends_in_quotes(body, last_start, delimiter).then_some(*last_line)
}

/// Whether the text from `start` (the start of a row) to the end of `body` ends inside a
/// quoted cell: a quote that opens a cell (after `delimiter` or a line end) is not closed.
fn ends_in_quotes(body: &str, start: usize, delimiter: u8) -> bool {
    let Some(text) = body.get(start..) else {
        return false;
    };
    let mut in_quotes = false;
    let mut field_start = true;
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if in_quotes && chars.peek() == Some(&'"') => {
                chars.next();
            }
            '"' if in_quotes => in_quotes = false,
            '"' if field_start => in_quotes = true,
            _ => {}
        }
        field_start = !in_quotes && (c == char::from(delimiter) || matches!(c, '\n' | '\r'));
    }
    in_quotes
}

/// Whether a cell is a number written with a decimal comma: `-3,5`, `105,6`.
fn is_decimal_comma(cell: &str) -> bool {
    let t = cell.trim().trim_start_matches(['-', '+']);
    let Some((int, frac)) = t.split_once(',') else {
        return false;
    };
    !int.is_empty()
        && !frac.is_empty()
        && int.bytes().all(|b| b.is_ascii_digit() || b == b'.')
        && frac.bytes().all(|b| b.is_ascii_digit())
}

/// The separator of a file without a `sep=` line: semicolons or tabs when its first line that
/// has any separator at all has more of them than commas (a European spreadsheet writes `;`
/// and decimal commas; title lines without a separator, `PRACTICE: 3/14/2026 6:05 PM`, say
/// nothing), else commas.
fn sniff_delimiter(body: &str) -> u8 {
    let count = |line: &str, c: char| line.matches(c).count();
    let first = body
        .split(['\n', '\r'])
        .filter(|l| !l.is_empty())
        .take(HEADER_SEARCH_ROWS)
        .find(|l| l.contains([',', ';', '\t']))
        .unwrap_or("");
    let (commas, semis, tabs) = (count(first, ','), count(first, ';'), count(first, '\t'));
    if semis > commas && semis >= tabs {
        b';'
    } else if tabs > commas {
        b'\t'
    } else {
        b','
    }
}

/// Drop a leading `sep=X` line (taking `X` as the delimiter) and then `skip_lines` lines.
/// Returns the CSV body, how many lines precede it, and the delimiter.
fn strip_preamble<'t>(
    path: &Path,
    text: &'t str,
    skip_lines: usize,
) -> Result<(&'t str, usize, Option<u8>), DataError> {
    let mut body = text;
    let mut offset_lines = 0usize;
    let mut delimiter = None;
    let first = next_line(body).0.trim();
    if let Some(sep) = first.strip_prefix("sep=") {
        let sep = sep.trim_matches('"');
        let [b] = sep.as_bytes() else {
            return Err(DataError::at(
                path,
                Some(1),
                None,
                format!("'{first}': the sep= line must name one character"),
            ));
        };
        delimiter = Some(*b);
        body = next_line(body).1;
        offset_lines += 1;
    }
    for _ in 0..skip_lines {
        if body.is_empty() {
            return Err(DataError::file(
                path,
                format!(
                    "skip_lines = {skip_lines}, but the file has only {offset_lines} line(s) \
                     before its end: lower skip_lines in the mapping"
                ),
            ));
        }
        body = next_line(body).1;
        offset_lines += 1;
    }
    Ok((body, offset_lines, delimiter))
}

/// The first line of `text` (without its line end: LF, CRLF or a lone CR) and the rest.
fn next_line(text: &str) -> (&str, &str) {
    match text.find(['\n', '\r']) {
        Some(i) if text[i..].starts_with("\r\n") => (&text[..i], &text[i + 2..]),
        Some(i) => (&text[..i], &text[i + 1..]),
        None => (text, ""),
    }
}

/// Parse the CSV body into trimmed cells, each row with its file line (`offset_lines` lines
/// precede the body); blank rows are dropped. Also the byte where the last row starts.
fn read_rows(
    path: &Path,
    body: &str,
    offset_lines: usize,
    delimiter: u8,
) -> Result<(Vec<Row>, usize), DataError> {
    let lines = crate::line_index::LineIndex::new(body.as_bytes());
    let line_of = |p: &csv::Position| lines.line_of(p) + offset_lines;
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .delimiter(delimiter)
        .from_reader(body.as_bytes());
    let mut rows: Vec<Row> = Vec::new();
    let mut last_start = 0;
    let mut blank_last = None;
    for rec in rdr.records() {
        let rec =
            rec.map_err(|e| DataError::at(path, e.position().map(line_of), None, e.to_string()))?;
        let line = rec
            .position()
            .map_or(rows.len() + 1 + offset_lines, line_of);
        // Spaces around a cell go, and a byte-order mark that is not at the file's start (a
        // line added above an export's header); line breaks stay: a quoted cell that runs over
        // its line's end (a quote a cut line left open) is found by them (`rows.rs`).
        let blank =
            |c: char| (c.is_ascii_whitespace() && c != '\n' && c != '\r') || c == '\u{feff}';
        let cells: Vec<String> = rec
            .iter()
            .map(|c| c.trim_matches(blank).to_owned())
            .collect();
        let start = rec
            .position()
            .map_or(0, |p| usize::try_from(p.byte()).unwrap_or(0));
        if cells.iter().all(|c| c.is_empty()) {
            // Blank, unless it is the file's last row cut inside its first quoted cell.
            blank_last = Some((line, cells, start));
            continue;
        }
        blank_last = None;
        last_start = start;
        rows.push((line, cells));
    }
    if let Some((line, cells, start)) = blank_last {
        if ends_in_quotes(body, start, delimiter) {
            rows.push((line, cells));
            last_start = start;
        }
    }
    Ok((rows, last_start))
}

/// Whether `cells` is a units row: every non-empty cell a unit or bracketed text (`[mph]`,
/// `[]`), at least one of them a unit, except that the first non-empty cell may be a legend
/// naming units (TrackMan's web sheets write `"Yds/Ft, Mph"` there) when two or more other cells
/// are units.
pub(super) fn is_unit_row(cells: &[String]) -> bool {
    let non_empty: Vec<&String> = cells.iter().filter(|c| !c.is_empty()).collect();
    let unit = |c: &str| Unit::parse(c).is_some();
    let is_unitish = |c: &str| unit(c) || (c.starts_with('[') && c.ends_with(']'));
    let legend = |c: &str| {
        c.split(['/', ',', ' ', ';'])
            .filter(|w| !w.is_empty())
            .all(|w| unit(w) || w.eq_ignore_ascii_case("yds") || w.eq_ignore_ascii_case("units"))
    };
    let Some((first, rest)) = non_empty.split_first() else {
        return false;
    };
    let units = non_empty.iter().filter(|c| unit(c)).count();
    if non_empty.iter().all(|c| is_unitish(c)) && units >= 1 {
        return true;
    }
    // Units written without brackets among a few other words (SkyTrak: `#,L/R,MPH,DEG,RPM,…,
    // SCORE`): no number, and units in at least half the cells, three at least.
    let number = |c: &str| c.trim().parse::<f64>().is_ok();
    if !non_empty.iter().any(|c| number(c)) && units >= 3 && 2 * units >= non_empty.len() {
        return true;
    }
    legend(first)
        && rest.iter().all(|c| is_unitish(c))
        && rest.iter().filter(|c| unit(c)).count() >= 2
}

/// Remove and return the units row under the header: the first row, or the second when the
/// first is a shot (a units row that slipped under the first shot).
fn take_unit_row(rows: &mut Vec<Row>) -> Option<Row> {
    let at = (0..rows.len().min(2)).find(|&i| is_unit_row(&rows[i].1))?;
    Some(rows.remove(at))
}
