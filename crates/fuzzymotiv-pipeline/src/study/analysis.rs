//! A study's analysis, pure: its per-seed values ([`PerSeedRow`]) in, its results out
//! ([`ClaimRow`] per hypothesis and scope, [`RoomResultRow`] per room), by the statistics of
//! [`fuzzymotiv::statistics`] and the rule the study declares. Verdicts are computed from the
//! values, never looked up.
//!
//! - compare: the paired test of the arms' per-seed values ([`statistics::paired`]);
//! - difference: the paired test of a − b against versus_a − versus_b, per seed (a difference
//!   of two paired differences; `reproduce --combination`'s claim differences);
//! - trend: per seed, the least-squares slope of the value against the arms' levels, tested
//!   against 0 (the sign-flip test of the slopes);
//! - range: the arm's mean and its interval; it holds when the mean is significantly above
//!   `min` and significantly below `max` (two paired tests against the bounds, p the larger),
//!   and is opposite when it is significantly outside;
//! - rising: the paired test of the last generation's mean F against the first's.
//!
//! The verdict of a test with effect margin m (the difference, the slope, or for a range the
//! distance to the nearer bound) and p-value p: inconclusive under the power rule when
//! |m| < the minimum detectable difference, else [`Verdict::of`] at α with p Holm-adjusted when
//! the analysis says so.

use fuzzymotiv::statistics::{self, Comparison, Expect, Settings, StatsError, Verdict};

use crate::files::error::CliError;
use crate::records::hypotheses::{
    AnalysisRecord, ArmMeasureRow, ClaimRow, Direction, FIRST_MEAN_F, HolmOver, Hypothesis,
    LAST_MEAN_F, POOLED, PerSeedRow, RoomResultRow, Rule, base_scope,
};

/// A test's outcome before its verdict.
#[derive(Debug, Clone, PartialEq)]
pub struct Tested {
    /// The effect reported.
    pub effect: f64,
    /// Its interval.
    pub ci: (f64, f64),
    /// The p-value.
    pub p: f64,
    /// The minimum detectable difference.
    pub mdd: Option<f64>,
    /// The signed margin the verdict reads (positive: the hypothesis's way).
    pub margin: f64,
    /// The seeds tested.
    pub seeds: usize,
}

impl Tested {
    fn of(c: &Comparison, expect: Direction, seeds: usize) -> Tested {
        Tested {
            effect: c.difference,
            ci: (c.ci_low, c.ci_high),
            p: c.p,
            mdd: c.mdd,
            margin: match expect {
                Direction::Higher => c.difference,
                Direction::Lower => -c.difference,
            },
            seeds,
        }
    }

    /// The verdict at α with p-value `p` (adjusted or not) by `rule`.
    pub fn verdict(&self, p: f64, alpha: f64, rule: Rule) -> Verdict {
        if rule == Rule::Power && self.mdd.is_some_and(|m| self.margin.abs() < m) {
            return Verdict::Inconclusive;
        }
        Verdict::of(self.margin, p, Expect::Higher, alpha)
    }
}

/// The statistics settings of an analysis over `scope`'s seeds: its resampling seeded by the
/// scope's first seed (plan order), as the paper's study seeds its claims' by its first seed,
/// so that a study of the paper's settings gives its numbers.
pub fn settings(a: &AnalysisRecord, rows: &[PerSeedRow], scope: &str) -> Settings {
    let first = rows
        .iter()
        .find(|r| scope == POOLED || base_scope(r.base_seed) == scope);
    Settings {
        alpha: a.alpha,
        confidence: a.confidence,
        power: a.power,
        seed: first.map_or(0, |r| r.seed),
        ..Settings::default()
    }
}

/// The paired test of `a` against `b`, `expect` the hypothesis's way.
pub fn compare(
    a: &[f64],
    b: &[f64],
    expect: Direction,
    s: &Settings,
) -> Result<Tested, StatsError> {
    Ok(Tested::of(&statistics::paired(a, b, s)?, expect, a.len()))
}

/// A difference of differences: the paired test of the per-seed `a` − `b` against `c` − `d`
/// (all four over the same seeds).
pub fn difference(
    [a, b, c, d]: [&[f64]; 4],
    expect: Direction,
    s: &Settings,
) -> Result<Tested, StatsError> {
    let minus = |x: &[f64], y: &[f64]| -> Result<Vec<f64>, StatsError> {
        if x.len() != y.len() {
            return Err(StatsError::Lengths {
                a: x.len(),
                b: y.len(),
            });
        }
        Ok(x.iter().zip(y).map(|(x, y)| x - y).collect())
    };
    compare(&minus(a, b)?, &minus(c, d)?, expect, s)
}

