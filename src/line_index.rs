//! Line numbers of byte offsets, whatever a file's line ends: `\n` (Unix), `\r\n` (Windows, as
//! Excel and Python's `csv` module write) or a lone `\r` (classic Mac OS, and some exporters).
//!
//! The `csv` crate ends a record at any of the three, but its positions' `line()` counts only
//! `\n`: a CRLF file is reported a line off after a blank line, and every record of a CR-only
//! file is on "line 1". Every CSV reader that names a line in its messages takes the line from
//! the record's byte offset through [`LineIndex`] (a whole file in memory) or [`LineTracker`] (a
//! file streamed through the reader) instead, and words the crate's errors through
//! [`csv_message`]. A bottom layer: the data readers, the shard merge and the flight's coefficient
//! tables all use it (`data::csv_error_at` turns the pair into a file error).

use std::cell::RefCell;
use std::collections::VecDeque;
use std::io::Read;

/// The 1-based line of a record the `csv` crate reports at a position.
pub trait RecordLines {
    /// Line of the record (or error) at `p`, counting `\n`, `\r\n` and lone `\r` alike.
    fn line_of(&self, p: &csv::Position) -> usize;
}

/// The one wording of a `csv` reading error, without the crate's own (miscounted) line: a row
/// whose field count differs from the header's, or a field that is not UTF-8 text.
pub fn csv_message(e: &csv::Error) -> String {
    match e.kind() {
        csv::ErrorKind::UnequalLengths {
            expected_len, len, ..
        } => field_count_message(*len, *expected_len),
        csv::ErrorKind::Utf8 { err, .. } => format!(
            "field {} is not valid UTF-8 text (save the file as UTF-8)",
            err.field() + 1
        ),
        csv::ErrorKind::Io(err) => format!("cannot read: {err}"),
        _ => e.to_string(),
    }
}

/// A row with `len` fields under a header of `header` fields (also for readers that count the
/// fields themselves).
pub fn field_count_message(len: u64, header: u64) -> String {
    format!("found a row with {len} field(s), but the header has {header} (one per column)")
}

/// Where the line breaks of a text are.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LineIndex<'a> {
    bytes: &'a [u8],
    /// Byte offset of the last byte of each line break (the `\n` of `\r\n`), ascending.
    ends: Vec<usize>,
    /// The comment byte of the `csv` reader, if it skips comment lines.
    comment: Option<u8>,
}

impl<'a> LineIndex<'a> {
    /// Index the line breaks of `bytes`: every `\n`, and every `\r` not followed by `\n`.
    pub fn new(bytes: &'a [u8]) -> Self {
        let ends = bytes
            .iter()
            .enumerate()
            .filter(|&(i, &b)| b == b'\n' || (b == b'\r' && bytes.get(i + 1) != Some(&b'\n')))
            .map(|(i, _)| i)
            .collect();
        Self {
            bytes,
            ends,
            comment: None,
        }
    }

    /// The same for a reader that skips lines starting with `comment`.
    pub fn with_comments(mut self, comment: u8) -> Self {
        self.comment = Some(comment);
        self
    }

    /// 1-based line of the record (or error) the `csv` crate reports at `p`. The reader
    /// reports where it started reading, which may be before the line breaks, blank lines and
    /// comment lines it skipped to reach the record: those are skipped here too.
    pub fn line_of(&self, p: &csv::Position) -> usize {
        let start = self.record_start(usize::try_from(p.byte()).unwrap_or(usize::MAX));
        self.ends.partition_point(|&e| e < start) + 1
    }

    /// The first byte at or after `i` that is not a line break or inside a comment line.
    fn record_start(&self, mut i: usize) -> usize {
        let b = self.bytes;
        loop {
            while i < b.len() && (b[i] == b'\n' || b[i] == b'\r') {
                i += 1;
            }
            if i >= b.len() || Some(b[i]) != self.comment {
                return i;
            }
            // A comment line: on to the end of its line break.
            let k = self.ends.partition_point(|&e| e < i);
            match self.ends.get(k) {
                Some(&e) => i = e + 1,
                None => return b.len(),
            }
        }
    }

