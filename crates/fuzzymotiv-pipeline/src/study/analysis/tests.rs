use super::*;
use crate::records::hypotheses::Measure;

fn analysis(rule: Rule, holm: HolmOver) -> AnalysisRecord {
    AnalysisRecord {
        alpha: 0.05,
        confidence: 0.95,
        power: 0.8,
        rule,
        holm,
    }
}

/// Per-seed rows of arms `lo`, `mid`, `hi` over six seeds of base seed 1: `value(arm, seed)`.
fn rows(value: impl Fn(usize, usize) -> f64) -> Vec<PerSeedRow> {
    let mut out = Vec::new();
    for seed in 0..6 {
        for (k, arm) in ["lo", "mid", "hi"].iter().enumerate() {
            for room in ["", "H"] {
                out.push(PerSeedRow {
                    base_seed: 1,
                    replicate: seed,
                    seed: seed as u64,
                    arm: arm.to_string(),
                    measure: "urgency_pct".into(),
                    room: room.into(),
                    value: value(k, seed),
                });
            }
        }
    }
    out
}

fn compare_h(expect: Direction) -> Hypothesis {
    Hypothesis::Compare {
        id: "c".into(),
        measure: Measure::Term("urgency".into()),
        a: "hi".into(),
        b: "lo".into(),
        expect,
    }
}

fn level(arm: &str) -> f64 {
    match arm {
        "lo" => 0.1,
        "mid" => 0.3,
        _ => 0.5,
    }
}

#[test]
fn a_comparisons_verdict_is_the_projects_rule_on_its_paired_test() {
    let rows = rows(|k, seed| 10.0 * k as f64 + (seed % 3) as f64);
    let a = analysis(Rule::Power, HolmOver::None);
    for expect in [Direction::Higher, Direction::Lower] {
        let h = compare_h(expect);
        let got = claims(std::slice::from_ref(&h), &rows, &[1], &level, &a).unwrap();
        let hi = values(&rows, "hi", "urgency_pct", "", POOLED);
        let lo = values(&rows, "lo", "urgency_pct", "", POOLED);
        let c = statistics::paired(&hi, &lo, &settings(&a, &rows, POOLED)).unwrap();
        let want = c.verdict_with_power(match expect {
            Direction::Higher => Expect::Higher,
            Direction::Lower => Expect::Lower,
        });
        assert_eq!(got[0].verdict, want.label());
        assert_eq!((got[0].effect, got[0].p), (c.difference, c.p));
    }
}

#[test]
fn a_trend_is_the_per_seed_slope_against_the_levels() {
    // 50 per unit of level on every seed, with seed noise that does not depend on the arm.
    let rows = rows(|k, seed| 5.0 * k as f64 + seed as f64);
    let h = Hypothesis::Trend {
        id: "t".into(),
        measure: Measure::Term("urgency".into()),
        arms: vec!["lo".into(), "mid".into(), "hi".into()],
        expect: Direction::Higher,
    };
    let a = analysis(Rule::P, HolmOver::None);
    let got = claims(std::slice::from_ref(&h), &rows, &[1], &level, &a).unwrap();
    assert!((got[0].effect - 25.0).abs() < 1e-9, "{}", got[0].effect);
    assert_eq!(got[0].p, 1.0 / 32.0); // six seeds all the same sign: 2/64
    assert_eq!(got[0].verdict, "holds");
    let down = Hypothesis::Trend {
        id: "t".into(),
        measure: Measure::Term("urgency".into()),
        arms: vec!["lo".into(), "mid".into(), "hi".into()],
        expect: Direction::Lower,
    };
    let got = claims(&[down], &rows, &[1], &level, &a).unwrap();
    assert_eq!(got[0].verdict, "opposite");
}

#[test]
fn a_level_measure_has_no_trend_exactly_and_the_verdict_of_no_difference() {
    // Every arm the same on each seed (a measure no arm moves, as a tiny study's zeros or a
    // level share): each seed's slope is 0, not the rounding error of the seed's mean.
    let rows = rows(|_, seed| 0.1 + seed as f64 / 3.0);
    assert_eq!(slope(&[0.1, 0.3, 0.5], &[0.7; 3]), 0.0);
    let trend = Hypothesis::Trend {
        id: "t".into(),
        measure: Measure::Term("urgency".into()),
        arms: vec!["lo".into(), "mid".into(), "hi".into()],
        expect: Direction::Lower,
    };
    let a = analysis(Rule::Power, HolmOver::None);
    let hs = [trend, compare_h(Direction::Higher)];
    let got = claims(&hs, &rows, &[1], &level, &a).unwrap();
    assert_eq!(
        (got[0].effect, got[0].ci_low, got[0].ci_high),
        (0.0, 0.0, 0.0)
    );
    assert_eq!(
        got[0].verdict, got[1].verdict,
        "a trend and a comparison of level data"
    );
}

