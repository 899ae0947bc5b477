//! Import circles inside a crate: each library's graph of top-level
//! modules, read from the source text, and its strongly connected
//! components.

use crate::{root, Result};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Edges that close import circles the check lets through for now, as
/// `(crate, from module, to module)`: one edge a circle, the one to cut.
///
/// Temporary, and empty at the lead's merge. Meant for a crate being
/// reworked on another branch (`codegen`, `host-sim`): its circle's
/// cutting edge is listed here so that CI runs meanwhile, while a new
/// circle anywhere (or a new edge in a listed component that closes
/// another circle) still fails. An entry whose edge no longer closes a
/// circle fails the check, so it cannot outlive its reason.
pub(super) const KNOWN_CYCLES: &[(&str, &str, &str)] = &[];

/// Where an edge comes from: the first place (in file and line order)
/// that names the other module.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Site {
    pub(super) file: PathBuf,
    pub(super) line: usize,
}

/// A library's top-level modules and the edges between them.
#[derive(Debug, Default)]
pub(super) struct ModuleGraph {
    pub(super) modules: BTreeSet<String>,
    pub(super) edges: BTreeMap<(String, String), Site>,
}

/// `text` with comments, string and character literals blanked out
/// (line breaks kept, so lines still count).
pub(super) fn code_only(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let blank = |out: &mut String, c: char| out.push(if c == '\n' { '\n' } else { ' ' });
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    blank(&mut out, chars[i]);
                    i += 1;
                }
            }
        } else if let Some((quote, hashes)) = raw_string(&chars, i) {
            // A raw string: r"…", r#"…"#, br"…".
            let mut j = quote + 1;
            while j < chars.len() {
                if chars[j] == '"'
                    && chars.len() > j + hashes
                    && chars[j + 1..=j + hashes].iter().all(|&h| h == '#')
                {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            for &ch in &chars[i..j.min(chars.len())] {
                blank(&mut out, ch);
            }
            i = j;
        } else if c == '"' {
            blank(&mut out, c);
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                if chars[i] == '\\' {
                    blank(&mut out, chars[i]);
                    i += 1;
                }
                if i < chars.len() {
                    blank(&mut out, chars[i]);
                    i += 1;
                }
            }
            if i < chars.len() {
                blank(&mut out, chars[i]);
                i += 1;
            }
        } else if c == '\'' && (next == Some('\\') || chars.get(i + 2) == Some(&'\'')) {
            // A character literal ('a', '\n', '\''), not a lifetime.
            let mut j = i + 1;
            if chars[j] == '\\' {
                j += 2;
            }
            while j < chars.len() && chars[j] != '\'' {
                j += 1;
            }
            for &ch in &chars[i..(j + 1).min(chars.len())] {
                blank(&mut out, ch);
            }
            i = j + 1;
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// Where the raw string literal starting at `chars[i]` (`r"`, `r#"`,
/// `br"`) has its opening quote, and how many `#` it has; `None` if no raw
/// string starts there.
pub(super) fn raw_string(chars: &[char], i: usize) -> Option<(usize, usize)> {
    let ident = |c: &char| c.is_alphanumeric() || *c == '_';
    if i > 0 && ident(&chars[i - 1]) {
        return None;
    }
    let start = match (chars.get(i), chars.get(i + 1)) {
        (Some('r'), _) => i + 1,
        (Some('b'), Some('r')) => i + 2,
        _ => return None,
    };
    let hashes = chars[start.min(chars.len())..]
        .iter()
        .take_while(|&&h| h == '#')
        .count();
    (chars.get(start + hashes) == Some(&'"')).then_some((start + hashes, hashes))
}

/// Whether a line (comments blanked) is an attribute that makes the next
/// item test-only: `#[cfg(test)]` or `#[cfg(all(test, …))]`.
pub(super) fn test_only_attribute(line: &str) -> bool {
    let t: String = line.chars().filter(|c| !c.is_whitespace()).collect();
    t.starts_with("#[cfg(test)]") || t.starts_with("#[cfg(all(test,") || t == "#[cfg(all(test))]"
}

/// The `mod name;` declarations of a file (comments blanked), with their
/// lines, leaving out test-only modules (by an attribute on the lines
/// above or before it on its line). Inline modules are not listed.
pub(super) fn module_declarations(code: &str) -> Vec<(String, usize)> {
    let lines: Vec<&str> = code.lines().collect();
    let mut found = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let mut t = line.trim();
        let mut test_only = false;
        // Attributes on the declaration's own line.
        while t.starts_with("#[") {
            let mut depth = 0;
            let end = t.char_indices().find_map(|(k, c)| {
                match c {
                    '[' => depth += 1,
                    ']' => depth -= 1,
                    _ => return None,
                }
                (depth == 0).then_some(k)
            });
            let Some(end) = end else { break };
            test_only |= test_only_attribute(&t[..=end]);
            t = t[end + 1..].trim_start();
        }
        if let Some(rest) = t.strip_prefix("pub") {
            let rest = rest.trim_start();
            t = match rest.strip_prefix('(') {
                Some(vis) => vis.split_once(')').map_or(rest, |(_, r)| r.trim_start()),
                None => rest,
            };
        }
        let Some(rest) = t.strip_prefix("mod ") else {
            continue;
        };
        let rest = rest.trim_start();
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if name.is_empty() || !rest[name.len()..].trim_start().starts_with(';') {
            continue;
        }
        test_only |= lines[..i]
            .iter()
            .rev()
            .map(|l| l.trim())
            .take_while(|l| l.is_empty() || l.starts_with("#["))
            .any(test_only_attribute);
        if !test_only {
            found.push((name, i + 1));
        }
    }
    found
}

/// A token of code: an identifier, `::`, or another punctuation
/// character; with its line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum Tok {
    Ident(String),
    PathSep,
    Punct(char),
}

