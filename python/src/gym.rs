//! The native side of `fuzzymotiv.gym`: `GymCore`, N trials of the config's robot stepped in
//! Rust in one call (the library's [`Episode`]: its step, noise streams and fitness terms), for
//! the Gymnasium env (N = 1) and the vector env.
//!
//! Each trial is the room-modelling instance run that `fm.simulate(genome, room, seed)` runs
//! (the experiment of that one room, [`single_room`], its instance stream under base seed
//! `seed`): driven by the genome's network outputs, the same trajectory, terms and F.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use fuzzymotiv::experiment::OrientationMode;
use fuzzymotiv::experiment::{Experiment, Run};
use fuzzymotiv::fitness::Episode;
use fuzzymotiv::random::{JSON_EXACT, derive};
use fuzzymotiv::random::{Rng, Rng64, index, rng_from_seed};
use fuzzymotiv::simulation::Action;
use fuzzymotiv::simulation::Arena;
use fuzzymotiv::simulation::{Controller, Mlp, MlpShape};
use fuzzymotiv::simulation::{StepObserver, Trajectory};
use fuzzymotiv_pipeline::files::inputs::{Loaded, room_entry};
use numpy::PyUntypedArrayMethods;
use numpy::{Element, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use crate::terms::{load_with_terms, one_trial, resolve_with_terms, supply_trials};
use crate::{ResetNeeded, config_err, input_err};

/// The experiment of one trial in `room` (a room of the config, a built-in room or a room
/// file), as `fuzzymotiv replay --room ROOM` and `fm.simulate` build it: that room only, and
/// neither recognition nor online orientation (they change no trajectory). `user`: the names
/// of the terms Python supplies (`terms=`).
pub(crate) fn single_room(loaded: &Loaded, room: &str, user: &[String]) -> PyResult<Experiment> {
    let entry = room_entry("room", room, loaded).map_err(config_err)?;
    let mut raw = loaded.raw.clone();
    raw.rooms = vec![entry];
    raw.aem.enabled = false;
    raw.fitness.orientation = OrientationMode::Offline;
    Ok(resolve_with_terms(raw, Path::new("."), "(simulate)", user)
        .map_err(config_err)?
        .experiment)
}

/// One room an env may be reset into.
struct Slot {
    exp: Arc<Experiment>,
    arena: Arc<Arena>,
    run: Run,
}

/// One env: its trial, the stream its next rooms and seeds are drawn from (autoreset), and
/// whether its trial ended at the last step (`NEXT_STEP` autoreset: the next step resets it).
struct Env {
    room: usize,
    episode: Episode<Arc<Arena>, Rng64>,
    chooser: Rng64,
    ended: bool,
    /// F of the terms after the last step (per-step reward).
    last_f: f64,
    /// The trial so far, recorded when Python supplies terms (they are computed from it).
    trajectory: Option<Trajectory>,
}

/// What the reward is: F at the end, or the change of F of the terms so far.
#[derive(Clone, Copy, PartialEq)]
enum Reward {
    End,
    PerStep,
}

/// N trials in one or more rooms, stepped together (`fuzzymotiv.gym`'s envs wrap it).
#[pyclass(module = "fuzzymotiv._fuzzymotiv", name = "GymCore")]
pub struct GymCore {
    slots: Vec<Slot>,
    envs: Vec<Env>,
    reward: Reward,
    float64: bool,
    /// The robot's sensors (an observation's length) and its largest reading (an
    /// observation is reading / `reading_max`).
    sensors: usize,
    reading_max: f64,
    /// The names of the terms Python supplies (`terms=`), and the function that computes
    /// their values from a batch of finished trials (`fuzzymotiv.trials._supplier`).
    user: Vec<String>,
    supply: Option<Py<PyAny>>,
    /// Set when supplying the terms at an episode's end failed: steps are refused until a
    /// reset (that step's results were lost).
    needs_reset: bool,
}

impl GymCore {
    /// An env at the start of a trial in slot `room` under base seed `base`; its later
    /// autoresets draw from `chooser`.
    fn fresh(&self, room: usize, base: u64, chooser: Rng64) -> Env {
        let s = &self.slots[room];
        let steps = s.exp.trial_params().steps();
        let trajectory =
            (!self.user.is_empty()).then(|| Trajectory::starting_at(s.arena.room().home, steps));
        Env {
            room,
            episode: s.exp.episode(s.arena.clone(), base, &s.run, 0),
            chooser,
            ended: false,
            last_f: 0.0,
            trajectory,
        }
    }

    /// Env `i`'s next episode, its room and base seed drawn from its chooser (autoreset).
    fn autoreset(&mut self, i: usize) {
        let mut chooser = self.envs[i].chooser.clone();
        let room = index(&mut chooser, self.slots.len());
        let base = chooser.next_u64() & JSON_EXACT;
        self.envs[i] = self.fresh(room, base, chooser);
    }

    /// Observations as an `(envs, sensors)` array of reading / `reading_max` (the Khepera's
    /// IR / 1023; `obs` holds them env after env, in the env's dtype).
    fn obs_array<'py>(&self, py: Python<'py>, obs: &Obs) -> Bound<'py, PyAny> {
        match obs {
            Obs::F64(v) => matrix(py, v, self.sensors).into_any(),
            Obs::F32(v) => matrix(py, v, self.sensors).into_any(),
        }
    }

    /// One step of env `i` (`NEXT_STEP` autoreset: an env whose trial ended is reset instead,
    /// its action ignored). Returns the reward, terminated, truncated and the executed action's
    /// index (-1 for a reset).
    fn step_one(&mut self, i: usize, act: Act) -> (f64, bool, bool, i64) {
        if self.envs[i].ended {
            self.autoreset(i);
            return (0.0, false, false, -1);
        }
        let (reward, slots) = (self.reward, &self.slots);
        let env = &mut self.envs[i];
        let step = match act {
            Act::Motors(m) => env.episode.step(m),
            Act::Action(a) => env.episode.step_action(a),
        };
        let action = ACTIONS.iter().position(|&a| a == step.action).unwrap_or(0) as i64;
        let over = env.episode.is_over();
        if let Some(trajectory) = &mut env.trajectory {
            trajectory.observe(&step);
            if over {
                env.episode
                    .run()
                    .rest()
                    .for_each(|idle| trajectory.observe(&idle));
            }
        }
        let home = env.episode.run().ended_at_home();
        let f = match (reward, over) {
            (Reward::PerStep, _) | (Reward::End, true) => {
                slots[env.room].exp.fuzzy_fitness(&env.episode.terms())
            }
            _ => 0.0,
        };
        let r = match reward {
            Reward::End => f,
            Reward::PerStep => f - env.last_f,
        };
        env.last_f = f;
        env.ended = over;
        (r, home, over && !home, action)
    }
}

