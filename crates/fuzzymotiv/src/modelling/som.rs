//! A one-dimensional self-organising map (SOM) for environment vectors (docs/model.md §9).
//!
//! Nodes lie on a line; the winner is the node with the smallest Euclidean distance (ties →
//! lowest index) and the neighbourhood is Gaussian in node index. Width and learning rate decay
//! geometrically over the epochs. Training is deterministic for a given generator state.

use crate::params::{BIG, FieldError, Num, check};
use crate::random::rng::{Rng, shuffle, uniform};
use crate::simulation::isa::Isa;

/// The most nodes a map may have.
pub const MAX_NODES: usize = 100_000;

/// The SOM's training parameters as given (in a config, the `[aem]` keys `som_nodes`,
/// `epochs`, `sigma_start`, `sigma_end`, `rate_start`, `rate_end`): see [`SomParams`] for each
/// one's unit, default and range; [`SomParams::from_raw`] checks them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RawSom {
    /// [`SomParams::nodes`].
    pub nodes: usize,
    /// [`SomParams::epochs`].
    pub epochs: usize,
    /// [`SomParams::sigma_start`].
    pub sigma_start: f64,
    /// [`SomParams::sigma_end`].
    pub sigma_end: f64,
    /// [`SomParams::rate_start`].
    pub rate_start: f64,
    /// [`SomParams::rate_end`].
    pub rate_end: f64,
}

impl Default for RawSom {
    fn default() -> Self {
        let d = SomParams::default();
        RawSom {
            nodes: d.nodes,
            epochs: d.epochs,
            sigma_start: d.sigma_start,
            sigma_end: d.sigma_end,
            rate_start: d.rate_start,
            rate_end: d.rate_end,
        }
    }
}

/// Checked training parameters of the SOM, built by [`SomParams::from_raw`] (or
/// [`SomParams::default`]: 128 nodes, 1000 epochs, σ 32 → 1, α 0.5 → 0.01).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SomParams {
    nodes: usize,
    epochs: usize,
    sigma_start: f64,
    sigma_end: f64,
    rate_start: f64,
    rate_end: f64,
}

impl Default for SomParams {
    fn default() -> Self {
        SomParams {
            nodes: 128,
            epochs: 1000,
            sigma_start: 32.0,
            sigma_end: 1.0,
            rate_start: 0.5,
            rate_end: 0.01,
        }
    }
}

impl SomParams {
    /// Checks the parameters, the one rule for them wherever they come from: `nodes` in
    /// 1..=100000, `epochs` in 1..=10⁶, widths and rates finite and > 0. An error names the
    /// `[aem]` key that sets the value (`aem.som_nodes`, `aem.epochs`, `aem.sigma_start`, …).
    pub fn from_raw(raw: &RawSom) -> Result<SomParams, FieldError> {
        check(
            (1..=MAX_NODES).contains(&raw.nodes),
            "aem.som_nodes",
            || format!("must be in 1..={MAX_NODES}, got {}", raw.nodes),
        )?;
        check((1..=BIG).contains(&raw.epochs), "aem.epochs", || {
            format!("must be in 1..={BIG}, got {}", raw.epochs)
        })?;
        for (name, v) in [
            ("aem.sigma_start", raw.sigma_start),
            ("aem.sigma_end", raw.sigma_end),
            ("aem.rate_start", raw.rate_start),
            ("aem.rate_end", raw.rate_end),
        ] {
            check(v.is_finite() && v > 0.0, name, || {
                format!("must be a finite number > 0, got {}", Num(v))
            })?;
        }
        Ok(SomParams {
            nodes: raw.nodes,
            epochs: raw.epochs,
            sigma_start: raw.sigma_start,
            sigma_end: raw.sigma_end,
            rate_start: raw.rate_start,
            rate_end: raw.rate_end,
        })
    }

    /// Number of nodes on the line; default 128; range 1..=100000.
    pub fn nodes(&self) -> usize {
        self.nodes
    }

    /// Number of epochs, each presenting every training vector once; default 1000; range
    /// 1..=10⁶.
    pub fn epochs(&self) -> usize {
        self.epochs
    }

