//! `smash flight` on a file of any size: the launch CSV is read a chunk at a time; each chunk is
//! cut at line starts into pieces that rayon's threads parse, fly and format (one pass over a
//! piece, so its launches and flights stay in cache); a writer thread appends the pieces, in
//! input order, to a temporary file beside the output while the next chunk is worked on, and
//! the temporary replaces the output only when every row has flown. Memory is bounded by the
//! chunk size whatever the file's length.
//!
//! The output is byte for byte what [`flight_csv`] writes for the same input (tested below).
//! Files the plain splitter does not handle exactly as the `csv` reader does (quoted cells,
//! carriage returns, a byte-order mark, invalid UTF-8) go through the one-piece path instead:
//! [`fly_csv_bytes`] ([`parse_launches`], [`fly`](crate::flight::fly), [`flight_csv`]).

use std::io::{Read, Write};
use std::path::Path;

use rayon::prelude::*;

use crate::data::flight_files::{
    flight_csv, flight_error_at, flight_value, launch_columns, split_at_line_ends, LaunchSource,
    OutputLayout, FLIGHT_COLUMNS, LAUNCH_COLUMNS,
};
use crate::data::flight_measured::{measured_flight_value, measured_value};
use crate::data::flight_output::Temporary;
use crate::data::launch_read::{parse_launches, LaunchRead};
use crate::data::left_out::{push_bad, refuse_when_unusable, LeftOut};
use crate::data::number::{parse_f64, push_cell};
use crate::data::{safe_write, write_atomic, DataError};
use crate::flight::integrate::fly_serial_in_hang_order;
use crate::flight::{Flight, FlightConfig, FlightError, FlightLaunch};

/// Bytes of input read per chunk (about 36,000 launches of a typical file): large enough that
/// the threads' start-up per chunk is negligible, small enough to bound memory and that the
/// last chunk's rows, which the output's `fsync` waits for, are a small part of the file.
pub const CHUNK_BYTES: usize = 1 << 20;
/// Bytes of input per piece a thread takes (about a thousand launches).
const PIECE_BYTES: usize = 1 << 16;

/// What a run flew.
#[derive(Debug, Clone, PartialEq)]
pub struct Flown {
    /// Launches flown (data rows).
    pub shots: usize,
    /// Which launch columns were flown.
    pub source: LaunchSource,
    /// Rows left out (a value that cannot be used, a launch that cannot be flown), by reason.
    pub left_out: Vec<LeftOut>,
}

impl Flown {
    /// One note per reason rows were left out ([`crate::data::left_out::notes`]).
    pub fn notes(&self) -> Vec<String> {
        let total = self.shots + self.left_out.iter().map(|l| l.lines.len()).sum::<usize>();
        crate::data::left_out::notes(&self.left_out, total)
    }
}

/// Fly every launch of `input` and write the flight file `out` (see the module
/// documentation). `chunk_bytes`: input read per chunk ([`CHUNK_BYTES`] in use; tests make it
/// small). A row that cannot be used (a cell that is not a number, a launch the flight model
/// does not take or that does not land, a bad measured flight cell) is left out and counted in
/// [`Flown::left_out`]; under `read.strict` the first (in file order) stops the run with an
/// error naming the file, line and column, as does a row of the wrong width, and as does a
/// file with no usable row or more than half bad ([`refuse_when_unusable`]); then `out` is left
/// as it was. `read.with_total` is taken from `cfg`'s ground model.
pub fn fly_csv_file(
    input: &Path,
    out: &Path,
    cfg: &FlightConfig,
    read: LaunchRead,
    chunk_bytes: usize,
) -> Result<Flown, DataError> {
    match stream(input, out, cfg, read, chunk_bytes.max(1))? {
        Some(flown) => Ok(flown),
        None => in_memory(input, out, cfg, read),
    }
}

/// The one-piece path (files with quoting, carriage returns, a byte-order mark or invalid
/// UTF-8).
fn in_memory(
    input: &Path,
    out: &Path,
    cfg: &FlightConfig,
    read: LaunchRead,
) -> Result<Flown, DataError> {
    let text = crate::data::read_text(input)?;
    let (bytes, flown) = fly_csv_bytes(input, text.as_bytes(), cfg, read)?;
    write_atomic(out, &bytes)?;
    Ok(flown)
}

