//! The import map of the command line (`crates/fuzzymotiv-cli/src`), the files crate it stands
//! on (`crates/fuzzymotiv-io/src`) and the library under both (`crates/fuzzymotiv/src`), every
//! folder included: each module belongs to a layer
//! of [`LAYERS`] (ARCHITECTURE.md), imports only from its own layer or the ones below, and no
//! modules import each other in a circle.
//!
//! Imports are the paths a file names after `crate::` (and `fuzzymotiv::`, in the
//! files crate and the command line, and `fuzzymotiv_io::` in the command line), `use` groups included, comments left out; an import is of the longest
//! module its path starts with, and the macros `out!`, `outln!` and `note!` are `console`'s.
//!
//! `cargo test -p fuzzymotiv-cli --test layers -- --nocapture` prints the import map.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The layers, lowest first: a module path, standing for the module and everything in it,
/// and its layer. A module imports only from its own layer and the ones below it.
const LAYERS: [(&str, usize); 31] = [
    // fuzzymotiv, the library: the pipeline's subsystems
    ("lib::params", 0),     // FieldError: the one error of every input
    ("lib::random", 0),     // seeded streams, noise
    ("lib::statistics", 0), // tests, intervals and verdicts over seeds (uses random only)
    ("lib::simulation", 1), // geometry, rooms, robot, sensors, controller, trials
    ("lib::fitness", 2),    // terms a, g, l, b; the TSK; FLL
    ("lib::evolution", 3),  // the GA's operators
    ("lib::modelling", 4),  // AEM, SOM, recognition
    ("lib::experiment", 5), // config, the entry, evaluation, the loop, room modelling, outcome
    ("lib", 6),             // the crate root: modules and re-exports
    // fuzzymotiv-io
    ("io::files", 7),     // the output guard, inputs, the error, the terminal macros
    ("io::records", 8),   // the output model (one serde type per file), the checkpoint
    ("io::render", 9),    // tables, the study's statistics, SVG figures, the report
    ("io::pipeline", 10), // run directory, sweep plan/jobs/merge, lanes, progress
    ("io", 11),           // the crate root (module declarations)
    // fuzzymotiv-lab: the browser lab (a library the binary starts)
    ("lab::limits", 12),   // the documented limits
    ("lab::errors", 12),   // the handlers' error (status + the CLI's message)
    ("lab::assets", 12),   // the embedded page, script and style
    ("lab::rooms", 13),    // built-in, drawn and uploaded rooms, checked and saved
    ("lab::security", 13), // token, Host check, security headers
    ("lab::live", 13),     // a run's events: generations, paths, result
    ("lab::settings", 14), // the page's settings → the CLI's config checks
    ("lab::runs", 15),     // the run list, the queue and the worker
    ("lab::compare", 16),  // two runs side by side, the library's statistics
    ("lab::api", 17),      // the routes
    ("lab::server", 18),   // start and stop
    ("lab", 19),           // the crate root
    // fuzzymotiv-cli
    ("cli::args", 20),     // clap options shared by commands
    ("cli::png", 20),      // the resvg rasteriser
    ("cli::progress", 20), // indicatif progress
    ("cli::commands", 21), // one module per command
    ("cli", 22),           // main.rs: parse the arguments, dispatch
];

/// The macros exported at the crate root, by the module that defines them.
const MACROS: [(&str, &str); 3] = [
    ("out", "io::files::console"),
    ("outln", "io::files::console"),
    ("note", "io::files::console"),
];

/// One import: `from` (in `file`) names `import`, which is of the module `to`.
#[derive(Debug, Clone)]
struct Edge {
    from: String,
    to: String,
    file: String,
    import: String,
}

/// Which path roots name which crate (by its module prefix) in a crate's code.
type Roots = &'static [(&'static str, &'static str)];

/// The crates read: the prefix of their module paths, their source folder (from this crate's
/// folder), and the path roots of their code.
const CRATES: [(&str, &str, Roots); 4] = [
    ("lib", "../fuzzymotiv/src", &[("crate", "lib")]),
    (
        "io",
        "../fuzzymotiv-io/src",
        &[("crate", "io"), ("fuzzymotiv", "lib")],
    ),
    (
        "lab",
        "../fuzzymotiv-lab/src",
        &[
            ("crate", "lab"),
            ("fuzzymotiv_io", "io"),
            ("fuzzymotiv", "lib"),
        ],
    ),
    (
        "cli",
        "src",
        &[
            ("crate", "cli"),
            ("fuzzymotiv_lab", "lab"),
            ("fuzzymotiv_io", "io"),
            ("fuzzymotiv", "lib"),
        ],
    ),
];

/// Every `.rs` file under `dir`, with its module path (`lib.rs`/`main.rs`: the crate root,
/// `mod.rs`: its folder).
fn modules(prefix: &str, dir: &Path) -> Vec<(String, PathBuf)> {
    let mut out = Vec::new();
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            out.extend(modules(&format!("{prefix}::{stem}"), &path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            let module = match stem.as_str() {
                "lib" | "main" | "mod" => prefix.to_string(),
                _ => format!("{prefix}::{stem}"),
            };
            out.push((module, path));
        }
    }
    out
}

