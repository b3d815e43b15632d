//! The documents hold together: every relative link of README.md, EXPERIMENTS.md,
//! ARCHITECTURE.md, docs/**/*.md, bench/README.md, bench/HISTORY.md and bench/enki/README.md
//! resolves (a `#anchor` to a Markdown file names one of its headings, as GitHub spells them),
//! and every shell block they mark as runnable runs. ARCHITECTURE.md names only files, folders,
//! crates, types and functions that exist; bench/README.md and docs/guide/performance.md hold
//! the current figures, the log apart (bench/HISTORY.md).
//!
//! A runnable block is a fenced block whose info string is `sh runnable`:
//!
//! ````text
//! ```sh runnable
//! fuzzymotiv run configs/tiny.toml --out out/tiny --set ga.generations=3
//! ```
//! ````
//!
//! The blocks of one document run in order (a later block may use an earlier one's output) with
//! `sh -e`, in a scratch directory holding a copy of the repository's `configs/` and `rooms/`,
//! with `fuzzymotiv` the binary under test (first on `PATH`). Mark only cheap blocks: small
//! sizes through `--set`, or `--quick`; never a paper-scale run. Python blocks are run by
//! python/tests/ (test_readme.py, test_frames.py, test_gym.py).

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use pulldown_cmark::{CodeBlockKind, Event, Options, Parser, Tag, TagEnd};

use crate::common;

use common::repo;

/// The documents, relative to the repository root.
fn documents() -> Vec<PathBuf> {
    let mut docs: Vec<PathBuf> = [
        "README.md",
        "EXPERIMENTS.md",
        "ARCHITECTURE.md",
        "bench/README.md",
        "bench/HISTORY.md",
        "bench/enki/README.md",
    ]
    .iter()
    .map(PathBuf::from)
    .collect();
    let mut stack = vec![PathBuf::from("docs")];
    while let Some(dir) = stack.pop() {
        for entry in fs::read_dir(repo().join(&dir)).expect("docs/ is readable") {
            let path = dir.join(entry.expect("a docs/ entry").file_name());
            if repo().join(&path).is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "md") {
                docs.push(path);
            }
        }
    }
    docs.sort();
    docs
}

/// What the checks need of one Markdown document.
#[derive(Default)]
struct Doc {
    /// Link and image destinations, with their line.
    links: Vec<(String, usize)>,
    /// The anchors of its headings, as GitHub makes them.
    anchors: Vec<String>,
    /// The text of its `sh runnable` blocks, with their line.
    runnable: Vec<(String, usize)>,
}

fn parse(text: &str) -> Doc {
    let line_of = |offset: usize| text[..offset].matches('\n').count() + 1;
    let mut doc = Doc::default();
    let mut heading: Option<String> = None;
    let mut block: Option<(String, usize)> = None;
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let options = Options::ENABLE_TABLES | Options::ENABLE_STRIKETHROUGH;
    for (event, range) in Parser::new_ext(text, options).into_offset_iter() {
        match event {
            Event::Start(Tag::Link { dest_url, .. } | Tag::Image { dest_url, .. }) => {
                doc.links.push((dest_url.to_string(), line_of(range.start)));
            }
            Event::Start(Tag::Heading { .. }) => heading = Some(String::new()),
            Event::End(TagEnd::Heading(_)) => {
                let slug = slug(&heading.take().unwrap_or_default());
                let n = seen.entry(slug.clone()).or_insert(0);
                doc.anchors.push(match *n {
                    0 => slug,
                    k => format!("{slug}-{k}"),
                });
                *n += 1;
            }
            Event::Start(Tag::CodeBlock(CodeBlockKind::Fenced(info))) => {
                let words: Vec<&str> = info.split_whitespace().collect();
                if words.first() == Some(&"sh") && words.contains(&"runnable") {
                    block = Some((String::new(), line_of(range.start)));
                }
            }
            Event::End(TagEnd::CodeBlock) => doc.runnable.extend(block.take()),
            Event::Text(t) | Event::Code(t) => {
                if let Some(h) = heading.as_mut() {
                    h.push_str(&t);
                }
                if let Some((b, _)) = block.as_mut() {
                    b.push_str(&t);
                }
            }
            _ => {}
        }
    }
    doc
}

