//! The facade: a validated [`Experiment`] built once from a [`RawConfig`] and its rooms, which
//! evolves populations ([`Experiment::evolve`]) and models rooms from the best robot's actions
//! ([`Experiment::environment_modelling`]).

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::aem::{Action, Encoder, environment_vector};
use crate::config::{Coefficients, ConfigError, EnergyMode, OrientationMode, RawConfig, Training};
use crate::controller::{Mlp, MlpShape};
use crate::fitness::{FitnessTerms, Homing, TermsRecorder};
use crate::fuzzy::{FuzzyError, Motivations, TskFitness};
use crate::ga::{GaParams, Genome, Stats, initial_population, next_generation};
use crate::recognition::{Confusion, Recognizer, nearest_unique};
use crate::rng::rng_from_seed;
use crate::robot::{KHEPERA_RADIUS, Khepera};
use crate::room::Room;
use crate::seed::{derive, hash_str, purpose};
use crate::som::{SomError, SomParams};
use crate::trial::{ActionLog, Arena, TrialParams, simulate};

/// Validated AEM parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AemParams {
    /// Whether AEM runs after evolution.
    pub enabled: bool,
    /// Action sequence → vector encoding.
    pub encoder: Encoder,
    /// SOM training parameters.
    pub som: SomParams,
    /// r-node gate (nodes).
    pub threshold: usize,
    /// Test runs per room.
    pub test_runs: usize,
    /// Action classification tolerance.
    pub action_tolerance: f64,
}

/// A validated experiment: nothing downstream re-checks these values.
#[derive(Debug, Clone)]
pub struct Experiment {
    /// Name.
    pub name: String,
    /// Base seed.
    pub seed: u64,
    /// Rooms, prepared for trials.
    pub arenas: Vec<Arena>,
    /// Training protocol.
    pub training: Training,
    /// Motivations X.
    pub motivations: Motivations,
    /// The TSK evaluator.
    pub fuzzy: TskFitness,
    /// GA parameters.
    pub ga: GaParams,
    /// Trial parameters.
    pub trial: TrialParams,
    /// Network shape.
    pub shape: MlpShape,
    /// Battery term direction.
    pub energy: EnergyMode,
    /// When `l` is measured.
    pub orientation: OrientationMode,
    /// How `g` is measured.
    pub homing: Homing,
    /// Environment modelling.
    pub aem: AemParams,
}

fn check(ok: bool, field: &str, reason: impl FnOnce() -> String) -> Result<(), (String, String)> {
    if ok {
        Ok(())
    } else {
        Err((field.to_string(), reason()))
    }
}

fn unit(v: f64) -> bool {
    v.is_finite() && (0.0..=1.0).contains(&v)
}

impl Experiment {
    /// Validates `raw` with its rooms already loaded (`rooms[i]` for `raw.rooms[i]`).
    pub fn new(
        raw: &RawConfig,
        rooms: Vec<Room>,
        source_name: &str,
    ) -> Result<Experiment, ConfigError> {
        Self::build(raw, rooms).map_err(|(field, reason)| ConfigError {
            source_name: source_name.to_string(),
            field,
            reason,
        })
    }

