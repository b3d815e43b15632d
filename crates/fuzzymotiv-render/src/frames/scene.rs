//! What a frame shows and where: the options ([`FrameOptions`]), the rollout drawn
//! ([`Track`]), the mapping from the room's millimetres to pixels ([`View`]) and the colours.

use super::error::{Column, FrameError};
use fuzzymotiv::simulation::Room;
use fuzzymotiv::simulation::Vec2;
use fuzzymotiv::simulation::{Action, Pose};
use fuzzymotiv::simulation::{Readings, RobotSpec, SensorModel};
use fuzzymotiv::simulation::{Trajectory, TrialParams};

use crate::frames::font::GLYPH_H;

/// Smallest frame side (pixels).
pub const MIN_SIZE: u32 = 64;
/// Largest frame side (pixels).
pub const MAX_SIZE: u32 = 2048;
/// Default frame side (pixels).
pub const DEFAULT_SIZE: u32 = 320;

/// The background outside the room.
pub const OUTSIDE: [u8; 3] = [236, 236, 236];
/// The floor.
pub const FLOOR: [u8; 3] = [255, 255, 255];
/// The walls (outline).
pub const WALL: [u8; 3] = [34, 34, 34];
/// Obstacles.
pub const OBSTACLE: [u8; 3] = [153, 153, 153];
/// The home zone's disc (the report's 10 % blue on white).
pub const HOME_ZONE: [u8; 3] = [233, 241, 247];
/// The home zone's dashed rim.
pub const HOME_RIM: [u8; 3] = [121, 173, 210];
/// A goal zone's disc (a colour of the palette's cube, so GIFs show it exactly).
pub const GOAL_ZONE: [u8; 3] = [255, 204, 153];
/// A goal zone's dashed rim.
pub const GOAL_RIM: [u8; 3] = [255, 102, 0];
/// A waypoint's disc.
pub const WAYPOINT_ZONE: [u8; 3] = [204, 204, 255];
/// A waypoint's dashed rim and its number.
pub const WAYPOINT_RIM: [u8; 3] = [153, 51, 204];
/// The path so far.
pub const PATH: [u8; 3] = [31, 119, 180];
/// The robot's body.
pub const BODY: [u8; 3] = [199, 221, 236];
/// The body's rim and the heading line.
pub const HEADING: [u8; 3] = [31, 78, 121];
/// An IR ray reading nothing (0).
pub const RAY_LOW: [u8; 3] = [200, 200, 200];
/// An IR ray reading its maximum (1023).
pub const RAY_HIGH: [u8; 3] = [214, 39, 40];
/// The labels' text.
pub const TEXT: [u8; 3] = [51, 51, 51];
/// Idle steps (after the trial ended at home) and the last pose.
pub const IDLE: [u8; 3] = [136, 136, 136];

/// The colour of an action's label (the report's action colours).
pub fn action_colour(a: Action) -> [u8; 3] {
    match a {
        Action::Straight => [76, 120, 168],
        Action::Left30 => [84, 162, 75],
        Action::Right30 => [228, 87, 86],
        Action::Turn180 => [178, 121, 162],
    }
}

/// The colour of an IR ray reading `v` (raw, 0 to the robot's largest reading `max`): grey
/// for nothing, red for a wall at contact, as the report draws them.
pub fn ray_colour(v: f64, max: f64) -> [u8; 3] {
    let t = (v / max).clamp(0.0, 1.0);
    let mix = |a: u8, b: u8| (f64::from(a) + (f64::from(b) - f64::from(a)) * t).round() as u8;
    [0, 1, 2].map(|k| mix(RAY_LOW[k], RAY_HIGH[k]))
}

/// The action whose label ([`Action::label`]) is `label`.
pub fn action_named(label: &str) -> Option<Action> {
    [
        Action::Straight,
        Action::Left30,
        Action::Right30,
        Action::Turn180,
    ]
    .into_iter()
    .find(|a| a.label() == label)
}

/// How frames are drawn: their size, which poses become frames, and the robot's body and
/// sensors (from the trial's parameters, [`FrameOptions::for_trial`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameOptions {
    size: u32,
    stride: usize,
    radius: f64,
    sensor_model: SensorModel,
    robot: &'static RobotSpec,
}

impl FrameOptions {
    /// Square frames of `size` pixels (64 to 2048) showing every `stride`-th pose (≥ 1),
    /// for the default robot. A bad value is named ([`FrameError::field`]).
    pub fn new(size: u32, stride: usize) -> Result<FrameOptions, FrameError> {
        if !(MIN_SIZE..=MAX_SIZE).contains(&size) {
            return Err(FrameError::Size {
                got: size,
                min: MIN_SIZE,
                max: MAX_SIZE,
            });
        }
        if stride == 0 {
            return Err(FrameError::Stride);
        }
        Ok(FrameOptions {
            size,
            stride,
            radius: RobotSpec::khepera().radius(),
            sensor_model: SensorModel::default(),
            robot: RobotSpec::khepera(),
        })
    }

