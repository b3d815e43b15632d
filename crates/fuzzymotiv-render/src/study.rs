//! The paper's study (docs/model.md §10): its two settings with the paper's tables, the
//! ablation's variants, a setting's runs over seeds with their statistics, and the paper's
//! claims tested on them.

use fuzzymotiv::statistics::{self, Expect, Settings, Verdict, mean_std, quantile};

use crate::svg::{BEST_BAND, FitnessPanel, MEAN_BAND};
use fuzzymotiv_records::records::context::RenderContext;
use fuzzymotiv_records::records::paper_claims::{ClaimId, Direction};
use fuzzymotiv_records::records::{
    ClaimRecord, ClaimStats, CurveStats, Finished, GenerationStat, RoomClaimStats, RoomRow,
    SeedSummary, SettingSummary, TableRow,
};

/// A built-in setting of the study with the paper's table.
pub struct Setting {
    /// Run directory name.
    pub name: &'static str,
    /// Figure/file tag.
    pub tag: &'static str,
    /// Built-in config.
    pub config: &'static str,
    /// Config overrides of this setting (applied before the study's and the user's).
    pub sets: &'static [&'static str],
    /// Built-in rooms (the file's path as configs name it, its text) that the config's `rooms`
    /// choose from; empty: the config's rooms are the built-in names or files it names.
    pub rooms: &'static [(&'static str, &'static str)],
    /// The paper's table: room, average fitness, % exploration, % recognition, % battery;
    /// empty for a setting the paper did not run.
    pub paper: &'static [(&'static str, f64, f64, f64, f64)],
}

/// The paper's two settings (Tables 1 and 2).
pub const SETTINGS: [Setting; 2] = [
    Setting {
        name: "high-curiosity",
        tag: "high_curiosity",
        config: include_str!("../../../configs/high-curiosity.toml"),
        sets: &[],
        rooms: &[],
        paper: &[
            ("H", 0.6421, 93.84, 80.00, 79.19),
            ("T", 0.6686, 91.77, 100.00, 78.45),
            ("L", 0.6507, 97.04, 100.00, 79.58),
            ("square", 0.6699, 99.88, 100.00, 79.56),
            ("rectangle", 0.6377, 95.29, 100.00, 79.88),
        ],
    },
    Setting {
        name: "low-curiosity",
        tag: "low_curiosity",
        config: include_str!("../../../configs/low-curiosity.toml"),
        sets: &[],
        rooms: &[],
        paper: &[
            ("H", 0.2465, 54.66, 20.00, 57.90),
            ("T", 0.2694, 57.84, 0.00, 59.66),
            ("L", 0.2707, 57.93, 0.00, 59.67),
            ("square", 0.3274, 80.63, 100.00, 74.64),
            ("rectangle", 0.267, 57.70, 0.00, 59.60),
        ],
    },
];

/// A variant of the study: the default model, or one modelling choice switched back.
pub struct Variant {
    /// Directory and table name.
    pub name: &'static str,
    /// What it switches back, in words.
    pub what: &'static str,
    /// Config overrides.
    pub sets: &'static [&'static str],
    /// Use the first release's rooms (rooms/first-release/) instead of the paper's.
    pub first_release_rooms: bool,
}

/// The default model: the paper's robot, rooms and home zone.
pub const DEFAULT_MODEL: Variant = Variant {
    name: "default",
    what: "the paper's robot (actions, end at home, escape homing, the paper's rooms)",
    sets: &[],
    first_release_rooms: false,
};