    fn build(raw: &RawConfig, rooms: Vec<Room>) -> Result<Experiment, (String, String)> {
        const BIG: usize = 1_000_000;
        let safe_name = !raw.name.is_empty()
            && raw.name.len() <= 100
            && raw.name != "."
            && raw.name != ".."
            && raw
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || "._-".contains(c));
        check(safe_name, "name", || {
            format!(
                "must be a plain name of letters, digits, '.', '_' or '-' (it names the output directory runs/NAME), got {:?}",
                raw.name
            )
        })?;
        check(!rooms.is_empty(), "rooms", || {
            "needs at least one room, e.g. rooms = [\"H\", \"T\", \"L\", \"square\", \"rectangle\"]"
                .into()
        })?;
        for (i, r) in rooms.iter().enumerate() {
            if let Some(j) = rooms[..i].iter().position(|o| o.name == r.name) {
                return Err((
                    format!("rooms[{i}]"),
                    format!(
                        "room name \"{}\" is used twice (also rooms[{j}]); names must be unique",
                        r.name
                    ),
                ));
            }
        }
        let m = &raw.motivations;
        let motivations = Motivations::new(m.curiosity, m.homing, m.orientation, m.energy)
            .map_err(|e| {
                let field = match &e {
                    FuzzyError::MotivationOutOfRange { name, .. } => format!("motivations.{name}"),
                    _ => "motivations".to_string(),
                };
                (field, e.to_string())
            })?;
        let ga = raw.ga;
        check((2..=BIG).contains(&ga.population), "ga.population", || {
            format!("must be an integer in 2..={BIG}, got {}", ga.population)
        })?;
        check(
            (1..=BIG).contains(&ga.generations),
            "ga.generations",
            || format!("must be an integer in 1..={BIG}, got {}", ga.generations),
        )?;
        check(ga.elite < ga.population, "ga.elite", || {
            format!(
                "must be smaller than ga.population ({}), got {}",
                ga.population, ga.elite
            )
        })?;
        check(
            ga.parent_fraction.is_finite() && ga.parent_fraction > 0.0 && ga.parent_fraction <= 1.0,
            "ga.parent_fraction",
            || format!("must be in (0, 1], got {}", ga.parent_fraction),
        )?;
        check(unit(ga.crossover), "ga.crossover", || {
            format!("must be a probability in [0, 1], got {}", ga.crossover)
        })?;
        check(unit(ga.mutation_rate), "ga.mutation_rate", || {
            format!("must be a probability in [0, 1], got {}", ga.mutation_rate)
        })?;
        check(
            ga.mutation_sigma.is_finite() && ga.mutation_sigma >= 0.0,
            "ga.mutation_sigma",
            || format!("must be a finite number ≥ 0, got {}", ga.mutation_sigma),
        )?;
        check(
            ga.weight_limit.is_finite() && ga.weight_limit > 0.0 && ga.weight_limit <= 1e6,
            "ga.weight_limit",
            || format!("must be in (0, 1e6], got {}", ga.weight_limit),
        )?;
        check(
            ga.init_range.is_finite() && ga.init_range >= 0.0 && ga.init_range <= ga.weight_limit,
            "ga.init_range",
            || format!("must be in [0, ga.weight_limit], got {}", ga.init_range),
        )?;
        let t = &raw.trial;
        check((1..=10 * BIG).contains(&t.steps), "trial.steps", || {
            format!("must be an integer in 1..={}, got {}", 10 * BIG, t.steps)
        })?;
        check(
            t.dt.is_finite() && t.dt > 0.0 && t.dt <= 10.0,
            "trial.dt",
            || format!("must be a time step in (0, 10] seconds, got {}", t.dt),
        )?;
        check(
            t.noise.is_finite() && (0.0..=0.5).contains(&t.noise),
            "trial.noise",
            || {
                format!(
                    "must be a noise level in [0, 0.5] (0.06 is the paper's 6 %), got {}",
                    t.noise
                )
            },
        )?;
        let robot: Khepera = raw.robot;
        check(
            robot.v_max.is_finite() && robot.v_max > 0.0,
            "robot.v_max",
            || format!("must be a speed > 0 (mm/s), got {}", robot.v_max),
        )?;
        // The sensor mounts are fixed (SPEC §4): they must sit inside the body, and a body far
        // larger than the sensors' reach would be blind.
        let mounts = crate::sensor::SENSOR_LAYOUT
            .iter()
            .map(|m| m.x.hypot(m.y))
            .fold(0.0, f64::max);
        check(
            robot.radius.is_finite() && robot.radius >= mounts && robot.radius <= 80.0,
            "robot.radius",
            || {
                format!(
                    "must be in [{mounts:.2}, 80] mm (the IR sensors sit {mounts:.2} mm from the centre and see 58 mm), got {}",
                    robot.radius
                )
            },
        )?;
        check(
            robot.wheel_base.is_finite() && robot.wheel_base > 0.0 && robot.wheel_base <= 1000.0,
            "robot.wheel_base",
            || format!("must be in (0, 1000] mm, got {}", robot.wheel_base),
        )?;
        let trial = TrialParams {
            steps: t.steps,
            dt: t.dt,
            noise: t.noise,
            sensor_model: t.sensor_model,
            robot,
            end_at_home: t.end_at_home,
            action_tolerance: raw.aem.action_tolerance,
        };
        check(trial.max_step() < robot.radius, "trial.dt", || {
            format!(
                "one step may move the robot {:.1} mm (robot.v_max × trial.dt × (1 + trial.noise)), which must stay below the body radius {} mm so it cannot pass through walls; use a smaller dt or v_max",
                trial.max_step(),
                robot.radius
            )
        })?;
        check(
            (1..=1024).contains(&raw.network.hidden),
            "network.hidden",
            || format!("must be in 1..=1024, got {}", raw.network.hidden),
        )?;
        let shape = MlpShape::with_hidden(raw.network.hidden);
        let fuzzy = match &raw.fuzzy.coefficients {
            Coefficients::Scheme(s) => TskFitness::with_scheme(raw.fuzzy.peaks.clone(), *s),
            Coefficients::Values(v) => TskFitness::new(raw.fuzzy.peaks.clone(), v.clone()),
        }
        .map_err(|e| {
            let field = match e {
                FuzzyError::CoefficientCount { .. } | FuzzyError::InvalidCoefficient { .. } => {
                    "fuzzy.coefficients"
                }
                _ => "fuzzy.peaks",
            };
            (field.to_string(), e.to_string())
        })?;
        let a = &raw.aem;
        let som = SomParams {
            nodes: a.som_nodes,
            epochs: a.epochs,
            sigma_start: a.sigma_start,
            sigma_end: a.sigma_end,
            rate_start: a.rate_start,
            rate_end: a.rate_end,
        };
        check(
            (1..=100_000).contains(&a.som_nodes),
            "aem.som_nodes",
            || format!("must be in 1..=100000, got {}", a.som_nodes),
        )?;
        check((1..=BIG).contains(&a.epochs), "aem.epochs", || {
            format!("must be in 1..={BIG}, got {}", a.epochs)
        })?;
        check(
            (1..=100_000).contains(&a.test_runs),
            "aem.test_runs",
            || format!("must be in 1..=100000, got {}", a.test_runs),
        )?;
        check(
            a.action_tolerance.is_finite() && (0.0..=2.0).contains(&a.action_tolerance),
            "aem.action_tolerance",
            || {
                format!(
                    "must be in [0, 2] (signed-speed units), got {}",
                    a.action_tolerance
                )
            },
        )?;
        for (name, v) in [
            ("aem.sigma_start", a.sigma_start),
            ("aem.sigma_end", a.sigma_end),
            ("aem.rate_start", a.rate_start),
            ("aem.rate_end", a.rate_end),
        ] {
            check(v.is_finite() && v > 0.0, name, || {
                format!("must be a finite number > 0, got {v}")
            })?;
        }
        check(
            !a.enabled || t.steps.saturating_mul(a.som_nodes) <= 50_000_000,
            "aem.som_nodes",
            || {
                format!(
                    "the SOM would hold aem.som_nodes × trial.steps = {} × {} weights; keep the product ≤ 5e7",
                    a.som_nodes, t.steps
                )
            },
        )?;
        check(!a.enabled || rooms.len() >= 2, "aem.enabled", || {
            format!(
                "room recognition needs at least 2 rooms, got {}; add rooms or set aem.enabled = false",
                rooms.len()
            )
        })?;
        let online = raw.fitness.orientation == OrientationMode::Online;
        check(
            !online || (rooms.len() >= 2 && raw.training == Training::AllRooms),
            "fitness.orientation",
            || "\"online\" needs training = \"all-rooms\" with at least 2 rooms".into(),
        )?;
        // Room files are validated against the Khepera; a bigger body needs its own check.
        if robot.radius > KHEPERA_RADIUS {
            for (i, r) in rooms.iter().enumerate() {
                let home = r.home.position();
                let clearance = r
                    .walls()
                    .iter()
                    .map(|w| w.dist_to(home))
                    .fold(f64::INFINITY, f64::min);
                check(clearance >= robot.radius, &format!("rooms[{i}]"), || {
                    format!(
                        "home of room \"{}\" is {clearance:.1} mm from a wall, closer than robot.radius {}",
                        r.name, robot.radius
                    )
                })?;
            }
        }
        let arenas = rooms.into_iter().map(|r| Arena::new(r, &trial)).collect();
        Ok(Experiment {
            name: raw.name.clone(),
            seed: raw.seed,
            arenas,
            training: raw.training,
            motivations,
            fuzzy,
            ga,
            trial,
            shape,
            energy: raw.fitness.energy,
            orientation: raw.fitness.orientation,
            homing: raw.fitness.homing,
            aem: AemParams {
                enabled: a.enabled,
                encoder: a.encoder,
                som,
                threshold: a.threshold,
                test_runs: a.test_runs,
                action_tolerance: a.action_tolerance,
            },
        })
    }

    /// Room names, in order.
    pub fn room_names(&self) -> Vec<String> {
        self.arenas.iter().map(|a| a.room().name.clone()).collect()
    }

    /// The evolutions the protocol asks for: one over all rooms, or one per room.
    pub fn runs(&self) -> Vec<Run> {
        match self.training {
            Training::AllRooms => vec![Run {
                label: "all".into(),
                tag: 0,
                rooms: (0..self.arenas.len()).collect(),
            }],
            Training::PerRoom => self
                .arenas
                .iter()
                .enumerate()
                .map(|(i, a)| Run {
                    label: a.room().name.clone(),
                    tag: hash_str(&a.room().name),
                    rooms: vec![i],
                })
                .collect(),
        }
    }

    fn room_key(&self, room: usize) -> u64 {
        hash_str(&self.arenas[room].room().name)
    }

    /// F for fitness terms under this experiment's motivations (battery direction applied).
    pub fn fuzzy_fitness(&self, terms: &FitnessTerms) -> f64 {
        self.fuzzy
            .evaluate(&self.motivations, self.fuzzy_inputs(terms))
    }

    /// The fuzzy inputs Y for fitness terms (with `energy = "conserve"`, Y₄ = 1 − b).
    pub fn fuzzy_inputs(&self, terms: &FitnessTerms) -> [f64; 4] {
        let b = match self.energy {
            EnergyMode::Use => terms.b,
            EnergyMode::Conserve => 1.0 - terms.b,
        };
        [terms.a, terms.g, terms.l, b]
    }

    fn controller(&self, genome: &[f64]) -> Mlp {
        Mlp::from_genome(self.shape, genome).expect("genome length matches the validated shape")
    }

    /// Runs one trial of `genome` in `room` with the random stream `seed`; returns the terms
    /// (`l` = 0) and the action labels.
    pub fn trial(&self, genome: &[f64], room: usize, seed: u64) -> (FitnessTerms, Vec<Action>) {
        let arena = &self.arenas[room];
        let mut rng = rng_from_seed(seed);
        let mut obs = (
            TermsRecorder::new(arena, &self.trial, self.homing),
            ActionLog {
                actions: Vec::with_capacity(self.trial.steps),
            },
        );
        simulate(
            arena,
            &mut self.controller(genome),
            &self.trial,
            &mut rng,
            &mut obs,
        );
        (obs.0.finish(), obs.1.actions)
    }

    /// The full trajectory of `genome` in `room` on the AEM instance stream of `run` (the very
    /// run whose actions became the room's stored instance): for figures and replays.
    pub fn instance_trajectory(
        &self,
        genome: &[f64],
        run: &Run,
        room: usize,
    ) -> crate::trial::Trajectory {
        let seed = derive(
            self.seed,
            &[purpose::AEM_INSTANCE, run.tag, self.room_key(room)],
        );
        let mut rng = rng_from_seed(seed);
        crate::trial::run_trial(
            &self.arenas[room],
            &mut self.controller(genome),
            &self.trial,
            &mut rng,
        )
    }

    /// Evaluates one individual of generation `generation` in the rooms of `run`.
    pub fn evaluate(
        &self,
        genome: &[f64],
        run: &Run,
        generation: usize,
        individual: usize,
    ) -> Evaluation {
        let online =
            self.orientation == OrientationMode::Online && self.motivations.orientation > 0.0;
        let mut per_room = Vec::with_capacity(run.rooms.len());
        let mut first_vectors = Vec::new();
        for &r in &run.rooms {
            let seed = derive(
                self.seed,
                &[
                    purpose::EVAL,
                    run.tag,
                    generation as u64,
                    individual as u64,
                    self.room_key(r),
                    0,
                ],
            );
            let (terms, actions) = if online {
                self.trial(genome, r, seed)
            } else {
                let arena = &self.arenas[r];
                let mut rng = rng_from_seed(seed);
                let mut rec = TermsRecorder::new(arena, &self.trial, self.homing);
                simulate(
                    arena,
                    &mut self.controller(genome),
                    &self.trial,
                    &mut rng,
                    &mut rec,
                );
                (rec.finish(), Vec::new())
            };
            if online {
                first_vectors.push(environment_vector(&actions, self.aem.encoder));
            }
            per_room.push(RoomScore { f: 0.0, terms });
        }
        if online {
            // SPEC §13: a second run per room, classified by 1-NN against the first runs.
            let mut correct = 0;
            for (k, &r) in run.rooms.iter().enumerate() {
                let seed = derive(
                    self.seed,
                    &[
                        purpose::ONLINE,
                        run.tag,
                        generation as u64,
                        individual as u64,
                        self.room_key(r),
                        1,
                    ],
                );
                let (_, actions) = self.trial(genome, r, seed);
                let v = environment_vector(&actions, self.aem.encoder);
                if nearest_unique(&first_vectors, &v).ok().flatten() == Some(k) {
                    correct += 1;
                }
            }
            let l = correct as f64 / run.rooms.len() as f64;
            for s in &mut per_room {
                s.terms.l = l;
            }
        }
        for s in &mut per_room {
            s.f = self.fuzzy_fitness(&s.terms);
        }
        let fitness = per_room.iter().map(|s| s.f).sum::<f64>() / per_room.len() as f64;
        Evaluation { fitness, per_room }
    }

    /// The initial population of a run.
    pub fn initial_population(&self, run: &Run) -> Vec<Genome> {
        let mut rng = rng_from_seed(derive(self.seed, &[purpose::INIT, run.tag]));
        initial_population(&self.ga, self.shape.genome_len(), &mut rng)
    }

    /// Evaluates a population in parallel (results in index order, independent of threads).
    pub fn evaluate_population(
        &self,
        population: &[Genome],
        run: &Run,
        generation: usize,
    ) -> Vec<Evaluation> {
        population
            .par_iter()
            .enumerate()
            .map(|(i, g)| self.evaluate(g, run, generation, i))
            .collect()
    }

    /// Statistics of an evaluated generation.
    pub fn generation_record(&self, generation: usize, evals: &[Evaluation]) -> GenerationRecord {
        let fitness: Vec<f64> = evals.iter().map(|e| e.fitness).collect();
        let n = evals.len() as f64;
        let mut mean = [0.0; 4];
        for e in evals {
            let t = e.mean_terms();
            for (m, v) in mean.iter_mut().zip(t.as_array()) {
                *m += v / n;
            }
        }
        GenerationRecord {
            generation,
            stats: Stats::of(&fitness),
            terms: FitnessTerms {
                a: mean[0],
                g: mean[1],
                l: mean[2],
                b: mean[3],
            },
        }
    }

    /// Breeds generation `generation + 1` from an evaluated generation.
    pub fn breed(
        &self,
        population: &[Genome],
        evals: &[Evaluation],
        run: &Run,
        generation: usize,
    ) -> Vec<Genome> {
        let fitness: Vec<f64> = evals.iter().map(|e| e.fitness).collect();
        let mut rng = rng_from_seed(derive(
            self.seed,
            &[purpose::BREED, run.tag, generation as u64],
        ));
        next_generation(population, &fitness, &self.ga, &mut rng)
    }

    /// Evolves one run from scratch, calling `on_generation` after each generation.
    pub fn evolve(
        &self,
        run: &Run,
        on_generation: &mut dyn FnMut(&GenerationState<'_>),
    ) -> Evolution {
        let population = self.initial_population(run);
        self.evolve_from(run, 0, population, Vec::new(), on_generation)
    }

    /// Continues a run at `generation` with `population` (not yet evaluated) and the records of
    /// the generations before it; the result equals an uninterrupted [`Experiment::evolve`],
    /// because every random stream is derived from (run, generation, individual, room).
    pub fn evolve_from(
        &self,
        run: &Run,
        generation: usize,
        mut population: Vec<Genome>,
        mut history: Vec<GenerationRecord>,
        on_generation: &mut dyn FnMut(&GenerationState<'_>),
    ) -> Evolution {
        let mut g = generation;
        loop {
            let evals = self.evaluate_population(&population, run, g);
            history.push(self.generation_record(g, &evals));
            if g + 1 >= self.ga.generations {
                on_generation(&GenerationState {
                    history: &history,
                    population: &population,
                    next: None,
                });
                let best =
                    crate::ga::ranking(&evals.iter().map(|e| e.fitness).collect::<Vec<_>>())[0];
                return Evolution {
                    run: run.clone(),
                    history,
                    population,
                    evaluations: evals,
                    best,
                };
            }
            let next = self.breed(&population, &evals, run, g);
            on_generation(&GenerationState {
                history: &history,
                population: &population,
                next: Some(&next),
            });
            population = next;
            g += 1;
        }
    }

    /// Rebuilds a finished evolution from its final population and history (the final
    /// generation is evaluated again on its own streams, giving the same evaluations).
    pub fn finished(
        &self,
        run: &Run,
        population: Vec<Genome>,
        history: Vec<GenerationRecord>,
    ) -> Evolution {
        let last = history.len().saturating_sub(1);
        let evals = self.evaluate_population(&population, run, last);
        let best = crate::ga::ranking(&evals.iter().map(|e| e.fitness).collect::<Vec<_>>())[0];
        Evolution {
            run: run.clone(),
            history,
            population,
            evaluations: evals,
            best,
        }
    }

    /// Action-based environment modelling with one robot: an instance run per room, SOM
    /// training, then `test_runs` recognition tests per room (SPEC §11–§12). With AEM disabled
    /// the test runs still measure exploration, homing and battery, and nothing is recognised.
    pub fn environment_modelling(&self, genome: &[f64], run: &Run) -> Result<AemReport, SomError> {
        let rooms = self.arenas.len();
        let recognizer = if self.aem.enabled {
            let vectors: Vec<Vec<f64>> = (0..rooms)
                .into_par_iter()
                .map(|r| {
                    let seed = derive(
                        self.seed,
                        &[purpose::AEM_INSTANCE, run.tag, self.room_key(r)],
                    );
                    environment_vector(&self.trial(genome, r, seed).1, self.aem.encoder)
                })
                .collect();
            let mut som_rng = rng_from_seed(derive(self.seed, &[purpose::SOM, run.tag]));
            Some(Recognizer::train(
                &vectors,
                &self.aem.som,
                self.aem.threshold,
                &mut som_rng,
            )?)
        } else {
            None
        };
        let tests: Vec<(usize, AemTest)> = (0..rooms)
            .flat_map(|r| (0..self.aem.test_runs).map(move |t| (r, t)))
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|(r, t)| {
                let seed = derive(
                    self.seed,
                    &[purpose::AEM_TEST, run.tag, self.room_key(r), t as u64],
                );
                let (terms, actions) = self.trial(genome, r, seed);
                let (answer, winner) = match &recognizer {
                    Some(rec) => {
                        let v = environment_vector(&actions, self.aem.encoder);
                        (rec.recognise(&v)?, Some(rec.som.winner(&v)?))
                    }
                    None => (None, None),
                };
                Ok((
                    r,
                    AemTest {
                        terms,
                        answer,
                        winner,
                    },
                ))
            })
            .collect::<Result<_, SomError>>()?;
        let mut confusion = Confusion::new(rooms);
        let mut per_room: Vec<AemRoom> = (0..rooms)
            .map(|r| AemRoom {
                room: self.arenas[r].room().name.clone(),
                r_node: recognizer.as_ref().map(|rec| rec.instances[r].r_node),
                tests: Vec::new(),
                correct: 0,
                recognition_pct: None,
                exploration_pct: 0.0,
                battery_pct: 0.0,
                homing_pct: 0.0,
            })
            .collect();
        for (r, test) in tests {
            confusion.record(r, test.answer);
            per_room[r].tests.push(test);
        }
        for (r, row) in per_room.iter_mut().enumerate() {
            let n = row.tests.len() as f64;
            row.correct = confusion.correct(r) as usize;
            row.recognition_pct = recognizer.is_some().then(|| confusion.percent(r));
            row.exploration_pct = row.tests.iter().map(|t| 100.0 * t.terms.a).sum::<f64>() / n;
            row.battery_pct = row.tests.iter().map(|t| 100.0 * t.terms.b).sum::<f64>() / n;
            row.homing_pct = row.tests.iter().map(|t| 100.0 * t.terms.g).sum::<f64>() / n;
        }
        Ok(AemReport {
            rooms: per_room,
            confusion,
            som_nodes: recognizer.as_ref().map_or(0, |rec| rec.som.nodes()),
        })
    }
}