pub(super) fn tokens(code: &str) -> Vec<(Tok, usize)> {
    let mut toks = Vec::new();
    for (n, line) in code.lines().enumerate() {
        let chars: Vec<char> = line.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            let c = chars[i];
            if c.is_alphabetic() || c == '_' {
                let start = i;
                while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                    i += 1;
                }
                let word: String = chars[start..i].iter().collect();
                // Raw identifiers: r#name.
                if word == "r" && chars.get(i) == Some(&'#') {
                    i += 1;
                    continue;
                }
                toks.push((Tok::Ident(word), n + 1));
            } else if c.is_ascii_digit() {
                while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                    i += 1;
                }
            } else if c == ':' && chars.get(i + 1) == Some(&':') {
                toks.push((Tok::PathSep, n + 1));
                i += 2;
            } else {
                if !c.is_whitespace() {
                    toks.push((Tok::Punct(c), n + 1));
                }
                i += 1;
            }
        }
    }
    toks
}

/// The top-level modules one file names, as `(module, line, the module
/// path where it is named)`, the file being module `path` (empty for the
/// crate root; inline modules extend it). Only paths that start at
/// `crate::` or climb there with `super::` count.
pub(super) fn referenced_modules(code: &str, path: &[String]) -> Vec<(String, usize, Vec<String>)> {
    let toks = tokens(code);
    let ident = |i: usize| match toks.get(i) {
        Some((Tok::Ident(s), _)) => Some(s.as_str()),
        _ => None,
    };
    let is = |i: usize, t: &Tok| toks.get(i).map(|(x, _)| x) == Some(t);
    let mut found = Vec::new();
    // Inline modules this point of the file is in, with the brace depth
    // they opened at.
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut depth = 0usize;
    let mut i = 0;
    while i < toks.len() {
        match &toks[i].0 {
            Tok::Punct('{') => depth += 1,
            Tok::Punct('}') => {
                depth = depth.saturating_sub(1);
                while inline.last().is_some_and(|&(_, d)| d == depth) {
                    inline.pop();
                }
            }
            Tok::Ident(kw) if kw == "mod" => {
                if let (Some(name), true) = (ident(i + 1), is(i + 2, &Tok::Punct('{'))) {
                    inline.push((name.to_string(), depth));
                    i += 2;
                    continue;
                }
            }
            Tok::Ident(kw)
                if (kw == "crate" || kw == "super")
                    && is(i + 1, &Tok::PathSep)
                    && !(i > 0 && is(i - 1, &Tok::PathSep)) =>
            {
                let current: Vec<String> = path
                    .iter()
                    .cloned()
                    .chain(inline.iter().map(|(m, _)| m.clone()))
                    .collect();
                let mut j = i;
                let base: Vec<String> = if kw == "crate" {
                    j += 2;
                    Vec::new()
                } else {
                    let mut up = 0;
                    while ident(j) == Some("super") && is(j + 1, &Tok::PathSep) {
                        up += 1;
                        j += 2;
                    }
                    if up > current.len() {
                        i = j;
                        continue;
                    }
                    current[..current.len() - up].to_vec()
                };
                // Below the root the path stays inside the top-level
                // module it climbed from: only the root's children count.
                if base.is_empty() {
                    if let Some(name) = ident(j) {
                        found.push((name.to_string(), toks[j].1, current.clone()));
                    } else if is(j, &Tok::Punct('{')) {
                        // use crate::{a, b::c, d::{e, f}}: the first
                        // segment of every item.
                        let mut level = 0;
                        let mut item_start = true;
                        let mut k = j + 1;
                        while k < toks.len() {
                            match &toks[k].0 {
                                Tok::Punct('{') => level += 1,
                                Tok::Punct('}') if level == 0 => break,
                                Tok::Punct('}') => level -= 1,
                                Tok::Punct(',') if level == 0 => {
                                    item_start = true;
                                    k += 1;
                                    continue;
                                }
                                Tok::Ident(name) if item_start && level == 0 => {
                                    found.push((name.clone(), toks[k].1, current.clone()));
                                }
                                _ => {}
                            }
                            item_start = false;
                            k += 1;
                        }
                    }
                }
                i = j;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    found
}

/// The file of module `name`, declared by `mod name;` in file `parent`.
pub(super) fn child_file(
    files: &BTreeMap<PathBuf, String>,
    parent: &Path,
    name: &str,
) -> Option<PathBuf> {
    let stem = parent.file_stem().and_then(|s| s.to_str()).unwrap_or("");
    let dir = parent.parent().unwrap_or(Path::new(""));
    let dir = if matches!(stem, "lib" | "mod" | "main") {
        dir.to_path_buf()
    } else {
        dir.join(stem)
    };
    [
        dir.join(format!("{name}.rs")),
        dir.join(name).join("mod.rs"),
    ]
    .into_iter()
    .find(|p| files.contains_key(p))
}

/// The graph of top-level modules of the library whose root is `lib`,
/// from the crate's files (path → text; paths as they are to be printed).
/// Modules are found by following `mod name;` from `lib`, so binaries,
/// test-only modules and `tests/` are not read.
pub(super) fn module_graph(files: &BTreeMap<PathBuf, String>, lib: &Path) -> Result<ModuleGraph> {
    // Files still to read, with their module paths.
    let mut queue = vec![(lib.to_path_buf(), Vec::<String>::new())];
    let mut reached = Vec::new();
    while let Some((file, path)) = queue.pop() {
        let text = files
            .get(&file)
            .ok_or_else(|| format!("{}: cannot read", file.display()))?;
        let code = code_only(text);
        for (name, line) in module_declarations(&code) {
            let child = child_file(files, &file, &name).ok_or_else(|| {
                format!(
                    "{}:{line}: `mod {name};` has neither {name}.rs nor {name}/mod.rs beside it",
                    file.display()
                )
            })?;
            let mut child_path = path.clone();
            child_path.push(name);
            queue.push((child, child_path));
        }
        // Test code: from the first test-only attribute to the end.
        let end = code
            .lines()
            .position(test_only_attribute)
            .unwrap_or(usize::MAX);
        let code: String = code.lines().take(end).map(|l| format!("{l}\n")).collect();
        reached.push((file, path, code));
    }
    reached.sort();
    let mut graph = ModuleGraph::default();
    for (_, path, code) in &reached {
        if let Some(top) = path.first() {
            graph.modules.insert(top.clone());
        } else {
            // Inline modules of the root are top-level modules too.
            for w in tokens(code).windows(3) {
                if let [(Tok::Ident(m), _), (Tok::Ident(name), _), (Tok::Punct('{'), _)] = w {
                    if m == "mod" {
                        graph.modules.insert(name.clone());
                    }
                }
            }
        }
    }
    for (file, path, code) in &reached {
        for (to, line, current) in referenced_modules(code, path) {
            let Some(from) = current.first() else {
                continue;
            };
            if *from == to || !graph.modules.contains(&to) {
                continue;
            }
            graph
                .edges
                .entry((from.clone(), to))
                .or_insert_with(|| Site {
                    file: file.clone(),
                    line,
                });
        }
    }
    Ok(graph)
}

/// Strongly connected components of more than one module (Tarjan), each
/// sorted, in sorted order.
pub(super) fn circles(
    modules: &BTreeSet<String>,
    edges: &BTreeSet<(String, String)>,
) -> Vec<Vec<String>> {
    struct Tarjan<'a> {
        edges: &'a BTreeSet<(String, String)>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on_stack: BTreeSet<&'a str>,
        found: Vec<Vec<String>>,
    }
    impl<'a> Tarjan<'a> {
        fn visit(&mut self, v: &'a str) {
            let n = self.index.len();
            self.index.insert(v, n);
            self.low.insert(v, n);
            self.stack.push(v);
            self.on_stack.insert(v);
            let edges = self.edges;
            for (_, w) in edges.iter().filter(|(a, _)| a == v) {
                let w = w.as_str();
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let low = self.low[v].min(self.low[w]);
                    self.low.insert(v, low);
                } else if self.on_stack.contains(w) {
                    let low = self.low[v].min(self.index[w]);
                    self.low.insert(v, low);
                }
            }
            if self.low[v] == self.index[v] {
                let mut component = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on_stack.remove(w);
                    component.push(w.to_string());
                    if w == v {
                        break;
                    }
                }
                if component.len() > 1 {
                    component.sort();
                    self.found.push(component);
                }
            }
        }
    }
    let mut t = Tarjan {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        found: Vec::new(),
    };
    for m in modules {
        if !t.index.contains_key(m.as_str()) {
            t.visit(m);
        }
    }
    t.found.sort();
    t.found
}

