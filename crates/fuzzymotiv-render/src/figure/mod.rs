//! The one figure builder every SVG figure is written with: the document and its elements
//! ([`Svg`], styled by [`Stroke`], [`Fill`] and [`Text`]), a panel's plot area with its scales,
//! grid, axes and labels ([`Area`], [`Scale`]), legends ([`Legend`]), rooms and robots' paths
//! ([`room::draw_room_and_path`]); under them the opening `<svg>` tag ([`open`]) with the one
//! font stack ([`FONT_STACK`]), the one tick rule ([`Ticks`]), the text width the layouts
//! reserve for that font ([`text_width`]), escaping ([`esc`]), the numbers written into
//! attributes ([`px`]) and the category colours ([`colour`]).
//!
//! Written by hand rather than with `plotters`: its backend places everything at whole
//! pixels (`BackendCoord = (i32, i32)`), measures text only with a font loaded at run time, and
//! writes no tooltips (`<title>`) or classes, which the figures and their tests use.

pub mod axis;
pub mod doc;
pub mod legend;
pub mod metrics;
pub mod room;

pub use axis::{Area, MUTED, PanelBox, Scale};
pub use doc::{Anchor, Fill, PathData, Stroke, Svg, Text};
pub use legend::{Legend, Mark};

use std::fmt::Display;

/// The font of every figure: DejaVu Sans, the font [`text_width`] is measured for (and the
/// first the binary's PNGs look for), else the viewer's sans-serif.
pub const FONT_STACK: &str = "DejaVu Sans, sans-serif";

/// The opening tag of a figure `width` × `height` px (as the figure writes them: whole pixels
/// or [`px`] values), its text at `font_size` px in [`FONT_STACK`]: the figure's first line.
pub fn open(width: impl Display, height: impl Display, font_size: u32) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\" font-family=\"{FONT_STACK}\" font-size=\"{font_size}\">\n"
    )
}

/// Escapes text for XML/HTML content and attribute values.
pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The width (px) of `text` at 12 px in DejaVu Sans (bold or not): [`text_width_at`].
pub fn text_width(text: &str, bold: bool) -> f64 {
    text_width_at(text, bold, 12.0)
}

/// The width (px) of `text` at a font size of `size` px, measured from DejaVu Sans, the font
/// [`FONT_STACK`] names first (the widest of the fonts the PNGs use): the sum of its
/// characters' advances ([`metrics`]), an em for a character the tables lack. Every layout
/// of every figure reserves room for text with it.
pub fn text_width_at(text: &str, bold: bool, size: f64) -> f64 {
    let (ascii, other) = if bold {
        (&metrics::BOLD_ASCII, &metrics::BOLD_OTHER[..])
    } else {
        (&metrics::REGULAR_ASCII, &metrics::REGULAR_OTHER[..])
    };
    let advance = |c: char| match c {
        ' '..='~' => ascii[c as usize - 0x20],
        _ => (other.iter().find(|(o, _)| *o == c)).map_or(metrics::OTHER, |&(_, w)| w),
    };
    let units: u32 = text.chars().map(|c| u32::from(advance(c))).sum();
    f64::from(units) / metrics::UNITS_PER_EM * size
}

/// A coordinate or size as figures print it: rounded to 2 decimals, so that Rust's shortest
/// round-trip formatting writes at most 2 (`428.52`, never `428.52000000000004`). Every
/// computed number a figure writes into an attribute goes through it.
pub fn px(v: f64) -> f64 {
    (v * 100.0).round() / 100.0 + 0.0
}

/// Colours for rooms (and other categories), in order; cycles after ten.
pub const PALETTE: [&str; 10] = [
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
    "#bcbd22", "#17becf",
];

/// The colour of category `k`.
pub fn colour(k: usize) -> &'static str {
    PALETTE[k % PALETTE.len()]
}

/// Axis ticks at round numbers: every multiple of `step` in a range, where `step` is 1, 2 or
/// 5 × 10^k.
#[derive(Debug, Clone, PartialEq)]
pub struct Ticks {
    /// Distance between ticks.
    pub step: f64,
    /// The ticks, ascending.
    pub values: Vec<f64>,
}

