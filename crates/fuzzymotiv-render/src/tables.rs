//! Tables: the run's per-room table, a study's tables (means ± std with the paper's values,
//! every seed's values), the paper's claims and the ablation, as Markdown, CSV and HTML. They
//! read records only.

use std::fmt::Write as _;

use fuzzymotiv::experiment::Training;
use fuzzymotiv::statistics::{EXACT_LIMIT, PERMUTATION_RESAMPLES};

use crate::figure::esc;
use crate::study::{SettingRuns, Variant, metrics, paper_row, room_stats, seed_index};
use fuzzymotiv_records::records::context::RenderContext;
use fuzzymotiv_records::records::{ClaimRecord, ClaimStats, RoomRow};

/// The per-room table as Markdown: the paper's columns, then, for an experiment that measures
/// more terms, "% missions done" (the share of test runs whose mission was done) and one
/// "% term" column per extra term (its mean over the test runs), by name.
pub fn table_markdown(rows: &[RoomRow]) -> String {
    let extra = extra_columns(rows);
    let mut s = String::from(
        "| room | average fitness | % optimal exploration | % recognition | % battery usage | % homing |",
    );
    let mut rule = String::from("|---|---|---|---|---|---|");
    for name in &extra {
        let _ = write!(s, " {name} |");
        rule.push_str("---|");
    }
    let _ = writeln!(s, "\n{rule}");
    for r in rows {
        let _ = write!(
            s,
            "| {} | {:.3} | {:.1} | {} | {:.1} | {:.1} |",
            r.room,
            r.average_fitness,
            r.exploration_pct,
            r.recognition_pct
                .map_or("n/a".to_string(), |p| format!("{p:.0}")),
            r.battery_pct,
            r.homing_pct
        );
        for cell in extra_cells(r) {
            let _ = write!(s, " {cell} |");
        }
        s.push('\n');
    }
    s
}

/// The headers of the extra columns of the per-room table (none for the paper's model), for
/// `table.md` and the report's table alike.
pub(crate) fn extra_columns(rows: &[RoomRow]) -> Vec<String> {
    let Some(r) = rows.first() else {
        return Vec::new();
    };
    let done = r.mission_done_pct.map(|_| "% missions done".to_string());
    done.into_iter()
        .chain(r.terms_pct.keys().map(|k| format!("% {k}")))
        .collect()
}

/// A row's cells in the extra columns ([`extra_columns`]).
pub(crate) fn extra_cells(r: &RoomRow) -> Vec<String> {
    let done = r.mission_done_pct.map(|p| format!("{p:.0}"));
    done.into_iter()
        .chain(r.terms_pct.values().map(|v| format!("{v:.1}")))
        .collect()
}

/// What the ± of every table means, for its caption: the standard deviation is the sample
/// one ([`fuzzymotiv::statistics::mean_std`], divided by n − 1), and one value has none.
pub const STD_IS_SAMPLE: &str = "std: the sample standard deviation, n − 1; — for one value";

/// `mean ± std` with `d` decimals over `n` values: the std an em dash for one value (no spread
/// to show, where the sample std is undefined).
pub fn mean_std_cell(mean: f64, std: f64, n: usize, d: usize) -> String {
    if n < 2 {
        format!("{mean:.d$} ± —")
    } else {
        format!("{mean:.d$} ± {std:.d$}")
    }
}

/// Where a table came from, as a Markdown line below it: program version, seed, GA size, trial
/// length and training (so a small trial run and a paper-scale one never look alike).
pub fn provenance_line(ctx: &RenderContext) -> String {
    format!(
        "\n{} · seed {} · GA {} robots × {} generations · {} steps per trial · training {}\n",
        fuzzymotiv::provenance(),
        ctx.seed,
        ctx.population,
        ctx.generations,
        ctx.steps,
        match ctx.training {
            Training::AllRooms => "all-rooms",
            Training::PerRoom => "per-room",
        },
    )
}

