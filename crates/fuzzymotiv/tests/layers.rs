//! The library's folders follow the pipeline, and imports only go down it: each folder (a
//! subsystem) uses only the folders below it in [`LAYERS`], and no two files import each other,
//! directly or round a circle. Doc comments are not imports; tests (`#[cfg(test)]` modules) are
//! skipped.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The subsystems, lowest first: a file may import from its own folder or from a folder
/// before it, never from one after it.
const LAYERS: [&str; 8] = [
    "params",
    "random",
    "statistics",
    "simulation",
    "fitness",
    "evolution",
    "modelling",
    "experiment",
];

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// A file's module path inside the crate: `simulation/trial.rs` → `simulation::trial`,
/// `experiment.rs` → `experiment`.
fn module_of(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    parts.join("::")
}

/// The modules a file's code (not its comments, not its tests) imports with `crate::…`.
fn imports(text: &str) -> Vec<String> {
    let code = text.split("#[cfg(test)]").next().unwrap_or("");
    let mut found = Vec::new();
    for line in code.lines() {
        let line = line.trim_start();
        if line.starts_with("//") {
            continue;
        }
        let line = line.split("//").next().unwrap_or("");
        let mut rest = line;
        while let Some(i) = rest.find("crate::") {
            rest = &rest[i + "crate::".len()..];
            if let Some(group) = rest.strip_prefix('{') {
                // `crate::{a::b, c::d}`: each item's first two segments.
                let inner = group.split('}').next().unwrap_or("");
                found.extend(inner.split(',').map(|item| path_head(item.trim())));
            } else {
                found.push(path_head(rest));
            }
        }
    }
    found.retain(|m| !m.is_empty());
    found
}

/// `simulation::trial::Arena` → `simulation::trial`; `params::FieldError` → `params`.
fn path_head(path: &str) -> String {
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect()
    };
    let first = ident(path);
    let folder = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("src")
        .join(&first);
    if first.is_empty() || !folder.is_dir() {
        return first;
    }
    match path[first.len()..].strip_prefix("::") {
        Some(rest) if rest.starts_with(|c: char| c.is_ascii_lowercase()) => {
            format!("{first}::{}", ident(rest))
        }
        _ => first,
    }
}

/// The layer of a module (its top folder's place in [`LAYERS`]); `None` for the crate root.
fn layer(module: &str) -> Option<usize> {
    let top = module.split("::").next().unwrap();
    LAYERS.iter().position(|l| *l == top)
}

/// The import edges of the library: (importing module, imported module).
fn edges() -> Vec<(String, String)> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut edges = Vec::new();
    for file in files {
        let module = module_of(&src, &file);
        if module == "lib" {
            continue;
        }
        let text = std::fs::read_to_string(&file).unwrap();
        for to in imports(&text) {
            if to != module {
                edges.push((module.clone(), to));
            }
        }
    }
    edges.sort();
    edges.dedup();
    edges
}

/// The imports that go up the layers.
fn upward(edges: &[(String, String)]) -> Vec<String> {
    edges
        .iter()
        .filter_map(|(from, to)| {
            let (a, b) = (layer(from)?, layer(to)?);
            (b > a).then(|| {
                format!(
                    "{from} imports {to} (layer {} above {})",
                    LAYERS[b], LAYERS[a]
                )
            })
        })
        .collect()
}

/// A circle of imports among modules, if any.
fn circle(edges: &[(String, String)]) -> Option<Vec<String>> {
    let mut next: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (a, b) in edges {
        next.entry(a).or_default().push(b);
    }
    fn visit<'a>(
        node: &'a str,
        next: &BTreeMap<&'a str, Vec<&'a str>>,
        path: &mut Vec<&'a str>,
        done: &mut Vec<&'a str>,
    ) -> Option<Vec<String>> {
        if let Some(i) = path.iter().position(|n| *n == node) {
            return Some(path[i..].iter().map(|s| s.to_string()).collect());
        }
        if done.contains(&node) {
            return None;
        }
        path.push(node);
        for n in next.get(node).into_iter().flatten() {
            if let Some(c) = visit(n, next, path, done) {
                return Some(c);
            }
        }
        path.pop();
        done.push(node);
        None
    }
    let mut done = Vec::new();
    next.keys()
        .find_map(|start| visit(start, &next, &mut Vec::new(), &mut done))
}

#[test]
fn imports_go_down_the_layers() {
    let edges = edges();
    assert!(edges.len() > 20, "the parser found the imports: {edges:?}");
    let up = upward(&edges);
    assert!(
        up.is_empty(),
        "imports against the layer order:\n{}",
        up.join("\n")
    );
}

#[test]
fn no_module_imports_itself_round_a_circle() {
    let edges = edges();
    assert_eq!(circle(&edges), None, "an import circle");
}

/// Every top folder of `src/` has its layer, so a new one cannot slip past the order.
#[test]
fn every_folder_has_a_layer() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    for file in files {
        let module = module_of(&src, &file);
        assert!(
            module == "lib" || layer(&module).is_some(),
            "{module} is in no layer of LAYERS"
        );
    }
}

/// The checks can fail: an upward import and a circle are found in made-up edges.
#[test]
fn the_checks_catch_what_they_look_for() {
    let e = |a: &str, b: &str| (a.to_string(), b.to_string());
    let up = upward(&[e("simulation::trial", "experiment::outcome")]);
    assert_eq!(up.len(), 1);
    assert!(up[0].contains("simulation::trial imports experiment::outcome"));
    let c = circle(&[
        e("fitness::fuzzy", "fitness::fll"),
        e("fitness::fll", "fitness::fuzzy"),
    ]);
    assert!(c.is_some());
    assert_eq!(
        imports("use crate::{simulation::trial::Arena, params::check};\n// crate::experiment::X\n"),
        ["simulation::trial", "params"]
    );
}