    /// Neighbourhood width σ at the first epoch, in node-index units; default 32; > 0, finite.
    pub fn sigma_start(&self) -> f64 {
        self.sigma_start
    }

    /// Neighbourhood width σ at the last epoch, in node-index units; default 1; > 0, finite.
    pub fn sigma_end(&self) -> f64 {
        self.sigma_end
    }

    /// Learning rate α at the first epoch; default 0.5; > 0, finite.
    pub fn rate_start(&self) -> f64 {
        self.rate_start
    }

    /// Learning rate α at the last epoch; default 0.01; > 0, finite.
    pub fn rate_end(&self) -> f64 {
        self.rate_end
    }

    /// The geometric schedule value at epoch `e`: `start·(end/start)^(e/(epochs−1))`
    /// (`start` when `epochs ≤ 1`).
    pub fn schedule(start: f64, end: f64, epoch: usize, epochs: usize) -> f64 {
        if epochs <= 1 {
            start
        } else {
            start * (end / start).powf(epoch as f64 / (epochs - 1) as f64)
        }
    }
}

/// Errors from SOM training, winner search and recognition.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SomError {
    /// No vectors were given (training set or reference set is empty).
    #[error("empty data: at least one vector is required")]
    EmptyData,
    /// Vectors have zero elements.
    #[error("vectors must have at least one element")]
    ZeroDimension,
    /// A vector's length differs from the expected dimension.
    #[error("dimension mismatch: expected length {expected}, found {found}")]
    DimensionMismatch {
        /// The expected length (the first vector's, or the map's dimension).
        expected: usize,
        /// The offending vector's length.
        found: usize,
    },
    /// A training value is NaN or infinite.
    #[error("non-finite value in vector {vector} at element {element}")]
    NonFinite {
        /// Index of the vector in the training set.
        vector: usize,
        /// Index of the element within the vector.
        element: usize,
    },
    /// Training parameters that do not fit the data (a map of `nodes × dim` weights too large
    /// to count).
    #[error("invalid SOM parameters: {0}")]
    InvalidParams(String),
    /// A map whose stored weights do not match its node count and dimension (e.g. a
    /// hand-edited deserialised model).
    #[error("inconsistent SOM: {nodes} nodes × {dim} dims but {len} weights")]
    Inconsistent {
        /// Stored node count.
        nodes: usize,
        /// Stored dimension.
        dim: usize,
        /// Stored number of weights.
        len: usize,
    },
}

/// A trained one-dimensional SOM: `nodes` weight vectors of length `dim`, stored flat,
/// node-major (node `j` occupies `weights[j·dim .. (j+1)·dim]`).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Som {
    nodes: usize,
    dim: usize,
    weights: Vec<f64>,
}

/// Squared Euclidean distance of equal-length slices (four partial sums, fixed order, so the
/// result is deterministic and the loop vectorises).
#[inline]
pub(crate) fn sq_dist(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0f64; 4];
    let ca = a.chunks_exact(4);
    let cb = b.chunks_exact(4);
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            let d = x[k] - y[k];
            acc[k] += d * d;
        }
    }
    let mut tail = 0.0;
    for (x, y) in ra.iter().zip(rb) {
        let d = x - y;
        tail += d * d;
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// Index of the row of `weights` (flat, rows of length `dim > 0`) nearest to `v`; ties → lowest.
#[inline]
fn winner_flat(weights: &[f64], dim: usize, v: &[f64]) -> usize {
    let mut best = 0;
    let mut best_d = f64::INFINITY;
    for (j, w) in weights.chunks_exact(dim).enumerate() {
        let d = sq_dist(w, v);
        if d < best_d {
            best_d = d;
            best = j;
        }
    }
    best
}

/// [`fit`] compiled for `isa`, which the processor must have ([`Isa::detected`]).
fn fit_on<R: Rng + ?Sized>(
    isa: Isa,
    weights: &mut [f64],
    dim: usize,
    data: &[Vec<f64>],
    params: &SomParams,
    rng: &mut R,
) {
    match isa {
        Isa::Baseline => fit(weights, dim, data, params, rng),
        #[cfg(target_arch = "x86_64")]
        // SAFETY: `Isa::Avx2` is only made when the processor has AVX2 (`Isa::detected`).
        Isa::Avx2 => unsafe { fit_avx2(weights, dim, data, params, rng) },
    }
}

/// [`fit`] with AVX2 instructions: four dimensions per vector operation instead of two. The
/// same IEEE-754 operations in the same order (AVX2 does not enable FMA), so the same bits.
///
/// # Safety
/// The processor must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn fit_avx2<R: Rng + ?Sized>(
    weights: &mut [f64],
    dim: usize,
    data: &[Vec<f64>],
    params: &SomParams,
    rng: &mut R,
) {
    fit(weights, dim, data, params, rng)
}

