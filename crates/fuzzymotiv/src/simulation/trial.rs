//! One trial: a robot with a controller runs `T` steps from home in a room.
//!
//! [`Arena`] precomputes everything per room that the hot loop needs (walls culled to a grid
//! of 50 mm cells, the reachable cells of the exploration grid); [`simulate`] is the
//! allocation-free step loop, reporting each step to a [`StepObserver`]; [`run_trial`] records a
//! whole [`Trajectory`]. The trial's parameters are in [`crate::simulation::trial_params`], the
//! memo of sightings and the registry of which arenas share it in `simulation/memo.rs`.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::params::{FieldError, Num};
use crate::random::noise::{perturb, perturb_sensors};
use crate::random::rng::Rng;
use crate::simulation::controller::Controller;
use crate::simulation::geom::{PreparedSegment, Segment, Vec2};
use crate::simulation::isa::Isa;
use crate::simulation::memo::{MemoClaim, Owner, SIGHT_SENSORS, Sight, SightKey, Table, memo_live};
use crate::simulation::robot::Action;
use crate::simulation::robot::{Compass, Motion, Pose, Robot, drive};
use crate::simulation::room::{Room, Zone};
use crate::simulation::sensing::{Eyes, Facing};
use crate::simulation::sensor::Readings;
use crate::simulation::sensor::{SensorModel, sensing_reach};
pub use crate::simulation::trial_params::{MAX_STEPS, RawTrial, TrialParams};

/// Side of a grid cell (mm): the exploration grid of docs/model.md §7 and the wall-culling grid.
pub const CELL: f64 = 50.0;

/// A room prepared for fast trials with the parameters it keeps ([`Arena::params`]): every
/// trial in it ([`simulate`], [`run_trial`]) runs with them, so the walls culled for its reach
/// are the walls its robot can touch.
#[derive(Debug, Clone)]
pub struct Arena {
    room: Room,
    params: TrialParams,
    walls: Vec<Segment>,
    /// The walls prepared for division-free culling tests (same order as `walls`).
    prepared: Vec<PreparedSegment>,
    grid: Grid,
    cell_start: Vec<u32>,
    cell_walls: Vec<u32>,
    /// Whether a cell's list of walls within reach is not empty: one load for the step loop's
    /// test of open floor ([`Arena::sight`]).
    walled: Vec<bool>,
    reachable: Vec<bool>,
    reachable_count: usize,
    d_max: f64,
    radius: f64,
    near_reach: f64,
    compass: Compass,
    eyes: Eyes,
    /// This arena's number in the [`crate::simulation::memo`] of each thread, shared with its clones and
    /// with every arena of the same [`SightKey`] ([`MemoClaim::of`]), or `None` when its poses
    /// are not remembered.
    memo: Option<Arc<MemoClaim>>,
}

/// A sight key is made from an arena's grid and walls, which only this module sees.
impl SightKey {
    /// The key of `arena`.
    fn of(arena: &Arena) -> SightKey {
        let g = &arena.grid;
        SightKey {
            walls: (arena.walls.iter())
                .map(|w| [w.a.x, w.a.y, w.b.x, w.b.y].map(f64::to_bits))
                .collect(),
            grid: [
                g.origin.x.to_bits(),
                g.origin.y.to_bits(),
                g.cols as u64,
                g.rows as u64,
            ],
            heading: arena.room.home.heading.to_bits(),
            sensor_model: arena.params.sensor_model,
            radius: arena.radius.to_bits(),
            near_reach: arena.near_reach.to_bits(),
        }
    }
}

impl Arena {
    /// Prepares `room` for trials with `params`, which the arena keeps: the sensor model, the
    /// body and the longest step decide the culling reach.
    pub fn new(room: Room, params: &TrialParams) -> Arena {
        let walls = room.walls();
        let (lo, hi) = room.bounds();
        let grid = Grid::new(lo, hi);
        let radius = params.robot.radius();
        let spec = params.robot.spec();
        let near_reach = sensing_reach(params.sensor_model, spec).max(radius + params.max_step());
        // A wall can matter to a robot in a cell if it is within reach of some point of the cell.
        let (cell_start, cell_walls) = grid.cull(
            &walls,
            near_reach + CELL * std::f64::consts::SQRT_2 / 2.0 + 1e-6,
        );
        let valid: Vec<bool> = (0..grid.cells())
            .map(|k| {
                let c = grid.centre(k);
                room.contains(c) && walls.iter().all(|w| w.dist2_to(c) >= radius * radius)
            })
            .collect();
        let walled = cell_start.windows(2).map(|w| w[0] != w[1]).collect();
        let list = |k: usize| &cell_walls[cell_start[k] as usize..cell_start[k + 1] as usize];
        let reachable = grid.reachable(&valid, room.home.position(), radius, &walls, list);
        let compass = Compass::new(room.home.heading);
        let arena = Arena {
            prepared: walls.iter().map(PreparedSegment::new).collect(),
            walls,
            grid,
            reachable_count: reachable.iter().filter(|&&r| r).count(),
            reachable,
            cell_start,
            cell_walls,
            walled,
            d_max: room.max_home_distance(),
            room,
            params: *params,
            radius,
            near_reach: near_reach + 1e-6,
            compass,
            eyes: Eyes::new(params.sensor_model, spec, &compass),
            memo: None,
        };
        // Only whole-number sensor values in 0–1023 of at most eight sensors fit the memo
        // (docs/model.md §3).
        let fits = SensorModel::whole_valued(params.sensor_model)
            && spec.sensors() <= SIGHT_SENSORS
            && spec.reading_max() <= 1023.0;
        let memo = fits.then(|| MemoClaim::of(SightKey::of(&arena)));
        Arena { memo, ..arena }
    }

    /// The trial parameters the arena was prepared with, which every trial in it runs with.
    pub fn params(&self) -> &TrialParams {
        &self.params
    }

    /// Whether this arena's poses are remembered (the per-thread memo of sightings; `sampled` sensors only).
    pub fn remembers(&self) -> bool {
        self.memo.is_some()
    }

    /// The same arena, its poses never remembered: every step casts its rays (the results are
    /// the same; this is for tests and measurements).
    pub fn without_memo(mut self) -> Arena {
        self.memo = None;
        self
    }

    /// The room.
    pub fn room(&self) -> &Room {
        &self.room
    }

    /// All walls.
    pub fn walls(&self) -> &[Segment] {
        &self.walls
    }

    /// Number of cells of the exploration grid.
    pub fn cell_count(&self) -> usize {
        self.grid.cells()
    }

    /// Grid size `(columns, rows)`.
    pub fn grid(&self) -> (usize, usize) {
        (self.grid.cols, self.grid.rows)
    }

    /// The grid cell containing `p` (clamped to the grid).
    #[inline]
    pub fn cell_of(&self, p: Vec2) -> usize {
        let g = &self.grid;
        let i = grid_index((p.x - g.origin.x) / CELL, g.last[0]);
        let j = grid_index((p.y - g.origin.y) / CELL, g.last[1]);
        j * g.cols + i
    }

    /// Cells whose centre the robot's centre can occupy, connected to home (docs/model.md §7).
    pub fn reachable_cells(&self) -> usize {
        self.reachable_count
    }

    /// Whether cell `k` is reachable.
    pub fn is_reachable(&self, k: usize) -> bool {
        self.reachable[k]
    }

    /// `d_max` of the homing term: farthest outline vertex from home (mm).
    pub fn d_max(&self) -> f64 {
        self.d_max
    }

    /// The first zone of the room's mission (the goal, then the waypoints in order) that the
    /// robot cannot reach from home, as an error in its room-file field (`goal`,
    /// `waypoints[2]`, …), or `None` when every zone can be reached. A zone can be reached when
    /// the robot's centre can enter it: some point of it where the body fits (inside the room,
    /// at least the body radius from every wall) is connected to home, i.e. is the centre of a
    /// cell the flood fill from home reaches, or slides in a straight line to home or to such a
    /// cell around it (docs/model.md §4, §7).
    pub fn unreachable_mission_zone(&self) -> Option<FieldError> {
        let (field, zone) = self
            .room
            .mission
            .zones()
            .find(|(_, z)| !self.zone_reached(z))?;
        let r = self.radius;
        let why = if self.zone_has_room(&zone) {
            "the points of it that far from every wall are cut off from home by walls or \
             obstacles (no passage the body fits through leads there)"
        } else {
            "every point of it is nearer a wall than that"
        };
        Some(FieldError::new(
            field,
            format!(
                "the zone centred at ({}, {}) with radius {} cannot be reached from home by a robot of body radius {r} mm, whose centre stays at least {r} mm from every wall: {why}; move it, or make it larger, into the part of the room connected to home",
                Num(zone.centre.x),
                Num(zone.centre.y),
                Num(zone.radius),
            ),
        ))
    }

