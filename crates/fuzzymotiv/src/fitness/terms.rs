//! The fitness terms (docs/model.md, "Fitness terms"): the paper's exploration `a`, homing `g`,
//! orientation `l` and battery `b`; the mission terms `goal`, `urgency`, `waypoints` (of a room
//! file's mission) and `safety`; and the values of terms a user defines ([`Term`]).

use std::borrow::Borrow;

use serde::{Deserialize, Serialize};

use crate::simulation::room::{Room, Zone};
use crate::simulation::trial::{Arena, CELL, Step, StepObserver, Trajectory};

/// The four fitness values Y = (a, g, l, b), each in [0, 1], higher is better for the fuzzy
/// combination (with `energy = "use"`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct FitnessTerms {
    /// Exploration: visited cells / optimum.
    pub a: f64,
    /// Homing: 1 − d_final / d_max (0 if the robot never escaped the home zone, with
    /// [`Homing::Escape`]).
    pub g: f64,
    /// Orientation (recognition); 0 during evolution unless online orientation is on.
    pub l: f64,
    /// Battery usage: the energy of the executed steps / T (one unit per action with
    /// `actions` motion; (|sL| + |sR|) / (2·v_max) of the commanded speeds with `wheels`).
    pub b: f64,
    /// The mission terms, when the experiment measures them (a motivation weighs one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mission: Option<MissionTerms>,
    /// The values of the experiment's user-defined terms, in the order they were registered.
    #[serde(default, skip_serializing_if = "UserValues::is_empty")]
    pub user: UserValues,
}

/// The mission terms of one trial (docs/model.md, "Fitness terms"), each in [0, 1].
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct MissionTerms {
    /// Goal: 1 once the robot's centre has been in the room's goal zone, else 1 − (closest
    /// approach to the zone) / (the room's largest distance).
    pub goal: f64,
    /// Urgency: 1 − t_done / T for a mission done at step t_done (1-based), 0 if never done.
    pub urgency: f64,
    /// Waypoints: the fraction of the room's waypoints visited (in order, or in any order).
    pub waypoints: f64,
    /// Safety: 1 − the fraction of executed steps whose move was blocked by a wall.
    pub safety: f64,
    /// The step (1-based) at which the mission was done, if it was.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub done_at: Option<usize>,
}

/// The most user-defined terms an experiment may have.
pub const MAX_USER_TERMS: usize = 8;

/// The values of user-defined terms, without allocating (at most [`MAX_USER_TERMS`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct UserValues {
    values: [f64; MAX_USER_TERMS],
    len: u8,
}

impl UserValues {
    /// `n` values of 0 (to be filled in).
    pub fn zeros(n: usize) -> UserValues {
        UserValues {
            values: [0.0; MAX_USER_TERMS],
            len: n.min(MAX_USER_TERMS) as u8,
        }
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The values.
    pub fn as_slice(&self) -> &[f64] {
        &self.values[..self.len as usize]
    }

    /// The values, to fill in.
    pub fn as_mut_slice(&mut self) -> &mut [f64] {
        &mut self.values[..self.len as usize]
    }
}

impl Serialize for UserValues {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.as_slice().serialize(s)
    }
}

impl<'de> Deserialize<'de> for UserValues {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = Vec::<f64>::deserialize(d)?;
        if v.len() > MAX_USER_TERMS {
            return Err(serde::de::Error::custom(format!(
                "at most {MAX_USER_TERMS} user terms, got {}",
                v.len()
            )));
        }
        let mut out = UserValues::zeros(v.len());
        out.as_mut_slice().copy_from_slice(&v);
        Ok(out)
    }
}

/// The terms of the library a motivation can weigh, by name: the paper's four, then the
/// mission terms.
pub const LIBRARY_TERMS: [&str; 8] = ["a", "g", "l", "b", "goal", "urgency", "waypoints", "safety"];

/// Names a user-defined term cannot take because the records already name a column so: the
/// stems of the fixed columns of `test_runs.csv` (`NAME_pct`) and `robustness.csv` (`NAME`,
/// `NAME_lo`, `NAME_hi`): the paper's measures, the missions done, and the rows' labels. A term
/// `NAME` writes the columns `NAME_pct` and `NAME`, `NAME_lo`, `NAME_hi`, so these, the library's
/// terms and [`TERM_ALIASES`] stay apart from every user term's columns (the records crate
/// asserts its columns are all here).
pub const RECORD_COLUMN_NAMES: [&str; 12] = [
    "room",
    "test",
    "answer",
    "exploration",
    "recognition",
    "battery",
    "homing",
    "mission_done",
    "perturbation",
    "trials",
    "f",
    "missions_done",
];