/// What produced a table: version, seeds, GA size, quick or not.
pub struct Provenance {
    /// The study's seeds.
    pub seeds: Vec<u64>,
    /// GA population.
    pub population: usize,
    /// GA generations.
    pub generations: usize,
    /// Whether `--quick`.
    pub quick: bool,
}

impl Provenance {
    /// The provenance of a study of `seeds` whose first run's setting is `ctx`.
    pub fn new(seeds: &[u64], ctx: &RenderContext, quick: bool) -> Provenance {
        Provenance {
            seeds: seeds.to_vec(),
            population: ctx.population,
            generations: ctx.generations,
            quick,
        }
    }

    /// The provenance as one line.
    pub fn line(&self) -> String {
        let seeds: Vec<String> = self.seeds.iter().map(u64::to_string).collect();
        format!(
            "{} · {} seed{} ({}) · GA {} × {}{}",
            fuzzymotiv::provenance(),
            self.seeds.len(),
            if self.seeds.len() == 1 { "" } else { "s" },
            seeds.join(", "),
            self.population,
            self.generations,
            if self.quick { " · quick" } else { "" }
        )
    }
}

/// The study's table with the paper's values beside the means: (Markdown with a per-seed
/// table below, CSV of mean/std/paper per room, CSV of every seed's rows).
pub fn study_table(study: &SettingRuns<'_>, prov: &Provenance) -> (String, String, String) {
    const DIGITS: [usize; 5] = [4, 1, 0, 1, 1];
    let mut md = format!(
        "{}\n\nMean ± std over seeds ({STD_IS_SAMPLE}); the paper's value in brackets.\n\n| room | average fitness | % optimal exploration | % recognition | % battery usage | % homing |\n|---|---|---|---|---|---|\n",
        prov.line()
    );
    let mut csv = String::from(
        "room,seeds,average_fitness,average_fitness_std,paper_average_fitness,exploration_pct,exploration_pct_std,paper_exploration_pct,recognition_pct,recognition_pct_std,paper_recognition_pct,battery_pct,battery_pct_std,paper_battery_pct,homing_pct,homing_pct_std\n",
    );
    let rows = &study.finished[0].rows;
    let n = study.seeds.len();
    for (i, row) in rows.iter().enumerate() {
        let stats = room_stats(study, i);
        let paper = paper_row(study.setting, &row.room);
        let _ = write!(md, "| {} |", row.room);
        let _ = write!(csv, "{},{}", row.room, study.seeds.len());
        for (c, stat) in stats.iter().enumerate() {
            let p = paper.and_then(|p| p.get(c).copied());
            let d = DIGITS[c];
            let cell = stat.map_or("n/a".to_string(), |(m, s)| mean_std_cell(m, s, n, d));
            let paper_cell = p.map_or(String::new(), |p| {
                format!(" ({p:.prec$})", prec = d.clamp(2, 4))
            });
            let _ = write!(md, " {cell}{paper_cell} |");
            // One seed's std is an empty cell, like a missing value.
            let (m, s) = stat.map_or((String::new(), String::new()), |(m, s)| {
                let s = if n < 2 {
                    String::new()
                } else {
                    format!("{s:.6}")
                };
                (format!("{m:.6}"), s)
            });
            let _ = write!(csv, ",{m},{s}");
            if c < 4 {
                let _ = write!(csv, ",{}", p.map_or(String::new(), |p| p.to_string()));
            }
        }
        md.push('\n');
        csv.push('\n');
    }
    md.push_str("\nPer seed:\n\n| room | seed | average fitness | % optimal exploration | % recognition | % battery usage | % homing |\n|---|---|---|---|---|---|---|\n");
    let mut seeds_csv = String::from(
        "room,seed,average_fitness,exploration_pct,recognition_pct,battery_pct,homing_pct\n",
    );
    for (i, row) in rows.iter().enumerate() {
        for (k, (seed, f)) in study.seeds.iter().zip(&study.finished).enumerate() {
            let values = metrics(&f.rows[i]);
            let index = seed_index(k, n);
            let _ = write!(md, "| {} | #{index} ({seed}) |", row.room);
            let _ = write!(seeds_csv, "{},{seed}", row.room);
            for (c, v) in values.iter().enumerate() {
                let d = DIGITS[c];
                let _ = write!(md, " {} |", v.map_or("n/a".into(), |v| format!("{v:.d$}")));
                let _ = write!(
                    seeds_csv,
                    ",{}",
                    v.map_or(String::new(), |v| format!("{v:.6}"))
                );
            }
            md.push('\n');
            seeds_csv.push('\n');
        }
    }
    (md, csv, seeds_csv)
}

