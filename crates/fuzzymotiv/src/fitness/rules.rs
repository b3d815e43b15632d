//! The rule base over N motivations (docs/model.md §8): every combination of one label per
//! input is a rule; only the (at most 2^N) rules with non-zero weight are visited, with the
//! arithmetic of the naive loop, so F is bit-identical to it.

use std::fmt;

use crate::fitness::fuzzy::{Candidates, TskFitness, clamp_unit, label_name};
use crate::fitness::motivation::{MAX_MOTIVATIONS, Motivation, Motivations};

impl TskFitness {
    /// Visits every rule that may have non-zero weight, in ascending rule number, passing
    /// 0-based labels (one per motivation), weight `w` and output `f`. The arithmetic matches
    /// the naive loop over all rules exactly: `w` is the minimum taken left to right and `f`
    /// the sum of `X_i·Y_i·C_i[x_i]` added left to right, input 1 varying fastest. `y` is
    /// already clamped; one value per motivation.
    #[inline]
    fn for_each_rule(&self, x: &Motivations, y: &[f64], mut visit: impl FnMut(&[usize], f64, f64)) {
        let n = x.len().min(y.len()).min(MAX_MOTIVATIONS);
        if n == 0 {
            return;
        }
        let mut cand = [Candidates::NONE; MAX_MOTIVATIONS];
        let mut coef: [&[f64]; MAX_MOTIVATIONS] = [&[]; MAX_MOTIVATIONS];
        let mut weight = [0.0; MAX_MOTIVATIONS];
        for (i, m) in x.iter().take(n).enumerate() {
            let labels = self.labels_of(m);
            cand[i] = labels.candidates(y[i]);
            coef[i] = labels.coefficients();
            weight[i] = m.weight();
        }
        let mut at = [0usize; MAX_MOTIVATIONS];
        let mut labels = [0usize; MAX_MOTIVATIONS];
        loop {
            labels[0] = cand[0].labels[at[0]];
            let mut w = cand[0].mu[at[0]];
            let mut f = weight[0] * y[0] * coef[0][labels[0]];
            for i in 1..n {
                labels[i] = cand[i].labels[at[i]];
                w = w.min(cand[i].mu[at[i]]);
                f += weight[i] * y[i] * coef[i][labels[i]];
            }
            visit(&labels[..n], w, f);
            // The next combination, input 1 fastest.
            let mut i = 0;
            loop {
                at[i] += 1;
                if at[i] < cand[i].len {
                    break;
                }
                at[i] = 0;
                i += 1;
                if i == n {
                    return;
                }
            }
        }
    }

    /// The labels motivation `m` is fuzzified with: its own, or these shared ones.
    fn labels_of<'a>(&'a self, m: &'a Motivation) -> &'a TskFitness {
        m.labels().unwrap_or(self)
    }

    /// `F = Σ w·f / Σ w` from the sums; 0 when `Σ w` is not positive.
    fn ratio(numerator: f64, weight_sum: f64) -> f64 {
        // With a partition of unity some label of every input has membership
        // >= 0.5, so Σ w >= 0.5 and this guard never fires; it is kept for
        // robustness.
        if weight_sum > 0.0 {
            numerator / weight_sum
        } else {
            0.0
        }
    }

    /// The fuzzy fitness `F` for motivations `x` and fitness values `y`, one per motivation
    /// (the value of the term it weighs; for the paper's four `y = [a, g, l, b]`).
    ///
    /// Each `y` value is clamped to `[0, 1]` first (NaN becomes 0); values beyond the number of
    /// motivations are ignored and missing ones count as 0. For valid motivations and
    /// coefficients in `[0, 1]` the result lies in `[0, 1]`. Does not allocate; never panics.
    pub fn evaluate(&self, x: &Motivations, y: &[f64]) -> f64 {
        let y = clamped(x, y);
        let mut numerator = 0.0;
        let mut weight_sum = 0.0;
        self.for_each_rule(x, &y, |_, w, f| {
            numerator += w * f;
            weight_sum += w;
        });
        Self::ratio(numerator, weight_sum)
    }