/// The ablation: the default model, then each new modelling choice switched back alone.
pub const ABLATION: [Variant; 5] = [
    DEFAULT_MODEL,
    Variant {
        name: "wheels",
        what: "robot.motion = \"wheels\" (continuous differential drive)",
        sets: &["robot.motion=\"wheels\""],
        first_release_rooms: false,
    },
    Variant {
        name: "no-end-at-home",
        what: "trial.end_at_home = false (every trial runs all T steps)",
        sets: &["trial.end_at_home=false"],
        first_release_rooms: false,
    },
    Variant {
        name: "distance-homing",
        what: "fitness.homing = \"distance\" (no escape condition)",
        sets: &["fitness.homing=\"distance\""],
        first_release_rooms: false,
    },
    Variant {
        name: "first-release-rooms",
        what: "the first release's rooms (rooms/first-release/)",
        sets: &[],
        first_release_rooms: true,
    },
];

/// The first release's five rooms (the files in rooms/first-release/, built into the binary).
pub const FIRST_RELEASE_ROOMS: [(&str, &str); 5] = [
    ("H", include_str!("../../../rooms/first-release/H.toml")),
    ("T", include_str!("../../../rooms/first-release/T.toml")),
    ("L", include_str!("../../../rooms/first-release/L.toml")),
    (
        "square",
        include_str!("../../../rooms/first-release/square.toml"),
    ),
    (
        "rectangle",
        include_str!("../../../rooms/first-release/rectangle.toml"),
    ),
];

/// One setting's runs, one per seed.
pub struct SettingRuns<'a> {
    /// The setting.
    pub setting: &'a Setting,
    /// Its seeds.
    pub seeds: Vec<u64>,
    /// Per seed, the run's setting.
    pub contexts: Vec<RenderContext>,
    /// Per seed, the results.
    pub finished: Vec<Finished>,
}

impl SettingRuns<'_> {
    /// The seed whose mean F over rooms is the median (the lower median for an even count):
    /// the robot the figures show.
    pub fn median(&self) -> usize {
        let score = |k: usize| {
            let rows = &self.finished[k].rows;
            rows.iter().map(|r| r.average_fitness).sum::<f64>() / rows.len().max(1) as f64
        };
        let mut order: Vec<usize> = (0..self.seeds.len()).collect();
        order.sort_by(|&a, &b| score(a).total_cmp(&score(b)).then(a.cmp(&b)));
        order[(order.len() - 1) / 2]
    }

    /// "seed: #1 (seed S)" or "median seed: #03 (seed S) of N": the median seed by its index,
    /// the seed itself beside it.
    pub fn median_label(&self) -> String {
        let m = self.median();
        let (n, seed) = (self.seeds.len(), self.seeds[m]);
        let index = seed_index(m, n);
        if n == 1 {
            format!("seed: #{index} (seed {seed})")
        } else {
            format!("median seed: #{index} (seed {seed}) of {n}")
        }
    }

    /// The run directory of seed `k` (counted from 0), relative to the study:
    /// `SETTING/seed-NN` ([`seed_dir`]).
    pub fn run_dir(&self, k: usize) -> String {
        format!("{}/{}", self.setting.name, seed_dir(k, self.seeds.len()))
    }
}

/// Seed `k` (counted from 0) of `count` by its index: counted from 1 (1 = the base seed) and
/// zero-padded to the width of `count`, e.g. `03` of 10. Derived seeds are 15–16 digit numbers;
/// names and titles use this index, the records keep the seeds.
pub fn seed_index(k: usize, count: usize) -> String {
    let width = count.max(1).to_string().len();
    format!("{:0width$}", k + 1)
}

/// The directory of seed `k` (counted from 0) of `count` in a study: `seed-` and its
/// [`seed_index`], e.g. `seed-03`.
pub fn seed_dir(k: usize, count: usize) -> String {
    format!("seed-{}", seed_index(k, count))
}

/// The table's five columns of a room row.
pub fn metrics(r: &RoomRow) -> [Option<f64>; 5] {
    [
        Some(r.average_fitness),
        Some(r.exploration_pct),
        r.recognition_pct,
        Some(r.battery_pct),
        Some(r.homing_pct),
    ]
}