/// The epochs of [`Som::train`] on the initial `weights` (flat, rows of length `dim > 0`).
///
/// Two shortcuts, neither of which changes a bit of the result:
/// - the winner search starts from the vector's winner of its previous presentation and
///   gives up on a node once its partial distance exceeds the best so far
///   ([`sq_dist_within`]); a node with an equal distance and a lower index still wins;
/// - a node whose step `α·h` is exactly 0 (far from the winner once σ is small) is not
///   visited, when the rates are at most 1 and the data at most 10³⁰⁰ in size: then every
///   update is a convex combination of finite numbers and no weight overflows, so
///   `w + 0·(x − w)` is `w` for every weight but −0, and no weight is ever −0 (the initial
///   weights are `lo + (hi − lo)·u` with `hi − lo ≥ 0`, and a sum is −0 only when both terms
///   are).
#[inline(always)]
fn fit<R: Rng + ?Sized>(
    weights: &mut [f64],
    dim: usize,
    data: &[Vec<f64>],
    params: &SomParams,
    rng: &mut R,
) {
    let nodes = weights.len() / dim;
    let mut order: Vec<usize> = (0..data.len()).collect();
    let mut last_win = vec![0; data.len()];
    // h by index distance |j − winner|, recomputed per epoch.
    let mut h_by_dist = vec![0.0f64; nodes];
    let skip_zero_steps = params.rate_start <= 1.0
        && params.rate_end <= 1.0
        && data.iter().flatten().all(|x| x.abs() <= 1e300);
    for epoch in 0..params.epochs {
        let sigma = SomParams::schedule(params.sigma_start, params.sigma_end, epoch, params.epochs);
        let rate = SomParams::schedule(params.rate_start, params.rate_end, epoch, params.epochs);
        let inv = 1.0 / (2.0 * sigma * sigma);
        for (d, h) in h_by_dist.iter_mut().enumerate() {
            let df = d as f64;
            *h = (-df * df * inv).exp();
        }
        for (i, o) in order.iter_mut().enumerate() {
            *o = i;
        }
        shuffle(rng, &mut order);
        for &i in &order {
            let x = data[i].as_slice();
            let win = winner_from(weights, dim, x, last_win[i]);
            last_win[i] = win;
            for (j, w) in weights.chunks_exact_mut(dim).enumerate() {
                let step = rate * h_by_dist[j.abs_diff(win)];
                if step == 0.0 && skip_zero_steps {
                    continue;
                }
                for (wk, &xk) in w.iter_mut().zip(x) {
                    *wk += step * (xk - *wk);
                }
            }
        }
    }
}

/// [`winner_flat`]'s answer (the nearest row, ties → lowest index), found by measuring row
/// `hint` first and then giving up on each other row as soon as its partial distance exceeds
/// the best so far.
#[inline(always)]
fn winner_from(weights: &[f64], dim: usize, v: &[f64], hint: usize) -> usize {
    let row = |j: usize| &weights[j * dim..(j + 1) * dim];
    let mut best = hint;
    let mut best_d = sq_dist(row(hint), v);
    if !best_d.is_finite() {
        return winner_flat(weights, dim, v); // NaN and ∞ rows never win there: keep its rule
    }
    for j in (0..weights.len() / dim).filter(|&j| j != hint) {
        if let Some(d) = sq_dist_within(row(j), v, best_d)
            && (d < best_d || (d == best_d && j < best))
        {
            best_d = d;
            best = j;
        }
    }
    best
}