/// One evolution: its label (`all` or a room name), its stream tag and its rooms.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Run {
    /// `all` for all-rooms training, else the room name.
    pub label: String,
    /// Seed-derivation tag (0 for all-rooms, the room name's hash for per-room).
    pub tag: u64,
    /// Indices of the rooms each individual is evaluated in.
    pub rooms: Vec<usize>,
}

/// F and terms of one individual in one room.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RoomScore {
    /// Fuzzy fitness F in this room.
    pub f: f64,
    /// The terms measured.
    pub terms: FitnessTerms,
}

/// One individual's evaluation: mean F over its rooms, and per-room scores.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// Fitness used by the GA (mean F over the run's rooms).
    pub fitness: f64,
    /// Per room of the run, in order.
    pub per_room: Vec<RoomScore>,
}

impl Evaluation {
    /// Mean terms over the rooms.
    pub fn mean_terms(&self) -> FitnessTerms {
        let n = self.per_room.len() as f64;
        let mut t = FitnessTerms::default();
        for s in &self.per_room {
            t.a += s.terms.a / n;
            t.g += s.terms.g / n;
            t.l += s.terms.l / n;
            t.b += s.terms.b / n;
        }
        t
    }
}

/// Statistics of one generation (a row of `generations.csv`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GenerationRecord {
    /// Generation index, from 0.
    pub generation: usize,
    /// Best/mean/std/min/max of F.
    pub stats: Stats,
    /// Population means of a, g, l, b.
    pub terms: FitnessTerms,
}