    /// Whether the robot's centre can enter `zone` ([`Arena::unreachable_mission_zone`]): a
    /// reachable cell's centre inside it, or a point of it sampled every
    /// [`Arena::zone_step`] around the reachable cells that joins home.
    fn zone_reached(&self, zone: &Zone) -> bool {
        if (0..self.cell_count()).any(|k| self.reachable[k] && zone.contains(self.grid.centre(k))) {
            return true;
        }
        let home = self.room.home.position();
        let step = self.zone_step(zone);
        self.cells_meeting(zone)
            .filter(|&k| {
                self.grid.around(k).any(|n| self.reachable[n])
                    || self.grid.centre(k).dist(home) <= 3.0 * CELL
            })
            .any(|k| {
                let (lo, hi) = self.grid.bounds(k);
                lattice(zone, step, lo, hi).any(|p| self.fits(p) && self.joins_home(p))
            })
    }

    /// Whether some point of `zone` (sampled on at most about 512 × 512 points) is one where
    /// the body fits, connected to home or not.
    fn zone_has_room(&self, zone: &Zone) -> bool {
        let step = self.zone_step(zone).max(zone.radius / 256.0);
        let reach = Vec2::new(zone.radius, zone.radius);
        lattice(zone, step, zone.centre - reach, zone.centre + reach).any(|p| self.fits(p))
    }

    /// The spacing of the points of `zone` tried: a tenth of the zone's or the body's radius,
    /// whichever is smaller, within [0.25, 5] mm.
    fn zone_step(&self, zone: &Zone) -> f64 {
        (zone.radius.min(self.radius) / 10.0).clamp(0.25, 5.0)
    }

    /// The cells of the grid whose square meets `zone`'s bounding box.
    fn cells_meeting(&self, zone: &Zone) -> impl Iterator<Item = usize> + '_ {
        let g = &self.grid;
        let index = |v: f64, o: f64, last: f64| grid_index((v - o) / CELL, last);
        let (c, r) = (zone.centre, zone.radius);
        let (i0, i1) = (
            index(c.x - r, g.origin.x, g.last[0]),
            index(c.x + r, g.origin.x, g.last[0]),
        );
        let (j0, j1) = (
            index(c.y - r, g.origin.y, g.last[1]),
            index(c.y + r, g.origin.y, g.last[1]),
        );
        (j0..=j1).flat_map(move |j| (i0..=i1).map(move |i| j * g.cols + i))
    }

    /// Whether the body fits at `p`: inside the room and at least its radius from every wall.
    fn fits(&self, p: Vec2) -> bool {
        let r2 = self.radius * self.radius;
        self.room.contains(p) && self.walls.iter().all(|w| w.dist2_to(p) >= r2)
    }

    /// Whether the body at `p` slides in a straight line to home (within two cells) or to the
    /// centre of a reachable cell of the 3 × 3 around `p`'s.
    fn joins_home(&self, p: Vec2) -> bool {
        let slides = |to: Vec2| clear(Segment::new(p, to), self.walls.iter(), self.radius);
        let home = self.room.home.position();
        (p.dist(home) <= 2.0 * CELL && slides(home))
            || (self.grid.around(self.cell_of(p)))
                .any(|k| self.reachable[k] && slides(self.grid.centre(k)))
    }

    /// Indices of the walls that can matter to a robot whose centre is in `cell`.
    #[inline]
    fn cell_list(&self, cell: usize) -> &[u32] {
        &self.cell_walls[self.cell_start[cell] as usize..self.cell_start[cell + 1] as usize]
    }

    /// Whether a body of the arena's radius centred at `p` overlaps a wall.
    #[inline]
    pub fn overlaps(&self, p: Vec2) -> bool {
        self.overlaps_near(p, &self.near_walls(p))
    }

    /// The robot's number of sensors.
    #[inline]
    pub fn sensors(&self) -> usize {
        self.eyes.count()
    }

    /// Noise-free sensor values (0 to the robot's `reading_max`) at `pose`.
    pub fn read_sensors(&self, pose: &Pose) -> Readings {
        let near = self.near_walls(pose.position());
        self.read_sensors_near(pose, &near)
    }

    /// The walls that can be seen by a sensor or touched within one step from a robot centred
    /// at `p`: those of `p`'s cell closer than the sensing (or one-step collision) reach. Usually none in open floor,
    /// which skips ray casting altogether.
    #[inline]
    pub(crate) fn near_walls(&self, p: Vec2) -> NearWalls {
        self.near_walls_in(p, self.cell_of(p))
    }

    /// As [`Arena::near_walls`], with `p`'s grid cell already known.
    #[inline]
    pub(crate) fn near_walls_in(&self, p: Vec2, cell: usize) -> NearWalls {
        let mut near = NearWalls {
            len: 0,
            overflow: false,
            cell: 0,
            walls: [0; NEAR_CAP],
        };
        let r2 = self.near_reach * self.near_reach;
        // A culling test: `near_reach` keeps a 1e-6 mm margin over every distance that can
        // matter, far above the rounding of the division-free test (see `PreparedSegment`).
        let list = self.cell_list(cell);
        if list.len() <= NEAR_CAP {
            // Every wall fits: each is written and counted only if near, without a branch
            // (whether a wall is near is unpredictable).
            for &k in list {
                near.walls[near.len] = k;
                near.len += usize::from(self.prepared[k as usize].dist2_to(p) <= r2);
            }
            near.cell = cell;
            return near;
        }
        for &k in list {
            if self.prepared[k as usize].dist2_to(p) <= r2 {
                if near.len == NEAR_CAP {
                    near.overflow = true;
                    break;
                }
                near.walls[near.len] = k;
                near.len += 1;
            }
        }
        if near.overflow {
            // More walls than fit: fall back to every wall of the cell (same results, slower).
            near.len = 0;
        }
        near.cell = cell;
        near
    }

    /// The indices of the `near` walls (the whole cell's list when they did not fit).
    #[inline]
    fn near_list<'a>(&'a self, near: &'a NearWalls) -> &'a [u32] {
        if near.overflow {
            self.cell_list(near.cell)
        } else {
            &near.walls[..near.len]
        }
    }

    /// Sensor values at `pose` given its [`Arena::near_walls`].
    #[inline]
    pub(crate) fn read_sensors_near(&self, pose: &Pose, near: &NearWalls) -> Readings {
        if near.is_empty() {
            return Readings::zeros(self.sensors());
        }
        let (sin, cos) = crate::simulation::math::sin_cos(pose.heading);
        let facing = Facing::Angle { sin, cos };
        self.eyes.read(
            pose.position(),
            facing,
            &self.prepared,
            self.near_list(near),
        )
    }

    /// Sensor values of a robot centred at `pos` facing compass direction `dir` (`actions`
    /// motion: the rays were turned once, in [`Arena::new`]).
    #[inline]
    pub(crate) fn read_sensors_on_compass(
        &self,
        pos: Vec2,
        dir: usize,
        near: &NearWalls,
    ) -> Readings {
        if near.is_empty() {
            return Readings::zeros(self.sensors());
        }
        let facing = Facing::Compass(self.eyes.on_compass(dir));
        self.eyes
            .read(pos, facing, &self.prepared, self.near_list(near))
    }

    /// The memo owner of this arena's poses for its straight moves ([`TrialParams::straight_step`]),
    /// or `None` when its poses are not remembered.
    pub(crate) fn memo_owner(&self) -> Option<Owner> {
        self.memo.as_ref().map(|claim| Owner {
            arena: claim.number,
            step: self.params.straight_step().to_bits(),
        })
    }

    /// What a robot centred at `pos` facing compass direction `dir` (`actions` motion), in grid
    /// cell `cell`, sees, and whether a straight move of `step` mm would overlap a wall;
    /// remembered in `memo` (this arena's table, from [`Arena::memo_owner`]) when the
    /// cell has walls near it, computed every time without one.
    #[inline(always)]
    pub(crate) fn sight(
        &self,
        memo: Option<&mut Table>,
        pos: Vec2,
        dir: usize,
        cell: usize,
        step: f64,
    ) -> Sight {
        if !self.walled[cell] {
            return Sight::CLEAR;
        }
        match memo {
            Some(table) => {
                debug_assert_eq!(Some(table.owner()), self.memo_owner(), "another's table");
                // The next step starts where one of the four actions takes the robot.
                let next = [
                    Action::Straight,
                    Action::Left30,
                    Action::Right30,
                    Action::Turn180,
                ]
                .map(|a| self.after(pos, dir, a, step));
                table.recall(pos, dir, &next, || self.look(pos, dir, cell, step))
            }
            None => self.look(pos, dir, cell, step),
        }
    }

    /// The position and compass direction that `action` (a straight move of `step` mm, or a
    /// turn) takes a robot centred at `pos` facing compass direction `dir` to, as
    /// [`Motion::execute`] computes them.
    #[inline]
    fn after(&self, pos: Vec2, dir: usize, action: Action, step: f64) -> (Vec2, usize) {
        let here = Pose {
            x: pos.x,
            y: pos.y,
            heading: self.compass.heading[dir],
        };
        let (pose, dir) = Motion::execute(here, dir, action, step, &self.compass);
        (pose.position(), dir)
    }

    /// [`Arena::sight`], computed: the sensors cast, the straight move tested (a robot of at
    /// most [`SIGHT_SENSORS`] sensors).
    fn look(&self, pos: Vec2, dir: usize, cell: usize, step: f64) -> Sight {
        let (sensors, blocked) = self.look_any(pos, dir, cell, step);
        Sight {
            sensors: sensors.first_eight(),
            blocked,
        }
    }

    /// What a robot centred at `pos` facing compass direction `dir` in `cell` reads, and
    /// whether a straight move of `step` mm would overlap a wall, for any number of sensors.
    fn look_any(&self, pos: Vec2, dir: usize, cell: usize, step: f64) -> (Readings, bool) {
        let near = self.near_walls_in(pos, cell);
        let (ahead, _) = self.after(pos, dir, Action::Straight, step);
        let sensors = self.read_sensors_on_compass(pos, dir, &near);
        (sensors, ahead != pos && self.overlaps_near(ahead, &near))
    }

    /// Whether a body centred at `p` overlaps one of the `near` walls (computed for a point
    /// at most one step away).
    #[inline]
    pub(crate) fn overlaps_near(&self, p: Vec2, near: &NearWalls) -> bool {
        let r2 = self.radius * self.radius;
        // Every wall tested, without an early exit (which wall overlaps is unpredictable).
        self.near_list(near).iter().fold(false, |any, &k| {
            any | (self.walls[k as usize].dist2_to(p) < r2)
        })
    }
}

