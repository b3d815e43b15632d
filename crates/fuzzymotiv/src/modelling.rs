//! Action-based environment modelling: a robot's actions → chain code vectors → a 1-D
//! self-organising map → room recognition by threshold and nearest neighbour.

pub mod aem;
pub mod recognition;
pub mod som;
