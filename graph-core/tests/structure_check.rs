//! The structure check every library crate runs in `cargo test` (graph-core/tests/structure.rs,
//! scene/tests/structure.rs, passes/tests/structure.rs): a crate's modules import in one
//! direction, from the layers of its table down, and no files import each other in a loop. It reads the
//! `use` declarations and the `crate::`/`super::` paths of a crate's `src` (comments, string
//! literals and `#[cfg(test)]` modules left out: tests may reach up), resolves each path to
//! the file that defines the item, following re-exports, and names every import that runs
//! up a layer and every cycle of files. Code behind `#[cfg(feature = ..)]` counts like any
//! other: a crate's structure holds with and without its features.
//!
//! A layer table lists a crate's top-level modules, bottom layer first: a module may import
//! from its own layer and the layers below; within a layer, files must not import each
//! other in a loop. `lib.rs`, the crate's face, declares and re-exports them all and is not
//! checked.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// A crate's layers, bottom first: each a name and the top-level modules in it.
pub type Layers<'a> = &'a [(&'a str, &'a [&'a str])];

/// Every `.rs` file under `src`, by its path relative to `src` (with `/`), and its text.
pub fn sources(src: &Path) -> BTreeMap<String, String> {
    let mut files = BTreeMap::new();
    read_sources(src, src, &mut files);
    files
}

/// Every pair of distinct files where the first imports from the second.
pub fn edges(files: &BTreeMap<String, String>) -> BTreeSet<(String, String)> {
    Crate::new(files)
        .edges()
        .into_keys()
        .map(|(from, to)| (from.to_owned(), to.to_owned()))
        .collect()
}

/// Every `.rs` file under `dir`, by its path relative to `src` (with `/`).
fn read_sources(src: &Path, dir: &Path, files: &mut BTreeMap<String, String>) {
    for entry in std::fs::read_dir(dir).expect("the source directory is readable") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            read_sources(src, &path, files);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let relative = path.strip_prefix(src).expect("under src");
            let name = relative.to_string_lossy().replace('\\', "/");
            let text = std::fs::read_to_string(&path).expect("a readable source file");
            files.insert(name, text);
        }
    }
}

/// The violations among `files` (source path -> text): imports up a layer, then cycles.
pub fn check(files: &BTreeMap<String, String>, layers: Layers<'_>) -> Vec<String> {
    let crate_ = Crate::new(files);
    let layer_of = |file: &str| -> Option<(usize, &str)> {
        let top = crate_.modules[file].first()?;
        layers
            .iter()
            .position(|(_, modules)| modules.contains(&top.as_str()))
            .map(|i| (i, layers[i].0))
    };
    let mut problems = Vec::new();
    for file in files.keys() {
        if crate_.modules[file.as_str()].is_empty() {
            continue; // lib.rs
        }
        if layer_of(file.as_str()).is_none() {
            problems.push(format!("{file} is in no layer: add its module to LAYERS"));
        }
    }
    let edges = crate_.edges();
    for ((from, to), path) in &edges {
        if let (Some((low, low_name)), Some((high, high_name))) = (layer_of(from), layer_of(to)) {
            if high > low {
                problems.push(format!(
                    "{from} (layer {low_name}) imports {path} from {to} (layer {high_name})"
                ));
            }
        }
    }
    problems.extend(cycles(&edges).into_iter().map(|c| format!("cycle: {c}")));
    problems
}

/// The files of a crate, each with its module path, its code without comments and
/// literals, and the names its `use` declarations bring into scope.
struct Crate<'f> {
    /// Module path of each file: `compile/mod.rs` and `compile.rs` are `["compile"]`.
    modules: BTreeMap<&'f str, Vec<String>>,
    /// The file of each module path.
    files: BTreeMap<Vec<String>, &'f str>,
    /// Per file: each `use` path of the file's own scope (what `super::` from a child
    /// and re-exports see), each `use` path of its inline modules (`mod gpu { .. }`),
    /// and the code left once `use` declarations are removed.
    uses: BTreeMap<&'f str, Vec<Use>>,
    inner_uses: BTreeMap<&'f str, Vec<Use>>,
    rest: BTreeMap<&'f str, String>,
}

