//! Fitness: the terms a trial is scored by (exploration a, homing g, orientation l, battery b)
//! and the Takagi–Sugeno–Kang fuzzy combination of them under the motivations X.

pub mod episode;
pub mod fll;
pub mod fuzzy;
pub mod terms;