/// The flight file of the launch CSV `bytes` (`input` names it in messages), in memory: what
/// [`fly_csv_file`] writes for a file holding `bytes`.
pub fn fly_csv_bytes(
    input: &Path,
    bytes: &[u8],
    cfg: &FlightConfig,
    read: LaunchRead,
) -> Result<(Vec<u8>, Flown), DataError> {
    let read = LaunchRead {
        with_total: cfg.ground.is_some(),
        ..read
    };
    let mut table = parse_launches(input, bytes, read)?;
    let results = crate::flight::fly(cfg, &table.launches);
    let prefix = table.source.prefix();
    let (flights, errs) = split_results(input, &table.lines, prefix, results);
    table.leave_out(input, errs, read.strict)?;
    let csv = flight_csv(
        &table.headers,
        &table.records,
        &flights,
        cfg.ground.is_some(),
    );
    Ok((
        csv,
        Flown {
            shots: flights.len(),
            source: table.source,
            left_out: table.left_out,
        },
    ))
}

/// The flights of `results` (one per line of `lines`) that landed, and per result the error of
/// one that did not, as a file error at its line (`prefix`: the launch columns').
pub fn split_results(
    input: &Path,
    lines: &[usize],
    prefix: &str,
    results: Vec<Result<Flight, FlightError>>,
) -> (Vec<Flight>, Vec<Option<DataError>>) {
    let mut flights = Vec::with_capacity(results.len());
    let errs = results
        .into_iter()
        .zip(lines)
        .map(|(r, &line)| match r {
            Ok(f) => {
                flights.push(f);
                None
            }
            Err(e) => Some(flight_error_at(input, line, prefix, &e)),
        })
        .collect();
    (flights, errs)
}

/// Where the columns are, from the header.
struct Plan {
    width: usize,
    launch: [Option<usize>; 5],
    prefix: &'static str,
    layout: OutputLayout,
}

/// Why a piece stopped.
enum Stop {
    /// Not plain CSV: the whole file goes the one-piece way.
    NotPlain,
    /// A row of the wrong width at this 0-based line of the piece.
    Bad(usize, Bad),
}

enum Bad {
    Width(usize),
    /// A launch cell (index into [`LAUNCH_COLUMNS`]) that is not a finite number.
    Cell(usize, String),
    /// A measured flight cell (index into [`FLIGHT_COLUMNS`]) and what is wrong with it.
    Measured(usize, String),
    Flight(FlightError),
}

/// One piece's output.
struct Piece {
    bytes: Vec<u8>,
    newlines: usize,
    shots: usize,
    stop: Option<Stop>,
    /// Rows left out, at their 0-based lines of the piece, in line order.
    bad: Vec<(usize, Bad)>,
}

/// Whether the streamed path can take `bytes`: no quoting, no CR, and no zero byte (UTF-16
/// text, which the one-piece path's reader refuses in words, looks like UTF-8 with zero bytes).
fn is_plain(bytes: &[u8]) -> bool {
    !bytes.iter().any(|&b| b == b'"' || b == b'\r' || b == 0)
}

fn trim(b: &[u8]) -> &[u8] {
    b.trim_ascii()
}

/// Read from `f` until `buf` holds at least `want` bytes or the file ends; `true` at the end.
/// Reads straight into `buf`'s spare capacity.
fn fill(f: &mut impl Read, buf: &mut Vec<u8>, want: usize) -> std::io::Result<bool> {
    while buf.len() < want {
        let need = (want - buf.len()) as u64;
        if f.by_ref().take(need).read_to_end(buf)? == 0 {
            return Ok(true);
        }
    }
    Ok(false)
}

/// The writer thread of [`stream`]: each chunk's parts appended to `w` and flushed to the
/// disk, their buffers then emptied into `spare` for the next pieces.
fn write_parts(
    rx: &std::sync::mpsc::Receiver<Vec<Vec<u8>>>,
    w: &mut std::fs::File,
    spare: &Spare,
) -> std::io::Result<()> {
    for parts in rx {
        for p in &parts {
            w.write_all(p)?;
        }
        w.sync_data()?;
        let mut pool = spare
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        for mut p in parts {
            p.clear();
            pool.push(p);
        }
    }
    Ok(())
}

