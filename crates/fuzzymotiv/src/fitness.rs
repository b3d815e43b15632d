//! The fitness terms of SPEC §9: exploration `a`, homing `g`, orientation `l`, battery `b`.

use serde::{Deserialize, Serialize};

use crate::trial::{Arena, CELL, Step, StepObserver, Trajectory, TrialParams};

/// The four fitness values Y = (a, g, l, b), each in [0, 1], higher is better for the fuzzy
/// combination (with `energy = "use"`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct FitnessTerms {
    /// Exploration: visited cells / optimum.
    pub a: f64,
    /// Homing: 1 − d_final / d_max.
    pub g: f64,
    /// Orientation (recognition); 0 during evolution unless online orientation is on.
    pub l: f64,
    /// Battery usage: mean (|sL| + |sR|) / (2·v_max) of the commanded speeds.
    pub b: f64,
}

impl FitnessTerms {
    /// As the array `[a, g, l, b]`.
    pub fn as_array(&self) -> [f64; 4] {
        [self.a, self.g, self.l, self.b]
    }

    /// Measures the terms of a recorded trajectory (`l` = 0).
    pub fn measure(arena: &Arena, params: &TrialParams, trajectory: &Trajectory) -> FitnessTerms {
        let mut rec = TermsRecorder::new(arena, params);
        for s in trajectory.steps() {
            rec.observe(&s);
        }
        rec.finish()
    }
}

/// `optimum = min(reachable, floor(T·v_max·dt / 50) + 1)`: the cells a full-speed robot that
/// never revisits a cell could enter.
pub fn exploration_optimum(arena: &Arena, params: &TrialParams) -> usize {
    let by_speed =
        (params.steps as f64 * params.robot.v_max * params.dt / CELL).floor() as usize + 1;
    arena.reachable_cells().min(by_speed).max(1)
}

/// Accumulates the terms step by step (used inside evaluation without storing a trajectory).
#[derive(Debug, Clone)]
pub struct TermsRecorder<'a> {
    arena: &'a Arena,
    visited: Vec<bool>,
    visited_count: usize,
    battery: f64,
    steps: usize,
    last: crate::robot::Pose,
    v_max: f64,
    optimum: usize,
}

impl<'a> TermsRecorder<'a> {
    /// A recorder for a trial starting at home (the home cell counts as visited).
    pub fn new(arena: &'a Arena, params: &TrialParams) -> Self {
        let home = arena.room().home;
        let mut visited = vec![false; arena.cell_count()];
        visited[arena.cell_of(home.position())] = true;
        Self {
            arena,
            visited,
            visited_count: 1,
            battery: 0.0,
            steps: 0,
            last: home,
            v_max: params.robot.v_max,
            optimum: exploration_optimum(arena, params),
        }
    }

    /// Cells visited so far.
    pub fn visited(&self) -> usize {
        self.visited_count
    }

    /// The terms so far (`l` = 0).
    pub fn finish(&self) -> FitnessTerms {
        let a = (self.visited_count as f64 / self.optimum as f64).clamp(0.0, 1.0);
        let home = self.arena.room().home.position();
        let g = (1.0 - self.last.position().dist(home) / self.arena.d_max()).clamp(0.0, 1.0);
        let b = if self.steps == 0 {
            0.0
        } else {
            (self.battery / self.steps as f64).clamp(0.0, 1.0)
        };
        FitnessTerms { a, g, l: 0.0, b }
    }
}

impl StepObserver for TermsRecorder<'_> {
    #[inline]
    fn observe(&mut self, s: &Step) {
        let k = s
            .cell
            .unwrap_or_else(|| self.arena.cell_of(s.pose.position()));
        if !self.visited[k] {
            self.visited[k] = true;
            self.visited_count += 1;
        }
        self.battery += (s.speeds[0].abs() + s.speeds[1].abs()) / (2.0 * self.v_max);
        self.steps += 1;
        self.last = s.pose;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::controller::{Controller, INPUTS};
    use crate::rng::rng_from_seed;
    use crate::room::Room;
    use crate::trial::run_trial;

    struct Fixed([f64; 2]);
    impl Controller for Fixed {
        fn step(&mut self, _: &[f64; INPUTS]) -> [f64; 2] {
            self.0
        }
    }

    fn terms(room: &str, motors: [f64; 2], steps: usize) -> FitnessTerms {
        let params = TrialParams {
            noise: 0.0,
            steps,
            ..TrialParams::default()
        };
        let arena = Arena::new(Room::builtin(room).unwrap(), &params);
        let tr = run_trial(&arena, &mut Fixed(motors), &params, &mut rng_from_seed(3));
        FitnessTerms::measure(&arena, &params, &tr)
    }

    #[test]
    fn robot_standing_still() {
        let t = terms("square", [0.5, 0.5], 400);
        // Optimum = min(100 reachable, floor(400·80·0.1/50)+1 = 65) = 65; one cell visited.
        assert_eq!(t.a, 1.0 / 65.0);
        assert_eq!(t.g, 1.0);
        assert_eq!(t.b, 0.0);
        assert_eq!(t.l, 0.0);
    }

    #[test]
    fn robot_driving_straight() {
        // From (150, 150) heading +x at 8 mm/step for 20 steps: 160 mm, ending at x = 310.
        let t = terms("square", [1.0, 1.0], 20);
        // Cells entered: x-cells 3,4,5,6 (150 → 310 crosses 200, 250, 300): 4 cells.
        // Optimum = floor(20·8/50)+1 = 4.
        assert_eq!(t.a, 1.0);
        // d_max from (150,150) is the far corner (600,600): 450·√2.
        let d_max = 450.0 * 2f64.sqrt();
        assert!((t.g - (1.0 - 160.0 / d_max)).abs() < 1e-9, "{t:?}");
        assert_eq!(t.b, 1.0);
    }

    #[test]
    fn recorder_and_trajectory_agree() {
        let params = TrialParams::default();
        let arena = Arena::new(Room::builtin("H").unwrap(), &params);
        let tr = run_trial(
            &arena,
            &mut Fixed([0.9, 0.7]),
            &params,
            &mut rng_from_seed(9),
        );
        let mut rec = TermsRecorder::new(&arena, &params);
        crate::trial::simulate(
            &arena,
            &mut Fixed([0.9, 0.7]),
            &params,
            &mut rng_from_seed(9),
            &mut rec,
        );
        assert_eq!(rec.finish(), FitnessTerms::measure(&arena, &params, &tr));
    }
}
