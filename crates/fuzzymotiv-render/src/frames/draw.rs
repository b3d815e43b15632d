//! Drawing one frame with tiny-skia: the room (drawn once, [`Painter::new`]), then per frame
//! the path so far, the IR rays, the body and heading, and the labels.

use super::error::FrameError;
use fuzzymotiv::simulation::{HomeZone, Room};
use fuzzymotiv::simulation::{RayMount, rays};
use fuzzymotiv::simulation::{Segment, Vec2};
use tiny_skia::{
    Color, FillRule, LineCap, LineJoin, Mask, Paint, Path, PathBuilder, Pixmap, Rect, Stroke,
    StrokeDash, Transform,
};

use crate::frames::font::{draw_text, text_width};
use crate::frames::scene::{
    BODY, FLOOR, FrameOptions, GOAL_RIM, GOAL_ZONE, HEADING, HOME_RIM, HOME_ZONE, IDLE, OBSTACLE,
    OUTSIDE, PATH, TEXT, Track, View, WALL, WAYPOINT_RIM, WAYPOINT_ZONE, action_colour, ray_colour,
};

/// Draws the frames of one rollout in one room: the room is drawn once, each frame on a copy.
pub struct Painter<'a> {
    room: &'a Room,
    track: Track<'a>,
    opts: FrameOptions,
    view: View,
    background: Pixmap,
    walls: Vec<Segment>,
    /// Each sensor's axis ray (robot frame), drawn as its ray.
    axes: Vec<RayMount>,
    /// Line widths scale with the frame: 1 at 320 pixels.
    k: f32,
}

fn paint(rgb: [u8; 3]) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(rgb[0], rgb[1], rgb[2], 255));
    p
}

fn stroke(width: f32, cap: LineCap) -> Stroke {
    Stroke {
        width,
        line_cap: cap,
        line_join: LineJoin::Round,
        ..Stroke::default()
    }
}

/// A zone (home, goal, waypoint) as its disc within the room's `outline`, filled and its rim
/// dashed in `colours` (fill, rim).
fn draw_zone(
    bg: &mut Pixmap,
    view: &View,
    outline: &Path,
    zone: HomeZone,
    (fill, rim): ([u8; 3], [u8; 3]),
    k: f32,
) {
    let id = Transform::identity();
    let (cx, cy) = view.point(zone.centre);
    let radius = (zone.radius * view.scale) as f32;
    if let (Some(disc), Some(mut mask)) = (
        PathBuilder::from_circle(cx, cy, radius),
        Mask::new(view.size, view.size),
    ) {
        mask.fill_path(outline, FillRule::Winding, true, id);
        bg.fill_path(&disc, &paint(fill), FillRule::Winding, id, Some(&mask));
        let mut line = stroke(1.2 * k, LineCap::Butt);
        line.dash = StrokeDash::new(vec![5.0 * k, 4.0 * k], 0.0);
        bg.stroke_path(&disc, &paint(rim), &line, id, Some(&mask));
    }
}

/// A closed polygon's path in frame pixels.
fn polygon(view: &View, poly: &[Vec2]) -> Option<Path> {
    let mut pb = PathBuilder::new();
    for (k, p) in poly.iter().enumerate() {
        let (x, y) = view.point(*p);
        if k == 0 {
            pb.move_to(x, y)
        } else {
            pb.line_to(x, y)
        }
    }
    pb.close();
    pb.finish()
}

impl<'a> Painter<'a> {
    /// A painter of `track` in `room`; the error names the track's bad column.
    pub fn new(room: &'a Room, track: Track<'a>, opts: FrameOptions) -> Result<Self, FrameError> {
        track.check()?;
        let view = View::new(room, opts.size());
        let robot = opts.robot();
        let axes = rays(opts.sensor_model(), robot)[..robot.sensors()]
            .iter()
            .map(|r| r[0])
            .collect();
        let mut painter = Painter {
            room,
            track,
            opts,
            view,
            background: Pixmap::new(opts.size(), opts.size()).expect("size checked"),
            walls: room.walls(),
            axes,
            k: (opts.size() as f32 / 320.0).max(0.4),
        };
        painter.draw_room();
        painter.number_waypoints();
        Ok(painter)
    }