/// One path a `use` declaration names, and the name it brings into scope.
struct Use {
    path: Vec<String>,
    name: String,
}

impl<'f> Crate<'f> {
    fn new(sources: &'f BTreeMap<String, String>) -> Self {
        let mut crate_ = Crate {
            modules: BTreeMap::new(),
            files: BTreeMap::new(),
            uses: BTreeMap::new(),
            inner_uses: BTreeMap::new(),
            rest: BTreeMap::new(),
        };
        for (file, text) in sources {
            let module = module_path(file);
            crate_.files.insert(module.clone(), file.as_str());
            crate_.modules.insert(file.as_str(), module);
            let code = without_test_modules(&strip(text));
            let (outer, inner) = split_inline_modules(&code);
            let (uses, rest) = split_uses(&outer);
            let (inner_uses, inner_rest) = split_uses(&inner);
            crate_.uses.insert(file.as_str(), uses);
            crate_.inner_uses.insert(file.as_str(), inner_uses);
            crate_.rest.insert(file.as_str(), rest + &inner_rest);
        }
        crate_
    }

    /// `(from, to) -> the first path that ties them`, for every pair of distinct files.
    fn edges(&self) -> BTreeMap<(&'f str, &'f str), String> {
        let mut edges = BTreeMap::new();
        for (&file, module) in &self.modules {
            let children: Vec<&str> = self
                .files
                .keys()
                .filter(|m| m.len() == module.len() + 1 && m.starts_with(module))
                .map(|m| m[module.len()].as_str())
                .collect();
            let mut paths: Vec<Vec<String>> = self.uses[file]
                .iter()
                .chain(&self.inner_uses[file])
                .map(|u| u.path.clone())
                .collect();
            paths.extend(inline_paths(&self.rest[file], &children));
            for path in paths {
                if let Some(to) = self.resolve(module, &path, 0) {
                    if to != file {
                        edges.entry((file, to)).or_insert_with(|| path.join("::"));
                    }
                }
            }
        }
        edges
    }

    /// The file defining what `path`, written in module `from`, names; `None` for other
    /// crates.
    fn resolve(&self, from: &[String], path: &[String], depth: usize) -> Option<&'f str> {
        assert!(depth < 16, "re-exports loop at {}", path.join("::"));
        let (mut module, mut rest) = (from.to_vec(), path);
        match rest.first()?.as_str() {
            "crate" => {
                module.clear();
                rest = &rest[1..];
            }
            "self" => rest = &rest[1..],
            "super" => {
                while rest.first().is_some_and(|s| s == "super") {
                    module.pop();
                    rest = &rest[1..];
                }
            }
            first => {
                let mut child = module.clone();
                child.push(first.to_string());
                if !self.files.contains_key(&child) {
                    return None; // another crate, or a local name
                }
            }
        }
        for (i, segment) in rest.iter().enumerate() {
            let mut child = module.clone();
            child.push(segment.clone());
            if self.files.contains_key(&child) {
                module = child;
                continue;
            }
            let file = self.files[&module];
            let reexport = self.uses[file].iter().find(|u| &u.name == segment);
            return match reexport {
                Some(u) => {
                    let mut path = u.path.clone();
                    path.extend(rest[i + 1..].iter().cloned());
                    self.resolve(&module, &path, depth + 1)
                }
                None => Some(file),
            };
        }
        Some(self.files[&module])
    }
}

/// `a/b.rs` and `a/b/mod.rs` are module `a::b`; `lib.rs` is the root.
fn module_path(file: &str) -> Vec<String> {
    let mut parts: Vec<String> = file
        .trim_end_matches(".rs")
        .split('/')
        .map(str::to_string)
        .collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
        parts.pop();
    }
    parts
}

