//! Trials in lock-step: four trials of one arena stepped together, their sensor noise and
//! their networks computed across the four in vector lanes, each lane taking the next trial
//! as soon as its own ends.
//!
//! A trial of [`simulate`](crate::simulation::trial::simulate) is one long chain of dependent
//! operations (pose → sensors → two logistic layers → action → next pose); four independent
//! chains side by side keep the processor busy while each waits, and the network's arithmetic
//! for four robots takes the instructions of one. Every trial takes exactly the steps
//! `simulate` takes: the same operations in the same order on each lane's own numbers, its own
//! random stream drawn in the same order (ten draws per step: eight sensors, two wheels), the
//! same observer calls. The one difference in the arithmetic is that a lane adds `w · 0` for a
//! sensor that reads 0 (unless it reads +0 in all four lanes: then all skip it), which
//! `simulate`'s network skips: with finite weights that term is ±0,
//! which leaves a sum unchanged except for the sign of a zero sum, and `logistic(±0)` is the
//! same 0.5. The tests below compare whole trajectories with `simulate`'s.
//!
//! With `actions` motion a step's network outputs matter only through its action, so when no
//! observer reads the outputs ([`StepObserver::reads_motors`]: the evaluation's fitness terms)
//! the lanes first compute them roughly (in single precision, eight numbers to a vector
//! instruction: [`Lanes::rough_network`]) with a bound on how far each can be from the exact
//! output, and keep them when every lane's action is the same for all outputs within the bounds
//! ([`actions_are_certain`]); otherwise (7 steps of the lanes in 10,000 on evolved robots:
//! generations 101–200 of the high-curiosity run) they compute the exact outputs. The actions,
//! and so every pose, cell and term, are the exact ones; only the steps' `motors` and `speeds`
//! are rough.

use crate::simulation::controller::{INPUTS, Mlp, OUTPUTS};
use crate::simulation::isa::Isa;
#[cfg(target_arch = "x86_64")]
use crate::simulation::math::logistic_rough_avx2;
use crate::simulation::math::{LOGISTIC_ROUGH_ERR, logistic_lanes, logistic_rough_lanes};
use crate::simulation::memo::{Sight, Table, memo_live, with_table};
use crate::simulation::robot::{Motion, Pose};
use crate::simulation::sensor::SENSOR_MAX;
use crate::simulation::trial::{Arena, Sensed, StepObserver, Walk};

/// Trials stepped together.
pub(crate) const LANES: usize = 4;
/// The hidden units of the networks the lanes run (the default 8-6-2).
const HIDDEN: usize = 6;
/// Random draws per step: the eight sensors', then the two wheels'.
const DRAWS: usize = INPUTS + 2;

/// One trial for [`walk_lanes`](crate::simulation::lanes_any::walk_lanes): its network, the seed
/// of its random stream (the stream of
/// [`rng_from_seed`](crate::random::rng::rng_from_seed)) and what watches its steps; `last` is
/// its final pose once it has run; `drawn`, the robot `[trial.randomise]` drew for it, if any.
pub(crate) struct LaneTrial<'a, O> {
    pub(crate) net: &'a Mlp,
    pub(crate) seed: u64,
    pub(crate) observer: O,
    pub(crate) last: Pose,
    pub(crate) drawn: Option<Drawn<'a>>,
}

/// A trial's own robot, drawn by `[trial.randomise]`: the arena prepared for its body, sensors
/// and noise, and the bias on its wheel speeds, which the trial's controller applies to the
/// network's outputs as [`Perturbed`](crate::experiment::robustness::Perturbed) does (even a
/// bias of 0, whose arithmetic may move an output by an ulp).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Drawn<'a> {
    /// The arena the trial runs in, in place of the batch's.
    pub(crate) arena: &'a Arena,
    /// Both wheel speeds multiplied by 1 + `bias`.
    pub(crate) bias: f64,
}

/// Whether the paper's lanes of this module run `trial` in `arena`: `actions` motion with
/// noise (so every step takes its ten draws), eight sensors reading 0–1023 (the Khepera's),
/// the 8-6-2 network, finite weights, the batch's own robot.
pub(crate) fn paper_fit<O>(arena: &Arena, trial: &LaneTrial<'_, O>) -> bool {
    let params = arena.params();
    let spec = params.robot.spec();
    params.robot.motion() == Motion::Actions
        && spec.sensors() == INPUTS
        && spec.reading_max() == SENSOR_MAX
        && params.noise > 0.0
        && trial.net.shape().inputs() == INPUTS
        && trial.net.shape().hidden() == HIDDEN
        && trial.net.is_finite()
        && trial.drawn.is_none()
}

