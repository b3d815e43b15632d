//! The search-strength study (`reproduce --search-strength`): the paper's claims, with their
//! statistics over seeds, at several GA populations — one table and one figure, made from
//! each population's [`StudySummary`] only.
//!
//! Within a population the two settings share each seed's streams, so each claim is the
//! study's paired test ([`super::study::claims`]). Across populations the runs are
//! independent (another population draws other random numbers from the same seed), so the
//! low-curiosity exploration of each population is compared with the smallest one's by the
//! unpaired permutation test ([`statistics::unpaired`]).

use std::fmt::Write as _;

use fuzzymotiv::statistics::{self, BOOTSTRAP_RESAMPLES, Settings, mean_interval};

use super::study::{CLAIMS_ALPHA, Variant, seed_means};
use crate::figure::{Fill, Legend, Mark, PanelBox, Stroke, Svg, Text, Ticks, colour};
use crate::tables::p_text;
use fuzzymotiv_records::records::paper_claims::ClaimId;
use fuzzymotiv_records::records::{ClaimRecord, SettingSummary, StudySummary, TableRow};

/// Picks one column of a table row.
type Column = fn(&TableRow) -> Option<f64>;

/// A mean with its interval: (value, low, high).
type Interval = Option<(f64, f64, f64)>;

/// The study's variants: the GA population, everything else the paper's (200 generations).
pub const SEARCH_STRENGTH: [Variant; 4] = [
    pop("pop-30", "ga.population = 30", &["ga.population=30"]),
    pop("pop-60", "ga.population = 60", &["ga.population=60"]),
    pop("pop-100", "ga.population = 100", &["ga.population=100"]),
    pop(
        "pop-200",
        "ga.population = 200 (the paper's)",
        &["ga.population=200"],
    ),
];

const fn pop(name: &'static str, what: &'static str, sets: &'static [&'static str]) -> Variant {
    Variant {
        name,
        what,
        sets,
        first_release_rooms: false,
    }
}

/// Each seed's low-curiosity (second setting's) mean exploration over rooms.
fn low_exploration(study: &StudySummary) -> Option<Vec<f64>> {
    let column: Column = |r| r.exploration_pct;
    seed_means(study.settings.get(1)?, column)
}

/// A setting's mean over seeds of each seed's mean over rooms of `column`.
fn grand(setting: &SettingSummary, column: impl Fn(&TableRow) -> Option<f64>) -> Option<f64> {
    seed_means(setting, column).map(|v| statistics::mean(&v))
}

/// Both settings' means of the measure a claim is about ([`ClaimId::measure`]); none for
/// Fig. 6's checks, whose measure is no column of the tables.
fn claim_means(study: &StudySummary, claim: ClaimId) -> (Option<f64>, Option<f64>) {
    let measure = claim.measure();
    let mean = |k: usize| grand(study.settings.get(k)?, |r: &TableRow| measure.of_row(r));
    (mean(0), mean(1))
}

fn num(v: Option<f64>, d: usize) -> String {
    v.map_or("n/a".into(), |v| format!("{v:.d$}"))
}

/// The provenance line of the whole study.
fn provenance(studies: &[StudySummary]) -> String {
    let first = &studies[0];
    let pops: Vec<String> = studies.iter().map(|s| s.population.to_string()).collect();
    let seeds: Vec<String> = first.seeds.iter().map(u64::to_string).collect();
    format!(
        "fuzzymotiv {} · {} seeds ({}) · GA population {} × {} generations{}",
        first.version,
        first.seeds.len(),
        seeds.join(", "),
        pops.join(", "),
        first.generations,
        if first.quick { " · quick" } else { "" }
    )
}