/// "holds" or "fails".
pub fn mark(holds: bool) -> &'static str {
    if holds { "holds" } else { "fails" }
}

/// A claim's verdict: a comparison's ("holds", "opposite", "not significant"), else
/// [`mark`].
pub fn verdict(c: &ClaimRecord) -> &str {
    c.stats.as_ref().map_or(mark(c.holds), |s| &s.verdict)
}

/// The claims' method, and the note on the smallest p-value their seeds can give.
fn claims_method(claims: &[ClaimRecord]) -> String {
    let Some(s) = claims.iter().find_map(|c| c.stats.as_ref()) else {
        return "The paper's claims, on means over rooms and seeds.".into();
    };
    format!(
        "The paper's claims. High against low curiosity: per seed, each setting's mean over \
         rooms; the settings share each seed's random streams, so the design is paired. The \
         effect is the mean over seeds of high − low (points), with a 95 % percentile bootstrap \
         interval (10 000 resamples); p is two-sided, from a sign-flip permutation test over \
         seeds (all 2^n sign patterns up to 16 seeds); a claim holds, or its opposite does, \
         only at p < α = {alpha}. MDD is the smallest difference these seeds would detect with \
         80 % power at α ((z₁₋α/₂ + z₀.₈) · sd/√n of the per-seed differences, a normal \
         approximation). An effect smaller than its MDD is \"inconclusive\", whatever p: the \
         study is at the edge of its power, and a study of as many seeds at another base seed \
         may well give the other verdict (EXPERIMENTS.md: verdicts that replicate). The last \
         two rows check Fig. 6's curves on means over seeds.\n\n\
         Note: {note}",
        alpha = s.alpha,
        note = min_p_note(s),
    )
}

/// The note on the smallest p-value the claims' seeds can give, as the sign-flip test finds it
/// ([`fuzzymotiv::statistics::sign_flip_p`]): up to 2^n = [`EXACT_LIMIT`] sign patterns all are
/// enumerated (smallest p 2/2^n); beyond, p is estimated from [`PERMUTATION_RESAMPLES`]
/// random patterns with the observed one counted once more, so the smallest is 2/(K + 1),
/// above the exact 2/2^n.
fn min_p_note(s: &ClaimStats) -> String {
    let n = s.seeds;
    let reach = if s.min_p < s.alpha {
        format!("below α = {}", s.alpha)
    } else {
        format!(
            "not below α = {}, so no claim can be shown with {n} seeds, whatever its size",
            s.alpha
        )
    };
    let min_p = p_text(s.min_p);
    if n < 64 && 1u64 << n <= EXACT_LIMIT {
        format!(
            "with {n} paired seeds p enumerates all 2^{n} sign patterns: the smallest two-sided \
             p is 2/2^{n} = {min_p} (1/16 for five seeds), {reach}."
        )
    } else {
        format!(
            "with {n} paired seeds (more than {limit}) p is estimated from {k} random sign \
             patterns, the observed one counted once more: the smallest it can give is \
             2/({k} + 1) = {min_p} (the exact floor 2/2^{n} would be {exact}), {reach}.",
            limit = EXACT_LIMIT.trailing_zeros(),
            k = PERMUTATION_RESAMPLES,
            exact = p_text(2.0 / 2f64.powi(n as i32)),
        )
    }
}

