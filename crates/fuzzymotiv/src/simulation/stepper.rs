//! A trial driven from outside, one step at a time: [`TrialRun`] takes exactly the steps of
//! [`simulate`](crate::simulation::trial::simulate) (the same sensors, noise streams, motion
//! model and end at home), but the motor outputs come from the caller (an RL agent, a
//! Gymnasium environment) instead of a [`Controller`](crate::simulation::controller::Controller).
//!
//! ```
//! use fuzzymotiv::random::rng_from_seed;
//! use fuzzymotiv::simulation::Room;
//! use fuzzymotiv::simulation::TrialRun;
//! use fuzzymotiv::simulation::{Arena, TrialParams};
//!
//! let arena = Arena::new(Room::builtin("square").unwrap(), &TrialParams::default());
//! let mut run = TrialRun::new(&arena, rng_from_seed(7));
//! while !run.is_over() {
//!     let ir = run.observe(); // 8 IR values, 0–1023, noise included
//!     let turn = ir[2] + ir[3] > 500.0;
//!     run.step(if turn { [0.2, 0.9] } else { [1.0, 1.0] });
//! }
//! // T = 400 steps, or fewer when the robot comes back into its home zone (`end_at_home`).
//! assert!(run.t() <= arena.params().steps());
//! ```

use std::borrow::Borrow;

use crate::random::rng::Rng;
use crate::simulation::memo::{memo_live, with_table};
use crate::simulation::robot::{Action, Motion, Pose};
use crate::simulation::sensor::{MAX_SENSORS, Readings};
use crate::simulation::trial::{Arena, Sensed, Step, Walk, inputs_of};

/// A trial in an arena (`A`: `&Arena`, or an owning handle such as `Arc<Arena>`), with the
/// arena's parameters and the random stream `rng` (the one [`simulate`] would be given), its
/// steps taken one by one by [`TrialRun::step`].
///
/// Each step draws, as in [`simulate`], the sensor noise when its sensors are first read
/// ([`TrialRun::observe`], or [`TrialRun::step`] itself), then the wheel noise: driving a run
/// with a network's outputs for its inputs gives [`simulate`]'s trajectory bit for bit. The run
/// is over after `T` steps, or (with `end_at_home`) after the step that brings an escaped robot
/// back into the home zone; the idle steps [`simulate`] reports for the rest of the `T` are
/// [`TrialRun::rest`]. With `actions` motion it shares the thread's memo of sightings with
/// [`simulate`] (a pure cache: the same bits as a cast).
///
/// [`simulate`]: crate::simulation::trial::simulate
#[derive(Debug, Clone)]
pub struct TrialRun<A: Borrow<Arena>, R: Rng> {
    arena: A,
    rng: R,
    walk: Walk,
    /// Steps taken.
    t: usize,
    /// Whether the trial ended at home.
    home: bool,
    /// The sensors of step `t`, once read (their noise drawn).
    sensed: Option<Sensed>,
}

impl<A: Borrow<Arena>, R: Rng> TrialRun<A, R> {
    /// A trial at the room's home pose, no step taken.
    pub fn new(arena: A, rng: R) -> Self {
        let walk = Walk::at_home(arena.borrow());
        TrialRun {
            arena,
            rng,
            walk,
            t: 0,
            home: false,
            sensed: None,
        }
    }

    /// The arena.
    pub fn arena(&self) -> &Arena {
        self.arena.borrow()
    }

    /// Steps taken so far (0 ≤ t ≤ T).
    pub fn t(&self) -> usize {
        self.t
    }

    /// The robot's pose now.
    pub fn pose(&self) -> Pose {
        self.walk.pose()
    }

    /// Whether the trial ended at home (`end_at_home` and an escaped robot back home).
    pub fn ended_at_home(&self) -> bool {
        self.home
    }

    /// Whether no step is left: ended at home, or all `T` steps taken.
    pub fn is_over(&self) -> bool {
        self.home || self.t >= self.arena().params().steps()
    }

    /// The sensor values (0 to the robot's `reading_max`, noise included) that step `t`
    /// reads, one per sensor; the first call of a step draws its sensor noise, later calls
    /// return the same values. All 0 once the run is over (as an idle step records).
    pub fn observe(&mut self) -> Readings {
        if self.is_over() {
            return Readings::zeros(self.arena().sensors());
        }
        self.sensed().sensors
    }

