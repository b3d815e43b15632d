//! The engine's integration tests, one test binary (`cargo test -p fuzzymotiv --test it`): each
//! file of this folder is a module named as its file (`cargo test -p fuzzymotiv --test it
//! invariants::` runs one file's tests). A new test file is a `mod` here, not a file beside this
//! folder (the binary's `test_binaries` checks both; docs/guide/testing.md says why).

mod fuzz_inputs;
mod golden_individuals;
mod guide_rust;
mod invariants;
mod libm_free;
mod model_version;
mod sensor_table;
mod user_terms;