/// The code without comments, with string and character literals emptied; lines kept.
fn strip(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut level = 0;
            loop {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    level += 1;
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    level -= 1;
                    i += 2;
                    if level == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if c == 'r' && (i == 0 || !ident(chars[i - 1])) && matches!(next, Some('"' | '#')) {
            // A raw string: r"..." or r#"..."#.
            let mut j = i + 1;
            while chars.get(j) == Some(&'#') {
                j += 1;
            }
            if chars.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            let hashes = j - i - 1;
            j += 1;
            while j < chars.len()
                && !(chars[j] == '"' && (1..=hashes).all(|k| chars.get(j + k) == Some(&'#')))
            {
                j += 1;
            }
            out.push_str("\"\"");
            i = j + 1 + hashes;
        } else if c == '"' {
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                i += if chars[i] == '\\' { 2 } else { 1 };
            }
            out.push_str("\"\"");
            i += 1;
        } else if c == '\'' && next == Some('\\') {
            // An escaped character literal.
            i += 2;
            while i < chars.len() && chars[i] != '\'' {
                i += 1;
            }
            out.push_str("' '");
            i += 1;
        } else if c == '\'' && chars.get(i + 2) == Some(&'\'') {
            out.push_str("' '");
            i += 3;
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// The code without `#[cfg(test)] mod name { .. }` items.
fn without_test_modules(code: &str) -> String {
    let mut out = code.to_string();
    while let Some(start) = out.find("#[cfg(test)]") {
        let after = &out[start + "#[cfg(test)]".len()..];
        let is_mod = after.trim_start().starts_with("mod ");
        let Some(open) = after.find('{').filter(|_| is_mod) else {
            // Not a module: drop the attribute alone.
            out.replace_range(start..start + "#[cfg(test)]".len(), "");
            continue;
        };
        let end = matching_brace(after, open).map_or(after.len(), |close| close + 1);
        let end = start + "#[cfg(test)]".len() + end;
        out.replace_range(start..end, "");
    }
    out
}

/// The code outside inline modules (`mod gpu { .. }`), and their bodies, where `super::`
/// (the file's module) is rewritten `self::`, as it is from the file's own scope.
fn split_inline_modules(code: &str) -> (String, String) {
    let (mut outer, mut inner) = (String::new(), String::new());
    let mut from = 0;
    for (at, _) in code.match_indices("mod ") {
        let before = code[..at].chars().next_back();
        if at < from || before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let head = &code[at..];
        let (Some(open), Some(semi)) = (head.find('{'), head.find(';').or(Some(usize::MAX))) else {
            continue;
        };
        if semi < open {
            continue; // `mod name;`: a module of its own file
        }
        let Some(close) = matching_brace(head, open) else {
            continue;
        };
        outer.push_str(&code[from..at]);
        inner.push_str(&head[open + 1..close].replace("super::", "self::"));
        inner.push('\n');
        from = at + close + 1;
    }
    outer.push_str(&code[from..]);
    (outer, inner)
}

/// The index of the `}` closing the `{` at `open`.
fn matching_brace(text: &str, open: usize) -> Option<usize> {
    let mut level = 0;
    for (i, c) in text[open..].char_indices() {
        match c {
            '{' => level += 1,
            '}' => {
                level -= 1;
                if level == 0 {
                    return Some(open + i);
                }
            }
            _ => {}
        }
    }
    None
}

/// The `use` declarations of `code`, expanded to one path each, and the code without them.
fn split_uses(code: &str) -> (Vec<Use>, String) {
    let mut uses = Vec::new();
    let mut rest = String::new();
    let mut from = 0;
    for (at, _) in code.match_indices("use ") {
        let before = code[..at].chars().next_back();
        if at < from || before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
            continue;
        }
        let Some(len) = code[at..].find(';') else {
            continue;
        };
        rest.push_str(&code[from..at]);
        expand(&code[at + 4..at + len], &[], &mut uses);
        from = at + len + 1;
    }
    rest.push_str(&code[from..]);
    (uses, rest)
}

/// Expands a use tree (`a::{b, c::{d as e}}`) under `prefix`.
fn expand(tree: &str, prefix: &[String], uses: &mut Vec<Use>) {
    let tree: String = tree.split_whitespace().collect::<Vec<_>>().join(" ");
    let tree = tree.replace(" ::", "::").replace(":: ", "::");
    let tree = tree.trim().trim_start_matches("::");
    if tree.is_empty() {
        return;
    }
    if let Some(open) = tree.find('{') {
        let mut path = prefix.to_vec();
        path.extend(segments(tree[..open].trim_end_matches("::")));
        let inner = &tree[open + 1..tree.rfind('}').expect("a closed use tree")];
        let mut level = 0;
        let mut start = 0;
        for (i, c) in inner.char_indices() {
            match c {
                '{' => level += 1,
                '}' => level -= 1,
                ',' if level == 0 => {
                    expand(&inner[start..i], &path, uses);
                    start = i + 1;
                }
                _ => {}
            }
        }
        expand(&inner[start..], &path, uses);
        return;
    }
    let (path_text, alias) = match tree.split_once(" as ") {
        Some((path, alias)) => (path, Some(alias.trim())),
        None => (tree, None),
    };
    let mut path = prefix.to_vec();
    path.extend(segments(path_text));
    if path.last().is_some_and(|s| s == "self") {
        path.pop();
    }
    if path.last().is_some_and(|s| s == "*") {
        path.pop(); // a glob depends on the module itself
    }
    let Some(last) = path.last().cloned() else {
        return;
    };
    uses.push(Use {
        name: alias.unwrap_or(&last).to_string(),
        path,
    });
}

fn segments(path: &str) -> impl Iterator<Item = String> + '_ {
    path.split("::")
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(str::to_string)
}

