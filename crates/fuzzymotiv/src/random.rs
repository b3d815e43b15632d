//! Random streams: one seeded stream per purpose and work item, so results do not depend on
//! the order or the threads that compute them (docs/model.md §11).

pub mod noise;
pub mod rng;
pub mod seed;
