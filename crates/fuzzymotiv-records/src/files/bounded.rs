//! Reading the user's files with bounds: every input file (configs, room files, sweep files,
//! sensor table files, `calibrate`'s measurements, robot logs, genome files, a run's or study's
//! records) is read through [`open_input`] or [`read_input`], so that a device, an endless pipe
//! or a binary file is refused at once with exit code 2, naming the file and what would be
//! right, and memory stays bounded.
//!
//! - Only a regular file or a pipe (a FIFO, `/dev/stdin` fed by a pipe) is read; a directory,
//!   a device (`/dev/zero`, a terminal) or a socket is refused before a byte is read.
//! - At most [`InputKind::limit`] bytes are read: a file or pipe holding more is refused once
//!   the limit is passed (the reader stops there).
//! - A line of a file read line by line (a robot's log, `calibrate`'s measurements) is at most
//!   [`LINE_LIMIT`] bytes; a file read whole (a config, a room file, a sensor table file, a
//!   record) has no line limit.
//! - Text is UTF-8 without NUL bytes: the first byte that breaks this is refused with its line.

use std::fmt;
use std::fs::File;
use std::io::Read;
use std::path::Path;

use crate::files::error::CliError;

/// The most bytes of a file the user writes by hand or with a script: a config, a room file,
/// a sweep file, a sensor table file, `calibrate`'s measurements (16 MiB). A genome file given
/// to `export` is read as a record ([`RECORD_LIMIT`], through `read_json`).
pub const TEXT_LIMIT: u64 = 16 << 20;

/// The most bytes of a robot's log (`recognise`, `replay --log`), read line by line: 256 MiB
/// (a day of steps at 10 Hz is about 30 MB).
pub const LOG_LIMIT: u64 = 256 << 20;

/// The most bytes of a record fuzzymotiv wrote and reads back (a run's or study's JSON and CSV
/// files, a checkpoint): 1 GiB (a checkpoint holds the whole population's weights).
pub const RECORD_LIMIT: u64 = 1 << 30;

/// The most bytes of one line of a file read line by line (a robot's log, `calibrate`'s
/// measurements): 1 MiB.
pub const LINE_LIMIT: u64 = 1 << 20;

/// A kind of input file: what it is called in messages, the most bytes it may hold, and
/// whether its lines are bounded (a file read line by line).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct InputKind {
    /// What the file is, in messages: "config file", "room file", "log file".
    pub what: &'static str,
    /// The most bytes it may hold.
    pub limit: u64,
    /// The most bytes of a line, for a file read line by line ([`LINE_LIMIT`]).
    pub line_limit: Option<u64>,
}

impl InputKind {
    /// A file written by hand or a script, read whole ([`TEXT_LIMIT`]).
    pub const fn text(what: &'static str) -> InputKind {
        InputKind {
            what,
            limit: TEXT_LIMIT,
            line_limit: None,
        }
    }

    /// A table read line by line ([`TEXT_LIMIT`], lines of at most [`LINE_LIMIT`]).
    pub const fn table(what: &'static str) -> InputKind {
        InputKind {
            line_limit: Some(LINE_LIMIT),
            ..InputKind::text(what)
        }
    }

    /// A robot's log, read line by line ([`LOG_LIMIT`], lines of at most [`LINE_LIMIT`]).
    pub const fn log(what: &'static str) -> InputKind {
        InputKind {
            what,
            limit: LOG_LIMIT,
            line_limit: Some(LINE_LIMIT),
        }
    }

    /// A record fuzzymotiv wrote, read whole ([`RECORD_LIMIT`]).
    pub const fn record(what: &'static str) -> InputKind {
        InputKind {
            what,
            limit: RECORD_LIMIT,
            line_limit: None,
        }
    }
}

/// The refusal carried inside the `std::io::Error` a [`Bounded`] reader returns, so that a
/// reader built on it (`csv`, `read_to_string`) passes it on; [`refusal`] takes it out again.
#[derive(Debug)]
struct Refused(String);