/// Per room and column, mean and std over seeds (none where a seed has no value).
pub fn room_stats(study: &SettingRuns<'_>, room: usize) -> [Option<(f64, f64)>; 5] {
    std::array::from_fn(|c| {
        let values: Option<Vec<f64>> = study
            .finished
            .iter()
            .map(|f| metrics(&f.rows[room])[c])
            .collect();
        values.map(|v| mean_std(&v))
    })
}

/// The paper's row for `room` in the setting's table (the four metrics), if it has one.
pub fn paper_row(setting: &Setting, room: &str) -> Option<[f64; 4]> {
    setting
        .paper
        .iter()
        .find(|p| p.0 == room)
        .map(|p| [p.1, p.2, p.3, p.4])
}

impl SettingRuns<'_> {
    /// The setting in `summary.json`: the documented fields (rows, first and last generation)
    /// are means over seeds; `std` and `per_seed` give the spread.
    pub fn summary(&self) -> SettingSummary {
        let ctx = &self.contexts[0];
        let rows = &self.finished[0].rows;
        let stats: Vec<_> = (0..rows.len()).map(|i| room_stats(self, i)).collect();
        let table = |std: bool| -> Vec<TableRow> {
            rows.iter()
                .zip(&stats)
                .map(|(r, s)| {
                    // One seed has no spread: its std is none, not 0.
                    let pick = |c: usize| match s[c] {
                        Some((_, sd)) if std => (self.seeds.len() > 1).then_some(sd),
                        stat => stat.map(|(m, _)| m),
                    };
                    TableRow {
                        room: r.room.clone(),
                        average_fitness: pick(0),
                        exploration_pct: pick(1),
                        recognition_pct: pick(2),
                        battery_pct: pick(3),
                        homing_pct: pick(4),
                    }
                })
                .collect()
        };
        let stat = |last: bool| GenerationStat {
            best: generation_stat(self, last, true),
            mean: generation_stat(self, last, false),
        };
        SettingSummary {
            name: self.setting.name.into(),
            motivations: ctx.motivations.clone(),
            rows: table(false),
            std: table(true),
            first_generation: stat(false),
            last_generation: stat(true),
            population: ctx.population,
            generations: ctx.generations,
            median_seed: self.seeds[self.median()],
            per_seed: self.per_seed(),
        }
    }

    /// Per generation, the 25th, 50th and 75th percentiles ([`quantile`]) over seeds of the
    /// population's best F (`best`) or mean F, up to the shortest run's last generation.
    pub fn quartiles_per_generation(&self, best: bool) -> Vec<[f64; 3]> {
        let histories: Vec<_> = self
            .finished
            .iter()
            .map(|f| &f.outcome.evolutions[0].history)
            .collect();
        let generations = histories.iter().map(|h| h.len()).min().unwrap_or(0);
        (0..generations)
            .map(|g| {
                let v: Vec<f64> = histories
                    .iter()
                    .map(|h| {
                        let stats = h[g].stats;
                        if best { stats.max } else { stats.mean }
                    })
                    .collect();
                [quantile(&v, 0.25), quantile(&v, 0.5), quantile(&v, 0.75)]
            })
            .collect()
    }

    /// The setting's panel of the study's fitness figure: per generation the median over seeds
    /// of the best and of the mean F, each with its inter-quartile band over seeds (none for
    /// one seed, whose curves are drawn as they are).
    pub fn fitness_panel(&self, title: &str) -> FitnessPanel {
        let (best, mean) = (
            self.quartiles_per_generation(true),
            self.quartiles_per_generation(false),
        );
        let n = self.seeds.len();
        let median = |q: &[[f64; 3]]| q.iter().map(|v| v[1]).collect::<Vec<_>>();
        let band = |q: &[[f64; 3]]| q.iter().map(|v| (v[0], v[2])).collect::<Vec<_>>();
        if n == 1 {
            return FitnessPanel {
                title: title.to_string(),
                best: (median(&best), "best F".into()),
                mean: (median(&mean), "mean F".into()),
                bands: Vec::new(),
                band_label: String::new(),
            };
        }
        FitnessPanel {
            title: title.to_string(),
            best: (median(&best), format!("median of best F over {n} seeds")),
            mean: (median(&mean), format!("median of mean F over {n} seeds")),
            bands: vec![(band(&best), BEST_BAND), (band(&mean), MEAN_BAND)],
            band_label: "IQR over seeds (25th–75th percentile)".into(),
        }
    }

    fn per_seed(&self) -> Vec<SeedSummary> {
        self.seeds
            .iter()
            .zip(&self.finished)
            .enumerate()
            .map(|(k, (&seed, f))| {
                let h = &f.outcome.evolutions[0].history;
                SeedSummary {
                    seed,
                    run_dir: self.run_dir(k),
                    rows: f.rows.iter().map(TableRow::of).collect(),
                    first_generation: GenerationStat::of(&h[0]),
                    last_generation: GenerationStat::of(&h[h.len() - 1]),
                    confusion: f
                        .outcome
                        .modelling
                        .iter()
                        .map(|a| a.confusion.counts.clone())
                        .collect(),
                }
            })
            .collect()
    }
}

