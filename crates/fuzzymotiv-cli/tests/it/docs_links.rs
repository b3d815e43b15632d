//! The documents hold together: every relative link of README.md, EXPERIMENTS.md,
//! ARCHITECTURE.md, docs/**/*.md and bench/README.md resolves (a `#anchor` to a Markdown file
//! names one of its headings, as GitHub spells them), and every shell block they mark as
//! runnable runs.
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

use std::collections::BTreeMap;
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
