//! The import map inside each crate of the workspace, every folder included: the library
//! (`crates/fuzzymotiv/src`), the records (`crates/fuzzymotiv-records/src`), the rendering
//! (`crates/fuzzymotiv-render/src`), the pipeline (`crates/fuzzymotiv-pipeline/src`), the lab and the
//! command line. Each module belongs to a layer of [`LAYERS`] (ARCHITECTURE.md), imports only
//! from its own layer or the ones below, and no modules import each other in a circle.
//!
//! Only what the compiler cannot check is read: the order of the crates is Cargo's (a crate
//! cannot import one that depends on it), so only imports inside a crate are read — the paths a
//! file names after `crate::`, `super::` (any number of them) and `self::`, `use` groups
//! included, comments and tests left out. An import is of the longest module its path starts
//! with; the macros `out!`, `outln!` and `note!` are the command line's `console`'s; the names a
//! crate root re-exports from a crate below ([`REEXPORTS`]) are that crate's, ordered by Cargo,
//! and not read.
//!
//! `cargo test -p fuzzymotiv-cli --test it layers:: -- --nocapture` prints the import map.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The layers, lowest first: a module path, standing for the module and everything in it,
/// and its layer. A module imports only from its own layer and the ones below it. Imports are
/// read inside a crate only, so the numbers order the modules of one crate; they go on rising
/// from crate to crate in Cargo's order.
const LAYERS: [(&str, usize); 37] = [
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
    // fuzzymotiv-records
    ("records::files", 7), // the output guard, inputs, the errors, the terminal macros, locks
    ("records::records", 8), // the output model (one serde type per file), the checkpoint
    ("records", 9),        // the crate root (module declarations)
    // fuzzymotiv-render: tables, the study's statistics, SVG figures, the report, frames
    ("render", 10),
    // fuzzymotiv-pipeline
    ("io::pipeline", 11), // run directory, sweep plan/jobs/merge, lanes, progress
    ("io", 12),           // the crate root (module declarations, re-exports)
    // fuzzymotiv-lab: the browser lab (a library the binary starts)
    ("lab::limits", 13),      // the documented limits
    ("lab::errors", 13),      // the handlers' error (status + the CLI's message)
    ("lab::assets", 13),      // the embedded page, script and style
    ("lab::rooms", 14),       // built-in, drawn and uploaded rooms, checked and saved
    ("lab::robots", 14),      // the built-in robots a run may drive, as the picker draws them
    ("lab::security", 14),    // token, Host check, security headers
    ("lab::live", 14),        // a run's events: generations, paths, result
    ("lab::motivations", 14), // the sliders' motivations: presets, a config's, explain over N
    ("lab::settings", 15),    // the page's settings → the CLI's config checks
    ("lab::runs", 16),        // the run list, the queue and the worker
    ("lab::start", 16),       // the config the lab starts on (--config)
    ("lab::compare", 17),     // two runs side by side, the library's statistics
    ("lab::studies", 17),     // studies of one's own, run by the library's study pipeline
    ("lab::api", 18),         // the routes
    ("lab::server", 19),      // start and stop
    ("lab", 20),              // the crate root
    // fuzzymotiv-cli
    ("cli::args", 21),     // clap options shared by commands
    ("cli::console", 21),  // the terminal: out!, outln!, note! and the notes on stderr
    ("cli::png", 21),      // the resvg rasteriser
    ("cli::progress", 21), // indicatif progress
    ("cli::commands", 22), // one module per command
    ("cli", 23),           // main.rs: parse the arguments, dispatch
];

/// The macros exported at the crate root, by the module that defines them.
const MACROS: [(&str, &str); 3] = [
    ("out", "cli::console"),
    ("outln", "cli::console"),
    ("note", "cli::console"),
];

/// The names a crate root re-exports from a crate below it (`crate::files::…` in the
/// pipeline is `fuzzymotiv_records::files::…`): imports of them are across crates, Cargo's.
const REEXPORTS: [(&str, &[&str]); 1] = [("io", &["files", "records", "render"])];