/// The study's table: per population and claim, both settings' means, the paired difference
/// with its interval, p, verdict and detectable difference; then the low-curiosity
/// exploration per population against the smallest. Returns (Markdown, CSV).
pub fn strength_table(studies: &[StudySummary]) -> (String, String) {
    let mut md = format!(
        "{}\n\nThe paper's claims at each GA population: high − low curiosity, paired by seed \
         (the mean over seeds of each seed's difference of its means over rooms, a 95 % \
         percentile bootstrap interval, a two-sided sign-flip permutation p, the verdict at \
         α = {CLAIMS_ALPHA} and the smallest difference the seeds could detect with 80 % \
         power). The verdict follows p, which is exact for the sign-flip test; the percentile \
         interval is a little narrow with few seeds, so it can leave out 0 where p ≥ α (the \
         verdict then says not significant). Each population's tables, per-room claims and \
         trajectories are in `pop-N/`.\n\n\
         | population | claim | high | low | difference [95 % interval] | p | verdict | detectable |\n\
         |---|---|---|---|---|---|---|---|\n",
        provenance(studies)
    );
    let mut csv =
        String::from("population,claim,high,low,difference,ci_low,ci_high,p,verdict,mdd,seeds\n");
    for study in studies {
        for c in &study.claims {
            claim_row(&mut md, &mut csv, study, c);
        }
    }
    exploration_rows(&mut md, &mut csv, studies);
    (md, csv)
}

/// One claim's row in both forms.
fn claim_row(md: &mut String, csv: &mut String, study: &StudySummary, c: &ClaimRecord) {
    let pop = study.population;
    let Some(s) = &c.stats else {
        let verdict = if c.holds { "holds" } else { "fails" };
        let _ = writeln!(
            md,
            "| {pop} | {} | | | {} | | {verdict} | |",
            c.claim, c.evidence
        );
        let _ = writeln!(csv, "{pop},\"{}\",,,,,,,{verdict},,", c.claim);
        return;
    };
    let (high, low) = claim_means(study, c.claim);
    let _ = writeln!(
        md,
        "| {pop} | {} | {} % | {} % | {:+.1} [{:+.1}, {:+.1}] | {} | {} | {} |",
        c.claim,
        num(high, 1),
        num(low, 1),
        s.difference,
        s.ci_low,
        s.ci_high,
        p_text(s.p),
        s.verdict,
        num(s.mdd, 1),
    );
    let _ = writeln!(
        csv,
        "{pop},\"{}\",{},{},{},{},{},{},{},{},{}",
        c.claim,
        num(high, 4),
        num(low, 4),
        s.difference,
        s.ci_low,
        s.ci_high,
        p_text(s.p),
        s.verdict,
        num(s.mdd, 4),
        s.seeds
    );
}

/// Low-curiosity exploration per population, each against the smallest population
/// (unpaired permutation test over seeds: independent runs).
fn exploration_rows(md: &mut String, csv: &mut String, studies: &[StudySummary]) {
    let Some(base) = studies.first().and_then(low_exploration) else {
        return;
    };
    let pop0 = studies[0].population;
    let _ = write!(
        md,
        "\nLow-curiosity exploration (mean over rooms, per seed) at each population against \
         population {pop0}: independent runs, so the unpaired two-sample permutation test and a \
         bootstrap interval of the difference of means.\n\n\
         | population | low-curiosity % exploration [95 % interval] | difference to {pop0} [95 % interval] | p |\n\
         |---|---|---|---|\n"
    );
    let options = Settings {
        alpha: CLAIMS_ALPHA,
        seed: studies[0].seeds.first().copied().unwrap_or(0),
        ..Settings::default()
    };
    for study in studies {
        let Some(low) = low_exploration(study) else {
            continue;
        };
        let (lo, hi) = mean_interval(&low, 0.95, BOOTSTRAP_RESAMPLES, options.seed);
        let m = statistics::mean(&low);
        let pop = study.population;
        let versus = (pop != pop0)
            .then(|| statistics::unpaired(&low, &base, &options).ok())
            .flatten();
        let (cell, p) = versus.as_ref().map_or(("—".into(), "—".into()), |v| {
            (
                format!("{:+.1} [{:+.1}, {:+.1}]", v.difference, v.ci_low, v.ci_high),
                p_text(v.p),
            )
        });
        let _ = writeln!(md, "| {pop} | {m:.1} [{lo:.1}, {hi:.1}] | {cell} | {p} |");
        let claim = format!("low-curiosity exploration vs population {pop0}");
        let _ = match &versus {
            Some(v) => writeln!(
                csv,
                "{pop},\"{claim}\",,{m},{},{},{},{},,{},{}",
                v.difference,
                v.ci_low,
                v.ci_high,
                v.p,
                num(v.mdd, 4),
                low.len()
            ),
            None => writeln!(csv, "{pop},\"{claim}\",,{m},,,,,,,{}", low.len()),
        };
    }
}

