//! The documentation runs as written: every shell command in README.md, configs/README.md,
//! CONTRIBUTING.md and docs/*.md (alphabetically) is run, in that order, in a copy of the
//! repository's tracked files (what a fresh clone holds), with `smash` on the PATH pointing at
//! the binary under test. The convention is in CONTRIBUTING.md ("Commands in the
//! documentation"):
//!
//! - a ```` ```sh ```` (or `bash`, `shell`) block is a script: it runs with `bash -e` and
//!   must succeed;
//! - in an untagged, `console` or `text` block, a line starting with `$ ` is a command (with `\` continuation
//!   lines); the lines after it, up to the next `$ ` line or the block's end, are output it must
//!   print (stdout, then stderr), in order, compared with runs of spaces collapsed;
//!   `...` or `…` on a line of its own skips any lines, and within a line matches any text;
//! - a line starting with `smash ` in such a block without `$ ` is refused (it would not run);
//! - a block preceded by `<!-- docs-run: skip: REASON -->` is not run (the reason is required).
//!
//! Files other than these are not read. A failing command names its file, line and output.
//!
//! That the guide holds together (its index, its links) is `docs_links.rs`'s test.
//!
//! Every documented command's default text fits [`MAX_COLUMNS`]: each line a `smash` command
//! prints (stdout and stderr), unless the script asks for more (`--wide`), for JSON, or pipes
//! or redirects what it prints (issue 42).

use crate::cli_support;

use std::path::Path;
use std::process::Command;

use cli_support::{doc_files, repo, SMASH};
use unicode_width::UnicodeWidthStr;

/// The widest line a command's default text may print, in display columns.
const MAX_COLUMNS: usize = 120;

/// Whether `script`'s output is commands' default text: every command of it (continuation
/// lines joined, comments and blank lines left out) a `smash` command whose output is not
/// piped, redirected, JSON or widened.
fn is_default_text(script: &str) -> bool {
    let joined = script.replace("\\\n", " ");
    let commands: Vec<&str> = joined
        .lines()
        .map(|l| l.split(" #").next().unwrap_or("").trim())
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .collect();
    !commands.is_empty()
        && commands.iter().all(|c| {
            c.starts_with("smash ")
                && !["|", ">", "--wide", "--json", "&&", ";", "$("]
                    .iter()
                    .any(|s| c.contains(s))
        })
}

/// The lines of `output` wider than [`MAX_COLUMNS`], each with its width.
fn too_wide(output: &str) -> Vec<String> {
    output
        .lines()
        .filter(|l| l.width() > MAX_COLUMNS)
        .map(|l| format!("({} columns) {l}", l.width()))
        .collect()
}

/// One command (or script) of the documentation.
#[derive(Debug)]
struct DocCommand {
    /// `FILE:LINE`.
    at: String,
    /// The script.
    script: String,
    /// Output lines it must print (empty for `sh` blocks).
    expect: Vec<String>,
}

const SKIP: &str = "<!-- docs-run: skip";

/// The commands of one markdown file.
fn commands(rel: &str, text: &str) -> Vec<DocCommand> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let Some(info) = lines[i].trim_start().strip_prefix("```") else {
            i += 1;
            continue;
        };
        let fence = lines[i].trim_start();
        let start = i + 1;
        let mut end = start;
        while end < lines.len() && !lines[end].trim_start().starts_with("```") {
            end += 1;
        }
        let skipped = i > 0 && lines[i - 1].trim_start().starts_with(SKIP);
        if skipped {
            let reason = lines[i - 1]
                .trim()
                .trim_start_matches(SKIP)
                .trim_end_matches("-->")
                .trim_start_matches(':')
                .trim();
            assert!(
                reason.len() > 10,
                "{rel}:{i}: a docs-run skip marker needs its reason: \
                 <!-- docs-run: skip: REASON -->"
            );
        }
        let body = &lines[start..end.min(lines.len())];
        let lang = info.split_whitespace().next().unwrap_or("");
        if !skipped && !fence.starts_with("````") {
            if matches!(lang, "sh" | "bash" | "shell") {
                out.push(DocCommand {
                    at: format!("{rel}:{}", start + 1),
                    script: body.join("\n"),
                    expect: Vec::new(),
                });
            } else if matches!(lang, "" | "console" | "text") {
                if let Some(k) = body.iter().position(|l| l.starts_with("smash ")) {
                    panic!(
                        "{rel}:{}: a command outside a sh block and without `$ `: write \
                         `$ {}` (its output below it) or put it in a ```sh block",
                        start + k + 1,
                        body[k]
                    );
                }
                out.extend(console_commands(rel, start, body));
            }
        }
        i = end + 1;
    }
    out
}