impl fmt::Display for Refused {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Refused {}

/// The input error an I/O error of a [`Bounded`] reader stands for (none for another error).
pub fn refusal(e: &std::io::Error) -> Option<CliError> {
    let refused = e.get_ref()?.downcast_ref::<Refused>()?;
    Some(CliError::input(refused.0.clone()))
}

/// [`refusal`] inside a `csv` error.
pub fn csv_refusal(e: &csv::Error) -> Option<CliError> {
    match e.kind() {
        csv::ErrorKind::Io(io) => refusal(io),
        _ => None,
    }
}

/// `n` bytes in words: "16 MiB", "1 GiB".
fn size(n: u64) -> String {
    match n {
        n if n >= 1 << 30 && n % (1 << 30) == 0 => format!("{} GiB", n >> 30),
        n if n >= 1 << 20 && n % (1 << 20) == 0 => format!("{} MiB", n >> 20),
        n => format!("{n} bytes"),
    }
}

/// An input file being read, with its bounds checked on every read (see the module's docs).
#[derive(Debug)]
pub struct Bounded<R> {
    inner: R,
    name: String,
    kind: InputKind,
    /// Bytes read so far.
    read: u64,
    /// The line being read (from 1) and its bytes so far.
    line: u64,
    line_len: u64,
    /// The start of a UTF-8 sequence the last read ended inside (at most 3 bytes).
    carry: Vec<u8>,
}

impl<R: Read> Bounded<R> {
    /// `inner`, read as the file `name` of `kind`.
    pub fn new(inner: R, name: String, kind: InputKind) -> Self {
        Bounded {
            inner,
            name,
            kind,
            read: 0,
            line: 1,
            line_len: 0,
            carry: Vec::new(),
        }
    }

    /// The file's name, as given.
    pub fn name(&self) -> &str {
        &self.name
    }

    fn refuse(&self, why: String) -> std::io::Error {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            Refused(format!("{}: {why}", self.name)),
        )
    }

    /// Checks the bytes just read: the total, each line's length, NUL bytes and UTF-8.
    fn check(&mut self, buf: &[u8]) -> std::io::Result<()> {
        self.read += buf.len() as u64;
        let what = self.kind.what;
        if self.read > self.kind.limit {
            return Err(self.refuse(format!(
                "is larger than the {} a {what} may be; give a {what} of at most that size",
                size(self.kind.limit)
            )));
        }
        let not_utf8 = |line: u64, b: u8| {
            format!(
                "line {line}: byte 0x{b:02x} is not UTF-8 text; a {what} is UTF-8 text (save it as UTF-8)"
            )
        };
        let bad = match self.utf8_error(buf) {
            // The carried bytes end the last read and are not a newline: the line is this one.
            Some(NotUtf8::Carried(b)) => return Err(self.refuse(not_utf8(self.line, b))),
            Some(NotUtf8::At(at)) => Some(at),
            None => None,
        };
        let upto = bad.map_or(buf.len(), |at| at + 1);
        for (i, &b) in buf[..upto].iter().enumerate() {
            if Some(i) == bad {
                return Err(self.refuse(not_utf8(self.line, b)));
            }
            if b == 0 {
                return Err(self.refuse(format!(
                    "line {}: a NUL byte (0x00), so this is not text; a {what} is UTF-8 text",
                    self.line
                )));
            }
            if b == b'\n' {
                self.line += 1;
                self.line_len = 0;
                continue;
            }
            self.line_len += 1;
            if let Some(max) = self.kind.line_limit.filter(|&max| self.line_len > max) {
                return Err(self.refuse(format!(
                    "line {} is longer than the {} a line of a {what} may be; a {what} holds one row per line",
                    self.line,
                    size(max)
                )));
            }
        }
        Ok(())
    }

