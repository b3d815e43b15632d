//! Random streams: one seeded stream per purpose and work item, so results do not depend on
//! the order or the threads that compute them (docs/model.md §11).

pub(crate) mod noise;
pub(crate) mod rng;
pub(crate) mod seed;

pub use noise::perturb;
pub use rng::{Rng, Rng64, index, rng_from_seed, standard_normal, uniform, uniform01};
pub use seed::{JSON_EXACT, Streams, derive, hash_str, study_seed};