impl GymCore {
    /// The supplied terms of the envs whose episode ended at this step, as `fm.Problem`
    /// supplies them: one call of `supply` per room with those trials, their values into
    /// `out`'s info and their F (with the library's terms) as the reward.
    fn supply_ended(&mut self, py: Python<'_>, out: &mut Out) -> PyResult<()> {
        let Some(supply) = &self.supply else {
            return Ok(());
        };
        let supply = supply.bind(py);
        for slot in 0..self.slots.len() {
            let ended: Vec<usize> = (0..self.envs.len())
                .filter(|&i| self.envs[i].room == slot && (out.terminated[i] || out.truncated[i]))
                .collect();
            if ended.is_empty() {
                continue;
            }
            let recorded = (ended.iter())
                .map(|&i| {
                    let env = &mut self.envs[i];
                    let trajectory = env.trajectory.take().expect("recorded with terms=");
                    one_trial(env.episode.terms(), trajectory)
                })
                .collect();
            let s = &self.slots[slot];
            let name = &s.arena.room().name;
            let evals = supply_trials(py, &s.exp, name, recorded, &self.user, supply)?;
            for (&i, e) in ended.iter().zip(evals) {
                out.reward[i] = e.fitness;
                let values = e.per_room[0].terms.user;
                for (column, &v) in out.user.iter_mut().zip(values.as_slice()) {
                    column[i] = v;
                }
                out.user_given[i] = true;
            }
        }
        Ok(())
    }
}

