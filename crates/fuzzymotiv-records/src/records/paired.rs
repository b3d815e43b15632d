//! The statistics of one paired comparison of a with b as the combination and urgency studies
//! record them: the shared tail of a `behaviour.csv` / `urgency.csv` row and of its record in
//! `summary.json` (embedded with `#[serde(flatten)]`, so the fields stand in the row itself).

use fuzzymotiv::statistics::{Comparison, Expect};
use serde::{Deserialize, Serialize};

/// a − b, paired by seed: the effect, its interval, p, what the design detects and the verdict.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PairedStats {
    /// a − b, the mean of the per-seed differences.
    pub difference: f64,
    /// Its 95 % bootstrap interval.
    pub ci_low: f64,
    /// Upper bound.
    pub ci_high: f64,
    /// Two-sided sign-flip permutation p-value.
    pub p: f64,
    /// The smallest difference the design detects with 80 % power; none without spread
    /// (`null` in JSON).
    pub detectable: Option<f64>,
    /// `higher` / `lower` for a (p < α and at least the detectable difference),
    /// `inconclusive` (a difference within the detectable one) or `not significant`
    /// ([`Comparison::verdict_with_power`]).
    pub verdict: String,
}

impl PairedStats {
    /// The statistics of `c`, its verdict said as a direction of a against b.
    pub fn of(c: &Comparison) -> PairedStats {
        PairedStats {
            difference: c.difference,
            ci_low: c.ci_low,
            ci_high: c.ci_high,
            p: c.p,
            detectable: c.mdd,
            verdict: c
                .verdict_with_power(Expect::Higher)
                .direction_label()
                .into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::PairedStats;
    use crate::records::combination::BehaviourRow;
    use crate::records::urgency::UrgencyRow;

    fn stats(detectable: Option<f64>) -> PairedStats {
        PairedStats {
            difference: 1.5,
            ci_low: -0.25,
            ci_high: 3.0,
            p: 0.125,
            detectable,
            verdict: "inconclusive".into(),
        }
    }

    /// Embedded, the statistics stand in the row itself, after its own fields and in their
    /// order (the layout the rows had before they shared them), and read back the same.
    #[test]
    fn paired_rows_write_their_statistics_as_their_own_fields() {
        let behaviour = BehaviourRow {
            combination: "weighted-sum".into(),
            setting: "high-curiosity".into(),
            measure: "% homing".into(),
            mean_combination: 51.5,
            mean_tsk: 50.0,
            stats: stats(Some(2.0)),
        };
        let json = serde_json::to_string(&behaviour).unwrap();
        assert_eq!(
            json,
            r#"{"combination":"weighted-sum","setting":"high-curiosity","measure":"% homing","mean_combination":51.5,"mean_tsk":50.0,"difference":1.5,"ci_low":-0.25,"ci_high":3.0,"p":0.125,"detectable":2.0,"verdict":"inconclusive"}"#
        );
        assert_eq!(
            serde_json::from_str::<BehaviourRow>(&json).unwrap(),
            behaviour
        );
        let urgency = UrgencyRow {
            measure: "% success".into(),
            from: 0.0,
            to: 0.1,
            pairs: 3,
            mean_from: 50.0,
            mean_to: 51.5,
            stats: stats(None),
        };
        let json = serde_json::to_string(&urgency).unwrap();
        assert_eq!(
            json,
            r#"{"measure":"% success","from":0.0,"to":0.1,"pairs":3,"mean_from":50.0,"mean_to":51.5,"difference":1.5,"ci_low":-0.25,"ci_high":3.0,"p":0.125,"detectable":null,"verdict":"inconclusive"}"#
        );
        assert_eq!(serde_json::from_str::<UrgencyRow>(&json).unwrap(), urgency);
    }
}
