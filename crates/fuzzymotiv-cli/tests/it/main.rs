//! The binary's integration tests, one test binary (`cargo test -p fuzzymotiv-cli --test it`):
//! each file of this folder is a module named as its file, so `cargo test -p fuzzymotiv-cli
//! --test it verdicts::` runs one file's tests and `… --test it NAME` the tests whose path
//! contains NAME. A binary per file linked the whole workspace once each (docs/guide/testing.md
//! has the build times). A new test file is a `mod` here, not a file beside this folder
//! (`test_binaries` checks both).

mod common;

mod browser;
mod calibrate;
mod claims;
mod cli;
mod combination;
mod compare;
mod continue_run;
mod docs_links;
mod documents;
mod example_outputs;
mod export;
mod fll;
mod gif;
mod inputs;
mod job_lock;
mod lab_browser;
mod layers;
mod library_study;
mod messages;
mod missions;
mod model;
mod names;
mod outputs;
mod promise;
mod recognise;
mod robustness;
mod seed_names;
mod shipped_studies;
mod strength;
mod study;
mod sweep;
mod test_binaries;
mod urgency;
mod verdicts;