/// One import: `from` (in `file`) names `import`, which is of the module `to`.
#[derive(Debug, Clone)]
struct Edge {
    from: String,
    to: String,
    file: String,
    import: String,
}

/// The crates read: the prefix of their module paths and their source folder (from this
/// crate's folder).
const CRATES: [(&str, &str); 6] = [
    ("lib", "../fuzzymotiv/src"),
    ("records", "../fuzzymotiv-records/src"),
    ("render", "../fuzzymotiv-render/src"),
    ("io", "../fuzzymotiv-pipeline/src"),
    ("lab", "../fuzzymotiv-lab/src"),
    ("cli", "src"),
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

/// Whether `crate_prefix`'s root re-exports `name` from a crate below ([`REEXPORTS`]).
fn reexported(crate_prefix: &str, name: &str) -> bool {
    REEXPORTS
        .iter()
        .any(|(c, names)| *c == crate_prefix && names.contains(&name))
}

/// The paths `code` (a file of `module`, in the crate `crate_prefix`) imports from its own
/// crate, each with the module path it starts from and as written: after `crate::` (the crate
/// root), after `self::` (the module) and after one or more `super::` (its parents).
fn imported_paths(
    code: &str,
    module: &str,
    crate_prefix: &str,
) -> Vec<(String, Vec<String>, String)> {
    let parent = |m: &str| m.rsplit_once("::").map(|(p, _)| p.to_string());
    let mut out = Vec::new();
    for root in ["crate::", "self::", "super::"] {
        for (at, _) in code.match_indices(root) {
            let before = code[..at].chars().next_back();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue; // `my_crate::`, or a `super::` after another (counted below)
            }
            let mut rest = &code[at + root.len()..];
            let base = match root {
                "crate::" => Some(crate_prefix.to_string()),
                "self::" => Some(module.to_string()),
                _ => {
                    let mut base = parent(module);
                    while let Some(r) = rest.strip_prefix("super::") {
                        rest = r;
                        base = base.and_then(|b| parent(&b));
                    }
                    base
                }
            };
            let written = &code[at..code.len() - rest.len()];
            let base = base.unwrap_or_else(|| panic!("{module}: `{written}` above the crate"));
            for p in use_paths(rest) {
                let import = format!("{written}{}", p.join("::"));
                out.push((base.clone(), p, import));
            }
        }
    }
    out
}

