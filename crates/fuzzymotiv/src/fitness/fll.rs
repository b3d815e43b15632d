//! Export of the TSK motivation fitness as a [fuzzylite](https://fuzzylite.com) FLL file, so
//! that fuzzylite (C++, Java, Python) and the tools built on it compute the same `F`.
//!
//! The engine has the four inputs `a, g, l, b` on `[0, 1]` (`lock-range: true`, i.e. clamped
//! like [`TskFitness::evaluate`] clamps), one term per label (a `Triangle` through the
//! neighbouring peaks; a first or last label whose shoulder matters inside `[0, 1]` becomes a
//! `Trapezoid`), and one output `F` with one first-order `Linear` term per rule: rule `n` with
//! labels `(x_a, x_g, x_l, x_b)` outputs `Σ_i X_i·C[x_i]·Y_i`, so its coefficients are
//! `X_i·C[x_i]` (constant 0). Conjunction `Minimum`, defuzzifier `WeightedAverage` (TSK), rules
//! numbered as in [`TskFitness::rule_number`] (`x_a` fastest). Numbers are printed in Rust's
//! shortest round-trip form, so every coefficient reads back to the same `f64`.
//!
//! ```
//! use fuzzymotiv::fitness::to_fll;
//! use fuzzymotiv::fitness::{Motivations, TskFitness};
//! let text = to_fll(&TskFitness::paper(), &Motivations::high_curiosity(), "high_curiosity");
//! assert_eq!(text.matches("\n  rule: ").count(), 625);
//! assert!(text.contains("term: r10 Linear 0.8 0.025 0 0 0"));
//! ```

use std::fmt::Write as _;

use crate::fitness::fuzzy::TskFitness;
use crate::fitness::motivation::Motivations;

/// Name of the FLL output variable.
pub const OUTPUT_NAME: &str = "F";

/// FLL identifier of label `m` (0-based) of `count` labels: `VL, L, M, H, VH` for the paper's
/// five labels, else `L1..LM`.
pub fn fll_label(m: usize, count: usize) -> String {
    const FIVE: [&str; 5] = ["VL", "L", "M", "H", "VH"];
    if count == FIVE.len() {
        FIVE[m].to_string()
    } else {
        format!("L{}", m + 1)
    }
}

/// A number in Rust's shortest round-trip decimal form (`-0` printed as `0`).
fn num(v: f64) -> String {
    if v == 0.0 {
        "0".to_string()
    } else {
        format!("{v}")
    }
}

/// Keeps only characters FLL accepts in an identifier (letters, digits, `_`).
fn identifier(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if s.is_empty() { "fuzzymotiv".into() } else { s }
}

/// The membership function of label `m` as an FLL term definition (after the term's name).
fn term_shape(peaks: &[f64], m: usize) -> String {
    let last = peaks.len() - 1;
    let p = peaks[m];
    if m == 0 {
        let high = peaks[1];
        if p <= 0.0 {
            // Inputs are clamped to [0, 1] >= p: the left half is never used.
            format!("Triangle {} {} {}", num(p - (high - p)), num(p), num(high))
        } else {
            format!(
                "Trapezoid {} {} {} {}",
                num(0.0),
                num(0.0),
                num(p),
                num(high)
            )
        }
    } else if m == last {
        let low = peaks[m - 1];
        if p >= 1.0 {
            format!("Triangle {} {} {}", num(low), num(p), num(p + (p - low)))
        } else {
            format!(
                "Trapezoid {} {} {} {}",
                num(low),
                num(p),
                num(1.0),
                num(1.0)
            )
        }
    } else {
        format!(
            "Triangle {} {} {}",
            num(peaks[m - 1]),
            num(p),
            num(peaks[m + 1])
        )
    }
}