/// Other names accepted for the paper's terms in a config (`term = "exploration"`).
pub const TERM_ALIASES: [(&str, &str); 4] = [
    ("exploration", "a"),
    ("homing", "g"),
    ("orientation", "l"),
    ("battery", "b"),
];

/// A term a motivation weighs, resolved: one of the library's, or user-defined term `k`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TermId {
    /// Exploration `a`.
    A,
    /// Homing `g`.
    G,
    /// Orientation `l`.
    L,
    /// Battery `b`.
    B,
    /// `goal`.
    Goal,
    /// `urgency`.
    Urgency,
    /// `waypoints`.
    Waypoints,
    /// `safety`.
    Safety,
    /// The experiment's user-defined term `k` (registration order).
    User(usize),
}

impl TermId {
    /// The library term named `name` (or one of [`TERM_ALIASES`]).
    pub fn library(name: &str) -> Option<TermId> {
        let name = TERM_ALIASES
            .iter()
            .find(|(alias, _)| *alias == name)
            .map_or(name, |(_, t)| t);
        let ids = [
            TermId::A,
            TermId::G,
            TermId::L,
            TermId::B,
            TermId::Goal,
            TermId::Urgency,
            TermId::Waypoints,
            TermId::Safety,
        ];
        LIBRARY_TERMS
            .iter()
            .position(|t| *t == name)
            .map(|k| ids[k])
    }

    /// Whether it is one of the mission terms (measured only when a motivation weighs one).
    pub fn is_mission(self) -> bool {
        matches!(
            self,
            TermId::Goal | TermId::Urgency | TermId::Waypoints | TermId::Safety
        )
    }
}

/// A term of your own: a value in [0, 1] of a finished trial (docs/guide, "Define your own
/// motivation"). Register it with [`crate::Experiment::with_terms`] under a name a
/// motivation's `term` can use; an experiment with one records each trial's steps for it.
pub trait Term: Send + Sync + std::fmt::Debug {
    /// The term's value for one finished trial, in [0, 1].
    ///
    /// # Panics
    ///
    /// A value outside [0, 1], or NaN, is a bug in the term: it is not clamped (which would
    /// hide the bug in F), and evolving returns an error naming the term and the value
    /// ([`crate::experiment::TermError`], `RunError::Term`), never a panic.
    fn value(&self, trial: &TrialRecord<'_>) -> f64;
}

/// A finished trial, as a [`Term`] sees it.
#[derive(Debug, Clone, Copy)]
pub struct TrialRecord<'a> {
    /// The arena (room, grid, parameters) the trial ran in.
    pub arena: &'a Arena,
    /// Every step: poses, sensors, motors, speeds, collisions, actions, idle, energy.
    pub trajectory: &'a Trajectory,
    /// The terms the library measured.
    pub terms: &'a FitnessTerms,
}

/// How the homing term `g` is measured (config `[fitness] homing`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Homing {
    /// `g = 1 − d_final / d_max` if the robot escaped the home zone during the trial, else 0
    /// (default: the paper's "escape from original neighborhood area").
    #[default]
    Escape,
    /// `g = 1 − d_final / d_max` whatever happened (the first release).
    Distance,
}

impl FitnessTerms {
    /// As the array `[a, g, l, b]`.
    pub fn as_array(&self) -> [f64; 4] {
        [self.a, self.g, self.l, self.b]
    }

    /// Adds `other / n`, term by term (the running mean of `n` trials' terms); a mission step
    /// (`done_at`) is not averaged.
    pub fn add_mean(&mut self, other: &FitnessTerms, n: f64) {
        self.a += other.a / n;
        self.g += other.g / n;
        self.l += other.l / n;
        self.b += other.b / n;
        if let Some(o) = &other.mission {
            let m = self.mission.get_or_insert_with(MissionTerms::default);
            m.goal += o.goal / n;
            m.urgency += o.urgency / n;
            m.waypoints += o.waypoints / n;
            m.safety += o.safety / n;
        }
        if self.user.len < other.user.len {
            self.user = UserValues::zeros(other.user.len as usize);
        }
        for (m, v) in self
            .user
            .as_mut_slice()
            .iter_mut()
            .zip(other.user.as_slice())
        {
            *m += v / n;
        }
    }

