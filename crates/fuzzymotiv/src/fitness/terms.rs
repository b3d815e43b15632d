//! The fitness terms (docs/model.md, "Fitness terms"): exploration `a`, homing `g`,
//! orientation `l`, battery `b`.

use std::borrow::Borrow;

use serde::{Deserialize, Serialize};

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
}

impl<A: Borrow<Arena>> TermsRecorder<A> {
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
        FitnessTerms { a, g, l: 0.0, b }
    }
}

impl<A: Borrow<Arena>> StepObserver for TermsRecorder<A> {
    #[inline]
    fn observe(&mut self, s: &Step) {
        let k = s
            .cell
            .unwrap_or_else(|| self.arena.borrow().cell_of(s.pose.position()));
        if !self.visited[k] {
            self.visited[k] = true;
            self.visited_count += 1;
        }
        self.battery += s.energy;
        self.steps += 1;
        self.executed += usize::from(!s.idle);
        self.last = s.pose;
        self.escaped = s.escaped;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modelling::aem::DEFAULT_ACTION_TOLERANCE;
    use crate::random::rng::rng_from_seed;
    use crate::simulation::controller::{Controller, INPUTS};
    use crate::simulation::robot::{Motion, RawRobot};
    use crate::simulation::room::Room;
    use crate::simulation::trial::{RawTrial, TrialParams, run_trial};

    /// A controller that plays a fixed list of motor outputs, then repeats the last one.
    struct Script(Vec<[f64; 2]>, usize);
    impl Controller for Script {
        fn step(&mut self, _: &[f64; INPUTS]) -> [f64; 2] {
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
        TrialParams::from_raw(&trial, &robot, DEFAULT_ACTION_TOLERANCE).unwrap()
    }

    fn params(motion: Motion, steps: usize) -> TrialParams {
        let trial = RawTrial {
            noise: 0.0,
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
                noise: 0.0,
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