/// A p-value as the tables show it: four decimals (`0.0312`), or, below 0.0001, two
/// significant digits in scientific notation (`1.9e-6` for 2/2^20), never `0.0000`.
pub fn p_text(p: f64) -> String {
    if p > 0.0 && p < 1e-4 {
        format!("{p:.1e}")
    } else {
        format!("{p:.4}")
    }
}

/// The statistics cells of a claim (difference with interval, p, MDD), dashes without them.
fn claim_cells(c: &ClaimRecord) -> [String; 3] {
    match &c.stats {
        Some(s) => [
            format!("{:+.1} [{:+.1}, {:+.1}]", s.difference, s.ci_low, s.ci_high),
            p_text(s.p),
            s.mdd.map_or("—".into(), |m| format!("{m:.1}")),
        ],
        None => ["—".into(), "—".into(), "—".into()],
    }
}

/// The claims as (Markdown, CSV): verdict, high − low with its 95 % interval, p, the minimum
/// detectable difference and the means behind them (CSV: Fig. 6's checks on the means with
/// empty cells, then their tests over seeds per setting).
pub fn claims_table(claims: &[ClaimRecord], prov: &Provenance) -> (String, String) {
    let mut md = format!(
        "{}\n\n{}\n\n| claim | verdict | high − low [95 % CI] | p | MDD | evidence |\n|---|---|---|---|---|---|\n",
        prov.line(),
        claims_method(claims)
    );
    let mut csv = String::from("claim,holds,verdict,difference,ci_low,ci_high,p,mdd,evidence\n");
    for c in claims {
        let [diff, p, mdd] = claim_cells(c);
        let _ = writeln!(
            md,
            "| {} | {} | {diff} | {p} | {mdd} | {} |",
            c.claim,
            verdict(c),
            c.evidence
        );
        let num = |v: Option<f64>| v.map_or(String::new(), |v| v.to_string());
        let s = c.stats.as_ref();
        let _ = writeln!(
            csv,
            "\"{}\",{},{},{},{},{},{},{},\"{}\"",
            c.claim,
            c.holds,
            verdict(c),
            num(s.map(|s| s.difference)),
            num(s.map(|s| s.ci_low)),
            num(s.map(|s| s.ci_high)),
            num(s.map(|s| s.p)),
            num(s.and_then(|s| s.mdd)),
            c.evidence
        );
        curve_claims_csv(&mut csv, c);
    }
    md.push_str(&room_claims_md(claims));
    md.push_str(&curve_claims_md(claims));
    (md, csv)
}

/// A Fig. 6 claim's tests over seeds as CSV rows, one per setting (`CLAIM — SETTING`): the
/// `difference` column holds the tested statistic (the first generation's mean F, or its rise),
/// with its interval, p and verdict; `mdd` is empty and `evidence` names the statistic.
fn curve_claims_csv(csv: &mut String, c: &ClaimRecord) {
    for r in &c.curves {
        let _ = writeln!(
            csv,
            "\"{} — {}\",{},{},{},{},{},{},,\"{}\"",
            c.claim,
            r.setting,
            r.verdict == "holds",
            r.verdict,
            r.value,
            r.ci_low,
            r.ci_high,
            r.p,
            r.statistic
        );
    }
}

/// What the Fig. 6 rows' tests are, for claims.md and the report.
const CURVES_METHOD: &str = "Fig. 6 over seeds, per setting (the verdict column above is the check on the means): the first generation's mean F lies in 0.05–0.15 when two one-sided sign-flip tests (mean above 0.05, mean below 0.15; one-sided p = half the two-sided p on the observed side, else 1) both give p < α, p being the larger (\"opposite\": outside the band, with the two-sided test against the nearer bound at p < α); the rise is the last minus the first generation's mean F, paired by seed (two-sided sign-flip test). Intervals: 95 % percentile bootstrap over seeds.";

