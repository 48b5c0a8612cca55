//! Word wrapping of long report lines, so that text reports stay within their width (100 or
//! 120 columns). Below the reports and the commands' own text (`infer`), so every layer may
//! wrap.
//! Lines are split at spaces only, and counted in characters (the reports' symbols, such as
//! `±`, `σ` and `×`, are one column wide).

/// `text` wrapped at spaces into lines of at most `width` columns (a longer word stands alone),
/// each ending in a newline, the continuation lines indented by `indent` spaces more than
/// `text`'s own leading spaces.
pub fn wrap(text: &str, width: usize, indent: usize) -> String {
    let lead = text.len() - text.trim_start_matches(' ').len();
    let cont = " ".repeat(lead + indent);
    let mut out = String::new();
    let mut line = " ".repeat(lead);
    let mut empty = true;
    for word in text.trim_start_matches(' ').split(' ') {
        if !empty && line.chars().count() + 1 + word.chars().count() > width {
            out.push_str(&line);
            out.push('\n');
            line.clone_from(&cont);
        } else if !empty {
            line.push(' ');
        }
        line.push_str(word);
        empty = false;
    }
    out.push_str(&line);
    out.push('\n');
    out
}

#[cfg(test)]
mod tests {
    use super::wrap;

    #[test]
    fn wraps_at_spaces_with_an_indent() {
        assert_eq!(wrap("aa bb cc dd", 5, 2), "aa bb\n  cc\n  dd\n");
        assert_eq!(wrap("  aa bb cc", 7, 2), "  aa bb\n    cc\n");
        assert_eq!(wrap("short", 99, 2), "short\n");
        assert_eq!(
            wrap("averyverylongword x", 5, 2),
            "averyverylongword\n  x\n"
        );
    }
}