    /// The value of term `id` (a mission term not measured is 0, a user term not filled in 0).
    pub fn get(&self, id: TermId) -> f64 {
        let mission = self.mission.unwrap_or_default();
        match id {
            TermId::A => self.a,
            TermId::G => self.g,
            TermId::L => self.l,
            TermId::B => self.b,
            TermId::Goal => mission.goal,
            TermId::Urgency => mission.urgency,
            TermId::Waypoints => mission.waypoints,
            TermId::Safety => mission.safety,
            TermId::User(k) => self.user.as_slice().get(k).copied().unwrap_or(0.0),
        }
    }

    /// Measures the terms of a trajectory recorded in `arena` (`l` = 0).
    pub fn measure(arena: &Arena, homing: Homing, trajectory: &Trajectory) -> FitnessTerms {
        let mut rec = TermsRecorder::new(arena, homing);
        for s in trajectory.steps() {
            rec.observe(&s);
        }
        rec.finish()
    }
}

/// `optimum = min(reachable, floor(T·v_max·dt / 50) + 1)`: the cells a full-speed robot that
/// never revisits a cell could enter, with the arena's parameters.
pub fn exploration_optimum(arena: &Arena) -> usize {
    let params = arena.params();
    let by_speed =
        (params.steps() as f64 * params.robot().v_max() * params.dt() / CELL).floor() as usize + 1;
    arena.reachable_cells().min(by_speed).max(1)
}

/// Accumulates the terms step by step (used inside evaluation without storing a trajectory)
/// in an arena `A`: `&Arena`, or an owning handle such as `Arc<Arena>` (for a trial driven
/// from outside, [`crate::fitness::episode::Episode`]).
#[derive(Debug, Clone)]
pub struct TermsRecorder<A: Borrow<Arena>> {
    arena: A,
    visited: Vec<bool>,
    visited_count: usize,
    battery: f64,
    steps: usize,
    executed: usize,
    last: crate::simulation::robot::Pose,
    escaped: bool,
    homing: Homing,
    optimum: usize,
    mission: Option<MissionTracker>,
}

/// How the mission terms are measured (config `[fitness]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum WaypointOrder {
    /// A waypoint counts only once the ones before it are visited (default).
    #[default]
    InOrder,
    /// Every waypoint counts, in whatever order.
    AnyOrder,
}

/// Follows a trial's mission (the room's waypoints, then its goal) and the blocked moves, for
/// the mission terms.
#[derive(Debug, Clone)]
pub struct MissionTracker {
    goal: Option<Zone>,
    waypoints: Vec<Zone>,
    order: WaypointOrder,
    largest: f64,
    closest: f64,
    goal_reached: bool,
    visited: Vec<bool>,
    visited_count: usize,
    blocked: usize,
    executed: usize,
    done_at: Option<usize>,
    end_when_done: bool,
}

impl MissionTracker {
    /// A tracker of the mission `goal` (if any) after `waypoints` in `room`; with
    /// `end_when_done`, the trial ends the step the mission is done.
    pub fn new(
        room: &Room,
        goal: Option<Zone>,
        waypoints: Vec<Zone>,
        order: WaypointOrder,
        end_when_done: bool,
    ) -> MissionTracker {
        let visited = vec![false; waypoints.len()];
        MissionTracker {
            goal,
            waypoints,
            order,
            largest: largest_distance(room),
            closest: f64::INFINITY,
            goal_reached: false,
            visited,
            visited_count: 0,
            blocked: 0,
            executed: 0,
            done_at: None,
            end_when_done,
        }
    }

    /// Whether every waypoint counts as visited.
    fn waypoints_done(&self) -> bool {
        self.visited_count == self.waypoints.len()
    }

    #[inline]
    fn observe(&mut self, s: &Step) {
        if s.idle {
            return;
        }
        self.executed += 1;
        self.blocked += usize::from(s.collided);
        let p = s.pose.position();
        self.visit_waypoints(p);
        if let Some(goal) = self.goal {
            let d = p - goal.centre;
            let rim = (d.dot(d).sqrt() - goal.radius).max(0.0);
            self.closest = self.closest.min(rim);
            self.goal_reached |= rim == 0.0;
        }
        let goal_now = self.goal.is_none_or(|g| g.contains(p));
        if self.done_at.is_none() && self.waypoints_done() && goal_now {
            self.done_at = Some(s.t + 1);
        }
    }