/// Mean of table column `c` (see [`metrics`]) over rooms and seeds; none if a value is missing.
pub fn grand_mean(study: &SettingRuns<'_>, c: usize) -> Option<f64> {
    let values: Option<Vec<f64>> = study
        .finished
        .iter()
        .flat_map(|f| f.rows.iter().map(move |r| metrics(r)[c]))
        .collect();
    values.map(|v| mean_std(&v).0)
}

/// Mean % exploration, % recognition and % battery over rooms and seeds.
pub fn overall(study: &SettingRuns<'_>) -> [Option<f64>; 3] {
    [
        grand_mean(study, 1),
        grand_mean(study, 2),
        grand_mean(study, 3),
    ]
}

/// Mean over seeds of the population's best (`best`) or mean F in the first or the last
/// generation.
pub fn generation_stat(study: &SettingRuns<'_>, last: bool, best: bool) -> f64 {
    let v: Vec<f64> = study
        .finished
        .iter()
        .map(|f| {
            let h = &f.outcome.evolutions[0].history;
            let rec = if last { &h[h.len() - 1] } else { &h[0] };
            if best { rec.stats.max } else { rec.stats.mean }
        })
        .collect();
    mean_std(&v).0
}

/// A column of a seed's table (see [`TableRow`]).
pub type Column = fn(&TableRow) -> Option<f64>;

/// Per seed, the mean over rooms of `column`; none if a value is missing.
pub fn seed_means(
    setting: &SettingSummary,
    column: impl Fn(&TableRow) -> Option<f64>,
) -> Option<Vec<f64>> {
    setting
        .per_seed
        .iter()
        .map(|s| {
            let values: Option<Vec<f64>> = s.rows.iter().map(&column).collect();
            values.map(|v| mean_std(&v).0)
        })
        .collect()
}

/// The mean of `column` over rooms and seeds (as the tables show it); none if a value is
/// missing.
fn grand_mean_of(
    setting: &SettingSummary,
    column: impl Fn(&TableRow) -> Option<f64>,
) -> Option<f64> {
    let values: Option<Vec<f64>> = setting
        .per_seed
        .iter()
        .flat_map(|s| s.rows.iter().map(&column))
        .collect();
    values.map(|v| mean_std(&v).0)
}

/// The significance level of the claims unless told otherwise (`claims --alpha`).
pub const CLAIMS_ALPHA: f64 = 0.05;

/// The stem of the claims files at `alpha` beside a study: `claims` at the study's own
/// [`CLAIMS_ALPHA`], `claims-alpha-A` at another (e.g. `claims-alpha-0.1`, written by
/// `fuzzymotiv claims DIR --alpha 0.1`), so another α never replaces the study's claims.
pub fn claims_stem(alpha: f64) -> String {
    if alpha == CLAIMS_ALPHA {
        "claims".into()
    } else {
        format!("claims-alpha-{alpha}")
    }
}