/// One shortest circle through the first module of `component`, as the
/// modules in order (the first repeated at the end).
pub(super) fn one_circle(component: &[String], edges: &BTreeSet<(String, String)>) -> Vec<String> {
    let start = &component[0];
    let inside = |m: &String| component.contains(m);
    // Breadth-first from `start` back to it, inside the component.
    let mut previous: BTreeMap<&String, &String> = BTreeMap::new();
    let mut frontier = vec![start];
    while !frontier.is_empty() {
        let mut next = Vec::new();
        for v in frontier {
            for (_, w) in edges.iter().filter(|(a, b)| a == v && inside(b)) {
                if w == start {
                    let mut circle = vec![start.clone()];
                    let mut at = v;
                    while at != start {
                        circle.push(at.clone());
                        at = previous[at];
                    }
                    circle.push(start.clone());
                    circle.reverse();
                    return circle;
                }
                if !previous.contains_key(w) {
                    previous.insert(w, v);
                    next.push(w);
                }
            }
        }
        frontier = next;
    }
    component.to_vec()
}

/// The import circles of one crate's graph, `known` edges left out, as
/// messages; and the `known` edges that close no circle.
pub(super) fn circle_failures(
    krate: &str,
    graph: &ModuleGraph,
    known: &[(&str, &str, &str)],
) -> (Vec<String>, Vec<String>) {
    let all: BTreeSet<(String, String)> = graph.edges.keys().cloned().collect();
    let known: Vec<(String, String)> = known
        .iter()
        .filter(|(k, _, _)| *k == krate)
        .map(|(_, a, b)| (a.to_string(), b.to_string()))
        .collect();
    let mut stale = Vec::new();
    let full = circles(&graph.modules, &all);
    for (a, b) in &known {
        let closes = all.contains(&(a.clone(), b.clone()))
            && full.iter().any(|c| c.contains(a) && c.contains(b));
        if !closes {
            stale.push(format!(
                "xtask/src/layers/modules.rs: KNOWN_CYCLES lets `{krate}`: {a} -> {b} through, but that \
                 edge closes no circle any more: delete the entry"
            ));
        }
    }
    let kept: BTreeSet<(String, String)> =
        all.iter().filter(|e| !known.contains(e)).cloned().collect();
    let mut failures = Vec::new();
    for component in circles(&graph.modules, &kept) {
        let mut msg = format!(
            "`{krate}`: import circle {} (modules {})",
            one_circle(&component, &kept).join(" -> "),
            component.join(", ")
        );
        for ((a, b), site) in &graph.edges {
            if kept.contains(&(a.clone(), b.clone()))
                && component.contains(a)
                && component.contains(b)
            {
                msg.push_str(&format!(
                    "\n    {a} -> {b}: {}:{}",
                    site.file.display(),
                    site.line
                ));
            }
        }
        failures.push(msg);
    }
    (failures, stale)
}

/// Every `.rs` file under `dir`, by path relative to the workspace root.
pub(super) fn read_sources(dir: &Path, files: &mut BTreeMap<PathBuf, String>) -> Result {
    let entries =
        std::fs::read_dir(root().join(dir)).map_err(|e| format!("{}: {e}", dir.display()))?;
    for entry in entries {
        let entry = entry.map_err(|e| format!("{}: {e}", dir.display()))?;
        let path = dir.join(entry.file_name());
        let kind = entry
            .file_type()
            .map_err(|e| format!("{}: {e}", path.display()))?;
        if kind.is_dir() {
            read_sources(&path, files)?;
        } else if path.extension().is_some_and(|e| e == "rs") {
            let text = std::fs::read_to_string(root().join(&path))
                .map_err(|e| format!("{}: {e}", path.display()))?;
            files.insert(path, text);
        }
    }
    Ok(())
}
