//! Rendering, from records only: tables ([`tables`]), the paper's study with its statistics
//! and claims ([`study`]), hand-written SVG figures ([`svg`]) written as files with an optional
//! PNG beside them ([`figures`]), and the self-contained report page ([`report`]).

pub mod figures;
pub mod report;
pub mod study;
pub mod svg;
pub mod tables;
