//! `fuzzymotiv lab`: the browser lab (the `fuzzymotiv-lab` crate), started and stopped.

use std::net::IpAddr;
use std::path::PathBuf;

use crate::console::{note, outln};
use fuzzymotiv_lab::{Lab, LabOptions};
use fuzzymotiv_pipeline::files::error::CliError;

/// Arguments of `fuzzymotiv lab`.
#[derive(clap::Args)]
pub struct LabArgs {
    /// TCP port (0: any free port).
    #[arg(long, allow_hyphen_values = true, default_value_t = 8765)]
    port: u16,
    /// Directory of the lab: its runs (DIR/runs/), drawn rooms (DIR/rooms/) and saved run
    /// directories (DIR/saved/). Everything the lab writes stays under it.
    #[arg(long, value_name = "DIR", default_value = "lab")]
    dir: PathBuf,
    /// Worker threads of a run, 1 to 256 [default: all cores]; further runs wait in a queue.
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = fuzzymotiv_pipeline::files::inputs::parse_threads)]
    threads: Option<usize>,
    /// Open the page in the default browser (where there is none, the address is printed).
    #[arg(long)]
    open: bool,
    /// Interface to listen on [default: 127.0.0.1, this machine only]. Another address lets
    /// other machines reach the lab: anyone with the token can run experiments and write
    /// under --dir, and the traffic (token included) is not encrypted. An IP address, or
    /// `localhost`.
    #[arg(long, value_name = "ADDR", value_parser = bind_address)]
    bind: Option<IpAddr>,
    /// The access token [default: a new random one at every start]. Giving the same one again
    /// lets the pages open before a restart go on working: 16 to 128 letters, digits, `-` or
    /// `_` (e.g. from `openssl rand -hex 16`).
    #[arg(long, value_name = "TOKEN", value_parser = token)]
    token: Option<String>,
    /// Open the page on this experiment config (TOML, as `fuzzymotiv run CONFIG` reads it):
    /// its motivations as the sliders, its rooms (room files listed beside the built-in
    /// rooms, the goals drawn) chosen for a run, and its name, seed, GA size, steps, motion
    /// model and room recognition in the form. Keys the lab cannot set (e.g. `training`,
    /// `[fuzzy]`) are named on the page. A bad file stops the lab before it starts (exit 2).
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// The folder of study files the page's Studies panel lists (docs/guide/studies.md); a
    /// study pasted or uploaded in the page has its configs relative to the working directory.
    #[arg(long, value_name = "DIR", default_value = "studies")]
    studies: PathBuf,
}

/// `--token`'s value: long enough not to be guessed, and safe in a URL and a cookie.
fn token(value: &str) -> Result<String, String> {
    let chars_ok = value
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
    if (16..=128).contains(&value.len()) && chars_ok {
        Ok(value.to_string())
    } else {
        Err(format!(
            "expected 16 to 128 letters, digits, `-` or `_` (got {} characters{}), e.g. the \
             output of `openssl rand -hex 16`",
            value.chars().count(),
            if chars_ok { "" } else { ", some of them other" }
        ))
    }
}

/// `--bind`'s value: an IP address or `localhost` (no name lookup: the lab must know which
/// address it serves, to check each request's Host header).
fn bind_address(value: &str) -> Result<IpAddr, String> {
    if value.eq_ignore_ascii_case("localhost") {
        return Ok(IpAddr::from([127, 0, 0, 1]));
    }
    value.parse().map_err(|_| {
        "expected an IP address (127.0.0.1 or ::1 for this machine only, 0.0.0.0 for every \
         interface, or one interface's address) or `localhost`"
            .to_string()
    })
}

/// Entry point of `fuzzymotiv lab`.
pub fn lab(args: LabArgs) -> Result<(), CliError> {
    let mut opts = LabOptions::new(args.dir);
    opts.port = args.port;
    opts.threads = args.threads;
    opts.token = args.token;
    opts.config = args.config;
    opts.studies = args.studies;
    if let Some(bind) = args.bind {
        if !bind.is_loopback() {
            note!(
                "note: --bind {bind}: other machines can reach the lab; anyone with its token can run experiments and write under its directory, and HTTP is not encrypted"
            );
        }
        opts.bind = bind;
    }
    let lab = Lab::start(opts)?;
    outln!("fuzzymotiv lab: {}", lab.url())?;
    if lab.addr().ip().is_unspecified() {
        note!(
            "from other machines: the same address with this machine's IP address in place of \
             127.0.0.1 (a host name is refused)"
        );
    }
    note!(
        "the lab writes under {}; Ctrl-C stops it (runs going on are stopped)",
        lab.dir().display()
    );
    if args.open {
        open_browser(&lab.url());
    }
    lab.wait_for_ctrl_c();
    note!("lab stopped");
    Ok(())
}

/// Opens `url` with the desktop's opener, if there is one.
fn open_browser(url: &str) {
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else if cfg!(windows) {
        "explorer"
    } else {
        "xdg-open"
    };
    let started = std::process::Command::new(opener)
        .arg(url)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn();
    if started.is_err() {
        note!("no browser to open ({opener} not found): open the address above");
    }
}