impl Ticks {
    /// Ticks over `[lo, hi]`, about `target` intervals (the smallest 1, 2, 5 × 10^k step not
    /// shorter than `(hi − lo) / target`); `integer` keeps the step at least 1 (generations,
    /// node indices). An empty or non-finite range gets the one tick `lo`.
    pub fn nice(lo: f64, hi: f64, target: usize, integer: bool) -> Ticks {
        if !(lo.is_finite() && hi.is_finite()) || hi <= lo {
            return Ticks {
                step: 1.0,
                values: vec![lo],
            };
        }
        let raw = (hi - lo) / target.max(1) as f64;
        let magnitude = 10f64.powf(raw.log10().floor());
        let mut step = [1.0, 2.0, 5.0, 10.0]
            .iter()
            .map(|m| m * magnitude)
            .find(|&s| s >= raw * (1.0 - 1e-9))
            .unwrap_or(10.0 * magnitude);
        if integer {
            step = step.max(1.0);
        }
        let first = (lo / step - 1e-9).ceil() as i64;
        let last = (hi / step + 1e-9).floor() as i64;
        let values = (first..=last).map(|k| k as f64 * step).collect();
        Ticks { step, values }
    }

    /// A tick's label, with as many decimals as the step needs ("0.2", "50", "1.0").
    pub fn label(&self, v: f64) -> String {
        let decimals = (-self.step.log10().floor()).max(0.0) as usize;
        let text = format!("{v:.decimals$}");
        // No "-0" for a tick at zero.
        if text
            .trim_start_matches('-')
            .chars()
            .all(|c| c == '0' || c == '.')
        {
            text.trim_start_matches('-').to_string()
        } else {
            text
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compare::compare_svg;
    use fuzzymotiv_records::records::compare::CompareRow;

    /// The opening of `svg`, up to its first `>`.
    fn opening(svg: &str) -> &str {
        svg.split('>').next().unwrap()
    }

    /// Text is measured from the font: a capital M is wider than an i, bold wider than
    /// regular, a character the tables lack takes an em; "Hello" at 12 px is DejaVu Sans's
    /// 30.42 px.
    #[test]
    fn text_width_is_measured_from_the_fonts_advances() {
        assert!(text_width("M", false) > 2.0 * text_width("i", false));
        assert!(text_width("Mean F", true) > text_width("Mean F", false));
        assert_eq!(text_width_at("\u{263A}", false, 10.0), 10.0);
        assert_eq!(px(text_width("Hello", false)), 30.42);
        assert_eq!(text_width("−", false), text_width("+", false));
    }

    #[test]
    fn the_opening_names_the_size_and_the_one_font_stack() {
        assert_eq!(
            open(420, format_args!("{:.0}", 323.6), 11),
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"420\" height=\"324\" \
             viewBox=\"0 0 420 324\" font-family=\"DejaVu Sans, sans-serif\" font-size=\"11\">\n"
        );
    }

    /// The figures drawn outside `svg.rs` (its own are checked by its text-fit test; the
    /// search-strength figure by the binary's `search_strength` test) open as every figure
    /// does: one opening, one font stack.
    #[test]
    fn the_compare_figure_opens_with_the_one_font_stack() {
        let row = CompareRow {
            setting: "high-curiosity".into(),
            metric: "exploration_pct".into(),
            room: "H".into(),
            design: "paired".into(),
            n_a: 3,
            n_b: 3,
            mean_a: 50.0,
            mean_b: 40.0,
            difference: 10.0,
            ci_low: 2.0,
            ci_high: 18.0,
            p: 0.25,
            exact: true,
            p_holm: 0.25,
            mdd: None,
        };
        let font = format!("font-family=\"{FONT_STACK}\"");
        let svg = compare_svg("A vs B", &[row], 0.05);
        assert!(svg.starts_with("<svg "), "{svg}");
        assert!(opening(&svg).contains(&font), "{}", opening(&svg));
        assert_eq!(svg.matches("<svg").count(), 1);
    }
}
