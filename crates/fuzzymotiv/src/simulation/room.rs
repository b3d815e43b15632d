//! Rooms: walls as polygons, the home pose, the five built-in rooms (docs/model.md §4) and room files.
//!
//! ```
//! use fuzzymotiv::simulation::Room;
//! let h = Room::builtin("H").unwrap();
//! assert_eq!(h.area(), 2.0 * 200.0 * 800.0 + 400.0 * 240.0);
//! assert_eq!(h.walls().len(), 12);
//! ```

use serde::{Deserialize, Serialize};

use crate::params::{FieldError, Num};
use crate::simulation::geom::{
    Segment, Vec2, edges, perimeter, point_in_polygon, self_intersection, signed_area,
};
use crate::simulation::robot::{KHEPERA_RADIUS, Pose};

/// Largest coordinate magnitude accepted in room files (mm): rooms up to 20 m across.
pub const MAX_COORD: f64 = 1e4;

/// Most wall segments a room file may have (outline plus obstacles).
pub const MAX_WALLS: usize = 2000;

/// Names of the built-in rooms, in the order of the paper's tables.
pub const BUILTIN_ROOMS: [&str; 5] = ["H", "T", "L", "square", "rectangle"];

/// A room: an outer wall polygon, optional interior obstacles and the home pose.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Room {
    /// Unique name, used in tables.
    pub name: String,
    /// Outer wall, counter-clockwise (mm), closed implicitly.
    pub outline: Vec<Vec2>,
    /// Interior obstacles, each a closed polygon (mm).
    pub obstacles: Vec<Vec<Vec2>>,
    /// Start pose of every trial.
    pub home: Pose,
    /// The home zone: the robot has *escaped* once its centre has been outside it, and an
    /// escaped robot whose centre is inside it again has come home (a trial can end then).
    pub home_zone: Zone,
    /// The room's mission (a goal zone and waypoints), empty unless the room file declares one.
    #[serde(default, skip_serializing_if = "Mission::is_empty")]
    pub mission: Mission,
}

/// A disc in a room (mm): the home zone, a mission's goal or one of its waypoints.
///
/// ```
/// use fuzzymotiv::simulation::{Vec2, Zone};
/// let zone = Zone { centre: Vec2::new(0.0, 0.0), radius: 160.0 };
/// assert!(zone.contains(Vec2::new(40.0, 40.0)));
/// assert!(zone.contains(Vec2::new(160.0, 0.0)));
/// assert!(!zone.contains(Vec2::new(120.0, 120.0)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Zone {
    /// Centre (mm).
    pub centre: Vec2,
    /// Radius (mm), > 0.
    pub radius: f64,
}

/// A room's mission (docs/model.md §4): an optional goal zone and waypoints, in order.
///
/// ```
/// use fuzzymotiv::simulation::{Mission, Vec2, Zone};
/// assert!(Mission::default().is_empty());
/// let goal = Zone { centre: Vec2::new(850.0, 750.0), radius: 60.0 };
/// let m = Mission { goal: Some(goal), waypoints: vec![] };
/// assert!(!m.is_empty());
/// assert_eq!(m.zones().next(), Some(("goal".to_string(), goal)));
/// ```
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Mission {
    /// The zone to reach, if any.
    pub goal: Option<Zone>,
    /// Zones to visit, in order.
    pub waypoints: Vec<Zone>,
}

impl Mission {
    /// Whether the mission has neither a goal nor waypoints.
    pub fn is_empty(&self) -> bool {
        self.goal.is_none() && self.waypoints.is_empty()
    }

    /// Every zone of the mission with its room-file field: `goal`, then `waypoints[0]`, ….
    pub fn zones(&self) -> impl Iterator<Item = (String, Zone)> + '_ {
        let goal = self.goal.map(|z| ("goal".to_string(), z));
        let waypoints = (self.waypoints.iter())
            .enumerate()
            .map(|(i, z)| (format!("waypoints[{i}]"), *z));
        goal.into_iter().chain(waypoints)
    }
}

impl Zone {
    /// Whether `p` is inside the zone (on its rim counts as inside).
    #[inline]
    pub fn contains(&self, p: Vec2) -> bool {
        let d = p - self.centre;
        d.x * d.x + d.y * d.y <= self.radius * self.radius
    }
}

/// Radius of the built-in rooms' home zones and of a room file's default zone (mm): the quarter
/// circle the paper's Figs. 7–8 draw in every room.
pub const HOME_ZONE_RADIUS: f64 = 160.0;

