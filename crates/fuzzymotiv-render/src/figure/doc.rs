//! The SVG document a figure is written into ([`Svg`]): its opening with the one font stack,
//! a white page, and one method per element, each writing its numbers through [`px`] and its
//! text through [`esc`], its look from a [`Stroke`], [`Fill`] or [`Text`] style.

use std::fmt::Write as _;

use super::{esc, open, px, text_width_at};

/// How a line is stroked: colour, width (the viewer's 1 when `None`), dashes and opacity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stroke<'a> {
    /// The colour.
    pub colour: &'a str,
    /// The width, px.
    pub width: Option<f64>,
    /// The dash pattern (`"5 4"`), if any.
    pub dash: Option<&'a str>,
    /// The opacity, if not 1.
    pub opacity: Option<f64>,
}

impl<'a> Stroke<'a> {
    /// A 1 px line of `colour`.
    pub const fn of(colour: &'a str) -> Stroke<'a> {
        Stroke {
            colour,
            width: None,
            dash: None,
            opacity: None,
        }
    }

    /// This stroke `width` px wide.
    pub const fn width(self, width: f64) -> Stroke<'a> {
        Stroke {
            width: Some(width),
            ..self
        }
    }

    /// This stroke dashed by `dash`.
    pub const fn dashed(self, dash: &'a str) -> Stroke<'a> {
        Stroke {
            dash: Some(dash),
            ..self
        }
    }

    /// This stroke at `opacity`.
    pub const fn opacity(self, opacity: f64) -> Stroke<'a> {
        Stroke {
            opacity: Some(opacity),
            ..self
        }
    }

    /// Its attributes, each with a leading space.
    fn attrs(&self) -> String {
        let mut s = format!(" stroke=\"{}\"", self.colour);
        if let Some(w) = self.width {
            let _ = write!(s, " stroke-width=\"{}\"", px(w));
        }
        if let Some(o) = self.opacity {
            let _ = write!(s, " stroke-opacity=\"{}\"", px(o));
        }
        if let Some(d) = self.dash {
            let _ = write!(s, " stroke-dasharray=\"{d}\"");
        }
        s
    }
}

/// How a shape is filled and outlined.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fill<'a> {
    /// The fill colour (`"none"` for none).
    pub colour: &'a str,
    /// The fill opacity, if not 1.
    pub opacity: Option<f64>,
    /// The outline, if any.
    pub stroke: Option<Stroke<'a>>,
}

impl<'a> Fill<'a> {
    /// Filled with `colour`, no outline.
    pub const fn of(colour: &'a str) -> Fill<'a> {
        Fill {
            colour,
            opacity: None,
            stroke: None,
        }
    }

    /// Unfilled, outlined by `stroke`.
    pub const fn outline(stroke: Stroke<'a>) -> Fill<'a> {
        Fill {
            colour: "none",
            opacity: None,
            stroke: Some(stroke),
        }
    }

    /// This fill at `opacity`.
    pub const fn opacity(self, opacity: f64) -> Fill<'a> {
        Fill {
            opacity: Some(opacity),
            ..self
        }
    }

    /// This fill outlined by `stroke`.
    pub const fn stroked(self, stroke: Stroke<'a>) -> Fill<'a> {
        Fill {
            stroke: Some(stroke),
            ..self
        }
    }

    /// Its attributes, each with a leading space.
    fn attrs(&self) -> String {
        let mut s = format!(" fill=\"{}\"", self.colour);
        if let Some(o) = self.opacity {
            let _ = write!(s, " fill-opacity=\"{}\"", px(o));
        }
        if let Some(stroke) = &self.stroke {
            s.push_str(&stroke.attrs());
        }
        s
    }
}

/// Where a text stands relative to its x.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    /// Starting at x.
    Start,
    /// Centred on x.
    Middle,
    /// Ending at x.
    End,
}

/// How a text is set: anchor, weight, size (the figure's when `None`), colour, and whether it
/// is turned a quarter left about its anchor (a y-axis label).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Text<'a> {
    /// The anchor.
    pub anchor: Anchor,
    /// Bold or not.
    pub bold: bool,
    /// The size, px, if not the figure's.
    pub size: Option<f64>,
    /// The colour, if not black.
    pub fill: Option<&'a str>,
    /// Turned a quarter left about (x, y).
    pub turned: bool,
}

