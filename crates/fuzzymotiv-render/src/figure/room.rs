//! Rooms and robots' paths in SVG ([`draw_room_and_path`]), the one drawing of a room every
//! SVG figure with rooms uses: the outline, the home zone and the mission's zones (each its
//! disc within the outline, the rim dashed where it runs inside the room), the obstacles, the
//! path with a heading tick per step, the home pose, the end (ringed when the trial ended at
//! home) and logged paths over it.

use fuzzymotiv::simulation::{HomeZone, Room, Trajectory, Vec2, point_in_polygon};

use super::doc::{Fill, PathData, Stroke, Svg, Text};

/// The home zone's colour.
pub const HOME_COLOUR: &str = "#1f77b4";
/// The goal zone's colour.
pub const GOAL_COLOUR: &str = "#ff7f0e";
/// The waypoints' colour.
pub const WAYPOINT_COLOUR: &str = "#9467bd";
/// The path's colour, and its step ticks'.
const PATH: &str = "#d62728";
const STEP_TICK: &str = "#7f1d1d";
/// The home pose's colour.
const HOME_POSE: &str = "#2ca02c";
/// Length of a step marker's heading tick (px).
const TICK: f64 = 3.0;
/// Sides of the polygon standing for a zone's circle (every 1.5°).
const ZONE_SIDES: usize = 240;
/// The robot's radius as drawn (mm): the Khepera's 27.5.
const BODY_MM: f64 = 27.5;

/// A logged path drawn over a room (e.g. a robot's tracked pose).
#[derive(Debug, Clone, PartialEq)]
pub struct LoggedPath {
    /// Its legend text (e.g. the log's file).
    pub label: String,
    /// The index, in the figure's rooms, of the room it was logged in.
    pub room: usize,
    /// Its positions in mm, in the room's frame.
    pub points: Vec<(f64, f64)>,
}

/// The colours of logged paths, in turn (none is a colour the rooms, zones or paths use).
const LOG_COLOURS: [&str; 4] = ["#0e7c86", "#8c564b", "#1a1a6e", "#7f7f00"];

/// The colour of the `k`-th logged path.
pub fn log_colour(k: usize) -> &'static str {
    LOG_COLOURS[k % LOG_COLOURS.len()]
}

/// Millimetres of a room to pixels: x to the right from `left`, y up in the room and down in
/// SVG from `top`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// The pixel of the room's left edge.
    pub left: f64,
    /// The pixel of the room's top edge.
    pub top: f64,
    /// The room's lower-left corner (mm).
    pub lo: Vec2,
    /// The room's upper-right corner (mm).
    pub hi: Vec2,
    /// Pixels per mm.
    pub scale: f64,
}

impl Projection {
    /// `room` at `scale` px per mm, its top-left corner at (left, top).
    pub fn of(room: &Room, (left, top): (f64, f64), scale: f64) -> Projection {
        let (lo, hi) = room.bounds();
        Projection {
            left,
            top,
            lo,
            hi,
            scale,
        }
    }

    /// The pixel of a point in mm.
    pub fn at(&self, x: f64, y: f64) -> (f64, f64) {
        (
            self.left + (x - self.lo.x) * self.scale,
            self.top + (self.hi.y - y) * self.scale,
        )
    }

    /// The pixels of points in mm.
    fn all(&self, pts: &[Vec2]) -> Vec<(f64, f64)> {
        pts.iter().map(|p| self.at(p.x, p.y)).collect()
    }
}

/// Pixels per mm for rooms side by side: 0.3 (the paper's 800 mm rooms 240 px wide, a room of
/// up to 1200 mm 360 px), less for larger rooms (a robot's own, e.g. the Thymio II's 2400 mm
/// ones) so that each room stays 360 px at most.
pub fn figure_scale<'a>(rooms: impl Iterator<Item = &'a Room>) -> f64 {
    let largest = rooms
        .map(|r| {
            let (lo, hi) = r.bounds();
            (hi.x - lo.x).max(hi.y - lo.y)
        })
        .fold(0.0, f64::max);
    if largest <= 1200.0 {
        0.3
    } else {
        360.0 / largest
    }
}