/// A comparison claim ([`ClaimId::COMPARISONS`]), high against low curiosity on its measure,
/// paired by seed
/// ([`statistics::paired`] on each seed's mean over rooms, resampling seeded by the study's
/// first seed): the verdict at `alpha`, the effect, its interval, p and the minimum detectable
/// difference.
fn compare_claim(settings: &[SettingSummary], claim: ClaimId, alpha: f64) -> ClaimRecord {
    let (hc, lc) = (&settings[0], &settings[1]);
    let measure = claim.measure();
    let column = |r: &TableRow| measure.of_row(r);
    let expect = claim.direction().expect().unwrap_or(Expect::Higher);
    let show = |v: Option<f64>| v.map_or("n/a".to_string(), |v| format!("{v:.1} %"));
    let evidence = format!(
        "high {} vs low {}",
        show(grand_mean_of(hc, column)),
        show(grand_mean_of(lc, column))
    );
    let options = Settings {
        alpha,
        seed: hc.per_seed.first().map_or(0, |s| s.seed),
        ..Settings::default()
    };
    let stats = match (seed_means(hc, column), seed_means(lc, column)) {
        (Some(a), Some(b)) => statistics::paired(&a, &b, &options).ok(),
        _ => None,
    };
    let stats = stats.map(|s| ClaimStats {
        seeds: hc.per_seed.len(),
        difference: s.difference,
        ci_low: s.ci_low,
        ci_high: s.ci_high,
        p: s.p,
        min_p: s.min_p,
        alpha,
        verdict: s.verdict_with_power(expect).label().into(),
        mdd: s.mdd,
        rooms: room_claims(hc, lc, &column, expect, &options),
    });
    ClaimRecord {
        claim,
        holds: stats.as_ref().is_some_and(|s| s.verdict == "holds"),
        evidence,
        stats,
        curves: Vec::new(),
    }
}

/// Per room, the paired comparison of `column` (exploratory): p-values Holm-adjusted over
/// the rooms ([`statistics::holm`]) and the verdict on the adjusted p. Rooms where a value is
/// missing are left out.
fn room_claims(
    hc: &SettingSummary,
    lc: &SettingSummary,
    column: &dyn Fn(&TableRow) -> Option<f64>,
    expect: Expect,
    options: &Settings,
) -> Vec<RoomClaimStats> {
    let values = |s: &SettingSummary, r: usize| -> Option<Vec<f64>> {
        s.per_seed
            .iter()
            .map(|seed| column(seed.rows.get(r)?))
            .collect()
    };
    let rooms = hc.rows.len();
    let tested: Vec<_> = (0..rooms)
        .filter_map(|r| {
            let c = statistics::paired(&values(hc, r)?, &values(lc, r)?, options).ok()?;
            Some((hc.rows[r].room.clone(), c))
        })
        .collect();
    let p: Vec<f64> = tested.iter().map(|(_, c)| c.p).collect();
    tested
        .into_iter()
        .zip(statistics::holm(&p))
        .map(|((room, c), p_holm)| RoomClaimStats {
            room,
            difference: c.difference,
            ci_low: c.ci_low,
            ci_high: c.ci_high,
            p: c.p,
            p_holm,
            verdict: Verdict::of(c.difference, p_holm, expect, options.alpha)
                .label()
                .into(),
        })
        .collect()
}

/// Per seed, the first (or the last) generation's mean F.
fn seed_mean_f(setting: &SettingSummary, last: bool) -> Vec<f64> {
    setting
        .per_seed
        .iter()
        .map(|s| {
            if last {
                s.last_generation.mean
            } else {
                s.first_generation.mean
            }
        })
        .collect()
}