/// `Ok(None)`: not plain, nothing written (the caller takes the one-piece path).
fn stream(
    input: &Path,
    out: &Path,
    cfg: &FlightConfig,
    read: LaunchRead,
    chunk_bytes: usize,
) -> Result<Option<Flown>, DataError> {
    let read_err = |e: std::io::Error| DataError::file(input, format!("cannot read: {e}"));
    safe_write::note_input(input);
    let mut file = std::fs::File::open(input).map_err(read_err)?;
    let mut buf: Vec<u8> = Vec::with_capacity(chunk_bytes + PIECE_BYTES);
    // The header: the first line.
    let mut eof = false;
    let head_end = loop {
        if let Some(i) = buf.iter().position(|&b| b == b'\n') {
            break i + 1;
        }
        if eof {
            break buf.len();
        }
        let want = buf.len() + PIECE_BYTES;
        eof = fill(&mut file, &mut buf, want).map_err(read_err)?;
    };
    let Some(headers) = plain_headers(&buf[..head_end]) else {
        return Ok(None);
    };
    let (source, launch) = launch_columns(input, &headers, read.source)?;
    let plan = Plan {
        width: headers.len(),
        launch,
        prefix: source.prefix(),
        layout: OutputLayout::new(&headers, cfg.ground.is_some()),
    };
    buf.drain(..head_end);
    let tmp = Temporary::create(out)?;
    let mut w = tmp
        .file
        .try_clone()
        .map_err(|e| DataError::file(out, format!("cannot write: {e}")))?;
    // Output buffers the writer has written, for the next pieces: filled again, they are not
    // fresh pages to fault in and clear (a 24 MB output was 6,000 such faults).
    let spare: Spare = std::sync::Mutex::new(Vec::new());
    let written = std::thread::scope(|scope| {
        let (tx, rx) = std::sync::mpsc::sync_channel::<Vec<Vec<u8>>>(2);
        let spare = &spare;
        // Each chunk's rows are written and then flushed to the disk here, while the next
        // chunk flies, so that the commit's `fsync` has only the last chunk left to wait for.
        let writer = scope.spawn(move || write_parts(&rx, &mut w, spare));
        let run = (|| -> Result<Option<(usize, Vec<LeftOut>)>, DataError> {
            if tx.send(vec![plan.layout.header_line()]).is_err() {
                return Ok(Some((0, Vec::new())));
            }
            let (mut line, mut shots) = (2usize, 0usize);
            let mut left_out = Vec::new();
            loop {
                if !eof {
                    eof = fill(&mut file, &mut buf, chunk_bytes).map_err(read_err)?;
                }
                let end = if eof {
                    buf.len()
                } else {
                    match buf.iter().rposition(|&b| b == b'\n') {
                        Some(i) => i + 1,
                        None => {
                            // A line longer than the chunk: read on.
                            let want = buf.len() + chunk_bytes;
                            eof = fill(&mut file, &mut buf, want).map_err(read_err)?;
                            continue;
                        }
                    }
                };
                let chunk = &buf[..end];
                if !is_plain(chunk) {
                    return Ok(None);
                }
                let pieces = fly_chunk(&plan, cfg, chunk, spare);
                let mut parts = Vec::with_capacity(pieces.len());
                for p in pieces {
                    if !take_piece(input, &plan, read.strict, line, &mut left_out, &p)? {
                        return Ok(None);
                    }
                    line += p.newlines;
                    shots += p.shots;
                    parts.push(p.bytes);
                }
                if tx.send(parts).is_err() {
                    break;
                }
                buf.drain(..end);
                if eof && buf.is_empty() {
                    break;
                }
            }
            refuse_when_unusable(input, &left_out, shots)?;
            Ok(Some((shots, left_out)))
        })();
        drop(tx);
        let wrote = writer.join().expect("the writer thread does not panic");
        (run, wrote)
    });
    match written {
        (Ok(Some((shots, left_out))), Ok(())) => {
            tmp.commit()?;
            Ok(Some(Flown {
                shots,
                source,
                left_out,
            }))
        }
        (Ok(None), _) => Ok(None),
        (Err(e), _) => Err(e),
        (Ok(Some(_)), Err(e)) => Err(DataError::file(out, format!("cannot write: {e}"))),
    }
}