/// [`sq_dist`] of `a` and `b` (equal lengths), or `None` once it is sure to exceed `bound`.
///
/// Every 32 elements the four partial sums are combined as [`sq_dist`] combines them at the
/// end; the partial sums only grow (each adds a square ≥ 0) and rounding is monotone, so
/// [`sq_dist`]'s result is at least that value, and a value above `bound` means a result above
/// it. When the row is measured to the end, the result is [`sq_dist`]'s, bit for bit.
#[inline(always)]
fn sq_dist_within(a: &[f64], b: &[f64], bound: f64) -> Option<f64> {
    const CHECK: usize = 8;
    let mut acc = [0.0f64; 4];
    let ca = a.chunks_exact(4);
    let cb = b.chunks_exact(4);
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (c, (x, y)) in ca.zip(cb).enumerate() {
        for k in 0..4 {
            let d = x[k] - y[k];
            acc[k] += d * d;
        }
        if c % CHECK == CHECK - 1 && (acc[0] + acc[1]) + (acc[2] + acc[3]) > bound {
            return None;
        }
    }
    let mut tail = 0.0;
    for (x, y) in ra.iter().zip(rb) {
        let d = x - y;
        tail += d * d;
    }
    Some((acc[0] + acc[1]) + (acc[2] + acc[3]) + tail)
}

impl Som {
    /// Trains a map on `data` (all vectors of equal, non-zero length, finite values).
    ///
    /// Weights start uniform in the data's per-dimension range `U(min_d, max_d)` (drawn node by
    /// node, dimension by dimension). Each epoch `e` uses σ(e) and α(e) from the geometric
    /// schedule ([`SomParams::schedule`]), presents every vector once in an order shuffled with
    /// `rng`, and updates every node `w_j += α·h_j·(x − w_j)` with
    /// `h_j = exp(−(j − winner)²/(2σ²))`. Errors: empty data, zero or mismatched lengths,
    /// non-finite values, a map too large to count its weights.
    pub fn train<R: Rng + ?Sized>(
        data: &[Vec<f64>],
        params: &SomParams,
        rng: &mut R,
    ) -> Result<Som, SomError> {
        let first = data.first().ok_or(SomError::EmptyData)?;
        let dim = first.len();
        if dim == 0 {
            return Err(SomError::ZeroDimension);
        }
        for (i, v) in data.iter().enumerate() {
            if v.len() != dim {
                return Err(SomError::DimensionMismatch {
                    expected: dim,
                    found: v.len(),
                });
            }
            if let Some(e) = v.iter().position(|x| !x.is_finite()) {
                return Err(SomError::NonFinite {
                    vector: i,
                    element: e,
                });
            }
        }
        let nodes = params.nodes;
        let len = nodes.checked_mul(dim).ok_or_else(|| {
            SomError::InvalidParams(format!("{nodes} nodes × {dim} dims overflows"))
        })?;

        // Per-dimension range of the data.
        let mut lo = first.clone();
        let mut hi = first.clone();
        for v in &data[1..] {
            for ((l, h), &x) in lo.iter_mut().zip(hi.iter_mut()).zip(v) {
                *l = l.min(x);
                *h = h.max(x);
            }
        }
        let mut weights = Vec::with_capacity(len);
        for _ in 0..nodes {
            for d in 0..dim {
                weights.push(uniform(rng, lo[d], hi[d]));
            }
        }

        fit_on(Isa::detected(), &mut weights, dim, data, params, rng);
        Ok(Som {
            nodes,
            dim,
            weights,
        })
    }

    /// A map from explicit weights (flat, node-major, `nodes × dim` values), e.g. for tests or
    /// a stored model. Errors if `nodes` or `dim` is zero or the length does not match.
    pub fn from_weights(nodes: usize, dim: usize, weights: Vec<f64>) -> Result<Som, SomError> {
        let som = Som {
            nodes,
            dim,
            weights,
        };
        som.check()?;
        Ok(som)
    }

    /// The winning node for `v`: smallest Euclidean distance, ties → lowest index.
    /// Errors if `v.len() != self.dim()` or the map is inconsistent. NaN distances never win.
    pub fn winner(&self, v: &[f64]) -> Result<usize, SomError> {
        self.check()?;
        if v.len() != self.dim {
            return Err(SomError::DimensionMismatch {
                expected: self.dim,
                found: v.len(),
            });
        }
        Ok(winner_flat(&self.weights, self.dim, v))
    }