    /// The view (where room points land in the frames).
    pub fn view(&self) -> &View {
        &self.view
    }

    /// The floor, the home zone (clipped to the floor), the obstacles and the walls, under a
    /// plain header band.
    fn draw_room(&mut self) {
        let (view, room, k) = (&self.view, self.room, self.k);
        let bg = &mut self.background;
        bg.fill(Color::from_rgba8(OUTSIDE[0], OUTSIDE[1], OUTSIDE[2], 255));
        let id = Transform::identity();
        let size = view.size as f32;
        if let Some(r) = Rect::from_xywh(0.0, 0.0, size, view.header as f32) {
            bg.fill_rect(r, &paint(FLOOR), id, None);
        }
        let Some(outline) = polygon(view, &room.outline) else {
            return;
        };
        bg.fill_path(&outline, &paint(FLOOR), FillRule::Winding, id, None);
        let zones = std::iter::once((room.home_zone, HOME_ZONE, HOME_RIM))
            .chain(room.mission.goal.map(|g| (g, GOAL_ZONE, GOAL_RIM)))
            .chain((room.mission.waypoints.iter()).map(|w| (*w, WAYPOINT_ZONE, WAYPOINT_RIM)));
        for (zone, fill, rim) in zones {
            draw_zone(bg, view, &outline, zone, (fill, rim), k);
        }
        for o in &room.obstacles {
            if let Some(p) = polygon(view, o) {
                bg.fill_path(&p, &paint(OBSTACLE), FillRule::Winding, id, None);
                bg.stroke_path(&p, &paint(WALL), &stroke(1.2 * k, LineCap::Butt), id, None);
            }
        }
        bg.stroke_path(
            &outline,
            &paint(WALL),
            &stroke(2.5 * k, LineCap::Butt),
            id,
            None,
        );
    }

    /// Numbers the room's waypoints (from 1) at their centres.
    fn number_waypoints(&mut self) {
        let (s, size) = (self.view.text_scale, self.view.size as usize);
        for (n, w) in self.room.mission.waypoints.iter().enumerate() {
            let label = (n + 1).to_string();
            let (x, y) = self.view.point(w.centre);
            let half = text_width(&label, s) as f32 / 2.0;
            let (x, y) = ((x - half).max(0.0), (y - 4.0 * s as f32).max(0.0));
            let data = self.background.data_mut();
            draw_text(
                data,
                size,
                (x as usize, y as usize),
                &label,
                s,
                WAYPOINT_RIM,
            );
        }
    }

    /// Draws the frame of pose `t` into `frame` (a pixmap of the frame's size).
    pub fn draw(&self, t: usize, frame: &mut Pixmap) {
        frame.data_mut().copy_from_slice(self.background.data());
        self.draw_path(t, frame);
        if let Some(reading) = self.track.sensors.and_then(|s| s.get(t)) {
            self.draw_rays(t, reading, frame);
        }
        self.draw_body(t, frame);
        self.draw_labels(t, frame);
    }

    /// The path from home to pose `t`.
    fn draw_path(&self, t: usize, frame: &mut Pixmap) {
        if t == 0 {
            return;
        }
        let mut pb = PathBuilder::with_capacity(t + 1, t + 1);
        for (k, p) in self.track.poses[..=t].iter().enumerate() {
            let (x, y) = self.view.point(p.position());
            if k == 0 {
                pb.move_to(x, y)
            } else {
                pb.line_to(x, y)
            }
        }
        if let Some(path) = pb.finish() {
            let s = stroke(1.6 * self.k, LineCap::Round);
            frame.stroke_path(&path, &paint(PATH), &s, Transform::identity(), None);
        }
    }