/// The header line's names, or `None` when the line is not plain (the one-piece path reads it).
fn plain_headers(head: &[u8]) -> Option<Vec<String>> {
    match std::str::from_utf8(head) {
        Ok(t) if is_plain(head) && !t.starts_with('\u{feff}') && !trim(head).is_empty() => Some(
            t.trim_end_matches('\n')
                .split(',')
                .map(|h| h.trim_ascii().to_string())
                .collect(),
        ),
        _ => None,
    }
}

/// Take the stops and bad rows of piece `p`, whose first line is `line` of the file: `false`
/// when it is not plain CSV (the file goes the one-piece way), an error for a row of the wrong
/// width, or (under `strict`) for its first bad row; else its bad rows go to `left_out`.
fn take_piece(
    input: &Path,
    plan: &Plan,
    strict: bool,
    line: usize,
    left_out: &mut Vec<LeftOut>,
    p: &Piece,
) -> Result<bool, DataError> {
    let first_bad = p.bad.first().map(|b| b.0);
    match &p.stop {
        None => {}
        Some(Stop::NotPlain) => return Ok(false),
        Some(Stop::Bad(at, bad)) if !strict || first_bad.is_none_or(|b| *at < b) => {
            return Err(bad_row(input, plan, line + at, bad));
        }
        Some(Stop::Bad(..)) => {}
    }
    for (at, bad) in &p.bad {
        let e = bad_row(input, plan, line + at, bad);
        if strict {
            return Err(e);
        }
        push_bad(left_out, line + at, e);
    }
    Ok(true)
}

fn bad_row(input: &Path, plan: &Plan, line: usize, bad: &Bad) -> DataError {
    match bad {
        Bad::Width(n) => DataError::at(
            input,
            Some(line),
            None,
            crate::line_index::field_count_message(*n as u64, plan.width as u64),
        ),
        Bad::Cell(k, cell) => DataError::at(
            input,
            Some(line),
            Some(format!("column '{}{}'", plan.prefix, LAUNCH_COLUMNS[*k])),
            format!("{} is not a finite number", crate::data::quote_cell(cell)),
        ),
        Bad::Measured(k, message) => DataError::at(
            input,
            Some(line),
            Some(format!("column '{}'", FLIGHT_COLUMNS[*k])),
            message.clone(),
        ),
        Bad::Flight(e) => flight_error_at(input, line, plan.prefix, e),
    }
}

/// Cut `chunk` (whole lines) into pieces at line starts and work them in parallel, in order.
fn fly_chunk(plan: &Plan, cfg: &FlightConfig, chunk: &[u8], spare: &Spare) -> Vec<Piece> {
    split_at_line_ends(chunk, PIECE_BYTES)
        .par_iter()
        .map(|p| fly_piece(plan, cfg, p, spare))
        .collect()
}

/// Written output buffers, emptied, for the next pieces to fill.
type Spare = std::sync::Mutex<Vec<Vec<u8>>>;