/// The Fig. 6 checks over seeds as a Markdown table (empty without any).
fn curve_claims_md(claims: &[ClaimRecord]) -> String {
    let mut md = format!(
        "\n{CURVES_METHOD}\n\n| claim | setting | value [95 % CI] | p | verdict |\n|---|---|---|---|---|\n"
    );
    let mut any = false;
    for c in claims {
        for r in &c.curves {
            any = true;
            let _ = writeln!(
                md,
                "| {} | {} | {:.3} [{:.3}, {:.3}] | {} | {} |",
                c.claim,
                r.setting,
                r.value,
                r.ci_low,
                r.ci_high,
                p_text(r.p),
                r.verdict
            );
        }
    }
    if any { md } else { String::new() }
}

/// The per-room comparisons as a Markdown table (empty without any).
fn room_claims_md(claims: &[ClaimRecord]) -> String {
    let mut md = String::from(
        "\nPer room (exploratory: each claim's p-values Holm-adjusted over its rooms, the verdict on the adjusted p):\n\n| claim | room | high − low [95 % CI] | p | Holm p | verdict |\n|---|---|---|---|---|---|\n",
    );
    let mut any = false;
    for c in claims {
        for r in c.stats.iter().flat_map(|s| &s.rooms) {
            any = true;
            let _ = writeln!(
                md,
                "| {} | {} | {:+.1} [{:+.1}, {:+.1}] | {} | {} | {} |",
                c.claim,
                r.room,
                r.difference,
                r.ci_low,
                r.ci_high,
                p_text(r.p),
                p_text(r.p_holm),
                r.verdict
            );
        }
    }
    if any { md } else { String::new() }
}

/// The claims as HTML for the report page: the claims with their statistics, the per-room
/// comparisons (Holm-adjusted) and Fig. 6's checks over seeds.
pub fn claims_html(claims: &[ClaimRecord]) -> String {
    let mut html = String::from(
        "<h2 id=\"claims\">The paper's claims</h2>\n<table><tr><th>claim</th><th>verdict</th><th>high − low [95 % CI]</th><th>p</th><th>MDD</th><th>evidence (means over rooms and seeds)</th></tr>\n",
    );
    for c in claims {
        let [diff, p, mdd] = claim_cells(c);
        let v = verdict(c);
        let _ = writeln!(
            html,
            "<tr><td class=\"left\">{}</td><td class=\"{}\">{v}</td><td>{diff}</td><td>{p}</td><td>{mdd}</td><td>{}</td></tr>",
            esc(&c.claim.sentence()),
            verdict_class(v),
            esc(&c.evidence)
        );
    }
    html.push_str("</table>\n");
    let _ = writeln!(
        html,
        "<p class=\"caption\">{}</p>",
        esc(&claims_method(claims))
    );
    html.push_str(&room_claims_html(claims));
    html.push_str(&curve_claims_html(claims));
    html
}

/// The CSS class of a verdict's cell.
fn verdict_class(v: &str) -> &'static str {
    match v {
        "holds" => "verdict-holds",
        "opposite" | "fails" => "verdict-opposite",
        _ => "verdict-ns",
    }
}

/// The per-room comparisons as an HTML table (empty without any).
fn room_claims_html(claims: &[ClaimRecord]) -> String {
    let mut html = String::from(
        "<h3 id=\"claims-rooms\">Per room</h3>\n<p>Exploratory: each claim tested in every room alone, its p-values Holm-adjusted over the rooms (family-wise error rate α), the verdict on the adjusted p.</p>\n<table><tr><th>claim</th><th>room</th><th>high − low [95 % CI]</th><th>p</th><th>Holm p</th><th>verdict</th></tr>\n",
    );
    let mut any = false;
    for c in claims {
        let rooms = c.stats.iter().flat_map(|s| &s.rooms).collect::<Vec<_>>();
        for (k, r) in rooms.iter().enumerate() {
            any = true;
            let claim = if k == 0 {
                format!(
                    "<td class=\"left\" rowspan=\"{}\">{}</td>",
                    rooms.len(),
                    esc(&c.claim.sentence())
                )
            } else {
                String::new()
            };
            let _ = writeln!(
                html,
                "<tr>{claim}<td class=\"left\">{}</td><td>{:+.1} [{:+.1}, {:+.1}]</td><td>{}</td><td>{}</td><td class=\"{}\">{}</td></tr>",
                esc(&r.room),
                r.difference,
                r.ci_low,
                r.ci_high,
                p_text(r.p),
                p_text(r.p_holm),
                verdict_class(&r.verdict),
                r.verdict
            );
        }
    }
    html.push_str("</table>\n");
    if any { html } else { String::new() }
}

