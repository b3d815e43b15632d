//! The CLI's modules import each other without circles, and only commands import commands
//! (ARCHITECTURE.md: commands → pipeline → rendering → records/files/inputs/error).
//!
//! `cargo test -p fuzzymotiv-cli --test layers -- --nocapture` prints the import map.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The command modules (the top layer).
const COMMANDS: [&str; 5] = ["run", "reproduce", "sweep", "replay", "bench"];

/// Module → the modules it names as `crate::NAME` (comments left out).
fn import_map() -> BTreeMap<String, BTreeSet<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut map = BTreeMap::new();
    for entry in std::fs::read_dir(&src).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        if path.extension().is_none_or(|e| e != "rs") || name == "lib" || name == "main" {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let mut uses = BTreeSet::new();
        for line in text.lines() {
            let code = line.split("//").next().unwrap();
            for part in code.split("crate::").skip(1) {
                let module: String = part
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                let module = macro_home(module);
                if !module.is_empty() && module != name {
                    uses.insert(module);
                }
            }
            // `use crate::{a, b::c}` groups.
            if let Some(group) = code.split("crate::{").nth(1) {
                for item in group.split(',') {
                    let module: String = item
                        .trim()
                        .chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect();
                    if !module.is_empty() && module != name {
                        uses.insert(module);
                    }
                }
            }
        }
        map.insert(name, uses);
    }
    map
}

/// The module that defines a `#[macro_export]` macro (named at the crate root), else `name`.
fn macro_home(name: String) -> String {
    match name.as_str() {
        "out" | "outln" | "note" => "console".to_string(),
        _ => name,
    }
}

/// A circle through `m`, if any (depth-first search).
fn circle(
    map: &BTreeMap<String, BTreeSet<String>>,
    m: &str,
    path: &mut Vec<String>,
    done: &mut BTreeSet<String>,
) -> Option<Vec<String>> {
    if let Some(k) = path.iter().position(|p| p == m) {
        let mut c = path[k..].to_vec();
        c.push(m.to_string());
        return Some(c);
    }
    if done.contains(m) {
        return None;
    }
    path.push(m.to_string());
    for next in map.get(m).into_iter().flatten() {
        if let Some(c) = circle(map, next, path, done) {
            return Some(c);
        }
    }
    path.pop();
    done.insert(m.to_string());
    None
}

#[test]
fn modules_import_without_circles() {
    let map = import_map();
    for (m, uses) in &map {
        println!(
            "{m} -> {}",
            uses.iter().cloned().collect::<Vec<_>>().join(", ")
        );
        for u in uses {
            assert!(map.contains_key(u), "{m} names an unknown module {u}");
        }
    }
    let mut done = BTreeSet::new();
    for m in map.keys() {
        if let Some(c) = circle(&map, m, &mut Vec::new(), &mut done) {
            panic!("import circle: {}", c.join(" -> "));
        }
    }
}

#[test]
fn only_commands_import_commands() {
    for (m, uses) in import_map() {
        if COMMANDS.contains(&m.as_str()) {
            continue;
        }
        for u in uses {
            assert!(
                !COMMANDS.contains(&u.as_str()),
                "{m} (below the commands) imports the command module {u}"
            );
        }
    }
}