/// `v` (a coordinate in cells from the grid's origin) truncated to a column or row index in
/// `0..=last`: below 0 (or NaN) is 0, above `last` is `last`. Clamped to ≥ 0 first, so
/// truncation equals floor. `max` then `min` rather than `f64::clamp`, whose check that its
/// bounds are in order and whose NaN case cost branches in the step loop; the same index for
/// every `v` (`clamp` keeps NaN, which `as` turns into 0).
#[inline(always)]
fn grid_index(v: f64, last: f64) -> usize {
    debug_assert!((0.0..=f64::from(u32::MAX)).contains(&last));
    let v = v.max(0.0).min(last);
    // SAFETY: `v` is a number (`max` returns 0 for NaN) in `[0, last]`, and `last` (a grid's
    // last index, below 400: the coordinates are within ±`MAX_COORD`) fits a `u32`, so the
    // truncation is in range.
    unsafe { v.to_int_unchecked::<u32>() as usize }
}

/// The 50 mm cells over a room's bounding box, row by row from `origin`.
#[derive(Debug, Clone)]
struct Grid {
    origin: Vec2,
    cols: usize,
    rows: usize,
    /// The last column's and the last row's index, as numbers (for [`Arena::cell_of`]).
    last: [f64; 2],
}

impl Grid {
    /// The cells covering the bounding box from `lo` to `hi`.
    fn new(lo: Vec2, hi: Vec2) -> Grid {
        let cols = (((hi.x - lo.x) / CELL).ceil() as usize).max(1);
        let rows = (((hi.y - lo.y) / CELL).ceil() as usize).max(1);
        let last = [(cols - 1) as f64, (rows - 1) as f64];
        Grid {
            origin: lo,
            cols,
            rows,
            last,
        }
    }

    fn cells(&self) -> usize {
        self.cols * self.rows
    }

    fn centre(&self, k: usize) -> Vec2 {
        Vec2::new(
            self.origin.x + ((k % self.cols) as f64 + 0.5) * CELL,
            self.origin.y + ((k / self.cols) as f64 + 0.5) * CELL,
        )
    }

    /// For each cell, the indices of the walls within `reach` of its centre, as one flat list
    /// (`walls[start[k]..start[k + 1]]` are cell `k`'s).
    fn cull(&self, walls: &[Segment], reach: f64) -> (Vec<u32>, Vec<u32>) {
        let mut start = Vec::with_capacity(self.cells() + 1);
        let mut list = Vec::new();
        for k in 0..self.cells() {
            start.push(list.len() as u32);
            let c = self.centre(k);
            list.extend((0..walls.len() as u32).filter(|&w| walls[w as usize].dist_to(c) <= reach));
        }
        start.push(list.len() as u32);
        (start, list)
    }

    /// Cell `k` and its 8 neighbours (those inside the grid).
    fn around(&self, k: usize) -> impl Iterator<Item = usize> + '_ {
        let (i, j) = ((k % self.cols) as i64, (k / self.cols) as i64);
        let (cols, rows) = (self.cols as i64, self.rows as i64);
        (-1..=1)
            .flat_map(move |dj| (-1..=1).map(move |di| (i + di, j + dj)))
            .filter(move |&(i, j)| (0..cols).contains(&i) && (0..rows).contains(&j))
            .map(move |(i, j)| (j * cols + i) as usize)
    }

    /// The corners (lowest, highest) of cell `k`'s square.
    fn bounds(&self, k: usize) -> (Vec2, Vec2) {
        let half = Vec2::new(CELL / 2.0, CELL / 2.0);
        let c = self.centre(k);
        (c - half, c + half)
    }

    /// Cell `k`'s 4-neighbours (`usize::MAX` where the grid ends).
    fn neighbours(&self, k: usize) -> [usize; 4] {
        let (i, j) = (k % self.cols, k / self.cols);
        [
            if i > 0 { k - 1 } else { usize::MAX },
            if i + 1 < self.cols { k + 1 } else { usize::MAX },
            if j > 0 { k - self.cols } else { usize::MAX },
            if j + 1 < self.rows {
                k + self.cols
            } else {
                usize::MAX
            },
        ]
    }

    /// The `valid` cells connected to home (docs/model.md §7): a flood fill (4-neighbours)
    /// stepping only where the body can slide from one centre to the next (the segment between
    /// them stays ≥ `radius` from every wall of `list(cell)`: a gap narrower than the body is
    /// not a passage). It starts from the valid cell nearest to home that the body can reach
    /// from home in a straight line.
    fn reachable<'a>(
        &self,
        valid: &[bool],
        home: Vec2,
        radius: f64,
        walls: &[Segment],
        list: impl Fn(usize) -> &'a [u32],
    ) -> Vec<bool> {
        let start = (0..self.cells())
            .filter(|&k| {
                let c = self.centre(k);
                valid[k]
                    && c.dist(home) <= 2.0 * CELL
                    && clear(Segment::new(home, c), walls.iter(), radius)
            })
            .min_by(|&a, &b| {
                let (da, db) = (self.centre(a).dist(home), self.centre(b).dist(home));
                da.total_cmp(&db).then(a.cmp(&b))
            });
        let mut reachable = vec![false; self.cells()];
        let Some(s) = start else {
            return reachable;
        };
        let mut stack = vec![s];
        reachable[s] = true;
        while let Some(k) = stack.pop() {
            for n in self.neighbours(k) {
                if n != usize::MAX && valid[n] && !reachable[n] {
                    let path = Segment::new(self.centre(k), self.centre(n));
                    if clear(path, list(k).iter().map(|&w| &walls[w as usize]), radius) {
                        reachable[n] = true;
                        stack.push(n);
                    }
                }
            }
        }
        reachable
    }
}

impl Room {
    /// Parses and validates a room file (docs/model.md §4): its geometry, and that its mission's
    /// zones are reachable from home by the Khepera (as home's clearance; a bigger body is
    /// checked by the experiment, [`check_missions_reachable`]). `source_name` (usually the
    /// path) is used in error messages.
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<Room, FieldError> {
        let room = Room::geometry_from_toml_str(text, source_name)?;
        if !room.mission.is_empty() {
            let arena = Arena::new(room.clone(), &TrialParams::default());
            if let Some(e) = arena.unreachable_mission_zone() {
                return Err(e.in_source(source_name));
            }
        }
        Ok(room)
    }
}

