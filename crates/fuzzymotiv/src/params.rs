//! The one error type of every value read from a user's input (config or room file): the source,
//! the field and what is wrong. Each parameter section is checked beside its own type
//! ([`crate::evolution::ga::GaParams::from_raw`], [`crate::simulation::trial::TrialParams::from_raw`],
//! [`crate::modelling::aem::AemParams::from_raw`], …) and [`crate::experiment::Experiment::new`] composes
//! the checks, naming the source.

pub(crate) mod plain;

/// A value that cannot be used: the file (or other source), the field and the reason.
///
/// ```
/// use fuzzymotiv::params::FieldError;
/// let e = FieldError::new("ga.population", "must be ≥ 2").in_source("c.toml");
/// assert_eq!(e.to_string(), "c.toml: field `ga.population`: must be ≥ 2");
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{source_name}: field `{field}`: {reason}")]
pub struct FieldError {
    /// File (or other source) the value came from; empty until [`FieldError::in_source`].
    pub source_name: String,
    /// Dotted key, e.g. `ga.population`, `rooms[2]` or `home.x`.
    pub field: String,
    /// What is wrong and what would be right.
    pub reason: String,
}

impl FieldError {
    /// An error in `field`, its source not yet known.
    pub fn new(field: impl Into<String>, reason: impl Into<String>) -> FieldError {
        FieldError {
            source_name: String::new(),
            field: field.into(),
            reason: reason.into(),
        }
    }

    /// The same error, read from `source_name`.
    pub fn in_source(mut self, source_name: &str) -> FieldError {
        self.source_name = source_name.to_string();
        self
    }
}

/// The items joined by commas, the last by `word` (`"and"`, `"or"`), for messages and reports:
///
/// ```
/// use fuzzymotiv::params::joined_list;
/// assert_eq!(joined_list(&["a"], "and"), "a");
/// assert_eq!(joined_list(&["a", "b", "c"], "or"), "a, b or c");
/// ```
pub fn joined_list<S: AsRef<str>>(items: &[S], word: &str) -> String {
    match items {
        [] => String::new(),
        [one] => one.as_ref().to_string(),
        [rest @ .., last] => {
            let rest: Vec<&str> = rest.iter().map(AsRef::as_ref).collect();
            format!("{} {word} {}", rest.join(", "), last.as_ref())
        }
    }
}

/// Reads a `T` from the serde deserializer `d` (e.g. a JSON record file's) with its type errors
/// in plain words, as a config's are: a number says "expected a number (e.g. 0.5)", a whole
/// number "expected a whole number ≥ 0", true/false "expected true or false", never serde's
/// Rust type names (`f64`, `u64`).
///
/// ```
/// let mut json = serde_json::Deserializer::from_str(r#"{"x": "a"}"#);
/// #[derive(serde::Deserialize, Debug)]
/// struct R { x: f64 }
/// let e = fuzzymotiv::params::deserialize_plain::<R, _>(&mut json).unwrap_err();
/// assert!(e.to_string().starts_with("invalid type: string \"a\", expected a number (e.g. 0.5)"));
/// ```
pub fn deserialize_plain<'de, T, D>(d: D) -> Result<T, D::Error>
where
    T: serde::Deserialize<'de>,
    D: serde::Deserializer<'de>,
{
    plain::deserialize(d, |_| "≥ 0".into())
}

/// The largest count most integer parameters accept (10⁶).
pub const BIG: usize = 1_000_000;

/// `Ok` if `ok`, else an error in `field` with the reason `reason()`.
pub fn check(ok: bool, field: &str, reason: impl FnOnce() -> String) -> Result<(), FieldError> {
    if ok {
        Ok(())
    } else {
        Err(FieldError::new(field, reason()))
    }
}

/// Whether `v` is a probability: finite and in [0, 1].
pub fn unit(v: f64) -> bool {
    v.is_finite() && (0.0..=1.0).contains(&v)
}

/// A number as messages show it: as written (`0.5`, `-3`, `250`) when that is short, in
/// scientific notation (`1e300`, `1.5e-9`) when it is very large or very small, never 300
/// digits; NaN and infinities as `NaN`, `inf`, `-inf`.
///
/// ```
/// use fuzzymotiv::params::Num;
/// assert_eq!(Num(1e300).to_string(), "1e300");
/// assert_eq!(Num(-2.5e-12).to_string(), "-2.5e-12");
/// assert_eq!(Num(0.3).to_string(), "0.3");
/// assert_eq!(Num(123456.5).to_string(), "123456.5");
/// assert_eq!(Num(f64::NAN).to_string(), "NaN");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num(pub f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let size = self.0.abs();
        if size.is_finite() && size != 0.0 && !(1e-6..1e16).contains(&size) {
            write!(f, "{:e}", self.0)
        } else {
            write!(f, "{}", self.0)
        }
    }
}

/// The key a TOML error at `span` refers to: the key on the line of the span, with the path of
/// the table it is in (`motivations.x`, `waypoints[1].x`); for a field `missing` from a table
/// (as the table's reader said, [`plain::Fault::Missing`]), that field under the table
/// (`motivations.x.weight`, `waypoints[0].y`, `home.y`). `(document)` where neither is known.
pub(crate) fn field_at(
    text: &str,
    span: Option<std::ops::Range<usize>>,
    missing: Option<&str>,
) -> String {
    if let Some(f) = missing {
        // A field missing from the document itself: its span starts the document, whose
        // first line may be a key (not the table that lacks the field).
        let root =
            span.as_ref().is_some_and(|s| s.start == 0) && !text.trim_start().starts_with('[');
        return match span.and_then(|span| value_path_at(text, span.start)) {
            Some(table) if !table.is_empty() && !root => format!("{table}.{f}"),
            _ => f.to_string(),
        };
    }
    span.and_then(|span| value_path_at(text, span.start))
        .unwrap_or_else(|| "(document)".to_string())
}