/// The keys of a step's `info` (a supplied term may not take one's name).
const INFO_KEYS: [&str; 10] = [
    "a", "g", "l", "b", "x", "y", "heading", "t", "room", "action",
];

/// Terms Python supplies (`terms=`): with their function, for the reward at the end, and named
/// apart from `info`'s keys.
fn check_gym_terms(terms: &[String], reward: Reward, supplied: bool) -> PyResult<()> {
    if terms.is_empty() {
        return Ok(());
    }
    if !supplied {
        return Err(input_err("terms: term names given without their function"));
    }
    if reward == Reward::PerStep {
        return Err(input_err(
            "reward: \"per-step\" cannot be used with terms= (a term of your own is a value of the whole trial, computed once at the episode's end); use reward=\"end\"",
        ));
    }
    if let Some(t) = terms
        .iter()
        .find(|t| INFO_KEYS.contains(&t.as_str()) || t.starts_with('_'))
    {
        return Err(input_err(format!(
            "terms[{t:?}]: the env reports each term of your own in `info` by its name, and {t:?} is taken (info has {INFO_KEYS:?} and their `_name` masks); name the term otherwise"
        )));
    }
    Ok(())
}

/// One env's action.
#[derive(Clone, Copy)]
enum Act {
    Motors([f64; 2]),
    Action(Action),
}

/// The four actions of the `Discrete(4)` variant, in order.
const ACTIONS: [Action; 4] = [
    Action::Straight,
    Action::Left30,
    Action::Right30,
    Action::Turn180,
];

/// The actions of a step: `(N, 2)` motor outputs (clipped to [0, 1]) or `(N,)` action indices.
fn actions(n: usize, arg: &Bound<'_, PyAny>) -> PyResult<Vec<Act>> {
    if let Ok(a) = arg.extract::<PyReadonlyArray2<'_, f64>>() {
        if a.shape() != [n, 2] {
            return Err(input_err(format!(
                "actions: expected shape ({n}, 2) (two motor outputs per env), got {:?}",
                a.shape()
            )));
        }
        let a = a.as_array();
        return (0..n)
            .map(|i| {
                let m = [a[[i, 0]], a[[i, 1]]];
                if m.iter().any(|v| !v.is_finite()) {
                    return Err(input_err(format!(
                        "actions: env {i}'s motor outputs {m:?} are not finite"
                    )));
                }
                Ok(Act::Motors(m.map(|v| v.clamp(0.0, 1.0))))
            })
            .collect();
    }
    let a: PyReadonlyArray1<'_, i64> = arg.extract().map_err(|_| {
        input_err("actions: expected a float64 array (N, 2) or an int64 array (N,)")
    })?;
    if a.len() != n {
        return Err(input_err(format!(
            "actions: expected {n} action indices, got {}",
            a.len()
        )));
    }
    (a.as_array().iter())
        .map(
            |&k| match usize::try_from(k).ok().and_then(|k| ACTIONS.get(k)) {
                Some(&a) => Ok(Act::Action(a)),
                None => Err(input_err(format!(
                    "actions: {k} is not an action (0 straight, 1 left30, 2 right30, 3 turn180)"
                ))),
            },
        )
        .collect()
}

/// The most environments of one vector env (about 0.5 KiB each, so 512 MiB).
const MAX_ENVS: usize = 1 << 20;