/// Each room's mission reachable from home by a robot of body `radius`
/// ([`Arena::unreachable_mission_zone`]; the other trial parameters their defaults): the first
/// room whose mission is not, as an error in `rooms[i]` naming the room and its field.
pub fn check_missions_reachable(rooms: &[Room], radius: f64) -> Result<(), FieldError> {
    let robot = Robot::default().with_radius(radius);
    let params = TrialParams {
        robot,
        ..TrialParams::default()
    };
    for (i, room) in rooms.iter().enumerate() {
        if room.mission.is_empty() {
            continue;
        }
        if let Some(e) = Arena::new(room.clone(), &params).unreachable_mission_zone() {
            return Err(FieldError::new(
                format!("rooms[{i}]"),
                format!(
                    "room \"{}\", field `{}` of its room file: {}",
                    room.name, e.field, e.reason
                ),
            ));
        }
    }
    Ok(())
}

/// The points of `zone` on the lattice of spacing `step` through its centre, within the box
/// from `lo` to `hi` (the centre first when it is in the box).
fn lattice(zone: &Zone, step: f64, lo: Vec2, hi: Vec2) -> impl Iterator<Item = Vec2> + '_ {
    let c = zone.centre;
    let range = |lo: f64, hi: f64, c: f64| {
        let (a, b) = (((lo - c) / step).ceil(), ((hi - c) / step).floor());
        // Within ±MAX_COORD / 0.25 mm: the counts fit an i64.
        (a as i64)..=(b as i64)
    };
    let (xs, ys) = (range(lo.x, hi.x, c.x), range(lo.y, hi.y, c.y));
    let centre = (xs.contains(&0) && ys.contains(&0)).then_some(c);
    let grid = ys.flat_map(move |j| {
        let xs = xs.clone();
        xs.map(move |i| Vec2::new(c.x + i as f64 * step, c.y + j as f64 * step))
    });
    centre
        .into_iter()
        .chain(grid)
        .filter(move |&p| zone.contains(p))
}

/// Whether a body of `radius` can slide along `path` without touching one of `walls`.
fn clear<'w>(path: Segment, mut walls: impl Iterator<Item = &'w Segment>, radius: f64) -> bool {
    walls.all(|w| w.dist_to_segment(&path) >= radius)
}

/// Capacity of [`NearWalls`]; a cell with more nearby walls falls back to its full list.
pub const NEAR_CAP: usize = 24;

/// The walls near a robot, found once per step and shared by sensing and collision.
#[derive(Debug, Clone, Copy)]
pub struct NearWalls {
    len: usize,
    overflow: bool,
    cell: usize,
    walls: [u32; NEAR_CAP],
}

impl NearWalls {
    /// Whether no wall is near.
    pub fn is_empty(&self) -> bool {
        self.len == 0 && !self.overflow
    }
}

/// What happened in one step, as reported to a [`StepObserver`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// Step index, 0-based.
    pub t: usize,
    /// Sensor values (0 to the robot's `reading_max`, noise included) read at the start of
    /// the step (0 when idle), one per sensor.
    pub sensors: Readings,
    /// Motor outputs `mL, mR` ∈ [0, 1] (0.5, 0.5 when idle: the network is not run).
    pub motors: [f64; 2],
    /// Commanded wheel speeds `sL, sR` (mm/s, before noise; 0 when idle).
    pub speeds: [f64; 2],
    /// Pose at the end of the step.
    pub pose: Pose,
    /// Whether the candidate move hit a wall (the robot kept its position).
    pub collided: bool,
    /// The grid cell of `pose`, when the simulator knows it (saves observers a lookup).
    pub cell: Option<usize>,
    /// The step's action: executed with `actions` motion, recorded with `wheels` motion;
    /// `Straight` when idle.
    pub action: Action,
    /// Whether the step is idle: the trial already ended at home (nothing is read, run or
    /// moved, no energy is used).
    pub idle: bool,
    /// Energy used by the step (see [`Motion::energy`]); 0 when idle.
    pub energy: f64,
    /// Whether the robot's centre has been outside the home zone by the end of this step.
    pub escaped: bool,
}

impl Step {
    /// An idle step `t` at `pose` (after the trial ended at home) of a robot with `sensors`
    /// sensors.
    pub fn idle(t: usize, sensors: usize, pose: Pose, cell: Option<usize>, escaped: bool) -> Step {
        Step {
            t,
            sensors: Readings::zeros(sensors),
            motors: [0.5; 2],
            speeds: [0.0; 2],
            pose,
            collided: false,
            cell,
            action: Action::Straight,
            idle: true,
            energy: 0.0,
            escaped,
        }
    }
}

/// Receives every step of a trial.
pub trait StepObserver {
    /// Called once per step, in order.
    fn observe(&mut self, step: &Step);

    /// Whether the trial should end now (e.g. its mission is done); the rest of its steps are
    /// then reported as idle. Default: never.
    #[inline]
    fn finished(&self) -> bool {
        false
    }

    /// Whether `observe` reads a step's `motors` or `speeds`. Default: yes. When no observer of
    /// a batch of evaluation trials does (the fitness terms, the action log), the lock-step
    /// lanes of the evaluation may choose a step's action from rough network outputs whenever
    /// the exact ones could not choose another, and report the rough outputs in `motors` and
    /// `speeds`; every other field of the step is exact.
    #[inline]
    fn reads_motors(&self) -> bool {
        true
    }
}

impl<O: StepObserver + ?Sized> StepObserver for &mut O {
    #[inline]
    fn observe(&mut self, step: &Step) {
        (**self).observe(step);
    }

    #[inline]
    fn finished(&self) -> bool {
        (**self).finished()
    }

    #[inline]
    fn reads_motors(&self) -> bool {
        (**self).reads_motors()
    }
}

impl StepObserver for () {
    fn observe(&mut self, _: &Step) {}

    #[inline]
    fn reads_motors(&self) -> bool {
        false
    }
}

impl<A: StepObserver, B: StepObserver> StepObserver for (A, B) {
    fn observe(&mut self, step: &Step) {
        self.0.observe(step);
        self.1.observe(step);
    }

    #[inline]
    fn finished(&self) -> bool {
        self.0.finished() || self.1.finished()
    }

    #[inline]
    fn reads_motors(&self) -> bool {
        self.0.reads_motors() || self.1.reads_motors()
    }
}

/// Runs one trial from the room's home pose with the arena's parameters ([`Arena::params`]),
/// reporting each of the `T` steps to `observer`. Returns the final pose. Per step: read
/// sensors, add sensor noise, run the network, add wheel noise, label the step and move by the
/// motion model ([`Motion`]), and undo the move (keeping the heading change) if the body would
/// overlap a wall. With `end_at_home`, the trial ends after the first step that brings an
/// escaped robot back into the home zone; the rest of the `T` steps are reported as idle.
pub fn simulate<C, R, O>(arena: &Arena, controller: &mut C, rng: &mut R, observer: &mut O) -> Pose
where
    C: Controller + ?Sized,
    R: Rng + ?Sized,
    O: StepObserver + ?Sized,
{
    let owner = match arena.params.robot.motion() {
        Motion::Actions => arena.memo_owner(),
        Motion::Wheels => None,
    };
    let isa = Isa::detected();
    match owner {
        Some(owner) => crate::simulation::memo::with_table(owner, memo_live, |table| {
            walk_trial_on(isa, arena, controller, rng, observer, table)
        }),
        None => walk_trial_on(isa, arena, controller, rng, observer, None),
    }
}

/// [`walk_trial`] compiled for `isa`, which the processor must have ([`Isa::detected`]).
#[inline]
pub(crate) fn walk_trial_on<C, R, O>(
    isa: Isa,
    arena: &Arena,
    controller: &mut C,
    rng: &mut R,
    observer: &mut O,
    memo: Option<&mut Table>,
) -> Pose
where
    C: Controller + ?Sized,
    R: Rng + ?Sized,
    O: StepObserver + ?Sized,
{
    match isa {
        Isa::Baseline => walk_trial(arena, controller, rng, observer, memo),
        #[cfg(target_arch = "x86_64")]
        // SAFETY: `Isa::Avx2` is only made when the processor has AVX2 (`Isa::detected`).
        Isa::Avx2 => unsafe { walk_trial_avx2(arena, controller, rng, observer, memo) },
    }
}

/// [`walk_trial`] with AVX2 instructions: the step loop, sensing and the network are inlined
/// here and compiled for AVX2.
///
/// # Safety
/// The processor must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn walk_trial_avx2<C, R, O>(
    arena: &Arena,
    controller: &mut C,
    rng: &mut R,
    observer: &mut O,
    memo: Option<&mut Table>,
) -> Pose
where
    C: Controller + ?Sized,
    R: Rng + ?Sized,
    O: StepObserver + ?Sized,
{
    walk_trial(arena, controller, rng, observer, memo)
}