impl<'a> Text<'a> {
    /// Text starting at x.
    pub const START: Text<'static> = Text {
        anchor: Anchor::Start,
        bold: false,
        size: None,
        fill: None,
        turned: false,
    };
    /// Text centred on x.
    pub const MIDDLE: Text<'static> = Text {
        anchor: Anchor::Middle,
        ..Text::START
    };
    /// Text ending at x.
    pub const END: Text<'static> = Text {
        anchor: Anchor::End,
        ..Text::START
    };

    /// This text in bold.
    pub const fn bold(self) -> Text<'a> {
        Text { bold: true, ..self }
    }

    /// This text at `size` px.
    pub const fn size(self, size: f64) -> Text<'a> {
        Text {
            size: Some(size),
            ..self
        }
    }

    /// This text in `colour`.
    pub const fn fill<'b>(self, colour: &'b str) -> Text<'b>
    where
        'a: 'b,
    {
        Text {
            fill: Some(colour),
            ..self
        }
    }

    /// This text turned a quarter left about its anchor.
    pub const fn turned(self) -> Text<'a> {
        Text {
            turned: true,
            ..self
        }
    }

    /// The width of `text` set so in a figure whose font size is `figure_size`
    /// ([`text_width_at`]).
    pub fn width(&self, text: &str, figure_size: f64) -> f64 {
        text_width_at(text, self.bold, self.size.unwrap_or(figure_size))
    }
}

/// An SVG figure being written: [`Svg::new`] opens it on a white page, the element methods
/// add to it in drawing order, [`Svg::finish`] closes it.
#[derive(Debug, Clone)]
pub struct Svg {
    out: String,
    font_size: f64,
}

