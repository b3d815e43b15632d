//! How a study's results are printed (`report.md`, `forest.svg`, the line `fuzzymotiv study`
//! prints): every number of one result by one rule ([`RowFormat`]), p-values to three decimals
//! ([`p_text`]), a pooled claim as one line ([`claim_line`]). The CSV and JSON records keep
//! the numbers whole.

use fuzzymotiv_records::records::hypotheses::ClaimRow;

/// How the numbers of one result (a claim or a room's row) are printed, the same for its
/// effect, interval bounds and detectable difference: one decimal for a percentage's
/// difference or value (points), else three significant digits of the row's largest number
/// (at most 6 decimals), every number of the row to those decimals. A trend's slope is per unit of its arms' level,
/// not in the measure's unit, so it always takes three significant digits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RowFormat {
    /// Decimals of every number of the row.
    pub decimals: usize,
}

impl RowFormat {
    /// The format of a result of kind `kind` over the measure column `measure` with these
    /// numbers (effect, bounds, detectable difference).
    pub fn of(kind: &str, measure: &str, numbers: &[f64]) -> RowFormat {
        if measure.ends_with("_pct") && kind != "trend" {
            return RowFormat { decimals: 1 };
        }
        let largest = (numbers.iter())
            .filter(|v| v.is_finite())
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        // At most 6 decimals; a row whose numbers all round to 0 there (rounding noise of a
        // zero effect, 1e-15) is printed as zeros to 3 decimals.
        let decimals = if largest >= 5e-7 {
            (2.0 - largest.log10().floor()).clamp(0.0, 6.0) as usize
        } else {
            3
        };
        RowFormat { decimals }
    }

    /// The format of a claim row.
    pub fn of_claim(c: &ClaimRow) -> RowFormat {
        let mut numbers = vec![c.effect, c.ci_low, c.ci_high];
        numbers.extend(c.mdd);
        RowFormat::of(&c.kind, &c.measure, &numbers)
    }

    /// `v` to the row's decimals, `−` for a negative (never `−0.0`).
    pub fn num(&self, v: f64) -> String {
        let d = self.decimals;
        let s = format!("{v:.d$}");
        if s.trim_start_matches('-')
            .chars()
            .all(|c| c == '0' || c == '.')
        {
            s.trim_start_matches('-').to_string()
        } else {
            s.replace('-', "−")
        }
    }

    /// A detectable difference, `–` where there is none (one seed).
    pub fn mdd(&self, v: Option<f64>) -> String {
        v.map_or_else(|| "–".into(), |v| self.num(v))
    }

    /// An interval, `[low, high]`.
    pub fn interval(&self, low: f64, high: f64) -> String {
        format!("[{}, {}]", self.num(low), self.num(high))
    }
}

/// A p-value as the report prints it: three decimals, `< 0.001` below.
pub fn p_text(p: f64) -> String {
    if p < 0.0005 {
        "< 0.001".into()
    } else {
        format!("{p:.3}")
    }
}

/// A pooled claim as one line (what `fuzzymotiv study` prints): id, verdict, sentence, effect,
/// interval and adjusted p, in the report's format.
pub fn claim_line(c: &ClaimRow) -> String {
    let f = RowFormat::of_claim(c);
    format!(
        "{}: {} — {} (effect {}, CI {}, p {})",
        c.id,
        c.verdict,
        c.sentence,
        f.num(c.effect),
        f.interval(c.ci_low, c.ci_high),
        p_text(c.p_adjusted)
    )
}
