//! A trial given as a log (its poses, motor outputs, actions and blocked moves, e.g. a robot's
//! or another simulator's) measured by the code that measures a simulated trial: the
//! evaluation's own [`TermsRecorder`] (with the mission's tracker and the user terms), fed
//! the log's steps as [`Step`]s, with the simulator's end at home and its idle rest. One
//! function, two sources: a simulated trial's own steps, written as a log and read back, give
//! its terms bit for bit (tested here and by `fuzzymotiv transfer`'s tests).

use crate::experiment::{Experiment, Run};
use crate::fitness::terms::FitnessTerms;
use crate::simulation::Readings;
use crate::simulation::controller::Mlp;
use crate::simulation::robot::{Action, Pose};
use crate::simulation::trial::{Step, StepObserver, Trajectory};

/// One executed step of a logged trial.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoggedStep {
    /// The pose at the end of the step (mm, rad, in the room's frame).
    pub pose: Pose,
    /// The readings the network was given (zeros when the log has none).
    pub sensors: Readings,
    /// The motor outputs `mL, mR` in [0, 1], when the log has them (`wheels` motion needs them
    /// for the energy; `actions` motion uses one unit per step whatever they are).
    pub motors: Option<[f64; 2]>,
    /// The action executed (`actions` motion) or recorded (`wheels`).
    pub action: Action,
    /// Whether the step's move was blocked by a wall (the simulator's collision).
    pub collided: bool,
}

/// What a logged trial measures: the trial's terms and the study's measures beyond them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoggedTrial {
    /// The terms (a, g, b; the mission's and user terms when the experiment measures them;
    /// `l` = 0), as the simulator measures its own trial.
    pub terms: FitnessTerms,
    /// The steps executed before the trial ended (at home, at its mission, at `T` or at the
    /// log's end; the rest of the `T` steps idle).
    pub executed: usize,
    /// The executed steps whose move was blocked.
    pub blocked: usize,
    /// The step (1-based) that brought the escaped robot back into its home zone, when it did
    /// (the trial ends there with `trial.end_at_home`).
    pub home_at: Option<usize>,
}

impl LoggedStep {
    /// The executed steps of a simulated trajectory (the idle rest left out), as a log
    /// records them.
    pub fn of_trajectory(tr: &Trajectory) -> Vec<LoggedStep> {
        (0..tr.len())
            .take_while(|&t| !tr.idle[t])
            .map(|t| LoggedStep {
                pose: tr.poses[t + 1],
                sensors: tr.sensors[t],
                motors: Some(tr.motors[t]),
                action: tr.actions[t],
                collided: tr.collisions[t],
            })
            .collect()
    }
}

impl Experiment {
    /// The test run `test` of `network` in `room` on the AEM test streams of `run` (the very
    /// trial [`Experiment::environment_modelling`] measures for `test_runs.csv`), with its
    /// whole trajectory and its terms.
    pub fn test_run(
        &self,
        network: &Mlp,
        run: &Run,
        room: usize,
        test: usize,
    ) -> (Trajectory, FitnessTerms) {
        let seed = self.streams().aem_test(run.tag, self.room_key(room), test);
        self.traced_trial(network, room, seed)
    }

    /// One evaluation trial of `network` in `room` on the stream `seed`, with its whole
    /// trajectory and its terms.
    pub fn traced_trial(
        &self,
        network: &Mlp,
        room: usize,
        seed: u64,
    ) -> (Trajectory, FitnessTerms) {
        let arena = &self.arenas[room];
        let mut trajectory = Trajectory::starting_at(arena.room().home, self.trial.steps());
        let (terms, _, _) = self.observed_trial(&mut network.clone(), room, seed, &mut trajectory);
        (trajectory, terms)
    }

    /// Measures the logged trial `steps` in room `room` (an index of [`Experiment::arenas`])
    /// as [`Experiment::trial`] measures a simulated one: each step becomes the simulator's
    /// [`Step`] (energy by the motion model from the logged motor outputs, escape from the
    /// home zone); the trial ends after the step that brings an escaped robot back home (with
    /// `trial.end_at_home`), when its mission ends it, or after `T` steps; the steps left of
    /// `T` are idle, as the simulator reports them. Steps of the log beyond the end are not
    /// counted.
    pub fn logged_trial(&self, room: usize, steps: &[LoggedStep]) -> LoggedTrial {
        let arena = &self.arenas[room];
        let (home, zone) = (arena.room().home, arena.room().home_zone);
        let (motion, v_max) = (self.trial.robot().motion(), self.trial.robot().v_max());
        let sensors = arena.sensors();
        let total = self.trial.steps();
        let mut recorder = self.recorder(arena);
        let mut trajectory = Trajectory::starting_at(home, total);
        let mut observer = (&mut recorder, &mut trajectory);
        let (mut escaped, mut last, mut home_at, mut executed, mut blocked) =
            (false, home, None, 0, 0);
        for (t, s) in steps.iter().take(total).enumerate() {
            let inside = zone.contains(s.pose.position());
            escaped |= !inside;
            let motors = s.motors.unwrap_or([0.5; 2]);
            let speeds = motors.map(|m| (2.0 * m - 1.0) * v_max);
            observer.observe(&Step {
                t,
                sensors: s.sensors,
                motors,
                speeds,
                pose: s.pose,
                collided: s.collided,
                cell: None,
                action: s.action,
                idle: false,
                energy: motion.energy(speeds, v_max),
                escaped,
            });
            (last, executed) = (s.pose, t + 1);
            blocked += usize::from(s.collided);
            let back = escaped && inside;
            if back && home_at.is_none() {
                home_at = Some(t + 1);
            }
            if (self.trial.end_at_home() && back) || observer.finished() {
                break;
            }
        }
        for t in executed..total {
            observer.observe(&Step::idle(t, sensors, last, None, escaped));
        }
        let mut terms = self.recorded_terms(&recorder);
        self.user_values(arena, &trajectory, &mut terms);
        LoggedTrial {
            terms,
            executed,
            blocked,
            home_at,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::RawConfig;
    use crate::experiment::setup::{BuiltinRoomsOnly, Setup};

    /// The experiment of `toml` (built-in rooms).
    fn experiment(toml: &str) -> Experiment {
        let raw = RawConfig::parse(toml, "test.toml", &[]).unwrap();
        Setup::resolve(raw, "test.toml", &BuiltinRoomsOnly)
            .unwrap()
            .experiment
    }

    /// A simulated trial's own steps, measured as a log, give its terms bit for bit (the
    /// simulator's end at home and idle rest included), for both motion models.
    #[test]
    fn a_simulated_trials_steps_measured_as_a_log_give_its_terms() {
        for motion in ["actions", "wheels"] {
            let exp = experiment(&format!(
                "rooms = [\"H\", \"square\"]\n[robot]\nmotion = \"{motion}\"\n[trial]\nsteps = 300\n"
            ));
            let network = exp.network(&vec![0.3; exp.shape().genome_len()]).unwrap();
            for room in 0..2 {
                for seed in 0..6 {
                    let run = exp.traced_trial(&network, room, seed);
                    let logged = exp.logged_trial(room, &LoggedStep::of_trajectory(&run.0));
                    assert_eq!(logged.terms, run.1, "{motion} room {room} seed {seed}");
                    assert_eq!(logged.executed, run.0.executed());
                    let blocked = (0..run.0.len())
                        .filter(|&t| !run.0.idle[t] && run.0.collisions[t])
                        .count();
                    assert_eq!(logged.blocked, blocked);
                }
            }
        }
    }
}
