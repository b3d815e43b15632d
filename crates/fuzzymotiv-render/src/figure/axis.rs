//! A panel's plot area and its axes ([`Area`]): a linear scale ([`Scale`]), the title over
//! it, grid lines with their labels, the axis lines, tick marks with labels under the x axis,
//! and the axis labels — the pieces every panel of every figure is drawn with.

use super::Ticks;
use super::doc::{Stroke, Svg, Text};

/// The light grey of grid lines.
pub const GRID: &str = "#ddd";
/// The grey of secondary text (captions, notes, some tick labels).
pub const MUTED: &str = "#555";

/// A linear map of values in `[lo, hi]` to pixels in `[a, b]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scale {
    lo: f64,
    hi: f64,
    a: f64,
    b: f64,
}

impl Scale {
    /// Values `lo ..= hi` onto pixels `a ..= b` (an empty range maps everything to `a`).
    pub fn new((lo, hi): (f64, f64), (a, b): (f64, f64)) -> Scale {
        Scale { lo, hi, a, b }
    }

    /// The pixel of `v`.
    pub fn at(&self, v: f64) -> f64 {
        let span = self.hi - self.lo;
        if span == 0.0 {
            self.a
        } else {
            self.a + (self.b - self.a) * (v - self.lo) / span
        }
    }
}

/// A plot area in pixels: x from `x0` (left) to `x1`, y from `y0` (the bottom, the x axis) up
/// to `y1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Area {
    /// Left.
    pub x0: f64,
    /// Right.
    pub x1: f64,
    /// Bottom.
    pub y0: f64,
    /// Top.
    pub y1: f64,
}

/// A panel of a grid of panels: its size and the margins around its plot area.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PanelBox {
    /// The panel's width.
    pub width: f64,
    /// The panel's height.
    pub height: f64,
    /// The margin left of the plot area (for the y tick labels).
    pub left: f64,
    /// The margin right of it.
    pub right: f64,
    /// The margin below it (for the x tick labels and axis label).
    pub bottom: f64,
    /// The margin above it (for the panel's title).
    pub top: f64,
}

impl PanelBox {
    /// The plot area of the panel in column `col` and row `row` of the grid.
    pub fn area(&self, col: usize, row: usize) -> Area {
        let (ox, oy) = (col as f64 * self.width, row as f64 * self.height);
        Area {
            x0: ox + self.left,
            x1: ox + self.width - self.right,
            y0: oy + self.height - self.bottom,
            y1: oy + self.top,
        }
    }
}

impl Area {
    /// The area's horizontal centre.
    pub fn mid_x(&self) -> f64 {
        (self.x0 + self.x1) / 2.0
    }

    /// The area's vertical centre.
    pub fn mid_y(&self) -> f64 {
        (self.y0 + self.y1) / 2.0
    }

    /// Values `lo ..= hi` across the area, left to right.
    pub fn x_scale(&self, lo: f64, hi: f64) -> Scale {
        Scale::new((lo, hi), (self.x0, self.x1))
    }

    /// Values `lo ..= hi` up the area, bottom to top.
    pub fn y_scale(&self, lo: f64, hi: f64) -> Scale {
        Scale::new((lo, hi), (self.y0, self.y1))
    }

    /// `title` in bold, centred over the area, its baseline at `y`.
    pub fn title(&self, svg: &mut Svg, y: f64, title: &str) {
        svg.text((self.mid_x(), y), title, Text::MIDDLE.bold());
    }

    /// A grid line across the area at each of `ticks` (on `y`), labelled left of the area
    /// in `label` style; the line at 0 in `zero` when given.
    pub fn y_grid(
        &self,
        svg: &mut Svg,
        ticks: &Ticks,
        y: Scale,
        label: Text<'_>,
        zero: Option<&str>,
    ) {
        // A third of the text's size below the line: the digits' middle on it.
        let raise = (label.size.unwrap_or(svg.font_size()) / 3.0).round();
        for &t in &ticks.values {
            let colour = zero.filter(|_| t == 0.0).unwrap_or(GRID);
            let yy = y.at(t);
            svg.line((self.x0, yy), (self.x1, yy), Stroke::of(colour));
            svg.text((self.x0 - 6.0, yy + raise), &ticks.label(t), label);
        }
    }

    /// The axis lines: up the left edge and along the bottom.
    pub fn axes(&self, svg: &mut Svg) {
        let black = Stroke::of("#000");
        svg.line((self.x0, self.y0), (self.x0, self.y1), black);
        svg.line((self.x0, self.y0), (self.x1, self.y0), black);
    }

    /// A label under the x axis at each `(x, text)`, its baseline `dy` below the axis, with a
    /// 4 px tick mark up to the axis when `marks`.
    pub fn x_ticks(
        &self,
        svg: &mut Svg,
        ticks: &[(f64, String)],
        dy: f64,
        marks: bool,
        label: Text<'_>,
    ) {
        for (x, text) in ticks {
            if marks {
                svg.line((*x, self.y0), (*x, self.y0 + 4.0), Stroke::of("#000"));
            }
            svg.text((*x, self.y0 + dy), text, label);
        }
    }

    /// The x axis's label, centred under the area with its baseline `dy` below the axis, and
    /// the y axis's turned along the left edge, `dx` left of it.
    pub fn labels(
        &self,
        svg: &mut Svg,
        (x, dy): (&str, f64),
        (y, dx): (&str, f64),
        style: Text<'_>,
    ) {
        self.x_label(svg, (x, dy), style);
        svg.text((self.x0 - dx, self.mid_y()), y, style.turned());
    }

    /// The x axis's label alone, centred under the area with its baseline `dy` below the axis.
    pub fn x_label(&self, svg: &mut Svg, (x, dy): (&str, f64), style: Text<'_>) {
        svg.text((self.mid_x(), self.y0 + dy), x, style);
    }
}

/// `ticks`' values on `scale`, each with its label.
pub fn placed(ticks: &Ticks, scale: Scale) -> Vec<(f64, String)> {
    (ticks.values.iter())
        .map(|&v| (scale.at(v), ticks.label(v)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scale_maps_its_ends_and_a_y_scale_runs_up() {
        let area = Area {
            x0: 50.0,
            x1: 150.0,
            y0: 200.0,
            y1: 100.0,
        };
        let (x, y) = (area.x_scale(0.0, 10.0), area.y_scale(0.0, 1.0));
        assert_eq!((x.at(0.0), x.at(5.0), x.at(10.0)), (50.0, 100.0, 150.0));
        assert_eq!((y.at(0.0), y.at(1.0)), (200.0, 100.0));
        assert_eq!(Scale::new((3.0, 3.0), (1.0, 9.0)).at(7.0), 1.0);
    }

    #[test]
    fn a_panels_plot_area_is_inside_its_margins_in_its_grid_cell() {
        let panel = PanelBox {
            width: 200.0,
            height: 100.0,
            left: 30.0,
            right: 10.0,
            bottom: 20.0,
            top: 15.0,
        };
        let a = panel.area(2, 1);
        assert_eq!((a.x0, a.x1, a.y0, a.y1), (430.0, 590.0, 180.0, 115.0));
    }
}
