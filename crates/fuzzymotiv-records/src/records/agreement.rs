//! A replication's agreement by seed count (`agreement.csv` of a study at several base seeds):
//! every hypothesis judged on each base seed's first n seeds, for every n from 2 to the
//! study's seeds, beside its pooled verdict, as `reproduce --replication` judges the paper's
//! claims (`replication_seeds.csv`). The smallest n from which on every base seed's verdict
//! equals the pooled one is the number of seeds the study needs ([`seeds_needed`]).

use serde::{Deserialize, Serialize};

/// One hypothesis judged on one base seed's first `seeds` seeds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AgreementRow {
    /// Seeds per base seed: the first `seeds` of each.
    pub seeds: usize,
    /// The hypothesis's id.
    pub id: String,
    /// The base seed.
    pub base_seed: u64,
    /// The effect on those seeds (as `claims.csv`'s).
    pub effect: f64,
    /// The p-value.
    pub p: f64,
    /// The p-value after Holm's adjustment when the analysis adjusts the hypotheses (`p`
    /// otherwise).
    pub p_adjusted: f64,
    /// The minimum detectable difference.
    pub mdd: Option<f64>,
    /// The verdict by the study's rule.
    pub verdict: String,
    /// The pooled verdict (every seed of every base seed).
    pub pooled: String,
    /// Whether `verdict` is the pooled verdict.
    pub agrees: bool,
}

/// Per number of seeds (ascending), whether every row at that number agrees.
pub fn agree_by_seeds(rows: &[AgreementRow]) -> Vec<(usize, bool)> {
    let mut out: Vec<(usize, bool)> = Vec::new();
    for r in rows {
        match out.iter_mut().find(|(n, _)| *n == r.seeds) {
            Some((_, all)) => *all &= r.agrees,
            None => out.push((r.seeds, r.agrees)),
        }
    }
    out.sort_by_key(|&(n, _)| n);
    out
}

/// The smallest number of seeds from which on (at every larger number too) everything
/// agrees; none when the last number does not, or nothing was tried.
pub fn seeds_needed(agree: &[(usize, bool)]) -> Option<usize> {
    match agree.iter().rposition(|&(_, a)| !a) {
        None => agree.first().map(|&(n, _)| n),
        Some(last) => agree.get(last + 1).map(|&(n, _)| n),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(seeds: usize, agrees: bool) -> AgreementRow {
        AgreementRow {
            seeds,
            id: "h".into(),
            base_seed: 1,
            effect: 0.0,
            p: 1.0,
            p_adjusted: 1.0,
            mdd: None,
            verdict: "holds".into(),
            pooled: "holds".into(),
            agrees,
        }
    }

    /// A number of seeds agrees only when every hypothesis at every base seed does, and the
    /// seeds needed are where agreement starts and lasts.
    #[test]
    fn one_disagreeing_row_makes_its_seed_count_disagree_and_moves_the_seeds_needed_on() {
        let rows = [row(2, true), row(2, false), row(3, true), row(3, true)];
        assert_eq!(agree_by_seeds(&rows), vec![(2, false), (3, true)]);
        assert_eq!(seeds_needed(&agree_by_seeds(&rows)), Some(3));
        assert_eq!(seeds_needed(&[(2, true), (3, true)]), Some(2));
        assert_eq!(seeds_needed(&[(2, true), (3, false)]), None);
        assert_eq!(seeds_needed(&[]), None);
    }
}
