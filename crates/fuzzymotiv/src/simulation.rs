//! The simulated Khepera in its rooms: geometry and the functions it is computed with, rooms,
//! the robot's body and motion, its infrared sensors, the neural controller and trials (a
//! controller driving the robot in a room for a number of steps).

pub(crate) mod controller;
pub(crate) mod geom;
pub(crate) mod isa;
pub(crate) mod lanes;
pub(crate) mod lanes_any;
pub(crate) mod math;
pub(crate) mod memo;
pub(crate) mod randomise;
pub(crate) mod robot;
pub(crate) mod robot_spec;
pub(crate) mod room;
pub(crate) mod sensing;
pub(crate) mod sensor;
pub(crate) mod sensor_layout;
pub(crate) mod sensor_table;
pub(crate) mod stepper;
pub(crate) mod trial;
pub(crate) mod trial_params;

pub use controller::{Controller, GenomeError, INPUTS, Mlp, MlpShape, OUTPUTS};
pub use geom::{PreparedSegment, Segment, Vec2, edges, point_in_polygon, signed_area};
pub use math::logistic_lanes;
pub use randomise::{Draw, Randomise, RawRandomise};
pub use robot::{Action, Compass, Motion, Pose, RawRobot, Robot, drive, wrap_angle};
pub use robot_spec::{BUILTIN_ROBOTS, RawRobotFile, RawSensor, RobotSpec};
pub use room::{BUILTIN_ROOMS, Mission, Room, Zone};
pub use sensor::{
    MAX_SENSORS, RayMount, Readings, SENSOR_LAYOUT, SENSOR_MAX, SENSORS, SensorModel, SensorMount,
    TableRef, rays,
};
pub use sensor_table::{
    Calibration, Measurement, RawRay, RawSensorRays, RawSensorTable, SensorScale, SensorTable,
    Spread, TableRay, calibrate,
};
pub use stepper::TrialRun;
pub use trial::{
    Arena, RawTrial, Step, StepObserver, Trajectory, TrialParams, check_missions_reachable,
    run_trial, simulate,
};