    /// Number of line breaks.
    pub fn breaks(&self) -> usize {
        self.ends.len()
    }
}

impl RecordLines for LineIndex<'_> {
    fn line_of(&self, p: &csv::Position) -> usize {
        LineIndex::line_of(self, p)
    }
}

/// How a file is UTF-16 text, when it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Utf16 {
    /// Little-endian (`UTF-16LE`, what Windows writes) rather than big-endian.
    pub little_endian: bool,
    /// Recognised by its byte-order mark (0xFF 0xFE or 0xFE 0xFF, two bytes to skip).
    pub bom: bool,
}

impl Utf16 {
    /// The encoding's name as `iconv` takes it.
    pub fn name(self) -> &'static str {
        if self.little_endian {
            "UTF-16LE"
        } else {
            "UTF-16BE"
        }
    }

    /// How it was recognised, for a note (`UTF-16 text (little-endian, without a byte-order
    /// mark)`).
    pub fn describe(self) -> &'static str {
        match (self.little_endian, self.bom) {
            (true, true) => "UTF-16 text (little-endian, with a byte-order mark)",
            (false, true) => "UTF-16 text (big-endian, with a byte-order mark)",
            (true, false) => "UTF-16 text (little-endian, without a byte-order mark)",
            (false, false) => "UTF-16 text (big-endian, without a byte-order mark)",
        }
    }

    /// The one-line refusal of a reader that takes UTF-8 only: what the file looks like and
    /// how to convert it (ASCII saved as UTF-16 is valid UTF-8 with a zero byte beside every
    /// character, so without this the reader names the header `C\0l\0u\0b…` as unknown).
    pub fn refusal(self) -> String {
        let looks = if self.bom {
            format!(
                "the file is {} text (it starts with a byte-order mark)",
                self.name()
            )
        } else {
            format!(
                "the file looks like {} text without a byte-order mark (a zero byte beside \
                 every character)",
                self.name()
            )
        };
        format!(
            "{looks}; smash reads UTF-8: convert it, e.g. `iconv -f {} -t UTF-8 FILE > NEW`, or \
             save it as \"CSV UTF-8\"",
            self.name()
        )
    }
}

/// Whether `bytes` are UTF-16 text: a byte-order mark (0xFF 0xFE little-endian, 0xFE 0xFF
/// big-endian), or, without one, a zero byte in most odd (little-endian) or most even
/// (big-endian) places of the first 256 bytes, as ASCII text saved as UTF-16 has (no UTF-8 text
/// holds zero bytes there: a zero byte is the character NUL).
pub fn utf16(bytes: &[u8]) -> Option<Utf16> {
    if bytes.starts_with(b"\xFF\xFE") || bytes.starts_with(b"\xFE\xFF") {
        return Some(Utf16 {
            little_endian: bytes[0] == 0xFF,
            bom: true,
        });
    }
    let head = &bytes[..bytes.len().min(256)];
    if head.len() < 4 {
        return None;
    }
    let zeros = |parity: usize| {
        head.iter()
            .skip(parity)
            .step_by(2)
            .filter(|&&b| b == 0)
            .count()
    };
    let pairs = head.len() / 2;
    let (even, odd) = (zeros(0), zeros(1));
    let without = |little_endian| {
        Some(Utf16 {
            little_endian,
            bom: false,
        })
    };
    if 10 * odd >= 7 * pairs && 10 * even <= pairs {
        without(true)
    } else if 10 * even >= 7 * pairs && 10 * odd <= pairs {
        without(false)
    } else {
        None
    }
}

/// `bytes` as text; otherwise the 1-based line of the first byte that is not UTF-8 and a message
/// naming its place on the line (a file saved as Latin-1, say), or, for UTF-16 text, line 1 and
/// [`Utf16::refusal`].
pub fn utf8_text(bytes: Vec<u8>) -> Result<String, (usize, String)> {
    if let Some(u) = utf16(&bytes) {
        return Err((1, u.refusal()));
    }
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let bytes = e.as_bytes();
        let index = LineIndex::new(bytes);
        let line = index.ends.partition_point(|&b| b < at) + 1;
        let line_start = match line {
            1 => 0,
            _ => index.ends[line - 2] + 1,
        };
        (
            line,
            format!(
                "byte {} of the line is not valid UTF-8 text (save the file as UTF-8)",
                at - line_start + 1
            ),
        )
    })
}