    /// [`TrialRun::observe`] without copying the readings out: the same values (all 0 once
    /// the run is over), one per sensor, borrowed from the run.
    pub fn observed(&mut self) -> &[f64] {
        if self.is_over() {
            let n = self.arena().sensors();
            return &NO_READINGS[..n];
        }
        &self.sensed().sensors
    }

    /// [`TrialRun::observe`] as the network's inputs: each value / `reading_max`, in [0, 1].
    pub fn inputs(&mut self) -> Readings {
        let max = self.arena().params().robot().spec().reading_max();
        inputs_of(&self.observe(), max)
    }

    /// Step `t` with the motor outputs `mL, mR` ∈ [0, 1] (what the network would give for
    /// [`TrialRun::inputs`]); its record. Once the run is over, the idle step `t` (nothing
    /// moves, no noise is drawn) while `t < T`, then the last idle step again.
    pub fn step(&mut self, motors: [f64; 2]) -> Step {
        self.advance(motors, None)
    }

    /// Step `t` executing `action` (a [`crate::simulation::robot::Action`] chosen from
    /// outside, e.g. a discrete agent's): with `actions` motion the action is executed as
    /// given, with the motor outputs of `motors_for` recorded and the wheel noise drawn as
    /// usual; with `wheels` motion it is the step with the motor outputs `motors_for`.
    pub fn step_action(&mut self, action: Action) -> Step {
        self.advance(motors_for(action), Some(action))
    }

    /// The idle steps that follow the end at home up to `T` (none if the run did not end at
    /// home): what [`simulate`](crate::simulation::trial::simulate) reports after the last
    /// step, for observers such as the fitness terms' recorder.
    pub fn rest(&self) -> impl Iterator<Item = Step> + '_ {
        let end = if self.home {
            self.arena().params().steps()
        } else {
            self.t
        };
        let n = self.arena().sensors();
        (self.t..end).map(move |t| self.walk.idle(t, n))
    }

    /// The sensors of step `t`, read (and their noise drawn) at the first call. Written
    /// straight into the run and lent out: a `Sensed` holds [`MAX_SENSORS`] readings, and
    /// passing it by value through the memo's closure copied it several times a step.
    ///
    /// [`MAX_SENSORS`]: crate::simulation::sensor::MAX_SENSORS
    fn sensed(&mut self) -> &Sensed {
        if self.sensed.is_none() {
            let (arena, walk, rng) = (self.arena.borrow(), &self.walk, &mut self.rng);
            let slot = &mut self.sensed;
            // With `actions` motion the thread's memo of sightings, as `simulate` uses it: a
            // pose seen before (by this run, another run or a trial in the same arena) is
            // not cast again; a lookup returns the very bits the cast gave.
            let owner = match arena.params().robot().motion() {
                Motion::Actions => arena.memo_owner(),
                Motion::Wheels => None,
            };
            match owner {
                Some(owner) => with_table(owner, memo_live, |t| {
                    *slot = Some(walk.sense(arena, rng, t));
                }),
                None => *slot = Some(walk.sense(arena, rng, None)),
            }
        }
        self.sensed.as_ref().expect("read above")
    }

    fn advance(&mut self, motors: [f64; 2], forced: Option<Action>) -> Step {
        if self.is_over() {
            let last = self.arena().params().steps().saturating_sub(1);
            return self.walk.idle(self.t.min(last), self.arena().sensors());
        }
        self.sensed();
        let sensed = self.sensed.as_ref().expect("read above");
        let arena = self.arena.borrow();
        let (step, home) = (self.walk).act(self.t, arena, sensed, motors, forced, &mut self.rng);
        self.sensed = None;
        self.t += 1;
        self.home = arena.params().end_at_home() && home;
        step
    }
}

/// The readings of a run that is over ([`TrialRun::observed`]): 0 for every sensor.
static NO_READINGS: [f64; MAX_SENSORS] = [0.0; MAX_SENSORS];

