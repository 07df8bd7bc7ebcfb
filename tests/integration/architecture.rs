//! The architecture, checked from the code's own `use` lines: the stages run one way
//! (`cad → ingest → tessellate → mesh → sheet → flatten → cut → pattern → nest → export → pipeline →
//! batch`, over the shared `geometry`, `units` and `progress`), each module importing only
//! modules to its left or inside itself, and no file-level import cycle anywhere (in particular,
//! no two files importing each other). A folder's `mod.rs` is its facade: it declares and re-exports its files, and its
//! files import one another by path (`super::sibling::Item`), never through the facade.
//!
//! Paths are read from `use` trees and from `crate::`/`super::` paths in code (comments and doc
//! comments are left out); each resolves to the deepest module file it names.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Top-level modules in pipeline order; a module may import only modules of a smaller rank.
/// The shared foundation (rank 0) imports nothing else of the crate.
const STAGES: &[(&str, usize)] = &[
    ("geometry", 0),
    ("units", 0),
    ("progress", 0),
    ("cad", 1),
    ("ingest", 2),
    ("tessellate", 3),
    ("mesh", 4),
    ("sheet", 5),
    ("flatten", 6),
    ("cut", 7),
    ("pattern", 8),
    ("nest", 9),
    ("export", 10),
    ("error", 11),
    ("pipeline", 12),
    ("batch", 13),
    ("cli", 14),
    ("main", 14),
];

/// A module path inside the crate: `["cut", "seam"]` for `src/cut/seam.rs`.
type ModulePath = Vec<String>;

/// Every source file of the crate, by module path. `lib.rs` is the crate root (the empty path).
fn source_files(root: &Path) -> BTreeMap<ModulePath, PathBuf> {
    let mut files = BTreeMap::new();
    let mut folders = vec![root.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).expect("source folder") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.insert(module_path(root, &path), path);
            }
        }
    }
    files
}

fn module_path(root: &Path, file: &Path) -> ModulePath {
    let relative = file
        .strip_prefix(root)
        .expect("inside src")
        .with_extension("");
    let mut parts: ModulePath = relative
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    if parts == ["lib"] {
        parts.clear();
    }
    parts
}

/// Whether the file is a folder's root (`mod.rs`, `lib.rs`, `main.rs`), whose `super` is its
/// parent folder's module and whose children are its own submodules.
fn is_folder_root(file: &Path) -> bool {
    matches!(
        file.file_name().and_then(|n| n.to_str()),
        Some("mod.rs" | "lib.rs" | "main.rs")
    )
}

/// The source without comments (line comments, doc comments, block comments) and string literals.
fn code_only(source: &str) -> String {
    let mut code = String::with_capacity(source.len());
    let mut chars = source.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '/' if chars.peek() == Some(&'/') => {
                for next in chars.by_ref() {
                    if next == '\n' {
                        code.push('\n');
                        break;
                    }
                }
            }
            '/' if chars.peek() == Some(&'*') => {
                chars.next();
                let mut previous = ' ';
                for next in chars.by_ref() {
                    if previous == '*' && next == '/' {
                        break;
                    }
                    previous = next;
                }
            }
            '"' => {
                let mut escaped = false;
                for next in chars.by_ref() {
                    if next == '"' && !escaped {
                        break;
                    }
                    escaped = next == '\\' && !escaped;
                }
                code.push_str("\"\"");
            }
            _ => code.push(c),
        }
    }
    code
}

/// Every path of every `use` tree: `use a::{b, c::{d, e}};` gives `a::b`, `a::c::d`, `a::c::e`.
fn use_paths(code: &str) -> Vec<(usize, Vec<String>)> {
    let mut paths = Vec::new();
    for at in word_positions(code, "use ") {
        let after = &code[at + 4..];
        let Some(end) = after.find(';') else { break };
        let tree = without_renames(&after[..end]);
        let mut expanded = Vec::new();
        expand_tree(&[], &tree, &mut expanded);
        paths.extend(expanded.into_iter().map(|path| (at, path)));
    }
    paths
}

/// Byte positions where `word` starts, not preceded by an identifier character.
fn word_positions(code: &str, word: &str) -> Vec<usize> {
    code.match_indices(word)
        .map(|(at, _)| at)
        .filter(|&at| {
            !code[..at]
                .chars()
                .last()
                .is_some_and(|c| c.is_alphanumeric() || c == '_')
        })
        .collect()
}