/// A reader that notes the line breaks of what passes through it, for files too large to hold
/// (a shard's face maps): the same lines as [`LineIndex`] (no comment lines), in memory only the
/// breaks not yet passed. Positions must be asked in ascending order, as a `csv` reader meets
/// its records.
pub struct LineTracker<R> {
    inner: R,
    state: RefCell<Breaks>,
}

/// The line breaks read so far.
#[derive(Default)]
struct Breaks {
    /// Bytes read.
    read: u64,
    /// Breaks dropped: they end before the last position asked.
    passed: usize,
    /// First and last byte of each break kept, ascending.
    kept: VecDeque<(u64, u64)>,
    /// A `\r` as the last byte read: a break, whether `\r\n` is decided by the next byte.
    cr: Option<u64>,
}

impl<R: Read> LineTracker<R> {
    /// Track the lines of `inner`.
    pub fn new(inner: R) -> Self {
        Self {
            inner,
            state: RefCell::new(Breaks::default()),
        }
    }
}

impl<R: Read> Read for LineTracker<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        let st = self.state.get_mut();
        if n == 0 {
            if let Some(c) = st.cr.take() {
                st.kept.push_back((c, c));
            }
        }
        for (i, &b) in buf[..n].iter().enumerate() {
            let at = st.read + i as u64;
            if let Some(c) = st.cr.take() {
                if b == b'\n' {
                    st.kept.push_back((c, at));
                    continue;
                }
                st.kept.push_back((c, c));
            }
            match b {
                b'\r' => st.cr = Some(at),
                b'\n' => st.kept.push_back((at, at)),
                _ => {}
            }
        }
        st.read += n as u64;
        Ok(n)
    }
}

impl<R> RecordLines for LineTracker<R> {
    fn line_of(&self, p: &csv::Position) -> usize {
        let mut st = self.state.borrow_mut();
        let at = p.byte();
        while st.kept.front().is_some_and(|&(_, last)| last < at) {
            st.kept.pop_front();
            st.passed += 1;
        }
        // Skip the line breaks (blank lines) the reader passed over to reach the record.
        let (mut pos, mut line) = (at, st.passed + 1);
        let pending = st.cr.map(|c| (c, c));
        for &(first, last) in st.kept.iter().chain(pending.iter()) {
            if first > pos {
                break;
            }
            pos = last + 1;
            line += 1;
        }
        line
    }
}

