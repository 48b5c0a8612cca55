//! The guide holds together: docs/SUMMARY.md (mdBook's index) lists every page under docs/ and
//! nothing else; every relative link of the documentation the documentation test runs
//! (`docs_run.rs`: README.md, configs/README.md, CONTRIBUTING.md, docs/*.md), outside code,
//! names a tracked file or folder, and its `#anchor` a heading of the page it points at; and
//! every page the README links to is one the documentation test runs.

use crate::cli_support;

use std::collections::{HashMap, HashSet};
use std::path::{Component, Path};
use std::process::Command;

use cli_support::{doc_files, repo};

/// `text` with the lines of fenced code blocks (and their fences) left empty: the prose.
fn outside_fences(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut open: Option<usize> = None;
    for line in text.lines() {
        let t = line.trim_start();
        let ticks = t.chars().take_while(|c| *c == '`').count();
        match open {
            None if ticks >= 3 => open = Some(ticks),
            Some(n) if ticks >= n && t[ticks..].trim().is_empty() => open = None,
            None => out.push_str(line),
            Some(_) => {}
        }
        out.push('\n');
    }
    out
}

/// `text` with its inline code spans (a run of backticks up to the next run as long) blanked,
/// line ends kept.
fn without_code_spans(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let run = |i: usize| chars[i..].iter().take_while(|c| **c == '`').count();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < chars.len() {
        if chars[i] != '`' {
            out.push(chars[i]);
            i += 1;
            continue;
        }
        let n = run(i);
        let mut j = i + n;
        while j < chars.len() && !(chars[j] == '`' && run(j) == n) {
            j += if chars[j] == '`' { run(j) } else { 1 };
        }
        if j >= chars.len() {
            out.extend(std::iter::repeat_n('`', n));
            i += n;
            continue;
        }
        out.extend(
            chars[i..j + n]
                .iter()
                .map(|c| if *c == '\n' { '\n' } else { ' ' }),
        );
        i = j + n;
    }
    out
}

/// The targets of the markdown links (and images) of `text` outside code, each with its line.
/// A code span ends within its paragraph.
fn links(text: &str) -> Vec<(usize, String)> {
    let prose: Vec<String> = outside_fences(text)
        .split("\n\n")
        .map(without_code_spans)
        .collect();
    let mut out = Vec::new();
    for (n, line) in prose.join("\n\n").lines().enumerate() {
        let mut rest = line;
        while let Some(p) = rest.find("](") {
            let t = &rest[p + 2..];
            let end = t
                .find(|c: char| c == ')' || c.is_whitespace())
                .unwrap_or(t.len());
            out.push((n + 1, t[..end].to_owned()));
            rest = &t[end..];
        }
    }
    out
}

/// The anchors of the headings of a markdown page, as GitHub (and mdBook) make them: lower case,
/// letters, digits, `-` and `_` kept, spaces made `-`, the rest dropped; a repeated one gets
/// `-1`, `-2`, ...
fn anchors(text: &str) -> HashSet<String> {
    let mut seen: HashMap<String, usize> = HashMap::new();
    let mut out = HashSet::new();
    for line in outside_fences(text).lines() {
        let hashes = line.chars().take_while(|c| *c == '#').count();
        if !(1..=6).contains(&hashes) || !line[hashes..].starts_with(' ') {
            continue;
        }
        let slug: String = line[hashes..]
            .trim()
            .to_lowercase()
            .chars()
            .filter_map(|c| match c {
                ' ' => Some('-'),
                c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
                _ => None,
            })
            .collect();
        let k = seen.entry(slug.clone()).or_insert(0);
        let anchor = if *k == 0 { slug } else { format!("{slug}-{k}") };
        *k += 1;
        out.insert(anchor);
    }
    out
}

/// `rel` (a path from the repository's root, `..` and `.` allowed) made plain, or `None` when
/// it leaves the repository.
fn normalise(rel: &Path) -> Option<String> {
    let mut parts: Vec<String> = Vec::new();
    for c in rel.components() {
        match c {
            Component::Normal(p) => parts.push(p.to_string_lossy().into_owned()),
            Component::ParentDir => {
                parts.pop()?;
            }
            Component::CurDir => {}
            _ => return None,
        }
    }
    Some(parts.join("/"))
}

/// The repository's tracked files (the index: what a commit of the working tree would hold).
fn tracked(root: &Path) -> HashSet<String> {
    let o = Command::new("git")
        .args(["ls-files"])
        .current_dir(root)
        .output()
        .expect("git is needed to list the repository's tracked files");
    assert!(o.status.success(), "git ls-files failed");
    String::from_utf8(o.stdout)
        .unwrap()
        .lines()
        .map(str::to_owned)
        .collect()
}