/// Runs every trial of `trials` in `arena` (each as [`simulate`](crate::simulation::trial::simulate)
/// would, from the room's home pose), four at a time, in the paper's lanes: every trial must
/// fit them ([`paper_fit`]). `lanes_any::walk_lanes` chooses these lanes or its own.
pub(crate) fn walk_paper_lanes<O: StepObserver>(arena: &Arena, trials: &mut [LaneTrial<'_, O>]) {
    debug_assert!(trials.iter().all(|t| paper_fit(arena, t)));
    let isa = Isa::detected();
    match arena.memo_owner() {
        Some(owner) => with_table(owner, memo_live, |table| walk_on(isa, arena, trials, table)),
        None => walk_on(isa, arena, trials, None),
    }
}

/// [`walk`] compiled for `isa`, which the processor must have ([`Isa::detected`]).
fn walk_on<O: StepObserver>(
    isa: Isa,
    arena: &Arena,
    trials: &mut [LaneTrial<'_, O>],
    memo: Option<&mut Table>,
) {
    match isa {
        Isa::Baseline => walk::<false, O>(arena, trials, memo),
        #[cfg(target_arch = "x86_64")]
        // SAFETY: `Isa::Avx2` is only made when the processor has AVX2 and FMA
        // (`Isa::detected`).
        Isa::Avx2 => unsafe { walk_avx2(arena, trials, memo) },
    }
}

/// [`walk`] with AVX2 instructions (the lanes of the noise and the network in one register),
/// and FMA in the rough network ([`rough_network_avx2`]).
///
/// # Safety
/// The processor must have AVX2 and FMA.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn walk_avx2<O: StepObserver>(
    arena: &Arena,
    trials: &mut [LaneTrial<'_, O>],
    memo: Option<&mut Table>,
) {
    walk::<true, O>(arena, trials, memo)
}

/// The step loop of the lanes: read and draw lane by lane, add the sensor noise and run the
/// networks across the lanes, then act and report lane by lane; a lane whose trial ends
/// reports its idle steps and takes the next trial. `AVX2`: the loop is compiled with AVX2
/// ([`walk_avx2`]), so that its explicit AVX2 parts may run.
#[inline(always)]
fn walk<const AVX2: bool, O: StepObserver>(
    arena: &Arena,
    trials: &mut [LaneTrial<'_, O>],
    mut memo: Option<&mut Table>,
) {
    let params = arena.params();
    let (lo, hi) = (1.0 - params.noise, 1.0 + params.noise);
    let (v_max, tolerance) = (params.robot.v_max(), params.action_tolerance());
    // Whether the steps must carry the networks' exact outputs, or only exact actions.
    let exact = !rough_speeds_fit(v_max) || trials.iter().any(|t| t.observer.reads_motors());
    let mut lanes = Lanes::new(arena);
    let mut next = 0;
    for l in 0..LANES {
        next = lanes.load(l, next, arena, trials);
    }
    while lanes.trial.iter().any(Option::is_some) {
        let (mut sights, mut ahead) = ([Sight::CLEAR; LANES], [0; LANES]);
        for l in 0..LANES {
            if lanes.trial[l].is_some() {
                sights[l] = lanes.walk[l].sight(arena, memo.as_deref_mut());
                // Taken now, off the chain from the network's outputs to the next pose.
                ahead[l] = lanes.walk[l].ahead_cell(arena);
            }
        }
        // Sensor `k` of every lane side by side, for the vector lanes below.
        let mut raw = side_by_side::<AVX2>(&sights);
        // Plain loops, not `array::from_fn`, here and below: a closure the compiler leaves out
        // of line would run without this function's AVX2.
        let mut draws = [[0.0; LANES]; DRAWS];
        for d in &mut draws {
            *d = lanes.streams.next_units::<AVX2>();
        }
        // In open floor every reading of a lane is 0 (a third of the study's steps), and so
        // every noisy reading and input; when that holds for all four, each network's output
        // is the one it computed at the start. Tested on the bits of the readings before the
        // noise, so that the test waits for nothing: one vector `or` per sensor. (A reading of
        // −0, or one whose noisy reading or input is 0, runs the networks, which compute the
        // same outputs from inputs of ±0.)
        let open_floor = all_plus_zero(raw.iter().flatten());
        add_sensor_noise(&mut raw, &draws, (lo, hi));
        // The wheels' noise factors (`perturb`), in the order `Walk::act` draws them.
        let mut factors = [[0.0; LANES]; 2];
        for (f, d) in factors.iter_mut().zip(&draws[INPUTS..]) {
            for l in 0..LANES {
                f[l] = lo + (hi - lo) * d[l];
            }
        }
        let motors = match open_floor {
            true => lanes.idle,
            false if exact => lanes.network(&inputs_of(&raw)),
            false => lanes.network_for_actions::<AVX2>(&raw, &factors, tolerance),
        };
        // The noisy speeds of every lane, as `perturb` computes them.
        let mut speeds = [[0.0; LANES]; 2];
        for ((s, m), f) in speeds.iter_mut().zip(&motors).zip(&factors) {
            for l in 0..LANES {
                s[l] = (2.0 * m[l] - 1.0) * v_max * f[l];
            }
        }
        let step = LaneStep {
            sights: &sights,
            ahead: &ahead,
            raw: &raw,
            motors: &motors,
            speeds: &speeds,
        };
        next = lanes.act(arena, trials, next, &step);
    }
}

/// What the lanes computed for one step, side by side: each lane's sight and the cell ahead of
/// it, the noisy readings (`raw[k][l]`: sensor `k` of lane `l`), the networks' outputs and
/// the noisy wheel speeds.
struct LaneStep<'a> {
    sights: &'a [Sight; LANES],
    ahead: &'a [usize; LANES],
    raw: &'a [[f64; LANES]; INPUTS],
    motors: &'a [[f64; LANES]; OUTPUTS],
    speeds: &'a [[f64; LANES]; 2],
}

impl Lanes {
    /// The end of a step of [`walk`]: each lane that runs a trial acts on `step` and reports
    /// its step; a lane whose trial ends reports its idle steps and takes the next trial from
    /// `next` on. Returns the next trial not yet taken.
    #[inline(always)]
    fn act<O: StepObserver>(
        &mut self,
        arena: &Arena,
        trials: &mut [LaneTrial<'_, O>],
        mut next: usize,
        step: &LaneStep<'_>,
    ) -> usize {
        let params = arena.params();
        for l in 0..LANES {
            let Some(j) = self.trial[l] else { continue };
            let mut noisy_sensors = [0.0; INPUTS];
            for (k, s) in noisy_sensors.iter_mut().enumerate() {
                *s = step.raw[k][l];
            }
            let sensed = Sensed::straight(noisy_sensors, step.sights[l].blocked);
            let m = [step.motors[0][l], step.motors[1][l]];
            let noisy = [step.speeds[0][l], step.speeds[1][l]];
            let t = self.t[l];
            let how = (None, Some(step.ahead[l]));
            let (taken, home) = self.walk[l].act_noisy(t, arena, &sensed, m, noisy, how);
            let trial = &mut trials[j];
            trial.observer.observe(&taken);
            self.t[l] = t + 1;
            if t + 1 == params.steps || (params.end_at_home && home) || trial.observer.finished() {
                for t in t + 1..params.steps {
                    trial.observer.observe(&self.walk[l].idle(t, INPUTS));
                }
                trial.last = self.walk[l].pose();
                next = self.load(l, next, arena, trials);
            }
        }
        next
    }
}

/// Whether every one of `values` is +0: their bits ORed together (no compare, no early exit, so
/// a few vector `or`s for an array).
#[inline(always)]
pub(crate) fn all_plus_zero<'a>(values: impl IntoIterator<Item = &'a f64>) -> bool {
    values.into_iter().fold(0, |z, v| z | v.to_bits()) == 0
}

/// `raw[k][l]`: sensor `k` of lane `l`'s sight (the readings transposed). The compiler moves
/// the 32 values one by one; the AVX2 form is eight loads and sixteen shuffles.
#[inline(always)]
fn side_by_side<const AVX2: bool>(sights: &[Sight; LANES]) -> [[f64; LANES]; INPUTS] {
    let mut raw = [[0.0; LANES]; INPUTS];
    #[cfg(target_arch = "x86_64")]
    if AVX2 {
        // SAFETY: `AVX2` is only set in `walk_avx2`, which runs only on processors with AVX2.
        unsafe { side_by_side_avx2(sights, &mut raw) };
        return raw;
    }
    for (k, r) in raw.iter_mut().enumerate() {
        for l in 0..LANES {
            r[l] = sights[l].sensors[k];
        }
    }
    raw
}

/// [`side_by_side`] in AVX2 instructions: each block of four sensors of the four lanes is a
/// 4 × 4 transposition (pairs interleaved within halves, then halves exchanged).
///
/// # Safety
/// The processor must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn side_by_side_avx2(sights: &[Sight; LANES], raw: &mut [[f64; LANES]; INPUTS]) {
    use std::arch::x86_64::{
        _mm256_loadu_pd, _mm256_permute2f128_pd, _mm256_storeu_pd, _mm256_unpackhi_pd,
        _mm256_unpacklo_pd,
    };
    const { assert!(LANES == 4 && INPUTS % 4 == 0, "blocks of four doubles") };
    for b in 0..INPUTS / 4 {
        // SAFETY: every pointer is to four consecutive `f64` inside `sights[l].sensors` or
        // `raw` (4·b + 3 < INPUTS); the unaligned forms need no alignment.
        unsafe {
            let row = |l: usize| _mm256_loadu_pd(sights[l].sensors[4 * b..].as_ptr());
            let (r0, r1, r2, r3) = (row(0), row(1), row(2), row(3));
            let (t0, t1) = (_mm256_unpacklo_pd(r0, r1), _mm256_unpackhi_pd(r0, r1));
            let (t2, t3) = (_mm256_unpacklo_pd(r2, r3), _mm256_unpackhi_pd(r2, r3));
            // Rows 4·b … 4·b + 3 of `raw`, end to end.
            let out = raw[4 * b..].as_mut_ptr().cast::<f64>();
            _mm256_storeu_pd(out, _mm256_permute2f128_pd::<0x20>(t0, t2));
            _mm256_storeu_pd(out.add(LANES), _mm256_permute2f128_pd::<0x20>(t1, t3));
            _mm256_storeu_pd(out.add(2 * LANES), _mm256_permute2f128_pd::<0x31>(t0, t2));
            _mm256_storeu_pd(out.add(3 * LANES), _mm256_permute2f128_pd::<0x31>(t1, t3));
        }
    }
}

/// Adds the sensor noise to the readings `raw[k][l]` (sensor `k` of lane `l`) with the step's
/// uniform draws `draws` on [`lo`, `hi`), as `perturb_sensors` does one robot's.
#[inline(always)]
fn add_sensor_noise(
    raw: &mut [[f64; LANES]; INPUTS],
    draws: &[[f64; LANES]; DRAWS],
    (lo, hi): (f64, f64),
) {
    // `perturb_sensors` keeps a reading of 0 and clamps a scaled one to [0, 1023]. A reading is
    // in [0, 1023] and the noise factor in [0.5, 1.5] (the noise level is at most 0.5), so the
    // product of a reading of ±0 is that same zero, and a product is never below 0: only the
    // upper end of the clamp can act. So one product and one minimum per value, in vector
    // lanes without a branch, give the bits of `perturb_sensors`' branches.
    debug_assert!(lo > 0.0 && hi.is_finite());
    for k in 0..INPUTS {
        for l in 0..LANES {
            raw[k][l] = (raw[k][l] * (lo + (hi - lo) * draws[k][l])).min(SENSOR_MAX);
        }
    }
}

/// The networks' inputs of the noisy readings `noisy[k][l]`: each / 1023, 0 for a reading of 0
/// (`inputs_of`).
#[inline(always)]
fn inputs_of(noisy: &[[f64; LANES]; INPUTS]) -> [[f64; LANES]; INPUTS] {
    let mut x = [[0.0; LANES]; INPUTS];
    for k in 0..INPUTS {
        for l in 0..LANES {
            let input = noisy[k][l] / SENSOR_MAX;
            x[k][l] = if noisy[k][l] == 0.0 { 0.0 } else { input };
        }
    }
    x
}

/// The lanes' random streams: xoshiro256++ (the generator of
/// [`rng_from_seed`](crate::random::rng::rng_from_seed), `rand_xoshiro`'s), one stream per
/// lane, its state word `i` of lane `l` in `s[i][l]` so that a draw for every lane is one
/// vector operation per step of the generator.
pub(crate) struct Streams {
    s: [[u64; LANES]; 4],
}

impl Streams {
    /// Four streams, each to be started ([`Streams::start`]) before it is drawn from.
    pub(crate) fn new() -> Streams {
        Streams { s: [[0; LANES]; 4] }
    }

    /// Lane `l` starts the stream of `seed` as `rng_from_seed` does: the state is four
    /// outputs of SplitMix64 from `seed`. (They are never all 0, the one state xoshiro
    /// cannot take: SplitMix64's output function is a bijection of its counter, which is
    /// different for each of the four.)
    pub(crate) fn start(&mut self, l: usize, seed: u64) {
        let mut x = seed;
        for word in &mut self.s {
            x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = x;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            word[l] = z ^ (z >> 31);
        }
    }

    /// The next draw of every lane, as a uniform draw from [0, 1) with 53 random bits
    /// ([`uniform01`](crate::random::rng::uniform01)'s value). `AVX2`: the caller is compiled
    /// with AVX2 ([`walk_avx2`]).
    #[inline(always)]
    pub(crate) fn next_units<const AVX2: bool>(&mut self) -> [f64; LANES] {
        let [s0, s1, s2, s3] = &mut self.s;
        let mut out = [0.0; LANES];
        for l in 0..LANES {
            let n = s0[l]
                .wrapping_add(s3[l])
                .rotate_left(23)
                .wrapping_add(s0[l]);
            let t = s1[l] << 17;
            s2[l] ^= s0[l];
            s3[l] ^= s1[l];
            s1[l] ^= s2[l];
            s0[l] ^= s3[l];
            s2[l] ^= t;
            out[l] = unit(n);
        }
        rotate_left_45::<AVX2>(s3);
        out
    }
}

/// Each word of `s` turned left by 45 bits. The compiler does the rotation of four words lane
/// by lane (AVX2 has no rotation of 64-bit lanes); in the AVX2 form it is two shifts and an
/// or across the lanes.
#[inline(always)]
fn rotate_left_45<const AVX2: bool>(s: &mut [u64; LANES]) {
    #[cfg(target_arch = "x86_64")]
    if AVX2 {
        // SAFETY: `AVX2` is only set in `walk_avx2`, which runs only on processors with AVX2.
        unsafe { rotate_left_45_avx2(s) };
        return;
    }
    for w in s {
        *w = w.rotate_left(45);
    }
}

/// [`rotate_left_45`] in AVX2 instructions.
///
/// # Safety
/// The processor must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn rotate_left_45_avx2(s: &mut [u64; LANES]) {
    use std::arch::x86_64::{
        __m256i, _mm256_loadu_si256, _mm256_or_si256, _mm256_slli_epi64, _mm256_srli_epi64,
        _mm256_storeu_si256,
    };
    const { assert!(LANES * 64 == 256, "four lanes are one AVX2 register") };
    let p = s.as_mut_ptr().cast::<__m256i>();
    // SAFETY: `s` is 256 bits (`LANES` u64), valid for reads and writes; the unaligned forms
    // need no alignment.
    unsafe {
        let v = _mm256_loadu_si256(p);
        let turned = _mm256_or_si256(_mm256_slli_epi64::<45>(v), _mm256_srli_epi64::<19>(v));
        _mm256_storeu_si256(p, turned);
    }
}