/// Fig. 6's checks over seeds as an HTML table (empty without any).
fn curve_claims_html(claims: &[ClaimRecord]) -> String {
    let mut html = String::from(
        "<h3 id=\"claims-fig6\">Fig. 6 over seeds</h3>\n<table><tr><th>claim</th><th>setting</th><th>value [95 % CI]</th><th>p</th><th>verdict</th></tr>\n",
    );
    let mut any = false;
    for c in claims {
        for r in &c.curves {
            any = true;
            let _ = writeln!(
                html,
                "<tr><td class=\"left\">{}</td><td>{}</td><td>{:.3} [{:.3}, {:.3}]</td><td>{}</td><td class=\"{}\">{}</td></tr>",
                esc(&c.claim.sentence()),
                esc(&r.setting),
                r.value,
                r.ci_low,
                r.ci_high,
                p_text(r.p),
                verdict_class(&r.verdict),
                r.verdict
            );
        }
    }
    let _ = writeln!(
        html,
        "</table>\n<p class=\"caption\">{}</p>",
        esc(CURVES_METHOD)
    );
    if any { html } else { String::new() }
}

/// The ablation table: one row per variant, one column per claim, as (Markdown, CSV).
pub fn ablation_table(
    rows: &[(&Variant, Vec<ClaimRecord>)],
    prov: &Provenance,
) -> (String, String) {
    let mut md = format!(
        "{}\n\nWhich of the paper's claims hold when one modelling choice is switched back (means over rooms and seeds; each variant's own tables are in its directory).\n\n| variant | switched back |",
        prov.line()
    );
    let mut csv = String::from("variant");
    for c in &rows[0].1 {
        let _ = write!(md, " {} |", c.claim);
        let _ = write!(csv, ",\"{}\"", c.claim);
    }
    md.push_str("\n|---|---|");
    md.push_str(&"---|".repeat(rows[0].1.len()));
    md.push('\n');
    csv.push('\n');
    for (v, claims) in rows {
        let _ = write!(md, "| {} | {} |", v.name, v.what);
        let _ = write!(csv, "{}", v.name);
        for c in claims {
            let _ = write!(md, " {} ({}) |", verdict(c), c.evidence);
            let _ = write!(csv, ",{}", c.holds);
        }
        md.push('\n');
        csv.push('\n');
    }
    (md, csv)
}