/// A heading's anchor as GitHub makes it: lower case; letters, digits, `-` and `_` kept, spaces
/// made `-`, everything else dropped.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// The broken relative links of the document `doc` (relative to `root`), one line each.
fn broken_links(root: &Path, doc: &Path, parsed: &Doc) -> Vec<String> {
    let mut broken = Vec::new();
    let dir = doc.parent().unwrap_or(Path::new(""));
    for (dest, line) in &parsed.links {
        if dest.contains("://") || dest.starts_with("mailto:") {
            continue;
        }
        let (path, anchor) = dest.split_once('#').unwrap_or((dest, ""));
        let at = format!("{}:{line}: `{dest}`", doc.display());
        if path.is_empty() {
            if !parsed.anchors.iter().any(|a| a == anchor) {
                broken.push(format!("{at}: no heading here with the anchor #{anchor}"));
            }
            continue;
        }
        let target = dir.join(path);
        if path.starts_with('/') || !root.join(&target).exists() {
            broken.push(format!("{at}: no file {}", target.display()));
            continue;
        }
        if anchor.is_empty() || target.extension().is_none_or(|e| e != "md") {
            continue;
        }
        let text = fs::read_to_string(root.join(&target)).expect("a linked document is readable");
        if !parse(&text).anchors.iter().any(|a| a == anchor) {
            broken.push(format!(
                "{at}: {} has no heading with the anchor #{anchor}",
                target.display()
            ));
        }
    }
    broken
}

#[test]
fn every_relative_link_resolves() {
    let root = repo();
    let (mut links, mut broken) = (0, Vec::new());
    for doc in documents() {
        let parsed = parse(&fs::read_to_string(root.join(&doc)).expect("a document is readable"));
        links += parsed.links.len();
        broken.extend(broken_links(&root, &doc, &parsed));
    }
    assert!(links >= 100, "only {links} links found in the documents");
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn a_missing_file_and_a_missing_anchor_are_found() {
    let root = tempfile::tempdir().unwrap();
    fs::create_dir(root.path().join("guide")).unwrap();
    fs::write(
        root.path().join("guide/a.md"),
        "# A page\n\n## Why ten seeds?\n",
    )
    .unwrap();
    let text = "[ok](guide/a.md#why-ten-seeds) [ok](guide/a.md#a-page) [ok](#top) \
        [web](https://example.org/x.md#nothing)\n\n# Top\n\n[gone](guide/b.md) \
        [no anchor](guide/a.md#why-ten) ![img](guide/none.svg) [root](/README.md) [here](#bottom)\n";
    let broken = broken_links(root.path(), Path::new("README.md"), &parse(text));
    assert_eq!(broken.len(), 5, "{broken:#?}");
    assert!(broken[0].contains("README.md:5: `guide/b.md`: no file"));
    assert!(broken[1].contains("has no heading with the anchor #why-ten"));
    assert!(broken[2].contains("guide/none.svg"));
    assert!(broken[3].contains("/README.md"));
    assert!(broken[4].contains("no heading here with the anchor #bottom"));
}

#[test]
fn anchors_are_spelled_as_github_spells_them() {
    let doc = parse(
        "# reproduce: the paper's study\n## Sweeps from Python (Dask, any executor)\n\
         ## `fm.GA`: ask/tell\n## Notes\n## Notes\n```sh runnable\n# Not a heading\necho hi\n```\n",
    );
    assert_eq!(
        doc.anchors,
        [
            "reproduce-the-papers-study",
            "sweeps-from-python-dask-any-executor",
            "fmga-asktell",
            "notes",
            "notes-1"
        ]
    );
    assert_eq!(
        doc.runnable,
        [("# Not a heading\necho hi\n".to_string(), 6)]
    );
}

/// Copies the directory `from` into `to`, recursively.
fn copy_dir(from: &Path, to: &Path) {
    fs::create_dir_all(to).unwrap();
    for entry in fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            fs::copy(entry.path(), &target).unwrap();
        }
    }
}