#[test]
fn a_range_holds_inside_is_opposite_outside_and_undecided_across_a_bound() {
    let rows = rows(|k, seed| 10.0 * k as f64 + seed as f64 * 0.1);
    let a = analysis(Rule::P, HolmOver::None);
    let range = |min: f64, max: f64| Hypothesis::Range {
        id: "r".into(),
        measure: Measure::Term("urgency".into()),
        arm: "mid".into(),
        min,
        max,
    };
    // mid: 10.0 … 10.5
    for ((min, max), verdict) in [
        ((5.0, 15.0), "holds"),
        ((20.0, 30.0), "opposite"),
        ((0.0, 5.0), "opposite"),
        ((10.2, 30.0), "not significant"),
    ] {
        let got = claims(&[range(min, max)], &rows, &[1], &level, &a).unwrap();
        assert_eq!(got[0].verdict, verdict, "[{min}, {max}]");
        assert!((got[0].effect - 10.25).abs() < 1e-9);
    }
}

#[test]
fn holm_over_hypotheses_adjusts_the_claims_and_over_rooms_the_rooms() {
    let rows = rows(|k, seed| 10.0 * k as f64 + (seed % 3) as f64);
    let hs = [compare_h(Direction::Higher), {
        let mut h = compare_h(Direction::Lower);
        if let Hypothesis::Compare { id, .. } = &mut h {
            *id = "d".into();
        }
        h
    }];
    let over = |holm| {
        let a = analysis(Rule::P, holm);
        let c = claims(&hs, &rows, &[1], &level, &a).unwrap();
        let r = room_results(&hs, &rows, &[1], &level, &a).unwrap();
        (c, r)
    };
    let (c, r) = over(HolmOver::Hypotheses);
    assert_eq!(c[0].p_adjusted, statistics::holm(&[c[0].p, c[1].p])[0]);
    assert!(c[0].p_adjusted > c[0].p);
    assert_eq!(r[0].p_adjusted, r[0].p);
    let (c, _) = over(HolmOver::None);
    assert_eq!(c[0].p_adjusted, c[0].p);
}

#[test]
fn several_base_seeds_give_a_pooled_scope_and_one_per_base_seed() {
    let mut rows = rows(|k, seed| 10.0 * k as f64 + seed as f64);
    let more: Vec<PerSeedRow> = rows
        .iter()
        .map(|r| PerSeedRow {
            base_seed: 2,
            ..r.clone()
        })
        .collect();
    rows.extend(more);
    let a = analysis(Rule::Power, HolmOver::Hypotheses);
    let got = claims(&[compare_h(Direction::Higher)], &rows, &[1, 2], &level, &a).unwrap();
    let scopes: Vec<(&str, usize)> = got.iter().map(|c| (c.scope.as_str(), c.seeds)).collect();
    assert_eq!(scopes, [("pooled", 12), ("base=1", 6), ("base=2", 6)]);
}

#[test]
fn a_trend_over_arms_of_unequal_seed_counts_is_an_error_not_a_panic() {
    let s = settings(&analysis(Rule::P, HolmOver::None), &[], POOLED);
    let got = trend(
        &[0.1, 0.3, 0.5],
        &[vec![1.0, 2.0], vec![1.0], vec![3.0, 4.0]],
        Direction::Higher,
        &s,
    );
    assert_eq!(got, Err(StatsError::Lengths { a: 2, b: 1 }));
}

/// A scope's tests resample seeded by the scope's first seed, as the paper's claims are: over
/// twenty seeds (too many sign patterns to enumerate) the p-value and the interval are those of
/// `statistics::paired` seeded by the first seed (11 at base seed 11), not by 0.
#[test]
fn a_scopes_resampling_is_seeded_by_its_first_seed() {
    let mut rows = Vec::new();
    for i in 0..20u64 {
        for (arm, value) in [("hi", 1.0 + (i % 7) as f64 - 2.5), ("lo", 0.0)] {
            rows.push(PerSeedRow {
                base_seed: 11,
                replicate: i as usize,
                seed: if i == 0 { 11 } else { 1000 + i },
                arm: arm.into(),
                measure: "urgency_pct".into(),
                room: String::new(),
                value,
            });
        }
    }
    let a = analysis(Rule::P, HolmOver::None);
    let got = claims(&[compare_h(Direction::Higher)], &rows, &[11], &level, &a).unwrap();
    let hi = values(&rows, "hi", "urgency_pct", "", POOLED);
    let lo = values(&rows, "lo", "urgency_pct", "", POOLED);
    let seeded = |seed| {
        let s = Settings {
            seed,
            ..settings(&a, &[], POOLED)
        };
        statistics::paired(&hi, &lo, &s).unwrap()
    };
    let (first, zero) = (seeded(11), seeded(0));
    assert!(
        first.p != zero.p || first.ci_low != zero.ci_low,
        "the seed matters here"
    );
    assert_eq!(settings(&a, &rows, POOLED).seed, 11);
    assert_eq!(
        (got[0].p, got[0].ci_low, got[0].ci_high),
        (first.p, first.ci_low, first.ci_high)
    );
}