#[pymethods]
impl GymCore {
    /// `num_envs` trials, each in one of `rooms` (room names or files), under the config;
    /// `terms` names the terms Python supplies, `supply` computes them from finished trials.
    #[new]
    #[pyo3(signature = (rooms, num_envs, config_path=None, config_text=None, sets=Vec::new(), reward="end", float64=false, terms=Vec::new(), supply=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        rooms: Vec<String>,
        num_envs: usize,
        config_path: Option<PathBuf>,
        config_text: Option<String>,
        sets: Vec<String>,
        reward: &str,
        float64: bool,
        terms: Vec<String>,
        supply: Option<Py<PyAny>>,
    ) -> PyResult<Self> {
        let reward = match reward {
            "end" => Reward::End,
            "per-step" | "per_step" => Reward::PerStep,
            r => {
                return Err(input_err(format!(
                    "reward: expected \"end\" or \"per-step\", got {r:?}"
                )));
            }
        };
        if rooms.is_empty() || num_envs == 0 {
            return Err(input_err("room: at least one room and one env are needed"));
        }
        if num_envs > MAX_ENVS {
            return Err(input_err(format!(
                "num_envs: at most {MAX_ENVS} (each environment holds its own trial), got \
                 {num_envs}; use several vector envs"
            )));
        }
        check_gym_terms(&terms, reward, supply.is_some())?;
        let loaded = load_with_terms(
            config_path.as_deref(),
            config_text.as_deref(),
            &sets,
            None,
            &terms,
        )
        .map_err(config_err)?;
        crate::warn_notes(&loaded.notes)?;
        let slots = (rooms.iter())
            .map(|r| {
                let exp = single_room(&loaded, r, &terms)?;
                let (arena, run) = (Arc::new(exp.arenas()[0].clone()), exp.runs().remove(0));
                let exp = Arc::new(exp);
                Ok(Slot { exp, arena, run })
            })
            .collect::<PyResult<Vec<_>>>()?;
        let spec = slots[0].exp.trial_params().robot().spec();
        let (sensors, reading_max) = (spec.sensors(), spec.reading_max());
        let mut core = GymCore {
            slots,
            envs: Vec::with_capacity(num_envs),
            reward,
            float64,
            sensors,
            reading_max,
            user: terms,
            supply,
            needs_reset: false,
        };
        for i in 0..num_envs {
            let env = core.fresh(0, i as u64, rng_from_seed(i as u64));
            core.envs.push(env);
        }
        Ok(core)
    }

    /// Number of envs.
    #[getter]
    fn num_envs(&self) -> usize {
        self.envs.len()
    }

    /// The robot's name.
    #[getter]
    fn robot(&self) -> String {
        let spec = self.slots[0].exp.trial_params().robot().spec();
        spec.name().to_string()
    }

    /// The robot's sensors: an observation's length.
    #[getter]
    fn sensors(&self) -> usize {
        self.sensors
    }

    /// The robot's largest reading (an observation is reading / `reading_max`).
    #[getter]
    fn reading_max(&self) -> f64 {
        self.reading_max
    }

    /// Steps per trial `T`.
    #[getter]
    fn max_steps(&self) -> usize {
        self.slots[0].exp.trial_params().steps()
    }

    /// The rooms' names, in slot order.
    #[getter]
    fn room_names(&self) -> Vec<String> {
        (self.slots.iter())
            .map(|s| s.arena.room().name.clone())
            .collect()
    }

    /// Starts env `i`'s trial in slot `room` under base seed `seed` (the instance run
    /// `fm.simulate(genome, room, seed)` runs); its later autoresets draw rooms and seeds from
    /// a stream of `seed`. `state()` then gives its first observation.
    fn reset_one(&mut self, i: usize, room: usize, seed: u64) -> PyResult<()> {
        if i >= self.envs.len() || room >= self.slots.len() {
            return Err(input_err(format!("reset: no env {i} or room slot {room}")));
        }
        let chooser = rng_from_seed(derive(seed, &[0x0067_796d]));
        self.envs[i] = self.fresh(room, seed, chooser);
        self.needs_reset = false;
        Ok(())
    }

    /// Steps every env once: `actions` is `(N, 2)` float64 motor outputs or `(N,)` int64
    /// action indices. Returns `(obs, reward, terminated, truncated, info)`, arrays over the
    /// envs; `info` holds `a`, `g`, `l`, `b`, `x`, `y`, `heading`, `t` and `room` (the slot),
    /// and each supplied term by name (NaN, and `_name` False, until the episode's end).
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        actions: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        if self.needs_reset {
            return Err(ResetNeeded::new_err(
                "step: the last step's episode end failed (a term of `terms=` raised or returned a bad value), so its results were lost; call reset() first",
            ));
        }
        let n = self.envs.len();
        let acts = self::actions(n, actions)?;
        let mut out = Out::for_envs(n, self);
        py.detach(|| {
            for (i, act) in acts.into_iter().enumerate() {
                let (r, term, trunc, action) = self.step_one(i, act);
                out.push(&mut self.envs[i], r, (term, trunc), action);
            }
        });
        if let Err(e) = self.supply_ended(py, &mut out) {
            self.needs_reset = true;
            return Err(e);
        }
        out.into_py(py, self)
    }

    /// The envs now: `(obs, info)` as `step` gives them (for `reset`; `action` -1).
    fn state<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let mut out = Out::for_envs(self.envs.len(), self);
        for env in &mut self.envs {
            out.push(env, 0.0, (false, false), -1);
        }
        let t = out.into_py(py, self)?;
        PyTuple::new(py, [t.get_item(0)?, t.get_item(4)?])
    }
}

