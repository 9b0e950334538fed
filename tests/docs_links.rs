//! The documentation's links, checked without a GPU or a network: std only, its own small
//! test binary (`cargo test --test docs_links`), since it links neither wgpu nor naga.
//!
//! For README.md and every Markdown file under docs/:
//! - every relative link and image (`[text](path)`, `![alt](path)`, outside code blocks and
//!   code spans) names a file or folder that exists, relative to the file it is written in;
//! - every anchor (`path.md#anchor` or `#anchor`) names a heading of that file, as GitHub
//!   makes anchors of headings (lower case, punctuation dropped, spaces as hyphens, `-1`,
//!   `-2` for repeats);
//! - every path under `bench/results/` the text names (linked or not, in code too) exists,
//!   so a results folder cannot be removed while the book still cites it (a path after
//!   `REV:`, as in `git show REV:bench/results/...`, names the history and is skipped).
//!
//! And every snippet, a fenced block after a `<!-- snippet: FILE -->` line (FILE from the
//! repository root), is found verbatim in FILE: the block is cut at lines `// ...` into
//! pieces, and each piece must appear in FILE as consecutive lines, in order, shifted right
//! by the same whitespace (trailing spaces ignored). The README's embedding example is one
//! (the README must have at least one, so removing its marker fails too); the graph-file
//! guide quotes `pipelines/*.ron`, which the build validates.
//!
//! A failure lists every problem as `FILE:LINE: ...`, naming the link or snippet line.

use std::collections::HashMap;
use std::fs;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and every `.md` file under docs/, sorted.
fn markdown_files() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = fs::read_dir(dir) else {
            return;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "md") {
                out.push(path);
            }
        }
    }
    let mut files = vec![root().join("README.md")];
    walk(&root().join("docs"), &mut files);
    files.sort();
    files
}

fn display(path: &Path) -> String {
    path.strip_prefix(root())
        .unwrap_or(path)
        .display()
        .to_string()
}

/// The lines outside fenced code blocks, with their 1-based numbers, code spans blanked.
fn prose_lines(text: &str) -> Vec<(usize, String)> {
    let mut fenced = false;
    let mut out = Vec::new();
    for (index, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if !fenced {
            out.push((index + 1, blank_code_spans(line)));
        }
    }
    out
}

/// The line with every `code span` replaced by spaces (a link inside one is no link).
fn blank_code_spans(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut in_code = false;
    for c in line.chars() {
        if c == '`' {
            in_code = !in_code;
            out.push(' ');
        } else if in_code {
            out.push(' ');
        } else {
            out.push(c);
        }
    }
    out
}

/// The targets of the inline links and images on a line: what stands in `](...)`.
fn link_targets(line: &str) -> Vec<String> {
    let mut targets = Vec::new();
    let mut rest = line;
    while let Some(at) = rest.find("](") {
        let after = &rest[at + 2..];
        let Some(end) = after.find(')') else { break };
        // `[text](path "title")`: the path is the first word.
        let target = after[..end].split_whitespace().next().unwrap_or("");
        targets.push(target.trim_matches(|c| c == '<' || c == '>').to_string());
        rest = &after[end..];
    }
    targets
}

/// GitHub's anchor for a heading's text.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == '-' || *c == '_' || *c == ' ')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// Every anchor a Markdown file's headings make, repeats numbered as GitHub numbers them.
fn anchors(text: &str) -> Vec<String> {
    let mut seen: HashMap<String, usize> = HashMap::new();
    let mut out = Vec::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        let hashes = line.chars().take_while(|&c| c == '#').count();
        if fenced || hashes == 0 || hashes > 6 || !line[hashes..].starts_with(' ') {
            continue;
        }
        let base = slug(&line[hashes..].replace('`', ""));
        let count = seen.entry(base.clone()).or_insert(0);
        out.push(if *count == 0 {
            base.clone()
        } else {
            format!("{base}-{count}")
        });
        *count += 1;
    }
    out
}