    fn visit_waypoints(&mut self, p: crate::simulation::Vec2) {
        match self.order {
            WaypointOrder::InOrder => {
                let k = self.visited_count;
                if k < self.waypoints.len() && self.waypoints[k].contains(p) {
                    self.visited[k] = true;
                    self.visited_count += 1;
                }
            }
            WaypointOrder::AnyOrder => {
                for (seen, w) in self.visited.iter_mut().zip(&self.waypoints) {
                    if !*seen && w.contains(p) {
                        *seen = true;
                        self.visited_count += 1;
                    }
                }
            }
        }
    }

    /// The mission terms after `steps` steps (T).
    fn finish(&self, steps: usize) -> MissionTerms {
        let goal = match self.goal {
            _ if self.goal_reached => 1.0,
            Some(_) if self.closest.is_finite() => {
                (1.0 - self.closest / self.largest).clamp(0.0, 1.0)
            }
            _ => 0.0,
        };
        let urgency = match self.done_at {
            Some(t) if steps > 0 => (1.0 - t as f64 / steps as f64).clamp(0.0, 1.0),
            _ => 0.0,
        };
        let waypoints = if self.waypoints.is_empty() {
            0.0
        } else {
            self.visited_count as f64 / self.waypoints.len() as f64
        };
        let safety = if self.executed == 0 {
            1.0
        } else {
            1.0 - self.blocked as f64 / self.executed as f64
        };
        MissionTerms {
            goal,
            urgency,
            waypoints,
            safety,
            done_at: self.done_at,
        }
    }
}

/// The largest distance between two points of the room's outline (mm), at least 1.
pub fn largest_distance(room: &Room) -> f64 {
    let mut most: f64 = 1.0;
    for (i, p) in room.outline.iter().enumerate() {
        for q in &room.outline[i + 1..] {
            let d = *p - *q;
            most = most.max(d.dot(d).sqrt());
        }
    }
    most
}

impl<A: Borrow<Arena>> TermsRecorder<A> {
    /// The same recorder, also following a mission (the mission terms).
    pub fn with_mission(mut self, tracker: MissionTracker) -> Self {
        self.mission = Some(tracker);
        self
    }

    /// A recorder for a trial in `arena` starting at home (the home cell counts as visited).
    pub fn new(arena: A, homing: Homing) -> Self {
        let a = arena.borrow();
        let home = a.room().home;
        let mut visited = vec![false; a.cell_count()];
        visited[a.cell_of(home.position())] = true;
        let optimum = exploration_optimum(a);
        Self {
            arena,
            visited,
            visited_count: 1,
            battery: 0.0,
            steps: 0,
            executed: 0,
            last: home,
            escaped: false,
            homing,
            optimum,
            mission: None,
        }
    }

    /// Steps executed so far (idle steps after the trial ended at home not counted).
    pub fn executed(&self) -> usize {
        self.executed
    }

    /// Cells visited so far.
    pub fn visited(&self) -> usize {
        self.visited_count
    }

    /// The terms so far (`l` = 0).
    pub fn finish(&self) -> FitnessTerms {
        let a = (self.visited_count as f64 / self.optimum as f64).clamp(0.0, 1.0);
        let arena = self.arena.borrow();
        let home = arena.room().home.position();
        let g = if self.homing == Homing::Escape && !self.escaped {
            0.0
        } else {
            // √(dx² + dy²) with IEEE operations only, not libm's `hypot` (whose last bit may
            // differ between platforms): the trial's results must not depend on the libm.
            let d = self.last.position() - home;
            (1.0 - d.dot(d).sqrt() / arena.d_max()).clamp(0.0, 1.0)
        };
        let b = if self.steps == 0 {
            0.0
        } else {
            (self.battery / self.steps as f64).clamp(0.0, 1.0)
        };
        FitnessTerms {
            a,
            g,
            l: 0.0,
            b,
            mission: self.mission.as_ref().map(|m| m.finish(self.steps)),
            user: UserValues::default(),
        }
    }
}