/// [`simulate`], with the arena's [`crate::simulation::memo`] table for the trial's poses, or none.
#[inline(always)]
fn walk_trial<C, R, O>(
    arena: &Arena,
    controller: &mut C,
    rng: &mut R,
    observer: &mut O,
    mut memo: Option<&mut Table>,
) -> Pose
where
    C: Controller + ?Sized,
    R: Rng + ?Sized,
    O: StepObserver + ?Sized,
{
    let params = &arena.params;
    let mut walk = Walk::at_home(arena);
    let mut t = 0;
    while t < params.steps {
        let (step, home) = walk.step(t, arena, controller, rng, memo.as_deref_mut());
        observer.observe(&step);
        t += 1;
        if (params.end_at_home && home) || observer.finished() {
            break;
        }
    }
    for t in t..params.steps {
        observer.observe(&walk.idle(t, arena.sensors()));
    }
    walk.pose
}

/// Where a robot is during a trial (shared by [`simulate`] and the public stepper
/// [`crate::simulation::stepper::TrialRun`]: both take exactly these steps).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Walk {
    pose: Pose,
    /// The grid cell of `pose`.
    cell: usize,
    /// The compass direction of `pose` (`actions` motion).
    dir: usize,
    /// Whether the robot has been outside the home zone.
    escaped: bool,
}

/// What the first half of a step ([`Walk::sense`]) read: the sensor values (noise included)
/// and what the move will be tested against.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sensed {
    pub(crate) sensors: Readings,
    walls: Walls,
}

impl Sensed {
    /// What an `actions` step of an eight-sensor robot (the lanes') read: `sensors` (noise
    /// included) and whether a straight move is `blocked`.
    #[inline(always)]
    pub(crate) fn straight(sensors: [f64; SIGHT_SENSORS], blocked: bool) -> Sensed {
        Sensed {
            sensors: Readings::from_eight(sensors, SIGHT_SENSORS),
            walls: Walls::Straight(blocked),
        }
    }
}

impl Walk {
    /// At the room's home pose, not yet escaped.
    #[inline]
    pub(crate) fn at_home(arena: &Arena) -> Walk {
        Walk {
            pose: arena.room.home,
            cell: arena.cell_of(arena.room.home.position()),
            dir: 0,
            escaped: false,
        }
    }

    /// The pose now.
    #[inline]
    pub(crate) fn pose(&self) -> Pose {
        self.pose
    }

    /// The compass direction now (`actions` motion): with the position, a memo's key.
    #[cfg(test)]
    pub(crate) fn dir(&self) -> usize {
        self.dir
    }

    /// The idle step `t` at the pose now (after the trial ended at home).
    #[inline]
    pub(crate) fn idle(&self, t: usize, sensors: usize) -> Step {
        Step::idle(t, sensors, self.pose, Some(self.cell), self.escaped)
    }

    /// Step `t`: [`Walk::sense`], run the network on the sensors / `reading_max`, then
    /// [`Walk::act`].
    /// Returns the step's record and whether the robot, having escaped, is back in the home
    /// zone.
    #[inline(always)]
    fn step<C, R>(
        &mut self,
        t: usize,
        arena: &Arena,
        controller: &mut C,
        rng: &mut R,
        memo: Option<&mut Table>,
    ) -> (Step, bool)
    where
        C: Controller + ?Sized,
        R: Rng + ?Sized,
    {
        let sensed = self.sense(arena, rng, memo);
        let max = arena.params.robot.spec().reading_max();
        let motors = controller.step(&inputs_of(&sensed.sensors, max));
        self.act(t, arena, &sensed, motors, None, rng)
    }

    /// The first half of a step: read the sensors and add their noise. `memo` is the trial's
    /// table of remembered sights, if any (`actions` motion; a pure cache).
    #[inline(always)]
    pub(crate) fn sense<R>(&self, arena: &Arena, rng: &mut R, memo: Option<&mut Table>) -> Sensed
    where
        R: Rng + ?Sized,
    {
        let mut sensed = self.read(arena, memo);
        let max = arena.params.robot.spec().reading_max();
        perturb_sensors(&mut sensed.sensors, arena.params.noise, max, rng);
        sensed
    }

    /// The cell a straight move from the pose now would end in (`actions` motion): known
    /// before the step's action, so the lanes take it early and a move need not wait for it.
    #[inline(always)]
    pub(crate) fn ahead_cell(&self, arena: &Arena) -> usize {
        let step = arena.params.straight_step();
        let (p, _) = arena.after(self.pose.position(), self.dir, Action::Straight, step);
        arena.cell_of(p)
    }

    /// What the robot sees from its pose and whether a straight move is blocked (`actions`
    /// motion; [`Arena::sight`]).
    #[inline(always)]
    pub(crate) fn sight(&self, arena: &Arena, memo: Option<&mut Table>) -> Sight {
        let step = arena.params.straight_step();
        arena.sight(memo, self.pose.position(), self.dir, self.cell, step)
    }

    /// [`Walk::sense`] before the noise: the sensor values the pose gives and what the move
    /// will be tested against.
    #[inline(always)]
    pub(crate) fn read(&self, arena: &Arena, memo: Option<&mut Table>) -> Sensed {
        let params = &arena.params;
        let pos = self.pose.position();
        let (sensors, walls) = match params.robot.motion() {
            Motion::Actions if arena.sensors() <= SIGHT_SENSORS => {
                let sight = self.sight(arena, memo);
                let sensors = Readings::from_eight(sight.sensors, arena.sensors());
                (sensors, Walls::Straight(sight.blocked))
            }
            Motion::Actions => {
                let step = params.straight_step();
                let (sensors, blocked) = arena.look_any(pos, self.dir, self.cell, step);
                (sensors, Walls::Straight(blocked))
            }
            Motion::Wheels => {
                let near = arena.near_walls_in(pos, self.cell);
                (
                    arena.read_sensors_near(&self.pose, &near),
                    Walls::Near(near),
                )
            }
        };
        Sensed { sensors, walls }
    }

    /// The second half of step `t`, given the motor outputs `motors`: add wheel noise, label
    /// the step (or take `forced`, an action chosen from outside, with `actions` motion) and
    /// move by the motion model, undoing the move (keeping the heading change) if the body
    /// would overlap a wall. Returns the step's record and whether the robot, having escaped,
    /// is back in the home zone.
    #[inline(always)]
    pub(crate) fn act<R>(
        &mut self,
        t: usize,
        arena: &Arena,
        sensed: &Sensed,
        motors: [f64; 2],
        forced: Option<Action>,
        rng: &mut R,
    ) -> (Step, bool)
    where
        R: Rng + ?Sized,
    {
        let v_max = arena.params.robot.v_max();
        let speeds = motors.map(|m| (2.0 * m - 1.0) * v_max);
        let noisy = [
            perturb(speeds[0], arena.params.noise, rng),
            perturb(speeds[1], arena.params.noise, rng),
        ];
        self.act_noisy(t, arena, sensed, motors, noisy, (forced, None))
    }

    /// [`Walk::act`] once the wheel noise is drawn: `noisy` are the commanded speeds of
    /// `motors` with their noise; `forced`, an action chosen from outside (`actions` motion);
    /// `ahead`, the cell a straight move from here ends in ([`Walk::ahead_cell`]), when the
    /// caller has it (`actions` motion).
    #[inline(always)]
    pub(crate) fn act_noisy(
        &mut self,
        t: usize,
        arena: &Arena,
        sensed: &Sensed,
        motors: [f64; 2],
        noisy: [f64; 2],
        (forced, ahead): (Option<Action>, Option<usize>),
    ) -> (Step, bool) {
        let params = &arena.params;
        let (motion, v_max) = (params.robot.motion(), params.robot.v_max());
        let speeds = motors.map(|m| (2.0 * m - 1.0) * v_max);
        let labelled = || motion.label(motors, noisy, v_max, params.action_tolerance);
        let action = match (forced, motion) {
            (Some(a), Motion::Actions) => a,
            _ => labelled(),
        };
        let collided = self.execute(action, noisy, arena, &sensed.walls, ahead);
        let inside = arena.room.home_zone.contains(self.pose.position());
        self.escaped |= !inside;
        let step = Step {
            t,
            sensors: sensed.sensors,
            motors,
            speeds,
            pose: self.pose,
            cell: Some(self.cell),
            collided,
            action,
            idle: false,
            energy: motion.energy(speeds, v_max),
            escaped: self.escaped,
        };
        (step, self.escaped && inside)
    }