/// The paths under bench/results/ a line names, with trailing punctuation dropped.
fn results_paths(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = line;
    while let Some(at) = rest.find("bench/results/") {
        // `git show REV:bench/results/...` names a path in the history, not in the tree.
        let in_history = rest[..at].ends_with(':');
        let tail = &rest[at..];
        let end = tail
            .find(|c: char| !(c.is_ascii_alphanumeric() || "_-./".contains(c)))
            .unwrap_or(tail.len());
        if !in_history {
            out.push(tail[..end].trim_end_matches(['.', '/']).to_string());
        }
        rest = &tail[end..];
    }
    out
}

fn check_links(file: &Path, problems: &mut Vec<String>) {
    let text = fs::read_to_string(file).expect("a Markdown file reads");
    let dir = file.parent().expect("a file has a folder");
    let own = anchors(&text);
    for (number, line) in prose_lines(&text) {
        for target in link_targets(&line) {
            let here = format!("{}:{number}: link `{target}`", display(file));
            if target.is_empty() {
                problems.push(format!("{here}: empty target"));
                continue;
            }
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            let (path, anchor) = match target.split_once('#') {
                Some((path, anchor)) => (path, Some(anchor)),
                None => (target.as_str(), None),
            };
            let resolved = if path.is_empty() {
                file.to_path_buf()
            } else {
                dir.join(path)
            };
            if !resolved.exists() {
                problems.push(format!(
                    "{here}: {} does not exist",
                    display(&normalise(&resolved))
                ));
                continue;
            }
            let Some(anchor) = anchor else { continue };
            let headings = if path.is_empty() {
                own.clone()
            } else if resolved.extension().is_some_and(|e| e == "md") {
                anchors(&fs::read_to_string(&resolved).unwrap_or_default())
            } else {
                continue;
            };
            if !headings.iter().any(|h| h == anchor) {
                problems.push(format!(
                    "{here}: no heading of {} makes the anchor #{anchor}",
                    display(&normalise(&resolved))
                ));
            }
        }
    }
    // Paths under bench/results/ anywhere, code spans and blocks too (a command's
    // --out-dir names the folder it regenerates).
    for (index, line) in text.lines().enumerate() {
        for path in results_paths(line) {
            if !root().join(&path).exists() {
                problems.push(format!(
                    "{}:{}: names {path}, which does not exist",
                    display(file),
                    index + 1
                ));
            }
        }
    }
}

/// `a/b/../c` as `a/c`, for messages.
fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// A README snippet: its marker's line, the file it quotes, and its block's lines with
/// their numbers.
type Snippet = (usize, String, Vec<(usize, String)>);

/// The README's snippets.
fn snippets(readme: &str) -> Vec<Snippet> {
    let lines: Vec<&str> = readme.lines().collect();
    let mut out = Vec::new();
    let mut index = 0;
    while index < lines.len() {
        let line = lines[index].trim();
        if let Some(rest) = line.strip_prefix("<!-- snippet:") {
            let quoted = rest.trim_end_matches("-->").trim().to_string();
            let marker = index + 1;
            // The next fenced block.
            let mut at = index + 1;
            while at < lines.len() && !lines[at].trim_start().starts_with("```") {
                at += 1;
            }
            let mut block = Vec::new();
            at += 1;
            while at < lines.len() && !lines[at].trim_start().starts_with("```") {
                block.push((at + 1, lines[at].to_string()));
                at += 1;
            }
            out.push((marker, quoted, block));
            index = at;
        }
        index += 1;
    }
    out
}

/// Whether `piece` stands in `source` at or after line `from`, each line shifted right by
/// the same whitespace (trailing spaces ignored); returns the line after the match.
fn find_piece(source: &[&str], piece: &[&str], from: usize) -> Option<usize> {
    let first = piece.first()?;
    let indent = |s: &str| s.len() - s.trim_start().len();
    'start: for start in from..source.len() {
        if start + piece.len() > source.len() {
            return None;
        }
        let Some(shift) = indent(source[start]).checked_sub(indent(first)) else {
            continue;
        };
        for (k, want) in piece.iter().enumerate() {
            let got = source[start + k].trim_end();
            let want = want.trim_end();
            let matches = if want.is_empty() {
                got.is_empty()
            } else {
                got.len() == want.len() + shift
                    && got[..shift].trim().is_empty()
                    && &got[shift..] == want
            };
            if !matches {
                continue 'start;
            }
        }
        return Some(start + piece.len());
    }
    None
}

