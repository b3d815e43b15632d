//! The documented limits of the lab: what one request may ask for (docs/guide/lab.md, "Limits").

/// Largest request body (bytes): settings, a room, a comparison. Larger bodies get HTTP 413.
pub const MAX_BODY: usize = 64 * 1024;
/// Largest GA population a run of the lab may ask for (the paper's is 200).
pub const MAX_POPULATION: usize = 400;
/// Most generations a run of the lab may ask for (the paper's is 200).
pub const MAX_GENERATIONS: usize = 400;
/// Most rooms in one run.
pub const MAX_ROOMS: usize = 10;
/// Most steps of one trial (the default is 1000).
pub const MAX_STEPS: usize = 5000;
/// Most vertices of a drawn room (outline and obstacles together).
pub const MAX_ROOM_VERTICES: usize = 400;
/// Most rooms kept under `DIR/rooms/`.
pub const MAX_SAVED_ROOMS: usize = 200;
/// Most runs waiting in the queue; more are refused (HTTP 503) until some finish.
pub const MAX_QUEUED: usize = 64;
/// Stopped or failed runs whose curves the lab keeps in memory; older ones stay in the list
/// (marked stopped or failed) without them.
pub const MAX_FORGOTTEN: usize = 32;
/// Stopped or failed runs the list shows at most (the oldest beyond it leave the list; finished
/// runs are on disk and stay): far more than a session stops by hand, and few enough that a lab
/// under load (`examples/load.rs`: thousands of runs started and cancelled) keeps its memory and
/// its `/api/runs` answers bounded.
pub const MAX_STOPPED_LISTED: usize = 1_000;
/// A live run sends the current best robot's paths every this many generations.
pub const PATHS_EVERY: usize = 5;
/// Most points of a path sent to the page.
pub const PATH_POINTS: usize = 400;