/// One panel of the figure: per population a point with a vertical interval.
struct Panel {
    title: String,
    y_label: &'static str,
    /// Per series (name, colour), per population: (value, low, high, verdict colour).
    series: Vec<(String, &'static str, Vec<Interval>)>,
    /// Per population, a mark colour by verdict (comparison panels only).
    verdicts: Vec<Option<&'static str>>,
    zero: bool,
}

const HOLDS: &str = "#2ca02c";
const OPPOSITE: &str = "#d62728";
const NOT_SIGNIFICANT: &str = "#7f7f7f";

fn verdict_colour(verdict: &str) -> &'static str {
    match verdict {
        "holds" => HOLDS,
        "opposite" => OPPOSITE,
        _ => NOT_SIGNIFICANT,
    }
}

/// The comparison panels, one per claim with statistics.
fn claim_panels(studies: &[StudySummary]) -> Vec<Panel> {
    let claims: Vec<&ClaimRecord> = studies[0]
        .claims
        .iter()
        .filter(|c| c.stats.is_some())
        .collect();
    claims
        .iter()
        .map(|claim| {
            let stats: Vec<_> = studies
                .iter()
                .map(|s| s.claims.get(claims_index(s, claim.claim)?)?.stats.clone())
                .collect();
            Panel {
                title: claim.claim.short(),
                y_label: "high − low (points)",
                series: vec![(
                    "difference".into(),
                    "#000",
                    stats
                        .iter()
                        .map(|s| s.as_ref().map(|s| (s.difference, s.ci_low, s.ci_high)))
                        .collect(),
                )],
                verdicts: stats
                    .iter()
                    .map(|s| s.as_ref().map(|s| verdict_colour(&s.verdict)))
                    .collect(),
                zero: true,
            }
        })
        .collect()
}

/// Where a population's study lists `claim`.
fn claims_index(study: &StudySummary, claim: ClaimId) -> Option<usize> {
    study.claims.iter().position(|c| c.claim == claim)
}

/// The exploration panel: both settings' means over seeds with bootstrap intervals.
fn exploration_panel(studies: &[StudySummary]) -> Panel {
    let column: Column = |r| r.exploration_pct;
    let names = ["high curiosity", "low curiosity"];
    let series = (0..2)
        .map(|k| {
            let values = studies
                .iter()
                .map(|s| {
                    let v = seed_means(s.settings.get(k)?, column)?;
                    let seed = s.seeds.first().copied().unwrap_or(0);
                    let (lo, hi) = mean_interval(&v, 0.95, BOOTSTRAP_RESAMPLES, seed);
                    Some((statistics::mean(&v), lo, hi))
                })
                .collect();
            (names[k].to_string(), colour(k), values)
        })
        .collect();
    Panel {
        title: "% exploration per setting".into(),
        y_label: "% exploration",
        series,
        verdicts: vec![None; studies.len()],
        zero: false,
    }
}

const PW: f64 = 270.0;
const PH: f64 = 300.0;
const ML: f64 = 58.0;
const MR: f64 = 14.0;
const MT: f64 = 34.0;
const MB: f64 = 74.0;
const PANEL: PanelBox = PanelBox {
    width: PW,
    height: PH,
    left: ML,
    right: MR,
    bottom: MB,
    top: MT,
};

/// The figure: the exploration of both settings, then each comparison claim's paired
/// difference with its 95 % interval, per population (green holds, red opposite, grey not
/// significant at α).
pub fn strength_svg(studies: &[StudySummary]) -> String {
    let mut panels = vec![exploration_panel(studies)];
    panels.extend(claim_panels(studies));
    let mut s = Svg::new(PW * panels.len() as f64, PH, 12);
    let pops: Vec<usize> = studies.iter().map(|s| s.population).collect();
    for (k, panel) in panels.iter().enumerate() {
        draw_panel(&mut s, panel, &pops, k);
    }
    strength_legend(&mut s, studies.first().map_or(0, |s| s.seeds.len()));
    s.finish()
}