/// A step's results over the envs, gathered without the GIL.
struct Out {
    /// Each env's readings / `reading_max`, env after env.
    obs: Obs,
    reading_max: f64,
    reward: Vec<f64>,
    terminated: Vec<bool>,
    truncated: Vec<bool>,
    /// a, g, l, b, x, y, heading per env.
    info: [Vec<f64>; 7],
    t: Vec<i64>,
    room: Vec<i64>,
    action: Vec<i64>,
    /// Each supplied term's value per env (NaN until its episode's end) and whether it is given.
    user: Vec<Vec<f64>>,
    user_given: Vec<bool>,
}

impl Out {
    /// Room for `n` envs of `core`.
    fn for_envs(n: usize, core: &GymCore) -> Out {
        let user = core.user.len();
        let values = n * core.sensors;
        Out {
            obs: if core.float64 {
                Obs::F64(Vec::with_capacity(values))
            } else {
                Obs::F32(Vec::with_capacity(values))
            },
            reading_max: core.reading_max,
            reward: Vec::with_capacity(n),
            terminated: Vec::with_capacity(n),
            truncated: Vec::with_capacity(n),
            info: std::array::from_fn(|_| Vec::with_capacity(n)),
            t: Vec::with_capacity(n),
            room: Vec::with_capacity(n),
            action: Vec::with_capacity(n),
            user: vec![Vec::with_capacity(n); user],
            user_given: Vec::with_capacity(n),
        }
    }

    fn push(
        &mut self,
        env: &mut Env,
        reward: f64,
        (terminated, truncated): (bool, bool),
        action: i64,
    ) {
        let max = self.reading_max;
        let seen = env.episode.observed().iter().map(|v| v / max);
        match &mut self.obs {
            Obs::F64(obs) => obs.extend(seen),
            Obs::F32(obs) => obs.extend(seen.map(|v| v as f32)),
        }
        let terms = env.episode.terms();
        let pose = env.episode.run().pose();
        let values = [
            terms.a,
            terms.g,
            terms.l,
            terms.b,
            pose.x,
            pose.y,
            pose.heading,
        ];
        for (column, v) in self.info.iter_mut().zip(values) {
            column.push(v);
        }
        self.reward.push(reward);
        self.terminated.push(terminated);
        self.truncated.push(truncated);
        self.t.push(env.episode.run().t() as i64);
        self.room.push(env.room as i64);
        self.action.push(action);
        for column in &mut self.user {
            column.push(f64::NAN);
        }
        self.user_given.push(false);
    }