/// What is wrong with the link `target` of the file `from` (a path from the root), if anything:
/// a missing file or folder, or a missing heading for its anchor. Web links are not followed.
/// Returns the file it points at otherwise.
fn check_link(
    root: &Path,
    files: &HashSet<String>,
    from: &str,
    target: &str,
) -> Result<String, String> {
    if target.contains("://") || target.starts_with("mailto:") {
        return Ok(String::new());
    }
    let (path, anchor) = target.split_once('#').unwrap_or((target, ""));
    let file = if path.is_empty() {
        from.to_owned()
    } else {
        let joined = Path::new(from).parent().unwrap().join(path);
        normalise(&joined).ok_or_else(|| format!("{target}: outside the repository"))?
    };
    let folder = format!("{}/", file.trim_end_matches('/'));
    if !files.contains(&file) && !files.iter().any(|f| f.starts_with(&folder)) {
        return Err(format!("{target}: no tracked file or folder {file}"));
    }
    if !anchor.is_empty() && file.ends_with(".md") {
        let text = std::fs::read_to_string(root.join(&file)).unwrap();
        if !anchors(&text).contains(anchor) {
            return Err(format!(
                "{target}: {file} has no heading with the anchor #{anchor}"
            ));
        }
    }
    Ok(file)
}

/// The pages docs/SUMMARY.md lists, in order, after checking its form: `# Summary`, then only
/// list items `- [Title](page.md)` (indented for sub-chapters) and blank lines.
fn summary_pages(text: &str) -> Vec<String> {
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    assert_eq!(
        lines.next(),
        Some("# Summary"),
        "docs/SUMMARY.md starts with `# Summary`"
    );
    lines
        .map(|l| {
            let item = l.trim_start().strip_prefix("- [");
            let page = item
                .and_then(|i| i.split_once("]("))
                .and_then(|(_, t)| t.strip_suffix(')'));
            match page {
                Some(p) if !p.is_empty() && !p.contains(['#', ' ']) => p.to_owned(),
                _ => panic!("docs/SUMMARY.md: not a `- [Title](page.md)` line: {l}"),
            }
        })
        .collect()
}

#[test]
fn the_guide_is_indexed_and_its_links_resolve() {
    let root = repo("").canonicalize().unwrap();
    let files = tracked(&root);
    let pages: Vec<String> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".md") && n != "SUMMARY.md")
        .collect();
    let listed = summary_pages(&std::fs::read_to_string(root.join("docs/SUMMARY.md")).unwrap());
    let mut problems = Vec::new();
    let mut once = HashSet::new();
    for p in &listed {
        if !once.insert(p) {
            problems.push(format!("docs/SUMMARY.md lists {p} twice"));
        }
        if !pages.contains(p) {
            problems.push(format!(
                "docs/SUMMARY.md lists {p}, which is not a page in docs/"
            ));
        }
    }
    for p in pages.iter().filter(|p| !listed.contains(p)) {
        problems.push(format!("docs/SUMMARY.md does not list docs/{p}"));
    }
    let run: Vec<String> = doc_files(&root)
        .iter()
        .map(|f| normalise(f.strip_prefix(&root).unwrap()).unwrap())
        .collect();
    for from in &run {
        let text = std::fs::read_to_string(root.join(from)).unwrap();
        for (line, target) in links(&text) {
            match check_link(&root, &files, from, &target) {
                Err(e) => problems.push(format!("{from}:{line}: {e}")),
                Ok(to) if from == "README.md" && to.ends_with(".md") && !run.contains(&to) => {
                    problems.push(format!(
                        "{from}:{line}: links {to}, which the documentation test does not run"
                    ))
                }
                Ok(_) => {}
            }
        }
    }
    assert!(problems.is_empty(), "the guide:\n{}", problems.join("\n"));
}

#[test]
fn links_anchors_and_the_summary_are_read_as_markdown() {
    let md = "# Top\n\nSee [a](docs/a.md#the-rule) and ![b](img.png), `[not](code.md)`,\n\
              ``x `[nor](this.md)` y``.\n```sh\necho [no](fence.md)\n```\n## The rule: one `x`\n\
              ## Top\n\nA lone ` and [c](c.md).\n\n[d](d.md) `x`\n";
    let l: Vec<String> = links(md).into_iter().map(|(_, t)| t).collect();
    assert_eq!(l, ["docs/a.md#the-rule", "img.png", "c.md", "d.md"]);
    let a = anchors(md);
    assert!(a.contains("top") && a.contains("top-1") && a.contains("the-rule-one-x"));
    assert_eq!(
        normalise(Path::new("docs/../configs/README.md")).unwrap(),
        "configs/README.md"
    );
    assert!(normalise(Path::new("../x.md")).is_none());
    let pages = summary_pages("# Summary\n\n- [A](a.md)\n    - [B](b.md)\n");
    assert_eq!(pages, ["a.md", "b.md"]);
}

#[test]
#[should_panic(expected = "not a `- [Title](page.md)` line")]
fn a_summary_line_that_is_not_a_chapter_is_refused() {
    summary_pages("# Summary\n\nsome prose\n");
}
