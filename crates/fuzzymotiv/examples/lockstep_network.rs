//! An evaluation for the performance issue's lockstep item: the 8-6-2 network run for one robot
//! at a time (the crate's `Mlp`, as trials run it) against four robots in lockstep (structure of
//! arrays, `math::logistic_lanes` across the robots), on inputs recorded from real trials in the
//! paper's H room with random genomes (the population benchmark's workload). It checks that both
//! give the same bits and prints the median time per robot-step of each.
//!
//! ```sh
//! cargo run --release -p fuzzymotiv --example lockstep_network
//! RUSTFLAGS="-C target-cpu=native" cargo run --release -p fuzzymotiv --example lockstep_network \
//!     --target-dir target/native    # with AVX2: four lanes per instruction
//! ```
//!
//! Measured 2026-11-22 on the 2-core EPYC VM: with the default target (SSE2, two lanes per
//! instruction; three runs) one robot at a time took 81–90 ns, four in lockstep 58–67 ns (about
//! 1.4×); with AVX2 (two runs) 82–86 ns against 45–50 ns (about 1.75×). The network is about
//! 30 % of a study's time.
use fuzzymotiv::modelling::DEFAULT_ACTION_TOLERANCE;
use fuzzymotiv::random::{rng_from_seed, uniform};
use fuzzymotiv::simulation::RawRobot;
use fuzzymotiv::simulation::Room;
use fuzzymotiv::simulation::logistic_lanes;
use fuzzymotiv::simulation::{Arena, RawTrial, Step, StepObserver, TrialParams, simulate};
use fuzzymotiv::simulation::{Controller, Mlp, MlpShape};
use std::time::Instant;

const L: usize = 4;
const H: usize = 6;

struct Inputs(Vec<[f64; 8]>);
impl StepObserver for Inputs {
    fn observe(&mut self, s: &Step) {
        if !s.idle {
            self.0.push(std::array::from_fn(|k| match s.sensors[k] {
                0.0 => 0.0,
                v => v / 1023.0,
            }));
        }
    }
}

/// Four genomes as structure of arrays.
struct Lanes {
    hb: [[f64; L]; H],
    hw: [[[f64; L]; H]; 8],
    ob: [[f64; L]; 2],
    ow: [[[f64; L]; H]; 2],
}

impl Lanes {
    fn new(g: &[Vec<f64>]) -> Lanes {
        let mut z = Lanes {
            hb: [[0.0; L]; H],
            hw: [[[0.0; L]; H]; 8],
            ob: [[0.0; L]; 2],
            ow: [[[0.0; L]; H]; 2],
        };
        for (l, g) in g.iter().enumerate() {
            for j in 0..H {
                z.hb[j][l] = g[j * 9];
                for i in 0..8 {
                    z.hw[i][j][l] = g[j * 9 + 1 + i];
                }
            }
            for o in 0..2 {
                let base = H * 9 + o * (H + 1);
                z.ob[o][l] = g[base];
                for j in 0..H {
                    z.ow[o][j][l] = g[base + 1 + j];
                }
            }
        }
        z
    }
    /// The four networks' step: per lane the crate's order of operations (hidden sums input by
    /// input from the bias, then the output sums unit by unit from the bias).
    #[inline(never)]
    fn step(&self, x: &[[f64; L]; 8]) -> [[f64; L]; 2] {
        let mut s = self.hb;
        for (row, xi) in self.hw.iter().zip(x) {
            for (sj, wj) in s.iter_mut().zip(row) {
                for ((a, w), v) in sj.iter_mut().zip(wj).zip(xi) {
                    *a += w * v;
                }
            }
        }
        let h = s.map(logistic_lanes);
        let mut o = self.ob;
        for (ok, wk) in o.iter_mut().zip(&self.ow) {
            for (wj, hj) in wk.iter().zip(&h) {
                for ((a, w), v) in ok.iter_mut().zip(wj).zip(hj) {
                    *a += w * v;
                }
            }
        }
        o.map(logistic_lanes)
    }
}

/// Four robots' inputs at one step, lane by lane.
fn gather(xs: &[[f64; 8]]) -> [[f64; L]; 8] {
    std::array::from_fn(|i| std::array::from_fn(|l| xs[l][i]))
}