/// The least-squares slope of `ys` against `xs`; exactly 0 when every y is the same (the
/// formula would give the rounding error of their mean: a tiny slope of either sign, so a
/// level measure would read as an undecided trend instead of none).
pub fn slope(xs: &[f64], ys: &[f64]) -> f64 {
    if ys.iter().all(|&y| y == ys[0]) {
        return 0.0;
    }
    let (mx, my) = (statistics::mean(xs), statistics::mean(ys));
    let sxy: f64 = xs.iter().zip(ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// A trend: `values[k]` the per-seed values of the arm at level `levels[k]`; the sign-flip
/// test of the per-seed slopes against 0.
pub fn trend(
    levels: &[f64],
    values: &[Vec<f64>],
    expect: Direction,
    s: &Settings,
) -> Result<Tested, StatsError> {
    let n = values.first().map_or(0, Vec::len);
    if let Some(other) = values.iter().find(|v| v.len() != n) {
        return Err(StatsError::Lengths {
            a: n,
            b: other.len(),
        });
    }
    let slopes: Vec<f64> = (0..n)
        .map(|i| {
            let ys: Vec<f64> = values.iter().map(|v| v[i]).collect();
            slope(levels, &ys)
        })
        .collect();
    compare(&slopes, &vec![0.0; n], expect, s)
}

/// A range: the mean of `values` between `min` and `max`.
pub fn range(values: &[f64], min: f64, max: f64, s: &Settings) -> Result<Tested, StatsError> {
    let n = values.len();
    let mean = statistics::paired(values, &vec![0.0; n], s)?;
    let low = statistics::paired(values, &vec![min; n], s)?;
    let high = statistics::paired(values, &vec![max; n], s)?;
    let (above, below) = (mean.difference - min, max - mean.difference);
    let (margin, p) = if above < 0.0 {
        (above, low.p)
    } else if below < 0.0 {
        (below, high.p)
    } else {
        (above.min(below), low.p.max(high.p))
    };
    Ok(Tested {
        effect: mean.difference,
        ci: (mean.ci_low, mean.ci_high),
        p,
        mdd: mean.mdd,
        margin,
        seeds: n,
    })
}

/// The values of one measure of one arm in one room (empty: the mean over the rooms) over the
/// seeds of a scope, in plan order.
pub fn values(rows: &[PerSeedRow], arm: &str, measure: &str, room: &str, scope: &str) -> Vec<f64> {
    rows.iter()
        .filter(|r| r.arm == arm && r.measure == measure && r.room == room)
        .filter(|r| scope == POOLED || base_scope(r.base_seed) == scope)
        .map(|r| r.value)
        .collect()
}

/// Hypothesis `h` tested in `room` over `scope`'s seeds (`levels`: each arm's level).
pub fn test(
    h: &Hypothesis,
    rows: &[PerSeedRow],
    room: &str,
    scope: &str,
    level: &dyn Fn(&str) -> f64,
    s: &Settings,
) -> Result<Tested, StatsError> {
    let column = h.measure_column();
    let of = |arm: &str| values(rows, arm, &column, room, scope);
    match h {
        Hypothesis::Compare { a, b, expect, .. } => compare(&of(a), &of(b), *expect, s),
        Hypothesis::Difference {
            a,
            b,
            versus_a,
            versus_b,
            expect,
            ..
        } => {
            let (a, b, c, d) = (of(a), of(b), of(versus_a), of(versus_b));
            difference([&a, &b, &c, &d], *expect, s)
        }
        Hypothesis::Trend { arms, expect, .. } => {
            let levels: Vec<f64> = arms.iter().map(|a| level(a)).collect();
            let ys: Vec<Vec<f64>> = arms.iter().map(|a| of(a)).collect();
            trend(&levels, &ys, *expect, s)
        }
        Hypothesis::Range { arm, min, max, .. } => range(&of(arm), *min, *max, s),
        Hypothesis::Rising { arm, .. } => {
            let last = values(rows, arm, LAST_MEAN_F, room, scope);
            let first = values(rows, arm, FIRST_MEAN_F, room, scope);
            compare(&last, &first, Direction::Higher, s)
        }
    }
}

/// The scopes of a study's results: pooled, then each base seed when there are several.
pub fn scopes(base_seeds: &[u64]) -> Vec<String> {
    let mut out = vec![POOLED.to_string()];
    if base_seeds.len() > 1 {
        out.extend(base_seeds.iter().map(|&b| base_scope(b)));
    }
    out
}

fn stats_err(id: &str, e: StatsError) -> CliError {
    CliError::input(format!("hypothesis `{id}`: {e}"))
}

/// Every hypothesis judged over every scope (`claims.csv`, in scope then hypothesis order).
pub fn claims(
    hypotheses: &[Hypothesis],
    rows: &[PerSeedRow],
    base_seeds: &[u64],
    level: &dyn Fn(&str) -> f64,
    analysis: &AnalysisRecord,
) -> Result<Vec<ClaimRow>, CliError> {
    let mut out = Vec::new();
    for scope in scopes(base_seeds) {
        let s = settings(analysis, rows, &scope);
        let tested: Vec<Tested> = (hypotheses.iter())
            .map(|h| test(h, rows, "", &scope, level, &s).map_err(|e| stats_err(h.id(), e)))
            .collect::<Result<_, _>>()?;
        let p: Vec<f64> = tested.iter().map(|t| t.p).collect();
        let adjusted = match analysis.holm {
            HolmOver::Hypotheses => statistics::holm(&p),
            _ => p,
        };
        for ((h, t), p_adjusted) in hypotheses.iter().zip(&tested).zip(adjusted) {
            out.push(ClaimRow {
                id: h.id().to_string(),
                kind: h.kind().to_string(),
                sentence: h.sentence(),
                measure: h.measure_column(),
                arms: h.arms().join(";"),
                expect: h.expect_label().to_string(),
                scope: scope.clone(),
                seeds: t.seeds,
                effect: t.effect,
                ci_low: t.ci.0,
                ci_high: t.ci.1,
                p: t.p,
                p_adjusted,
                mdd: t.mdd,
                verdict: t
                    .verdict(p_adjusted, analysis.alpha, analysis.rule)
                    .label()
                    .into(),
            });
        }
    }
    Ok(out)
}

/// The rooms hypothesis `h` can be judged in: those of its first arm (in their order) that
/// every arm of it has values in.
pub fn rooms_of(h: &Hypothesis, rows: &[PerSeedRow]) -> Vec<String> {
    let column = h.measure_column();
    let arms = h.arms();
    let has = |arm: &str, room: &str| {
        (rows.iter()).any(|r| r.arm == arm && r.measure == column && r.room == room)
    };
    let mut out: Vec<String> = Vec::new();
    for r in rows
        .iter()
        .filter(|r| r.arm == arms[0] && r.measure == column)
    {
        if !r.room.is_empty() && !out.contains(&r.room) && arms.iter().all(|a| has(a, &r.room)) {
            out.push(r.room.clone());
        }
    }
    out
}

/// Every hypothesis over a measure judged in each of its rooms ([`rooms_of`]) over every
/// scope (`rooms.csv`).
pub fn room_results(
    hypotheses: &[Hypothesis],
    rows: &[PerSeedRow],
    base_seeds: &[u64],
    level: &dyn Fn(&str) -> f64,
    analysis: &AnalysisRecord,
) -> Result<Vec<RoomResultRow>, CliError> {
    let mut out = Vec::new();
    for scope in scopes(base_seeds) {
        let s = settings(analysis, rows, &scope);
        for h in hypotheses.iter().filter(|h| h.measure().is_some()) {
            let rooms = rooms_of(h, rows);
            let tested: Vec<Tested> = (rooms.iter())
                .map(|r| test(h, rows, r, &scope, level, &s).map_err(|e| stats_err(h.id(), e)))
                .collect::<Result<_, _>>()?;
            let p: Vec<f64> = tested.iter().map(|t| t.p).collect();
            let adjusted = match analysis.holm {
                HolmOver::Rooms => statistics::holm(&p),
                _ => p,
            };
            for ((room, t), p_adjusted) in rooms.iter().zip(&tested).zip(adjusted) {
                out.push(RoomResultRow {
                    id: h.id().to_string(),
                    scope: scope.clone(),
                    room: room.clone(),
                    effect: t.effect,
                    ci_low: t.ci.0,
                    ci_high: t.ci.1,
                    p: t.p,
                    p_adjusted,
                    mdd: t.mdd,
                    verdict: t
                        .verdict(p_adjusted, analysis.alpha, analysis.rule)
                        .label()
                        .into(),
                });
            }
        }
    }
    Ok(out)
}

/// Each arm's value of every measure of `rows` (`per_seed.csv`), over each scope's seeds, in
/// each room and over the rooms (room empty): the seeds, their mean and sample standard
/// deviation (`arms.csv`; the report's "Measures per arm"). What a study without hypotheses
/// (a sweep of arms) reports.
pub fn arm_measures(rows: &[PerSeedRow], arms: &[&str], base_seeds: &[u64]) -> Vec<ArmMeasureRow> {
    let mut out = Vec::new();
    for scope in scopes(base_seeds) {
        for &arm in arms {
            let mut keys: Vec<(&str, &str)> = Vec::new();
            for r in rows.iter().filter(|r| r.arm == arm) {
                if !keys.contains(&(r.measure.as_str(), r.room.as_str())) {
                    keys.push((&r.measure, &r.room));
                }
            }
            for (measure, room) in keys {
                let v = values(rows, arm, measure, room, &scope);
                out.push(ArmMeasureRow {
                    scope: scope.clone(),
                    arm: arm.to_string(),
                    measure: measure.to_string(),
                    room: room.to_string(),
                    seeds: v.len(),
                    mean: statistics::mean(&v),
                    sd: statistics::sample_sd(&v),
                });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests;
