//! Neural controllers: the [`Controller`] trait and the paper's logistic MLP.

use serde::{Deserialize, Serialize};

/// Number of network inputs of the paper's Khepera (its eight IR sensors); a robot file's
/// robot has one input per sensor ([`MlpShape::inputs`]).
pub const INPUTS: usize = crate::simulation::sensor::SENSORS;
/// Number of network outputs (left and right motor).
pub const OUTPUTS: usize = 2;

/// Maps normalised sensor readings (each in [0, 1], one per sensor of the robot) to motor
/// outputs `mL, mR` in [0, 1].
pub trait Controller {
    /// One network step.
    fn step(&mut self, inputs: &[f64]) -> [f64; OUTPUTS];
}

/// The shape of the MLP: N inputs (one per sensor of the robot; the Khepera's 8) → `hidden`
/// logistic units → 2 logistic outputs, with biases. Built only by checking
/// ([`MlpShape::with_hidden`], [`RawNetwork::shape`], [`MlpShape::with_inputs`]) or as the
/// paper's ([`MlpShape::default`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MlpShape {
    inputs: usize,
    hidden: usize,
}

impl Default for MlpShape {
    /// The paper's 8-6-2 network.
    fn default() -> Self {
        MlpShape {
            inputs: INPUTS,
            hidden: MlpShape::DEFAULT_HIDDEN,
        }
    }
}

/// `[network]` in a config, as written.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawNetwork {
    /// [`MlpShape::hidden`].
    pub hidden: usize,
}

impl Default for RawNetwork {
    fn default() -> Self {
        Self {
            hidden: MlpShape::DEFAULT_HIDDEN,
        }
    }
}

impl RawNetwork {
    /// The checked shape ([`MlpShape::with_hidden`]).
    pub fn shape(&self) -> Result<MlpShape, crate::params::FieldError> {
        MlpShape::with_hidden(self.hidden)
    }
}

impl MlpShape {
    /// The paper's hidden layer: 6 units.
    pub const DEFAULT_HIDDEN: usize = 6;

    /// The most hidden units a network may have.
    pub const MAX_HIDDEN: usize = 1024;

    /// The shape with the Khepera's 8 inputs and `hidden` hidden units, in
    /// 1..=[`MlpShape::MAX_HIDDEN`]; an error names `network.hidden`.
    ///
    /// ```
    /// use fuzzymotiv::simulation::MlpShape;
    /// assert_eq!(MlpShape::with_hidden(6).unwrap(), MlpShape::default());
    /// assert_eq!(MlpShape::with_hidden(0).unwrap_err().field, "network.hidden");
    /// ```
    pub fn with_hidden(hidden: usize) -> Result<MlpShape, crate::params::FieldError> {
        crate::params::check(
            (1..=Self::MAX_HIDDEN).contains(&hidden),
            "network.hidden",
            || format!("must be in 1..={}, got {hidden}", Self::MAX_HIDDEN),
        )?;
        Ok(MlpShape {
            inputs: INPUTS,
            hidden,
        })
    }

    /// The same shape with `inputs` inputs (a robot's sensors: 1 to
    /// [`crate::simulation::MAX_SENSORS`]); an error names `robot` (the robot file gives them).
    ///
    /// ```
    /// use fuzzymotiv::simulation::MlpShape;
    /// let thymio = MlpShape::default().with_inputs(7).unwrap();
    /// assert_eq!((thymio.inputs(), thymio.genome_len()), (7, 62));
    /// ```
    pub fn with_inputs(self, inputs: usize) -> Result<MlpShape, crate::params::FieldError> {
        let most = crate::simulation::MAX_SENSORS;
        crate::params::check((1..=most).contains(&inputs), "robot", || {
            format!("a network has 1 to {most} inputs (one per sensor), got {inputs}")
        })?;
        Ok(MlpShape { inputs, ..self })
    }

