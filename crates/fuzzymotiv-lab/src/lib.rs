//! `fuzzymotiv lab`: a local web page where a person sets the motivations (the paper's C, H, O,
//! E or any config's), chooses or draws rooms and their missions, picks a built-in robot
//! (khepera, epuck2, thymio2), evolves robots live and compares runs.
//!
//! The server (axum on tokio) binds to loopback by default and answers only requests that
//! carry its random token (`?token=` once, then a cookie, or the `x-fuzzymotiv-token` header)
//! and name it in their `Host` header (no DNS rebinding). The page, its script and style are
//! embedded; its Content-Security-Policy allows requests to the server only. Runs go through
//! the library's entry ([`fuzzymotiv::Experiment::run_from`] via the run-directory pipeline
//! of `fuzzymotiv-pipeline`), one at a time on a pool of `--threads` threads, further runs queued.
//! Everything the lab writes stays under its directory:
//!
//! ```text
//! DIR/runs/ID/     one run directory per finished run (as `fuzzymotiv run` writes it)
//! DIR/rooms/N.toml rooms drawn or uploaded in the page (the `rooms --check` format)
//! DIR/saved/NAME/  runs saved with "Save as run directory" (never replacing one)
//! DIR/studies/ID/  one study directory per study started in the page (as `fuzzymotiv study`
//!                  writes it)
//! ```
//!
//! ```no_run
//! use fuzzymotiv_lab::{Lab, LabOptions};
//! let lab = Lab::start(LabOptions::new("lab-runs".into())).unwrap();
//! println!("{}", lab.url());
//! lab.wait_for_ctrl_c();
//! ```

mod api;
mod assets;
mod compare;
mod errors;
pub mod limits;
mod live;
mod motivations;
mod robots;
mod rooms;
mod runs;
mod security;
mod server;
mod settings;
mod start;
mod studies;

pub use server::{Lab, LabOptions};