/// What a figure's caption says of its rooms' missions (nothing when no room has one).
pub fn mission_caption<'a>(rooms: impl Iterator<Item = &'a Room> + Clone) -> String {
    let goal = rooms.clone().any(|r| r.mission.goal.is_some());
    let waypoints = rooms.clone().any(|r| !r.mission.waypoints.is_empty());
    let mut s = String::new();
    if goal {
        s.push_str("orange: goal zone; ");
    }
    if waypoints {
        s.push_str("purple: waypoints, numbered in order; ");
    }
    s
}

/// `room` with the trial `tr` in it at `p`, and the logged paths `logs` (each with its
/// colour) over it.
pub fn draw_room_and_path(
    svg: &mut Svg,
    (room, tr): (&Room, &Trajectory),
    p: &Projection,
    logs: &[(&LoggedPath, &str)],
) {
    draw_room(svg, room, p);
    draw_mission(svg, room, p);
    draw_path(svg, tr, p);
    draw_home_and_end(svg, room, tr, p);
    for (log, colour) in logs {
        draw_logged_path(svg, log, colour, p);
    }
}

/// A room's outline, home zone and obstacles (over the zone).
fn draw_room(svg: &mut Svg, room: &Room, p: &Projection) {
    let wall = Stroke::of("#222");
    svg.polygon(
        &p.all(&room.outline),
        Fill::of("#fafafa").stroked(wall.width(2.0)),
    );
    draw_zone(svg, room, room.home_zone, HOME_COLOUR, p);
    for o in &room.obstacles {
        svg.polygon(&p.all(o), Fill::of("#888").stroked(wall));
    }
}

/// A room's mission: its goal zone and its waypoints (numbered from 1).
fn draw_mission(svg: &mut Svg, room: &Room, p: &Projection) {
    let label = |svg: &mut Svg, c: Vec2, text: &str, colour: &str| {
        let (x, y) = p.at(c.x, c.y);
        svg.text((x, y + 4.0), text, Text::MIDDLE.fill(colour).bold());
    };
    if let Some(goal) = room.mission.goal {
        draw_zone(svg, room, goal, GOAL_COLOUR, p);
        label(svg, goal.centre, "goal", GOAL_COLOUR);
    }
    for (k, w) in room.mission.waypoints.iter().enumerate() {
        draw_zone(svg, room, *w, WAYPOINT_COLOUR, p);
        label(svg, w.centre, &(k + 1).to_string(), WAYPOINT_COLOUR);
    }
}

/// A zone as its disc within the room's outline, filled lightly in `colour`, its rim dashed
/// where it runs inside the room.
fn draw_zone(svg: &mut Svg, room: &Room, zone: HomeZone, colour: &str, p: &Projection) {
    let (floor, rim) = zone_within(room, zone);
    if floor.len() >= 3 {
        svg.polygon(
            &p.all(&floor),
            Fill::of(colour).opacity(0.10).stroked(Stroke::of("none")),
        );
    }
    let mut d = PathData::new();
    for run in &rim {
        d = d.move_to(p.at(run[0].x, run[0].y));
        for q in &run[1..] {
            d = d.line_to(p.at(q.x, q.y));
        }
    }
    if !d.is_empty() {
        let rim = Stroke::of(colour).opacity(0.6).dashed("4 3");
        svg.path(&d, Fill::outline(rim), None);
    }
}

/// A zone within the room, in mm: the room's outline clipped to the zone's disc (a 240-gon;
/// Sutherland–Hodgman, exact for a convex clip region and any simple outline; where the
/// result falls apart in pieces they are joined by zero-width seams along the rim, which the
/// unstroked fill does not show), and the runs of the rim inside the outline.
fn zone_within(room: &Room, zone: HomeZone) -> (Vec<Vec2>, Vec<Vec<Vec2>>) {
    let circle: Vec<Vec2> = (0..ZONE_SIDES)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / ZONE_SIDES as f64;
            Vec2::new(
                zone.centre.x + zone.radius * a.cos(),
                zone.centre.y + zone.radius * a.sin(),
            )
        })
        .collect();
    (
        clip_to(&room.outline, &circle),
        rim_inside(&room.outline, &circle),
    )
}