/// The mean over seeds of the first (or the last) generation's mean F.
fn mean_f(setting: &SettingSummary, last: bool) -> f64 {
    mean_std(&seed_mean_f(setting, last)).0
}

pub use fuzzymotiv_records::records::paper_claims::FIRST_F_BAND;

/// The one-sided p of "mean(a) > mean(b)" from the paired two-sided sign-flip test: half the
/// two-sided p when the observed difference is positive (the null distribution is symmetric),
/// else 1 (conservative).
fn one_sided_p(a: &[f64], b: &[f64], options: &Settings) -> Option<(statistics::Comparison, f64)> {
    let c = statistics::paired(a, b, options).ok()?;
    let p = if c.difference > 0.0 { c.p / 2.0 } else { 1.0 };
    Some((c, p))
}

/// Whether the mean of `x` lies inside `band`, over seeds: two one-sided sign-flip tests
/// (mean above the lower bound, mean below the upper; p the larger of the two); "holds" when
/// p < α, "opposite" when the mean lies outside the band and the two-sided test against the
/// nearer bound gives p < α. Returns the mean, its interval, p and the verdict.
fn band_test(
    x: &[f64],
    band: (f64, f64),
    options: &Settings,
) -> Option<(f64, f64, f64, f64, Verdict)> {
    let (lo, hi) = (vec![band.0; x.len()], vec![band.1; x.len()]);
    let (above, p_above) = one_sided_p(x, &lo, options)?;
    let (_, p_below) = one_sided_p(&hi, x, options)?;
    let p = p_above.max(p_below);
    let mean = above.mean_a;
    let outside = if mean < band.0 {
        Some(above.p)
    } else if mean > band.1 {
        statistics::paired(x, &hi, options).ok().map(|c| c.p)
    } else {
        None
    };
    let verdict = if p < options.alpha {
        Verdict::Holds
    } else if outside.is_some_and(|q| q < options.alpha) {
        Verdict::Opposite
    } else {
        Verdict::NotSignificant
    };
    Some((
        mean,
        above.ci_low + band.0,
        above.ci_high + band.0,
        p,
        verdict,
    ))
}

/// One setting's first-generation mean F against [`FIRST_F_BAND`] ([`band_test`]).
fn first_f_stats(setting: &SettingSummary, options: &Settings) -> Option<CurveStats> {
    let x = seed_mean_f(setting, false);
    let (value, ci_low, ci_high, p, verdict) = band_test(&x, FIRST_F_BAND, options)?;
    Some(CurveStats {
        setting: setting.name.clone(),
        seeds: x.len(),
        statistic:
            "first-generation mean F; p: two one-sided sign-flip tests against 0.05 and 0.15".into(),
        value,
        ci_low,
        ci_high,
        p,
        verdict: verdict.label().into(),
        alpha: options.alpha,
    })
}

/// One setting's rise of the mean F, last against first generation, paired by seed.
fn rise_stats(setting: &SettingSummary, options: &Settings) -> Option<CurveStats> {
    let (last, first) = (seed_mean_f(setting, true), seed_mean_f(setting, false));
    let c = statistics::paired(&last, &first, options).ok()?;
    Some(CurveStats {
        setting: setting.name.clone(),
        seeds: last.len(),
        statistic: "last − first generation mean F; p: sign-flip test over seeds".into(),
        value: c.difference,
        ci_low: c.ci_low,
        ci_high: c.ci_high,
        p: c.p,
        verdict: c.verdict(Expect::Higher).label().into(),
        alpha: options.alpha,
    })
}

/// Whether `value` lies in the band of a claim whose direction is a band (inclusive).
fn within(claim: ClaimId, value: f64) -> bool {
    match claim.direction() {
        Direction::Within(lo, hi) => (lo..=hi).contains(&value),
        Direction::Higher | Direction::Lower => false,
    }
}