    /// Inputs: one per sensor of the robot (the Khepera's eight IR sensors: [`INPUTS`]).
    pub fn inputs(&self) -> usize {
        self.inputs
    }

    /// Hidden units; default 6 ([`MlpShape::DEFAULT_HIDDEN`]); range 1..=1024.
    pub fn hidden(&self) -> usize {
        self.hidden
    }

    /// Outputs: the two motors ([`OUTPUTS`]).
    pub fn outputs(&self) -> usize {
        OUTPUTS
    }

    /// Genome length: per hidden unit `[bias, N input weights]`, then per output `[bias,
    /// hidden weights]`. 68 for the paper's 8-6-2.
    ///
    /// ```
    /// assert_eq!(fuzzymotiv::simulation::MlpShape::default().genome_len(), 68);
    /// ```
    pub fn genome_len(&self) -> usize {
        self.hidden * (self.inputs + 1) + OUTPUTS * (self.hidden + 1)
    }
}

impl MlpShape {
    /// `Ok` when `genome` has this network's length.
    pub(crate) fn check(&self, genome: &[f64]) -> Result<(), GenomeError> {
        if genome.len() == self.genome_len() {
            Ok(())
        } else {
            Err(GenomeError {
                inputs: self.inputs,
                hidden: self.hidden,
                expected: self.genome_len(),
                actual: genome.len(),
            })
        }
    }
}

/// A genome whose length is not its network's ([`Mlp::from_genome`]).
///
/// ```
/// use fuzzymotiv::simulation::{Mlp, MlpShape};
/// let e = Mlp::from_genome(MlpShape::default(), &[0.0; 67]).unwrap_err();
/// assert_eq!(e.to_string(), "a genome of the 8-6-2 network has 68 weights, got 67");
/// ```
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("a genome of the {inputs}-{hidden}-2 network has {expected} weights, got {actual}")]
pub struct GenomeError {
    /// The network's inputs.
    pub inputs: usize,
    /// The network's hidden units.
    pub hidden: usize,
    /// The network's genome length ([`MlpShape::genome_len`]).
    pub expected: usize,
    /// The genome's length.
    pub actual: usize,
}

/// Logistic function 1 / (1 + e^(−x)), with the project's own `exp` (error bound and range:
/// [`crate::simulation::math::logistic`]).
pub use crate::simulation::math::logistic;
use crate::simulation::math::logistic_lanes;

/// The feed-forward logistic MLP whose weights are the genome.
#[derive(Debug, Clone)]
pub struct Mlp {
    shape: MlpShape,
    /// The output layer's weights, as the genome lays them out: per output `[bias, hidden
    /// weights]`.
    out_weights: Vec<f64>,
    /// The hidden layer's weights by input: the biases, then for each input its weight into
    /// every hidden unit (so a sensor that reads 0 is skipped as a whole row).
    by_input: Vec<f64>,
    hidden: Vec<f64>,
    /// The outputs when every input is 0, computed once: the hidden units are then
    /// `logistic(bias)` (in open floor all sensors read 0, and a term `w · 0` adds ±0,
    /// which changes no sum that reaches the logistic: `exp(±0)` is 1 either way), so these
    /// are the loop's results bit for bit.
    idle_out: [f64; OUTPUTS],
}

impl Mlp {
    /// A network from a genome laid out as [`MlpShape::genome_len`] describes; an error when
    /// the length does not match.
    pub fn from_genome(shape: MlpShape, genome: &[f64]) -> Result<Self, GenomeError> {
        shape.check(genome)?;
        Ok(Self::of_checked(shape, genome))
    }