    /// Number of nodes.
    pub fn nodes(&self) -> usize {
        self.nodes
    }

    /// Length of the weight (and input) vectors.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The weight vector of `node` (length `dim`); an empty slice if `node` is out of range.
    pub fn weights(&self, node: usize) -> &[f64] {
        node.checked_mul(self.dim)
            .and_then(|s| self.weights.get(s..s.checked_add(self.dim)?))
            .unwrap_or(&[])
    }

    /// Checks that the stored weights match `nodes × dim` with both non-zero.
    fn check(&self) -> Result<(), SomError> {
        if self.nodes == 0
            || self.dim == 0
            || Some(self.weights.len()) != self.nodes.checked_mul(self.dim)
        {
            return Err(SomError::Inconsistent {
                nodes: self.nodes,
                dim: self.dim,
                len: self.weights.len(),
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::rng::{Rng64, index, rng_from_seed, uniform};

    fn clusters(seed: u64) -> (Vec<Vec<f64>>, Vec<usize>) {
        let centres = [
            [0.0, 0.0, 0.0],
            [10.0, 0.0, 0.0],
            [0.0, 10.0, 0.0],
            [0.0, 0.0, 10.0],
        ];
        let mut rng = rng_from_seed(seed);
        let mut data = Vec::new();
        let mut labels = Vec::new();
        for (c, centre) in centres.iter().enumerate() {
            for _ in 0..5 {
                data.push(
                    centre
                        .iter()
                        .map(|&x| x + uniform(&mut rng, -0.5, 0.5))
                        .collect(),
                );
                labels.push(c);
            }
        }
        (data, labels)
    }

    /// Checked parameters from `raw`.
    fn checked(raw: RawSom) -> SomParams {
        SomParams::from_raw(&raw).unwrap()
    }

    fn small_params() -> SomParams {
        checked(RawSom {
            nodes: 20,
            epochs: 200,
            sigma_start: 5.0,
            ..RawSom::default()
        })
    }

    #[test]
    fn separable_clusters_get_distinct_winners() {
        let (data, labels) = clusters(1);
        let som = Som::train(&data, &small_params(), &mut rng_from_seed(7)).unwrap();
        let winners: Vec<usize> = data.iter().map(|v| som.winner(v).unwrap()).collect();
        for i in 0..data.len() {
            for j in 0..data.len() {
                if labels[i] != labels[j] {
                    assert_ne!(
                        winners[i], winners[j],
                        "clusters {} and {}",
                        labels[i], labels[j]
                    );
                }
            }
        }
    }

    #[test]
    fn deterministic_for_seed() {
        let (data, _) = clusters(2);
        let a = Som::train(&data, &small_params(), &mut rng_from_seed(3)).unwrap();
        let b = Som::train(&data, &small_params(), &mut rng_from_seed(3)).unwrap();
        let c = Som::train(&data, &small_params(), &mut rng_from_seed(4)).unwrap();
        let bits = |s: &Som| s.weights.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a), bits(&b));
        assert_ne!(bits(&a), bits(&c));
    }

    #[test]
    fn init_within_range_and_constant_dims() {
        let data = vec![vec![1.0, 5.0, 2.0], vec![3.0, 5.0, 4.0]];
        let p = checked(RawSom {
            nodes: 8,
            epochs: 1,
            rate_start: 1e-300,
            rate_end: 1e-300,
            ..RawSom::default()
        });
        let som = Som::train(&data, &p, &mut rng_from_seed(0)).unwrap();
        for j in 0..8 {
            let w = som.weights(j);
            assert!((1.0..=3.0).contains(&w[0]));
            assert_eq!(w[1], 5.0);
            assert!((2.0..=4.0).contains(&w[2]));
        }
        assert!(som.weights(8).is_empty());
        assert!(som.weights(usize::MAX).is_empty());
        assert_eq!((som.nodes(), som.dim()), (8, 3));
    }

    #[test]
    fn schedule_endpoints() {
        assert_eq!(SomParams::schedule(32.0, 1.0, 0, 1000), 32.0);
        assert!((SomParams::schedule(32.0, 1.0, 999, 1000) - 1.0).abs() < 1e-12);
        assert!((SomParams::schedule(0.5, 0.01, 999, 1000) - 0.01).abs() < 1e-12);
        assert_eq!(SomParams::schedule(0.5, 0.01, 0, 1), 0.5);
    }

    #[test]
    fn single_node_and_ties() {
        let data = vec![vec![1.0, 2.0]];
        let p = checked(RawSom {
            nodes: 1,
            epochs: 1,
            ..RawSom::default()
        });
        let som = Som::train(&data, &p, &mut rng_from_seed(0)).unwrap();
        assert_eq!(som.winner(&[100.0, -3.0]).unwrap(), 0);
        // Identical nodes: tie → lowest index.
        let som = Som {
            nodes: 3,
            dim: 1,
            weights: vec![1.0, 0.0, 0.0],
        };
        assert_eq!(som.winner(&[0.0]).unwrap(), 1);
        assert_eq!(som.winner(&[f64::NAN]).unwrap(), 0);
    }

    #[test]
    fn errors() {
        let p = SomParams::default();
        let mut rng = rng_from_seed(0);
        assert_eq!(Som::train(&[], &p, &mut rng), Err(SomError::EmptyData));
        assert_eq!(
            Som::train(&[vec![], vec![]], &p, &mut rng),
            Err(SomError::ZeroDimension)
        );
        assert_eq!(
            Som::train(&[vec![1.0, 2.0], vec![1.0]], &p, &mut rng),
            Err(SomError::DimensionMismatch {
                expected: 2,
                found: 1
            })
        );
        assert_eq!(
            Som::train(&[vec![1.0, f64::NAN]], &p, &mut rng),
            Err(SomError::NonFinite {
                vector: 0,
                element: 1
            })
        );
        let raw = RawSom::default();
        for (bad, field) in [
            (RawSom { nodes: 0, ..raw }, "aem.som_nodes"),
            (
                RawSom {
                    nodes: 100_001,
                    ..raw
                },
                "aem.som_nodes",
            ),
            (RawSom { epochs: 0, ..raw }, "aem.epochs"),
            (
                RawSom {
                    sigma_end: 0.0,
                    ..raw
                },
                "aem.sigma_end",
            ),
            (
                RawSom {
                    rate_start: f64::NAN,
                    ..raw
                },
                "aem.rate_start",
            ),
            (
                RawSom {
                    rate_end: -0.1,
                    ..raw
                },
                "aem.rate_end",
            ),
        ] {
            assert_eq!(SomParams::from_raw(&bad).unwrap_err().field, field);
        }
        let small = checked(RawSom {
            nodes: 4,
            epochs: 2,
            ..raw
        });
        let som = Som::train(&[vec![1.0, 2.0]], &small, &mut rng).unwrap();
        assert_eq!(
            som.winner(&[1.0]),
            Err(SomError::DimensionMismatch {
                expected: 2,
                found: 1
            })
        );
        let broken = Som {
            nodes: 2,
            dim: 3,
            weights: vec![0.0; 5],
        };
        assert!(matches!(
            broken.winner(&[0.0; 3]),
            Err(SomError::Inconsistent { .. })
        ));
        let zero = Som {
            nodes: 0,
            dim: 0,
            weights: vec![],
        };
        assert!(matches!(
            zero.winner(&[]),
            Err(SomError::Inconsistent { .. })
        ));
    }

    /// The epochs as [`Som::train`] ran them before its shortcuts: every node measured in
    /// full, every node updated.
    fn fit_plain(
        weights: &mut [f64],
        dim: usize,
        data: &[Vec<f64>],
        p: &SomParams,
        rng: &mut Rng64,
    ) {
        let nodes = weights.len() / dim;
        let mut order: Vec<usize> = (0..data.len()).collect();
        let mut h_by_dist = vec![0.0f64; nodes];
        for epoch in 0..p.epochs {
            let sigma = SomParams::schedule(p.sigma_start, p.sigma_end, epoch, p.epochs);
            let rate = SomParams::schedule(p.rate_start, p.rate_end, epoch, p.epochs);
            let inv = 1.0 / (2.0 * sigma * sigma);
            for (d, h) in h_by_dist.iter_mut().enumerate() {
                let df = d as f64;
                *h = (-df * df * inv).exp();
            }
            for (i, o) in order.iter_mut().enumerate() {
                *o = i;
            }
            shuffle(rng, &mut order);
            for &i in &order {
                let x = data[i].as_slice();
                let win = winner_flat(weights, dim, x);
                for (j, w) in weights.chunks_exact_mut(dim).enumerate() {
                    let step = rate * h_by_dist[j.abs_diff(win)];
                    for (wk, &xk) in w.iter_mut().zip(x) {
                        *wk += step * (xk - *wk);
                    }
                }
            }
        }
    }

    /// Both compiled forms of the training, with their shortcuts, leave every weight with the
    /// bits of the plain training: chain-code-like walks, repeated vectors (ties), every
    /// length mod 4, maps of 1 to 128 nodes, σ small enough that far nodes get a zero step,
    /// and rates above 1 (no skipping).
    #[test]
    fn shortcuts_train_the_plain_maps_bit_for_bit() {
        let mut isas = vec![Isa::Baseline];
        if Isa::detected() != Isa::Baseline {
            isas.push(Isa::detected());
        }
        let mut draws = rng_from_seed(41);
        let cases = [
            (128, 400, 5, 60, 32.0, 0.3, 0.5),
            (128, 37, 5, 40, 4.0, 0.2, 0.5),
            (17, 8, 9, 50, 8.0, 0.5, 1.0),
            (40, 33, 4, 30, 2.0, 0.1, 2.0),
            (1, 6, 3, 10, 1.0, 1.0, 0.5),
            (2, 1, 6, 20, 1.0, 0.05, 0.9),
        ];
        for (nodes, dim, n, epochs, sigma_start, sigma_end, rate_start) in cases {
            let mut data: Vec<Vec<f64>> = (0..n)
                .map(|_| {
                    let mut code = 0i64;
                    (0..dim)
                        .map(|_| {
                            code += index(&mut draws, 5) as i64 - 2;
                            code as f64 / 12.0
                        })
                        .collect()
                })
                .collect();
            data.push(data[0].clone());
            let p = checked(RawSom {
                nodes,
                epochs,
                sigma_start,
                sigma_end,
                rate_start,
                rate_end: 0.01,
            });
            let init: Vec<f64> = (0..nodes * dim)
                .map(|_| uniform(&mut draws, -3.0, 3.0))
                .collect();
            let mut plain = init.clone();
            fit_plain(&mut plain, dim, &data, &p, &mut rng_from_seed(7));
            for &isa in &isas {
                let mut fast = init.clone();
                fit_on(isa, &mut fast, dim, &data, &p, &mut rng_from_seed(7));
                let bits = |w: &[f64]| w.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&fast), bits(&plain), "{isa:?}, {nodes} nodes × {dim}");
            }
        }
    }