/// `$ ` commands of a block and the output lines each must print.
fn console_commands(rel: &str, start: usize, body: &[&str]) -> Vec<DocCommand> {
    let mut out: Vec<DocCommand> = Vec::new();
    let mut k = 0;
    while k < body.len() {
        let Some(cmd) = body[k].strip_prefix("$ ") else {
            if let Some(c) = out.last_mut() {
                c.expect.push(body[k].to_owned());
            }
            k += 1;
            continue;
        };
        let mut script = cmd.to_owned();
        let at = format!("{rel}:{}", start + k + 1);
        while script.ends_with('\\') && k + 1 < body.len() {
            k += 1;
            script.push('\n');
            script.push_str(body[k]);
        }
        out.push(DocCommand {
            at,
            script,
            expect: Vec::new(),
        });
        k += 1;
    }
    out
}

fn collapse(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Whether `line` matches the expected line `want` (`...`/`…` within it match any text).
fn line_matches(want: &str, line: &str) -> bool {
    let (want, line) = (collapse(want), collapse(line));
    let parts: Vec<&str> = want.split(['…']).flat_map(|p| p.split("...")).collect();
    if parts.len() == 1 {
        return want == line;
    }
    let mut rest = line.as_str();
    for (j, p) in parts.iter().enumerate() {
        let p = p.trim();
        if p.is_empty() {
            continue;
        }
        match rest.find(p) {
            Some(pos) if j > 0 || pos == 0 => rest = &rest[pos + p.len()..],
            _ => return false,
        }
    }
    parts.last().is_some_and(|p| p.trim().is_empty()) || rest.is_empty()
}

/// The first expected line the output does not print, in order.
fn missing_line(expect: &[String], output: &str) -> Option<String> {
    // Blank lines are layout: neither side's count.
    let lines: Vec<&str> = output.lines().filter(|l| !l.trim().is_empty()).collect();
    let mut at = 0;
    let mut loose = false;
    for want in expect {
        let w = want.trim();
        if w.is_empty() {
            continue;
        }
        if w == "..." || w == "…" {
            loose = true;
            continue;
        }
        let found = if loose {
            (at..lines.len()).find(|&j| line_matches(w, lines[j]))
        } else {
            (at < lines.len() && line_matches(w, lines[at])).then_some(at)
        };
        match found {
            Some(j) => at = j + 1,
            None => return Some(want.clone()),
        }
        loose = false;
    }
    None
}

/// The repository's tracked files copied to `dir` (a fresh clone's content, with the working
/// tree's edits).
fn copy_tracked(root: &Path, dir: &Path) {
    let o = Command::new("git")
        .args(["ls-files", "-z"])
        .current_dir(root)
        .output()
        .expect("git is needed to list the repository's tracked files");
    assert!(o.status.success(), "git ls-files failed");
    for rel in o.stdout.split(|b| *b == 0).filter(|r| !r.is_empty()) {
        let rel = std::str::from_utf8(rel).unwrap();
        let (from, to) = (root.join(rel), dir.join(rel));
        if !from.is_file() {
            continue; // deleted in the working tree
        }
        std::fs::create_dir_all(to.parent().unwrap()).unwrap();
        std::fs::copy(&from, &to).unwrap();
    }
}

#[test]
fn documented_commands_run_as_written() {
    let root = repo("");
    let root = root.canonicalize().unwrap();
    let clone = tempfile::tempdir().unwrap();
    copy_tracked(&root, clone.path());
    let bin = tempfile::tempdir().unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(SMASH, bin.path().join("smash")).unwrap();
    let path = format!(
        "{}:{}",
        bin.path().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let mut ran = 0;
    let mut wide = Vec::new();
    for file in doc_files(&root) {
        let rel = file.strip_prefix(&root).unwrap().display().to_string();
        let text = std::fs::read_to_string(&file).unwrap();
        for c in commands(&rel, &text) {
            let started = std::time::Instant::now();
            let o = Command::new("bash")
                .args(["-e", "-o", "pipefail", "-c", &c.script])
                .current_dir(clone.path())
                .env("PATH", &path)
                .output()
                .unwrap();
            let output = format!(
                "{}{}",
                String::from_utf8_lossy(&o.stdout),
                String::from_utf8_lossy(&o.stderr)
            );
            assert!(
                o.status.success(),
                "{}: the documented command failed ({}):\n{}\n--- output:\n{output}",
                c.at,
                o.status,
                c.script
            );
            if let Some(line) = missing_line(&c.expect, &output) {
                panic!(
                    "{}: the documented output does not match the run; this line is not \
                     printed (in order):\n{line}\n--- command:\n{}\n--- output:\n{output}",
                    c.at, c.script
                );
            }
            if is_default_text(&c.script) {
                wide.extend(
                    too_wide(&output)
                        .into_iter()
                        .map(|l| format!("{}: {l}", c.at)),
                );
            }
            eprintln!("{}: {:.1} s", c.at, started.elapsed().as_secs_f64());
            ran += 1;
        }
    }
    assert!(ran > 10, "only {ran} documented commands found");
    assert!(
        wide.is_empty(),
        "documented commands print lines wider than {MAX_COLUMNS} columns:\n{}",
        wide.join("\n")
    );
}

#[test]
fn the_runner_reads_blocks_markers_and_outputs() {
    let md = "text\n```sh\nsmash a \\\n  --b\n```\n<!-- docs-run: skip: needs a cluster to run on -->\n\
              ```sh\nsbatch x\n```\n```\n$ smash c\nline one\n...\nline   three … end\n$ smash d\n```\n\
              ```toml\n$ not = \"a command\"\n```\n";
    let c = commands("x.md", md);
    let scripts: Vec<&str> = c.iter().map(|c| c.script.as_str()).collect();
    assert_eq!(scripts, ["smash a \\\n  --b", "smash c", "smash d"]);
    assert_eq!(c[1].expect, ["line one", "...", "line   three … end"]);
    assert_eq!(c[1].at, "x.md:11");
    let out = "line one\nsomething\nline three and the end\n";
    assert_eq!(missing_line(&c[1].expect, out), None);
    assert_eq!(
        missing_line(&c[1].expect, "line one\nline four\n"),
        Some("line   three … end".to_owned())
    );
    // Without `...`, lines must follow each other.
    let strict = vec!["a".to_owned(), "c".to_owned()];
    assert!(missing_line(&strict, "a\nb\nc\n").is_some());
    assert!(missing_line(&strict, "a\nc\n").is_none());
    assert!(line_matches("x = 1 …", "x = 1 and more"));
    assert!(!line_matches("x = 2 …", "x = 1 and more"));
}

#[test]
fn default_text_is_a_lone_command_without_wide_or_json() {
    assert!(is_default_text(
        "smash diagnose --club c.toml --shots s.csv"
    ));
    for s in [
        "smash diagnose --wide",
        "smash diagnose --json",
        "smash run s.toml | head",
        "smash flight > f.txt",
        "ls\nsmash x",
        "cat README.md",
    ] {
        assert!(!is_default_text(s), "{s}");
    }
    assert!(is_default_text(
        "# two\nsmash a \\\n  --b  # the first\n\nsmash c  # a comment > no redirect"
    ));
    assert_eq!(too_wide(&format!("{}\nshort\n", "±".repeat(121))).len(), 1);
    assert!(too_wide(&"σ".repeat(120)).is_empty());
    assert_eq!(too_wide(&format!("shots: {}", "x".repeat(120))).len(), 1);
}

#[test]
#[should_panic(expected = "needs its reason")]
fn a_skip_marker_without_a_reason_is_refused() {
    commands("x.md", "<!-- docs-run: skip -->\n```sh\nls\n```\n");
}