/// The motor outputs `mL, mR` recorded for an action chosen from outside
/// ([`TrialRun::step_action`]), each well inside its label's region: `straight` (1, 1),
/// `left30` (0.5, 1), `right30` (1, 0.5), `turn180` (0, 0).
pub fn motors_for(action: Action) -> [f64; 2] {
    match action {
        Action::Straight => [1.0, 1.0],
        Action::Left30 => [0.5, 1.0],
        Action::Right30 => [1.0, 0.5],
        Action::Turn180 => [0.0, 0.0],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::rng::rng_from_seed;
    use crate::simulation::controller::{Controller, Mlp, MlpShape};
    use crate::simulation::robot::{Motion, RawRobot};
    use crate::simulation::room::Room;
    use crate::simulation::trial::{RawTrial, Trajectory, TrialParams, run_trial};
    use std::sync::Arc;

    fn arena(room: &str, motion: Motion, end_at_home: bool) -> Arena {
        let raw = RawTrial {
            end_at_home,
            ..RawTrial::default()
        };
        let robot = RawRobot {
            motion,
            ..RawRobot::default()
        };
        let params =
            TrialParams::from_raw(&raw, &robot, crate::simulation::RobotSpec::khepera(), 0.25)
                .unwrap();
        Arena::new(Room::builtin(room).unwrap(), &params)
    }

    /// A network with weights from a seed (spread so it turns and reaches walls).
    fn network(seed: u64) -> Mlp {
        let shape = MlpShape::default();
        let mut rng = rng_from_seed(seed);
        let genome: Vec<f64> = (0..shape.genome_len())
            .map(|_| crate::random::rng::uniform(&mut rng, -4.0, 4.0))
            .collect();
        Mlp::from_genome(shape, &genome).unwrap()
    }

    /// Out of the home zone and back: `out` steps straight, a turn of 180°, then straight.
    #[derive(Clone)]
    struct OutAndBack {
        t: usize,
        out: usize,
    }
    impl Controller for OutAndBack {
        fn step(&mut self, _: &[f64]) -> [f64; 2] {
            self.t += 1;
            if self.t == self.out + 1 {
                [0.0, 0.0]
            } else {
                [1.0, 1.0]
            }
        }
    }

    /// Drives a run with `net` and records it as `simulate` records a trial.
    fn driven<A: Borrow<Arena>>(arena: A, net: &mut dyn Controller, seed: u64) -> Trajectory {
        let home = arena.borrow().room().home;
        let steps = arena.borrow().params().steps();
        let mut run = TrialRun::new(arena, rng_from_seed(seed));
        let mut tr = Trajectory::starting_at(home, steps);
        use crate::simulation::trial::StepObserver;
        while !run.is_over() {
            let inputs = run.inputs();
            assert_eq!(run.inputs(), inputs, "a second look draws no noise");
            let step = run.step(net.step(&inputs));
            tr.observe(&step);
        }
        run.rest().for_each(|s| tr.observe(&s));
        tr
    }

    /// The stepper takes simulate's steps, bit for bit: both motion models, with and without
    /// the end at home, the memo on or off, several networks and seeds.
    #[test]
    fn driving_with_a_network_gives_simulates_trajectory() {
        let mut ended = 0;
        for motion in [Motion::Actions, Motion::Wheels] {
            for (room, end) in [("H", true), ("T", true), ("square", false)] {
                let a = arena(room, motion, end);
                for seed in 0..6 {
                    let mut net = network(seed);
                    let want = run_trial(&a, &mut net.clone(), &mut rng_from_seed(seed + 100));
                    let got = driven(&a, &mut net, seed + 100);
                    assert_eq!(got, want, "{room} {motion:?} seed {seed}");
                    let no_memo = Arc::new(a.clone().without_memo());
                    assert_eq!(driven(no_memo, &mut network(seed), seed + 100), want);
                }
            }
        }
        // Trials that end at home: the idle rest too.
        let a = arena("square", Motion::Actions, true);
        for out in [25, 30, 40] {
            let script = OutAndBack { t: 0, out };
            let want = run_trial(&a, &mut script.clone(), &mut rng_from_seed(out as u64));
            assert!(want.idle.last() == Some(&true), "out {out}: not back home");
            assert_eq!(driven(&a, &mut script.clone(), out as u64), want);
            ended += 1;
        }
        assert!(ended > 0);
    }

    /// A chosen action is executed as given (`actions` motion): a left turn is +30°.
    #[test]
    fn step_action_executes_the_action() {
        let a = arena("square", Motion::Actions, true);
        let mut run = TrialRun::new(&a, rng_from_seed(1));
        let h0 = run.pose().heading;
        let s = run.step_action(Action::Left30);
        assert_eq!((s.action, s.motors), (Action::Left30, [0.5, 1.0]));
        assert!((s.pose.heading - h0 - std::f64::consts::FRAC_PI_6).abs() < 1e-12);
        let s = run.step_action(Action::Straight);
        assert_eq!(s.action, Action::Straight);
        assert!(s.pose.x != a.room().home.x || s.pose.y != a.room().home.y || s.collided);
    }

    /// After the last step: idle steps, no noise drawn, t stays at T.
    #[test]
    fn steps_after_the_end_are_idle() {
        let a = arena("square", Motion::Wheels, false);
        let mut run = TrialRun::new(&a, rng_from_seed(3));
        for _ in 0..400 {
            assert!(!run.step([0.9, 0.7]).idle);
        }
        assert!(run.is_over());
        let s = run.step([1.0, 1.0]);
        assert!(s.idle && s.t == 399 && run.t() == 400);
        assert_eq!(run.observe(), [0.0; 8]);
        assert_eq!(run.rest().count(), 0);
    }

    /// `observed` lends the values `observe` returns, drawing no noise of its own: a run read
    /// through it takes the steps of a run read through `observe` (both motions, past the end
    /// too, where both are all 0).
    #[test]
    fn observed_lends_what_observe_returns() {
        for motion in [Motion::Actions, Motion::Wheels] {
            let a = arena("H", motion, false);
            let mut lent = TrialRun::new(&a, rng_from_seed(8));
            let mut copied = TrialRun::new(&a, rng_from_seed(8));
            let mut drive = rng_from_seed(9);
            let mut lit = 0;
            for _ in 0..410 {
                let values = lent.observed().to_vec();
                assert_eq!(
                    values[..],
                    copied.observe()[..],
                    "{motion:?} t {}",
                    lent.t()
                );
                assert_eq!(
                    lent.observed(),
                    values.as_slice(),
                    "a second look draws nothing"
                );
                lit += usize::from(values.iter().any(|&v| v > 0.0));
                let motors = [0, 1].map(|_| crate::random::rng::uniform(&mut drive, 0.0, 1.0));
                assert_eq!(lent.step(motors), copied.step(motors));
            }
            assert!(
                lent.is_over() && lit > 20,
                "{motion:?}: {lit} steps near walls"
            );
        }
    }

    /// With `actions` motion a run keeps what it saw near walls in the thread's memo of
    /// sightings, as `simulate` does: each pose it read its sensors at near a wall is there
    /// afterwards (the memo's recall does not compute it again). The Gymnasium envs step
    /// trials through `TrialRun`; without the memo every step near a wall was cast anew.
    #[test]
    fn a_run_remembers_its_sightings_near_walls() {
        use crate::simulation::geom::Vec2;
        let a = arena("H", Motion::Actions, false);
        let owner = a.memo_owner().expect("the Khepera's arena has a memo");
        let mut run = TrialRun::new(&a, rng_from_seed(5));
        let mut drive = rng_from_seed(6);
        // Each pose once (a robot against a wall stands on the same poses again and again).
        let mut near_walls = Vec::new();
        while !run.is_over() {
            let (pos, dir) = (run.pose().position(), run.walk.dir());
            let key = (pos.x.to_bits(), pos.y.to_bits(), dir);
            let seen = near_walls
                .iter()
                .any(|&(p, d): &(Vec2, usize)| (p.x.to_bits(), p.y.to_bits(), d) == key);
            if run.observe().iter().any(|&v| v > 0.0) && !seen {
                near_walls.push((pos, dir));
            }
            let motors = [0, 1].map(|_| crate::random::rng::uniform(&mut drive, 0.0, 1.0));
            run.step(motors);
        }
        assert!(
            near_walls.len() >= 30,
            "{} poses near walls",
            near_walls.len()
        );
        let computed = with_table(owner, memo_live, |table| {
            let table = table.expect("no trial is borrowing the tables");
            (near_walls.iter())
                .filter(|&&(pos, dir)| {
                    let mut computed = false;
                    table.recall(pos, dir, &[], || {
                        computed = true;
                        crate::simulation::memo::Sight::CLEAR
                    });
                    computed
                })
                .count()
        });
        // A set holds a pose's two newest neighbours by hash: a few may have been replaced.
        assert!(
            computed * 10 <= near_walls.len(),
            "{computed} of {} not remembered",
            near_walls.len()
        );
    }
}