/// Each of `robots` random 8-H-2 networks driven one trial in room H (its own seed): the
/// genomes and the inputs each network saw, step by step.
fn record_inputs(robots: usize) -> (Vec<Vec<f64>>, Vec<Vec<[f64; 8]>>) {
    let trial = RawTrial {
        end_at_home: false,
        ..RawTrial::default()
    };
    let khepera = fuzzymotiv::simulation::RobotSpec::khepera();
    let params = TrialParams::from_raw(
        &trial,
        &RawRobot::default(),
        khepera,
        DEFAULT_ACTION_TOLERANCE,
    )
    .expect("valid parameters");
    let arena = Arena::new(Room::builtin("H").unwrap(), &params);
    let shape = MlpShape::with_hidden(H).expect("a valid hidden layer");
    let mut rng = rng_from_seed(7);
    let genomes: Vec<Vec<f64>> = (0..robots)
        .map(|_| {
            (0..shape.genome_len())
                .map(|_| uniform(&mut rng, -1.0, 1.0))
                .collect()
        })
        .collect();
    let mut inputs = Vec::new();
    for (r, g) in genomes.iter().enumerate() {
        let mut obs = Inputs(Vec::new());
        simulate(
            &arena,
            &mut Mlp::from_genome(shape, g).unwrap(),
            &mut rng_from_seed(r as u64),
            &mut obs,
        );
        inputs.push(obs.0);
    }
    (genomes, inputs)
}

/// Median nanoseconds per robot-step of `reps` passes of `a` and of `b`, over 7 timings of
/// each taken in turn (so that a drift of the machine weighs on both alike).
fn medians_ns(
    reps: usize,
    robot_steps: usize,
    mut a: impl FnMut(),
    mut b: impl FnMut(),
) -> (f64, f64) {
    let time = |pass: &mut dyn FnMut()| {
        let t0 = Instant::now();
        for _ in 0..reps {
            pass();
        }
        t0.elapsed().as_secs_f64() * 1e9 / (reps * robot_steps) as f64
    };
    let (mut ta, mut tb) = (Vec::new(), Vec::new());
    for _ in 0..7 {
        ta.push(time(&mut a));
        tb.push(time(&mut b));
    }
    ta.sort_by(f64::total_cmp);
    tb.sort_by(f64::total_cmp);
    (ta[3], tb[3])
}

fn main() {
    let robots = 64;
    let (genomes, inputs) = record_inputs(robots);
    let shape = MlpShape::with_hidden(H).expect("a valid hidden layer");
    let steps = inputs.iter().map(|v| v.len()).min().unwrap();
    let zero = inputs
        .iter()
        .flat_map(|v| &v[..steps])
        .filter(|x| x.iter().all(|&v| v == 0.0))
        .count();
    println!(
        "{steps} steps per robot; all-zero inputs in {:.1} % of robot-steps",
        100.0 * zero as f64 / (steps * robots) as f64
    );
    let by_step: Vec<Vec<[f64; 8]>> = (0..steps)
        .map(|t| inputs.iter().map(|v| v[t]).collect())
        .collect();
    let mut mlps: Vec<Mlp> = genomes
        .iter()
        .map(|g| Mlp::from_genome(shape, g).unwrap())
        .collect();
    let groups: Vec<Lanes> = genomes.chunks(L).map(Lanes::new).collect();
    // The same bits, robot by robot.
    for row in &by_step {
        let lanes = groups.iter().zip(row.chunks_exact(L));
        for ((grp, xs), nets) in lanes.zip(mlps.chunks_exact_mut(L)) {
            let o = grp.step(&gather(xs));
            for (l, (net, x)) in nets.iter_mut().zip(xs).enumerate() {
                let s = net.step(x);
                assert_eq!([o[0][l], o[1][l]].map(f64::to_bits), s.map(f64::to_bits));
            }
        }
    }
    let (reps, robot_steps) = (200, steps * robots);
    let (mut sink_scalar, mut sink_lanes) = (0.0, 0.0);
    let (scalar, lanes) = medians_ns(
        reps,
        robot_steps,
        || {
            for row in &by_step {
                for (net, x) in mlps.iter_mut().zip(row) {
                    sink_scalar += net.step(x)[0];
                }
            }
        },
        || {
            for row in &by_step {
                for (grp, xs) in groups.iter().zip(row.chunks_exact(L)) {
                    sink_lanes += grp.step(&gather(xs))[0][0];
                }
            }
        },
    );
    let sink = sink_scalar + sink_lanes;
    println!(
        "ns per robot-step, median of 7: scalar {scalar:.1}, lockstep x4 {lanes:.1}  ({sink:.0})"
    );
}
