//! The lock-step lanes for every robot, motion and network: four trials stepped together as
//! in [`crate::simulation::lanes`], for what the paper's lanes there do not run — `wheels`
//! motion, any sensor layout (1 to [`MAX_SENSORS`] sensors, any `reading_max`), any hidden
//! size, any noise level, and trials whose robot `[trial.randomise]` drew (each lane in its
//! own arena, with its own noise and wheel bias).
//!
//! Every trial takes exactly the steps [`simulate`](crate::simulation::trial::simulate)
//! takes: each lane reads its sensors and moves by [`Walk`]'s own code (the sensing, the arc
//! of `wheels` motion, the collision rule, the labels); between the two, the lanes draw their
//! noise from their streams in `simulate`'s order (`n` sensors, then the two wheels), add it
//! as `perturb_sensors` and `perturb` do, and run the four networks in double precision with
//! the operations of [`Mlp`]'s step in the same order ([`NetLanes::outputs`]). A lane adds
//! `w · 0` for an input of 0 that `Mlp` skips (unless it is +0 in all four lanes), which
//! changes a sum only in the sign of a zero sum, whose logistic is the same ½ — the argument
//! of the paper's lanes. A noise level of 0 gives factors of exactly 1 (`1 + 0 · u`), which
//! leave every value as `simulate`, which draws nothing, leaves it; the lane's stream is
//! then drawn but never seen. The tests compare whole trajectories with `simulate`'s.

use crate::simulation::controller::{Mlp, OUTPUTS};
use crate::simulation::isa::Isa;
use crate::simulation::lanes::{
    LANES, LaneTrial, Streams, all_plus_zero, paper_fit, walk_paper_lanes,
};
use crate::simulation::math::logistic_lanes;
use crate::simulation::memo::{Table, memo_live, with_table};
use crate::simulation::robot::Motion;
use crate::simulation::sensor::MAX_SENSORS;
use crate::simulation::trial::{Arena, Sensed, StepObserver, Walk};

/// Whether [`walk_lanes`] can run `net`'s trials in `arena` (or in arenas drawn from it):
/// any robot, motion, noise level and hidden size, one network input per sensor, finite
/// weights.
pub(crate) fn lanes_fit(arena: &Arena, net: &Mlp) -> bool {
    net.shape().inputs() == arena.sensors() && net.is_finite()
}

/// Runs every trial of `trials` in `arena` (each as [`simulate`](crate::simulation::trial::simulate)
/// would, from the room's home pose, in its drawn arena when it has one), four at a time. Each
/// trial must fit ([`lanes_fit`]). The paper's robot runs in the paper's lanes
/// (`lanes::walk_paper_lanes`), every other in this module's ([`walk_any`]).
pub(crate) fn walk_lanes<'a, O: StepObserver>(arena: &'a Arena, trials: &mut [LaneTrial<'a, O>]) {
    debug_assert!(trials.iter().all(|t| lanes_fit(arena, t.net)));
    if trials.iter().all(|t| paper_fit(arena, t)) {
        walk_paper_lanes(arena, trials)
    } else {
        walk_any(arena, trials)
    }
}

/// Runs every trial of `trials` in `arena` (a trial with a drawn robot in its own arena), as
/// [`simulate`](crate::simulation::trial::simulate) would, four at a time (one or two trials
/// one at a time: [`lanes_pay`]). Every network must
/// have one input per sensor and the same shape, and finite weights
/// ([`lanes_fit`]). With `actions` motion and no drawn robot the
/// lanes share the arena's memo of sightings, as `simulate` uses it (a pure cache).
pub(crate) fn walk_any<'a, O: StepObserver>(arena: &'a Arena, trials: &mut [LaneTrial<'a, O>]) {
    if !lanes_pay(trials.len()) {
        return walk_alone(arena, trials);
    }
    let Some(first) = trials.first() else { return };
    let shape = first.net.shape();
    debug_assert!(trials.iter().all(|t| t.net.shape() == shape));
    let shared = arena.params().robot.motion() == Motion::Actions
        && trials.iter().all(|t| t.drawn.is_none());
    let isa = Isa::detected();
    match arena.memo_owner().filter(|_| shared) {
        Some(owner) => with_table(owner, memo_live, |table| walk_on(isa, arena, trials, table)),
        None => walk_on(isa, arena, trials, None),
    }
}

