//! Export bytes to text: any number of UTF-8 byte-order marks, and bytes that are not UTF-8
//! read as Windows-1252 (the code page of spreadsheets saved on Windows, where `°` is the single
//! byte 0xB0), each such byte counted and the first one's line named, and UTF-16 text, with or
//! without a byte-order mark, read as such. A byte that Windows-1252 leaves undefined, or broken
//! UTF-16, is refused in one line.

use std::borrow::Cow;
use std::path::Path;

use crate::data::DataError;

const UTF8_BOM: &[u8] = b"\xEF\xBB\xBF";

/// A UTF-8 byte-order mark read as Windows-1252 (`ï»¿`) and written again as UTF-8: what a
/// tool that does not know the mark leaves at the start of a re-saved export.
const MANGLED_BOM: &[u8] = "\u{ef}\u{bb}\u{bf}".as_bytes();

/// The export as text, and a note when some bytes were read as Windows-1252.
pub(super) fn decode<'b>(
    path: &Path,
    bytes: &'b [u8],
) -> Result<(Cow<'b, str>, Option<String>), DataError> {
    if let Some((encoding, skip, how)) = utf16(bytes) {
        let (text, bad) = encoding.decode_without_bom_handling(&bytes[skip..]);
        if bad {
            return Err(DataError::at(
                path,
                Some(1),
                None,
                format!(
                    "{how} that is not valid UTF-16 (an odd number of bytes, or a broken \
                     surrogate); save the export as CSV in UTF-8"
                ),
            ));
        }
        let text = text.trim_start_matches('\u{feff}').to_owned();
        return Ok((Cow::Owned(text), Some(format!("{how}: read as such"))));
    }
    let mut body = bytes;
    let mut mangled = false;
    loop {
        if let Some(rest) = body.strip_prefix(UTF8_BOM) {
            body = rest;
        } else if let Some(rest) = body.strip_prefix(MANGLED_BOM) {
            (body, mangled) = (rest, true);
        } else {
            break;
        }
    }
    let mangled_note = mangled.then(|| {
        "the file starts with a byte-order mark saved twice ('ï»¿': read as Windows-1252 and \
         saved again as UTF-8): dropped"
            .to_owned()
    });
    if let Ok(text) = std::str::from_utf8(body) {
        return Ok((Cow::Borrowed(text), mangled_note));
    }
    let mut text = String::with_capacity(body.len() + 16);
    let mut converted = 0usize;
    let mut first: Option<(usize, u8, char)> = None;
    for chunk in body.utf8_chunks() {
        text.push_str(chunk.valid());
        for &b in chunk.invalid() {
            let line = 1 + text.matches('\n').count();
            let c = windows_1252(b);
            if c.is_control() {
                return Err(DataError::at(
                    path,
                    Some(line),
                    None,
                    format!(
                        "byte 0x{b:02X} is neither UTF-8 nor a Windows-1252 character; save the \
                         export as CSV in UTF-8"
                    ),
                ));
            }
            converted += 1;
            first.get_or_insert((line, b, c));
            text.push(c);
        }
    }
    let (line, b, c) = first.expect("not UTF-8, so at least one byte was converted");
    let mut note = format!(
        "{converted} byte(s) are not UTF-8 and were read as Windows-1252 (the first on line \
         {line}: 0x{b:02X} = '{c}')"
    );
    if let Some(m) = mangled_note {
        note = format!("{m}; {note}");
    }
    Ok((Cow::Owned(text), Some(note)))
}

/// [`crate::line_index::utf16`] as the encoding to decode with, the bytes to skip and how the
/// text was recognised, for the note.
fn utf16(bytes: &[u8]) -> Option<(&'static encoding_rs::Encoding, usize, &'static str)> {
    let u = crate::line_index::utf16(bytes)?;
    let encoding = if u.little_endian {
        encoding_rs::UTF_16LE
    } else {
        encoding_rs::UTF_16BE
    };
    Some((encoding, if u.bom { 2 } else { 0 }, u.describe()))
}

/// The character a Windows-1252 byte stands for (WHATWG's table: the five bytes the code page
/// leaves undefined come out as C1 control characters).
fn windows_1252(b: u8) -> char {
    let byte = [b];
    let (s, _) = encoding_rs::WINDOWS_1252.decode_without_bom_handling(&byte);
    s.chars().next().unwrap_or('\u{fffd}')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boms_and_windows_1252() {
        let p = Path::new("x.csv");
        let (t, n) = decode(p, b"\xEF\xBB\xBF\xEF\xBB\xBFsep=,\n").unwrap();
        assert_eq!(t, "sep=,\n");
        assert!(n.is_none());
        // A mark read as Windows-1252 and saved again as UTF-8 (FSX Play sessions re-saved).
        let (t, n) = decode(p, b"\xC3\xAF\xC2\xBB\xC2\xBFShot Number,Club\n").unwrap();
        assert_eq!(t, "Shot Number,Club\n");
        assert!(n.unwrap().contains("saved twice"));
        let (t, n) = decode(p, b"a,b\nSwing H (\xB0),\xE2\x80\xB3\n").unwrap();
        assert_eq!(t, "a,b\nSwing H (\u{b0}),\u{2033}\n");
        let n = n.unwrap();
        assert!(
            n.contains("1 byte(s)") && n.contains("line 2") && n.contains("0xB0"),
            "{n}"
        );
        let e = decode(p, b"a\nb\n\x81\n").unwrap_err().to_string();
        assert!(e.contains(":3") && e.contains("0x81"), "{e}");
        let (t, n) = decode(p, b"\xFF\xFEC\x00l\x00u\x00b\x00").unwrap();
        assert_eq!(t, "Club");
        assert!(n.unwrap().contains("little-endian, with a byte-order mark"));
        let (t, n) = decode(p, b"C\x00l\x00u\x00b\x00,\x00x\x00").unwrap();
        assert_eq!(t, "Club,x");
        assert!(n.unwrap().contains("without a byte-order mark"));
        let (t, _) = decode(p, b"\x00C\x00l\x00u\x00b").unwrap();
        assert_eq!(t, "Club");
        assert!(decode(p, b"\xFF\xFEa\x00b")
            .unwrap_err()
            .to_string()
            .contains("not valid UTF-16"));
    }
}