/// Runs a document's runnable blocks in order in a scratch copy of configs/ and rooms/; the
/// failures, one message each.
fn run_blocks(doc: &Path, blocks: &[(String, usize)]) -> Vec<String> {
    let scratch = tempfile::tempdir().unwrap();
    for dir in ["configs", "rooms"] {
        copy_dir(&repo().join(dir), &scratch.path().join(dir));
    }
    let bin = scratch.path().join(".bin");
    fs::create_dir(&bin).unwrap();
    std::os::unix::fs::symlink(env!("CARGO_BIN_EXE_fuzzymotiv"), bin.join("fuzzymotiv")).unwrap();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let mut failures = Vec::new();
    for (block, line) in blocks {
        let out = Command::new("sh")
            .args(["-e", "-c", block])
            .current_dir(scratch.path())
            .env("PATH", &path)
            .output()
            .expect("sh runs");
        if !out.status.success() {
            failures.push(format!(
                "{}:{line}: the runnable block failed ({}):\n{block}--- stderr:\n{}",
                doc.display(),
                out.status,
                String::from_utf8_lossy(&out.stderr)
            ));
        }
    }
    failures
}

#[test]
fn runnable_blocks_run() {
    let (mut count, mut failures) = (0, Vec::new());
    for doc in documents() {
        let parsed = parse(&fs::read_to_string(repo().join(&doc)).unwrap());
        if parsed.runnable.is_empty() {
            continue;
        }
        count += parsed.runnable.len();
        failures.extend(run_blocks(&doc, &parsed.runnable));
    }
    assert!(count >= 5, "only {count} runnable blocks found");
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn a_failing_runnable_block_is_reported() {
    let blocks = [
        ("fuzzymotiv rooms\n".to_string(), 3),
        ("fuzzymotiv run configs/no-such.toml\n".to_string(), 9),
    ];
    let failures = run_blocks(Path::new("guide.md"), &blocks);
    assert_eq!(failures.len(), 1, "{failures:#?}");
    assert!(failures[0].starts_with("guide.md:9: the runnable block failed"));
    assert!(failures[0].contains("no-such.toml"));
}

// ---------------------------------------------------------------------------------------------
// ARCHITECTURE.md against the tree (issue #56 item 7): what a test can check of its claims.

/// One row of a table of ARCHITECTURE.md: its line, the code spans of its first cell, and
/// those of its other cells.
#[derive(Debug, Default)]
struct Row {
    line: usize,
    first: Vec<String>,
    rest: Vec<String>,
}

/// What the checks read of ARCHITECTURE.md: the rows of its tables (the header rows left
/// out), every code span with its line, and the text of its fenced blocks.
#[derive(Debug, Default)]
struct Architecture {
    rows: Vec<Row>,
    spans: Vec<(String, usize)>,
    fenced: String,
}

fn read_architecture(text: &str) -> Architecture {
    let line_of = |offset: usize| text[..offset].matches('\n').count() + 1;
    let mut arch = Architecture::default();
    let (mut row, mut cell, mut in_head, mut in_block) = (None::<Row>, 0, false, false);
    let options = Options::ENABLE_TABLES | Options::ENABLE_STRIKETHROUGH;
    for (event, range) in Parser::new_ext(text, options).into_offset_iter() {
        match event {
            Event::Start(Tag::TableHead) => in_head = true,
            Event::End(TagEnd::TableHead) => in_head = false,
            Event::Start(Tag::TableRow) => {
                cell = 0;
                row = Some(Row {
                    line: line_of(range.start),
                    ..Row::default()
                });
            }
            Event::End(TagEnd::TableRow) => arch.rows.extend(row.take()),
            Event::End(TagEnd::TableCell) => cell += 1,
            Event::Start(Tag::CodeBlock(_)) => in_block = true,
            Event::End(TagEnd::CodeBlock) => in_block = false,
            Event::Text(t) if in_block => arch.fenced.push_str(&t),
            Event::Code(code) => {
                arch.spans.push((code.to_string(), line_of(range.start)));
                if let (Some(r), false) = (row.as_mut(), in_head) {
                    match cell {
                        0 => r.first.push(code.to_string()),
                        _ => r.rest.push(code.to_string()),
                    }
                }
            }
            _ => {}
        }
    }
    arch
}

/// A code span that names a source file or a folder of the repository: a file of source
/// (`.rs`, `.py`, `.cpp`, `.js`, `.css`, `.sh`) or a folder (`name/`), placeholders in capitals
/// (`DIR/runs/`) and output files (`report.md`, `config.resolved.toml`) left out.
fn names_source(span: &str) -> bool {
    let word = span.trim();
    let folder = word.ends_with('/')
        && word
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || "_-./".contains(c));
    let source = [".rs", ".py", ".cpp", ".js", ".css", ".sh"]
        .iter()
        .any(|ext| word.ends_with(ext))
        && !word.contains(char::is_whitespace);
    folder || source
}