/// Parse, fly and format one piece of whole lines. A row that cannot be used is left out and
/// listed in [`Piece::bad`] (parse errors and flight errors in line order); a row of the wrong
/// width stops the piece.
fn fly_piece(plan: &Plan, cfg: &FlightConfig, bytes: &[u8], spare: &Spare) -> Piece {
    let newlines = bytes.iter().filter(|&&b| b == b'\n').count();
    let mut piece = Piece {
        bytes: Vec::new(),
        newlines,
        shots: 0,
        stop: None,
        bad: Vec::new(),
    };
    if std::str::from_utf8(bytes).is_err() {
        piece.stop = Some(Stop::NotPlain);
        return piece;
    }
    let w = plan.width;
    // Field spans of every row (w per row), the row's 0-based line in the piece, its launch.
    let mut spans: Vec<(u32, u32)> = Vec::with_capacity(newlines * w + w);
    let mut rows: Vec<usize> = Vec::with_capacity(newlines + 1);
    let mut launches: Vec<FlightLaunch> = Vec::with_capacity(newlines + 1);
    let mut parse_stop: Option<(usize, Bad)> = None;
    let mut pos = 0usize;
    for (li, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line_start = pos;
        pos += raw.len() + 1;
        if raw.is_empty() {
            continue;
        }
        let first = spans.len();
        let mut at = line_start;
        for field in raw.split(|&b| b == b',') {
            let t = trim(field);
            let s = at + (t.as_ptr() as usize - field.as_ptr() as usize);
            spans.push((s as u32, (s + t.len()) as u32));
            at += field.len() + 1;
        }
        let n = spans.len() - first;
        if n != w {
            spans.truncate(first);
            parse_stop = Some((li, Bad::Width(n)));
            break;
        }
        let cells = &spans[first..];
        let mut v = [0.0; 5];
        let mut bad = None;
        for (k, col) in plan.launch.iter().enumerate() {
            if let Some(i) = *col {
                let (s, e) = cells[i];
                let cell = &bytes[s as usize..e as usize];
                // Valid UTF-8 (checked above) split at ASCII bytes.
                let text = std::str::from_utf8(cell).unwrap_or("");
                match parse_f64(text) {
                    Some(x) if x.is_finite() => v[k] = x,
                    _ => {
                        bad = Some(Bad::Cell(k, text.to_string()));
                        break;
                    }
                }
            }
        }
        if bad.is_none() {
            for &(k, i) in &plan.layout.measured {
                let (s, e) = cells[i];
                let text = std::str::from_utf8(&bytes[s as usize..e as usize]).unwrap_or("");
                if let Err(m) = measured_flight_value(k, text) {
                    bad = Some(Bad::Measured(k, m.to_string()));
                    break;
                }
            }
        }
        if let Some(b) = bad {
            spans.truncate(first);
            piece.bad.push((li, b));
            continue;
        }
        rows.push(li);
        launches.push(FlightLaunch::from_file_units(v[0], v[1], v[2], v[3], v[4]));
    }
    let mut results = vec![Err(FlightError::NeverLands { time_limit_s: 0.0 }); launches.len()];
    fly_serial_in_hang_order(cfg, &launches, &mut results);
    for (r, res) in results.iter().enumerate() {
        if let Err(e) = res {
            piece.bad.push((rows[r], Bad::Flight(*e)));
        }
    }
    piece.bad.sort_by_key(|b| b.0);
    if let Some((li, bad)) = parse_stop {
        piece.stop = Some(Stop::Bad(li, bad));
        return piece;
    }
    piece.shots = results.iter().filter(|r| r.is_ok()).count();
    let out = spare
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
        .pop()
        .unwrap_or_default();
    piece.bytes = format_rows(plan, bytes, &spans, &results, out);
    piece
}

/// The output rows of a piece (as [`flight_csv`] writes them: no cell of a plain file needs
/// quoting).
fn format_rows(
    plan: &Plan,
    bytes: &[u8],
    spans: &[(u32, u32)],
    results: &[Result<Flight, FlightError>],
    mut out: Vec<u8>,
) -> Vec<u8> {
    let w = plan.width;
    let l = &plan.layout;
    out.reserve(bytes.len() + results.len() * 100);
    for (cells, f) in spans.chunks_exact(w).zip(results) {
        let Ok(f) = f else { continue };
        let cell = |i: usize| &bytes[cells[i].0 as usize..cells[i].1 as usize];
        let mut first = true;
        let mut sep = |out: &mut Vec<u8>| {
            if !first {
                out.push(b',');
            }
            first = false;
        };
        // Kept cells that follow one another in the input with one comma between them (no
        // padding) are copied as one run of bytes, commas included.
        let mut run: Option<(usize, u32, u32)> = None;
        for &i in &l.keep {
            let (s, e) = cells[i];
            match &mut run {
                Some((last, _, end)) if i == *last + 1 && s == *end + 1 => {
                    *last = i;
                    *end = e;
                }
                _ => {
                    if let Some((_, rs, re)) = run {
                        sep(&mut out);
                        out.extend_from_slice(&bytes[rs as usize..re as usize]);
                    }
                    run = Some((i, s, e));
                }
            }
        }
        if let Some((_, rs, re)) = run {
            sep(&mut out);
            out.extend_from_slice(&bytes[rs as usize..re as usize]);
        }
        for &k in &l.outs {
            sep(&mut out);
            if let Some(v) = flight_value(f, k) {
                push_cell(&mut out, v);
            }
        }
        for &(k, i) in &l.measured {
            sep(&mut out);
            let m = std::str::from_utf8(cell(i))
                .ok()
                .and_then(|c| measured_value(k, c));
            if let (Some(p), Some(m)) = (flight_value(f, k), m) {
                push_cell(&mut out, p - m);
            }
        }
        out.push(b'\n');
    }
    out
}

#[cfg(test)]
#[path = "stream_tests.rs"]
mod tests;
