//! Action-based environment modelling: a robot's actions → chain code vectors → a 1-D
//! self-organising map → room recognition by threshold and nearest neighbour.

pub(crate) mod aem;
pub(crate) mod recognition;
pub(crate) mod som;

pub use aem::{Action, AemParams, DEFAULT_ACTION_TOLERANCE, Encoder};
pub use recognition::{Chosen, Confusion, Explanation, Recognizer, RoomInstance};
pub use som::{RawSom, Som, SomError, SomParams};