/// The byte ranges of inline modules (`mod tests { ... }`): a `super` inside one stays in the file.
fn inline_module_spans(code: &str) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    for at in word_positions(code, "mod ") {
        let rest = &code[at + 4..];
        let name_end = rest
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(rest.len());
        let after_name = rest[name_end..].trim_start();
        if !after_name.starts_with('{') {
            continue;
        }
        let open = code.len() - after_name.len();
        let mut depth = 0usize;
        for (offset, c) in code[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        spans.push((open, open + offset));
                        break;
                    }
                }
                _ => {}
            }
        }
    }
    spans
}

/// `path` as seen from the file's own module: the first `super`s of a path written inside
/// inline modules climb out of those modules only; `None` when the path stays inside the file.
fn lifted(path: Vec<String>, at: usize, spans: &[(usize, usize)]) -> Option<Vec<String>> {
    let enclosing = spans.iter().filter(|&&(a, b)| a <= at && at <= b).count();
    let supers = path.iter().take_while(|s| *s == "super").count();
    if enclosing == 0 || supers == 0 {
        return Some(path);
    }
    (supers > enclosing).then(|| path[enclosing..].to_vec())
}

/// A `use` tree without whitespace and without its renames (`a as b` becomes `a`).
fn without_renames(tree: &str) -> String {
    let mut kept = String::new();
    let mut tokens = tree
        .split(|c: char| c.is_whitespace())
        .filter(|t| !t.is_empty());
    while let Some(token) = tokens.next() {
        if token == "as" {
            let renamed = tokens.next().unwrap_or_default();
            kept.extend(
                renamed
                    .chars()
                    .skip_while(|c| c.is_alphanumeric() || *c == '_'),
            );
        } else {
            kept.push_str(token);
        }
    }
    kept
}

fn expand_tree(prefix: &[String], tree: &str, paths: &mut Vec<Vec<String>>) {
    for item in split_top_level(tree) {
        match item.find('{') {
            Some(open) if item.ends_with('}') => {
                let mut inner_prefix = prefix.to_vec();
                inner_prefix.extend(segments(item[..open].trim_end_matches("::")));
                expand_tree(&inner_prefix, &item[open + 1..item.len() - 1], paths);
            }
            _ => {
                let mut path = prefix.to_vec();
                path.extend(segments(item));
                paths.push(path);
            }
        }
    }
}

fn segments(path: &str) -> impl Iterator<Item = String> + '_ {
    path.split("::")
        .filter(|s| !s.is_empty())
        .map(str::to_owned)
}