/// Whether a batch of `trials` trials is walked in these lanes rather than one trial at a
/// time ([`walk_alone`]): from three on. The lanes' noise, networks and bookkeeping cost
/// the same whether a lane has a trial or not, so two trials in four lanes pay for four
/// (`bench --population 2`, `wheels` in the first release's H room, callgrind: 1,678
/// instructions a robot-step in the lanes against 1,382 alone, and slower by time too).
pub(crate) fn lanes_pay(trials: usize) -> bool {
    trials > 2
}

/// Each trial of `trials` alone, by [`simulate`](crate::simulation::trial::simulate) in its
/// arena (its drawn one, with its wheel bias on the network as `[trial.randomise]` puts it,
/// when it has one): the steps the lanes take, which the oracle tests compare with these.
fn walk_alone<'a, O: StepObserver>(arena: &'a Arena, trials: &mut [LaneTrial<'a, O>]) {
    use crate::experiment::robustness::Perturbed;
    use crate::random::rng::rng_from_seed;
    use crate::simulation::trial::simulate;
    for t in trials {
        let mut rng = rng_from_seed(t.seed);
        let mut net = t.net.clone();
        t.last = match t.drawn {
            Some(d) => {
                let mut biased = Perturbed {
                    net: &mut net,
                    dead: None,
                    bias: d.bias,
                };
                simulate(d.arena, &mut biased, &mut rng, &mut t.observer)
            }
            None => simulate(arena, &mut net, &mut rng, &mut t.observer),
        };
    }
}

/// [`walk`] compiled for `isa`, which the processor must have ([`Isa::detected`]).
fn walk_on<'a, O: StepObserver>(
    isa: Isa,
    arena: &'a Arena,
    trials: &mut [LaneTrial<'a, O>],
    memo: Option<&mut Table>,
) {
    // Eight rows of readings hold most robots' (the Khepera's, the e-puck2's, the Thymio
    // II's seven); any other count takes all `MAX_SENSORS`.
    let few = arena.sensors() <= 8;
    match isa {
        Isa::Baseline if few => walk::<false, 8, O>(arena, trials, memo),
        Isa::Baseline => walk::<false, MAX_SENSORS, O>(arena, trials, memo),
        #[cfg(target_arch = "x86_64")]
        // SAFETY: `Isa::Avx2` is only made when the processor has AVX2 and FMA
        // (`Isa::detected`).
        Isa::Avx2 if few => unsafe { walk_avx2::<8, O>(arena, trials, memo) },
        #[cfg(target_arch = "x86_64")]
        // SAFETY: as above.
        Isa::Avx2 => unsafe { walk_avx2::<MAX_SENSORS, O>(arena, trials, memo) },
    }
}

/// [`walk`] with AVX2 instructions: the lanes of the noise and the networks in one register,
/// and each lane's sensing and move compiled for AVX2.
///
/// # Safety
/// The processor must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn walk_avx2<'a, const S: usize, O: StepObserver>(
    arena: &'a Arena,
    trials: &mut [LaneTrial<'a, O>],
    memo: Option<&mut Table>,
) {
    walk::<true, S, O>(arena, trials, memo)
}