/// The paths of a `use` tree starting at `text` (right after `root::`): `a::b`, `a::{b, c::d}`
/// → `[[a, b]]`, `[[a, b], [a, c, d]]`. Stops at anything else (`!`, `(`, `;`, a space).
fn use_paths(text: &str) -> Vec<Vec<String>> {
    fn tree(s: &[char], i: &mut usize, base: &[String], out: &mut Vec<Vec<String>>) {
        let skip_space = |i: &mut usize| {
            while *i < s.len() && s[*i].is_whitespace() {
                *i += 1;
            }
        };
        let mut path = base.to_vec();
        loop {
            skip_space(i);
            if *i < s.len() && s[*i] == '{' {
                *i += 1;
                loop {
                    tree(s, i, &path, out);
                    skip_space(i);
                    match s.get(*i) {
                        Some(',') => *i += 1,
                        Some('}') => {
                            *i += 1;
                            return;
                        }
                        _ => return,
                    }
                    skip_space(i);
                    if s.get(*i) == Some(&'}') {
                        *i += 1;
                        return;
                    }
                }
            }
            let start = *i;
            while *i < s.len() && (s[*i].is_alphanumeric() || s[*i] == '_') {
                *i += 1;
            }
            if *i == start {
                break;
            }
            path.push(s[start..*i].iter().collect());
            if s[*i..].starts_with(&[':', ':']) {
                *i += 2;
            } else {
                break;
            }
        }
        if path.len() > base.len() {
            out.push(path);
        }
    }
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    tree(&chars, &mut 0, &[], &mut out);
    out
}

/// A file's code without its line comments (and so without its doc comments) and without its
/// tests (everything from the first `#[cfg(test)]`: tests may use any layer).
fn code(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    text.split("#[cfg(test)]")
        .next()
        .unwrap()
        .lines()
        .map(|line| line.split("//").next().unwrap())
        .collect::<Vec<_>>()
        .join("\n")
}

/// The module an imported path is of: the longest known module it starts with, or the module
/// defining a root macro; `None` if there is no such module.
fn resolve(path: &[String], known: &BTreeSet<String>) -> Option<String> {
    if let [root, name] = path
        && let Some((_, home)) = MACROS.iter().find(|(m, _)| m == name)
        && known.contains(root)
    {
        return Some(home.to_string());
    }
    (1..=path.len())
        .rev()
        .map(|n| path[..n].join("::"))
        .find(|m| known.contains(m))
}

/// Every import of both crates, and every module.
fn import_edges() -> (Vec<Edge>, BTreeMap<String, PathBuf>) {
    let mut files = BTreeMap::new();
    let mut roots = Vec::new();
    for (prefix, dir, names) in CRATES {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
        for (module, path) in modules(prefix, &dir) {
            roots.push((module.clone(), names));
            files.insert(module, path);
        }
    }
    let known: BTreeSet<String> = files.keys().cloned().collect();
    let mut edges = Vec::new();
    for (module, names) in roots {
        let path = &files[&module];
        let text = code(path);
        for &(root, crate_prefix) in names {
            let marker = format!("{root}::");
            for (at, _) in text.match_indices(&marker) {
                let before = text[..at].chars().next_back();
                if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
                    continue; // e.g. `fuzzymotiv_io::` is not `io::`
                }
                for p in use_paths(&text[at + marker.len()..]) {
                    let full: Vec<String> = std::iter::once(crate_prefix.to_string())
                        .chain(p.iter().cloned())
                        .collect();
                    let import = format!("{root}::{}", p.join("::"));
                    let to = resolve(&full, &known).unwrap_or_else(|| {
                        panic!("{}: `{import}` names no module", path.display())
                    });
                    if to != module {
                        edges.push(Edge {
                            from: module.clone(),
                            to,
                            file: path.display().to_string(),
                            import,
                        });
                    }
                }
            }
        }
    }
    (edges, files)
}

/// The layer of a module: that of the longest entry of `layers` it is in.
fn layer_of(module: &str, layers: &[(&str, usize)]) -> Option<usize> {
    layers
        .iter()
        .filter(|(m, _)| module == *m || module.starts_with(&format!("{m}::")))
        .max_by_key(|(m, _)| m.len())
        .map(|&(_, l)| l)
}

/// Every import from a lower layer to a higher one, as a message naming the file and the import.
fn layer_violations(edges: &[Edge], layers: &[(&str, usize)]) -> Vec<String> {
    let mut out = Vec::new();
    for e in edges {
        let (Some(from), Some(to)) = (layer_of(&e.from, layers), layer_of(&e.to, layers)) else {
            out.push(format!("{}: {} or {} has no layer", e.file, e.from, e.to));
            continue;
        };
        if to > from {
            out.push(format!(
                "{}: `{}` imports {} (layer {to}) into {} (layer {from}), a lower layer",
                e.file, e.import, e.to, e.from
            ));
        }
    }
    out
}