/// Checks the snippets of one Markdown file against the files they quote; returns how many
/// snippets it has.
fn check_snippets_of(file: &Path, problems: &mut Vec<String>) -> usize {
    let text = fs::read_to_string(file).expect("a Markdown file reads");
    let name = display(file);
    let found = snippets(&text);
    let count = found.len();
    for (marker, quoted, block) in found {
        let Ok(source) = fs::read_to_string(root().join(&quoted)) else {
            problems.push(format!(
                "{name}:{marker}: snippet quotes {quoted} (from the repository root), which does not read"
            ));
            continue;
        };
        let source: Vec<&str> = source.lines().collect();
        if block.iter().all(|(_, l)| l.trim().is_empty()) {
            problems.push(format!("{name}:{marker}: the snippet of {quoted} is empty"));
            continue;
        }
        let mut from = 0;
        for piece in block.split(|(_, l)| l.trim() == "// ...") {
            // Blank lines around an elision belong to neither side.
            let start = piece.iter().position(|(_, l)| !l.trim().is_empty());
            let end = piece.iter().rposition(|(_, l)| !l.trim().is_empty());
            let (Some(start), Some(end)) = (start, end) else {
                continue;
            };
            let piece = &piece[start..=end];
            let lines: Vec<&str> = piece.iter().map(|(_, l)| l.as_str()).collect();
            match find_piece(&source, &lines, from) {
                Some(next) => from = next,
                None => problems.push(format!(
                    "{name}:{}: snippet lines {}-{} (from `{}`) are not in {quoted} as \
                     written, in order after the previous piece: copy them from the file again",
                    piece[0].0,
                    piece[0].0,
                    piece[piece.len() - 1].0,
                    lines[0].trim()
                )),
            }
        }
    }
    count
}

#[test]
fn links_images_anchors_and_results_paths_resolve() {
    let mut problems = Vec::new();
    let files = markdown_files();
    assert!(files.len() > 1, "no Markdown files under docs/");
    for file in &files {
        check_links(file, &mut problems);
    }
    assert!(
        problems.is_empty(),
        "{} broken link(s) in the documentation:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

#[test]
fn snippets_are_verbatim_in_the_files_they_quote() {
    let mut problems = Vec::new();
    let mut readme = 0;
    for file in markdown_files() {
        let count = check_snippets_of(&file, &mut problems);
        if file == root().join("README.md") {
            readme = count;
        }
    }
    if readme == 0 {
        problems.push(
            "README.md: no `<!-- snippet: FILE -->` before the embedding example, so nothing \
             ties it to a file that compiles"
                .to_string(),
        );
    }
    assert!(
        problems.is_empty(),
        "{} snippet(s) drifted from the files they quote:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

#[test]
fn the_checker_finds_what_it_should() {
    assert_eq!(
        slug("The lean G-buffer: 16 bytes per sample"),
        "the-lean-g-buffer-16-bytes-per-sample"
    );
    assert_eq!(slug("A live view: rgraph view"), "a-live-view-rgraph-view");
    assert_eq!(anchors("# A\n## A\n```\n# not\n```\n"), ["a", "a-1"]);
    assert_eq!(
        link_targets(&blank_code_spans(
            "see [x](a.md#b) and `[y](c.md)` ![i](g.png \"t\")"
        )),
        ["a.md#b", "g.png"]
    );
    assert_eq!(
        results_paths("in `bench/results/h200/main/results.md`, then bench/results/lavapipe."),
        [
            "bench/results/h200/main/results.md",
            "bench/results/lavapipe"
        ]
    );
    assert!(results_paths("`git show c67acb0:bench/results/gpu/x/results.md`").is_empty());
    let source = ["fn f() {", "    let a = 1;", "    let b = 2;", "}"];
    assert_eq!(
        find_piece(&source, &["let a = 1;", "let b = 2;"], 0),
        Some(3)
    );
    assert_eq!(
        find_piece(&source, &["fn f() {", "    let a = 1;"], 0),
        Some(2)
    );
    assert_eq!(find_piece(&source, &["fn f() {", "  let a = 1;"], 0), None);
    assert_eq!(find_piece(&source, &["let b = 2;", "let a = 1;"], 0), None);
    assert_eq!(find_piece(&source, &["let a = 1;"], 2), None);
}