/// The step loop: each lane reads its sensors, the lanes draw and add their noise and run
/// their networks together, then each lane moves and reports its step; a lane whose trial
/// ends reports its idle steps and takes the next trial. `AVX2`: compiled with AVX2
/// ([`walk_avx2`]); `S`: rows for the readings, at least the robot's sensors.
#[inline(always)]
fn walk<'a, const AVX2: bool, const S: usize, O: StepObserver>(
    arena: &'a Arena,
    trials: &mut [LaneTrial<'a, O>],
    mut memo: Option<&mut Table>,
) {
    let n = arena.sensors();
    debug_assert!(n <= S);
    let mut lanes = AnyLanes::new(arena, trials[0].net);
    let mut next = 0;
    for l in 0..LANES {
        next = lanes.load(l, next, arena, trials);
    }
    while lanes.trial.iter().any(Option::is_some) {
        let mut sensed: [Option<Sensed>; LANES] = [None; LANES];
        // Sensor `k` of lane `l` in `raw[k][l]` (+0 for a lane without a trial).
        let mut raw = [[0.0; LANES]; S];
        for l in 0..LANES {
            if lanes.trial[l].is_some() {
                let s = lanes.walk[l].read(lanes.arena[l], memo.as_deref_mut());
                for (r, &v) in raw.iter_mut().zip(s.sensors.iter()) {
                    r[l] = v;
                }
                sensed[l] = Some(s);
            }
        }
        let raw = &mut raw[..n];
        // Every reading +0 in every lane: every network gives its outputs for inputs of 0
        // (`Mlp::step` returns them for inputs that are all 0).
        let open_floor = all_plus_zero(raw.iter().flatten());
        let (lo, hi) = (lanes.noise[0], lanes.noise[1]);
        for r in raw.iter_mut() {
            let d = lanes.streams.next_units::<AVX2>();
            for l in 0..LANES {
                // `perturb_sensors`: a reading of ±0 stays itself; a product is never below 0
                // (a reading ≥ 0, a factor ≥ 0.5), so only the clamp's upper end can act.
                r[l] = (r[l] * (lo[l] + (hi[l] - lo[l]) * d[l])).min(lanes.max[l]);
            }
        }
        let mut factors = [[0.0; LANES]; 2];
        for f in &mut factors {
            let d = lanes.streams.next_units::<AVX2>();
            for l in 0..LANES {
                f[l] = lo[l] + (hi[l] - lo[l]) * d[l];
            }
        }
        let mut motors = match open_floor {
            true => lanes.net.idle,
            false => lanes.net.outputs(&inputs_of::<S>(raw, &lanes.max)),
        };
        lanes.bias_motors(&mut motors);
        for l in 0..LANES {
            let (Some(j), Some(sensed)) = (lanes.trial[l], &mut sensed[l]) else {
                continue;
            };
            for (v, r) in sensed.sensors.iter_mut().zip(raw.iter()) {
                *v = r[l];
            }
            let m = [motors[0][l], motors[1][l]];
            let v_max = lanes.v_max[l];
            let noisy = [0, 1].map(|w| (2.0 * m[w] - 1.0) * v_max * factors[w][l]);
            let (t, lane_arena) = (lanes.t[l], lanes.arena[l]);
            let (step, home) =
                lanes.walk[l].act_noisy(t, lane_arena, sensed, m, noisy, (None, None));
            let trial = &mut trials[j];
            trial.observer.observe(&step);
            lanes.t[l] = t + 1;
            let params = lane_arena.params();
            if t + 1 == params.steps || (params.end_at_home && home) || trial.observer.finished() {
                for t in t + 1..params.steps {
                    trial.observer.observe(&lanes.walk[l].idle(t, n));
                }
                trial.last = lanes.walk[l].pose();
                next = lanes.load(l, next, arena, trials);
            }
        }
    }
}

/// The networks' inputs of the noisy readings `noisy[k][l]`: each / lane `l`'s `reading_max`,
/// 0 for a reading of 0 (`trial::inputs_of`).
#[inline(always)]
fn inputs_of<const S: usize>(noisy: &[[f64; LANES]], max: &[f64; LANES]) -> [[f64; LANES]; S] {
    let mut x = [[0.0; LANES]; S];
    for (xk, nk) in x.iter_mut().zip(noisy) {
        for l in 0..LANES {
            let input = nk[l] / max[l];
            xk[l] = if nk[l] == 0.0 { 0.0 } else { input };
        }
    }
    x
}