/// `text` with every line break (`\r\n` or a lone `\r`) written as `\n`: the same lines, for
/// readers whose CSV dialect ends a comment only at `\n` (the `csv` crate's comments would
/// otherwise swallow a CR-only file from the first comment on).
pub fn normalise_line_ends(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.contains('\r') {
        return std::borrow::Cow::Borrowed(text);
    }
    std::borrow::Cow::Owned(text.replace("\r\n", "\n").replace('\r', "\n"))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The line of every record, as the index reads the `csv` crate's positions.
    fn record_lines(text: &str) -> Vec<(String, usize)> {
        let idx = LineIndex::new(text.as_bytes()).with_comments(b'#');
        let mut rdr = csv::ReaderBuilder::new()
            .has_headers(false)
            .flexible(true)
            .comment(Some(b'#'))
            .from_reader(text.as_bytes());
        rdr.records()
            .map(|r| {
                let r = r.unwrap();
                (r[0].to_string(), idx.line_of(r.position().unwrap()))
            })
            .collect()
    }

    #[test]
    fn records_are_on_their_lines_with_every_kind_of_line_end() {
        // Each record's first cell names the line it is on: blank lines, a comment line and a
        // quoted cell. (The csv crate ends a comment only at `\n`, so CR-only text with
        // comments is normalised first, as the reader that allows comments does; without
        // comments it is read as it is.)
        let lines = [
            "h,x", "l2,1", "", "l4,2", "# note", "", "", "l8,\"3\"", "l9,4",
        ];
        for end in ["\n", "\r\n", "\r"] {
            for last in ["", end] {
                for comment in [true, false] {
                    let kept: Vec<&str> = lines
                        .iter()
                        .map(|&l| {
                            if !comment && l.starts_with('#') {
                                ""
                            } else {
                                l
                            }
                        })
                        .collect();
                    let raw = kept.join(end) + last;
                    let text = if comment {
                        normalise_line_ends(&raw).into_owned()
                    } else {
                        raw
                    };
                    let got: Vec<usize> = record_lines(&text).iter().map(|g| g.1).collect();
                    assert_eq!(got, [1, 2, 4, 8, 9], "{end:?} {last:?} {comment}");
                }
            }
        }
    }

    #[test]
    fn normalised_text_keeps_every_line() {
        let text = "a\r\nb\rc\n\r\rd";
        let n = normalise_line_ends(text);
        assert_eq!(n, "a\nb\nc\n\n\nd");
        assert_eq!(
            LineIndex::new(text.as_bytes()).breaks(),
            LineIndex::new(n.as_bytes()).breaks()
        );
        assert!(matches!(
            normalise_line_ends("a\nb"),
            std::borrow::Cow::Borrowed(_)
        ));
    }

    #[test]
    fn a_mixed_file_counts_each_break_once() {
        let text = "h\r\na\rb\nc\r\n\rd";
        let got: Vec<usize> = record_lines(text).iter().map(|g| g.1).collect();
        assert_eq!(got, [1, 2, 3, 4, 6]);
        assert_eq!(LineIndex::new(text.as_bytes()).breaks(), 5);
    }

    /// Reads at most `k` bytes at a time: breaks split across reads.
    struct Trickle<'a>(&'a [u8], usize);
    impl Read for Trickle<'_> {
        fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
            let n = self.1.min(buf.len()).min(self.0.len());
            buf[..n].copy_from_slice(&self.0[..n]);
            self.0 = &self.0[n..];
            Ok(n)
        }
    }

    #[test]
    fn a_streamed_file_has_the_lines_of_the_whole_one() {
        let lines = [
            "h,x", "l2,1", "", "l4,2", "", "", "l7,\"3\"", "l8,4,5", "l9,6",
        ];
        for end in ["\n", "\r\n", "\r"] {
            for last in ["", end] {
                let text = lines.join(end) + last;
                let whole = LineIndex::new(text.as_bytes());
                for k in [1, 2, 3, 64] {
                    let mut rdr = csv::ReaderBuilder::new()
                        .has_headers(false)
                        .from_reader(LineTracker::new(Trickle(text.as_bytes(), k)));
                    let mut rec = csv::StringRecord::new();
                    let mut got = Vec::new();
                    loop {
                        match rdr.read_record(&mut rec) {
                            Ok(false) => break,
                            Ok(true) => {
                                let p = rec.position().unwrap();
                                got.push(rdr.get_ref().line_of(p));
                                assert_eq!(got.last(), Some(&whole.line_of(p)));
                            }
                            Err(e) => {
                                let p = e.position().unwrap();
                                got.push(rdr.get_ref().line_of(p));
                                assert!(csv_message(&e).starts_with("found a row with 3 field(s)"));
                            }
                        }
                    }
                    assert_eq!(got, [1, 2, 4, 7, 8, 9], "{end:?} {last:?} {k}");
                }
            }
        }
    }

    #[test]
    fn a_bad_byte_names_its_field() {
        let bytes = b"a,b\r\n1,x\xff\r\n";
        let idx = LineIndex::new(bytes);
        let mut rdr = csv::Reader::from_reader(&bytes[..]);
        // The header first, as every reader does (a record read before it would be reported
        // at the header's position).
        assert_eq!(rdr.headers().unwrap().len(), 2);
        let e = rdr.records().next().unwrap().unwrap_err();
        assert_eq!(idx.line_of(e.position().unwrap()), 2);
        assert_eq!(
            csv_message(&e),
            "field 2 is not valid UTF-8 text (save the file as UTF-8)"
        );
    }
}