impl<A: Borrow<Arena>> StepObserver for TermsRecorder<A> {
    // Always inlined: in the step loops it then reads the step's fields where they were
    // computed, instead of a call with the step written out to memory.
    #[inline(always)]
    fn observe(&mut self, s: &Step) {
        let k = s
            .cell
            .unwrap_or_else(|| self.arena.borrow().cell_of(s.pose.position()));
        // Without a branch: whether a cell is new is as good as random, so a branch on it is
        // often mispredicted.
        self.visited_count += usize::from(!std::mem::replace(&mut self.visited[k], true));
        self.battery += s.energy;
        self.steps += 1;
        self.executed += usize::from(!s.idle);
        self.last = s.pose;
        self.escaped = s.escaped;
        if let Some(m) = &mut self.mission {
            m.observe(s);
        }
    }

    #[inline]
    fn finished(&self) -> bool {
        self.mission
            .as_ref()
            .is_some_and(|m| m.end_when_done && m.done_at.is_some())
    }

    /// The terms come from poses, cells, energies and idle flags, never from motors or speeds.
    #[inline]
    fn reads_motors(&self) -> bool {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modelling::aem::DEFAULT_ACTION_TOLERANCE;
    use crate::random::rng::rng_from_seed;
    use crate::simulation::controller::Controller;
    use crate::simulation::robot::{Motion, RawRobot};
    use crate::simulation::room::Room;
    use crate::simulation::trial::{RawTrial, TrialParams, run_trial};

    /// A controller that plays a fixed list of motor outputs, then repeats the last one.
    struct Script(Vec<[f64; 2]>, usize);
    impl Controller for Script {
        fn step(&mut self, _: &[f64]) -> [f64; 2] {
            let m = self.0[self.1.min(self.0.len() - 1)];
            self.1 += 1;
            m
        }
    }

    /// Checked parameters from the raw `[trial]` and the motion model.
    fn checked(trial: RawTrial, motion: Motion) -> TrialParams {
        let robot = RawRobot {
            motion,
            ..RawRobot::default()
        };
        TrialParams::from_raw(
            &trial,
            &robot,
            crate::simulation::RobotSpec::khepera(),
            DEFAULT_ACTION_TOLERANCE,
        )
        .unwrap()
    }

    fn params(motion: Motion, steps: usize) -> TrialParams {
        let trial = RawTrial {
            noise: Some(0.0),
            steps,
            ..RawTrial::default()
        };
        checked(trial, motion)
    }

    fn measure(
        room: &str,
        params: &TrialParams,
        homing: Homing,
        script: Vec<[f64; 2]>,
    ) -> (FitnessTerms, Trajectory) {
        let arena = Arena::new(Room::builtin(room).unwrap(), params);
        let tr = run_trial(&arena, &mut Script(script, 0), &mut rng_from_seed(3));
        (FitnessTerms::measure(&arena, homing, &tr), tr)
    }

    const STRAIGHT: [f64; 2] = [1.0, 1.0];
    const BACK: [f64; 2] = [0.0, 0.0];
    const LEFT: [f64; 2] = [0.3, 0.9];

    #[test]
    fn wheels_robot_standing_still() {
        let (t, _) = measure(
            "square",
            &params(Motion::Wheels, 400),
            Homing::Distance,
            vec![[0.5, 0.5]],
        );
        // Optimum = min(196 reachable, floor(400·80·0.1/50)+1 = 65) = 65; one cell visited.
        assert_eq!(t.a, 1.0 / 65.0);
        assert_eq!(t.g, 1.0);
        assert_eq!(t.b, 0.0);
        assert_eq!(t.l, 0.0);
        // With the escape rule, a robot that never left the home zone has not homed.
        let (t, _) = measure(
            "square",
            &params(Motion::Wheels, 400),
            Homing::Escape,
            vec![[0.5, 0.5]],
        );
        assert_eq!(t.g, 0.0);
    }

    /// A robot that only turns on the spot never leaves the zone: g = 0, and every turn is an
    /// executed action, so b = 1.
    #[test]
    fn a_robot_that_never_leaves_the_zone_gets_no_homing() {
        let (t, tr) = measure(
            "square",
            &params(Motion::Actions, 400),
            Homing::Escape,
            vec![LEFT],
        );
        assert_eq!(t.g, 0.0);
        assert_eq!(t.b, 1.0);
        assert_eq!(t.a, 1.0 / 65.0);
        assert_eq!(tr.executed(), 400);
        assert!(tr.escaped.iter().all(|&e| !e));
    }

    /// Out of the zone along +x, turn 180°, back in: the trial ends at re-entry and the rest of
    /// the 400 steps are idle; b counts the executed actions.
    #[test]
    fn a_robot_that_comes_back_ends_its_trial_at_home() {
        let mut script = vec![STRAIGHT; 20];
        script.push(BACK);
        script.extend([STRAIGHT; 400]);
        let (t, tr) = measure(
            "square",
            &params(Motion::Actions, 400),
            Homing::Escape,
            script,
        );
        // 20 moves to x = 200 (out of the 160 mm zone after x = 160), one turn, then 6 moves
        // back to x = 152, where |(152, 40)| = 157.2 ≤ 160: 27 executed steps.
        assert_eq!(tr.executed(), 27);
        assert_eq!(tr.len(), 400);
        assert_eq!(tr.poses.len(), 401);
        let end = tr.poses[27];
        assert_eq!((end.x, end.y), (152.0, 40.0));
        assert!(
            tr.poses[27..].iter().all(|p| *p == end),
            "idle steps stand still"
        );
        assert!(tr.idle[27..].iter().all(|&i| i) && tr.idle[..27].iter().all(|&i| !i));
        assert!(
            tr.actions[27..]
                .iter()
                .all(|&a| a == crate::modelling::aem::Action::Straight)
        );
        assert!(tr.energy[27..].iter().all(|&e| e == 0.0));
        assert_eq!(t.b, 27.0 / 400.0);
        // g: 112 mm from home (40, 40); d_max = |(800, 800) − (40, 40)| = 760·√2.
        assert!(
            (t.g - (1.0 - 112.0 / (760.0 * 2f64.sqrt()))).abs() < 1e-12,
            "{t:?}"
        );
        // Cells of x = 40 … 200 on the bottom row: 0, 1, 2, 3, 4.
        assert_eq!(t.a, 5.0 / 65.0);
        // Without end_at_home the robot drives on to the far wall.
        let p = checked(
            RawTrial {
                noise: Some(0.0),
                end_at_home: false,
                ..RawTrial::default()
            },
            Motion::Actions,
        );
        let mut script = vec![STRAIGHT; 20];
        script.push(BACK);
        script.extend([STRAIGHT; 400]);
        let (_, tr) = measure("square", &p, Homing::Escape, script);
        assert_eq!(tr.executed(), 400);
    }

    #[test]
    fn wheels_robot_driving_straight() {
        // From (40, 40) heading +x at 8 mm/step for 20 steps: 160 mm, ending at x = 200.
        let (t, _) = measure(
            "square",
            &params(Motion::Wheels, 20),
            Homing::Distance,
            vec![STRAIGHT],
        );
        // Cells entered: x-cells 0 … 4: 5 cells; optimum = floor(20·8/50)+1 = 4 → a = 1.
        assert_eq!(t.a, 1.0);
        let d_max = 760.0 * 2f64.sqrt();
        assert!((t.g - (1.0 - 160.0 / d_max)).abs() < 1e-9, "{t:?}");
        assert_eq!(t.b, 1.0);
    }

    /// A room 800 × 400 mm, home at (100, 200) heading +x, for the mission terms; `mission` is
    /// its goal and waypoints (room-file TOML). Its largest distance is √(800² + 400²).
    fn mission_room(mission: &str) -> Room {
        let text = format!(
            "name='m'\noutline=[[0,0],[800,0],[800,400],[0,400]]\nhome={{x=100,y=200,heading_deg=0}}\n{mission}"
        );
        Room::from_toml_str(&text, "m.toml").unwrap()
    }

    /// The terms and trajectory of a scripted `actions` trial of `steps` steps in `room`,
    /// following its mission (waypoints counted by `order`; ending when done with `end`).
    fn mission_trial(
        room: &Room,
        steps: usize,
        order: WaypointOrder,
        end: bool,
        script: Vec<[f64; 2]>,
    ) -> (MissionTerms, Trajectory) {
        let arena = Arena::new(room.clone(), &params(Motion::Actions, steps));
        let tracker = MissionTracker::new(
            room,
            room.mission.goal,
            room.mission.waypoints.clone(),
            order,
            end,
        );
        let mut observer = (
            TermsRecorder::new(&arena, Homing::Escape).with_mission(tracker),
            Trajectory::starting_at(room.home, steps),
        );
        crate::simulation::trial::simulate(
            &arena,
            &mut Script(script, 0),
            &mut rng_from_seed(3),
            &mut observer,
        );
        let terms = observer.0.finish();
        (terms.mission.expect("the mission is followed"), observer.1)
    }

    /// A goal zone at (700, 200), radius 60, on the robot's straight path.
    const GOAL: &str = "goal={x=700,y=200,radius=60}\n";

    /// goal = 1 − (closest approach to the zone's rim) / (the room's largest distance) when the
    /// zone is never reached; urgency 0 (never done).
    #[test]
    fn goal_not_reached_is_one_minus_the_closest_approach_over_the_largest_distance() {
        let room = mission_room(GOAL);
        assert_eq!(
            largest_distance(&room),
            (800f64 * 800.0 + 400.0 * 400.0).sqrt()
        );
        // 21 moves of 8 mm to x = 268 (out of the home zone, radius 160 around x = 100), a
        // half turn, then back: x = 260 is inside the zone again and the trial ends there. The
        // closest approach is at x = 268, 372 mm from the rim (700 − 60 − 268), not the final
        // x = 260.
        let mut script = vec![STRAIGHT; 21];
        script.push(BACK);
        script.extend([STRAIGHT; 40]);
        let (m, tr) = mission_trial(&room, 60, WaypointOrder::InOrder, false, script);
        assert_eq!(tr.poses[21].x, 268.0);
        assert_eq!(tr.executed(), 23, "ended at home");
        assert_eq!(tr.poses[23].x, 260.0);
        let expected = 1.0 - 372.0 / (800f64 * 800.0 + 400.0 * 400.0).sqrt();
        assert!((m.goal - expected).abs() < 1e-12, "{m:?} vs {expected}");
        assert_eq!((m.urgency, m.done_at), (0.0, None));
        // No waypoints: the waypoints term is 0.
        assert_eq!(m.waypoints, 0.0);
    }

    /// goal = 1 once the centre has been in the zone (even if the robot drives on), urgency
    /// = 1 − t_done / T with t_done the 1-based step it got there.
    #[test]
    fn a_goal_reached_at_step_68_of_100_gives_goal_1_and_urgency_0_32() {
        let room = mission_room(GOAL);
        // x = 100 + 8k enters the zone (x ≥ 640) at k = 68 and drives on to the far wall.
        let (m, tr) = mission_trial(&room, 100, WaypointOrder::InOrder, false, vec![STRAIGHT]);
        assert_eq!(tr.poses[68].x, 644.0);
        assert_eq!(tr.poses[67].x, 636.0);
        assert!(tr.poses[100].x > 700.0 + 60.0, "drove past the goal");
        assert_eq!(m.goal, 1.0);
        assert_eq!(m.done_at, Some(68));
        assert_eq!(m.urgency, 1.0 - 68.0 / 100.0);
        assert!((m.urgency - 0.32).abs() < 1e-12);
        assert_eq!(
            tr.executed(),
            100,
            "without end_at_mission the trial goes on"
        );
    }

    /// With `end_at_mission`, the trial ends the step its mission is done: step 68 of 100, the
    /// 32 left idle, standing in the goal.
    #[test]
    fn end_at_mission_ends_the_trial_the_step_the_mission_is_done() {
        let room = mission_room(GOAL);
        let (m, tr) = mission_trial(&room, 100, WaypointOrder::InOrder, true, vec![STRAIGHT]);
        assert_eq!(tr.executed(), 68);
        assert_eq!(tr.len(), 100);
        assert!(tr.idle[68..].iter().all(|&i| i) && tr.idle[..68].iter().all(|&i| !i));
        assert!(tr.poses[68..].iter().all(|p| p.x == 644.0));
        assert_eq!((m.goal, m.done_at), (1.0, Some(68)));
        assert_eq!(m.urgency, 1.0 - 68.0 / 100.0);
        // A mission never done does not end the trial.
        let (m, tr) = mission_trial(&room, 60, WaypointOrder::InOrder, true, vec![STRAIGHT]);
        assert_eq!((tr.executed(), m.done_at, m.urgency), (60, None, 0.0));
    }

    /// Waypoints listed (500, 200), (300, 200), (300, 340): the straight path passes (300, 200)
    /// at step 20 and (500, 200) at step 45 and never the third.
    const THREE_WAYPOINTS: &str =
        "waypoints=[{x=500,y=200,radius=40},{x=300,y=200,radius=40},{x=300,y=340,radius=40}]\n";

    /// in-order counts a waypoint only after the ones before it: the first listed is visited
    /// (after the second was passed), so 1 of 3; any-order counts both passed: 2 of 3.
    #[test]
    fn waypoints_count_the_fraction_visited_in_order_or_in_any_order() {
        let room = mission_room(THREE_WAYPOINTS);
        let (m, tr) = mission_trial(&room, 60, WaypointOrder::InOrder, false, vec![STRAIGHT]);
        assert_eq!((tr.poses[20].x, tr.poses[45].x), (260.0, 460.0));
        assert_eq!(m.waypoints, 1.0 / 3.0);
        assert_eq!((m.urgency, m.done_at), (0.0, None));
        let (m, _) = mission_trial(&room, 60, WaypointOrder::AnyOrder, false, vec![STRAIGHT]);
        assert_eq!(m.waypoints, 2.0 / 3.0);
        assert_eq!((m.urgency, m.done_at), (0.0, None));
        // The goal term is 0 without a goal.
        assert_eq!(m.goal, 0.0);
    }

    /// A mission of waypoints alone is done when the last counts: in any order at step 45 of
    /// 60 (urgency 1 − 45/60); in order never (the first listed comes after the second).
    #[test]
    fn a_waypoint_mission_is_done_when_every_waypoint_counts() {
        let room = mission_room("waypoints=[{x=500,y=200,radius=40},{x=300,y=200,radius=40}]\n");
        let (m, _) = mission_trial(&room, 60, WaypointOrder::AnyOrder, false, vec![STRAIGHT]);
        assert_eq!((m.waypoints, m.done_at), (1.0, Some(45)));
        assert_eq!(m.urgency, 1.0 - 45.0 / 60.0);
        let (m, tr) = mission_trial(&room, 60, WaypointOrder::AnyOrder, true, vec![STRAIGHT]);
        assert_eq!((tr.executed(), m.done_at), (45, Some(45)));
        let (m, _) = mission_trial(&room, 60, WaypointOrder::InOrder, false, vec![STRAIGHT]);
        assert_eq!((m.waypoints, m.done_at, m.urgency), (0.5, None, 0.0));
        // Listed in the order the path meets them, in order counts both, done at step 45.
        let room = mission_room("waypoints=[{x=300,y=200,radius=40},{x=500,y=200,radius=40}]\n");
        let (m, _) = mission_trial(&room, 60, WaypointOrder::InOrder, false, vec![STRAIGHT]);
        assert_eq!((m.waypoints, m.done_at), (1.0, Some(45)));
    }

    /// With waypoints and a goal, reaching the goal is not the mission: the goal term is 1,
    /// but the mission is done only once the waypoints are visited too, so urgency stays 0.
    #[test]
    fn the_goal_alone_does_not_finish_a_mission_with_waypoints_left() {
        let room = mission_room(&format!("{GOAL}waypoints=[{{x=300,y=340,radius=40}}]\n"));
        let (m, tr) = mission_trial(&room, 100, WaypointOrder::InOrder, true, vec![STRAIGHT]);
        assert_eq!((m.goal, m.waypoints), (1.0, 0.0));
        assert_eq!((m.urgency, m.done_at), (0.0, None));
        assert_eq!(tr.executed(), 100);
    }

    #[test]
    fn recorder_and_trajectory_agree() {
        for motion in [Motion::Actions, Motion::Wheels] {
            let params = checked(RawTrial::default(), motion);
            let arena = Arena::new(Room::builtin("H").unwrap(), &params);
            let tr = run_trial(
                &arena,
                &mut Script(vec![[0.9, 0.7]], 0),
                &mut rng_from_seed(9),
            );
            let mut rec = TermsRecorder::new(&arena, Homing::Escape);
            crate::simulation::trial::simulate(
                &arena,
                &mut Script(vec![[0.9, 0.7]], 0),
                &mut rng_from_seed(9),
                &mut rec,
            );
            assert_eq!(
                rec.finish(),
                FitnessTerms::measure(&arena, Homing::Escape, &tr)
            );
        }
    }
}