/// The line of `text` around byte `at`: (its start, the line).
fn line_at(text: &str, at: usize) -> (usize, &str) {
    let at = at.min(text.len());
    let start = text[..at].rfind('\n').map_or(0, |i| i + 1);
    let end = text[at..].find('\n').map_or(text.len(), |i| at + i);
    (start, &text[start..end])
}

/// The path of a table header line (`[a.b]` → `a.b`, the third `[[w]]` → `w[2]`), counting the
/// same `[[…]]` headers before byte `line_start`; `None` for another line.
fn header_path(text: &str, line_start: usize, line: &str) -> Option<String> {
    let line = line.trim();
    if let Some(name) = line.strip_prefix("[[").and_then(|l| l.split("]]").next()) {
        let name = name.trim();
        let header = |l: &str| {
            let l = l.trim();
            l.strip_prefix("[[")
                .and_then(|l| l.split("]]").next())
                .is_some_and(|n| n.trim() == name)
        };
        let index = text[..line_start].lines().filter(|l| header(l)).count();
        return Some(format!("{name}[{index}]"));
    }
    let name = line.strip_prefix('[')?.split(']').next()?.trim();
    Some(name.to_string())
}

/// The path of the table the line starting at `line_start` is in (empty at the top).
fn enclosing_table(text: &str, line_start: usize) -> String {
    let mut offset = line_start;
    for line in text[..line_start].lines().rev() {
        offset -= line.len() + 1;
        if line.trim_start().starts_with('[') {
            return header_path(text, offset.min(line_start), line).unwrap_or_default();
        }
    }
    String::new()
}

/// `table.key` of the `key = …` line around byte `at` (or the header's path on a header line).
fn key_path_at(text: &str, at: usize) -> Option<String> {
    let (start, line) = line_at(text, at);
    if line.trim_start().starts_with('[') {
        return header_path(text, start, line);
    }
    let key = line[..line.find('=')?].trim();
    if key.is_empty() {
        return None;
    }
    Some(match enclosing_table(text, start) {
        t if t.is_empty() => key.to_string(),
        t => format!("{t}.{key}"),
    })
}

/// The path of the value or key at byte `at`: a header's table, `table.key` of a `key = …`
/// line, and within an inline value on it the entry (`goal.y`) or element (`waypoints[1]`)
/// it lies in, down to the key standing at `at` (`waypoints[0].colour`).
fn value_path_at(text: &str, at: usize) -> Option<String> {
    let (start, line) = line_at(text, at);
    let key = key_path_at(text, at)?;
    if line.trim_start().starts_with('[') {
        return Some(key);
    }
    // On the key, or at the end of the line (where a syntax error stops): the line's key.
    let eq = line.find('=')?;
    if at - start <= eq || at - start >= line.len() {
        return Some(key);
    }
    let key_here: String = (text[at..].chars())
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_' || *c == '-')
        .collect();
    Some(key + &inline_suffix(&line[eq + 1..at - start], &key_here))
}

/// One level of an inline value read by [`inline_suffix`]: a table with the key of its
/// current entry (still being read while `in_key`), or an array with its current element.
enum Level {
    Table { key: String, in_key: bool },
    Array(usize),
}

/// The path inside an inline value whose text up to the position is `within`: `.key` for a
/// table's entry, `[i]` for an array's element; `key_here` is the key at the position, for a
/// position where a key stands.
fn inline_suffix(within: &str, key_here: &str) -> String {
    let mut levels: Vec<Level> = Vec::new();
    let mut chars = within.chars();
    while let Some(c) = chars.next() {
        let top = levels.last_mut();
        match (c, top) {
            ('"' | '\'', top) => {
                let mut s = String::new();
                let mut escaped = false;
                for d in chars.by_ref() {
                    if d == c && !escaped {
                        break;
                    }
                    escaped = c == '"' && d == '\\' && !escaped;
                    s.push(d);
                }
                if let Some(Level::Table { key, in_key: true }) = top {
                    key.push_str(&s);
                }
            }
            ('{', _) => levels.push(Level::Table {
                key: String::new(),
                in_key: true,
            }),
            ('[', _) => levels.push(Level::Array(0)),
            ('}' | ']', _) => drop(levels.pop()),
            (',', Some(Level::Array(i))) => *i += 1,
            (',', Some(Level::Table { key, in_key })) => {
                key.clear();
                *in_key = true;
            }
            ('=', Some(Level::Table { in_key, .. })) => *in_key = false,
            (c, Some(Level::Table { key, in_key: true })) if !c.is_whitespace() => key.push(c),
            _ => {}
        }
    }
    let last = levels.len().saturating_sub(1);
    let mut path = String::new();
    for (i, level) in levels.iter().enumerate() {
        match level {
            Level::Array(k) => path.push_str(&format!("[{k}]")),
            Level::Table { key, in_key } => {
                let key = if *in_key && i == last {
                    key_here
                } else {
                    key.trim()
                };
                if !key.is_empty() {
                    path.push('.');
                    path.push_str(key);
                }
            }
        }
    }
    path
}