/// The TSK fuzzy fitness `tsk` under `motivations` as a fuzzylite FLL engine named `name`
/// (characters other than letters, digits and `_` become `_`). See the module documentation.
pub fn to_fll(tsk: &TskFitness, motivations: &Motivations, name: &str) -> String {
    let inputs = motivations.input_names();
    let labels: Vec<&TskFitness> = motivations
        .iter()
        .map(|m| m.labels().unwrap_or(tsk))
        .collect();
    let x = motivations.weights();
    let mut s = String::new();
    let _ = writeln!(s, "Engine: {}", identifier(name));
    let _ = writeln!(
        s,
        "  description: fuzzymotiv {} TSK motivation fitness, {}, {} rules",
        env!("CARGO_PKG_VERSION"),
        describe(motivations),
        tsk.rule_count(motivations)
    );
    for (input, l) in inputs.iter().zip(&labels) {
        let _ = writeln!(s, "InputVariable: {input}");
        s.push_str("  enabled: true\n  range: 0 1\n  lock-range: true\n");
        for k in 0..l.labels() {
            let _ = writeln!(
                s,
                "  term: {} {}",
                fll_label(k, l.labels()),
                term_shape(l.peaks(), k)
            );
        }
    }
    let _ = writeln!(s, "OutputVariable: {OUTPUT_NAME}");
    s.push_str(
        "  enabled: true\n  range: 0 1\n  lock-range: false\n  aggregation: none\n  defuzzifier: WeightedAverage TakagiSugeno\n  default: nan\n  lock-previous: false\n",
    );
    let rules = tsk.rule_count(motivations);
    for n in 1..=rules {
        let rule = tsk.rule_labels(motivations, n);
        let coefs: Vec<String> = (0..rule.len())
            .map(|i| num(x[i] * labels[i].coefficients()[rule[i] - 1]))
            .collect();
        let _ = writeln!(s, "  term: r{n} Linear {} 0", coefs.join(" "));
    }
    s.push_str(
        "RuleBlock: rules\n  enabled: true\n  conjunction: Minimum\n  disjunction: none\n  implication: none\n  activation: General\n",
    );
    for n in 1..=rules {
        let rule = tsk.rule_labels(motivations, n);
        let condition: Vec<String> = inputs
            .iter()
            .zip(&rule)
            .zip(&labels)
            .map(|((input, &l), t)| format!("{input} is {}", fll_label(l - 1, t.labels())))
            .collect();
        let _ = writeln!(
            s,
            "  rule: if {} then {OUTPUT_NAME} is r{n}",
            condition.join(" and ")
        );
    }
    s
}

