//! A trial driven from outside with its fitness terms kept up to date: the
//! [`TrialRun`] stepper and the [`TermsRecorder`] that [`simulate`]'s callers use, fed the
//! same steps (the idle rest after an end at home included), so the terms at the end are
//! those of the same trial run by [`simulate`].
//!
//! [`simulate`]: crate::simulation::trial::simulate

use std::borrow::Borrow;

use crate::fitness::terms::{FitnessTerms, Homing, TermsRecorder};
use crate::random::rng::Rng;
use crate::simulation::robot::Action;
use crate::simulation::stepper::TrialRun;
use crate::simulation::trial::{Arena, Step, StepObserver};

/// A [`TrialRun`] and its [`TermsRecorder`]: each step taken is recorded; when the run is
/// over (at `T`, or at home with the idle rest of the `T` steps recorded as [`simulate`]
/// reports them), [`Episode::terms`] are the trial's terms a, g, b (l = 0).
///
/// [`simulate`]: crate::simulation::trial::simulate
#[derive(Debug, Clone)]
pub struct Episode<A: Borrow<Arena> + Clone, R: Rng> {
    run: TrialRun<A, R>,
    recorder: TermsRecorder<A>,
}

impl<A: Borrow<Arena> + Clone, R: Rng> Episode<A, R> {
    /// A trial in `arena` with the random stream `rng`, its homing term measured by `homing`.
    pub fn new(arena: A, homing: Homing, rng: R) -> Self {
        Episode {
            recorder: TermsRecorder::new(arena.clone(), homing),
            run: TrialRun::new(arena, rng),
        }
    }

    /// The trial.
    pub fn run(&self) -> &TrialRun<A, R> {
        &self.run
    }

    /// Whether no step is left ([`TrialRun::is_over`]).
    pub fn is_over(&self) -> bool {
        self.run.is_over()
    }

    /// The sensor values of the next step ([`TrialRun::observe`]).
    pub fn observe(&mut self) -> crate::simulation::Readings {
        self.run.observe()
    }

    /// The sensor values of the next step, borrowed ([`TrialRun::observed`]).
    pub fn observed(&mut self) -> &[f64] {
        self.run.observed()
    }

    /// The next step with motor outputs `motors` ([`TrialRun::step`]), recorded.
    pub fn step(&mut self, motors: [f64; 2]) -> Step {
        let over = self.run.is_over();
        let step = self.run.step(motors);
        self.record(over, &step);
        step
    }

    /// The next step executing `action` ([`TrialRun::step_action`]), recorded.
    pub fn step_action(&mut self, action: Action) -> Step {
        let over = self.run.is_over();
        let step = self.run.step_action(action);
        self.record(over, &step);
        step
    }

    /// The terms so far (`l` = 0); the trial's terms once it is over.
    pub fn terms(&self) -> FitnessTerms {
        self.recorder.finish()
    }

    /// Records a step taken (not one asked for after the end), and the idle rest when it ended
    /// the trial at home.
    fn record(&mut self, was_over: bool, step: &Step) {
        if was_over {
            return;
        }
        self.recorder.observe(step);
        for idle in self.run.rest() {
            self.recorder.observe(&idle);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::rng::{rng_from_seed, uniform};
    use crate::simulation::controller::{Controller, Mlp, MlpShape};
    use crate::simulation::room::Room;
    use crate::simulation::trial::{TrialParams, simulate};

    /// Out of the home zone and back: 30 steps straight, a turn of 180°, then straight.
    #[derive(Clone)]
    struct OutAndBack(usize);
    impl Controller for OutAndBack {
        fn step(&mut self, _: &[f64]) -> [f64; 2] {
            self.0 += 1;
            if self.0 == 31 { [0.0, 0.0] } else { [1.0, 1.0] }
        }
    }

    /// The terms of `driver`'s trial, by `simulate` with a `TermsRecorder` and by an episode;
    /// and whether it ended at home.
    fn both<C: Controller + Clone>(
        arena: &Arena,
        mut driver: C,
    ) -> (FitnessTerms, FitnessTerms, bool) {
        let mut rec = TermsRecorder::new(arena, Homing::Escape);
        simulate(arena, &mut driver.clone(), &mut rng_from_seed(9), &mut rec);
        let mut ep = Episode::new(arena, Homing::Escape, rng_from_seed(9));
        while !ep.is_over() {
            let mut inputs = ep.observe();
            inputs.iter_mut().for_each(|v| *v /= 1023.0);
            ep.step(driver.step(&inputs));
        }
        (ep.terms(), rec.finish(), ep.run().ended_at_home())
    }

    /// The episode's terms at the end are those of `simulate` with a `TermsRecorder`, trials
    /// that end at home included.
    #[test]
    fn terms_at_the_end_are_simulates() {
        for room in ["H", "T", "L"] {
            let arena = Arena::new(Room::builtin(room).unwrap(), &TrialParams::default());
            for seed in 0..8 {
                let mut rng = rng_from_seed(seed);
                let shape = MlpShape::default();
                let genome: Vec<f64> = (0..shape.genome_len())
                    .map(|_| uniform(&mut rng, -4.0, 4.0))
                    .collect();
                let net = Mlp::from_genome(shape, &genome).unwrap();
                let (got, want, _) = both(&arena, net);
                assert_eq!(got, want, "{room} seed {seed}");
            }
        }
        let square = Arena::new(Room::builtin("square").unwrap(), &TrialParams::default());
        let (got, want, home) = both(&square, OutAndBack(0));
        assert!(home, "the scripted trial did not end at home");
        assert_eq!(got, want);
        // The idle rest counts in b: 47 executed steps of 400.
        assert!(got.g > 0.8 && got.b < 0.2, "{got:?}");
    }
}