/// The first of `bases` (folders relative to `root`) under which `path` exists.
fn resolve(root: &Path, bases: &[PathBuf], path: &str) -> Option<PathBuf> {
    bases
        .iter()
        .map(|b| b.join(path))
        .find(|p| root.join(p).exists())
}

/// The folders a resolved path lets the rest of its row name files relative to: its own
/// folder (or itself, a folder) and a module's folder beside it (`report.rs` → `report/`).
fn bases_of(root: &Path, path: &Path) -> Vec<PathBuf> {
    if root.join(path).is_dir() {
        return vec![path.to_path_buf()];
    }
    let mut bases = vec![path.parent().unwrap_or(Path::new("")).to_path_buf()];
    let stem = path.with_extension("");
    if root.join(&stem).is_dir() {
        bases.push(stem);
    }
    bases
}

/// The files and folders ARCHITECTURE.md names that do not exist in the tree under `root`, one
/// message each. A table row's first cell names paths relative to the crate (or top folder) of
/// the last unindented row (`  src/params.rs` under `crates/fuzzymotiv/`), a later path of the
/// cell also relative to the one before it (`src/report.rs`, `report/`); the other cells name
/// source files relative to the root, `crates/`, the crate, its `src/`, or a folder the row
/// named before. Code spans outside tables name paths from the root or `crates/`.
fn missing_paths(root: &Path, arch: &Architecture) -> Vec<String> {
    let mut missing = Vec::new();
    let mut top = PathBuf::new();
    for row in &arch.rows {
        let mut row_dirs: Vec<PathBuf> = Vec::new();
        for (i, entry) in row.first.iter().enumerate() {
            let path = entry.split_whitespace().next().unwrap_or("");
            let tried: Vec<PathBuf> = if i == 0 && !entry.starts_with(' ') {
                top = PathBuf::from(path);
                vec![PathBuf::new()]
            } else if i == 0 {
                vec![top.clone()]
            } else {
                let mut t = vec![top.clone()];
                t.extend(row_dirs.iter().cloned());
                t.push(PathBuf::new());
                t
            };
            match resolve(root, &tried, path) {
                Some(found) => row_dirs.extend(bases_of(root, &found)),
                None => missing.push(format!(
                    "ARCHITECTURE.md:{}: `{path}` (under {}) does not exist",
                    row.line,
                    top.display()
                )),
            }
        }
        let mut bases = vec![
            PathBuf::new(),
            PathBuf::from("crates"),
            top.clone(),
            top.join("src"),
        ];
        bases.extend(row_dirs);
        for span in row.rest.iter().filter(|s| names_source(s)) {
            match resolve(root, &bases, span.trim()) {
                Some(found) => bases.extend(bases_of(root, &found)),
                None => missing.push(format!(
                    "ARCHITECTURE.md:{}: `{span}` is named in the row of {} but is in none of \
                     its folders",
                    row.line,
                    top.display()
                )),
            }
        }
    }
    let in_rows: BTreeSet<usize> = arch.rows.iter().map(|r| r.line).collect();
    for (span, line) in &arch.spans {
        let outside = !in_rows.contains(line) && names_source(span);
        let roots = [PathBuf::new(), PathBuf::from("crates")];
        if outside && resolve(root, &roots, span.trim()).is_none() {
            missing.push(format!("ARCHITECTURE.md:{line}: `{span}` does not exist"));
        }
    }
    missing
}

#[test]
fn architecture_names_only_files_and_folders_that_exist() {
    let text = fs::read_to_string(repo().join("ARCHITECTURE.md")).unwrap();
    let arch = read_architecture(&text);
    assert!(arch.rows.len() >= 100, "only {} rows read", arch.rows.len());
    let missing = missing_paths(&repo(), &arch);
    assert!(missing.is_empty(), "{}", missing.join("\n"));
}