/// `poly` clipped to the convex counter-clockwise `circle` (Sutherland–Hodgman).
fn clip_to(poly: &[Vec2], circle: &[Vec2]) -> Vec<Vec2> {
    // The circle runs counter-clockwise: inside its edge a → b means on the left.
    let mut poly = poly.to_vec();
    for (k, &a) in circle.iter().enumerate() {
        let b = circle[(k + 1) % circle.len()];
        let side = |q: Vec2| (b - a).cross(q - a);
        let mut out = Vec::with_capacity(poly.len() + 2);
        for (i, &cur) in poly.iter().enumerate() {
            let prev = poly[(i + poly.len() - 1) % poly.len()];
            let (sc, sp) = (side(cur), side(prev));
            if (sc >= 0.0) != (sp >= 0.0) {
                out.push(prev + (cur - prev) * (sp / (sp - sc)));
            }
            if sc >= 0.0 {
                out.push(cur);
            }
        }
        poly = out;
        if poly.is_empty() {
            break;
        }
    }
    poly
}

/// The runs of `circle`'s sides inside `outline`, each from its first point to its last, so
/// the dashes run on along a run (a path's dashes restart at every move).
fn rim_inside(outline: &[Vec2], circle: &[Vec2]) -> Vec<Vec<Vec2>> {
    let n = circle.len();
    let inside: Vec<bool> = (0..n)
        .map(|k| point_in_polygon(outline, (circle[k] + circle[(k + 1) % n]) * 0.5))
        .collect();
    let mut rim: Vec<Vec<Vec2>> = Vec::new();
    let start = (0..n).find(|&k| !inside[k]).map_or(0, |k| k + 1);
    for k in (start..start + n).map(|k| k % n) {
        if !inside[k] {
            continue;
        }
        if k == start % n || !inside[(k + n - 1) % n] || rim.is_empty() {
            rim.push(vec![circle[k]]);
        }
        rim.last_mut().expect("a run").push(circle[(k + 1) % n]);
    }
    rim
}

/// The path of the executed steps, with a tick along the heading after each step, so turns
/// on the spot show as several ticks on one point.
fn draw_path(svg: &mut Svg, tr: &Trajectory, p: &Projection) {
    let executed = tr.executed();
    let path: Vec<(f64, f64)> = tr.poses[..=executed]
        .iter()
        .map(|q| p.at(q.x, q.y))
        .collect();
    svg.polyline(&path, Stroke::of(PATH).width(1.0), None);
    let mut ticks = PathData::new();
    for q in &tr.poses[1..=executed] {
        let (dx, dy) = (TICK * q.heading.cos(), -TICK * q.heading.sin());
        ticks = ticks.move_to(p.at(q.x, q.y)).line_by((dx, dy));
    }
    svg.path(
        &ticks,
        Fill::outline(Stroke::of(STEP_TICK).width(0.8)),
        None,
    );
}

/// The home pose (circle and heading) and the end of the trial (ringed when it ended at home).
fn draw_home_and_end(svg: &mut Svg, room: &Room, tr: &Trajectory, p: &Projection) {
    let home = room.home;
    let r = BODY_MM * p.scale;
    let green = Stroke::of(HOME_POSE).width(2.0);
    svg.circle(p.at(home.x, home.y), r, Fill::outline(green), None);
    let nose = (
        home.x + 2.0 * BODY_MM * home.heading.cos(),
        home.y + 2.0 * BODY_MM * home.heading.sin(),
    );
    svg.line(p.at(home.x, home.y), p.at(nose.0, nose.1), green);
    if let Some(end) = tr.poses.last() {
        let executed = tr.executed();
        let at_home = executed < tr.len();
        let ring = Stroke::of(if at_home { "#000" } else { "none" }).width(1.5);
        let title = if at_home {
            format!("back in the home zone after step {executed}: the trial ended")
        } else {
            format!("end of the trial after {} steps", tr.len())
        };
        let fill = Fill::of(PATH).opacity(0.5).stroked(ring);
        svg.circle(p.at(end.x, end.y), r, fill, Some(&title));
    }
}

/// A logged path: a dashed line through its positions and a square at its end.
fn draw_logged_path(svg: &mut Svg, log: &LoggedPath, colour: &str, p: &Projection) {
    let path: Vec<(f64, f64)> = log.points.iter().map(|&(x, y)| p.at(x, y)).collect();
    let stroke = Stroke::of(colour).width(1.5).dashed("5 3");
    svg.polyline(&path, stroke, Some("logged"));
    if let Some(&(x, y)) = path.last() {
        svg.rect((x - 3.0, y - 3.0), (6.0, 6.0), Fill::of(colour));
    }
}
