//! Line numbers of byte offsets, whatever a file's line ends: `\n` (Unix), `\r\n` (Windows, as
//! Excel and Python's `csv` module write) or a lone `\r` (classic Mac OS, and some exporters).
//!
//! The `csv` crate ends a record at any of the three, but its positions' `line()` counts only
//! `\n`: a CRLF file is reported a line off after a blank line, and every record of a CR-only
//! file is on "line 1". Every CSV reader that names a line in its messages takes the line from
//! the record's byte offset through [`LineIndex`] instead. A bottom layer: the data readers and
//! the flight's coefficient tables both use it.

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
}