    /// Like [`TskFitness::evaluate`] but also lists every firing rule
    /// (`w > 0`) in ascending rule number. `fitness` is bit-identical to
    /// `evaluate`; `weight_sum` is `Σ w` over all rules.
    pub fn explain(&self, x: &Motivations, y: &[f64]) -> Explanation {
        let y = clamped(x, y);
        let mut numerator = 0.0;
        let mut weight_sum = 0.0;
        let mut rules = Vec::new();
        self.for_each_rule(x, &y, |labels0, w, f| {
            numerator += w * f;
            weight_sum += w;
            if w > 0.0 {
                let labels: Vec<usize> = labels0.iter().map(|l| l + 1).collect();
                let label_names = x
                    .iter()
                    .zip(labels0)
                    .map(|(m, &l)| label_name(l, self.labels_of(m).labels()))
                    .collect();
                rules.push(FiringRule {
                    number: self.rule_number(x, &labels),
                    labels,
                    label_names,
                    weight: w,
                    output: f,
                });
            }
        });
        Explanation {
            fitness: Self::ratio(numerator, weight_sum),
            rules,
            weight_sum,
            inputs: x.input_names(),
        }
    }

    /// Number of labels `M_i` of each motivation's input.
    pub fn label_counts(&self, x: &Motivations) -> Vec<usize> {
        x.iter().map(|m| self.labels_of(m).labels()).collect()
    }

    /// Number of rules `Π M_i` (625 for the paper's four inputs of five labels); saturates at
    /// `usize::MAX`.
    pub fn rule_count(&self, x: &Motivations) -> usize {
        self.label_counts(x)
            .iter()
            .try_fold(1usize, |n, &m| n.checked_mul(m))
            .unwrap_or(usize::MAX)
    }

    /// Rule number `n = 1 + Σ_i (x_i − 1)·Π_{j<i} M_j` (1-based) of the 1-based labels
    /// `[x_1, …, x_N]`; `x_1` varies fastest.
    ///
    /// # Panics
    /// If a label is 0 or greater than its input's `M_i`, or the count is not N (a
    /// programming error).
    pub fn rule_number(&self, x: &Motivations, labels: &[usize]) -> usize {
        let counts = self.label_counts(x);
        assert!(
            labels.len() == counts.len()
                && labels
                    .iter()
                    .zip(&counts)
                    .all(|(&l, &m)| (1..=m).contains(&l)),
            "rule labels must be one per input, in 1..=M_i ({counts:?}), got {labels:?}"
        );
        1 + labels
            .iter()
            .zip(&counts)
            .rev()
            .fold(0, |acc, (&l, &m)| acc * m + (l - 1))
    }

    /// The 1-based labels `[x_1, …, x_N]` of rule `n` (1-based); the inverse of
    /// [`TskFitness::rule_number`].
    ///
    /// # Panics
    /// If `n` is 0 or greater than [`TskFitness::rule_count`] (a programming error).
    pub fn rule_labels(&self, x: &Motivations, n: usize) -> Vec<usize> {
        let count = self.rule_count(x);
        assert!(
            (1..=count).contains(&n),
            "rule number must be in 1..={count}, got {n}"
        );
        let mut rest = n - 1;
        self.label_counts(x)
            .into_iter()
            .map(|m| {
                let l = rest % m + 1;
                rest /= m;
                l
            })
            .collect()
    }
}

/// One value per motivation, each clamped to `[0, 1]` (NaN and missing values become 0).
fn clamped(x: &Motivations, y: &[f64]) -> [f64; MAX_MOTIVATIONS] {
    let mut out = [0.0; MAX_MOTIVATIONS];
    for (o, &v) in out.iter_mut().zip(y).take(x.len()) {
        *o = clamp_unit(v);
    }
    out
}