/// Home position of the built-in rooms (mm), heading +x.
pub const BUILTIN_HOME: (f64, f64) = (40.0, 40.0);

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRoom {
    name: String,
    outline: Vec<[f64; 2]>,
    home: RawHome,
    home_zone: Option<RawZone>,
    #[serde(default)]
    obstacles: Vec<RawObstacle>,
    goal: Option<RawZone>,
    #[serde(default)]
    waypoints: Vec<RawZone>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawZone {
    x: f64,
    y: f64,
    radius: f64,
}

impl RawZone {
    /// The zone, its centre within ±`MAX_COORD` and its radius > 0 (`field` names it).
    fn zone(&self, field: &str) -> Result<Zone, FieldError> {
        for (name, v) in [("x", self.x), ("y", self.y)] {
            if !(v.is_finite() && v.abs() <= MAX_COORD) {
                return Err(FieldError::new(
                    format!("{field}.{name}"),
                    format!(
                        "must be a finite coordinate within ±{MAX_COORD} mm, got {}",
                        Num(v)
                    ),
                ));
            }
        }
        if !(self.radius > 0.0 && self.radius <= MAX_COORD) {
            return Err(FieldError::new(
                format!("{field}.radius"),
                format!(
                    "must be a radius > 0 and ≤ {MAX_COORD} mm, got {} (e.g. radius = 60)",
                    Num(self.radius)
                ),
            ));
        }
        Ok(Zone {
            centre: Vec2::new(self.x, self.y),
            radius: self.radius,
        })
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawHome {
    x: f64,
    y: f64,
    heading_deg: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawObstacle {
    outline: Vec<[f64; 2]>,
}

impl RawRoom {
    /// Every coordinate finite and within ±`MAX_COORD`, and at most `MAX_WALLS` walls.
    fn check_coordinates(&self) -> Result<(), FieldError> {
        for (i, p) in self.outline.iter().enumerate() {
            if !p[0].is_finite() || !p[1].is_finite() {
                return Err(FieldError::new(
                    format!("outline[{i}]"),
                    format!(
                        "coordinates must be finite numbers (mm), got [{}, {}]",
                        p[0], p[1]
                    ),
                ));
            }
        }
        let walls = self.outline.len()
            + self
                .obstacles
                .iter()
                .map(|o| o.outline.len())
                .sum::<usize>();
        if walls > MAX_WALLS {
            return Err(FieldError::new(
                "outline",
                format!("the room has {walls} wall segments; at most {MAX_WALLS} are supported"),
            ));
        }
        for (i, p) in self.outline.iter().enumerate() {
            if p[0].abs() > MAX_COORD || p[1].abs() > MAX_COORD {
                return Err(FieldError::new(
                    format!("outline[{i}]"),
                    format!(
                        "coordinates must be within ±{MAX_COORD} mm (10 m), got [{}, {}]",
                        p[0], p[1]
                    ),
                ));
            }
        }
        for (k, o) in self.obstacles.iter().enumerate() {
            for (i, p) in o.outline.iter().enumerate() {
                if !p[0].is_finite()
                    || !p[1].is_finite()
                    || p[0].abs() > MAX_COORD
                    || p[1].abs() > MAX_COORD
                {
                    return Err(FieldError::new(
                        format!("obstacles[{k}].outline[{i}]"),
                        format!(
                            "coordinates must be finite numbers (mm), got [{}, {}]",
                            p[0], p[1]
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The home pose's values finite, and its zone (given, or the default around home).
    fn home_zone(&self) -> Result<Zone, FieldError> {
        for (name, v) in [
            ("home.x", self.home.x),
            ("home.y", self.home.y),
            ("home.heading_deg", self.home.heading_deg),
        ] {
            if !v.is_finite() {
                return Err(FieldError::new(
                    name,
                    format!("must be a finite number, got {v}"),
                ));
            }
        }
        let Some(z) = &self.home_zone else {
            return Ok(Zone {
                centre: Vec2::new(self.home.x, self.home.y),
                radius: HOME_ZONE_RADIUS,
            });
        };
        for (name, v) in [
            ("home_zone.x", z.x),
            ("home_zone.y", z.y),
            ("home_zone.radius", z.radius),
        ] {
            if !v.is_finite() {
                return Err(FieldError::new(
                    name,
                    format!("must be a finite number (mm), got {v}"),
                ));
            }
        }
        Ok(Zone {
            centre: Vec2::new(z.x, z.y),
            radius: z.radius,
        })
    }

    /// The mission's zones, each with finite values and a radius > 0.
    fn mission(&self) -> Result<Mission, FieldError> {
        let goal = self.goal.as_ref().map(|z| z.zone("goal")).transpose()?;
        let waypoints = (self.waypoints.iter().enumerate())
            .map(|(i, z)| z.zone(&format!("waypoints[{i}]")))
            .collect::<Result<_, _>>()?;
        Ok(Mission { goal, waypoints })
    }
}

fn pts(v: &[(f64, f64)]) -> Vec<Vec2> {
    v.iter().map(|&(x, y)| Vec2::new(x, y)).collect()
}

impl Room {
    /// One of the five built-in rooms by name (`H`, `T`, `L`, `square`, `rectangle`): the
    /// paper's rooms as its Figs. 7–8 draw them (docs/model.md), 800 mm across, home at
    /// (40, 40) heading +x, home zone of radius 160 mm centred on the bottom-left corner.
    pub fn builtin(name: &str) -> Option<Room> {
        let outline = match name {
            "square" => pts(&[(0., 0.), (800., 0.), (800., 800.), (0., 800.)]),
            "rectangle" => pts(&[(0., 0.), (800., 0.), (800., 400.), (0., 400.)]),
            "L" => pts(&[
                (0., 0.),
                (400., 0.),
                (400., 400.),
                (800., 400.),
                (800., 800.),
                (0., 800.),
            ]),
            "T" => pts(&[
                (0., 0.),
                (400., 0.),
                (400., 240.),
                (800., 240.),
                (800., 560.),
                (400., 560.),
                (400., 800.),
                (0., 800.),
            ]),
            "H" => pts(&[
                (0., 0.),
                (200., 0.),
                (200., 280.),
                (600., 280.),
                (600., 0.),
                (800., 0.),
                (800., 800.),
                (600., 800.),
                (600., 520.),
                (200., 520.),
                (200., 800.),
                (0., 800.),
            ]),
            _ => return None,
        };
        Some(Room {
            name: name.to_string(),
            outline,
            obstacles: Vec::new(),
            home: Pose::new(BUILTIN_HOME.0, BUILTIN_HOME.1, 0.0),
            home_zone: Zone {
                centre: Vec2::new(0.0, 0.0),
                radius: HOME_ZONE_RADIUS,
            },
            mission: Mission::default(),
        })
    }

    /// Parses a room file and checks its geometry (docs/model.md §4), but not that its mission
    /// is reachable: [`Room::from_toml_str`] (beside the arena's flood fill) does both.
    pub(crate) fn geometry_from_toml_str(
        text: &str,
        source_name: &str,
    ) -> Result<Room, FieldError> {
        // A room's values are numbers and names, no whole numbers: their range is not asked.
        let raw: RawRoom = crate::params::plain::from_str(text, |_| "≥ 0".into()).map_err(|e| {
            let msg = e.toml.message();
            FieldError::new(e.field(text), format!("{msg} (expected: name = \"...\", outline = [[x, y], ...], home = {{ x, y, heading_deg }}, optional home_zone = {{ x, y, radius }}, optional [[obstacles]] outline, optional goal = {{ x, y, radius }}, optional [[waypoints]] x, y, radius)")).in_source(source_name)
        })?;
        raw.check_coordinates()
            .map_err(|e| e.in_source(source_name))?;
        let home_zone = raw.home_zone().map_err(|e| e.in_source(source_name))?;
        let mission = raw.mission().map_err(|e| e.in_source(source_name))?;
        let to_vec = |v: &[[f64; 2]]| v.iter().map(|p| Vec2::new(p[0], p[1])).collect::<Vec<_>>();
        let room = Room {
            name: raw.name,
            outline: to_vec(&raw.outline),
            obstacles: raw.obstacles.iter().map(|o| to_vec(&o.outline)).collect(),
            home: Pose::new(raw.home.x, raw.home.y, raw.home.heading_deg.to_radians()),
            home_zone,
            mission,
        };
        room.validated(source_name)
    }

    /// Checks the geometry (docs/model.md §4) and normalises the outline to counter-clockwise order.
    pub fn validated(mut self, source_name: &str) -> Result<Room, FieldError> {
        let in_source = |e: FieldError| e.in_source(source_name);
        if self.name.trim().is_empty() {
            return Err(in_source(FieldError::new(
                "name",
                "must be a non-empty name, e.g. name = \"U\"",
            )));
        }
        check_polygon(&self.outline, "outline").map_err(in_source)?;
        if signed_area(&self.outline) < 0.0 {
            self.outline.reverse();
        }
        self.check_obstacles().map_err(in_source)?;
        self.check_home().map_err(in_source)?;
        self.check_mission().map_err(in_source)?;
        Ok(self)
    }

    /// Every zone of the mission has a radius > 0 and its centre on the floor (inside the
    /// outline, outside every obstacle).
    fn check_mission(&self) -> Result<(), FieldError> {
        for (field, zone) in self.mission.zones() {
            if !(zone.radius > 0.0 && zone.radius <= MAX_COORD) {
                return Err(FieldError::new(
                    format!("{field}.radius"),
                    format!(
                        "must be a radius > 0 and ≤ {MAX_COORD} mm, got {} (e.g. radius = 60)",
                        Num(zone.radius)
                    ),
                ));
            }
            let c = zone.centre;
            if !point_in_polygon(&self.outline, c) {
                return Err(FieldError::new(
                    field,
                    format!(
                        "the centre ({}, {}) lies outside the room outline; put it inside the room",
                        Num(c.x),
                        Num(c.y)
                    ),
                ));
            }
            if let Some(k) = self.obstacles.iter().position(|o| point_in_polygon(o, c)) {
                return Err(FieldError::new(
                    field,
                    format!(
                        "the centre ({}, {}) lies inside obstacles[{k}]; put it on the free floor",
                        Num(c.x),
                        Num(c.y)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Every obstacle is a simple polygon strictly inside the outline.
    fn check_obstacles(&self) -> Result<(), FieldError> {
        for (k, obstacle) in self.obstacles.iter().enumerate() {
            let field = format!("obstacles[{k}].outline");
            check_polygon(obstacle, &field)?;
            if let Some(p) = obstacle
                .iter()
                .find(|p| !point_in_polygon(&self.outline, **p))
            {
                return Err(FieldError::new(
                    field,
                    format!(
                        "obstacle point ({}, {}) lies outside the room outline; obstacles must be inside the room",
                        p.x, p.y
                    ),
                ));
            }
            if edges(obstacle).any(|e| edges(&self.outline).any(|w| w.intersects(&e))) {
                return Err(FieldError::new(
                    field,
                    "obstacle crosses or touches the room outline; it must lie strictly inside",
                ));
            }
        }
        Ok(())
    }

    /// Home inside the room, a body radius from every wall, and inside its home zone.
    fn check_home(&self) -> Result<(), FieldError> {
        let home = self.home.position();
        let inside = point_in_polygon(&self.outline, home)
            && !self.obstacles.iter().any(|o| point_in_polygon(o, home));
        if !inside {
            return Err(FieldError::new(
                "home",
                format!(
                    "home ({}, {}) is outside the room (or inside an obstacle); put it inside the outline",
                    home.x, home.y
                ),
            ));
        }
        let clearance = self
            .walls()
            .iter()
            .map(|w| w.dist_to(home))
            .fold(f64::INFINITY, f64::min);
        if clearance < KHEPERA_RADIUS {
            return Err(FieldError::new(
                "home",
                format!(
                    "home ({}, {}) is {clearance:.1} mm from a wall; it must be at least the body radius ({KHEPERA_RADIUS} mm) away",
                    home.x, home.y
                ),
            ));
        }
        let zone = self.home_zone;
        if !(zone.radius > 0.0 && zone.radius <= MAX_COORD) {
            return Err(FieldError::new(
                "home_zone.radius",
                format!(
                    "must be a radius > 0 and ≤ {MAX_COORD} mm, got {} (the default is {HOME_ZONE_RADIUS})",
                    Num(zone.radius)
                ),
            ));
        }
        if !zone.contains(home) {
            return Err(FieldError::new(
                "home_zone",
                format!(
                    "home ({}, {}) is {:.1} mm from the zone centre ({}, {}), outside its radius {}; the home position must lie inside its zone",
                    home.x,
                    home.y,
                    home.dist(zone.centre),
                    zone.centre.x,
                    zone.centre.y,
                    zone.radius
                ),
            ));
        }
        Ok(())
    }

    /// All wall segments: the outline's edges, then each obstacle's.
    pub fn walls(&self) -> Vec<Segment> {
        let mut w: Vec<Segment> = edges(&self.outline).collect();
        for o in &self.obstacles {
            w.extend(edges(o));
        }
        w
    }

    /// Free floor area (mm²): outline minus obstacles.
    pub fn area(&self) -> f64 {
        signed_area(&self.outline).abs()
            - self
                .obstacles
                .iter()
                .map(|o| signed_area(o).abs())
                .sum::<f64>()
    }

    /// Length of the outer wall (mm).
    pub fn perimeter(&self) -> f64 {
        perimeter(&self.outline)
    }

    /// Axis-aligned bounding box of the outline `(min, max)`.
    pub fn bounds(&self) -> (Vec2, Vec2) {
        let mut lo = Vec2::new(f64::INFINITY, f64::INFINITY);
        let mut hi = Vec2::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
        for p in &self.outline {
            lo = Vec2::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Vec2::new(hi.x.max(p.x), hi.y.max(p.y));
        }
        (lo, hi)
    }

    /// Whether a point is on the floor: inside the outline and outside every obstacle.
    pub fn contains(&self, p: Vec2) -> bool {
        point_in_polygon(&self.outline, p) && !self.obstacles.iter().any(|o| point_in_polygon(o, p))
    }

    /// Largest distance from home to any outline vertex (mm): `d_max` of the homing term.
    pub fn max_home_distance(&self) -> f64 {
        let h = self.home.position();
        self.outline.iter().map(|p| p.dist(h)).fold(0.0, f64::max)
    }
}

fn check_polygon(poly: &[Vec2], field: &str) -> Result<(), FieldError> {
    if poly.len() < 3 {
        return Err(FieldError::new(
            field,
            format!("needs at least 3 points [x, y] (mm), got {}", poly.len()),
        ));
    }
    if let Some((i, j)) = self_intersection(poly) {
        return Err(FieldError::new(
            field,
            format!(
                "the polygon intersects itself (edges {i} and {j} cross); list the corners in order around the room"
            ),
        ));
    }
    if signed_area(poly).abs() < 1e-9 {
        return Err(FieldError::new(field, "the polygon has zero area"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_rooms_are_valid() {
        for name in BUILTIN_ROOMS {
            let r = Room::builtin(name).unwrap();
            r.clone().validated(name).unwrap();
            assert!(signed_area(&r.outline) > 0.0, "{name} not CCW");
        }
        assert_eq!(Room::builtin("square").unwrap().area(), 640_000.0);
        assert_eq!(Room::builtin("rectangle").unwrap().area(), 320_000.0);
        assert_eq!(Room::builtin("L").unwrap().area(), 480_000.0);
        assert_eq!(
            Room::builtin("T").unwrap().area(),
            320_000.0 + 400.0 * 320.0
        );
        assert_eq!(
            Room::builtin("H").unwrap().area(),
            2.0 * 200.0 * 800.0 + 400.0 * 240.0
        );
        assert_eq!(Room::builtin("L").unwrap().perimeter(), 3200.0);
        for name in BUILTIN_ROOMS {
            let r = Room::builtin(name).unwrap();
            assert_eq!((r.home.x, r.home.y, r.home.heading), (40.0, 40.0, 0.0));
            assert_eq!(r.home_zone.centre, Vec2::new(0.0, 0.0));
            assert_eq!(r.home_zone.radius, 160.0);
        }
        assert!(Room::builtin("nope").is_none());
    }

    #[test]
    fn room_file_round_trip_and_clockwise_normalised() {
        let text = r#"
name = "U"
outline = [[0,0],[0,800],[250,800],[250,250],[650,250],[650,800],[900,800],[900,0]]
home = { x = 125, y = 600, heading_deg = -90 }
[[obstacles]]
outline = [[400,100],[500,100],[500,200],[400,200]]
"#;
        let r = Room::from_toml_str(text, "u.toml").unwrap();
        assert!(signed_area(&r.outline) > 0.0);
        assert_eq!(r.walls().len(), 12);
        assert!((r.home.heading + std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        // No home_zone: centred on home, radius 160.
        assert_eq!(r.home_zone.centre, Vec2::new(125.0, 600.0));
        assert_eq!(r.home_zone.radius, HOME_ZONE_RADIUS);
        let z = Room::from_toml_str(
            &format!("{text}\nhome_zone = {{ x = 100, y = 650, radius = 120 }}\n").replace(
                "[[obstacles]]\noutline = [[400,100],[500,100],[500,200],[400,200]]\n",
                "",
            ),
            "u.toml",
        )
        .unwrap();
        assert_eq!(z.home_zone.centre, Vec2::new(100.0, 650.0));
        assert_eq!(z.home_zone.radius, 120.0);
    }

    /// Room-file `home_zone` errors name the field (radius > 0, finite, home inside the zone).
    #[test]
    fn bad_home_zones_name_the_field() {
        let room = "name='x'\noutline=[[0,0],[300,0],[300,300],[0,300]]\nhome={x=150,y=150,heading_deg=0}\n";
        let e = bad(&format!("{room}home_zone={{x=150,y=150,radius=0}}"));
        assert_eq!(e.field, "home_zone.radius");
        assert!(e.reason.contains("> 0"), "{e}");
        let e = bad(&format!("{room}home_zone={{x=150,y=150,radius=-5}}"));
        assert_eq!(e.field, "home_zone.radius");
        let e = bad(&format!("{room}home_zone={{x=150,y=150,radius=nan}}"));
        assert_eq!(e.field, "home_zone.radius");
        let e = bad(&format!("{room}home_zone={{x=inf,y=150,radius=10}}"));
        assert_eq!(e.field, "home_zone.x");
        let e = bad(&format!("{room}home_zone={{x=0,y=0,radius=100}}"));
        assert_eq!(e.field, "home_zone");
        assert!(e.reason.contains("inside its zone"), "{e}");
        let e = bad(&format!("{room}home_zone={{x=0,y=0}}"));
        assert!(e.to_string().contains("radius"), "{e}");
    }

    fn bad(text: &str) -> FieldError {
        Room::from_toml_str(text, "bad.toml").unwrap_err()
    }

    #[test]
    fn bad_room_files_name_the_field() {
        let e = bad("name='x'\noutline=[[0,0],[1,1]]\nhome={x=0,y=0,heading_deg=0}");
        assert_eq!(e.field, "outline");
        assert!(e.reason.contains("at least 3"));
        let e = bad(
            "name='x'\noutline=[[0,0],[100,100],[100,0],[0,100]]\nhome={x=50,y=20,heading_deg=0}",
        );
        assert_eq!(e.field, "outline");
        assert!(e.reason.contains("intersects"), "{e}");
        let e = bad("name='x'\noutline=[[0,0],[100,0],[200,0]]\nhome={x=50,y=20,heading_deg=0}");
        assert_eq!(e.field, "outline");
        let e = bad(
            "name='x'\noutline=[[0,0],[300,0],[300,300],[0,300]]\nhome={x=10,y=150,heading_deg=0}",
        );
        assert_eq!(e.field, "home");
        assert!(e.reason.contains("body radius"), "{e}");
        let e = bad(
            "name='x'\noutline=[[0,0],[300,0],[300,300],[0,300]]\nhome={x=500,y=150,heading_deg=0}",
        );
        assert_eq!(e.field, "home");
        let e = bad(
            "name='x'\noutline=[[0,0],[300,0],[300,300],[0,300]]\nhome={x=150,y=150,heading_deg=0}\n[[obstacles]]\noutline=[[200,200],[400,200],[400,250]]",
        );
        assert_eq!(e.field, "obstacles[0].outline");
        let e = bad(
            "name='x'\noutline=[[0,0],[300,0],[300,300],[0,300]]\nhome={x=150,y=150,heading_deg=0}\ncolour='red'",
        );
        assert_eq!(e.field, "colour");
        let e = bad(
            "name='x'\noutline=[[0,0],[300,0],[300,nan],[0,300]]\nhome={x=150,y=150,heading_deg=0}",
        );
        assert_eq!(e.field, "outline[2]");
        let e = bad(
            "name='x'\noutline=[[0,0],[300,0],[300,300],[0,300]]\nhome={x='a',y=150,heading_deg=0}",
        );
        assert!(e.field.starts_with("home"), "{e}");
    }
    /// A square room 800 × 400 with home on the left, for the mission tests.
    const MISSION_ROOM: &str =
        "name='m'\noutline=[[0,0],[800,0],[800,400],[0,400]]\nhome={x=100,y=200,heading_deg=0}\n";

    #[test]
    fn room_file_goal_and_waypoints_parse_in_both_toml_forms() {
        let text = format!(
            "{MISSION_ROOM}goal = {{ x = 700, y = 300, radius = 60 }}\n\
             [[waypoints]]\nx = 400\ny = 100\nradius = 50\n\
             [[waypoints]]\nx = 600\ny = 300\nradius = 40.5\n"
        );
        let r = Room::from_toml_str(&text, "m.toml").unwrap();
        let zone = |x, y, radius| Zone {
            centre: Vec2::new(x, y),
            radius,
        };
        assert_eq!(r.mission.goal, Some(zone(700.0, 300.0, 60.0)));
        assert_eq!(
            r.mission.waypoints,
            vec![zone(400.0, 100.0, 50.0), zone(600.0, 300.0, 40.5)]
        );
        let inline = format!(
            "{MISSION_ROOM}waypoints = [{{ x = 400, y = 100, radius = 50 }}, {{ x = 600, y = 300, radius = 40.5 }}]\n\
             goal = {{ x = 700, y = 300, radius = 60 }}\n"
        );
        assert_eq!(Room::from_toml_str(&inline, "m.toml").unwrap(), r);
        let none = Room::from_toml_str(MISSION_ROOM, "m.toml").unwrap();
        assert!(none.mission.is_empty());
    }

    fn bad_mission(extra: &str) -> FieldError {
        bad(&format!("{MISSION_ROOM}{extra}"))
    }

    #[test]
    fn a_goal_outside_the_outline_names_goal() {
        let e = bad_mission("goal={x=900,y=200,radius=50}");
        assert_eq!(
            (e.source_name.as_str(), e.field.as_str()),
            ("bad.toml", "goal")
        );
        assert!(e.reason.contains("outside the room outline"), "{e}");
    }

    #[test]
    fn a_waypoint_inside_an_obstacle_names_the_waypoint() {
        let e = bad_mission(
            "waypoints=[{x=200,y=100,radius=50},{x=450,y=200,radius=30}]\n\
             [[obstacles]]\noutline=[[400,150],[500,150],[500,250],[400,250]]",
        );
        assert_eq!(e.field, "waypoints[1]");
        assert!(e.reason.contains("inside obstacles[0]"), "{e}");
        let e = bad_mission(
            "goal={x=450,y=200,radius=30}\n[[obstacles]]\noutline=[[400,150],[500,150],[500,250],[400,250]]",
        );
        assert_eq!(e.field, "goal");
    }

    #[test]
    fn a_zone_radius_zero_negative_or_nan_names_its_radius() {
        for r in ["0", "-5", "nan", "inf", "1e5"] {
            let e = bad_mission(&format!("goal={{x=700,y=200,radius={r}}}"));
            assert_eq!(e.field, "goal.radius", "radius {r}: {e}");
            assert!(e.reason.contains("> 0"), "{e}");
            let e = bad_mission(&format!(
                "[[waypoints]]\nx=300\ny=200\nradius=40\n[[waypoints]]\nx=700\ny=200\nradius={r}"
            ));
            assert_eq!(e.field, "waypoints[1].radius", "radius {r}: {e}");
        }
    }

    #[test]
    fn a_zone_centre_not_finite_or_too_far_names_its_coordinate() {
        let e = bad_mission("goal={x=nan,y=200,radius=50}");
        assert_eq!(e.field, "goal.x");
        let e = bad_mission("waypoints=[{x=300,y=-inf,radius=50}]");
        assert_eq!(e.field, "waypoints[0].y");
        let e = bad_mission("goal={x=2e4,y=200,radius=50}");
        assert_eq!(e.field, "goal.x");
        assert!(e.reason.contains("10000"), "{e}");
    }

    #[test]
    fn an_unknown_or_missing_key_in_goal_names_the_key_under_goal() {
        let e = bad_mission("goal={x=700,y=200,radius=50,colour='red'}");
        assert_eq!(e.field, "goal.colour");
        assert!(e.reason.contains("colour"), "{e}");
        assert!(e.reason.contains("optional goal = { x, y, radius }"), "{e}");
        let e = bad_mission("goal={x=700,y=200}");
        assert!(e.to_string().contains("radius"), "{e}");
        let e = bad_mission("[[waypoints]]\nx=300\ny=200\nradius=40\nsize=3");
        assert_eq!(e.field, "waypoints[0].size");
    }

    /// A goal behind a wall with no gap the body fits through is refused when the file is read.
    #[test]
    fn a_goal_in_a_closed_off_pocket_is_unreachable() {
        let wall = "[[obstacles]]\noutline=[[400,5],[420,5],[420,395],[400,395]]\n";
        let e = bad_mission(&format!("goal={{x=700,y=200,radius=50}}\n{wall}"));
        assert_eq!(
            (e.source_name.as_str(), e.field.as_str()),
            ("bad.toml", "goal")
        );
        assert!(e.reason.contains("cannot be reached from home"), "{e}");
        let e = bad_mission(&format!(
            "waypoints=[{{x=200,y=200,radius=50}},{{x=600,y=100,radius=50}}]\n{wall}"
        ));
        assert_eq!(e.field, "waypoints[1]");
        // The same goal with the wall open in the middle is fine.
        let open = "[[obstacles]]\noutline=[[400,5],[420,5],[420,140],[400,140]]\n\
                    [[obstacles]]\noutline=[[400,260],[420,260],[420,395],[400,395]]\n";
        Room::from_toml_str(
            &format!("{MISSION_ROOM}goal={{x=700,y=200,radius=50}}\n{open}"),
            "ok.toml",
        )
        .unwrap();
    }

    /// Issue #52 item 6: a goal the robot drives through from home (heading 0°, along y = 40)
    /// or reaches along a wall or into a corner is accepted, decided at the robot's scale (the
    /// body radius), not by whether a 50 mm cell's centre lies in it.
    #[test]
    fn a_goal_the_robot_drives_through_is_reachable() {
        let room =
            "name='g'\noutline=[[0,0],[800,0],[800,800],[0,800]]\nhome={x=40,y=40,heading_deg=0}\n";
        for goal in [
            "x=100,y=40,radius=30",
            "x=300,y=40,radius=20",
            "x=750,y=400,radius=20",
            "x=780,y=780,radius=50",
        ] {
            let r = Room::from_toml_str(&format!("{room}goal={{{goal}}}\n"), "g.toml");
            assert!(r.is_ok(), "{goal}: {r:?}");
        }
    }

    /// A goal nearer the walls than the body radius everywhere, or cut off from home by a gap
    /// narrower than the body, is still refused, and the message says which.
    #[test]
    fn an_unreachable_goal_is_refused_saying_truly_why() {
        let room =
            "name='g'\noutline=[[0,0],[800,0],[800,800],[0,800]]\nhome={x=40,y=40,heading_deg=0}\n";
        let e = Room::from_toml_str(&format!("{room}goal={{x=790,y=790,radius=10}}\n"), "g.toml")
            .unwrap_err();
        assert_eq!(e.field, "goal");
        assert!(
            e.reason
                .contains("every point of it is nearer a wall than that"),
            "{e}"
        );
        assert!(e.reason.contains("body radius 27.5 mm"), "{e}");
        let dumbbell = "name='d'\noutline=[[0,0],[400,0],[400,180],[500,180],[500,0],[900,0],[900,400],[500,400],[500,220],[400,220],[400,400],[0,400]]\nhome={x=100,y=100,heading_deg=0}\ngoal={x=700,y=200,radius=50}\n";
        let e = Room::from_toml_str(dumbbell, "d.toml").unwrap_err();
        assert_eq!(e.field, "goal");
        assert!(e.reason.contains("cut off from home"), "{e}");
        assert!(!e.reason.contains("nearer a wall"), "{e}");
        // A gap wider than the body opens the way.
        let wide = dumbbell.replace("180],", "120],").replace("220],", "280],");
        assert!(Room::from_toml_str(&wide, "d.toml").is_ok());
    }

    /// A zone whose centre is too close to a wall for the body's centre can still be reached
    /// where it reaches into the floor the body can cover.
    #[test]
    fn a_zone_centred_in_a_corner_is_reachable_through_its_disc() {
        let r = Room::from_toml_str(
            &format!("{MISSION_ROOM}goal={{x=790,y=390,radius=100}}"),
            "corner.toml",
        )
        .unwrap();
        assert_eq!(r.mission.goal.unwrap().centre, Vec2::new(790.0, 390.0));
        let e = bad_mission("goal={x=795,y=395,radius=10}");
        assert_eq!(e.field, "goal");
    }

    /// A room without a mission serializes exactly as before missions existed (the goldens and
    /// saved runs hold such rooms).
    #[test]
    fn rooms_without_a_mission_serialize_as_before() {
        let old = concat!(
            r#"{"name":"rectangle","outline":[{"x":0.0,"y":0.0},{"x":800.0,"y":0.0},"#,
            r#"{"x":800.0,"y":400.0},{"x":0.0,"y":400.0}],"obstacles":[],"#,
            r#""home":{"x":40.0,"y":40.0,"heading":0.0},"#,
            r#""home_zone":{"centre":{"x":0.0,"y":0.0},"radius":160.0}}"#
        );
        let room = Room::builtin("rectangle").unwrap();
        assert_eq!(serde_json::to_string(&room).unwrap(), old);
        assert_eq!(serde_json::from_str::<Room>(old).unwrap(), room);
        let with = Room {
            mission: Mission {
                goal: Some(Zone {
                    centre: Vec2::new(700.0, 300.0),
                    radius: 60.0,
                }),
                waypoints: Vec::new(),
            },
            ..room
        };
        let json = serde_json::to_string(&with).unwrap();
        assert!(json.ends_with(r#""mission":{"goal":{"centre":{"x":700.0,"y":300.0},"radius":60.0},"waypoints":[]}}"#), "{json}");
        assert_eq!(serde_json::from_str::<Room>(&json).unwrap(), with);
    }

    #[test]
    fn the_shipped_mission_rooms_are_valid() {
        let fetch =
            Room::from_toml_str(include_str!("../../../../rooms/fetch-L.toml"), "fetch-L").unwrap();
        let goal = fetch.mission.goal.unwrap();
        let far = fetch.outline.iter().map(|p| p.dist(fetch.home.position()));
        assert!(goal.centre.dist(fetch.home.position()) > 0.85 * far.fold(0.0, f64::max));
        let patrol =
            Room::from_toml_str(include_str!("../../../../rooms/patrol.toml"), "patrol").unwrap();
        assert_eq!(
            (patrol.mission.goal, patrol.mission.waypoints.len()),
            (None, 3)
        );
    }
}