/// The paper's claims from a study's records (`settings[0]` high curiosity, `settings[1]`
/// low, as in `summary.json`): high vs low curiosity, each tested at level `alpha` (paired
/// over seeds, see `fuzzymotiv::statistics`), and Fig. 6's fitness curves: `holds` on the
/// means over seeds, with each setting's test over seeds in `curves`.
pub fn claims(settings: &[SettingSummary], alpha: f64) -> Vec<ClaimRecord> {
    let (hc, lc) = (&settings[0], &settings[1]);
    let first = [mean_f(hc, false), mean_f(lc, false)];
    let last = [mean_f(hc, true), mean_f(lc, true)];
    let options = Settings {
        alpha,
        seed: hc.per_seed.first().map_or(0, |s| s.seed),
        ..Settings::default()
    };
    let curves = |test: fn(&SettingSummary, &Settings) -> Option<CurveStats>| {
        settings.iter().filter_map(|s| test(s, &options)).collect()
    };
    let mut out: Vec<ClaimRecord> = (ClaimId::COMPARISONS.iter())
        .map(|&claim| compare_claim(settings, claim, alpha))
        .collect();
    out.extend([
        ClaimRecord {
            claim: ClaimId::FirstGenerationF,
            holds: first.iter().all(|f| within(ClaimId::FirstGenerationF, *f)),
            evidence: format!("high {:.3}, low {:.3}", first[0], first[1]),
            stats: None,
            curves: curves(first_f_stats),
        },
        ClaimRecord {
            claim: ClaimId::FitnessRises,
            holds: last[0] > first[0] && last[1] > first[1],
            evidence: format!(
                "high {:.3} → {:.3}, low {:.3} → {:.3}",
                first[0], last[0], first[1], last[1]
            ),
            stats: None,
            curves: curves(rise_stats),
        },
    ]);
    out
}

#[cfg(test)]
mod tests {
    use super::{FIRST_F_BAND, Settings, Verdict, band_test, seed_dir, seed_index};

    /// Seeds are named by their index from 1 (the base seed), zero-padded to the width of the
    /// count, so that the directories of a study sort in seed order.
    #[test]
    fn seed_indices_are_padded_to_the_width_of_the_count() {
        assert_eq!(seed_index(0, 1), "1");
        assert_eq!(seed_index(8, 9), "9");
        assert_eq!(seed_index(2, 10), "03");
        assert_eq!(seed_index(9, 10), "10");
        assert_eq!(seed_index(0, 1000), "0001");
        assert_eq!(seed_dir(2, 10), "seed-03");
        assert_eq!(seed_dir(19, 20), "seed-20");
    }

    /// Fig. 6's "about 0.1" over seeds: five seeds inside the band give the one-sided p 1/32 on
    /// both sides (holds at 0.05); five above it cannot show the opposite (two-sided 1/16), six
    /// can (1/32); a mean inside the band with a seed outside cannot hold.
    #[test]
    fn first_generation_band_is_tested_over_seeds() {
        let o = Settings::default();
        let (mean, lo, hi, p, v) =
            band_test(&[0.1, 0.11, 0.09, 0.1, 0.12], FIRST_F_BAND, &o).unwrap();
        assert!((mean - 0.104).abs() < 1e-12 && lo <= mean && mean <= hi);
        assert_eq!((p, v), (1.0 / 32.0, Verdict::Holds));
        let v5 = band_test(&[0.3; 5], FIRST_F_BAND, &o).unwrap().4;
        assert_eq!(v5, Verdict::NotSignificant);
        let (_, _, _, p6, v6) = band_test(&[0.3; 6], FIRST_F_BAND, &o).unwrap();
        assert_eq!((p6, v6), (1.0, Verdict::Opposite));
        let v = band_test(&[0.1, 0.1, 0.1, 0.1, 0.01], FIRST_F_BAND, &o).unwrap();
        assert_eq!(v.4, Verdict::NotSignificant, "{v:?}");
    }
}