/// `(n >> 11) as f64 · 2⁻⁵³`, [`uniform01`](crate::random::rng::uniform01)'s value of the 64
/// bits `n`, with operations that have vector forms. `m = n >> 11 < 2⁵³` is split into its
/// high 21 and low 32 bits, each written into the significand of a double whose value is then
/// exactly `2⁸⁴ + high·2³²` and `2⁵² + low`; subtracting `2⁸⁴ + 2⁵²` from the first and adding
/// the second gives `m` exactly (every intermediate value is a whole multiple of its own
/// precision below 2⁵³), and the scaling by a power of two is exact.
#[inline(always)]
fn unit(n: u64) -> f64 {
    let m = n >> 11;
    let high = f64::from_bits((m >> 32) | 0x4530_0000_0000_0000);
    let low = f64::from_bits((m & 0xffff_ffff) | 0x4330_0000_0000_0000);
    let m = (high - f64::from_bits(0x4530_0000_0010_0000)) + low;
    m * (1.0 / (1u64 << 53) as f64)
}

/// The state of the four lanes.
struct Lanes {
    /// The random stream of each lane's trial.
    streams: Streams,
    /// The trial each lane runs (`None` once no trial is left for it).
    trial: [Option<usize>; LANES],
    walk: [Walk; LANES],
    /// The step each lane is at.
    t: [usize; LANES],
    /// `hidden[k][h][l]`: lane `l`'s weight of input `k` into hidden unit `h` (`k` = 0: the
    /// bias), [`Mlp::layers`]' order across the lanes.
    hidden: [[[f64; LANES]; HIDDEN]; INPUTS + 1],
    /// `out[o][k][l]`: lane `l`'s weight of hidden unit `k` into output `o` (`k` = 0: the bias).
    out: [[[f64; LANES]; HIDDEN + 1]; OUTPUTS],
    /// `idle[o][l]`: lane `l`'s output `o` when all its inputs are 0 ([`Mlp::idle_outputs`]).
    idle: [[f64; LANES]; OUTPUTS],
    /// `rough_hidden[k][h · LANES + l]`: `hidden[k][h][l]` in single precision, for
    /// [`Lanes::rough_network`]; the weights of the inputs (`k` ≥ 1) divided by 1023 first, so
    /// that the network takes the readings as they are.
    rough_hidden: [[f32; HIDDEN * LANES]; INPUTS + 1],
    /// `rough_out[k][o · LANES + l]`: `out[o][k][l]` in single precision.
    rough_out: [[f32; OUTPUTS * LANES]; HIDDEN + 1],
    /// `rough[o][l]`: how far lane `l`'s output `o` of [`Lanes::rough_network`] can be from
    /// the exact one ([`rough_output_bound`]).
    rough: [[f64; LANES]; OUTPUTS],
}