/// Every import inside each crate (`crate::…`, `super::…`, `self::…`), and every module.
fn import_edges() -> (Vec<Edge>, BTreeMap<String, PathBuf>) {
    let mut files = BTreeMap::new();
    let mut prefixes = Vec::new();
    for (prefix, dir) in CRATES {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
        for (module, path) in modules(prefix, &dir) {
            prefixes.push((module.clone(), prefix));
            files.insert(module, path);
        }
    }
    let known: BTreeSet<String> = files.keys().cloned().collect();
    let mut edges = Vec::new();
    for (module, crate_prefix) in prefixes {
        let path = &files[&module];
        let text = code(path);
        for (base, p, import) in imported_paths(&text, &module, crate_prefix) {
            if base == crate_prefix && reexported(crate_prefix, &p[0]) {
                continue;
            }
            let full: Vec<String> = (base.split("::").map(String::from))
                .chain(p.iter().cloned())
                .collect();
            let to = resolve(&full, &known)
                .unwrap_or_else(|| panic!("{}: `{import}` names no module", path.display()));
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
    assert!(files.contains_key("records::files::guard"), "{files:?}");
    assert!(files.contains_key("render::frames::scene"), "{files:?}");
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
    // The import map is really read: the records import the file layer, a command the
    // shared options, the pipeline its own modules.
    let read = |from: &str, to: &str| {
        edges
            .iter()
            .any(|e| e.from.starts_with(from) && e.to.starts_with(to))
    };
    assert!(read("records::records", "records::files"));
    assert!(read("cli::commands", "cli::args"));
    assert!(read("io::pipeline::", "io::pipeline::"));
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
    let upward = [edge(
        "records::files::guard",
        "records::records::checkpoint",
    )];
    let bad = layer_violations(&upward, &LAYERS);
    assert_eq!(
        bad,
        [
            "records::files::guard.rs: `crate::records::records::checkpoint` imports \
          records::records::checkpoint (layer 8) into records::files::guard (layer 7), a lower \
          layer"
        ]
    );
    let downward = [edge("cli::commands::run", "cli::args")];
    assert!(layer_violations(&downward, &LAYERS).is_empty());
    let unplaced = [edge("cli::stray", "cli::args")];
    assert_eq!(layer_violations(&unplaced, &[("cli::args", 0)]).len(), 1);
    let circle = [
        edge("render::svg", "render::study"),
        edge("render::study", "render::tables"),
        edge("render::tables", "render::svg"),
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
    let known: BTreeSet<String> = ["cli", "cli::console", "render::svg"]
        .map(String::from)
        .into();
    let path = |s: &str| s.split("::").map(String::from).collect::<Vec<_>>();
    assert_eq!(
        resolve(&path("cli::note"), &known).as_deref(),
        Some("cli::console")
    );
    assert_eq!(
        resolve(&path("render::svg::esc"), &known).as_deref(),
        Some("render::svg")
    );
    // The pipeline's `crate::files::…` is the records crate's, re-exported: not read.
    assert!(reexported("io", "files") && !reexported("io", "pipeline"));
}

/// Issue #56 item 5: `super::` (any number) and `self::` imports are read, each from the module
/// it starts at, so a circle through them is seen.
#[test]
fn super_and_self_imports_are_read() {
    let code = "use super::plain::Plain;\nuse super::super::random::Streams;\n\
                use self::inner::X;\nuse crate::params::FieldError;\nlet s = Self::new();\n";
    let got: Vec<(String, String)> = imported_paths(code, "lib::experiment::config", "lib")
        .into_iter()
        .map(|(base, p, _)| (base, p.join("::")))
        .collect();
    let want = [
        ("lib", "params::FieldError"),
        ("lib::experiment::config", "inner::X"),
        ("lib::experiment", "plain::Plain"),
        ("lib", "random::Streams"),
    ]
    .map(|(b, p)| (b.to_string(), p.to_string()));
    assert_eq!(got, want);
    // A circle through `super::` is an edge like any other.
    let known: BTreeSet<String> = ["lib::experiment::config", "lib::experiment::plain"]
        .map(String::from)
        .into();
    let (base, p, _) =
        &imported_paths("use super::plain::Plain;", "lib::experiment::config", "lib")[0];
    let full: Vec<String> = base
        .split("::")
        .map(String::from)
        .chain(p.clone())
        .collect();
    assert_eq!(
        resolve(&full, &known).as_deref(),
        Some("lib::experiment::plain")
    );
}

/// The library crates, read by [`library_violations`]: every crate but the command line's.
const LIBRARIES: [(&str, &str); 5] = [
    ("lib", "../fuzzymotiv/src"),
    ("records", "../fuzzymotiv-records/src"),
    ("render", "../fuzzymotiv-render/src"),
    ("io", "../fuzzymotiv-pipeline/src"),
    ("lab", "../fuzzymotiv-lab/src"),
];

/// What a library crate's code never holds (issue #56 item 2): a print, an exit or an abort
/// (its notes are returned or handed to the caller's `Notes`; its failures are errors), and
/// process-wide mutable state (a `static` of a `Once`, lock, cell or atomic, a `thread_local!`,
/// a `static mut`). A `static` of plain data computed once (`LazyLock<Vec<_>>`) is a constant.
const FORBIDDEN: [&str; 10] = [
    "print!",
    "println!",
    "dbg!",
    "process::exit",
    "process::abort",
    "abort()",
    "io::stdout",
    "io::stderr",
    "thread_local!",
    "static mut",
];

/// The types that make a `static` mutable state.
const STATEFUL: [&str; 6] = ["Once", "Atomic", "Mutex", "RwLock", "Cell", "Lazy<"];

/// The only process-wide state allowed in a library, with why: the engine's memo of sightings
/// (`simulation/memo.rs`: per-thread tables and the registry of the arenas sharing them), a
/// cache whose every lookup returns exactly the bits the computation returns (results are
/// identical with or without it, whatever the threads); and the engine's interned robots and
/// sensor tables (`RobotSpec::intern`, `SensorTable::intern`: equal ones share one `'static`
/// copy, so a value given is always answered with an equal one). Nothing a front sees or a
/// result holds depends on them; making them owned (`Arc`) is left for another change.
const ALLOWED: [(&str, &str); 4] = [
    ("lib::simulation::memo", "thread_local!"),
    ("lib::simulation::memo", "static"),
    ("lib::simulation::robot_spec", "static"),
    ("lib::simulation::sensor_table", "static"),
];

/// Whether `path` is a test module's file: declared by `#[cfg(test)] mod NAME;` in its crate.
fn test_only(path: &Path, crate_texts: &[String]) -> bool {
    let stem = path.file_stem().unwrap().to_string_lossy();
    let name = if stem == "mod" {
        path.parent()
            .unwrap()
            .file_name()
            .unwrap()
            .to_string_lossy()
    } else {
        stem
    };
    let decl = format!("mod {name};");
    crate_texts.iter().any(|t| {
        t.match_indices(&decl)
            .any(|(at, _)| t[..at].trim_end().ends_with("#[cfg(test)]"))
    })
}

/// Every print, exit, abort and process-wide state in `code` (a file of `module`), as
/// messages naming the file and the line.
fn forbidden_in(module: &str, file: &str, code: &str) -> Vec<String> {
    let allowed = |what: &str| ALLOWED.contains(&(module, what));
    let mut out = Vec::new();
    for (n, line) in code.lines().enumerate() {
        let what = FORBIDDEN
            .iter()
            .find(|f| line.contains(**f))
            .copied()
            .or_else(|| {
                let t = line.trim_start();
                let t = t
                    .strip_prefix("pub ")
                    .or(t.strip_prefix("pub(crate) "))
                    .unwrap_or(t);
                (t.starts_with("static ") && STATEFUL.iter().any(|s| t.contains(s)))
                    .then_some("static")
            });
        if let Some(what) = what.filter(|w| !allowed(w)) {
            out.push(format!("{file}:{}: `{what}`: {}", n + 1, line.trim()));
        }
    }
    out
}

/// Every forbidden line of the library crates (tests and comments left out).
fn library_violations() -> Vec<String> {
    let mut out = Vec::new();
    for (prefix, dir) in LIBRARIES {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
        let files = modules(prefix, &dir);
        let texts: Vec<String> = (files.iter())
            .map(|(_, p)| std::fs::read_to_string(p).unwrap())
            .collect();
        for (module, path) in &files {
            if !test_only(path, &texts) {
                out.extend(forbidden_in(
                    module,
                    &path.display().to_string(),
                    &code(path),
                ));
            }
        }
    }
    out
}

/// Issue #56 item 2: the library crates never print, exit, abort or keep process-wide state
/// (but the engine's memo, [`ALLOWED`]): the fronts do.
#[test]
fn library_crates_never_print_exit_abort_or_keep_process_state() {
    let bad = library_violations();
    assert!(bad.is_empty(), "in the library crates:\n{}", bad.join("\n"));
}

/// The check fails when it should: a note printed, an abort, a `static Once`, process state in
/// a module that is not allowed it; a constant and the memo's state pass.
#[test]
fn the_library_check_catches_prints_aborts_and_process_state() {
    let code = "fn f() {\n    eprintln!(\"note: {x}\");\n    std::process::abort();\n}\n\
                static SAID: std::sync::Once = std::sync::Once::new();\n\
                pub static N: AtomicUsize = AtomicUsize::new(0);\n\
                thread_local! { static T: Cell<u8> = Cell::new(0); }\n\
                pub static PALETTE: LazyLock<Vec<u8>> = LazyLock::new(Vec::new);\n";
    let bad = forbidden_in("records::files::inputs", "inputs.rs", code);
    assert_eq!(bad.len(), 5, "{bad:#?}");
    assert!(bad[0].starts_with("inputs.rs:2: `println!`"), "{bad:?}");
    // The memo keeps its state, and prints no more than any other module.
    assert_eq!(
        forbidden_in("lib::simulation::memo", "memo.rs", code).len(),
        2
    );
    let decl = ["#[cfg(test)]\nmod playground;\n".to_string()];
    assert!(test_only(
        Path::new("src/export/aseba/playground.rs"),
        &decl
    ));
    assert!(!test_only(Path::new("src/export/aseba/interp.rs"), &decl));
}

/// The methods that read or rewrite text.
const TEXT_METHODS: [&str; 12] = [
    "replace",
    "replacen",
    "contains",
    "starts_with",
    "ends_with",
    "find",
    "rfind",
    "strip_prefix",
    "strip_suffix",
    "split_once",
    "matches",
    "trim_start_matches",
];

/// Receivers that are a message: an error's text (`msg`, `message`, `e.message()`, `e.reason`,
/// `e.to_string()` of an error named `e`, `err`, `error` or `inner`) or its source's
/// (`source_name`).
fn is_message(receiver: &str) -> bool {
    let parts: Vec<&str> = receiver.split('.').collect();
    let last = parts[parts.len() - 1];
    let before = parts.len().checked_sub(2).map(|i| parts[i]);
    matches!(
        last,
        "msg" | "message" | "message()" | "reason" | "source_name"
    ) || (last == "to_string()"
        && before.is_some_and(|b| matches!(b, "e" | "err" | "error" | "inner")))
}

/// Every line of `code` that reads or rewrites a message's text (`msg.contains("missing
/// field")`, `e.reason.replace("got", …)`, `source_name.ends_with(…)`), as `file:line: line`.
fn message_reads_in(file: &str, code: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (n, line) in code.lines().enumerate() {
        let hit = TEXT_METHODS.iter().any(|m| {
            line.match_indices(&format!(".{m}(")).any(|(at, _)| {
                let start = line[..at]
                    .rfind(|c: char| !(c.is_alphanumeric() || "_.()".contains(c)))
                    .map_or(0, |i| i + 1);
                let receiver = line[start..at].trim_start_matches(['(', '.']);
                is_message(receiver)
            })
        });
        if hit {
            out.push(format!("{file}:{}: {}", n + 1, line.trim()));
        }
    }
    out
}

/// Every line of the workspace's and the Python module's code (tests and comments left out)
/// that reads or rewrites a message.
fn message_reads() -> Vec<String> {
    (workspace_code().iter())
        .flat_map(|(file, code)| message_reads_in(file, code))
        .collect()
}

/// Issue #56 item 3: no message is parsed, matched or rewritten: what code needs to know of an
/// error (the field missing, the key not taken, the value got) is data of the error's type,
/// and each message is rendered once from it.
#[test]
fn no_message_is_parsed_matched_or_rewritten() {
    let bad = message_reads();
    assert!(
        bad.is_empty(),
        "messages read or rewritten (keep what is needed as data of the error instead):\n{}",
        bad.join("\n")
    );
}

/// The check fails when it should: the three ways a message was read before (a field parsed
/// out of serde's text, a suffix checked, another check's words rewritten); text that is not a
/// message passes.
#[test]
fn the_message_check_catches_parsing_matching_and_rewriting() {
    let code = "    if msg.contains(\"missing field\") {\n\
                let at = if source_name.ends_with(\"(with --set overrides)\") {\n\
                FieldError::new(f, e.reason.replace(\"got\", \"got an end\"))\n\
                let inner = inner.to_string().replace(\"expected f64\", \"a number\");\n\
                if e.message().starts_with(\"unknown field\") {\n\
                let ok = name.ends_with(\".toml\") && path.contains(&p);\n\
                let s = e.path().to_string().starts_with('[');\n";
    let bad = message_reads_in("c.rs", code);
    assert_eq!(bad.len(), 5, "{bad:#?}");
    assert!(bad[0].starts_with("c.rs:1: if msg.contains"), "{bad:?}");
}

/// The workspace's code files (the Python module's included), tests left out: (file, code).
fn workspace_code() -> Vec<(String, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dirs = CRATES
        .iter()
        .copied()
        .chain([("python", "../../python/src")]);
    let mut out = Vec::new();
    for (prefix, dir) in dirs {
        let files = modules(prefix, &root.join(dir));
        let texts: Vec<String> = (files.iter())
            .map(|(_, p)| std::fs::read_to_string(p).unwrap())
            .collect();
        for (_, path) in &files {
            if !test_only(path, &texts) {
                out.push((path.display().to_string(), code(path)));
            }
        }
    }
    out
}

/// Every `type A = B;` of a module (not an impl's associated type: a line not indented) in
/// `files` where `B` (its last path segment) is a struct or enum the files define: one type
/// under two names.
fn aliases_in(files: &[(String, String)]) -> Vec<String> {
    let defined: BTreeSet<&str> = (files.iter())
        .flat_map(|(_, code)| code.lines())
        .filter_map(|line| {
            let t = line.trim_start();
            let t = t
                .strip_prefix("pub ")
                .or(t.strip_prefix("pub(crate) "))
                .unwrap_or(t);
            let rest = t.strip_prefix("struct ").or(t.strip_prefix("enum "))?;
            rest.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .next()
        })
        .collect();
    let mut out = Vec::new();
    for (file, code) in files {
        for (n, line) in code.lines().enumerate() {
            let t = line;
            let t = t
                .strip_prefix("pub ")
                .or(t.strip_prefix("pub(crate) "))
                .unwrap_or(t);
            let Some((_, target)) = t.strip_prefix("type ").and_then(|r| r.split_once('=')) else {
                continue;
            };
            let target = target.trim().trim_end_matches(';').trim();
            let last = target.rsplit("::").next().unwrap_or(target);
            if defined.contains(last) {
                out.push(format!("{file}:{}: {}", n + 1, line.trim()));
            }
        }
    }
    out
}

/// Issue #56 item 4: no type goes by two names (`ConfigError = RoomError = FieldError`,
/// `HomeZone = Zone` were one type under three and two): each has one name, its users use it.
#[test]
fn no_type_goes_by_two_names() {
    let bad = aliases_in(&workspace_code());
    assert!(
        bad.is_empty(),
        "aliases of the workspace's own types:\n{}",
        bad.join("\n")
    );
}

/// The alias check fails when it should: an alias of a struct the files define, by path or
/// not; an alias of a tuple, a generic or another crate's type passes.
#[test]
fn the_alias_check_catches_a_second_name() {
    let files = [
        (
            "a.rs".to_string(),
            "pub struct FieldError {}\npub enum Zone {}\n".to_string(),
        ),
        (
            "b.rs".to_string(),
            "pub type ConfigError = FieldError;\npub type HomeZone = crate::room::Zone;\n\
             pub type Genome = Vec<f64>;\npub type Rng64 = rand_xoshiro::Xoshiro256PlusPlus;\n\
             pub type Part<'a> = (&'a str, &'a str);\n\
             impl Iterator for Zones {\n    type Item = Zone;\n}\n"
                .to_string(),
        ),
    ];
    let bad = aliases_in(&files);
    assert_eq!(bad.len(), 2, "{bad:#?}");
    assert!(
        bad[0].starts_with("b.rs:1: pub type ConfigError"),
        "{bad:?}"
    );
}
