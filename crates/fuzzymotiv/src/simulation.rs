//! The simulated Khepera in its rooms: geometry and the functions it is computed with, rooms,
//! the robot's body and motion, its infrared sensors, the neural controller and trials (a
//! controller driving the robot in a room for a number of steps).

pub mod controller;
pub mod geom;
pub mod math;
pub(crate) mod memo;
pub mod robot;
pub mod room;
pub(crate) mod sensing;
pub mod sensor;
pub mod stepper;
pub mod trial;
pub mod trial_params;