    /// The network of `genome`, whose length is `shape`'s (checked by the caller).
    pub(crate) fn of_checked(shape: MlpShape, genome: &[f64]) -> Self {
        debug_assert_eq!(genome.len(), shape.genome_len());
        let n = shape.inputs;
        let (hidden_w, out_w) = genome.split_at(shape.hidden * (n + 1));
        let idle_hidden: Vec<f64> = hidden_w
            .chunks_exact(n + 1)
            .map(|w| logistic(w[0]))
            .collect();
        let by_input = (0..=n)
            .flat_map(|k| hidden_w.chunks_exact(n + 1).map(move |w| w[k]))
            .collect();
        Self {
            shape,
            out_weights: out_w.to_vec(),
            by_input,
            hidden: vec![0.0; shape.hidden],
            idle_out: output_layer(out_w, &idle_hidden),
        }
    }

    /// The network's shape.
    pub fn shape(&self) -> MlpShape {
        self.shape
    }

    /// The hidden layer's weights by input (the biases, then each input's weight into every
    /// hidden unit) and the output layer's (per output `[bias, hidden weights]`).
    pub(crate) fn layers(&self) -> (&[f64], &[f64]) {
        (&self.by_input, &self.out_weights)
    }

    /// The outputs when every input is 0 (open floor), computed once.
    pub(crate) fn idle_outputs(&self) -> [f64; OUTPUTS] {
        self.idle_out
    }

    /// Whether every weight is finite (then `w · 0 = ±0` for each of them).
    pub(crate) fn is_finite(&self) -> bool {
        self.by_input
            .iter()
            .chain(&self.out_weights)
            .all(|w| w.is_finite())
    }
}

/// The hidden layer's weighted sums, input by input: each unit's sum is
/// `bias + w₁·x₁ + … + w_N·x_N` added in that order, as the genome lays it out, but inputs that
/// are exactly 0 (a sensor that sees nothing: most of them, most of the time) are skipped.
/// Adding `w · 0 = ±0` leaves a sum unchanged except for the sign of a zero sum, and
/// `logistic(−0) = logistic(+0) = 0.5`, so the outputs are the same bits.
#[inline(always)]
fn hidden_sums(by_input: &[f64], inputs: &[f64], sums: &mut [f64]) {
    let h = sums.len();
    sums.copy_from_slice(&by_input[..h]);
    for (row, &x) in by_input[h..].chunks_exact(h).zip(inputs) {
        if x != 0.0 {
            for (s, &w) in sums.iter_mut().zip(row) {
                *s += w * x;
            }
        }
    }
}

/// The network with `H` hidden units known at compile time: the same arithmetic in the same
/// order as the general path (so identical results), with fixed trip counts the compiler
/// unrolls and vectorises, and each layer's logistic units done together
/// ([`logistic_lanes`]: the scalar function's bits).
#[inline(always)]
fn step_fixed<const H: usize>(by_input: &[f64], out_w: &[f64], inputs: &[f64]) -> [f64; OUTPUTS] {
    let mut hidden = [0.0; H];
    hidden_sums(&by_input[..H * (inputs.len() + 1)], inputs, &mut hidden);
    let hidden = logistic_lanes(hidden);
    let mut out = [0.0; OUTPUTS];
    for (o, w) in out.iter_mut().zip(out_w.chunks_exact(H + 1)) {
        let mut s = w[0];
        for k in 0..H {
            s += w[k + 1] * hidden[k];
        }
        *o = s;
    }
    logistic_lanes(out)
}

impl Controller for Mlp {
    // Always inlined: the step loop is also compiled for AVX2 (`isa::Isa`), and a network
    // called out of line would run the baseline code there.
    #[inline(always)]
    fn step(&mut self, inputs: &[f64]) -> [f64; OUTPUTS] {
        debug_assert_eq!(inputs.len(), self.shape.inputs, "one input per sensor");
        if inputs.iter().all(|&x| x == 0.0) {
            return self.idle_out;
        }
        if self.shape.hidden == 6 {
            return step_fixed::<6>(&self.by_input, &self.out_weights, inputs);
        }
        hidden_sums(&self.by_input, inputs, &mut self.hidden);
        for h in &mut self.hidden {
            *h = logistic(*h);
        }
        output_layer(&self.out_weights, &self.hidden)
    }
}