fn split_top_level(tree: &str) -> Vec<&str> {
    let mut items = Vec::new();
    let mut depth = 0usize;
    let mut start = 0;
    for (i, c) in tree.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth = depth.saturating_sub(1),
            ',' if depth == 0 => {
                items.push(&tree[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    items.push(&tree[start..]);
    items.into_iter().filter(|s| !s.is_empty()).collect()
}

/// `crate::a::b` and `super::a` paths written inline in code.
fn inline_paths(code: &str) -> Vec<(usize, Vec<String>)> {
    let mut paths = Vec::new();
    for keyword in ["crate::", "super::"] {
        for at in word_positions(code, keyword) {
            let start = &code[at..];
            let end = start
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .unwrap_or(start.len());
            paths.push((at, segments(&start[..end]).collect()));
        }
    }
    paths
}

/// The module files one file imports (without itself and without the crate root).
fn imports(
    module: &ModulePath,
    file: &Path,
    files: &BTreeMap<ModulePath, PathBuf>,
) -> BTreeSet<ModulePath> {
    let code = code_only(&std::fs::read_to_string(file).expect("source"));
    let folder_root = is_folder_root(file);
    let spans = inline_module_spans(&code);
    let mut targets = BTreeSet::new();
    let paths = use_paths(&code).into_iter().chain(inline_paths(&code));
    for path in paths.filter_map(|(at, path)| lifted(path, at, &spans)) {
        let Some(first) = path.first() else { continue };
        let absolute: ModulePath = match first.as_str() {
            "crate" => path[1..].to_vec(),
            "super" | "self" => {
                let supers = path.iter().take_while(|s| *s == "super").count();
                let mut base = module.clone();
                base.truncate(module.len().saturating_sub(supers));
                let skipped = if first == "self" { 1 } else { supers };
                base.extend(path[skipped..].iter().cloned());
                base
            }
            child if folder_root => {
                let mut candidate = module.clone();
                candidate.push(child.to_owned());
                if !files.contains_key(&candidate) {
                    continue;
                }
                candidate.extend(path[1..].iter().cloned());
                candidate
            }
            _ => continue,
        };
        let resolved = (1..=absolute.len())
            .rev()
            .map(|n| absolute[..n].to_vec())
            .find(|prefix| files.contains_key(prefix));
        if let Some(target) = resolved
            && target != *module
        {
            targets.insert(target);
        }
    }
    targets
}

/// The import graph of the crate's files.
fn import_graph() -> BTreeMap<ModulePath, BTreeSet<ModulePath>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let files = source_files(&root);
    files
        .iter()
        .map(|(module, file)| (module.clone(), imports(module, file, &files)))
        .collect()
}

fn rank(module: &ModulePath) -> Option<usize> {
    let top = module.first()?;
    STAGES
        .iter()
        .find(|(name, _)| name == top)
        .map(|&(_, rank)| rank)
}

fn name(module: &ModulePath) -> String {
    if module.is_empty() {
        "lib".to_owned()
    } else {
        module.join("/")
    }
}

#[test]
fn every_top_level_module_has_a_place_in_the_pipeline() {
    let unknown: Vec<String> = import_graph()
        .keys()
        .filter(|m| !m.is_empty() && rank(m).is_none())
        .map(name)
        .collect();
    assert!(
        unknown.is_empty(),
        "modules with no place in STAGES: {unknown:?}"
    );
}

#[test]
fn no_module_imports_a_stage_to_its_right() {
    let mut violations = Vec::new();
    for (module, targets) in import_graph() {
        let Some(from) = rank(&module) else { continue };
        for target in targets {
            if target.first() == module.first() {
                continue;
            }
            if rank(&target).is_some_and(|to| to >= from) {
                violations.push(format!("{} -> {}", name(&module), name(&target)));
            }
        }
    }
    assert!(
        violations.is_empty(),
        "imports against the pipeline order:\n  {}",
        violations.join("\n  ")
    );
}

#[test]
fn no_files_import_each_other() {
    let graph = import_graph();
    let cycles = strongly_connected_components(&graph);
    let listed: Vec<String> = cycles
        .iter()
        .map(|cycle| cycle.iter().map(name).collect::<Vec<_>>().join(" <-> "))
        .collect();
    assert!(
        listed.is_empty(),
        "files in import cycles:\n  {}",
        listed.join("\n  ")
    );
}

/// Components of more than one file (Tarjan's algorithm, iterative over a sorted graph).
fn strongly_connected_components(
    graph: &BTreeMap<ModulePath, BTreeSet<ModulePath>>,
) -> Vec<Vec<ModulePath>> {
    let nodes: Vec<&ModulePath> = graph.keys().collect();
    let position: BTreeMap<&ModulePath, usize> =
        nodes.iter().enumerate().map(|(i, m)| (*m, i)).collect();
    let successors: Vec<Vec<usize>> = nodes
        .iter()
        .map(|m| {
            graph[*m]
                .iter()
                .filter(|t| !t.is_empty())
                .filter_map(|t| position.get(t).copied())
                .collect()
        })
        .collect();
    let count = nodes.len();
    let mut index = vec![usize::MAX; count];
    let mut low = vec![0; count];
    let mut on_stack = vec![false; count];
    let mut stack = Vec::new();
    let mut next_index = 0;
    let mut components = Vec::new();
    for start in 0..count {
        if index[start] != usize::MAX {
            continue;
        }
        let mut work = vec![(start, 0usize)];
        while let Some(&mut (node, ref mut child)) = work.last_mut() {
            if *child == 0 && index[node] == usize::MAX {
                index[node] = next_index;
                low[node] = next_index;
                next_index += 1;
                stack.push(node);
                on_stack[node] = true;
            }
            if let Some(&successor) = successors[node].get(*child) {
                *child += 1;
                if index[successor] == usize::MAX {
                    work.push((successor, 0));
                } else if on_stack[successor] {
                    low[node] = low[node].min(index[successor]);
                }
                continue;
            }
            work.pop();
            if let Some(&(parent, _)) = work.last() {
                low[parent] = low[parent].min(low[node]);
            }
            if low[node] == index[node] {
                let mut component = Vec::new();
                while let Some(member) = stack.pop() {
                    on_stack[member] = false;
                    component.push(nodes[member].clone());
                    if member == node {
                        break;
                    }
                }
                if component.len() > 1 {
                    component.sort();
                    components.push(component);
                }
            }
        }
    }
    components
}