    /// Moves by `action` (`actions` motion) or the `noisy` wheel speeds (`wheels`); a move
    /// into one of the `walls` is undone, its heading change kept. Returns whether it collided.
    /// `ahead`: the cell of the straight move's end, if known ([`Walk::act_noisy`]).
    #[inline(always)]
    fn execute(
        &mut self,
        action: Action,
        noisy: [f64; 2],
        arena: &Arena,
        walls: &Walls,
        ahead: Option<usize>,
    ) -> bool {
        let params = &arena.params;
        let pose = self.pose;
        let (candidate, next_dir) = match params.robot.motion() {
            Motion::Actions => Motion::execute(
                pose,
                self.dir,
                action,
                params.straight_step(),
                &arena.compass,
            ),
            Motion::Wheels => {
                let (wheel_base, dt) = (params.robot.wheel_base(), params.dt);
                (drive(pose, noisy[0], noisy[1], wheel_base, dt), self.dir)
            }
        };
        self.dir = next_dir;
        // A turn on the spot cannot collide: the position is the previous, wall-free one.
        let moved = candidate.x != pose.x || candidate.y != pose.y;
        let collided = moved
            && match walls {
                // `actions` motion moves only straight on, so the candidate is the move tested.
                Walls::Straight(blocked) => *blocked,
                Walls::Near(near) => arena.overlaps_near(candidate.position(), near),
            };
        if collided {
            // Position (and so cell) unchanged; the heading change is kept.
            self.pose.heading = candidate.heading;
        } else {
            self.pose = candidate;
            if moved {
                // `actions` motion moves only straight on, so its end is `ahead`'s cell.
                self.cell = ahead.unwrap_or_else(|| arena.cell_of(self.pose.position()));
            }
        }
        collided
    }
}

/// The network's inputs: the sensor values / `max` (the robot's `reading_max`; the Khepera's
/// 1023, [`crate::simulation::SENSOR_MAX`]).
#[inline(always)]
pub(crate) fn inputs_of(sensors: &Readings, max: f64) -> Readings {
    // Most readings are 0 in open floor; 0 / max is exactly 0, so skip the division.
    sensors.map(|v| if v == 0.0 { 0.0 } else { v / max })
}

/// What a step knows of the walls in its way.
#[derive(Debug, Clone, Copy)]
enum Walls {
    /// `actions` motion: whether a straight move is blocked ([`Arena::sight`]).
    Straight(bool),
    /// `wheels` motion: the walls near the robot, to test the move against.
    Near(NearWalls),
}

/// Everything recorded in a trial, one entry per step (idle steps included).
/// `poses[0]` is home; `poses[t + 1]` the pose after step `t`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Trajectory {
    /// Poses, `steps + 1` of them.
    pub poses: Vec<Pose>,
    /// Sensor values per step (noise included), one per sensor.
    pub sensors: Vec<Readings>,
    /// Motor outputs per step.
    pub motors: Vec<[f64; 2]>,
    /// Commanded wheel speeds per step (mm/s).
    pub speeds: Vec<[f64; 2]>,
    /// Whether each step collided.
    pub collisions: Vec<bool>,
    /// The action of each step.
    pub actions: Vec<Action>,
    /// Whether each step was idle (after the trial ended at home).
    pub idle: Vec<bool>,
    /// Energy used by each step.
    pub energy: Vec<f64>,
    /// Whether the robot had escaped the home zone by the end of each step.
    pub escaped: Vec<bool>,
}

impl Trajectory {
    /// An empty trajectory at `home`, with room for `steps` steps.
    pub fn starting_at(home: Pose, steps: usize) -> Trajectory {
        let mut poses = Vec::with_capacity(steps + 1);
        poses.push(home);
        Trajectory {
            poses,
            sensors: Vec::with_capacity(steps),
            motors: Vec::with_capacity(steps),
            speeds: Vec::with_capacity(steps),
            collisions: Vec::with_capacity(steps),
            actions: Vec::with_capacity(steps),
            idle: Vec::with_capacity(steps),
            energy: Vec::with_capacity(steps),
            escaped: Vec::with_capacity(steps),
        }
    }

    /// Number of steps.
    pub fn len(&self) -> usize {
        self.motors.len()
    }

    /// Whether no step was recorded.
    pub fn is_empty(&self) -> bool {
        self.motors.is_empty()
    }

    /// Steps executed before the trial ended (the rest are idle).
    pub fn executed(&self) -> usize {
        self.idle.iter().filter(|&&i| !i).count()
    }

    /// The step records, in order (for replaying into observers).
    pub fn steps(&self) -> impl Iterator<Item = Step> + '_ {
        (0..self.len()).map(|t| Step {
            t,
            sensors: self.sensors[t],
            motors: self.motors[t],
            speeds: self.speeds[t],
            pose: self.poses[t + 1],
            cell: None,
            collided: self.collisions[t],
            action: self.actions[t],
            idle: self.idle[t],
            energy: self.energy[t],
            escaped: self.escaped[t],
        })
    }
}

impl StepObserver for Trajectory {
    fn observe(&mut self, s: &Step) {
        self.sensors.push(s.sensors);
        self.motors.push(s.motors);
        self.speeds.push(s.speeds);
        self.poses.push(s.pose);
        self.collisions.push(s.collided);
        self.actions.push(s.action);
        self.idle.push(s.idle);
        self.energy.push(s.energy);
        self.escaped.push(s.escaped);
    }
}

/// Records only the action of each step (for environment vectors).
#[derive(Debug, Clone, Default)]
pub struct ActionLog {
    /// The actions so far.
    pub actions: Vec<Action>,
}

impl StepObserver for ActionLog {
    #[inline]
    fn observe(&mut self, s: &Step) {
        self.actions.push(s.action);
    }

    #[inline]
    fn reads_motors(&self) -> bool {
        false
    }
}