/// The output layer on `hidden`, whatever its size (the fixed-size path repeats this
/// arithmetic in the same order).
fn output_layer(out_w: &[f64], hidden: &[f64]) -> [f64; OUTPUTS] {
    let mut out = [0.0; OUTPUTS];
    for (o, w) in out.iter_mut().zip(out_w.chunks_exact(hidden.len() + 1)) {
        let mut s = w[0];
        for (wk, h) in w[1..].iter().zip(hidden) {
            s += wk * h;
        }
        *o = logistic(s);
    }
    out
}

/// A network with a dead sensor or biased wheels.
pub(crate) struct Perturbed<'a> {
    pub(crate) net: &'a mut Mlp,
    pub(crate) dead: Option<usize>,
    pub(crate) bias: f64,
}

impl Controller for Perturbed<'_> {
    fn step(&mut self, inputs: &[f64]) -> [f64; OUTPUTS] {
        let mut x = crate::simulation::sensor::Readings::from_slice(inputs);
        if let Some(s) = self.dead {
            x[s] = 0.0;
        }
        // Motor m drives the wheel at (2m − 1)·v_max: scaling the speed by 1 + bias.
        self.net
            .step(&x)
            .map(|m| ((2.0 * m - 1.0) * (1.0 + self.bias) + 1.0) / 2.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_and_general_paths_agree_bit_for_bit() {
        let mut rng = crate::random::rng::rng_from_seed(4);
        for hidden in [5, 6, 7] {
            let shape = MlpShape::with_hidden(hidden).unwrap();
            let g: Vec<f64> = (0..shape.genome_len())
                .map(|_| crate::random::rng::uniform(&mut rng, -5.0, 5.0))
                .collect();
            let mut m = Mlp::from_genome(shape, &g).unwrap();
            for i in 0..50 {
                // Input 0: open floor (all sensors 0), the cached idle path.
                let x: [f64; 8] = std::array::from_fn(|_| match i {
                    0 => 0.0,
                    _ => crate::random::rng::uniform01(&mut rng),
                });
                let fast = m.step(&x);
                // The general loop, written out.
                let (hw, ow) = g.split_at(hidden * 9);
                let h: Vec<f64> = hw
                    .chunks_exact(9)
                    .map(|w| logistic((0..8).fold(w[0], |s, k| s + w[k + 1] * x[k])))
                    .collect();
                let slow: Vec<f64> = ow
                    .chunks_exact(hidden + 1)
                    .map(|w| logistic((0..hidden).fold(w[0], |s, k| s + w[k + 1] * h[k])))
                    .collect();
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&fast), bits(&slow));
            }
        }
    }

    #[test]
    fn zero_genome_outputs_half() {
        let shape = MlpShape::default();
        let mut m = Mlp::from_genome(shape, &vec![0.0; 68]).unwrap();
        assert_eq!(m.step(&[1.0; 8]), [0.5, 0.5]);
        let e = Mlp::from_genome(shape, &[0.0; 67]).unwrap_err();
        assert_eq!((e.expected, e.actual), (68, 67));
    }

    #[test]
    fn hand_computed_output() {
        // One hidden unit: bias 0, weight 1 on input 0 → logistic(1). Output 0: bias -1, w 2.
        let shape = MlpShape::with_hidden(1).unwrap();
        let mut g = vec![0.0; shape.genome_len()];
        g[1] = 1.0; // hidden unit, input 0
        g[9] = -1.0; // output 0 bias
        g[10] = 2.0; // output 0 weight on hidden 0
        let mut m = Mlp::from_genome(shape, &g).unwrap();
        let mut x = [0.0; 8];
        x[0] = 1.0;
        let o = m.step(&x);
        let h = logistic(1.0);
        assert_eq!(o[0], logistic(-1.0 + 2.0 * h));
        assert_eq!(o[1], 0.5);
    }
}