    /// These options with the body radius and sensor model of a trial's robot.
    pub fn for_trial(self, trial: &TrialParams) -> FrameOptions {
        FrameOptions {
            radius: trial.robot().radius(),
            sensor_model: trial.sensor_model(),
            robot: trial.robot().spec(),
            ..self
        }
    }

    /// The frame side (pixels).
    pub fn size(&self) -> u32 {
        self.size
    }

    /// Every how many poses a frame is drawn.
    pub fn stride(&self) -> usize {
        self.stride
    }

    /// The robot's body radius (mm).
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The IR sensor model (whose axis rays are drawn).
    pub fn sensor_model(&self) -> SensorModel {
        self.sensor_model
    }

    /// The robot whose sensors are drawn (its layout and largest reading).
    pub fn robot(&self) -> &'static RobotSpec {
        self.robot
    }

    /// The pose of each frame: `0, stride, 2·stride, …`, and the last pose when the stride
    /// steps over it, so the last frame always shows where the rollout ended.
    ///
    /// ```
    /// use fuzzymotiv_render::frames::FrameOptions;
    /// let o = FrameOptions::new(320, 3).unwrap();
    /// assert_eq!(o.frame_poses(8), [0, 3, 6, 7]);
    /// assert_eq!(o.frame_poses(7), [0, 3, 6]);
    /// ```
    pub fn frame_poses(&self, poses: usize) -> Vec<usize> {
        let mut out: Vec<usize> = (0..poses).step_by(self.stride).collect();
        if poses > 0 && out.last() != Some(&(poses - 1)) {
            out.push(poses - 1);
        }
        out
    }
}

/// The rollout a set of frames shows: `T + 1` poses (the pose at the start of every step, then
/// the final one) and, when known, per step the eight IR readings (raw, 0–1023), the action
/// taken and whether the step was idle (after the trial ended at home). Sensors, actions and
/// idle flags have `T` or `T + 1` rows: frame `t` shows row `t` when there is one.
#[derive(Debug, Clone, Copy)]
pub struct Track<'a> {
    /// The poses (mm, rad).
    pub poses: &'a [Pose],
    /// The IR readings at each pose.
    pub sensors: Option<&'a [Readings]>,
    /// The action taken from each pose.
    pub actions: Option<&'a [Action]>,
    /// Whether each step was idle.
    pub idle: Option<&'a [bool]>,
}

impl<'a> Track<'a> {
    /// The whole of a recorded trial.
    pub fn of(tr: &'a Trajectory) -> Track<'a> {
        Track {
            poses: &tr.poses,
            sensors: Some(&tr.sensors),
            actions: Some(&tr.actions),
            idle: Some(&tr.idle),
        }
    }

    /// Checks the track: at least one pose, finite poses and readings, and `T` or `T + 1` rows
    /// of the optional columns; the error names the column (`x`, `y`, `heading`, `sensors`,
    /// `action`, `idle`), the row and what is wrong.
    pub fn check(&self) -> Result<(), FrameError> {
        let n = self.poses.len();
        if n == 0 {
            return Err(FrameError::NoPoses);
        }
        for (t, p) in self.poses.iter().enumerate() {
            for (column, value) in [
                (Column::X, p.x),
                (Column::Y, p.y),
                (Column::Heading, p.heading),
            ] {
                if !value.is_finite() {
                    return Err(FrameError::NotFinite {
                        column,
                        row: t,
                        value,
                    });
                }
            }
        }
        let rows = |column: Column, len: usize| {
            if len + 1 == n || len == n {
                Ok(())
            } else {
                Err(FrameError::Rows {
                    column,
                    rows: len,
                    poses: n,
                })
            }
        };
        if let Some(s) = self.sensors {
            rows(Column::Sensors, s.len())?;
            if let Some((t, k)) = (s.iter().enumerate())
                .find_map(|(t, r)| r.iter().position(|v| !v.is_finite()).map(|k| (t, k)))
            {
                return Err(FrameError::Reading {
                    row: t,
                    sensor: k,
                    value: s[t][k],
                });
            }
        }
        if let Some(a) = self.actions {
            rows(Column::Action, a.len())?;
        }
        if let Some(i) = self.idle {
            rows(Column::Idle, i.len())?;
        }
        Ok(())
    }
}

/// Where the room lies in a frame: a header band for the labels on top, the room's bounding
/// box below it, scaled to fit with a margin and centred, y pointing up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Frame side (pixels).
    pub size: u32,
    /// Pixels per millimetre.
    pub scale: f64,
    /// The room's smallest x and largest y (mm): the top-left corner of its box.
    corner: Vec2,
    /// Where that corner lands (pixels).
    origin: (f64, f64),
    /// Font pixels per device pixel of the labels.
    pub text_scale: usize,
    /// Height of the header band (pixels).
    pub header: u32,
}

