//! What the text reports share so that they fit a terminal: the width prose
//! is wrapped to, tables that move from side by side to one above the other when they would
//! not fit, and a shell command laid out on lines of its own.
//!
//! The default text fits a terminal of 100 columns (prose is wrapped at [`WIDTH`]; tables are
//! laid out to fit); `--wide` prints the full tables, each row on one line, as wide as they need.
//! JSON and the HTML reports always carry everything.

use crate::report::{error_table_text, error_tables_side_by_side};
use crate::stats::ErrorTable;

/// The widest line of the default text reports' prose, in columns: under 100, as the reports
/// wrapped before.
pub const WIDTH: usize = 99;

/// Every line of `text` longer than [`WIDTH`] wrapped at spaces, its continuation lines
/// indented two spaces more than its own; shorter lines unchanged.
pub fn wrap_long(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let body = line.strip_suffix('\n').unwrap_or(line);
        if body.chars().count() > WIDTH {
            out.push_str(&crate::report::wrap::wrap(body, WIDTH, 2));
            if !line.ends_with('\n') {
                out.pop();
            }
        } else {
            out.push_str(line);
        }
    }
    out
}

/// The errors before and after, side by side when they fit [`WIDTH`] (or `wide`), else one
/// above the other, each under its title.
pub fn before_after(
    before: &ErrorTable,
    after: &ErrorTable,
    titles: (&str, &str),
    wide: bool,
) -> String {
    let side = error_tables_side_by_side(before, after, titles);
    if wide || side.lines().all(|l| l.chars().count() <= WIDTH) {
        return side;
    }
    format!(
        "{}:\n{}\n{}:\n{}",
        titles.0,
        error_table_text(before),
        titles.1,
        error_table_text(after)
    )
}

/// `word` quoted for a POSIX shell when it holds anything but safe characters.
pub fn shell_word(word: &str) -> String {
    let safe = |c: char| c.is_ascii_alphanumeric() || "-_./,=@:+%".contains(c);
    if !word.is_empty() && word.chars().all(safe) {
        word.to_owned()
    } else {
        format!("'{}'", word.replace('\'', r"'\''"))
    }
}

/// A command of `words` laid out on lines of its own for copying into a shell: indented by
/// `indent`, a flag kept on the line of its value, the line broken with ` \` before a flag
/// that would pass [`WIDTH`]. A value too long for a line of its own (a comma-separated list)
/// is double-quoted with a space after each comma and broken at those spaces: the commands
/// trim the items of such lists.
pub fn shell_command(indent: &str, words: &[String]) -> String {
    // A flag and its value are one unit.
    let mut units: Vec<(String, Option<&String>)> = Vec::new();
    let mut i = 0;
    while i < words.len() {
        let value = words
            .get(i + 1)
            .filter(|v| words[i].starts_with("--") && !v.starts_with("--") && i + 1 < words.len());
        units.push((words[i].clone(), value));
        i += if value.is_some() { 2 } else { 1 };
    }
    let cont = format!("{indent}  ");
    let mut lines: Vec<String> = Vec::new();
    for (flag, value) in units {
        let whole = match value {
            Some(v) => format!("{flag} {v}"),
            None => flag,
        };
        let len = whole.chars().count();
        match lines.last_mut() {
            None => lines.push(format!("{indent}{whole}")),
            // Room for the unit and a ` \` after it.
            Some(last) if last.chars().count() + 1 + len + 2 <= WIDTH => {
                last.push(' ');
                last.push_str(&whole);
            }
            Some(last) => {
                last.push_str(" \\");
                let line = format!("{cont}{whole}");
                match value {
                    Some(v) if len + cont.len() + 2 > WIDTH && v.contains(',') => {
                        let flag = whole.split(' ').next().unwrap_or_default();
                        let spaced = v.split(',').collect::<Vec<_>>().join(", ");
                        let quoted = crate::report::wrap::wrap(
                            &format!("{cont}{flag} \"{spaced}\""),
                            WIDTH,
                            2,
                        );
                        lines.push(quoted.trim_end_matches('\n').to_owned());
                    }
                    _ => lines.push(line),
                }
            }
        }
    }
    let mut s = lines.join("\n");
    s.push('\n');
    s
}

/// `n` and the noun, plural unless `n` is 1: "1 group", "3 groups".
pub fn counted(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_lines_wrap_and_short_ones_stay() {
        let long = format!("{} end", "word ".repeat(30));
        let out = wrap_long(&format!("short\n{long}\n"));
        assert!(out.starts_with("short\nword word"));
        assert!(out.lines().all(|l| l.chars().count() <= WIDTH));
        assert!(out.lines().nth(2).unwrap().starts_with("  word"));
        assert_eq!(wrap_long("a\nb"), "a\nb");
    }

    #[test]
    fn a_command_breaks_before_flags_and_quotes_long_lists() {
        let words: Vec<String> = ["smash", "calibrate", "--club", "my club.toml"]
            .iter()
            .map(|w| shell_word(w))
            .collect();
        assert_eq!(
            shell_command("  ", &words),
            "  smash calibrate --club 'my club.toml'\n"
        );
        let list = (0..20)
            .map(|i| format!("name_{i}=0.{i}"))
            .collect::<Vec<_>>();
        let mut words: Vec<String> = ["smash", "calibrate", "--effects", "ball_offset"]
            .map(String::from)
            .to_vec();
        words.extend(["--delivery-noise".to_owned(), list.join(",")]);
        let out = shell_command("", &words);
        assert!(out.lines().all(|l| l.chars().count() <= WIDTH), "{out}");
        assert!(
            out.starts_with(
                "smash calibrate --effects ball_offset \\\n  --delivery-noise \"name_0=0.0, "
            ),
            "{out}"
        );
        assert!(out.trim_end().ends_with("name_19=0.19\""), "{out}");
        // Every item is there, in order, once the shell joins the lines and the command trims.
        let joined = out.replace(" \\\n", " ").replace('\n', " ");
        let items: Vec<String> = joined
            .split_once('"')
            .unwrap()
            .1
            .trim_end()
            .trim_end_matches('"')
            .split(',')
            .map(|s| s.trim().to_owned())
            .collect();
        assert_eq!(items, list);
    }
}