/// A circle of imports, if there is one (depth-first search).
fn find_circle(edges: &[Edge]) -> Option<Vec<String>> {
    let mut map: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
    for e in edges {
        map.entry(&e.from).or_default().insert(&e.to);
    }
    fn visit<'a>(
        map: &BTreeMap<&'a str, BTreeSet<&'a str>>,
        m: &'a str,
        path: &mut Vec<&'a str>,
        done: &mut BTreeSet<&'a str>,
    ) -> Option<Vec<String>> {
        if let Some(k) = path.iter().position(|p| *p == m) {
            let mut c: Vec<String> = path[k..].iter().map(|s| s.to_string()).collect();
            c.push(m.to_string());
            return Some(c);
        }
        if done.contains(m) {
            return None;
        }
        path.push(m);
        for next in map.get(m).into_iter().flatten() {
            if let Some(c) = visit(map, next, path, done) {
                return Some(c);
            }
        }
        path.pop();
        done.insert(m);
        None
    }
    let mut done = BTreeSet::new();
    let starts: Vec<&str> = map.keys().copied().collect();
    starts
        .into_iter()
        .find_map(|m| visit(&map, m, &mut Vec::new(), &mut done))
}

#[test]
fn every_module_has_a_layer_and_every_layer_a_module() {
    let (_, files) = import_edges();
    for m in files.keys() {
        assert!(layer_of(m, &LAYERS).is_some(), "{m} has no layer in LAYERS");
    }
    for (entry, _) in LAYERS {
        assert!(
            files
                .keys()
                .any(|m| m == entry || m.starts_with(&format!("{entry}::"))),
            "LAYERS names {entry}, which is no module"
        );
    }
    // The folders are read: a module two folders down is there.
    assert!(files.contains_key("io::pipeline::run_dir"), "{files:?}");
    assert!(files.contains_key("cli::commands::run"), "{files:?}");
    assert!(files.contains_key("lib::simulation::trial"), "{files:?}");
}

#[test]
fn imports_go_down_the_layers_without_circles() {
    let (edges, _) = import_edges();
    let mut map: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
    for e in &edges {
        map.entry(&e.from).or_default().insert(&e.to);
    }
    for (m, uses) in &map {
        println!(
            "{m} -> {}",
            uses.iter().copied().collect::<Vec<_>>().join(", ")
        );
    }
    // The import map is really read: the command line imports the files crate.
    assert!(
        edges
            .iter()
            .any(|e| e.from.starts_with("cli::") && e.to.starts_with("io::"))
    );
    let bad = layer_violations(&edges, &LAYERS);
    assert!(
        bad.is_empty(),
        "imports against the layer order:\n{}",
        bad.join("\n")
    );
    if let Some(c) = find_circle(&edges) {
        panic!("import circle: {}", c.join(" -> "));
    }
}

fn edge(from: &str, to: &str) -> Edge {
    Edge {
        from: from.into(),
        to: to.into(),
        file: format!("{from}.rs"),
        import: format!("crate::{to}"),
    }
}

/// The checks fail when they should: an upward import, a module without a layer, a circle.
#[test]
fn the_checks_catch_a_backward_edge_and_a_circle() {
    let upward = [edge("io::records", "io::render::svg")];
    let bad = layer_violations(&upward, &LAYERS);
    assert_eq!(
        bad,
        [
            "io::records.rs: `crate::io::render::svg` imports io::render::svg (layer 9) into \
          io::records (layer 8), a lower layer"
        ]
    );
    let downward = [edge("cli::commands::run", "io::files::guard")];
    assert!(layer_violations(&downward, &LAYERS).is_empty());
    let unplaced = [edge("cli::stray", "io::files")];
    assert_eq!(layer_violations(&unplaced, &[("io", 0)]).len(), 1);
    let circle = [
        edge("io::render::svg", "io::render::study"),
        edge("io::render::study", "io::render::tables"),
        edge("io::render::tables", "io::render::svg"),
    ];
    assert!(layer_violations(&circle, &LAYERS).is_empty());
    assert_eq!(find_circle(&circle).map(|c| c.len()), Some(4));
    assert_eq!(find_circle(&circle[..2]), None);
}

/// `use` trees: groups, nested groups and macros are read; a path ends where the code does.
#[test]
fn use_trees_are_read() {
    let paths = |s: &str| {
        use_paths(s)
            .into_iter()
            .map(|p| p.join("::"))
            .collect::<Vec<_>>()
    };
    assert_eq!(
        paths("files::guard::{StagedDir, io_err};"),
        ["files::guard::StagedDir", "files::guard::io_err"]
    );
    assert_eq!(
        paths("{note, render::{svg::esc, tables}};"),
        ["note", "render::svg::esc", "render::tables"]
    );
    assert_eq!(paths("out!(\"{x}\")?;"), ["out"]);
    let known: BTreeSet<String> = ["io", "io::files::console", "io::render::svg"]
        .map(String::from)
        .into();
    let path = |s: &str| s.split("::").map(String::from).collect::<Vec<_>>();
    assert_eq!(
        resolve(&path("io::note"), &known).as_deref(),
        Some("io::files::console")
    );
    assert_eq!(
        resolve(&path("io::render::svg::esc"), &known).as_deref(),
        Some("io::render::svg")
    );
}
