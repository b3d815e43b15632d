//! The Rust of docs/guide/motivations.md §5, "A term of your own, in Rust", is
//! `examples/own_term.rs` (compiled by `cargo build --examples`): the guide quotes the example
//! verbatim from its first `use`, and the example runs to the end here.

use std::fs;
use std::path::Path;

mod example {
    include!("../../examples/own_term.rs");

    /// The guide's code registers the term, evolves, and reads the result without an error.
    #[test]
    fn the_guide_example_runs_end_to_end() {
        main().unwrap();
    }
}

const SECTION: &str = "## 5. A term of your own, in Rust";

/// The text of the first ```rust block after `heading` in `doc`.
fn rust_block_after(doc: &str, heading: &str) -> Option<String> {
    let after = &doc[doc.find(heading)? + heading.len()..];
    let start = after.find("```rust\n")? + "```rust\n".len();
    let body = &after[start..];
    Some(body[..body.find("\n```")? + 1].to_string())
}

#[test]
fn the_guide_quotes_the_example_verbatim() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let guide = fs::read_to_string(root.join("../../docs/guide/motivations.md")).unwrap();
    let example = fs::read_to_string(root.join("examples/own_term.rs")).unwrap();
    let code = &example[example.find("\nuse ").expect("the example has a `use`") + 1..];
    let quoted = rust_block_after(&guide, SECTION).unwrap_or_else(|| {
        panic!("docs/guide/motivations.md has no ```rust block under {SECTION:?}")
    });
    assert_eq!(
        quoted, code,
        "docs/guide/motivations.md §5 must quote crates/fuzzymotiv/examples/own_term.rs from its first `use`"
    );
}

#[test]
fn a_block_is_found_only_under_its_heading() {
    let doc = "# x\n```rust\nfn a() {}\n```\n## 5. A term of your own, in Rust\ntext\n```rust\nuse b;\n```\n";
    assert_eq!(rust_block_after(doc, SECTION).as_deref(), Some("use b;\n"));
    assert_eq!(
        rust_block_after("## 5. A term of your own, in Rust\nno code\n", SECTION),
        None
    );
}