    /// The robot's IR sensors' axis rays at pose `t`: from the sensor to the first wall, at
    /// most the ray's range; grey and thin for nothing seen, red and thick for a wall at
    /// contact.
    fn draw_rays(&self, t: usize, reading: &[f64], frame: &mut Pixmap) {
        let max = self.opts.robot().reading_max();
        let pose = self.track.poses[t];
        for (ray, &v) in self.axes.iter().zip(reading) {
            let origin = pose.position() + ray.origin.rotate(pose.heading);
            let dir = Vec2::from_angle(pose.heading + ray.angle);
            let reach = (self.walls.iter())
                .filter_map(|w| w.ray_hit(origin, dir))
                .fold(ray.range(), f64::min);
            let (x0, y0) = self.view.point(origin);
            let (x1, y1) = self.view.point(origin + dir * reach);
            let mut pb = PathBuilder::new();
            pb.move_to(x0, y0);
            pb.line_to(x1, y1);
            let width = (1.0 + 3.0 * (v / max).clamp(0.0, 1.0) as f32) * self.k;
            if let Some(path) = pb.finish() {
                let s = stroke(width, LineCap::Butt);
                frame.stroke_path(
                    &path,
                    &paint(ray_colour(v, max)),
                    &s,
                    Transform::identity(),
                    None,
                );
            }
        }
    }

    /// The body at pose `t` (a disc of the robot's radius) and its heading: a line from a third
    /// of the radius to the rim, so the body's centre keeps the body colour.
    fn draw_body(&self, t: usize, frame: &mut Pixmap) {
        let pose = self.track.poses[t];
        let (cx, cy) = self.view.point(pose.position());
        let r = self.opts.radius();
        let id = Transform::identity();
        if let Some(disc) = PathBuilder::from_circle(cx, cy, (r * self.view.scale) as f32) {
            frame.fill_path(&disc, &paint(BODY), FillRule::Winding, id, None);
            let rim = stroke(1.5 * self.k, LineCap::Butt);
            frame.stroke_path(&disc, &paint(HEADING), &rim, id, None);
        }
        let dir = Vec2::from_angle(pose.heading);
        let (x0, y0) = self.view.point(pose.position() + dir * (r / 3.0));
        let (x1, y1) = self.view.point(pose.position() + dir * r);
        let mut pb = PathBuilder::new();
        pb.move_to(x0, y0);
        pb.line_to(x1, y1);
        if let Some(line) = pb.finish() {
            let s = stroke(2.0 * self.k, LineCap::Butt);
            frame.stroke_path(&line, &paint(HEADING), &s, id, None);
        }
    }

    /// The header: the room and the step counter on the left, the action taken from pose `t`
    /// on the right (`idle` after the trial ended at home, `end` at the last pose).
    fn draw_labels(&self, t: usize, frame: &mut Pixmap) {
        let (s, size) = (self.view.text_scale, self.view.size as usize);
        let pad = View::pad(s);
        let last = self.track.poses.len() - 1;
        let (action, colour) = match (self.track.actions.and_then(|a| a.get(t)), t < last) {
            _ if (self.track.idle.and_then(|i| i.get(t))) == Some(&true) => ("idle", IDLE),
            (Some(a), _) => (a.label(), action_colour(*a)),
            (None, false) if self.track.actions.is_some() => ("end", IDLE),
            _ => ("", TEXT),
        };
        let right = text_width(action, s);
        let step = format!("step {t}/{last}");
        let fits = |text: &str| text_width(text, s) + right + 4 * pad <= size;
        let left = [
            format!("{}: {step}", self.room.name),
            step,
            format!("{t}/{last}"),
        ]
        .into_iter()
        .find(|l| fits(l))
        .unwrap_or_default();
        let data = frame.data_mut();
        draw_text(data, size, (pad, pad), &left, s, TEXT);
        draw_text(
            data,
            size,
            (size.saturating_sub(right + pad), pad),
            action,
            s,
            colour,
        );
    }
}