    /// The winner search with a hint answers as the plain one for every hint, including rows
    /// at equal distances (the lowest wins) and rows at infinite or NaN distances.
    #[test]
    fn winner_from_any_hint_is_the_plain_winner() {
        let dim = 5;
        let rows: Vec<f64> = [
            [1.0, 2.0, 3.0, 4.0, 5.0],
            [0.0, 0.0, 0.0, 0.0, 1.0],
            [1.0, 2.0, 3.0, 4.0, 5.0],
            [0.0, 0.0, 0.0, 0.0, 1.0],
            [9.0, 9.0, 9.0, 9.0, 9.0],
        ]
        .concat();
        for v in [
            [0.0; 5],
            [1.0, 2.0, 3.0, 4.0, 5.0],
            [9.0; 5],
            [5.0, 4.0, 3.0, 2.0, 1.0],
        ] {
            for hint in 0..5 {
                assert_eq!(
                    winner_from(&rows, dim, &v, hint),
                    winner_flat(&rows, dim, &v)
                );
            }
        }
        let mut odd = rows.clone();
        odd[0] = f64::NAN;
        odd[10] = f64::INFINITY;
        odd[11] = f64::MAX;
        for v in [[0.0; 5], [9.0; 5]] {
            for hint in 0..5 {
                assert_eq!(winner_from(&odd, dim, &v, hint), winner_flat(&odd, dim, &v));
            }
        }
    }
}