/// The report's spread table of one setting: mean ± sample std over seeds and the range, per
/// room.
pub fn spread_html(study: &SettingRuns<'_>) -> String {
    let n = study.seeds.len();
    let mut html = String::from(
        "<table><tr><th>room</th><th>average fitness</th><th>% optimal exploration</th><th>% recognition</th><th>% battery usage</th><th>% homing</th></tr>\n",
    );
    for (i, row) in study.finished[0].rows.iter().enumerate() {
        let _ = write!(html, "<tr><td>{}</td>", esc(&row.room));
        for (c, stat) in room_stats(study, i).iter().enumerate() {
            let values: Vec<f64> = study
                .finished
                .iter()
                .filter_map(|f| metrics(&f.rows[i])[c])
                .collect();
            let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let d = if c == 0 { 3 } else { 1 };
            let _ = write!(
                html,
                "<td>{}</td>",
                stat.map_or("n/a".into(), |(m, s)| format!(
                    "{} <span class=\"paper\">[{lo:.d$}–{hi:.d$}]</span>",
                    mean_std_cell(m, s, n, d)
                ))
            );
        }
        html.push_str("</tr>\n");
    }
    html.push_str("</table>\n");
    let _ = writeln!(
        html,
        "<p class=\"caption\">Mean ± standard deviation over {} seeds ({}), with the range in brackets ({STD_IS_SAMPLE}). The figures and the detailed sections below show the {}.</p>",
        n,
        study
            .seeds
            .iter()
            .map(u64::to_string)
            .collect::<Vec<_>>()
            .join(", "),
        study.median_label()
    );
    html
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A claim over `seeds` paired seeds with p-value `p` and smallest attainable p `min_p`.
    fn claim_over(seeds: usize, p: f64, min_p: f64) -> ClaimRecord {
        ClaimRecord {
            claim: fuzzymotiv_records::records::paper_claims::ClaimId::Explores,
            curves: Vec::new(),
            evidence: "high 91.2 % vs low 89.5 %".into(),
            holds: true,
            stats: Some(ClaimStats {
                seeds,
                difference: 1.7,
                ci_low: 1.0,
                ci_high: 2.4,
                p,
                min_p,
                alpha: 0.05,
                verdict: "holds".into(),
                mdd: Some(0.8),
                rooms: Vec::new(),
            }),
        }
    }

    fn provenance_of(seeds: u64) -> Provenance {
        Provenance {
            seeds: (1..=seeds).collect(),
            population: 200,
            generations: 200,
            quick: false,
        }
    }

    /// Issue #52 item 7: a p below 0.0001 is printed in claims.md's p column as 1.9e-6, not as
    /// 0.0000; a larger p keeps four decimals.
    #[test]
    fn the_smallest_p_of_twenty_seeds_is_printed_readably() {
        let p = 2.0 / 2f64.powi(20);
        assert_eq!(p_text(p), "1.9e-6");
        assert_eq!(p_text(0.5), "0.5000");
        assert_eq!(p_text(0.0), "0.0000");
        let resampled = 2.0 / (PERMUTATION_RESAMPLES + 1) as f64;
        let (md, _) = claims_table(&[claim_over(20, p, resampled)], &provenance_of(20));
        assert!(md.contains("| 1.9e-6 |") && !md.contains("0.0000"), "{md}");
    }

    /// Issue #52: the note on the smallest p says how p was found. Up to 16 seeds every sign
    /// pattern is enumerated (2/2^n); beyond, p is estimated from PERMUTATION_RESAMPLES random
    /// patterns, whose floor 2/(K + 1) = 2.0e-5 is said, and 2/2^20 only as the exact floor.
    #[test]
    fn the_note_on_the_smallest_p_says_whether_p_is_exact_or_resampled() {
        let (five, _) = claims_table(&[claim_over(5, 0.0625, 0.0625)], &provenance_of(5));
        assert!(
            five.contains(
                "with 5 paired seeds p enumerates all 2^5 sign patterns: the smallest two-sided p \
                 is 2/2^5 = 0.0625 (1/16 for five seeds), not below α = 0.05"
            ),
            "{five}"
        );
        let resampled = 2.0 / (PERMUTATION_RESAMPLES + 1) as f64;
        let (twenty, _) = claims_table(&[claim_over(20, resampled, resampled)], &provenance_of(20));
        assert!(
            twenty.contains(
                "with 20 paired seeds (more than 16) p is estimated from 99999 random sign \
                 patterns, the observed one counted once more: the smallest it can give is \
                 2/(99999 + 1) = 2.0e-5 (the exact floor 2/2^20 would be 1.9e-6), below α = 0.05."
            ),
            "{twenty}"
        );
        assert!(
            !twenty.contains("smallest two-sided p is 2/2^20"),
            "{twenty}"
        );
    }
}