/// Runs a trial (with the arena's parameters) and records its whole trajectory.
pub fn run_trial<C, R>(arena: &Arena, controller: &mut C, rng: &mut R) -> Trajectory
where
    C: Controller + ?Sized,
    R: Rng + ?Sized,
{
    let mut tr = Trajectory::starting_at(arena.room.home, arena.params.steps);
    simulate(arena, controller, rng, &mut tr);
    tr
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::rng::rng_from_seed;
    use crate::simulation::memo::registry;
    use crate::simulation::robot::RawRobot;

    struct Fixed([f64; 2]);
    impl Controller for Fixed {
        fn step(&mut self, _: &[f64]) -> [f64; 2] {
            self.0
        }
    }

    fn square() -> Arena {
        Arena::new(Room::builtin("square").unwrap(), &TrialParams::default())
    }

    /// `cell_of` is the clamped floor of the position in cells, computed in `usize`, for
    /// points inside, on the edges of and far outside the grid of rooms of every size.
    #[test]
    fn cells_are_the_clamped_floor_of_the_position() {
        let far = crate::simulation::room::MAX_COORD;
        for name in ["square", "H", "T", "L", "rectangle"] {
            let a = Arena::new(Room::builtin(name).unwrap(), &TrialParams::default());
            let g = &a.grid;
            let plain = |p: Vec2| {
                let i = ((p.x - g.origin.x) / CELL).clamp(0.0, (g.cols - 1) as f64) as usize;
                let j = ((p.y - g.origin.y) / CELL).clamp(0.0, (g.rows - 1) as f64) as usize;
                j * g.cols + i
            };
            let mut xs = vec![
                -far,
                3.0 * -far,
                g.origin.x,
                g.origin.x - 1e-9,
                far,
                3.0 * far,
            ];
            xs.extend((0..=4 * g.cols.max(g.rows)).map(|k| g.origin.x + 12.5 * k as f64));
            xs.extend((0..997).map(|k| g.origin.x - 60.0 + 0.73 * k as f64));
            for &x in &xs {
                for &y in &xs {
                    let p = Vec2::new(x, y - g.origin.x + g.origin.y);
                    assert_eq!(a.cell_of(p), plain(p), "{name} at {p:?}");
                }
            }
            assert_eq!(a.cell_of(Vec2::new(far, far)), g.cells() - 1);
        }
    }

    #[test]
    fn sensors_at_known_distances() {
        let a = square();
        // Facing the x = 800 wall from 30 mm away (centre): front sensors 2, 3 are at x + 24.5,
        // so the wall is 5.5 mm along their axis → first axis sample 12 mm → 900.
        let p = Pose::new(770.0, 300.0, 0.0);
        let s = a.read_sensors(&p);
        // Side rays at ±24.2° hit at 5.5 / cos(24.2°) = 6.03 mm → 800 each; 900 + 1600 capped.
        assert_eq!(s[2], 1023.0);
        assert_eq!(s[3], 1023.0);
        // Rear sensors face away into 770 mm of empty room.
        assert_eq!(s[6], 0.0);
        assert_eq!(s[7], 0.0);
        // In the middle of the room nothing is seen.
        assert_eq!(a.read_sensors(&Pose::new(400.0, 400.0, 0.3)), [0.0; 8]);
        // 40 mm from the sensor face: axis hits at 40 → 44 mm sample → 160; sides at
        // 40 / cos 24.2° = 43.86 → 43.9 mm sample → 60 each.
        let s = a.read_sensors(&Pose::new(800.0 - 24.5 - 40.0, 300.0, 0.0));
        assert_eq!(s[2], 160.0 + 60.0 + 60.0);
    }

    #[test]
    fn linear_sensor_at_known_distance() {
        let params = TrialParams {
            sensor_model: SensorModel::Linear,
            ..TrialParams::default()
        };
        let a = Arena::new(Room::builtin("square").unwrap(), &params);
        let s = a.read_sensors(&Pose::new(800.0 - 24.5 - 25.0, 300.0, 0.0));
        assert!((s[2] - 511.5).abs() < 1e-9, "{}", s[2]);
    }

    #[test]
    fn reachable_cells_of_the_square() {
        // Cells of 50 mm in an 800 mm square: centres at 25, 75, …, 775; those ≥ 27.5 mm from
        // the walls are 75 … 725, i.e. 14 × 14.
        assert_eq!(square().reachable_cells(), 196);
    }

    /// A 50 mm gap is narrower than the 55 mm body: the far half is not reachable, even though
    /// valid cell centres lie on both sides of the gap 50 mm apart (regression: the first flood
    /// fill joined any two valid neighbours).
    #[test]
    fn a_gap_narrower_than_the_body_is_not_a_passage() {
        let text = "name='gap'\noutline=[[0,0],[700,0],[700,300],[0,300]]\nhome={x=100,y=150,heading_deg=0}\n\
            [[obstacles]]\noutline=[[349,2],[351,2],[351,100],[349,100]]\n\
            [[obstacles]]\noutline=[[349,150],[351,150],[351,298],[349,298]]\n";
        let room = Room::from_toml_str(text, "gap.toml").unwrap();
        let narrow = Arena::new(room.clone(), &TrialParams::default());
        assert_eq!(narrow.reachable_cells(), 21);
        // A 70 mm gap (y 90..160): both halves are reachable.
        let mut wide = room;
        wide.obstacles[0] = wide.obstacles[0]
            .iter()
            .map(|p| Vec2::new(p.x, if p.y == 100.0 { 90.0 } else { p.y }))
            .collect();
        wide.obstacles[1] = wide.obstacles[1]
            .iter()
            .map(|p| Vec2::new(p.x, if p.y == 150.0 { 160.0 } else { p.y }))
            .collect();
        assert_eq!(
            Arena::new(wide, &TrialParams::default()).reachable_cells(),
            42
        );
    }

    #[test]
    fn driving_into_a_wall_stops_at_it() {
        let a = square();
        let params = TrialParams {
            noise: 0.0,
            ..TrialParams::default()
        };
        let a = Arena::new(a.room.clone(), &params);
        let tr = run_trial(&a, &mut Fixed([1.0, 1.0]), &mut rng_from_seed(1));
        // 400 steps × 8 mm would be 3.2 m; the wall stops the robot at x = 40 + 91·8 = 768,
        // short of 800 − 27.5; every later straight action collides and stays.
        let last = tr.poses.last().unwrap();
        assert_eq!((last.x, last.y, last.heading), (768.0, 40.0, 0.0));
        assert_eq!(tr.collisions.iter().filter(|&&c| c).count(), 400 - 91);
        assert!(tr.poses[92..].iter().all(|p| p == last));
        assert_eq!(tr.poses.len(), 401);
    }

    /// The step loop compiled for AVX2 takes the very steps of the baseline build: every
    /// pose, sensor value, motor output, speed, collision and action has the same bits, for
    /// random networks (most of which touch walls) in the paper's H room and in the square,
    /// with both motion models, the memo of sightings on and off. Skipped on a processor
    /// without AVX2 (there only the baseline runs).
    #[test]
    fn avx2_step_loop_takes_the_baseline_steps_bit_for_bit() {
        if Isa::detected() == Isa::Baseline {
            return;
        }
        let shape = crate::simulation::MlpShape::default();
        let mut draw = rng_from_seed(38);
        for (room, motion) in [
            ("H", Motion::Actions),
            ("H", Motion::Wheels),
            ("square", Motion::Wheels),
        ] {
            let robot = RawRobot {
                motion,
                ..RawRobot::default()
            };
            let params = TrialParams::from_raw(
                &RawTrial::default(),
                &robot,
                crate::simulation::RobotSpec::khepera(),
                crate::simulation::robot::DEFAULT_ACTION_TOLERANCE,
            )
            .unwrap();
            let arena = Arena::new(Room::builtin(room).unwrap(), &params);
            for k in 0..40u64 {
                let genome: Vec<f64> = (0..shape.genome_len())
                    .map(|_| crate::random::rng::uniform(&mut draw, -4.0, 4.0))
                    .collect();
                let run = |isa: Isa, memo: bool| {
                    let mut net = crate::simulation::Mlp::from_genome(shape, &genome).unwrap();
                    let mut tr = Trajectory::starting_at(arena.room.home, params.steps);
                    let mut rng = rng_from_seed(k);
                    let owner = arena.memo_owner().filter(|_| memo);
                    match owner {
                        Some(owner) => crate::simulation::memo::with_table(owner, memo_live, |t| {
                            walk_trial_on(isa, &arena, &mut net, &mut rng, &mut tr, t)
                        }),
                        None => walk_trial_on(isa, &arena, &mut net, &mut rng, &mut tr, None),
                    };
                    format!("{:?}", bits_of(&tr))
                };
                for memo in [false, true] {
                    let base = run(Isa::Baseline, memo);
                    assert_eq!(run(Isa::detected(), memo), base, "{room} {motion:?} #{k}");
                }
            }
        }
    }

    /// A trajectory as bit patterns (so that -0.0 and 0.0, or two NaNs, are told apart).
    fn bits_of(tr: &Trajectory) -> Vec<Vec<u64>> {
        let f = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let mut out: Vec<Vec<u64>> = tr.poses.iter().map(|p| f(&[p.x, p.y, p.heading])).collect();
        out.extend(tr.sensors.iter().map(|s| f(s)));
        out.extend(tr.motors.iter().map(|m| f(m)));
        out.extend(tr.speeds.iter().map(|m| f(m)));
        out.push(tr.collisions.iter().map(|&c| u64::from(c)).collect());
        out.push(tr.actions.iter().map(|&a| a as u64).collect());
        out
    }

    fn noiseless() -> TrialParams {
        TrialParams {
            noise: 0.0,
            ..TrialParams::default()
        }
    }

    /// `actions` motion, hand-computed poses: straight moves 8 mm along the heading, left30
    /// rotates by exactly π/6, right30 by −π/6, turn180 by π, all on the spot.
    #[test]
    fn actions_move_and_turn_exactly() {
        let a = square();
        let one = |motors: [f64; 2]| {
            let p = TrialParams {
                steps: 1,
                ..noiseless()
            };
            let a = Arena::new(a.room.clone(), &p);
            let tr = run_trial(&a, &mut Fixed(motors), &mut rng_from_seed(1));
            (tr.poses[1], tr.actions[0])
        };
        let (p, act) = one([1.0, 1.0]);
        assert_eq!(
            (p.x, p.y, p.heading, act),
            (48.0, 40.0, 0.0, Action::Straight)
        );
        let (p, act) = one([0.3, 0.9]);
        assert_eq!((p.x, p.y, act), (40.0, 40.0, Action::Left30));
        assert_eq!(p.heading, std::f64::consts::FRAC_PI_6);
        let (p, act) = one([0.9, 0.3]);
        assert_eq!((p.x, p.y, act), (40.0, 40.0, Action::Right30));
        assert_eq!(p.heading, -std::f64::consts::FRAC_PI_6);
        let (p, act) = one([0.1, 0.2]);
        assert_eq!((p.x, p.y, act), (40.0, 40.0, Action::Turn180));
        assert_eq!(p.heading, std::f64::consts::PI);
        // Three left turns then straight: heading π/2, 8 mm up.
        let p = TrialParams {
            steps: 4,
            ..noiseless()
        };
        struct Seq(usize);
        impl Controller for Seq {
            fn step(&mut self, _: &[f64]) -> [f64; 2] {
                self.0 += 1;
                if self.0 <= 3 { [0.3, 0.9] } else { [1.0, 1.0] }
            }
        }
        let a = Arena::new(a.room.clone(), &p);
        let tr = run_trial(&a, &mut Seq(0), &mut rng_from_seed(1));
        let end = tr.poses[4];
        assert!(
            (end.x - 40.0).abs() < 1e-12 && (end.y - 48.0).abs() < 1e-12,
            "{end:?}"
        );
        assert!((end.heading - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    }

    /// A straight action into a wall collides: the robot stays where it was.
    #[test]
    fn a_straight_action_into_a_wall_collides_and_stays() {
        let a = square();
        // Facing −x from home (40, 40): the wall x = 0 is 40 mm away, closer than 27.5 + 8.
        struct Back(bool);
        impl Controller for Back {
            fn step(&mut self, _: &[f64]) -> [f64; 2] {
                let first = self.0;
                self.0 = false;
                if first { [0.0, 0.0] } else { [1.0, 1.0] }
            }
        }
        let p = TrialParams {
            steps: 3,
            ..noiseless()
        };
        let a = Arena::new(a.room.clone(), &p);
        let tr = run_trial(&a, &mut Back(true), &mut rng_from_seed(1));
        assert_eq!(tr.actions[0], Action::Turn180);
        // 40 → 32 is still ≥ 27.5 from the wall; 32 → 24 is not.
        assert_eq!((tr.poses[2].x, tr.collisions[1]), (32.0, false));
        assert_eq!((tr.poses[3].x, tr.collisions[2]), (32.0, true));
        assert_eq!(tr.poses[3].heading, std::f64::consts::PI);
    }

    /// The memo number of `arena`, if it has one.
    fn number(arena: &Arena) -> Option<u64> {
        arena.memo.as_ref().map(|claim| claim.number)
    }

    /// Equal arenas share a memo number (and so their tables), also when they differ only in
    /// what a sight does not read (the number of steps); a different room, body or sensor
    /// model does not, and a different step length does not share a table.
    #[test]
    fn equal_arenas_share_their_memo_number() {
        let params = TrialParams::default();
        let h = |params: &TrialParams| Arena::new(Room::builtin("H").unwrap(), params);
        let first = h(&params);
        assert!(number(&first).is_some());
        assert_eq!(number(&first), number(&h(&params)));
        assert_eq!(number(&first), number(&first.clone()));
        let longer = TrialParams {
            steps: 1000,
            ..params
        };
        assert_eq!(number(&first), number(&h(&longer)));
        assert_ne!(number(&first), number(&square()));
        let raw = RawTrial::default();
        let wider = RawRobot {
            radius: Some(params.robot.radius() + 1.0),
            ..RawRobot::default()
        };
        let faster = RawRobot {
            v_max: Some(100.0),
            ..RawRobot::default()
        };
        let other = |robot| {
            h(&TrialParams::from_raw(
                &raw,
                &robot,
                crate::simulation::RobotSpec::khepera(),
                params.action_tolerance,
            )
            .unwrap())
        };
        // A wider body reads other sights: another number.
        let wide = other(wider);
        assert!(number(&wide).is_some());
        assert_ne!(number(&first), number(&wide));
        assert_ne!(first.memo_owner(), wide.memo_owner());
        // A longer straight move (the sensors reach farther than it) has the same sights but
        // other next poses: the same number, another table.
        assert_ne!(first.memo_owner(), other(faster).memo_owner());
        let linear = TrialParams {
            sensor_model: SensorModel::Linear,
            ..params
        };
        assert_eq!(number(&h(&linear)), None);
    }

    /// Two arenas with different parameters never share a table: whatever they ran before, a
    /// trial reads exactly what the same arena without a memo reads.
    #[test]
    fn arenas_with_different_params_never_share_a_table() {
        let room = Room::builtin("T").unwrap();
        let slow = TrialParams {
            noise: 0.0,
            ..TrialParams::default()
        };
        let wide = TrialParams::from_raw(
            &RawTrial {
                noise: Some(0.0),
                ..RawTrial::default()
            },
            &RawRobot {
                radius: Some(40.0),
                ..RawRobot::default()
            },
            crate::simulation::RobotSpec::khepera(),
            slow.action_tolerance,
        )
        .unwrap();
        let arenas = [Arena::new(room.clone(), &slow), Arena::new(room, &wide)];
        assert_ne!(arenas[0].memo_owner(), arenas[1].memo_owner());
        let run = |a: &Arena| run_trial(a, &mut Fixed([0.9, 0.8]), &mut rng_from_seed(2));
        // Each arena's memo warmed by the other's trials, then compared with casting.
        for (a, b) in [(0, 1), (1, 0), (0, 1)] {
            run(&arenas[a]);
            let remembered = run(&arenas[b]);
            let cast = run(&arenas[b].clone().without_memo());
            assert_eq!(remembered, cast);
        }
    }

    /// An arena's registry entry goes with its last arena: making and dropping many distinct
    /// arenas leaves the registry as it was, and a later equal arena gets a fresh number.
    #[test]
    fn dropped_arenas_leave_the_registry() {
        let registered = |key: &SightKey| registry().contains_key(key);
        let before = registry().len();
        let mut last = None;
        for k in 0..500 {
            // Squares of a size no other test uses (other tests run at the same time).
            let side = 900.0 + k as f64 * 0.5;
            let text = format!(
                "name='s{k}'\noutline=[[0,0],[{side},0],[{side},{side}],[0,{side}]]\nhome={{x=100,y=100,heading_deg=0}}\n"
            );
            let room = Room::from_toml_str(&text, "square.toml").unwrap();
            let arena = Arena::new(room, &TrialParams::default());
            let key = SightKey::of(&arena);
            assert!(registered(&key));
            let again = arena.clone();
            drop(arena);
            assert!(registered(&key), "a clone still holds it");
            last = number(&again);
            drop(again);
            assert!(!registered(&key), "square {k} still registered");
        }
        // Other tests' arenas come and go meanwhile, but not 500 of them.
        assert!(registry().len() < before + 100, "{}", registry().len());
        let number_then = last.unwrap();
        let side = 900.0 + 499.0 * 0.5;
        let text = format!(
            "name='s499'\noutline=[[0,0],[{side},0],[{side},{side}],[0,{side}]]\nhome={{x=100,y=100,heading_deg=0}}\n"
        );
        let again = Arena::new(
            Room::from_toml_str(&text, "square.toml").unwrap(),
            &TrialParams::default(),
        );
        assert!(
            number(&again).unwrap() > number_then,
            "numbers are not reused"
        );
        assert!(!memo_live(number_then));
        assert!(memo_live(number(&again).unwrap()));
    }

    const MISSION_ROOM: &str =
        "name='m'\noutline=[[0,0],[800,0],[800,400],[0,400]]\nhome={x=100,y=200,heading_deg=0}\n";
    /// A room whose goal lies behind a 120 mm gap: the Khepera (55 mm across) passes it, a
    /// body of radius 60 does not.
    fn gap_room() -> Room {
        let text = format!(
            "{MISSION_ROOM}goal={{x=700,y=200,radius=50}}\n\
             [[obstacles]]\noutline=[[400,5],[420,5],[420,140],[400,140]]\n\
             [[obstacles]]\noutline=[[400,260],[420,260],[420,395],[400,395]]\n"
        );
        Room::from_toml_str(&text, "gap.toml").unwrap()
    }

    #[test]
    fn the_arena_finds_the_mission_zone_its_body_cannot_reach() {
        let room = gap_room();
        let khepera = Arena::new(room.clone(), &TrialParams::default());
        assert_eq!(khepera.unreachable_mission_zone(), None);
        let params = TrialParams {
            robot: Robot::default().with_radius(60.0),
            ..TrialParams::default()
        };
        let e = Arena::new(room, &params)
            .unreachable_mission_zone()
            .unwrap();
        assert_eq!(e.field, "goal");
        assert!(e.reason.contains("body radius 60 mm"), "{e}");
    }

    #[test]
    fn a_bigger_body_that_cannot_reach_a_goal_names_the_room_and_field() {
        let rooms = [Room::builtin("H").unwrap(), gap_room()];
        crate::simulation::check_missions_reachable(
            &rooms,
            crate::simulation::robot::KHEPERA_RADIUS,
        )
        .unwrap();
        let e = crate::simulation::check_missions_reachable(&rooms, 60.0).unwrap_err();
        assert_eq!(e.field, "rooms[1]");
        assert!(e.reason.contains("room \"m\", field `goal`"), "{e}");
    }
}