impl Lanes {
    fn new(arena: &Arena) -> Lanes {
        Lanes {
            streams: Streams::new(),
            trial: [None; LANES],
            walk: [Walk::at_home(arena); LANES],
            t: [0; LANES],
            hidden: [[[0.0; LANES]; HIDDEN]; INPUTS + 1],
            out: [[[0.0; LANES]; HIDDEN + 1]; OUTPUTS],
            idle: [[0.5; LANES]; OUTPUTS],
            rough_hidden: [[0.0; HIDDEN * LANES]; INPUTS + 1],
            rough_out: [[0.0; OUTPUTS * LANES]; HIDDEN + 1],
            rough: [[f64::INFINITY; LANES]; OUTPUTS],
        }
    }

    /// Puts the first trial from `next` on that has steps to run into lane `l` (a trial of no
    /// steps ends at home at once); returns the next trial not yet taken.
    fn load<O>(
        &mut self,
        l: usize,
        mut next: usize,
        arena: &Arena,
        trials: &mut [LaneTrial<'_, O>],
    ) -> usize {
        self.trial[l] = None;
        while let Some(trial) = trials.get_mut(next) {
            next += 1;
            if arena.params().steps == 0 {
                trial.last = arena.room().home;
                continue;
            }
            let (hidden, out) = trial.net.layers();
            for (k, row) in hidden.chunks_exact(HIDDEN).enumerate() {
                for (h, &w) in row.iter().enumerate() {
                    self.hidden[k][h][l] = w;
                    let w = if k == 0 { w } else { w / SENSOR_MAX };
                    self.rough_hidden[k][h * LANES + l] = w as f32;
                }
            }
            let mut hidden_sums = [0.0f64; HIDDEN];
            for row in hidden.chunks_exact(HIDDEN) {
                for (sum, w) in hidden_sums.iter_mut().zip(row) {
                    *sum += w.abs();
                }
            }
            let hidden_sum = hidden_sums.iter().fold(0.0, |a, &b| f64::max(a, b));
            for (o, row) in out.chunks_exact(HIDDEN + 1).enumerate() {
                for (k, &w) in row.iter().enumerate() {
                    self.out[o][k][l] = w;
                    self.rough_out[k][o * LANES + l] = w as f32;
                }
                self.rough[o][l] = rough_output_bound(row, hidden_sum);
            }
            for (idle, m) in self.idle.iter_mut().zip(trial.net.idle_outputs()) {
                idle[l] = m;
            }
            self.streams.start(l, trial.seed);
            self.trial[l] = Some(next - 1);
            self.walk[l] = Walk::at_home(arena);
            self.t[l] = 0;
            break;
        }
        next
    }

    /// Outputs of the four networks on the noisy readings `noisy` that choose the same actions
    /// as the exact ones ([`Lanes::network`] of [`inputs_of`]): the rough outputs
    /// ([`Lanes::rough_network`]) when, for every lane
    /// that runs a trial, no output within the rough ones' bounds could choose another action
    /// with the step's wheel noise factors `factors[w][l]` (wheel `w` of lane `l`) and
    /// `tolerance` ([`actions_are_certain`]), else the exact outputs. Only for observers that
    /// do not read the outputs.
    #[inline(always)]
    fn network_for_actions<const AVX2: bool>(
        &self,
        noisy: &[[f64; LANES]; INPUTS],
        factors: &[[f64; LANES]; 2],
        tolerance: f64,
    ) -> [[f64; LANES]; OUTPUTS] {
        let rough = self.rough_network::<AVX2>(noisy);
        let mut certain = true;
        for l in 0..LANES {
            let noise = [factors[0][l], factors[1][l]];
            let m = [rough[0][l], rough[1][l]];
            let bound = [self.rough[0][l], self.rough[1][l]];
            let sure = actions_are_certain(m, bound, noise, tolerance);
            certain &= sure | self.trial[l].is_none();
        }
        #[cfg(test)]
        tests::count_rough(certain);
        match certain {
            true => rough,
            false => self.network(&inputs_of(noisy)),
        }
    }

    /// The four networks on their inputs `x[k][l]` (input `k` of lane `l`): each unit's sum
    /// `bias + w₁·x₁ + … + w₈·x₈` in that order, as `Mlp::step` adds it (it skips an input of
    /// 0; here an input of +0 in all four lanes is skipped, as most are, and any other added:
    /// `w · 0` changes no sum but the sign of a zero one), then the logistic
    /// units of a layer together ([`logistic_lanes`]: the scalar function's bits).
    #[inline(always)]
    fn network(&self, x: &[[f64; LANES]; INPUTS]) -> [[f64; LANES]; OUTPUTS] {
        let mut sums = self.hidden[0];
        for (k, xk) in x.iter().enumerate() {
            if all_plus_zero(xk) {
                continue;
            }
            for (s, w) in sums.iter_mut().zip(&self.hidden[k + 1]) {
                for l in 0..LANES {
                    s[l] += w[l] * xk[l];
                }
            }
        }
        let hidden = logistic_lanes::<{ HIDDEN * LANES }>(flat(&sums));
        let mut out = [[0.0; LANES]; OUTPUTS];
        for (o, w) in out.iter_mut().zip(&self.out) {
            *o = w[0];
            for k in 0..HIDDEN {
                for l in 0..LANES {
                    o[l] += w[k + 1][l] * hidden[k * LANES + l];
                }
            }
        }
        let flat = logistic_lanes::<{ OUTPUTS * LANES }>(flat(&out));
        for (o, row) in out.iter_mut().zip(flat.chunks_exact(LANES)) {
            o.copy_from_slice(row);
        }
        out
    }

    /// The four networks' outputs on the noisy readings `noisy[k][l]`, roughly: in single
    /// precision, eight numbers to a vector instruction (two hidden units of the four lanes,
    /// or both outputs), with the weights of [`Lanes::load`] (the inputs' divided by 1023, so
    /// the readings go in as they are), sums in their own order and
    /// [`logistic_rough_lanes`]. Within [`Lanes::rough`] of the exact outputs
    /// ([`rough_output_bound`]); for [`Lanes::network_for_actions`]. `AVX2`: the caller is
    /// compiled with AVX2 and FMA ([`walk_avx2`]), and the AVX2 form runs
    /// ([`rough_network_avx2`]).
    #[inline(always)]
    fn rough_network<const AVX2: bool>(
        &self,
        noisy: &[[f64; LANES]; INPUTS],
    ) -> [[f64; LANES]; OUTPUTS] {
        #[cfg(target_arch = "x86_64")]
        if AVX2 {
            // SAFETY: `AVX2` is only set in `walk_avx2`, which runs only on processors with AVX2
            // and FMA.
            return unsafe { rough_network_avx2(&self.rough_hidden, &self.rough_out, noisy) };
        }
        let hidden = logistic_rough_lanes::<{ HIDDEN * LANES }>(self.rough_sums(noisy));
        let mut out = self.rough_out[0];
        for (h, w) in self.rough_out[1..].iter().enumerate() {
            // Unit `h` of the four lanes once for each output, so that both outputs' sums
            // take one vector operation.
            let mut y = [0.0f32; OUTPUTS * LANES];
            for (i, y) in y.iter_mut().enumerate() {
                *y = hidden[h * LANES + i % LANES];
            }
            for i in 0..OUTPUTS * LANES {
                out[i] += w[i] * y[i];
            }
        }
        let m = logistic_rough_lanes::<{ OUTPUTS * LANES }>(out);
        let mut outputs = [[0.0; LANES]; OUTPUTS];
        for (o, row) in outputs.iter_mut().zip(m.chunks_exact(LANES)) {
            for l in 0..LANES {
                o[l] = f64::from(row[l]);
            }
        }
        outputs
    }

    /// The hidden units' sums of [`Lanes::rough_network`]: `sums[h · LANES + l]`, unit `h` of
    /// lane `l`, in single precision. Every input is added (one whose reading is 0 in all four
    /// lanes adds zeros): eight instructions cost less than a branch on the readings, which
    /// is as good as random.
    #[inline(always)]
    fn rough_sums(&self, noisy: &[[f64; LANES]; INPUTS]) -> [f32; HIDDEN * LANES] {
        let mut sums = self.rough_hidden[0];
        for (k, rk) in noisy.iter().enumerate() {
            let mut r = [0.0f32; LANES];
            for l in 0..LANES {
                r[l] = rk[l] as f32;
            }
            for (h, s) in sums.chunks_exact_mut(LANES).enumerate() {
                let w = &self.rough_hidden[k + 1][h * LANES..(h + 1) * LANES];
                for l in 0..LANES {
                    s[l] += w[l] * r[l];
                }
            }
        }
        sums
    }
}

/// [`Lanes::rough_network`] in AVX2 and FMA instructions, from the lanes' single-precision
/// weights `hidden_w` and `out_w` ([`Lanes::rough_hidden`], [`Lanes::rough_out`]), arranged
/// so that few steps wait on one another (a mispredicted action waits for the whole network):
/// the hidden sums in three registers (two units of the four lanes each), each in two chains
/// (even and odd inputs) added at the end, each reading converted once and put in both halves;
/// the outputs' sums in one register (both outputs of the four lanes), again in two chains,
/// each hidden value put in both halves; products and sums fused ([`logistic_rough_avx2`]'s
/// too). That rounds less than the plain form, so the same bound holds.
///
/// # Safety
/// The processor must have AVX2 and FMA.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
#[inline]
unsafe fn rough_network_avx2(
    hidden_w: &[[f32; HIDDEN * LANES]; INPUTS + 1],
    out_w: &[[f32; OUTPUTS * LANES]; HIDDEN + 1],
    noisy: &[[f64; LANES]; INPUTS],
) -> [[f64; LANES]; OUTPUTS] {
    use std::arch::x86_64::{
        _mm256_add_ps, _mm256_castps256_ps128, _mm256_cvtpd_ps, _mm256_cvtps_pd,
        _mm256_extractf128_ps, _mm256_fmadd_ps, _mm256_loadu_pd, _mm256_loadu_ps,
        _mm256_permute2f128_ps, _mm256_set_m128, _mm256_setzero_ps, _mm256_storeu_pd,
    };
    const {
        assert!(
            HIDDEN * LANES == 24 && OUTPUTS * LANES == 8,
            "three and one registers"
        )
    };
    let mut outputs = [[0.0; LANES]; OUTPUTS];
    // SAFETY: each load reads eight `f32` at 0, 8 or 16 of a 24-`f32` row of `hidden_w`, or a
    // whole 8-`f32` row of `out_w`, or a row of four `f64` of `noisy`; each store writes a row
    // of four `f64` of `outputs`; the unaligned forms need no alignment.
    unsafe {
        // Each sum in two chains, the even inputs' from the bias and the odd inputs', added at
        // the end: half the fused steps one after another.
        let (bias, zero) = (hidden_w[0].as_ptr(), _mm256_setzero_ps());
        let mut even = [0, 8, 16].map(|q| _mm256_loadu_ps(bias.add(q)));
        let mut odd = [zero; 3];
        for (k, (w, r)) in hidden_w[1..].iter().zip(noisy).enumerate() {
            let r = _mm256_cvtpd_ps(_mm256_loadu_pd(r.as_ptr()));
            let r = _mm256_set_m128(r, r);
            let sums = if k % 2 == 0 { &mut even } else { &mut odd };
            for (q, sum) in sums.iter_mut().enumerate() {
                *sum = _mm256_fmadd_ps(_mm256_loadu_ps(w.as_ptr().add(8 * q)), r, *sum);
            }
        }
        // The outputs' sums likewise: the even units' from the bias, the odd units'.
        let (mut out_even, mut out_odd) = (_mm256_loadu_ps(out_w[0].as_ptr()), zero);
        for q in 0..3 {
            // Units 2q and 2q + 1 of the four lanes, each then in both halves.
            let y = logistic_rough_avx2(_mm256_add_ps(even[q], odd[q]));
            let (lo, hi) = (
                _mm256_permute2f128_ps::<0x00>(y, y),
                _mm256_permute2f128_ps::<0x11>(y, y),
            );
            let w = |h: usize| _mm256_loadu_ps(out_w[h + 1].as_ptr());
            out_even = _mm256_fmadd_ps(w(2 * q), lo, out_even);
            out_odd = _mm256_fmadd_ps(w(2 * q + 1), hi, out_odd);
        }
        let m = logistic_rough_avx2(_mm256_add_ps(out_even, out_odd));
        let (m0, m1) = (_mm256_castps256_ps128(m), _mm256_extractf128_ps::<1>(m));
        _mm256_storeu_pd(outputs[0].as_mut_ptr(), _mm256_cvtps_pd(m0));
        _mm256_storeu_pd(outputs[1].as_mut_ptr(), _mm256_cvtps_pd(m1));
    }
    outputs
}

/// How far a rough output ([`Lanes::rough_network`]) can be from the exact one, for the
/// output unit whose weights are `row` (bias first) in a network whose hidden units' sums of
/// `|w|` are at most `hidden_sum`. The rough network rounds to single precision (`u` = 2⁻²⁴)
/// the weights (those of the inputs after the division by 1023), the readings, each product
/// and each sum: a hidden unit's sum is within about `11u` of its terms' sum of magnitudes
/// (three roundings in a product, eight in the sums), which is at most `hidden_sum` (each
/// reading ≤ 1023, so each exact input ≤ 1), so within `c · hidden_sum` of the exact sum,
/// `c` = [`ROUGH_SUM_ERR`] (the exact sum's own roundings are far smaller). The exact
/// logistic is within a few ulp (under 10⁻¹⁵) of the true function, whose slope is ≤ ¼, and
/// the rough logistic within `ε` ([`LOGISTIC_ROUGH_ERR`]) of the exact one of its argument, so
/// each hidden value is within `e = ε + c · hidden_sum / 4 + 10⁻¹⁴`; the output's sum (seven
/// products of values ≤ 1 + e, each rounded like the hidden ones) within `W·(e + c)` (`W` =
/// the sum of `|w|` of `row`), and the output within `ε + W·(e + c)/4 + 10⁻¹⁴`, taken 1 %
/// wider for the rounding of this bound. Infinite when a sum of `|w|` exceeds 10³⁰ or is NaN
/// (single precision could overflow): then no action is certain.
fn rough_output_bound(row: &[f64], hidden_sum: f64) -> f64 {
    let w: f64 = row.iter().map(|w| w.abs()).sum();
    if !(hidden_sum <= 1e30 && w <= 1e30) {
        return f64::INFINITY;
    }
    let e = LOGISTIC_ROUGH_ERR + ROUGH_SUM_ERR * hidden_sum / 4.0 + 1e-14;
    1.01 * (LOGISTIC_ROUGH_ERR + w * (e + ROUGH_SUM_ERR) / 4.0 + 1e-14)
}

/// How far a sum of [`Lanes::rough_network`] can be from the exact one, per unit of its terms'
/// magnitudes ([`rough_output_bound`]): 16·2⁻²⁴ ≈ 9.5·10⁻⁷ covers the eleven roundings, and
/// 10⁻⁶ more than that.
const ROUGH_SUM_ERR: f64 = 1e-6;

/// Whether the labels' speeds stay far from the ends of the double range with this `v_max`,
/// which [`actions_are_certain`] needs: a speed it certifies is at least 10⁻¹² in units of
/// `v_max` and at most 1.5 (the noise is at most 0.5), so with `v_max` in [10⁻²⁹⁰, 10³⁰⁰]
/// every speed it certifies is a normal number, rounded by at most 2⁻⁵³ of itself, and
/// `speed / v_max` is within a few ulp of `(2m − 1)·noise`. A robot outside that range (valid,
/// if absurd: only `v_max > 0` is required) always takes the exact outputs.
fn rough_speeds_fit(v_max: f64) -> bool {
    (1e-290..=1e300).contains(&v_max)
}

/// Whether the action [`Motion::label`](crate::simulation::robot::Motion::label) gives is the
/// same for every pair of outputs within `bound` of `m`, with the step's wheel noise factors
/// `noise` (each in [1 − noise, 1 + noise)) and the action `tolerance`. The labels compare the
/// noisy speeds `s = (2m − 1)·noise` (scaled by `v_max` and back) with 0 (a turn back when both
/// are below) and their difference with `±tolerance`; an output within `b` of `m` moves its
/// speed by at most `2·noise·b`, the roundings (with `v_max` in the range of
/// [`rough_speeds_fit`]) by less than 10⁻¹², so each comparison is certain when its margin
/// exceeds that. A branch-free test (NaN is never certain).
#[inline(always)]
fn actions_are_certain(m: [f64; 2], bound: [f64; 2], noise: [f64; 2], tolerance: f64) -> bool {
    let s = [0, 1].map(|w| (2.0 * m[w] - 1.0) * noise[w]);
    let e = [0, 1].map(|w| 2.0 * noise[w] * bound[w] + 1e-12);
    let (d, ed) = (s[1] - s[0], e[0] + e[1] + 1e-12);
    (s[0].abs() > e[0])
        & (s[1].abs() > e[1])
        & ((d - tolerance).abs() > ed)
        & ((d + tolerance).abs() > ed)
}

/// `rows` laid end to end.
#[inline(always)]
fn flat<const R: usize, const N: usize>(rows: &[[f64; LANES]; R]) -> [f64; N] {
    debug_assert_eq!(R * LANES, N);
    let mut out = [0.0; N];
    for (chunk, row) in out.chunks_exact_mut(LANES).zip(rows) {
        chunk.copy_from_slice(row);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::rng::{rng_from_seed, uniform};
    use crate::simulation::controller::MlpShape;
    use crate::simulation::lanes_any::{lanes_fit, walk_lanes};
    use crate::simulation::room::Room;
    use crate::simulation::trial::{Trajectory, TrialParams, simulate};

    fn arena(room: &str, end_at_home: bool, steps: usize) -> Arena {
        let params = TrialParams {
            end_at_home,
            steps,
            ..TrialParams::default()
        };
        Arena::new(Room::builtin(room).unwrap(), &params)
    }

    /// The room's arena, with its memo of sightings and without.
    fn with_and_without_memo(room: &str, end_at_home: bool, steps: usize) -> [Arena; 2] {
        [
            arena(room, end_at_home, steps),
            arena(room, end_at_home, steps).without_memo(),
        ]
    }

    fn networks(n: usize, seed: u64, scale: f64) -> Vec<Mlp> {
        let shape = MlpShape::default();
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

    /// Every trial run in the lanes records the same trajectory, bit for bit, as the same
    /// trial run alone by `simulate`: rooms with and without walls near home, trials that end
    /// at home at different steps (so lanes are refilled mid-walk), fewer trials than lanes,
    /// small and large weights (sums past the logistic's fast range), memo on and off.
    #[test]
    fn lanes_take_the_steps_simulate_takes_bit_for_bit() {
        for (room, end, steps, n, scale) in [
            ("H", true, 400, 13, 1.0),
            ("H", false, 150, 9, 1.0),
            ("T", true, 300, 7, 5.0),
            ("square", true, 200, 3, 1.0),
            ("L", false, 120, 6, 800.0),
            ("rectangle", true, 0, 5, 1.0),
        ] {
            for arena in with_and_without_memo(room, end, steps) {
                let executed = check_lanes(&arena, n, scale, true);
                // Trials end at different steps (their observers stop them), so lanes are
                // refilled while the others walk on.
                let mut ends = executed.clone();
                ends.dedup();
                assert!(steps == 0 || ends.len() > 2, "{room}: {executed:?}");
            }
        }
    }

    thread_local! {
        /// Steps of this thread's lanes whose actions came from the rough outputs, and those
        /// that needed the exact ones.
        static ROUGH: std::cell::Cell<[usize; 2]> = const { std::cell::Cell::new([0; 2]) };
    }

    /// Counts a step of [`Lanes::network_for_actions`].
    pub(super) fn count_rough(certain: bool) {
        ROUGH.with(|c| {
            let mut n = c.get();
            n[usize::from(!certain)] += 1;
            c.set(n);
        });
    }

    /// A trajectory, with each step's grid cell, that asks its trial to end after a number of
    /// steps of its own (trial `i`: 17 + 29·i) or at its end. With `motors` false it does not
    /// read the steps' motors and speeds (it records them as 0), so the lanes may choose
    /// actions from rough outputs.
    #[derive(Debug)]
    struct Until {
        path: Trajectory,
        cells: Vec<Option<usize>>,
        stop: usize,
        motors: bool,
    }

    impl Until {
        fn new(arena: &Arena, i: usize, motors: bool) -> Until {
            let steps = arena.params().steps;
            Until {
                path: Trajectory::starting_at(arena.room().home, steps),
                cells: Vec::new(),
                stop: 17 + 29 * i,
                motors,
            }
        }
    }

    impl StepObserver for Until {
        fn observe(&mut self, step: &crate::simulation::trial::Step) {
            self.cells.push(step.cell);
            match self.motors {
                true => self.path.observe(step),
                false => self.path.observe(&crate::simulation::trial::Step {
                    motors: [0.0; 2],
                    speeds: [0.0; 2],
                    ..*step
                }),
            }
        }

        fn finished(&self) -> bool {
            self.path.poses.len() > self.stop
        }

        fn reads_motors(&self) -> bool {
            self.motors
        }
    }

    /// Trials whose observers do not read the motors take, bit for bit, the steps that
    /// `simulate` takes (every field but the motors and speeds, which are rough), both when the
    /// rough outputs decide the actions and when a margin is too thin and the exact outputs
    /// are computed: weights small enough that the outputs stay near ½ (speeds near 0, so
    /// the exact outputs are often needed), and larger ones.
    #[test]
    fn rough_actions_are_the_exact_actions() {
        ROUGH.with(|c| c.set([0; 2]));
        for (room, end, steps, n, scale) in [
            ("H", true, 400, 13, 1.0),
            ("H", false, 300, 9, 2e-5),
            ("T", true, 300, 7, 5.0),
            ("square", false, 250, 6, 0.05),
            ("L", false, 120, 6, 800.0),
            ("rectangle", true, 200, 5, 0.3),
        ] {
            for arena in with_and_without_memo(room, end, steps) {
                check_lanes(&arena, n, scale, false);
            }
        }
        let [rough, exact] = ROUGH.with(std::cell::Cell::get);
        assert!(rough > 1000 && exact > 100, "rough {rough}, exact {exact}");
    }

    /// Lanes with the networks `nets` (one a lane) loaded in `arena`.
    fn loaded(arena: &Arena, nets: &[Mlp]) -> Lanes {
        let mut lanes = Lanes::new(arena);
        let mut trials: Vec<_> = (nets.iter())
            .map(|net| LaneTrial {
                net,
                seed: 1,
                observer: (),
                last: arena.room().home,
                drawn: None,
            })
            .collect();
        let mut next = 0;
        for l in 0..LANES {
            next = lanes.load(l, next, arena, &mut trials);
        }
        lanes
    }

    /// The rough outputs' bound holds: for random weights of several scales and inputs, each
    /// rough output, of the plain form and (where the processor has it) the AVX2 form, is
    /// within its lane's bound of the exact output.
    #[test]
    fn rough_outputs_are_within_their_bounds() {
        let arena = arena("H", true, 10);
        for (i, scale) in [0.01, 1.0, 10.0, 100.0, 800.0].into_iter().enumerate() {
            let nets = networks(LANES, 40 + i as u64, scale);
            let lanes = loaded(&arena, &nets);
            let mut rng = rng_from_seed(7 + i as u64);
            for _ in 0..2000 {
                let mut noisy = [[0.0; LANES]; INPUTS];
                for v in noisy.iter_mut().flatten() {
                    *v = uniform(&mut rng, 0.0, SENSOR_MAX);
                }
                let exact = lanes.network(&inputs_of(&noisy));
                let mut forms = vec![lanes.rough_network::<false>(&noisy)];
                if Isa::detected() != Isa::Baseline {
                    forms.push(lanes.rough_network::<true>(&noisy));
                }
                for rough in forms {
                    for (o, l) in (0..OUTPUTS).flat_map(|o| (0..LANES).map(move |l| (o, l))) {
                        let gap = (rough[o][l] - exact[o][l]).abs();
                        assert!(
                            gap <= lanes.rough[o][l],
                            "scale {scale}: {gap} > {}",
                            lanes.rough[o][l]
                        );
                    }
                }
            }
        }
    }

    /// The rough hidden sums are within `ROUGH_SUM_ERR` per unit of their terms' magnitudes of
    /// the exact ones, and come near that bound (so that a bound much too tight fails):
    /// random weights of several scales, random readings, and some readings of 0.
    #[test]
    fn rough_sums_within_their_share_of_the_bound() {
        let arena = arena("H", true, 10);
        let mut rng = rng_from_seed(61);
        let mut worst = 0.0f64;
        for scale in [0.3, 1.0, 50.0, 1e4] {
            let nets = networks(LANES, scale as u64 + 3, scale);
            let lanes = loaded(&arena, &nets);
            for i in 0..5000 {
                let mut noisy = [[0.0; LANES]; INPUTS];
                for v in noisy.iter_mut().flatten() {
                    *v = uniform(&mut rng, 0.0, SENSOR_MAX);
                }
                noisy[i % INPUTS] = [0.0; LANES];
                let rough = lanes.rough_sums(&noisy);
                let x = inputs_of(&noisy);
                for (h, l) in (0..HIDDEN).flat_map(|h| (0..LANES).map(move |l| (h, l))) {
                    let bias = lanes.hidden[0][h][l];
                    let (mut exact, mut size) = (bias, bias.abs());
                    for (w, xk) in lanes.hidden[1..].iter().zip(&x) {
                        exact += w[h][l] * xk[l];
                        size += (w[h][l] * xk[l]).abs();
                    }
                    let share = (f64::from(rough[h * LANES + l]) - exact).abs() / size;
                    assert!(share <= ROUGH_SUM_ERR, "scale {scale}: {share}");
                    worst = worst.max(share);
                }
            }
        }
        assert!(worst > ROUGH_SUM_ERR / 8.0, "{worst}: far below the bound");
    }

    /// The test of certainty takes the labels' side of every comparison: outputs that would
    /// change the action inside the bound are not certain, outputs well clear of every edge
    /// are, and NaN never is.
    #[test]
    fn certainty_needs_every_margin() {
        use crate::simulation::robot::Action;
        let (noise, tol) = ([1.0, 1.0], 0.25);
        let label = |m: [f64; 2]| Action::from_speeds(2.0 * m[0] - 1.0, 2.0 * m[1] - 1.0, tol);
        let b = [1e-4; 2];
        // Clear of every edge: certain, and every output in the bound labels alike.
        for m in [[0.9, 0.95], [0.1, 0.2], [0.3, 0.9], [0.9, 0.3]] {
            assert!(actions_are_certain(m, b, noise, tol), "{m:?}");
            for dm in [[-1e-4, 1e-4], [1e-4, -1e-4], [1e-4, 1e-4], [-1e-4, -1e-4]] {
                assert_eq!(label([m[0] + dm[0], m[1] + dm[1]]), label(m), "{m:?}");
            }
        }
        // On an edge: a speed at 0, a difference at ±tolerance.
        for m in [
            [0.5 + 5e-5, 0.2],
            [0.2, 0.5 - 5e-5],
            [0.6, 0.725 + 5e-5],
            [0.725, 0.6],
        ] {
            assert!(!actions_are_certain(m, b, noise, tol), "{m:?}");
        }
        assert!(!actions_are_certain([f64::NAN, 0.9], b, noise, tol));
        // Speeds that would be subnormal or overflow in the labels never take the rough path.
        assert!(rough_speeds_fit(80.0) && rough_speeds_fit(1e-290) && rough_speeds_fit(1e300));
        for v_max in [5e-324, f64::MIN_POSITIVE, 1e-291, 1e301, f64::MAX, f64::NAN] {
            assert!(!rough_speeds_fit(v_max), "{v_max}");
        }
        assert!(!actions_are_certain(
            [0.9, 0.1],
            [f64::INFINITY; 2],
            noise,
            tol
        ));
    }

    /// Runs `n` random trials in `arena` in the lanes and alone, requires the same
    /// trajectories and final poses, and returns each trial's executed steps. `motors`: whether
    /// the observers read (and so compare) the motors and speeds.
    fn check_lanes(arena: &Arena, n: usize, scale: f64, motors: bool) -> Vec<usize> {
        let (room, steps) = (&arena.room().name, arena.params().steps);
        let nets = networks(n, steps as u64 + n as u64, scale);
        let seed = |i: usize| 1000 + i as u64;
        let mut trials: Vec<_> = nets
            .iter()
            .enumerate()
            .map(|(i, net)| LaneTrial {
                net,
                seed: seed(i),
                observer: Until::new(arena, i, motors),
                last: Pose::new(f64::NAN, f64::NAN, f64::NAN),
                drawn: None,
            })
            .collect();
        assert!(trials.iter().all(|t| lanes_fit(arena, t.net)));
        walk_lanes(arena, &mut trials);
        let mut executed = Vec::new();
        for (i, trial) in trials.iter().enumerate() {
            let mut alone = Until::new(arena, i, motors);
            let mut rng = rng_from_seed(seed(i));
            let last = simulate(arena, &mut nets[i].clone(), &mut rng, &mut alone);
            let what = format!("{room}, trial {i}");
            // Debug prints each f64 so that it reads back to the same bits (−0 included).
            let (lanes, alone_text) = (format!("{:?}", trial.observer), format!("{alone:?}"));
            assert!(lanes == alone_text, "{what}: the trajectories differ");
            let bits = |p: Pose| [p.x, p.y, p.heading].map(f64::to_bits);
            assert_eq!(bits(trial.last), bits(last), "{what}");
            executed.push(alone.path.idle.iter().filter(|&&idle| !idle).count());
        }
        executed
    }

    /// The lanes' streams are `rng_from_seed`'s, draw for draw, in the plain form and (where
    /// the processor has it) the AVX2 form, and their units `uniform01`'s, for random and
    /// extreme bits.
    #[test]
    fn lane_streams_are_rng_from_seed_and_units_uniform01() {
        let seeds = [0, 1, 2, u64::MAX, 0x9e37_79b9_7f4a_7c15, 12_345_678_901];
        let avx2 = Isa::detected() == Isa::Avx2;
        for form in [false, true].into_iter().filter(|&f| !f || avx2) {
            let mut streams = Streams { s: [[0; LANES]; 4] };
            for chunk in seeds.chunks(LANES) {
                let mut rngs: Vec<_> = chunk.iter().map(|&s| rng_from_seed(s)).collect();
                for (l, &s) in chunk.iter().enumerate() {
                    streams.start(l, s);
                }
                for _ in 0..1000 {
                    let units = match form {
                        false => streams.next_units::<false>(),
                        true => streams.next_units::<true>(),
                    };
                    for (l, rng) in rngs.iter_mut().enumerate() {
                        let want = crate::random::rng::uniform01(rng);
                        assert_eq!(units[l].to_bits(), want.to_bits(), "AVX2 form: {form}");
                    }
                }
            }
        }
        let mut rng = rng_from_seed(7);
        let edges = [
            0,
            1,
            2047,
            2048,
            u64::MAX,
            u64::MAX - 2047,
            1 << 63,
            (1 << 43) - 1,
        ];
        let random = (0..10_000).map(|_| crate::random::rng::Rng::next_u64(&mut rng));
        for n in edges.into_iter().chain(random) {
            let want = (n >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
            assert_eq!(unit(n).to_bits(), want.to_bits(), "{n:#x}");
        }
    }

    /// The AVX2 transposition of the lanes' readings is the plain one, value for value (with
    /// distinct bits in every place, and the signs of zeros).
    #[test]
    fn readings_side_by_side_in_both_forms() {
        if Isa::detected() == Isa::Baseline {
            return; // no AVX2 here: only the plain form runs
        }
        let mut sights = [Sight::CLEAR; LANES];
        for (l, sight) in sights.iter_mut().enumerate() {
            for (k, v) in sight.sensors.iter_mut().enumerate() {
                *v = (10 * l + k) as f64 + 0.25;
            }
        }
        sights[2].sensors[5] = -0.0;
        let plain = side_by_side::<false>(&sights);
        for (k, row) in plain.iter().enumerate() {
            for (l, v) in row.iter().enumerate() {
                assert_eq!(v.to_bits(), sights[l].sensors[k].to_bits());
            }
        }
        let avx2 = side_by_side::<true>(&sights);
        assert_eq!(
            flat::<INPUTS, 32>(&avx2).map(f64::to_bits),
            flat(&plain).map(f64::to_bits)
        );
    }

    /// The lanes run every network with one input per sensor and finite weights, the paper's
    /// lanes only the paper's robot: another hidden size, no noise, `wheels` motion or a drawn
    /// robot go to the general lanes; a weight that is not finite or another number of
    /// inputs to none.
    #[test]
    fn lanes_fit_what_they_run_exactly() {
        let arena = arena("H", true, 10);
        let nets = networks(1, 1, 1.0);
        let trial = |net| LaneTrial {
            net,
            seed: 1,
            observer: (),
            last: arena.room().home,
            drawn: None,
        };
        assert!(lanes_fit(&arena, &nets[0]) && paper_fit(&arena, &trial(&nets[0])));
        let shape = MlpShape::with_hidden(5).unwrap();
        let other = Mlp::from_genome(shape, &vec![0.1; shape.genome_len()]).unwrap();
        assert!(lanes_fit(&arena, &other) && !paper_fit(&arena, &trial(&other)));
        let drawn = LaneTrial {
            drawn: Some(Drawn {
                arena: &arena,
                bias: 0.0,
            }),
            ..trial(&nets[0])
        };
        assert!(!paper_fit(&arena, &drawn));
        let quiet = Arena::new(
            Room::builtin("H").unwrap(),
            &TrialParams::default().with_noise(0.0),
        );
        assert!(lanes_fit(&quiet, &nets[0]) && !paper_fit(&quiet, &trial(&nets[0])));
        let mut g = vec![0.1; MlpShape::default().genome_len()];
        g[20] = f64::INFINITY;
        let inf = Mlp::from_genome(MlpShape::default(), &g).unwrap();
        assert!(!lanes_fit(&arena, &inf));
        let seven = MlpShape::default().with_inputs(7).unwrap();
        let short = Mlp::from_genome(seven, &vec![0.1; seven.genome_len()]).unwrap();
        assert!(!lanes_fit(&arena, &short));
    }
}