impl Svg {
    /// A figure `width` × `height` px (written through [`px`]), its text at `font_size` px,
    /// on a white page.
    pub fn new(width: f64, height: f64, font_size: u32) -> Svg {
        let (w, h) = (px(width), px(height));
        let mut out = open(w, h, font_size);
        let _ = writeln!(out, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
        Svg {
            out,
            font_size: font_size as f64,
        }
    }

    /// The figure's font size, px.
    pub fn font_size(&self) -> f64 {
        self.font_size
    }

    /// The width of `text` set in `style` in this figure.
    pub fn text_width(&self, text: &str, style: Text<'_>) -> f64 {
        style.width(text, self.font_size)
    }

    /// A line from `a` to `b`.
    pub fn line(&mut self, (x1, y1): (f64, f64), (x2, y2): (f64, f64), stroke: Stroke<'_>) {
        let _ = writeln!(
            self.out,
            r#"<line x1="{}" x2="{}" y1="{}" y2="{}"{}/>"#,
            px(x1),
            px(x2),
            px(y1),
            px(y2),
            stroke.attrs()
        );
    }

    /// `text` at (x, y) set in `style`.
    pub fn text(&mut self, (x, y): (f64, f64), text: &str, style: Text<'_>) {
        let (x, y) = (px(x), px(y));
        let mut attrs = String::new();
        match style.anchor {
            Anchor::Start => {}
            Anchor::Middle => attrs.push_str(r#" text-anchor="middle""#),
            Anchor::End => attrs.push_str(r#" text-anchor="end""#),
        }
        if let Some(size) = style.size {
            let _ = write!(attrs, r#" font-size="{}""#, px(size));
        }
        if style.bold {
            attrs.push_str(r#" font-weight="bold""#);
        }
        if let Some(fill) = style.fill {
            let _ = write!(attrs, r#" fill="{fill}""#);
        }
        if style.turned {
            let _ = write!(attrs, r#" transform="rotate(-90 {x} {y})""#);
        }
        let _ = writeln!(
            self.out,
            r#"<text x="{x}" y="{y}"{attrs}>{}</text>"#,
            esc(text)
        );
    }

    /// A circle of radius `r` about `c`, with `title` as its tooltip.
    pub fn circle(&mut self, (cx, cy): (f64, f64), r: f64, fill: Fill<'_>, title: Option<&str>) {
        let head = format!(
            r#"<circle cx="{}" cy="{}" r="{}"{}"#,
            px(cx),
            px(cy),
            px(r),
            fill.attrs()
        );
        self.close(head, "circle", title);
    }

    /// A rectangle from (x, y), `w` × `h`.
    pub fn rect(&mut self, (x, y): (f64, f64), (w, h): (f64, f64), fill: Fill<'_>) {
        let _ = writeln!(
            self.out,
            r#"<rect x="{}" y="{}" width="{}" height="{}"{}/>"#,
            px(x),
            px(y),
            px(w),
            px(h),
            fill.attrs()
        );
    }

    /// An open line through `points`, with an optional class.
    pub fn polyline(&mut self, points: &[(f64, f64)], stroke: Stroke<'_>, class: Option<&str>) {
        let class = class.map_or(String::new(), |c| format!(r#" class="{c}""#));
        let _ = writeln!(
            self.out,
            r#"<polyline{class} points="{}" fill="none"{} stroke-linejoin="round"/>"#,
            points_attr(points),
            stroke.attrs()
        );
    }

    /// A closed shape through `points`.
    pub fn polygon(&mut self, points: &[(f64, f64)], fill: Fill<'_>) {
        let _ = writeln!(
            self.out,
            r#"<polygon points="{}"{}/>"#,
            points_attr(points),
            fill.attrs()
        );
    }

    /// A path of data `d` ([`PathData`]), with an optional class and tooltip.
    pub fn path(&mut self, d: &PathData, fill: Fill<'_>, class: Option<&str>) {
        let class = class.map_or(String::new(), |c| format!(r#" class="{c}""#));
        let _ = writeln!(self.out, r#"<path{class} d="{}"{}/>"#, d.0, fill.attrs());
    }

    /// Opens a group of `class` (closed by [`Svg::end_group`]).
    pub fn group(&mut self, class: &str) {
        let _ = writeln!(self.out, r#"<g class="{class}">"#);
    }

    /// Closes the group [`Svg::group`] opened.
    pub fn end_group(&mut self) {
        self.out.push_str("</g>\n");
    }

    /// An element's start `head`, then its tooltip and end tag, or `/>`.
    fn close(&mut self, head: String, name: &str, title: Option<&str>) {
        self.out.push_str(&head);
        match title {
            Some(t) => {
                let _ = writeln!(self.out, "><title>{}</title></{name}>", esc(t));
            }
            None => self.out.push_str("/>\n"),
        }
    }

    /// The finished figure.
    pub fn finish(mut self) -> String {
        self.out.push_str("</svg>\n");
        self.out
    }
}

/// `x,y x,y …` with [`px`] numbers.
fn points_attr(points: &[(f64, f64)]) -> String {
    let pts: Vec<String> = (points.iter())
        .map(|&(x, y)| format!("{},{}", px(x), px(y)))
        .collect();
    pts.join(" ")
}

/// A path's data, built move by move.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PathData(String);

impl PathData {
    /// No moves yet.
    pub fn new() -> PathData {
        PathData::default()
    }

    /// Moves to (x, y).
    pub fn move_to(mut self, (x, y): (f64, f64)) -> PathData {
        let _ = write!(self.0, "M{},{}", px(x), px(y));
        self
    }

    /// A line to (x, y) (a move when the path is empty).
    pub fn line_to(mut self, (x, y): (f64, f64)) -> PathData {
        let op = if self.0.is_empty() { 'M' } else { 'L' };
        let _ = write!(self.0, "{op}{},{}", px(x), px(y));
        self
    }

    /// A line by (dx, dy) from where the path is.
    pub fn line_by(mut self, (dx, dy): (f64, f64)) -> PathData {
        let _ = write!(self.0, "l{},{}", px(dx), px(dy));
        self
    }

    /// Closes the current shape.
    pub fn close(mut self) -> PathData {
        self.0.push('Z');
        self
    }

    /// Whether there are no moves.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every element writes its numbers with at most 2 decimals, its text escaped, its style
    /// as attributes; a turned text turns about its own anchor.
    #[test]
    fn elements_write_compact_numbers_escaped_text_and_their_style() {
        let mut s = Svg::new(100.0, 50.004, 12);
        s.line(
            (0.0, 1.0 / 3.0),
            (10.0, 2.0),
            Stroke::of("#000").dashed("5 4"),
        );
        s.text((5.0, 6.0), "a < b", Text::END.bold().fill("#555"));
        s.text((1.0, 2.0), "p", Text::MIDDLE.turned());
        s.circle((1.0, 2.0), 4.0, Fill::of("red"), Some("x & y"));
        let path = PathData::new()
            .line_to((1.0, 2.0))
            .line_to((3.0, 4.0))
            .close();
        s.path(&path, Fill::of("#abc").opacity(0.45), None);
        let svg = s.finish();
        assert!(svg.starts_with(&open(100.0, 50.0, 12)), "{svg}");
        for part in [
            r##"<line x1="0" x2="10" y1="0.33" y2="2" stroke="#000" stroke-dasharray="5 4"/>"##,
            r##"<text x="5" y="6" text-anchor="end" font-weight="bold" fill="#555">a &lt; b</text>"##,
            r#"<text x="1" y="2" text-anchor="middle" transform="rotate(-90 1 2)">p</text>"#,
            r#"<circle cx="1" cy="2" r="4" fill="red"><title>x &amp; y</title></circle>"#,
            r##"<path d="M1,2L3,4Z" fill="#abc" fill-opacity="0.45"/>"##,
        ] {
            assert!(svg.contains(part), "{part} not in {svg}");
        }
        assert!(svg.ends_with("</svg>\n"));
    }
}