impl View {
    /// The view of `room` in frames of `size` pixels.
    pub fn new(room: &Room, size: u32) -> View {
        let s = f64::from(size);
        let text_scale = (size as usize / 160).max(1);
        let header = (GLYPH_H * text_scale + 2 * View::pad(text_scale)) as u32;
        let margin = (s * 0.03).max(3.0);
        let (lo, hi) = room.bounds();
        let (w, h) = ((hi.x - lo.x).max(1.0), (hi.y - lo.y).max(1.0));
        let (avail_w, avail_h) = (s - 2.0 * margin, s - f64::from(header) - 2.0 * margin);
        let scale = (avail_w / w).min(avail_h / h);
        let origin = (
            margin + (avail_w - w * scale) / 2.0,
            f64::from(header) + margin + (avail_h - h * scale) / 2.0,
        );
        View {
            size,
            scale,
            corner: Vec2::new(lo.x, hi.y),
            origin,
            text_scale,
            header,
        }
    }

    /// The labels' distance from the frame's edges (pixels) at `text_scale`.
    pub fn pad(text_scale: usize) -> usize {
        2 * text_scale + 1
    }

    /// Where the room point `p` (mm) lands in the frame (pixels, y down).
    pub fn point(&self, p: Vec2) -> (f32, f32) {
        (
            (self.origin.0 + (p.x - self.corner.x) * self.scale) as f32,
            (self.origin.1 + (self.corner.y - p.y) * self.scale) as f32,
        )
    }

    /// The pixel `(column, row)` that holds the room point `p`, if it is in the frame.
    pub fn pixel(&self, p: Vec2) -> Option<(u32, u32)> {
        let (x, y) = self.point(p);
        let inside = |v: f32| v >= 0.0 && v < self.size as f32;
        (inside(x) && inside(y)).then(|| (x.floor() as u32, y.floor() as u32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn options_name_the_bad_value() {
        assert_eq!(FrameOptions::new(63, 1).unwrap_err().field(), Some("size"));
        assert_eq!(
            FrameOptions::new(4096, 1).unwrap_err().field(),
            Some("size")
        );
        assert_eq!(
            FrameOptions::new(320, 0).unwrap_err().field(),
            Some("stride")
        );
        assert_eq!(FrameOptions::new(320, 1).unwrap().frame_poses(3), [0, 1, 2]);
        assert_eq!(FrameOptions::new(320, 5).unwrap().frame_poses(1), [0]);
    }

    #[test]
    fn the_room_fits_below_the_header() {
        let room = Room::builtin("H").unwrap();
        let v = View::new(&room, 320);
        let (lo, hi) = room.bounds();
        let (x0, y0) = v.point(Vec2::new(lo.x, hi.y));
        let (x1, y1) = v.point(Vec2::new(hi.x, lo.y));
        assert!(x0 >= 0.0 && y0 >= v.header as f32, "{x0} {y0}");
        assert!(x1 <= 320.0 && y1 <= 320.0, "{x1} {y1}");
        assert!(y1 > y0, "y points up in the room, down in the frame");
    }

    #[test]
    fn ray_colours_run_from_grey_to_red() {
        assert_eq!(ray_colour(0.0, 1023.0), RAY_LOW);
        assert_eq!(ray_colour(1023.0, 1023.0), RAY_HIGH);
        assert_eq!(ray_colour(5000.0, 1023.0), RAY_HIGH);
        assert_eq!(ray_colour(2000.0, 4000.0), ray_colour(511.5, 1023.0));
        assert_eq!(action_named("turn180"), Some(Action::Turn180));
        assert_eq!(action_named("jump"), None);
    }

    #[test]
    fn a_track_names_its_bad_column() {
        let poses = [Pose::new(0.0, 0.0, 0.0), Pose::new(1.0, 0.0, 0.0)];
        let sensors = [Readings::zeros(8); 3];
        let t = Track {
            poses: &poses,
            sensors: Some(&sensors),
            actions: None,
            idle: None,
        };
        let e = t.check().unwrap_err();
        assert_eq!(e.field(), Some("sensors"));
        assert!(e.to_string().starts_with("sensors: 3 rows for 2 poses"));
        let bad = [Pose {
            x: f64::NAN,
            y: 0.0,
            heading: 0.0,
        }];
        let t = Track {
            poses: &bad,
            sensors: None,
            actions: None,
            idle: None,
        };
        let e = t.check().unwrap_err();
        assert!(matches!(
            e,
            FrameError::NotFinite {
                column: Column::X,
                row: 0,
                ..
            }
        ));
        assert!(e.to_string().starts_with("x[0]"));
    }
}