/// The y range of a panel: every interval, and zero for a difference.
fn y_range(panel: &Panel) -> (f64, f64) {
    let points = panel.series.iter().flat_map(|(_, _, v)| v.iter().flatten());
    let (mut lo, mut hi) = points.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
        (lo.min(p.1), hi.max(p.2))
    });
    if panel.zero || !lo.is_finite() {
        lo = lo.min(0.0);
        hi = hi.max(0.0);
    }
    if !(lo.is_finite() && hi.is_finite()) || hi - lo < 1.0 {
        (lo.min(0.0) - 1.0, hi.max(0.0) + 1.0)
    } else {
        let pad = (hi - lo) * 0.05;
        (lo - pad, hi + pad)
    }
}

fn draw_panel(s: &mut Svg, panel: &Panel, pops: &[usize], col: usize) {
    let area = PANEL.area(col, 0);
    let (lo, hi) = y_range(panel);
    let y = area.y_scale(lo, hi);
    let n = pops.len().max(1) as f64;
    let x = |i: usize| area.x0 + (area.x1 - area.x0) * (i as f64 + 0.5) / n;
    area.title(s, 18.0, &panel.title);
    let ticks = Ticks::nice(lo, hi, 5, false);
    let zero = panel.zero.then_some("#000");
    area.y_grid(s, &ticks, y, Text::END, zero);
    area.axes(s);
    let labels: Vec<(f64, String)> = (pops.iter().enumerate())
        .map(|(i, p)| (x(i), p.to_string()))
        .collect();
    area.x_ticks(s, &labels, 17.0, false, Text::MIDDLE);
    let axis_labels = (("GA population", 34.0), (panel.y_label, 40.0));
    area.labels(s, axis_labels.0, axis_labels.1, Text::MIDDLE);
    draw_points(s, panel, pops.len(), &x, &|v| y.at(v));
}

fn draw_points(
    s: &mut Svg,
    panel: &Panel,
    n: usize,
    x: &dyn Fn(usize) -> f64,
    y: &dyn Fn(f64) -> f64,
) {
    let shift = |k: usize| (k as f64 - (panel.series.len() as f64 - 1.0) / 2.0) * 8.0;
    for (k, (_, stroke, values)) in panel.series.iter().enumerate() {
        let pts: Vec<(f64, f64)> = (0..n)
            .filter_map(|i| values.get(i).copied().flatten().map(|v| (i, v)))
            .map(|(i, v)| (x(i) + shift(k), y(v.0)))
            .collect();
        s.polyline(&pts, Stroke::of(stroke).width(1.0).dashed("3 3"), None);
        for (i, v) in values.iter().enumerate() {
            let Some((m, lo, hi)) = *v else { continue };
            let xx = x(i) + shift(k);
            let fill = panel.verdicts.get(i).copied().flatten().unwrap_or(stroke);
            s.line((xx, y(lo)), (xx, y(hi)), Stroke::of(stroke).width(1.5));
            s.circle(
                (xx, y(m)),
                4.5,
                Fill::of(fill).stroked(Stroke::of(stroke)),
                None,
            );
        }
    }
}

/// What the marks mean, under the panels.
fn strength_legend(s: &mut Svg, seeds: usize) {
    let note = format!(
        "mean over {seeds} seeds with its 95 % bootstrap interval; verdicts at α = {CLAIMS_ALPHA} (paired sign-flip test)"
    );
    let legend = Legend::new(vec![
        (Mark::Dot(colour(0)), "high curiosity".into()),
        (Mark::Dot(colour(1)), "low curiosity".into()),
        (Mark::Dot(HOLDS), "holds".into()),
        (Mark::Dot(OPPOSITE), "opposite".into()),
        (
            Mark::Dot(NOT_SIGNIFICANT),
            "not significant or inconclusive".into(),
        ),
    ]);
    let width = legend.width(s);
    legend.flow(s, (ML, f64::INFINITY), PH - 16.0, 16.0);
    s.text((ML + width, PH - 16.0), &note, Text::START);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn variants_set_only_the_population() {
        for (v, p) in SEARCH_STRENGTH.iter().zip([30, 60, 100, 200]) {
            assert_eq!(v.sets, [format!("ga.population={p}").as_str()]);
            assert_eq!(v.name, format!("pop-{p}"));
            assert!(!v.first_release_rooms);
        }
    }
}