#[test]
fn a_path_architecture_names_that_is_gone_is_found() {
    let root = tempfile::tempdir().unwrap();
    for dir in ["crates/a/src/report", "crates/a/tests", "scripts"] {
        fs::create_dir_all(root.path().join(dir)).unwrap();
    }
    for file in [
        "crates/a/src/report.rs",
        "crates/a/src/lib.rs",
        "scripts/t.py",
    ] {
        fs::write(root.path().join(file), "").unwrap();
    }
    let text = "| folder / file | purpose |\n|---|---|\n\
        | `crates/a/` | a crate |\n\
        | `  src/report.rs`, `report/` | the report, `lib.rs`, `gone.rs` |\n\
        | `  src/old.rs` | moved away |\n\
        | `  tests/` | `scripts/t.py`, `DIR/runs/`, `report.md` |\n\
        | `scripts/t.py`, `u.py` | a script |\n\nSee `crates/a/src/none.rs`.\n";
    let missing = missing_paths(root.path(), &read_architecture(text));
    assert_eq!(missing.len(), 4, "{missing:#?}");
    assert!(missing[0].contains(":4: `gone.rs`"), "{}", missing[0]);
    assert!(
        missing[1].contains(":5: `src/old.rs` (under crates/a/)"),
        "{}",
        missing[1]
    );
    assert!(missing[2].contains(":7: `u.py`"));
    assert!(missing[3].contains(":9: `crates/a/src/none.rs`"));
}

/// The workspace's member folders, from the root Cargo.toml.
fn workspace_members() -> Vec<String> {
    let text = fs::read_to_string(repo().join("Cargo.toml")).unwrap();
    let manifest: toml::Table = text.parse().expect("Cargo.toml parses");
    let members = manifest["workspace"]["members"].as_array().unwrap();
    members
        .iter()
        .map(|m| m.as_str().unwrap().to_string())
        .collect()
}

/// The crate names a text mentions: `fuzzymotiv-…` words (`fuzzymotiv_…` counts as its
/// `-` spelling).
fn crate_names(text: &str) -> BTreeSet<String> {
    let text = text.replace("fuzzymotiv_", "fuzzymotiv-");
    text.match_indices("fuzzymotiv-")
        .map(|(i, _)| {
            let rest = &text[i + "fuzzymotiv-".len()..];
            let end = rest
                .find(|c: char| !c.is_ascii_lowercase())
                .unwrap_or(rest.len());
            format!("fuzzymotiv-{}", &rest[..end])
        })
        .collect()
}

#[test]
fn architecture_crate_rows_and_diagram_are_the_workspace_crates() {
    let text = fs::read_to_string(repo().join("ARCHITECTURE.md")).unwrap();
    let arch = read_architecture(&text);
    let members: BTreeSet<String> = workspace_members()
        .iter()
        .map(|m| format!("{}/", m))
        .collect();
    let rows: BTreeSet<String> = (arch.rows.iter())
        .filter_map(|r| r.first.first())
        .filter(|p| p.starts_with("crates/") && p.matches('/').count() == 2 && p.ends_with('/'))
        .cloned()
        .collect();
    assert_eq!(
        rows, members,
        "the crate rows of ARCHITECTURE.md's folder table"
    );
    let names: BTreeSet<String> = members
        .iter()
        .map(|m| {
            m.trim_end_matches('/')
                .rsplit('/')
                .next()
                .unwrap()
                .to_string()
        })
        .collect();
    let named = crate_names(&text);
    let unknown: Vec<&String> = named.difference(&names).collect();
    assert!(
        unknown.is_empty(),
        "ARCHITECTURE.md names crates that are not in the workspace: {unknown:?}"
    );
    for name in &names {
        assert!(
            arch.fenced.contains(name.as_str()),
            "the crate diagram of ARCHITECTURE.md leaves out {name}"
        );
    }
}

/// ARCHITECTURE.md: "The fronts (the binary, the lab, `python/`) depend on
/// `fuzzymotiv-pipeline` alone for all three file crates".
#[test]
fn the_fronts_reach_the_file_crates_through_the_pipeline_only() {
    for front in ["crates/fuzzymotiv-cli", "crates/fuzzymotiv-lab", "python"] {
        let text = fs::read_to_string(repo().join(front).join("Cargo.toml")).unwrap();
        let manifest: toml::Table = text.parse().expect("a Cargo.toml parses");
        let deps = manifest["dependencies"].as_table().unwrap();
        assert!(deps.contains_key("fuzzymotiv-pipeline"), "{front}");
        for direct in ["fuzzymotiv-records", "fuzzymotiv-render"] {
            assert!(
                !deps.contains_key(direct),
                "{front} depends on {direct} itself, where ARCHITECTURE.md says the fronts \
                 reach it through fuzzymotiv-pipeline"
            );
        }
    }
}

