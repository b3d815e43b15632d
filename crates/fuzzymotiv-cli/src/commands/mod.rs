//! The commands, one module each (`sweep` holds `plan`, `sweep` and `merge`): each turns its
//! arguments into calls of `fuzzymotiv` and `fuzzymotiv_pipeline`, and shows the outcome.

pub mod bench;
pub mod calibrate;
pub mod claims;
pub mod compare;
pub mod export;
pub mod fuzzy;
pub mod lab;
pub mod recognise;
pub mod replay;
pub mod reproduce;
pub mod robustness;
pub mod rooms;
pub mod run;
pub mod study;
pub mod sweep;
pub mod transfer;