    // The arrays are NumPy's own, filled from the columns (`from_slice`): an array made from a
    // `Vec` (`from_vec`) also makes a Python object to own the `Vec`, and a step makes 15.
    // The keys are interned once, not made anew each step.
    fn into_py<'py>(self, py: Python<'py>, core: &GymCore) -> PyResult<Bound<'py, PyTuple>> {
        let info = PyDict::new(py);
        let names = [
            intern!(py, "a"),
            intern!(py, "g"),
            intern!(py, "l"),
            intern!(py, "b"),
            intern!(py, "x"),
            intern!(py, "y"),
            intern!(py, "heading"),
        ];
        for (name, column) in names.into_iter().zip(&self.info) {
            info.set_item(name, PyArray1::from_slice(py, column))?;
        }
        info.set_item(intern!(py, "t"), PyArray1::from_slice(py, &self.t))?;
        info.set_item(intern!(py, "room"), PyArray1::from_slice(py, &self.room))?;
        info.set_item(
            intern!(py, "action"),
            PyArray1::from_slice(py, &self.action),
        )?;
        // Gymnasium's vector info convention: `_key` says which envs have `key` (all do).
        let all = PyArray1::from_slice(py, &vec![true; self.reward.len()]);
        let masks = [
            intern!(py, "_a"),
            intern!(py, "_g"),
            intern!(py, "_l"),
            intern!(py, "_b"),
            intern!(py, "_x"),
            intern!(py, "_y"),
            intern!(py, "_heading"),
            intern!(py, "_t"),
            intern!(py, "_room"),
            intern!(py, "_action"),
        ];
        for mask in masks {
            info.set_item(mask, &all)?;
        }
        if !self.user.is_empty() {
            let given = PyArray1::from_slice(py, &self.user_given);
            for (name, column) in core.user.iter().zip(&self.user) {
                info.set_item(name, PyArray1::from_slice(py, column))?;
                info.set_item(format!("_{name}"), &given)?;
            }
        }
        let items: [Bound<'py, PyAny>; 5] = [
            core.obs_array(py, &self.obs),
            PyArray1::from_slice(py, &self.reward).into_any(),
            PyArray1::from_slice(py, &self.terminated).into_any(),
            PyArray1::from_slice(py, &self.truncated).into_any(),
            info.into_any(),
        ];
        PyTuple::new(py, items)
    }
}

/// A step's observations in the env's dtype (float32 by default, float64 on request).
enum Obs {
    F32(Vec<f32>),
    F64(Vec<f64>),
}

/// `values` (rows of `columns` values, one after another) as a `(rows, columns)` array of
/// NumPy's own.
fn matrix<'py, T: Element + Copy>(
    py: Python<'py>,
    values: &[T],
    columns: usize,
) -> Bound<'py, PyArray2<T>> {
    let rows = values.len() / columns;
    // SAFETY: the array is new and C-contiguous, and every element is written just below,
    // before any Python code can see it.
    unsafe {
        let a = PyArray2::<T>::new(py, [rows, columns], false);
        let out = a.as_slice_mut().expect("a new array is contiguous");
        out.copy_from_slice(values);
        a
    }
}

/// The motor outputs of the network of `genome` (the library's `Mlp`, `hidden` units, one
/// input per sensor) for `inputs` (one value in [0, 1] per sensor): what it gives the
/// simulator.
#[pyfunction]
pub(crate) fn network_outputs(
    genome: Vec<f64>,
    hidden: usize,
    inputs: Vec<f64>,
) -> PyResult<[f64; 2]> {
    let shape = MlpShape::with_hidden(hidden)
        .map_err(|e| input_err(format!("hidden: {e}")))?
        .with_inputs(inputs.len())
        .map_err(|e| input_err(format!("obs: {} inputs: {}", inputs.len(), e.reason)))?;
    let mut net =
        Mlp::from_genome(shape, &genome).map_err(|e| input_err(format!("genome: {e}")))?;
    Ok(net.step(&inputs))
}
