//! A replication's agreement by seed count, pure: with several base seeds, every hypothesis
//! judged on each base seed's first n seeds (n from 2 to the study's seeds) by the study's
//! analysis ([`analysis::claims`] over those seeds alone: its resampling seeded by the base
//! seed's first seed, Holm over the hypotheses when declared), beside its pooled verdict. The
//! rows of `agreement.csv`; `reproduce --replication` judges the paper's claims the same way
//! (`replication_seeds.csv`).

use crate::files::error::CliError;
use crate::records::agreement::AgreementRow;
use crate::records::hypotheses::{AnalysisRecord, ClaimRow, Hypothesis, POOLED, PerSeedRow};
use crate::study::analysis;

/// The agreement rows of a study of `seeds` seeds per base seed (none with one base seed), in
/// seed count, base seed and hypothesis order; `claims` its results (the pooled verdicts).
pub fn agreement(
    hypotheses: &[Hypothesis],
    rows: &[PerSeedRow],
    base_seeds: &[u64],
    seeds: usize,
    level: &dyn Fn(&str) -> f64,
    a: &AnalysisRecord,
    claims: &[ClaimRow],
) -> Result<Vec<AgreementRow>, CliError> {
    if base_seeds.len() < 2 {
        return Ok(Vec::new());
    }
    let pooled = |id: &str| {
        (claims.iter())
            .find(|c| c.scope == POOLED && c.id == id)
            .map_or_else(String::new, |c| c.verdict.clone())
    };
    let mut out = Vec::new();
    for n in 2..=seeds {
        for &b in base_seeds {
            let first: Vec<PerSeedRow> = (rows.iter())
                .filter(|r| r.base_seed == b && r.replicate < n)
                .cloned()
                .collect();
            for c in analysis::claims(hypotheses, &first, &[b], level, a)? {
                let pooled = pooled(&c.id);
                out.push(AgreementRow {
                    seeds: n,
                    agrees: c.verdict == pooled,
                    id: c.id,
                    base_seed: b,
                    effect: c.effect,
                    p: c.p,
                    p_adjusted: c.p_adjusted,
                    mdd: c.mdd,
                    verdict: c.verdict,
                    pooled,
                });
            }
        }
    }
    Ok(out)
}
