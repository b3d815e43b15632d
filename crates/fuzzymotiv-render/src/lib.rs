//! Rendering, from records and a run's [`RenderContext`](fuzzymotiv_records::records::context::RenderContext)
//! only, never the live experiment or the pipeline (this crate depends on `fuzzymotiv` and
//! `fuzzymotiv-records` alone, so the compiler keeps it so): tables ([`tables`]), the paper's study with its statistics
//! and claims ([`study`]), SVG figures ([`svg`], a study's forest plot [`forest`] and its numbers [`claim_format`], written with one builder: [`figure`]) written as files with an optional
//! PNG beside them ([`figures`]), the fitness terms in words ([`terms`]), the self-contained
//! report page ([`report`]) and rollout frames and GIFs drawn in pure Rust ([`frames`]).

#![warn(missing_docs)]

pub mod agreement;
pub mod claim_format;
pub mod combination;
pub mod compare;
pub mod figure;
pub mod figures;
pub mod forest;
pub mod frames;
pub mod hypotheses;

pub mod replication;
pub mod report;
pub mod robustness;
pub mod strength;
pub mod study;
pub mod svg;
pub mod tables;
pub mod terms;
pub mod urgency;