/// One rule with non-zero firing strength, as listed by
/// [`TskFitness::explain`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FiringRule {
    /// Rule number `n` (1-based, input 1 varies fastest).
    pub number: usize,
    /// 1-based labels, one per motivation (for the paper's four: `[a, g, l, b]`).
    pub labels: Vec<usize>,
    /// Label names, one per motivation (see [`label_name`]).
    pub label_names: Vec<String>,
    /// Firing strength `w[n] = min_i μ(Y_i)`, in `(0, 1]`.
    pub weight: f64,
    /// Rule output `f[n] = Σ_i X_i·Y_i·C[x_i]`.
    pub output: f64,
}

/// Breakdown of one fuzzy fitness evaluation.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Explanation {
    /// The fitness `F` (bit-identical to [`TskFitness::evaluate`]).
    pub fitness: f64,
    /// Rules with `w > 0`, in ascending rule number.
    pub rules: Vec<FiringRule>,
    /// `Σ w` over all rules.
    pub weight_sum: f64,
    /// The terms the inputs are (for the paper's four `a, g, l, b`), in input order.
    #[serde(skip)]
    pub inputs: Vec<String>,
}

impl fmt::Display for Explanation {
    /// A table of the firing rules followed by the final `F`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let width = 14 * self.inputs.len().max(4);
        writeln!(
            f,
            "{:>6}  {:<width$}  {:>10}  {:>10}",
            "rule", "if", "w", "f"
        )?;
        for rule in &self.rules {
            let condition = self
                .inputs
                .iter()
                .zip(&rule.label_names)
                .map(|(input, name)| format!("{input} is {name}"))
                .collect::<Vec<_>>()
                .join(" and ");
            writeln!(
                f,
                "{:>6}  {:<width$}  {:>10.6}  {:>10.6}",
                rule.number,
                format!("if {condition}"),
                rule.weight,
                rule.output
            )?;
        }
        write!(
            f,
            "sum of w = {:.6}; F = sum(w*f) / sum(w) = {:.6}",
            self.weight_sum, self.fitness
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fitness::fuzzy::{CoefficientScheme, FuzzyError, PAPER_PEAKS};

    /// Tiny deterministic LCG (Knuth MMIX constants).
    struct Lcg(u64);

    impl Lcg {
        fn next_f64(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Straightforward reference: loop over all Π M_i rules in rule-number order (input 1
    /// fastest), each motivation with its own labels or the shared ones.
    fn reference(t: &TskFitness, x: &Motivations, y: &[f64]) -> f64 {
        let y: Vec<f64> = y
            .iter()
            .map(|v| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) })
            .collect();
        let inputs: Vec<(&TskFitness, f64)> = x
            .iter()
            .map(|m| (m.labels().unwrap_or(t), m.weight()))
            .collect();
        let mut num = 0.0;
        let mut den = 0.0;
        for n in 1..=t.rule_count(x) {
            let labels = t.rule_labels(x, n);
            let mut w = f64::INFINITY;
            let mut f = None;
            for (i, &l) in labels.iter().enumerate() {
                let (labels_i, weight) = inputs[i];
                w = if i == 0 {
                    labels_i.membership(l - 1, y[i])
                } else {
                    w.min(labels_i.membership(l - 1, y[i]))
                };
                let term = weight * y[i] * labels_i.coefficients()[l - 1];
                f = Some(f.map_or(term, |s| s + term));
            }
            num += w * f.unwrap();
            den += w;
        }
        if den > 0.0 { num / den } else { 0.0 }
    }

    /// Random motivations: `n` of them, some with their own labels.
    fn random_motivations(rng: &mut Lcg, n: usize, own: &[TskFitness]) -> Motivations {
        let raw: Vec<f64> = (0..n).map(|_| rng.next_f64() + 1e-3).collect();
        let total: f64 = raw.iter().sum();
        let list = raw
            .iter()
            .enumerate()
            .map(|(i, w)| {
                let m = Motivation::new(format!("m{i}"), w / total, "a");
                let pick = (rng.next_f64() * (own.len() + 2) as f64) as usize;
                match own.get(pick) {
                    Some(labels) => m.with_labels(labels.clone()),
                    None => m,
                }
            })
            .collect();
        Motivations::from_list(list).unwrap().0
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-6
    }

    #[test]
    fn worked_values() {
        let t = TskFitness::paper();
        let f1 = t.evaluate(&Motivations::high_curiosity(), &[0.95, 0.5, 0.0, 0.79]);
        assert!(close(f1, 0.797220), "{f1}");
        let f2 = t.evaluate(&Motivations::low_curiosity(), &[0.55, 0.3, 0.0, 0.58]);
        assert!(close(f2, 0.263309), "{f2}");
        let x = Motivations::new(0.25, 0.25, 0.25, 0.25).unwrap();
        let f3 = t.evaluate(&x, &[1.0, 1.0, 1.0, 1.0]);
        assert!(close(f3, 1.0), "{f3}");
    }

    #[test]
    fn constants_are_valid() {
        for m in [Motivations::high_curiosity(), Motivations::low_curiosity()] {
            let [c, h, o, e] = m.as_array();
            assert_eq!(Motivations::new(c, h, o, e), Ok(m));
        }
    }

    #[test]
    fn rule_numbering() {
        let t = TskFitness::paper();
        assert_eq!(t.labels(), 5);
        let x = Motivations::high_curiosity();
        assert_eq!(t.rule_count(&x), 625);
        assert_eq!(t.rule_number(&x, &[5, 2, 1, 1]), 10);
        assert_eq!(t.rule_labels(&x, 10), [5, 2, 1, 1]);
        assert_eq!(t.rule_number(&x, &[1, 1, 1, 1]), 1);
        assert_eq!(t.rule_number(&x, &[5, 5, 5, 5]), 625);
        for n in 1..=625 {
            assert_eq!(t.rule_number(&x, &t.rule_labels(&x, n)), n);
        }
    }

    /// The fast path (at most 2^N rules visited) is bit-identical to the naive loop over all
    /// rules, for N = 1 … 8 motivations, shared and own labels.
    #[test]
    fn fast_path_is_bit_identical_to_full_loop() {
        let ts = [
            TskFitness::paper(),
            TskFitness::with_scheme(PAPER_PEAKS.to_vec(), CoefficientScheme::Ratio).unwrap(),
            TskFitness::new(vec![0.1, 0.3, 0.35, 0.9], vec![0.05, 0.9, 0.3, 1.0]).unwrap(),
            TskFitness::with_scheme(vec![0.0, 1.0], CoefficientScheme::Linear).unwrap(),
            TskFitness::with_scheme(
                vec![0.0, 0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0],
                CoefficientScheme::Linear,
            )
            .unwrap(),
        ];
        let own = [
            TskFitness::with_scheme(vec![0.0, 0.5, 1.0], CoefficientScheme::Ratio).unwrap(),
            TskFitness::new(vec![0.2, 0.4], vec![1.0, 0.3]).unwrap(),
        ];
        let mut rng = Lcg(12345);
        let specials = [0.0, 0.25, 0.5, 0.75, 1.0, 0.35, -0.2, 1.5, f64::NAN];
        for n in 1..=MAX_MOTIVATIONS {
            // The naive loop visits Π M_i rules (5^8 = 390 625 for eight inputs): fewer rounds
            // and at most five labels for many inputs.
            let rounds = match n {
                1..=4 => 3000,
                5..=6 => 60,
                _ => 12,
            };
            let shared: Vec<&TskFitness> =
                ts.iter().filter(|t| n <= 4 || t.labels() <= 5).collect();
            for t in shared {
                for _ in 0..rounds {
                    let x = random_motivations(&mut rng, n, &own);
                    let y: Vec<f64> = (0..n)
                        .map(|_| {
                            let r = rng.next_f64();
                            if r < 0.3 {
                                specials[(rng.next_f64() * specials.len() as f64) as usize]
                            } else {
                                rng.next_f64() * 1.4 - 0.2
                            }
                        })
                        .collect();
                    let fast = t.evaluate(&x, &y);
                    let slow = reference(t, &x, &y);
                    assert_eq!(fast.to_bits(), slow.to_bits(), "{x:?} {y:?}");
                    assert_eq!(t.explain(&x, &y).fitness.to_bits(), fast.to_bits());
                }
            }
        }
    }

    #[test]
    fn explanation_is_consistent() {
        let t = TskFitness::paper();
        let x = Motivations::high_curiosity();
        let y = [0.95, 0.5, 0.0, 0.79];
        let e = t.explain(&x, &y);
        assert_eq!(e.fitness, t.evaluate(&x, &y));
        assert_eq!(e.rules.len(), 4);
        let s: f64 = e.rules.iter().map(|r| r.weight).sum();
        assert!((s - e.weight_sum).abs() < 1e-12);
        assert!(e.rules.iter().all(|r| r.weight > 0.0));
        assert!(e.rules.windows(2).all(|p| p[0].number < p[1].number));
        for r in &e.rules {
            assert_eq!(t.rule_labels(&x, r.number), r.labels);
        }
        let text = e.to_string();
        assert!(text.contains("V.H."), "{text}");
        assert!(text.contains("if a is V.H. and g is M and l is V.L. and b is H"));
        assert!(text.contains("0.797220"), "{text}");

        let sample = t.explain(&x, &[1.0, 0.25, 0.0, 0.0]);
        assert_eq!(sample.rules.len(), 1);
        assert_eq!(sample.rules[0].number, 10);
        assert_eq!(sample.rules[0].label_names, ["V.H.", "L", "V.L.", "V.L."]);
    }

    #[test]
    fn out_of_range_y_is_clamped() {
        let t = TskFitness::paper();
        let x = Motivations::low_curiosity();
        assert_eq!(
            t.evaluate(&x, &[1.7, -0.3, f64::NAN, f64::INFINITY]),
            t.evaluate(&x, &[1.0, 0.0, 0.0, 1.0])
        );
    }

    #[test]
    fn a_nan_motivation_is_blamed_on_its_own_field() {
        let names = ["curiosity", "homing", "orientation", "energy"];
        for (k, name) in names.into_iter().enumerate() {
            let mut x = [0.25; 4];
            x[k] = f64::NAN;
            for err in [
                Motivations::new(x[0], x[1], x[2], x[3]).unwrap_err(),
                Motivations::normalised(x[0], x[1], x[2], x[3]).unwrap_err(),
            ] {
                assert!(
                    matches!(&err, FuzzyError::MotivationOutOfRange { name: n, value }
                        if n == name && value.is_nan()),
                    "{name}: {err}"
                );
            }
        }
    }

    #[test]
    fn motivation_errors() {
        let err = Motivations::new(0.5, 0.3, 0.0, 0.1).unwrap_err();
        let msg = err.to_string();
        assert!(msg.contains("sum to 1"), "{msg}");
        assert!(msg.contains("0.9"), "{msg}");
        assert!(matches!(err, FuzzyError::MotivationSum { .. }));

        let msg = Motivations::new(1.5, 0.0, 0.0, 0.0)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("curiosity") && msg.contains("1.5"), "{msg}");
        let msg = Motivations::new(0.5, -0.1, 0.3, 0.3)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("homing") && msg.contains("-0.1"), "{msg}");
        let msg = Motivations::new(0.5, 0.5, f64::NAN, 0.0)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("orientation") && msg.contains("NaN"), "{msg}");
        let msg = Motivations::new(0.5, 0.5, 0.0, f64::INFINITY)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("energy"), "{msg}");

        assert!(Motivations::new(0.5, 0.5, 0.0, 1e-10).is_ok());
        assert!(Motivations::new(0.5, 0.5, 0.0, 1e-8).is_err());
    }
}