    /// Where in `buf` the first byte that is not UTF-8 lies (after the bytes carried from the
    /// last read; a sequence cut at the end of `buf` is carried to the next), or the carried
    /// byte that is not (a sequence cut at the end of the last read that `buf` breaks).
    fn utf8_error(&mut self, buf: &[u8]) -> Option<NotUtf8> {
        let carried = self.carry.len();
        let joined;
        let bytes = if carried == 0 {
            buf
        } else {
            joined = [self.carry.as_slice(), buf].concat();
            &joined
        };
        match std::str::from_utf8(bytes) {
            Ok(_) => {
                self.carry.clear();
                None
            }
            Err(e) if e.error_len().is_none() => {
                self.carry = bytes[e.valid_up_to()..].to_vec();
                None
            }
            Err(e) if e.valid_up_to() < carried => Some(NotUtf8::Carried(bytes[e.valid_up_to()])),
            Err(e) => Some(NotUtf8::At((e.valid_up_to() - carried).min(buf.len() - 1))),
        }
    }
}

/// The first byte of a read that is not UTF-8 ([`Bounded::utf8_error`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum NotUtf8 {
    /// A byte carried from the last read, with its value.
    Carried(u8),
    /// The byte at this index of the read.
    At(usize),
}

impl<R: Read> Read for Bounded<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        if n == 0 && !self.carry.is_empty() {
            return Err(self.refuse(format!(
                "line {}: the file ends inside a UTF-8 character; a {} is UTF-8 text",
                self.line, self.kind.what
            )));
        }
        self.check(&buf[..n])?;
        Ok(n)
    }
}

/// Opens the input file `path` of `kind` (see the module's docs): a regular file or a pipe;
/// anything else, or a file that cannot be opened, is an input error naming it.
pub fn open_input(path: &Path, kind: InputKind) -> Result<Bounded<File>, CliError> {
    let name = path.display().to_string();
    let what = kind.what;
    let cannot = |e: std::io::Error| CliError::input(format!("{name}: cannot read {what}: {e}"));
    let meta = std::fs::metadata(path).map_err(cannot)?;
    if let Some(is) = not_readable(&meta) {
        return Err(CliError::input(format!(
            "{name}: is {is}, not a file; a {what} is read from a regular file (or a pipe)"
        )));
    }
    let file = File::open(path).map_err(cannot)?;
    Ok(Bounded::new(file, name, kind))
}

/// What a file-system entry is when it is not read as an input (a directory, a device, a
/// socket); `None` for a regular file or a pipe.
fn not_readable(meta: &std::fs::Metadata) -> Option<&'static str> {
    let t = meta.file_type();
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return None;
        }
    }
    if t.is_file() {
        None
    } else {
        Some(what_it_is(meta))
    }
}

/// Reads the whole input file `path` of `kind` as text ([`open_input`]; at most
/// [`InputKind::limit`] bytes of UTF-8 text). The text is reserved once from the length of a
/// regular file (at most the limit and one byte, enough to see a file over it), so that a file
/// near the limit does not make the text grow by doubling to twice the limit.
pub fn read_input(path: &Path, kind: InputKind) -> Result<String, CliError> {
    let mut input = open_input(path, kind)?;
    let length = (input.inner.metadata().ok())
        .filter(|meta| meta.is_file())
        .map_or(0, |meta| meta.len().min(kind.limit + 1));
    let mut text = String::with_capacity(usize::try_from(length).unwrap_or(0));
    input.read_to_string(&mut text).map_err(|e| {
        refusal(&e).unwrap_or_else(|| {
            CliError::input(format!("{}: cannot read {}: {e}", input.name, kind.what))
        })
    })?;
    Ok(text)
}