/// `(C,H,O,E) = (0.8,0.1,0,0.1)` for the paper's four, else `X = (name 0.6, …)`.
fn describe(motivations: &Motivations) -> String {
    if motivations.is_paper() {
        let x: Vec<String> = motivations.weights().into_iter().map(num).collect();
        format!("(C,H,O,E) = ({})", x.join(","))
    } else {
        let x: Vec<String> = motivations
            .iter()
            .map(|m| format!("{} {}", m.name(), num(m.weight())))
            .collect();
        format!("X = ({})", x.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fitness::fuzzy::CoefficientScheme;

    /// Evaluates an FLL text the way fuzzylite does, from the text alone (terms, rules,
    /// `Linear` coefficients), for the shapes `to_fll` writes.
    fn eval_fll(text: &str, y: &[f64]) -> f64 {
        let y: Vec<f64> = y.iter().map(|v| v.clamp(0.0, 1.0)).collect();
        let mut terms: Vec<std::collections::HashMap<String, Vec<f64>>> = vec![];
        let mut outputs = std::collections::HashMap::new();
        let mut in_output = false;
        let mut num = 0.0;
        let mut den = 0.0;
        for line in text.lines() {
            let line = line.trim();
            if line.starts_with("InputVariable:") {
                terms.push(Default::default());
            } else if line.starts_with("OutputVariable:") {
                in_output = true;
            } else if let Some(rest) = line.strip_prefix("term: ") {
                let parts: Vec<&str> = rest.split(' ').collect();
                let values: Vec<f64> = parts[2..].iter().map(|p| p.parse().unwrap()).collect();
                if in_output {
                    assert_eq!(parts[1], "Linear");
                    outputs.insert(parts[0].to_string(), values);
                } else {
                    terms
                        .last_mut()
                        .unwrap()
                        .insert(parts[0].to_string(), values);
                }
            } else if let Some(rest) = line.strip_prefix("rule: if ") {
                let (cond, out) = rest.split_once(" then F is ").unwrap();
                let mut w: f64 = 1.0;
                for (i, clause) in cond.split(" and ").enumerate() {
                    let label = clause.split(" is ").nth(1).unwrap();
                    let v = &terms[i][label];
                    let x = y[i];
                    let mu = match v.len() {
                        3 if x < v[0] || x > v[2] => 0.0,
                        3 if x == v[1] => 1.0,
                        3 if x < v[1] => (x - v[0]) / (v[1] - v[0]),
                        3 => (v[2] - x) / (v[2] - v[1]),
                        _ if x < v[0] || x > v[3] => 0.0,
                        _ if x < v[1] => (x - v[0]) / (v[1] - v[0]),
                        _ if x <= v[2] => 1.0,
                        _ => (v[3] - x) / (v[3] - v[2]),
                    };
                    w = w.min(mu);
                }
                let c = &outputs[out];
                let f: f64 = (0..y.len()).map(|i| c[i] * y[i]).sum::<f64>() + c[y.len()];
                num += w * f;
                den += w;
            }
        }
        num / den
    }

    #[test]
    fn paper_engine_has_625_rules_and_terms() {
        let x = Motivations::high_curiosity();
        let text = to_fll(&TskFitness::paper(), &x, "high curiosity");
        assert!(text.starts_with("Engine: high_curiosity\n"));
        assert_eq!(text.matches("\n  rule: if ").count(), 625);
        assert_eq!(text.matches(" Linear ").count(), 625);
        assert_eq!(text.matches("InputVariable: ").count(), 4);
        assert!(text.contains("  term: VL Triangle -0.25 0 0.25\n"));
        assert!(text.contains("  term: VH Triangle 0.75 1 1.25\n"));
        assert!(text.contains("conjunction: Minimum"));
        assert!(text.contains("defuzzifier: WeightedAverage TakagiSugeno"));
        // Rule 10 = (V.H., L, V.L., V.L.): coefficients X_i·C[x_i].
        assert!(
            text.contains("  term: r10 Linear 0.8 0.025 0 0 0\n"),
            "{text}"
        );
        assert!(
            text.contains("  rule: if a is VH and g is L and l is VL and b is VL then F is r10\n")
        );
    }

    #[test]
    fn coefficients_round_trip() {
        let x = Motivations::new(0.3, 0.2, 0.1, 0.4).unwrap();
        let tsk = TskFitness::new(
            crate::fitness::fuzzy::PAPER_PEAKS.to_vec(),
            vec![0.1, 1.0 / 3.0, 0.5, 2.0 / 3.0, 0.9],
        )
        .unwrap();
        let text = to_fll(&tsk, &x, "t");
        for n in 1..=625 {
            let labels = tsk.rule_labels(&x, n);
            let prefix = format!("  term: r{n} Linear ");
            let line = text.lines().find(|l| l.starts_with(&prefix)).unwrap();
            let values: Vec<f64> = line[prefix.len()..]
                .split(' ')
                .map(|v| v.parse().unwrap())
                .collect();
            assert_eq!(values.len(), 5);
            for i in 0..4 {
                let expected = x.as_array()[i] * tsk.coefficients()[labels[i] - 1];
                assert_eq!(
                    values[i].to_bits(),
                    expected.to_bits(),
                    "rule {n} input {i}"
                );
            }
            assert_eq!(values[4], 0.0);
        }
    }

    #[test]
    fn fll_semantics_match_evaluate() {
        let cases = [
            (TskFitness::paper(), Motivations::high_curiosity()),
            (TskFitness::paper(), Motivations::low_curiosity()),
            (
                TskFitness::with_scheme(vec![0.1, 0.3, 0.35, 0.9], CoefficientScheme::Ratio)
                    .unwrap(),
                Motivations::new(0.25, 0.25, 0.25, 0.25).unwrap(),
            ),
        ];
        for (tsk, x) in &cases {
            let text = to_fll(tsk, x, "t");
            for k in 0..400 {
                let t = k as f64;
                let y = [
                    (t * 0.137).fract() * 1.2 - 0.1,
                    (t * 0.291).fract(),
                    (t * 0.533).fract(),
                    (t * 0.771).fract(),
                ];
                let ours = tsk.evaluate(x, &y);
                let theirs = eval_fll(&text, &y);
                assert!((ours - theirs).abs() < 1e-12, "{y:?}: {ours} vs {theirs}");
            }
        }
        let text = to_fll(&TskFitness::paper(), &Motivations::high_curiosity(), "t");
        assert!((eval_fll(&text, &[0.95, 0.5, 0.0, 0.79]) - 0.797220).abs() < 1e-6);
    }
}