#[test]
fn an_old_crate_name_is_found() {
    let named = crate_names("over `fuzzymotiv_io::pipeline` and fuzzymotiv-records (the records)");
    assert_eq!(
        named.into_iter().collect::<Vec<_>>(),
        ["fuzzymotiv-io", "fuzzymotiv-records"]
    );
}

/// Names ARCHITECTURE.md quotes that are not declared in our sources: the standard library's
/// `ControlFlow` and `Break`, the HTTP header `Host`, Python's `True`, plotters'
/// `BackendCoord` (why the render crate does not use plotters), record columns and measure
/// prefixes.
const NOT_DECLARED: [&str; 11] = [
    "ControlFlow",
    "Break",
    "Host",
    "True",
    "BackendCoord",
    "homing_pct",
    "mission_done_pct",
    "NAME_pct",
    "distance_mm",
    "enki_",
    "gap_",
];

/// The names the Rust and Python sources under `dirs` (relative to `root`) declare: after
/// `struct`, `enum`, `trait`, `type`, `union`, `const`, `static`, `fn`, `mod`, `def` or `class`.
fn declared_names(root: &Path, dirs: &[&str]) -> BTreeSet<String> {
    const KEYWORDS: [&str; 11] = [
        "struct", "enum", "trait", "type", "union", "const", "static", "fn", "mod", "def", "class",
    ];
    let mut names = BTreeSet::new();
    let mut stack: Vec<PathBuf> = dirs.iter().map(|d| root.join(d)).collect();
    while let Some(dir) = stack.pop() {
        for entry in fs::read_dir(&dir).into_iter().flatten().flatten() {
            let path = entry.path();
            if path.is_dir() {
                if path.file_name().is_some_and(|n| n != "target") {
                    stack.push(path);
                }
                continue;
            }
            if path.extension().is_none_or(|e| e != "rs" && e != "py") {
                continue;
            }
            let text = fs::read_to_string(&path).unwrap_or_default();
            let words: Vec<&str> = text.split_whitespace().collect();
            for pair in words.windows(2) {
                if KEYWORDS.contains(&pair[0]) {
                    let name: String = (pair[1].chars())
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect();
                    names.insert(name);
                }
            }
        }
    }
    names
}

/// The identifiers of the code spans `spans` that name code — a type (`CamelCase`) or a function
/// or module (`snake_case` with an underscore), not a file (followed by `.`) or a crate
/// (`fuzzymotiv_…`) — and that `declared` does not hold, with their line.
fn undeclared(spans: &[(String, usize)], declared: &BTreeSet<String>) -> Vec<String> {
    let mut found = Vec::new();
    for (span, line) in spans {
        let mut rest = span.as_str();
        while let Some(start) = rest.find(|c: char| c.is_ascii_alphabetic() || c == '_') {
            let tail = &rest[start..];
            let end = tail
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(tail.len());
            let (name, after) = tail.split_at(end);
            rest = after;
            let camel = name.starts_with(|c: char| c.is_ascii_uppercase())
                && name.contains(|c: char| c.is_ascii_lowercase());
            let snake = name.contains('_')
                && name
                    .chars()
                    .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
            let code =
                (camel || snake) && !after.starts_with('.') && !name.starts_with("fuzzymotiv_");
            if code && !declared.contains(name) && !NOT_DECLARED.contains(&name) {
                found.push(format!("ARCHITECTURE.md:{line}: `{name}` (in `{span}`)"));
            }
        }
    }
    found
}

#[test]
fn architecture_names_only_types_and_functions_that_are_declared() {
    let text = fs::read_to_string(repo().join("ARCHITECTURE.md")).unwrap();
    let arch = read_architecture(&text);
    let declared = declared_names(&repo(), &["crates", "python/src", "python/fuzzymotiv"]);
    assert!(declared.contains("Experiment") && declared.contains("run_concurrently"));
    let found = undeclared(&arch.spans, &declared);
    assert!(
        found.is_empty(),
        "ARCHITECTURE.md names code that is declared nowhere:\n{}",
        found.join("\n")
    );
}