/// What a file-system entry is, for messages: "a regular file", "a directory", "a symbolic
/// link", "a FIFO (named pipe)", "a socket", "a device"; "not a regular file or directory"
/// when it is none of these.
pub fn what_it_is(meta: &std::fs::Metadata) -> &'static str {
    let t = meta.file_type();
    if t.is_symlink() {
        return "a symbolic link";
    }
    if t.is_dir() {
        return "a directory";
    }
    if t.is_file() {
        return "a regular file";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if t.is_socket() {
            return "a socket";
        }
        if t.is_block_device() || t.is_char_device() {
            return "a device";
        }
    }
    "not a regular file or directory"
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_all(bytes: &[u8], kind: InputKind, chunk: usize) -> Result<String, String> {
        struct Chunks<'a>(&'a [u8], usize);
        impl Read for Chunks<'_> {
            fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
                let n = self.0.len().min(self.1).min(buf.len());
                buf[..n].copy_from_slice(&self.0[..n]);
                self.0 = &self.0[n..];
                Ok(n)
            }
        }
        let mut r = Bounded::new(Chunks(bytes, chunk), "f.csv".into(), kind);
        let mut text = String::new();
        match r.read_to_string(&mut text) {
            Ok(_) => Ok(text),
            Err(e) => Err(refusal(&e).expect("a refusal").to_string()),
        }
    }

    #[test]
    fn utf8_cut_between_reads_is_read_and_a_bad_byte_is_refused_with_its_line() {
        let text = "a,b\nné,ü€\n";
        for chunk in 1..5 {
            assert_eq!(
                read_all(text.as_bytes(), InputKind::text("x"), chunk).unwrap(),
                text
            );
        }
        let bad = b"a,b\n1,2\n\xff3\n";
        for chunk in 1..5 {
            let e = read_all(bad, InputKind::text("config"), chunk).unwrap_err();
            assert!(
                e.starts_with("f.csv: line 3: byte 0xff is not UTF-8"),
                "{e}"
            );
        }
        let e = read_all(b"ab\n\xc3", InputKind::text("x"), 2).unwrap_err();
        assert!(
            e.contains("line 2: the file ends inside a UTF-8 character"),
            "{e}"
        );
        let e = read_all(b"ab\ncd\0", InputKind::text("config"), 3).unwrap_err();
        assert!(e.contains("line 2: a NUL byte"), "{e}");
    }

    #[test]
    fn a_sequence_cut_between_reads_and_broken_by_the_next_read_names_its_first_byte_and_line() {
        // Latin-1 "né,x": 0xE9 starts a 3-byte sequence that the ',' of the next read breaks.
        let bad = b"a,b\nn\xe9,x\n";
        for chunk in 1..5 {
            let e = read_all(bad, InputKind::text("sensor table"), chunk).unwrap_err();
            assert!(
                e.starts_with("f.csv: line 2: byte 0xe9 is not UTF-8"),
                "chunk {chunk}: {e}"
            );
        }
        // Two carried bytes (0xE2 0x82 of '€') broken by the next read: the first is named.
        let bad = b"a\nb\n\xe2\x82x\n";
        for chunk in 1..7 {
            let e = read_all(bad, InputKind::text("sensor table"), chunk).unwrap_err();
            assert!(
                e.starts_with("f.csv: line 3: byte 0xe2 is not UTF-8"),
                "chunk {chunk}: {e}"
            );
        }
    }

    #[test]
    fn a_regular_file_is_read_into_text_reserved_once_from_its_length() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("record.json");
        let body = "x".repeat(5000);
        std::fs::write(&path, &body).unwrap();
        let text = read_input(&path, InputKind::record("record file")).unwrap();
        assert_eq!(text, body);
        // Grown by doubling, the text would hold 8192 bytes or more.
        assert!(text.capacity() <= body.len() + 1, "{}", text.capacity());
        let kind = InputKind {
            limit: 100,
            ..InputKind::text("config")
        };
        let e = read_input(&path, kind).unwrap_err().to_string();
        assert!(
            e.contains("is larger than the 100 bytes a config may be"),
            "{e}"
        );
    }

    #[test]
    fn a_file_over_its_limit_or_a_line_over_the_line_limit_is_refused() {
        let kind = InputKind {
            limit: 10,
            ..InputKind::text("config")
        };
        assert!(read_all(b"0123456789", kind, 4).is_ok());
        let e = read_all(b"0123456789a", kind, 4).unwrap_err();
        assert_eq!(
            e,
            "f.csv: is larger than the 10 bytes a config may be; give a config of at most that size"
        );
        let kind = InputKind {
            line_limit: Some(3),
            ..InputKind::table("log")
        };
        assert!(read_all(b"abc\nabc\n", kind, 2).is_ok());
        let e = read_all(b"abc\nabcd\n", kind, 2).unwrap_err();
        assert!(e.contains("line 2 is longer than the 3 bytes"), "{e}");
    }
}
