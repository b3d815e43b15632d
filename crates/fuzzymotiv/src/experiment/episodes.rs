//! Trials driven from outside ([`Episode`]) on the experiment's streams: the room-modelling
//! instance run of [`Experiment::instance_run`] (what `fuzzymotiv replay` and Python's
//! `fm.simulate` run) step by step, under any base seed.

use crate::experiment::{Experiment, Run};
use crate::fitness::episode::Episode;
use crate::random::rng::{Rng64, rng_from_seed};
use crate::random::seed::Streams;
use crate::simulation::trial::Arena;

impl Experiment {
    /// The seed of the instance run of `run` in `room` ([`Streams::aem_instance`]) had the
    /// experiment's base seed been `base`: with `base = self.seed()`, the stream of
    /// [`Experiment::instance_run`].
    pub fn instance_seed(&self, base: u64, run: &Run, room: usize) -> u64 {
        Streams::new(base).aem_instance(run.tag, self.room_key(room))
    }

    /// The instance run of `run` in `room` under base seed `base`, driven from outside: with
    /// a network's outputs for its inputs, the trial [`Experiment::instance_run`] runs (for
    /// `base = self.seed()`), its terms at the end included. `arena` is the room's arena or an
    /// owning handle to a copy of it (`Arc<Arena>`).
    pub fn episode<A>(&self, arena: A, base: u64, run: &Run, room: usize) -> Episode<A, Rng64>
    where
        A: std::borrow::Borrow<Arena> + Clone,
    {
        let seed = self.instance_seed(base, run, room);
        Episode::new(arena, self.homing, rng_from_seed(seed))
    }
}

#[cfg(test)]
mod tests {
    use crate::experiment::testing::experiment;
    use crate::random::rng::{rng_from_seed, uniform};
    use crate::simulation::controller::Controller;
    use crate::simulation::trial::{StepObserver, Trajectory};
    use std::sync::Arc;

    /// Driving the episode with the network's outputs is the instance run, bit for bit: the
    /// trajectory, the terms and F, with a borrowed and an owned arena.
    #[test]
    fn an_episode_driven_by_the_network_is_the_instance_run() {
        let exp = experiment(&["trial.steps=120"]);
        let run = exp.runs().remove(0);
        let mut rng = rng_from_seed(4);
        for room in 0..exp.arenas().len() {
            let genome: Vec<f64> = (0..exp.shape().genome_len())
                .map(|_| uniform(&mut rng, -3.0, 3.0))
                .collect();
            let net = exp.network(&genome).unwrap();
            let want = exp.instance_run(&net, &run, room);
            let arena = Arc::new(exp.arenas()[room].clone());
            let mut ep = exp.episode(arena, exp.seed(), &run, room);
            let home = exp.arenas()[room].room().home;
            let mut tr = Trajectory::starting_at(home, 120);
            let mut driver = net.clone();
            while !ep.is_over() {
                let mut inputs = ep.observe();
                inputs.iter_mut().for_each(|v| *v /= 1023.0);
                tr.observe(&ep.step(driver.step(&inputs)));
            }
            ep.run().rest().for_each(|s| tr.observe(&s));
            assert_eq!(tr, want.trajectory, "room {room}");
            assert_eq!(ep.terms(), want.terms);
            assert_eq!(exp.fuzzy_fitness(&ep.terms()).to_bits(), want.f.to_bits());
        }
    }
}