/// A difference of differences is the paired test of the per-seed (a − b) − (c − d): here
/// hi − mid exceeds mid − lo by 10 on every seed (the seed's noise cancels), so the effect is
/// 10 and p the smallest six seeds give; the other way it is opposite; and its numbers are
/// `statistics::paired` of the two differences, as `reproduce --combination` tests them.
#[test]
fn a_difference_is_the_paired_test_of_two_paired_differences() {
    let rows = rows(|k, seed| 5.0 * (k * k) as f64 + seed as f64 * 1.5);
    let h = |expect| Hypothesis::Difference {
        id: "d".into(),
        measure: Measure::Term("urgency".into()),
        a: "hi".into(),
        b: "mid".into(),
        versus_a: "mid".into(),
        versus_b: "lo".into(),
        expect,
    };
    let a = analysis(Rule::P, HolmOver::None);
    let got = claims(&[h(Direction::Higher)], &rows, &[1], &level, &a).unwrap();
    assert!((got[0].effect - 10.0).abs() < 1e-9, "{}", got[0].effect);
    assert_eq!(got[0].p, 1.0 / 32.0);
    assert_eq!(
        (got[0].verdict.as_str(), got[0].kind.as_str()),
        ("holds", "difference")
    );
    assert_eq!(got[0].arms, "hi;mid;mid;lo");
    let of = |arm| values(&rows, arm, "urgency_pct", "", POOLED);
    let minus =
        |x: Vec<f64>, y: Vec<f64>| -> Vec<f64> { x.iter().zip(&y).map(|(x, y)| x - y).collect() };
    let c = statistics::paired(
        &minus(of("hi"), of("mid")),
        &minus(of("mid"), of("lo")),
        &settings(&a, &rows, POOLED),
    )
    .unwrap();
    assert_eq!(
        (got[0].effect, got[0].ci_low, got[0].p),
        (c.difference, c.ci_low, c.p)
    );
    let got = claims(&[h(Direction::Lower)], &rows, &[1], &level, &a).unwrap();
    assert_eq!(got[0].verdict, "opposite");
    // Per room too: the rooms every one of its four arms has.
    let r = room_results(&[h(Direction::Higher)], &rows, &[1], &level, &a).unwrap();
    assert_eq!(r.len(), 1);
    assert_eq!(r[0].room, "H");
}

/// Arms of unequal seed counts are an error, not a panic.
#[test]
fn a_difference_over_arms_of_unequal_seed_counts_is_an_error() {
    let s = settings(&analysis(Rule::P, HolmOver::None), &[], POOLED);
    let got = difference(
        [&[1.0, 2.0], &[1.0], &[3.0, 4.0], &[0.0, 0.0]],
        Direction::Higher,
        &s,
    );
    assert_eq!(got, Err(StatsError::Lengths { a: 2, b: 1 }));
}

/// Each arm's measures over each scope: the seeds' mean and sample sd, per room and over the
/// rooms, in the order per_seed.csv first has them.
#[test]
fn each_arms_measures_are_the_mean_and_sd_of_its_seeds() {
    let rows = rows(|k, seed| 10.0 * k as f64 + seed as f64);
    let got = arm_measures(&rows, &["lo", "hi"], &[1]);
    assert_eq!(got.len(), 2 * 2, "{got:?}");
    let hi = got
        .iter()
        .find(|m| m.arm == "hi" && m.room.is_empty())
        .unwrap();
    assert_eq!((hi.seeds, hi.mean), (6, 22.5));
    let v: Vec<f64> = (0..6).map(|s| 20.0 + s as f64).collect();
    assert_eq!(hi.sd, statistics::sample_sd(&v));
    assert_eq!(hi.measure, "urgency_pct");
}
