//! Claims at the edge of the default study's power, as the replication found them.
//!
//! `reproduce --replication` ran the default study at base seeds 1 and 11 (twenty paired seeds
//! each) and pooled their forty seeds. No number of seeds up to twenty made both base seeds'
//! verdicts equal the pooled ones; the claims whose pooled effect lies within the difference
//! one twenty-seed study detects (its MDD, 80 % power) are at the edge of that study's power: one
//! base seed can show them and the next not. A study of the same design (the same model,
//! population, generations, no overrides, not `--quick`) with at most as many seeds as were
//! pooled reports those claims "inconclusive", whatever its own p, and says so beside its own
//! statistics, so that its verdicts do not flip with the base seed. Any other study keeps its
//! own verdicts: the replication says nothing of its design.
//!
//! The numbers below are the replication's (`docs/results/replication` in the repository); a
//! test of the CLI's documents keeps them equal to those records.

use fuzzymotiv_records::records::{AtEdgeNote, ClaimRecord};

/// The design the replication measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StudyDesign {
    /// `MODEL_VERSION` of the program that ran it.
    pub model: u32,
    /// GA population.
    pub population: usize,
    /// GA generations.
    pub generations: usize,
    /// Whether `--quick` shortened it.
    pub quick: bool,
    /// Whether `--set` changed its configs.
    pub overrides: bool,
    /// Paired seeds.
    pub seeds: usize,
}

/// A claim the replication found at the edge of one study's power.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeClaim {
    /// The claim, as [`crate::study::claims`] words it.
    pub claim: &'static str,
    /// The pooled effect (high − low, points) over the replication's seeds.
    pub pooled_effect: f64,
    /// The larger of the two base seeds' MDDs: the difference one study detects.
    pub one_study_mdd: f64,
}

/// The replicated design: model 2, population 200, 200 generations, up to 40 pooled seeds.
pub const REPLICATED: StudyDesign = StudyDesign {
    model: 2,
    population: 200,
    generations: 200,
    quick: false,
    overrides: false,
    seeds: 40,
};

/// The replication's base seeds.
pub const REPLICATION_BASE_SEEDS: [u64; 2] = [1, 11];

/// The claims at the edge (`at_edge` in the replication's `replication.csv`).
pub const AT_THE_EDGE: [EdgeClaim; 3] = [
    EdgeClaim {
        claim: "high curiosity explores more than low curiosity",
        pooled_effect: 1.0953846153846167,
        one_study_mdd: 3.51671042777531,
    },
    EdgeClaim {
        claim: "high curiosity uses more battery",
        pooled_effect: 1.9958750000000003,
        one_study_mdd: 3.5067679311576665,
    },
    EdgeClaim {
        claim: "high curiosity recognises rooms better",
        pooled_effect: -5.5,
        one_study_mdd: 23.947020871887947,
    },
];

/// Whether a study of `design` is one the replication speaks for: the replicated design with
/// at most as many seeds as were pooled.
pub fn replicated(design: &StudyDesign) -> bool {
    let same = StudyDesign {
        seeds: REPLICATED.seeds,
        ..*design
    };
    same == REPLICATED && design.seeds <= REPLICATED.seeds
}

/// Marks the claims of a study of `design` that the replication found at the edge of its power:
/// verdict "inconclusive", `holds` false, the study's own verdict and the replication's numbers
/// in [`ClaimRecord::at_edge`]. A study of another design is left as it is.
pub fn mark_at_edge(claims: &mut [ClaimRecord], design: &StudyDesign) {
    if !replicated(design) {
        return;
    }
    for c in claims {
        let Some(edge) = AT_THE_EDGE.iter().find(|e| e.claim == c.claim) else {
            continue;
        };
        let Some(stats) = c.stats.as_mut() else {
            continue;
        };
        let own = std::mem::replace(&mut stats.verdict, "inconclusive".into());
        c.holds = false;
        c.at_edge = Some(AtEdgeNote {
            own_verdict: own,
            pooled_effect: edge.pooled_effect,
            one_study_mdd: edge.one_study_mdd,
            pooled_seeds: REPLICATED.seeds,
            base_seeds: REPLICATION_BASE_SEEDS.to_vec(),
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fuzzymotiv_records::records::ClaimStats;

    fn claim(name: &str, verdict: &str) -> ClaimRecord {
        ClaimRecord {
            claim: name.into(),
            curves: Vec::new(),
            evidence: "high 95.0 % vs low 92.2 %".into(),
            holds: verdict == "holds",
            stats: Some(ClaimStats {
                seeds: 20,
                difference: 2.9,
                ci_low: 1.2,
                ci_high: 4.8,
                p: 0.0054,
                min_p: 2.0 / 2f64.powi(20),
                alpha: 0.05,
                verdict: verdict.into(),
                mdd: Some(2.6),
                rooms: Vec::new(),
            }),
            at_edge: None,
        }
    }

    /// The default design's battery claim is inconclusive whatever its own verdict, which the
    /// note keeps; a claim the replication settled (homing) keeps its verdict.
    #[test]
    fn the_replicated_design_reports_its_edge_claims_inconclusive() {
        let design = StudyDesign {
            seeds: 20,
            ..REPLICATED
        };
        let mut claims = vec![
            claim("high curiosity uses more battery", "holds"),
            claim("high curiosity returns home less (lower % homing)", "holds"),
        ];
        mark_at_edge(&mut claims, &design);
        assert_eq!(claims[0].stats.as_ref().unwrap().verdict, "inconclusive");
        assert!(!claims[0].holds);
        let note = claims[0].at_edge.as_ref().unwrap();
        assert_eq!(note.own_verdict, "holds");
        assert_eq!(note.pooled_seeds, 40);
        assert!(note.pooled_effect.abs() <= note.one_study_mdd);
        assert_eq!(claims[1].stats.as_ref().unwrap().verdict, "holds");
        assert!(claims[1].holds && claims[1].at_edge.is_none());
    }

    /// Another design (smaller, overridden, quick, more seeds than pooled, another model) keeps
    /// its own verdicts.
    #[test]
    fn other_designs_keep_their_own_verdicts() {
        let base = StudyDesign {
            seeds: 20,
            ..REPLICATED
        };
        for design in [
            StudyDesign {
                generations: 20,
                ..base
            },
            StudyDesign {
                population: 50,
                ..base
            },
            StudyDesign {
                overrides: true,
                ..base
            },
            StudyDesign {
                quick: true,
                ..base
            },
            StudyDesign { seeds: 41, ..base },
            StudyDesign { model: 3, ..base },
        ] {
            let mut claims = vec![claim("high curiosity uses more battery", "holds")];
            mark_at_edge(&mut claims, &design);
            assert_eq!(
                claims[0].stats.as_ref().unwrap().verdict,
                "holds",
                "{design:?}"
            );
            assert!(claims[0].holds && claims[0].at_edge.is_none());
        }
        assert!(replicated(&StudyDesign { seeds: 1, ..base }));
    }
}