/// Where an evolution stands after a generation: enough to checkpoint it.
#[derive(Debug, Clone, Copy)]
pub struct GenerationState<'a> {
    /// Records of every generation so far (the last is the one just evaluated).
    pub history: &'a [GenerationRecord],
    /// The generation just evaluated.
    pub population: &'a [Genome],
    /// The next generation (not yet evaluated), or `None` after the last generation.
    pub next: Option<&'a [Genome]>,
}

impl GenerationState<'_> {
    /// The record of the generation just evaluated.
    pub fn record(&self) -> &GenerationRecord {
        self.history.last().expect("at least one generation")
    }
}

/// The outcome of one evolution.
#[derive(Debug, Clone)]
pub struct Evolution {
    /// The run.
    pub run: Run,
    /// Per generation.
    pub history: Vec<GenerationRecord>,
    /// The final generation.
    pub population: Vec<Genome>,
    /// Its evaluations.
    pub evaluations: Vec<Evaluation>,
    /// Index of the best final individual.
    pub best: usize,
}

impl Evolution {
    /// Mean F of the final population in room position `k` of the run.
    pub fn mean_room_fitness(&self, k: usize) -> f64 {
        self.evaluations
            .iter()
            .map(|e| e.per_room[k].f)
            .sum::<f64>()
            / self.evaluations.len() as f64
    }
}