/// Paths written in code: `crate::..`, `super::..`, `self::..`, and `child::..` for the
/// module's child modules.
fn inline_paths(code: &str, children: &[&str]) -> Vec<Vec<String>> {
    let chars: Vec<char> = code.chars().collect();
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    let mut paths = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        if !ident(chars[i]) || (i > 0 && (ident(chars[i - 1]) || chars[i - 1] == ':')) {
            i += 1;
            continue;
        }
        let mut path = Vec::new();
        let mut j = i;
        loop {
            let start = j;
            while j < chars.len() && ident(chars[j]) {
                j += 1;
            }
            path.push(chars[start..j].iter().collect::<String>());
            if chars.get(j) == Some(&':')
                && chars.get(j + 1) == Some(&':')
                && chars.get(j + 2).is_some_and(|&c| ident(c))
            {
                j += 2;
            } else {
                break;
            }
        }
        let first = path[0].as_str();
        let anchored = matches!(first, "crate" | "super" | "self") || children.contains(&first);
        if path.len() > 1 && anchored {
            paths.push(path);
        }
        i = j;
    }
    paths
}

/// Cycles of files, as `a -> b -> a`: for each strongly connected component of more
/// than one file, the shortest loop through its first file.
fn cycles(edges: &BTreeMap<(&str, &str), String>) -> Vec<String> {
    let mut next: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
    for &(from, to) in edges.keys() {
        next.entry(from).or_default().insert(to);
    }
    let mut found = Vec::new();
    let mut done = BTreeSet::new();
    for &file in next.keys() {
        if done.contains(file) {
            continue;
        }
        // Breadth first from `file`, remembering how each file was reached.
        let mut came_from: BTreeMap<&str, &str> = BTreeMap::new();
        let mut queue = std::collections::VecDeque::from([file]);
        while let Some(at) = queue.pop_front() {
            for &to in next.get(at).into_iter().flatten() {
                if !came_from.contains_key(to) {
                    came_from.insert(to, at);
                    queue.push_back(to);
                }
            }
        }
        let Some(&last) = came_from.get(file) else {
            continue; // no way back: on no cycle
        };
        let mut back = Vec::new();
        let mut at = last;
        while at != file {
            back.push(at);
            at = came_from[at];
        }
        let mut walk = vec![file];
        walk.extend(back.into_iter().rev());
        walk.push(file);
        // Leave out the rest of the component: one message per tangle.
        done.extend(
            came_from
                .keys()
                .copied()
                .filter(|other| reaches(&next, other, file)),
        );
        found.push(walk.join(" -> "));
    }
    found
}

/// Whether `to` can be reached from `from`.
fn reaches(next: &BTreeMap<&str, BTreeSet<&str>>, from: &str, to: &str) -> bool {
    let mut seen = BTreeSet::from([from]);
    let mut todo = vec![from];
    while let Some(file) = todo.pop() {
        if file == to {
            return true;
        }
        for &n in next.get(file).into_iter().flatten() {
            if seen.insert(n) {
                todo.push(n);
            }
        }
    }
    false
}