#[test]
fn a_renamed_type_or_function_is_found() {
    let declared: BTreeSet<String> = ["Arena", "simulate"].map(String::from).into();
    let spans = [
        ("Arena::sight".to_string(), 3),
        ("OldArena".to_string(), 4),
        ("run_trial_old(pose)".to_string(), 5),
        ("lanes_any.rs".to_string(), 6),
        ("fuzzymotiv_pipeline::study".to_string(), 7),
        ("ControlFlow".to_string(), 8),
    ];
    assert_eq!(
        undeclared(&spans, &declared),
        [
            "ARCHITECTURE.md:4: `OldArena` (in `OldArena`)",
            "ARCHITECTURE.md:5: `run_trial_old` (in `run_trial_old(pose)`)"
        ]
    );
}

// ---------------------------------------------------------------------------------------------
// The figures: current ones in bench/README.md and docs/guide/performance.md, the log apart.

#[test]
fn bench_readme_is_a_summary_with_its_log_beside_it() {
    let readme = fs::read_to_string(repo().join("bench/README.md")).unwrap();
    assert!(
        readme.len() <= 15_000,
        "bench/README.md is {} bytes: the current figures fit in 15 KB, the rest goes to \
         bench/HISTORY.md",
        readme.len()
    );
    assert!(
        readme.contains("](HISTORY.md)"),
        "bench/README.md links its log"
    );
    let history = fs::read_to_string(repo().join("bench/HISTORY.md")).unwrap();
    assert!(history.starts_with("# bench: the log\n"));
    assert!(
        history.contains("](README.md)"),
        "the log links the current figures"
    );
}

/// The rows of the first table under `## Figures` of `text`, each row's cells trimmed.
fn figures_rows(text: &str) -> Vec<Vec<String>> {
    let section = text.split("\n## Figures\n").nth(1).unwrap_or("");
    let section = section.split("\n## ").next().unwrap_or("");
    (section.lines())
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'))
        .skip(2)
        .map(|l| {
            (l.trim().trim_matches('|').split(" | "))
                .map(|c| c.trim().to_string())
                .collect()
        })
        .collect()
}

/// Why a figures table is not one of current figures: a quantity listed twice, a row without
/// the date it was measured (`YYYY-MM-DD`) or without its command.
fn figures_faults(rows: &[Vec<String>]) -> Vec<String> {
    let mut faults = Vec::new();
    let mut seen = BTreeSet::new();
    for row in rows {
        let [what, _figure, measured, command] = row.as_slice() else {
            faults.push(format!("not four cells: {row:?}"));
            continue;
        };
        if !seen.insert(what.clone()) {
            faults.push(format!("listed twice: {what}"));
        }
        let dated = measured.as_bytes().windows(10).any(|w| {
            w.iter().enumerate().all(|(i, b)| match i {
                4 | 7 => *b == b'-',
                _ => b.is_ascii_digit(),
            })
        });
        if !dated {
            faults.push(format!("no date: {what}"));
        }
        if command.is_empty() {
            faults.push(format!("no command: {what}"));
        }
    }
    faults
}

#[test]
fn performance_lists_each_current_figure_once_with_its_date_and_command() {
    let text = fs::read_to_string(repo().join("docs/guide/performance.md")).unwrap();
    let rows = figures_rows(&text);
    assert!(rows.len() >= 10, "only {} figures", rows.len());
    let faults = figures_faults(&rows);
    assert!(faults.is_empty(), "docs/guide/performance.md: {faults:#?}");
}

#[test]
fn a_figure_listed_twice_or_undated_is_found() {
    let text = "# P\n\n## Figures\n\nMeasured.\n\n| what | figure | measured | command |\n|---|---|---|---|\n\
        | study | 0.98× | 2026-12-05, 8944131 | `reproduce` |\n\
        | study | 1.18× | 2026-12-04 | `reproduce` |\n\
        | bench | 3 M | f2a6b0d | `bench` |\n\
        | gym | 2 M | 2026-12-07 |  |\n\n## Why\n\n| a | b |\n|---|---|\n| x | y |\n";
    let rows = figures_rows(text);
    assert_eq!(rows.len(), 4);
    assert_eq!(
        figures_faults(&rows),
        ["listed twice: study", "no date: bench", "no command: gym"]
    );
}