/// One AEM test run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AemTest {
    /// Terms measured in the test run.
    pub terms: FitnessTerms,
    /// The recognised room, if any.
    pub answer: Option<usize>,
    /// The SOM winner of the test vector (none with AEM disabled).
    pub winner: Option<usize>,
}

/// AEM results for one room.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AemRoom {
    /// Room name.
    pub room: String,
    /// The instance's r-node (none with AEM disabled).
    pub r_node: Option<usize>,
    /// The test runs.
    pub tests: Vec<AemTest>,
    /// Correct recognitions.
    pub correct: usize,
    /// % recognition (none with AEM disabled).
    pub recognition_pct: Option<f64>,
    /// Mean 100·a over the tests.
    pub exploration_pct: f64,
    /// Mean 100·b over the tests.
    pub battery_pct: f64,
    /// Mean 100·g over the tests.
    pub homing_pct: f64,
}

/// The AEM outcome for one robot.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AemReport {
    /// Per room.
    pub rooms: Vec<AemRoom>,
    /// Truth × answer counts.
    pub confusion: Confusion,
    /// Number of SOM nodes.
    pub som_nodes: usize,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::room::BUILTIN_ROOMS;

    fn experiment(extra: &[&str]) -> Experiment {
        let mut sets: Vec<String> = [
            "ga.population=8",
            "ga.generations=3",
            "trial.steps=120",
            "aem.epochs=10",
            "aem.test_runs=2",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        sets.extend(extra.iter().map(|s| s.to_string()));
        let raw = RawConfig::parse("", "test", &sets).unwrap();
        let rooms = BUILTIN_ROOMS
            .iter()
            .map(|r| Room::builtin(r).unwrap())
            .collect();
        Experiment::new(&raw, rooms, "test").unwrap()
    }

    const ORIENTED: [&str; 5] = [
        "fitness.orientation=\"online\"",
        "motivations.curiosity=0.4",
        "motivations.homing=0.2",
        "motivations.orientation=0.3",
        "motivations.energy=0.1",
    ];

    /// Online l is exactly the off-line 1-NN computation on the same trajectories, run on the
    /// derived streams (EVAL for the first run, ONLINE for the second).
    #[test]
    fn online_orientation_equals_offline_nearest_neighbour() {
        let exp = experiment(&ORIENTED);
        let run = &exp.runs()[0];
        let genome = &exp.initial_population(run)[3];
        let (g, i) = (2usize, 3usize);
        let eval = exp.evaluate(genome, run, g, i);
        let first: Vec<Vec<f64>> = run
            .rooms
            .iter()
            .map(|&r| {
                let seed = derive(
                    exp.seed,
                    &[
                        purpose::EVAL,
                        run.tag,
                        g as u64,
                        i as u64,
                        exp.room_key(r),
                        0,
                    ],
                );
                environment_vector(&exp.trial(genome, r, seed).1, exp.aem.encoder)
            })
            .collect();
        let mut correct = 0;
        for (k, &r) in run.rooms.iter().enumerate() {
            let seed = derive(
                exp.seed,
                &[
                    purpose::ONLINE,
                    run.tag,
                    g as u64,
                    i as u64,
                    exp.room_key(r),
                    1,
                ],
            );
            assert_ne!(
                seed,
                derive(
                    exp.seed,
                    &[
                        purpose::EVAL,
                        run.tag,
                        g as u64,
                        i as u64,
                        exp.room_key(r),
                        0
                    ]
                )
            );
            let v = environment_vector(&exp.trial(genome, r, seed).1, exp.aem.encoder);
            if crate::recognition::nearest_unique(&first, &v).unwrap() == Some(k) {
                correct += 1;
            }
        }
        let l = correct as f64 / run.rooms.len() as f64;
        assert!(
            eval.per_room.iter().all(|s| s.terms.l == l),
            "{eval:?} vs l = {l}"
        );
        // The first run's terms are those of the off-line evaluation on the same stream.
        let offline = experiment(&[
            "fitness.orientation=\"offline\"",
            "motivations.curiosity=0.4",
            "motivations.homing=0.2",
            "motivations.orientation=0.3",
            "motivations.energy=0.1",
        ]);
        let off = offline.evaluate(genome, run, g, i);
        for (a, b) in eval.per_room.iter().zip(&off.per_room) {
            assert_eq!(
                (a.terms.a, a.terms.g, a.terms.b),
                (b.terms.a, b.terms.g, b.terms.b)
            );
            assert_eq!(b.terms.l, 0.0);
        }
    }

    /// With O = 0, online mode computes nothing extra and gives byte-identical evolutions.
    #[test]
    fn zero_orientation_online_equals_offline() {
        let off = experiment(&[]);
        let on = experiment(&["fitness.orientation=\"online\""]);
        let run = &off.runs()[0];
        let a = off.evolve(run, &mut |_| {});
        let b = on.evolve(run, &mut |_| {});
        assert_eq!(a.history, b.history);
        assert_eq!(a.population, b.population);
        assert_eq!(a.evaluations, b.evaluations);
    }

    /// Online orientation makes F depend on O and stays deterministic.
    #[test]
    fn online_orientation_is_deterministic_and_used() {
        let mut sets = ORIENTED.to_vec();
        sets.push("ga.population=40");
        let exp = experiment(&sets);
        let run = &exp.runs()[0];
        let x = exp.evolve(run, &mut |_| {});
        let y = exp.evolve(run, &mut |_| {});
        assert_eq!(x.history, y.history);
        assert!(
            x.history.iter().any(|h| h.terms.l > 0.0),
            "some robot recognises something"
        );
    }

    /// A resumed evolution equals an uninterrupted one.
    #[test]
    fn evolve_from_a_checkpoint_equals_uninterrupted() {
        let exp = experiment(&[]);
        let run = &exp.runs()[0];
        let mut saved = None;
        let full = exp.evolve(run, &mut |s| {
            if s.history.len() == 2 {
                saved = Some((s.history.to_vec(), s.next.unwrap().to_vec()));
            }
        });
        let (history, next) = saved.unwrap();
        let resumed = exp.evolve_from(run, history.len(), next, history, &mut |_| {});
        assert_eq!(full.history, resumed.history);
        assert_eq!(full.evaluations, resumed.evaluations);
        let rebuilt = exp.finished(run, full.population.clone(), full.history.clone());
        assert_eq!(rebuilt.evaluations, full.evaluations);
    }
}
