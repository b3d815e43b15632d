//! The rendering's integration tests, one test binary (`cargo test -p fuzzymotiv-render --test
//! it`): each file of this folder is a module named as its file (`cargo test -p
//! fuzzymotiv-render --test it gallery::` runs one file's tests; docs/guide/testing.md says why).

mod frames;
mod gallery;