/// The state of the four lanes.
struct AnyLanes<'a> {
    /// The random stream of each lane's trial.
    streams: Streams,
    /// The trial each lane runs (`None` once no trial is left for it).
    trial: [Option<usize>; LANES],
    /// The arena each lane's trial runs in (its drawn robot's, or the batch's).
    arena: [&'a Arena; LANES],
    walk: [Walk; LANES],
    /// The step each lane is at.
    t: [usize; LANES],
    /// `noise[0][l]`, `noise[1][l]`: the ends `1 − n`, `1 + n` of lane `l`'s noise factors.
    noise: [[f64; LANES]; 2],
    /// Each lane's largest sensor value (its robot's `reading_max`).
    max: [f64; LANES],
    /// Each lane's top wheel speed (mm/s).
    v_max: [f64; LANES],
    /// Each lane's wheel bias, for a drawn robot.
    bias: [Option<f64>; LANES],
    net: NetLanes,
}

impl<'a> AnyLanes<'a> {
    /// Lanes in `arena`, for networks of `net`'s shape, no trial loaded.
    fn new(arena: &'a Arena, net: &Mlp) -> AnyLanes<'a> {
        AnyLanes {
            streams: Streams::new(),
            trial: [None; LANES],
            arena: [arena; LANES],
            walk: [Walk::at_home(arena); LANES],
            t: [0; LANES],
            noise: [[1.0; LANES]; 2],
            max: [1.0; LANES],
            v_max: [0.0; LANES],
            bias: [None; LANES],
            net: NetLanes::new(net),
        }
    }

    /// Puts the first trial from `next` on that has steps to run into lane `l` (a trial of no
    /// steps ends at home at once); returns the next trial not yet taken.
    fn load<O>(
        &mut self,
        l: usize,
        mut next: usize,
        arena: &'a Arena,
        trials: &mut [LaneTrial<'a, O>],
    ) -> usize {
        self.trial[l] = None;
        while let Some(trial) = trials.get_mut(next) {
            next += 1;
            let here = trial.drawn.map_or(arena, |d| d.arena);
            let params = here.params();
            if params.steps == 0 {
                trial.last = here.room().home;
                continue;
            }
            self.net.load(l, trial.net);
            self.streams.start(l, trial.seed);
            self.trial[l] = Some(next - 1);
            self.arena[l] = here;
            self.walk[l] = Walk::at_home(here);
            self.t[l] = 0;
            self.noise[0][l] = 1.0 - params.noise;
            self.noise[1][l] = 1.0 + params.noise;
            self.max[l] = params.robot.spec().reading_max();
            self.v_max[l] = params.robot.v_max();
            self.bias[l] = trial.drawn.map(|d| d.bias);
            break;
        }
        next
    }

    /// A drawn robot's wheel bias on its lane's outputs, as
    /// [`Perturbed`](crate::experiment::robustness::Perturbed) applies it: output `m` drives
    /// its wheel at `(2m − 1)·v_max`, scaled by `1 + bias`.
    #[inline(always)]
    fn bias_motors(&self, motors: &mut [[f64; LANES]; OUTPUTS]) {
        for (l, bias) in self.bias.iter().enumerate() {
            if let Some(b) = bias {
                for m in motors.iter_mut() {
                    m[l] = ((2.0 * m[l] - 1.0) * (1.0 + b) + 1.0) / 2.0;
                }
            }
        }
    }
}

/// Four networks of one shape (`inputs`-`hidden`-2), their weights side by side.
struct NetLanes {
    hidden: usize,
    /// `hidden_w[k · hidden + h][l]`: lane `l`'s weight of input `k` into hidden unit `h`
    /// (`k` = 0: the bias), [`Mlp::layers`]' order across the lanes.
    hidden_w: Vec<[f64; LANES]>,
    /// `out_w[o · (hidden + 1) + k][l]`: lane `l`'s weight of hidden unit `k` into output `o`
    /// (`k` = 0: the bias).
    out_w: Vec<[f64; LANES]>,
    /// `idle[o][l]`: lane `l`'s output `o` when all its inputs are 0 ([`Mlp::idle_outputs`]).
    idle: [[f64; LANES]; OUTPUTS],
    /// The hidden units' sums, then values, of one step (kept to spare an allocation a step).
    units: Vec<[f64; LANES]>,
}

impl NetLanes {
    /// Room for four networks of `net`'s shape, all weights 0.
    fn new(net: &Mlp) -> NetLanes {
        let shape = net.shape();
        let hidden = shape.hidden();
        NetLanes {
            hidden,
            hidden_w: vec![[0.0; LANES]; hidden * (shape.inputs() + 1)],
            out_w: vec![[0.0; LANES]; OUTPUTS * (hidden + 1)],
            idle: [[0.5; LANES]; OUTPUTS],
            units: vec![[0.0; LANES]; hidden],
        }
    }

    /// Puts `net` (of the lanes' shape) into lane `l`.
    fn load(&mut self, l: usize, net: &Mlp) {
        let (hidden, out) = net.layers();
        debug_assert_eq!(
            (hidden.len(), out.len()),
            (self.hidden_w.len(), self.out_w.len())
        );
        for (w, &v) in self.hidden_w.iter_mut().zip(hidden) {
            w[l] = v;
        }
        for (w, &v) in self.out_w.iter_mut().zip(out) {
            w[l] = v;
        }
        for (idle, m) in self.idle.iter_mut().zip(net.idle_outputs()) {
            idle[l] = m;
        }
    }

    /// The four networks on their inputs `x[k][l]` (input `k` of lane `l`; inputs past the
    /// networks' are ignored): each hidden sum `bias + w₁·x₁ + …` in that order, as
    /// `Mlp::step` adds it (an input of +0 in all four lanes skipped, as `Mlp` skips it), the
    /// logistic of each unit ([`logistic_lanes`]: the scalar function's bits), then each
    /// output's sum `bias + v₁·y₁ + …` and its logistic.
    #[inline(always)]
    fn outputs<const S: usize>(&mut self, x: &[[f64; LANES]; S]) -> [[f64; LANES]; OUTPUTS] {
        match self.hidden {
            6 => self.outputs_of::<S, 6>(x),
            _ => self.outputs_of::<S, 0>(x),
        }
    }

    /// [`NetLanes::outputs`] with `H` hidden units, or (`H` = 0) the networks' own number.
    #[inline(always)]
    fn outputs_of<const S: usize, const H: usize>(
        &mut self,
        x: &[[f64; LANES]; S],
    ) -> [[f64; LANES]; OUTPUTS] {
        let h = if H == 0 { self.hidden } else { H };
        let units = &mut self.units[..h];
        units.copy_from_slice(&self.hidden_w[..h]);
        for (xk, row) in x.iter().zip(self.hidden_w[h..].chunks_exact(h)) {
            if all_plus_zero(xk) {
                continue;
            }
            for (s, w) in units.iter_mut().zip(row) {
                for l in 0..LANES {
                    s[l] += w[l] * xk[l];
                }
            }
        }
        for s in units.iter_mut() {
            *s = logistic_lanes(*s);
        }
        let mut out = [[0.0; LANES]; OUTPUTS];
        for (o, w) in out.iter_mut().zip(self.out_w.chunks_exact(h + 1)) {
            let mut s = w[0];
            for (wk, y) in w[1..].iter().zip(units.iter()) {
                for l in 0..LANES {
                    s[l] += wk[l] * y[l];
                }
            }
            *o = logistic_lanes(s);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::robustness::Perturbed;
    use crate::random::rng::{rng_from_seed, uniform};
    use crate::simulation::controller::MlpShape;
    use crate::simulation::lanes::Drawn;
    use crate::simulation::robot::{DEFAULT_ACTION_TOLERANCE, Pose, RawRobot};
    use crate::simulation::robot_spec::RobotSpec;
    use crate::simulation::room::Room;
    use crate::simulation::trial::{RawTrial, Step, Trajectory, TrialParams, simulate};

    /// The trial parameters of the built-in robot `robot` with `motion`, `steps` steps,
    /// `end_at_home` and the robot file's noise unless `noise` is given.
    fn params(
        robot: &str,
        motion: Motion,
        steps: usize,
        end_at_home: bool,
        noise: Option<f64>,
    ) -> TrialParams {
        let spec = RobotSpec::builtin(robot).unwrap();
        let raw = RawTrial {
            steps,
            end_at_home,
            noise,
            ..RawTrial::default()
        };
        let robot = RawRobot {
            file: Some(robot.to_string()),
            motion,
            ..RawRobot::default()
        };
        TrialParams::from_raw(&raw, &robot, spec, DEFAULT_ACTION_TOLERANCE).unwrap()
    }

    /// The paper's room `name` for `robot`: the Thymio II's scaled 3× for its 80 mm body
    /// (rooms/thymio2/), the built-in room for the others.
    fn room_for(robot: &str, name: &str) -> Room {
        match (robot, name) {
            ("thymio2", "H") => thymio_room(include_str!("../../../../rooms/thymio2/H.toml")),
            ("thymio2", "T") => thymio_room(include_str!("../../../../rooms/thymio2/T.toml")),
            _ => Room::builtin(name).unwrap(),
        }
    }

    fn thymio_room(text: &str) -> Room {
        Room::from_toml_str(text, "rooms/thymio2").unwrap()
    }

    /// `n` networks of `hidden` units for `inputs` sensors, weights uniform in ±`scale`.
    fn networks(n: usize, inputs: usize, hidden: usize, seed: u64, scale: f64) -> Vec<Mlp> {
        let shape = (MlpShape::with_hidden(hidden).unwrap())
            .with_inputs(inputs)
            .unwrap();
        let mut rng = rng_from_seed(seed);
        (0..n)
            .map(|_| {
                let g: Vec<f64> = (0..shape.genome_len())
                    .map(|_| uniform(&mut rng, -scale, scale))
                    .collect();
                Mlp::from_genome(shape, &g).unwrap()
            })
            .collect()
    }

    /// A whole trajectory with each step's cell, which asks its trial to end after a number of
    /// steps of its own (trial `i`: 23 + 31·i) or at its end.
    #[derive(Debug)]
    struct Until {
        path: Trajectory,
        cells: Vec<Option<usize>>,
        stop: usize,
    }

    impl Until {
        fn new(arena: &Arena, i: usize) -> Until {
            let steps = arena.params().steps();
            Until {
                path: Trajectory::starting_at(arena.room().home, steps),
                cells: Vec::new(),
                stop: 23 + 31 * i,
            }
        }
    }

    impl StepObserver for Until {
        fn observe(&mut self, step: &Step) {
            self.cells.push(step.cell);
            self.path.observe(step);
        }

        fn finished(&self) -> bool {
            self.path.poses.len() > self.stop
        }
    }

    /// Runs `nets` (one trial each, trial `i` in `drawn[i]`'s arena when it has one) in the
    /// lanes and each alone in `simulate` (a drawn trial with its wheel bias on the network),
    /// requires the same trajectories, cells and final poses bit for bit, and returns how many
    /// steps each executed and how many of all steps collided.
    fn check(arena: &Arena, nets: &[Mlp], drawn: &[Option<Drawn<'_>>]) -> (Vec<usize>, usize) {
        let seed = |i: usize| 7000 + i as u64;
        let here = |i: usize| drawn[i].map_or(arena, |d| d.arena);
        let mut trials: Vec<_> = (nets.iter().enumerate())
            .map(|(i, net)| LaneTrial {
                net,
                seed: seed(i),
                observer: Until::new(here(i), i),
                last: Pose::new(f64::NAN, f64::NAN, f64::NAN),
                drawn: drawn[i],
            })
            .collect();
        assert!(nets.iter().all(|net| lanes_fit(arena, net)));
        walk_lanes(arena, &mut trials);
        let (mut executed, mut collided) = (Vec::new(), 0);
        for (i, trial) in trials.iter().enumerate() {
            let mut alone = Until::new(here(i), i);
            let mut rng = rng_from_seed(seed(i));
            let mut net = nets[i].clone();
            let last = match drawn[i] {
                Some(d) => {
                    let mut biased = Perturbed {
                        net: &mut net,
                        dead: None,
                        bias: d.bias,
                    };
                    simulate(d.arena, &mut biased, &mut rng, &mut alone)
                }
                None => simulate(arena, &mut net, &mut rng, &mut alone),
            };
            let what = format!("{}, trial {i}", arena.room().name);
            // Debug prints each f64 so that it reads back to the same bits (−0 included).
            let (lanes, alone_text) = (format!("{:?}", trial.observer), format!("{alone:?}"));
            assert!(lanes == alone_text, "{what}: the trajectories differ");
            let bits = |p: Pose| [p.x, p.y, p.heading].map(f64::to_bits);
            assert_eq!(bits(trial.last), bits(last), "{what}");
            executed.push(alone.path.executed());
            collided += alone.path.collisions.iter().filter(|&&c| c).count();
        }
        (executed, collided)
    }

    /// The Khepera with `wheels` motion takes in the lanes, bit for bit, the steps `simulate`
    /// takes: the arc, the wheel noise, the collision rule, the labels, in rooms with walls
    /// near home and without, trials that end at home or by their observers at different steps
    /// (lanes refilled mid-walk), fewer trials than lanes, small and large weights, and other
    /// hidden sizes; some moves collide.
    #[test]
    fn wheels_lanes_take_the_steps_simulate_takes() {
        let mut collided = 0;
        for (room, end, steps, n, hidden, scale) in [
            ("H", true, 400, 13, 6, 1.0),
            ("H", false, 250, 9, 6, 30.0),
            ("T", true, 300, 7, 3, 5.0),
            ("square", true, 200, 3, 6, 1.0),
            ("L", false, 160, 6, 11, 800.0),
            ("rectangle", true, 1, 5, 6, 1.0),
        ] {
            let p = params("khepera", Motion::Wheels, steps, end, None);
            let arena = Arena::new(Room::builtin(room).unwrap(), &p);
            let nets = networks(n, 8, hidden, steps as u64 + n as u64, scale);
            let (executed, c) = check(&arena, &nets, &vec![None; n]);
            collided += c;
            let mut ends = executed.clone();
            ends.dedup();
            assert!(steps == 1 || ends.len() > 2, "{room}: {executed:?}");
        }
        assert!(
            collided > 50,
            "{collided} collisions: the collision rule is barely tested"
        );
    }

    /// Lanes are used from three trials on: one or two trials in four lanes would pay for
    /// four (see [`lanes_pay`]).
    #[test]
    fn lanes_pay_from_three_trials() {
        assert!(!lanes_pay(1) && !lanes_pay(2));
        assert!((3..=40).all(lanes_pay));
    }

    /// A batch of one or two trials, walked alone, takes the steps `simulate` takes: either
    /// motion, the batch's own robot and drawn ones (their arena and wheel bias).
    #[test]
    fn small_batches_take_the_steps_simulate_takes() {
        use crate::experiment::Perturbation as P;
        for (robot, motion, n) in [
            ("khepera", Motion::Wheels, 1),
            ("khepera", Motion::Wheels, 2),
            ("epuck2", Motion::Actions, 2),
        ] {
            let p = params(robot, motion, 300, true, None);
            let arena = Arena::new(room_for(robot, "H"), &p);
            let own = Arena::new(arena.room().clone(), &P::Noise(0.09).apply(p).unwrap());
            let nets = networks(n, arena.sensors(), 6, 5 + n as u64, 3.0);
            let (executed, _) = check(&arena, &nets, &vec![None; n]);
            assert!(executed.iter().all(|&e| e > 0), "{robot}: {executed:?}");
            let drawn = vec![
                Some(Drawn {
                    arena: &own,
                    bias: -0.08
                });
                n
            ];
            check(&arena, &nets, &drawn);
        }
    }

    /// The e-puck2 (eight sensors reading up to 3731) and the Thymio II (seven, up to 4505)
    /// take in the lanes the steps `simulate` takes, with `wheels` and `actions` motion, and
    /// the Khepera with `actions` motion and networks the paper's lanes do not run (other
    /// hidden sizes, no noise).
    #[test]
    fn other_layouts_and_networks_take_the_steps_simulate_takes() {
        for (robot, motion, room, hidden, noise) in [
            ("epuck2", Motion::Wheels, "H", 6, None),
            ("epuck2", Motion::Actions, "T", 6, None),
            ("thymio2", Motion::Wheels, "H", 6, None),
            ("thymio2", Motion::Actions, "T", 4, None),
            ("khepera", Motion::Actions, "H", 9, None),
            ("khepera", Motion::Actions, "T", 6, Some(0.0)),
            ("thymio2", Motion::Wheels, "H", 6, Some(0.0)),
        ] {
            let p = params(robot, motion, 300, true, noise);
            let arena = Arena::new(room_for(robot, room), &p);
            let inputs = arena.sensors();
            let nets = networks(10, inputs, hidden, inputs as u64, 4.0);
            let (executed, collided) = check(&arena, &nets, &[None; 10]);
            let lit = executed.iter().filter(|&&e| e > 0).count();
            assert!(lit == 10, "{robot} {motion:?}: {executed:?}");
            assert!(collided > 0, "{robot} {motion:?} in {room:?}: no collision");
        }
    }

    /// Trials whose robot `[trial.randomise]` drew (another noise level, sensor table scale
    /// and body radius: each lane in its own arena; a wheel bias, 0 included, on its network)
    /// take in the lanes the steps `simulate` takes with the drawn arena and the biased
    /// network, among trials of the batch's own robot: the Khepera with either motion, the
    /// e-puck2 with `wheels`.
    #[test]
    fn drawn_robots_take_the_steps_simulate_takes() {
        use crate::experiment::Perturbation as P;
        for (robot, motion) in [
            ("khepera", Motion::Actions),
            ("khepera", Motion::Wheels),
            ("epuck2", Motion::Wheels),
        ] {
            let p = params(robot, motion, 300, true, None);
            let arena = Arena::new(room_for(robot, "H"), &p);
            let radius = p.robot().radius();
            let draws = [
                vec![P::Noise(0.11), P::TableScale(0.83), P::Radius(radius * 1.1)],
                vec![P::Noise(0.0)],
                vec![P::TableScale(1.27)],
                vec![P::Radius(radius * 1.2), P::Noise(0.02)],
                vec![],
            ];
            let arenas: Vec<Arena> = (draws.iter())
                .map(|d| {
                    let drawn = d.iter().fold(p, |t, q| q.apply(t).unwrap());
                    Arena::new(arena.room().clone(), &drawn)
                })
                .collect();
            let n = 11;
            let drawn: Vec<Option<Drawn<'_>>> = (0..n)
                .map(|i| {
                    (i % 4 != 3).then(|| Drawn {
                        arena: &arenas[i % arenas.len()],
                        bias: [0.0, 0.07, -0.12][i % 3],
                    })
                })
                .collect();
            let nets = networks(n, arena.sensors(), 6, 99, 3.0);
            let (executed, _) = check(&arena, &nets, &drawn);
            assert!(executed.iter().all(|&e| e > 0), "{robot}: {executed:?}");
        }
    }
}
