//! Hand-written SVG figures: fitness evolution (paper Fig. 6), trajectories (Figs. 7–8), the
//! fitness terms per generation, the membership functions and the rooms' nodes on the SOM line.

use std::fmt::Write as _;

use crate::plot::{Ticks, colour, esc, open, px, text_width};

use fuzzymotiv::experiment::GenerationRecord;
use fuzzymotiv::fitness::TermId;
use fuzzymotiv::simulation::Trajectory;
use fuzzymotiv::simulation::{Room, Zone};
use fuzzymotiv::simulation::{Vec2, point_in_polygon};
use fuzzymotiv_records::records::MotivationEntry;

/// One panel of [`fitness_panels_svg`]: curves per generation with shaded bands.
pub struct FitnessPanel {
    /// Panel title.
    pub title: String,
    /// The best F per generation (red) and its legend text.
    pub best: (Vec<f64>, String),
    /// The mean F per generation (blue) and its legend text.
    pub mean: (Vec<f64>, String),
    /// Shaded bands, `(low, high)` per generation, each with its colour.
    pub bands: Vec<(Vec<(f64, f64)>, &'static str)>,
    /// The bands' legend text (one entry for all of them).
    pub band_label: String,
}

impl FitnessPanel {
    /// One run's panel: the population's best and mean F, and its min–max band.
    pub fn of_run(title: &str, hist: &[GenerationRecord]) -> FitnessPanel {
        FitnessPanel {
            title: title.to_string(),
            best: (hist.iter().map(|r| r.stats.max).collect(), "best F".into()),
            mean: (hist.iter().map(|r| r.stats.mean).collect(), "mean F".into()),
            bands: vec![(
                hist.iter().map(|r| (r.stats.min, r.stats.max)).collect(),
                BAND,
            )],
            band_label: "population min–max".into(),
        }
    }
}

/// One panel per run: best and mean F per generation, with the population's min–max band.
pub fn fitness_svg(panels: &[(String, Vec<GenerationRecord>)]) -> String {
    let panels: Vec<FitnessPanel> = panels
        .iter()
        .map(|(title, hist)| FitnessPanel::of_run(title, hist))
        .collect();
    fitness_panels_svg(&panels)
}

/// Fitness panels side by side: per generation the best F (red) and the mean F (blue) with
/// their shaded bands; ticks at round numbers; the legend under each panel's x axis.
pub fn fitness_panels_svg(panels: &[FitnessPanel]) -> String {
    let (ml, mr, mt) = (50.0, 15.0, 30.0);
    let plot_h = 230.0;
    let y0 = mt + plot_h;
    let widths: Vec<f64> = panels
        .iter()
        // The title is centred over the plot area, which is off the panel's centre.
        .map(|p| px(420f64.max(text_width(&p.title, true) + ml - mr + 10.0)))
        .collect();
    let legends: Vec<Vec<(LegendMark, &str)>> = panels.iter().map(fitness_legend).collect();
    let legend_top = y0 + 54.0;
    let rows = widths
        .iter()
        .zip(&legends)
        .map(|(w, l)| legend_rows(l, w - ml - mr))
        .max()
        .unwrap_or(1);
    let ph = legend_top + 16.0 * (rows - 1) as f64 + 10.0;
    let width = px(widths.iter().sum::<f64>().max(1.0));
    let mut s = open(width, ph, 12);
    let _ = writeln!(s, r#"<rect width="{width}" height="{ph}" fill="white"/>"#);
    let mut ox = 0.0;
    for ((panel, pw), legend) in panels.iter().zip(&widths).zip(&legends) {
        let (x0, x1, y1) = (ox + ml, ox + pw - mr, mt);
        let generations = panel.best.0.len();
        let n = generations.max(2) as f64 - 1.0;
        let x = |g: usize| x0 + (x1 - x0) * g as f64 / n;
        let y = |f: f64| y0 + (y1 - y0) * f.clamp(0.0, 1.0);
        panel_frame(
            &mut s,
            &panel.title,
            (x0, x1, y0, y1),
            generations,
            "fuzzy fitness F",
        );
        draw_fitness_curves(&mut s, panel, x, y);
        draw_legend(&mut s, legend, (x0, x1), legend_top);
        ox += pw;
    }
    s.push_str("</svg>\n");
    s
}

/// A fitness panel's legend: the best and the mean F curves, and its bands (one entry).
fn fitness_legend(p: &FitnessPanel) -> Vec<(LegendMark, &str)> {
    let mut entries = vec![
        (LegendMark::Line(BEST), p.best.1.as_str()),
        (LegendMark::Line(MEAN), p.mean.1.as_str()),
    ];
    if !p.bands.is_empty() {
        let colours = p.bands.iter().map(|b| b.1).collect();
        entries.push((LegendMark::Bands(colours), p.band_label.as_str()));
    }
    entries
}

/// A fitness panel's shaded bands, then its best and mean F curves, at `x(generation)` and
/// `y(F)`.
fn draw_fitness_curves(
    s: &mut String,
    panel: &FitnessPanel,
    x: impl Fn(usize) -> f64,
    y: impl Fn(f64) -> f64,
) {
    for (band, colour) in &panel.bands {
        // One closed outline: along the highs, back along the lows.
        let mut d = String::new();
        for (g, (_, hi)) in band.iter().enumerate() {
            let _ = write!(
                d,
                "{}{:.1},{:.1}",
                if g == 0 { 'M' } else { 'L' },
                x(g),
                y(*hi)
            );
        }
        for (g, (lo, _)) in band.iter().enumerate().rev() {
            let _ = write!(d, "L{:.1},{:.1}", x(g), y(*lo));
        }
        let _ = writeln!(
            s,
            r#"<path d="{d}Z" fill="{colour}" fill-opacity="0.45" stroke="none"/>"#
        );
    }
    for (values, colour) in [(&panel.best.0, BEST), (&panel.mean.0, MEAN)] {
        let pts: String = values
            .iter()
            .enumerate()
            .map(|(g, &f)| format!("{:.1},{:.1} ", x(g), y(f)))
            .collect();
        let _ = writeln!(
            s,
            r#"<polyline points="{pts}" fill="none" stroke="{colour}" stroke-width="1.8" stroke-linejoin="round"/>"#
        );
    }
}

/// Colours of the best and mean F curves, of the run's min–max band and of the bands around
/// the best and the mean over seeds.
const BEST: &str = "#d62728";
const MEAN: &str = "#1f77b4";
const BAND: &str = "#9ecae1";
/// The band around the best F over seeds.
pub const BEST_BAND: &str = "#f4a6a6";
/// The band around the mean F over seeds.
pub const MEAN_BAND: &str = "#9ecae1";

/// A legend entry's mark: a line of a colour, or swatches of band colours.
enum LegendMark {
    Line(&'static str),
    Bands(Vec<&'static str>),
}

/// Width of a legend entry: a 20 px mark, a gap, the text, and room before the next entry.
fn legend_entry_width(text: &str) -> f64 {
    px(26.0 + text_width(text, false) + 14.0)
}

/// Rows a legend needs when its entries flow left to right in `width` px.
fn legend_rows(entries: &[(LegendMark, &str)], width: f64) -> usize {
    let (mut rows, mut used) = (1, 0.0);
    for (_, text) in entries {
        let w = legend_entry_width(text);
        if used > 0.0 && used + w > width {
            rows += 1;
            used = 0.0;
        }
        used += w;
    }
    rows
}

/// A legend flowing left to right from `x0`, wrapping before `x1`, its first row's text
/// baseline at `top`.
fn draw_legend(s: &mut String, entries: &[(LegendMark, &str)], (x0, x1): (f64, f64), top: f64) {
    let (mut x, mut y) = (x0, top);
    for (mark, text) in entries {
        let w = legend_entry_width(text);
        if x > x0 && x + w > x1 {
            x = x0;
            y += 16.0;
        }
        match mark {
            LegendMark::Line(colour) => {
                let _ = writeln!(
                    s,
                    r#"<line x1="{}" x2="{}" y1="{}" y2="{}" stroke="{colour}" stroke-width="2"/>"#,
                    px(x),
                    px(x + 20.0),
                    y - 4.0,
                    y - 4.0
                );
            }
            LegendMark::Bands(colours) => {
                let sw = 20.0 / colours.len().max(1) as f64;
                for (k, colour) in colours.iter().enumerate() {
                    let _ = writeln!(
                        s,
                        r#"<rect x="{:.1}" y="{}" width="{sw:.1}" height="10" fill="{colour}" fill-opacity="0.45"/>"#,
                        x + sw * k as f64,
                        y - 9.0
                    );
                }
            }
        }
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}">{}</text>"#,
            px(x + 26.0),
            px(y),
            esc(text)
        );
        x += w;
    }
}

/// Every room of the experiment with the best robot's path in it (`trajectories[r]` for room
/// `r`), as [`trajectories_svg`] draws them.
pub fn best_paths_svg(title: &str, rooms: &[Room], trajectories: &[&Trajectory]) -> String {
    let pairs: Vec<_> = rooms.iter().zip(trajectories.iter().copied()).collect();
    trajectories_svg(title, &pairs)
}

/// Length of a step marker's heading tick in the trajectory figures (px).
const TICK: f64 = 3.0;

/// Millimetres of a room to pixels of its panel: x to the right from `x_off`, y up in the
/// room and down in SVG.
struct Projection {
    x_off: f64,
    lo: fuzzymotiv::simulation::Vec2,
    hi: fuzzymotiv::simulation::Vec2,
    scale: f64,
}

impl Projection {
    fn x(&self, x: f64) -> f64 {
        self.x_off + (x - self.lo.x) * self.scale
    }

    fn y(&self, y: f64) -> f64 {
        40.0 + (self.hi.y - y) * self.scale
    }

    fn polygon(&self, pts: &[fuzzymotiv::simulation::Vec2]) -> String {
        pts.iter()
            .map(|p| format!("{:.1},{:.1}", self.x(p.x), self.y(p.y)))
            .collect::<Vec<_>>()
            .join(" ")
    }
}

/// Rooms drawn to scale side by side, each with its home zone, the path with a marker per
/// executed step, the home pose and the end point (ringed when the trial ended at home).
pub fn trajectories_svg(title: &str, rooms: &[(&Room, &Trajectory)]) -> String {
    trajectories_svg_with(title, rooms, &[])
}

/// A logged path drawn over a room of [`trajectories_svg_with`] (e.g. a robot's tracked pose).
#[derive(Debug, Clone, PartialEq)]
pub struct LoggedPath {
    /// Its legend text (e.g. the log's file).
    pub label: String,
    /// The index, in the figure's rooms, of the room it was logged in.
    pub room: usize,
    /// Its positions in mm, in the room's frame.
    pub points: Vec<(f64, f64)>,
}

/// The colours of logged paths, in turn (none is a colour the rooms, zones or paths use).
const LOG_COLOURS: [&str; 4] = ["#0e7c86", "#8c564b", "#1a1a6e", "#7f7f00"];

/// Pixels per mm of the trajectories figure: 0.3 (the paper's 800 mm rooms 240 px wide, a room
/// of up to 1200 mm 360 px), less for larger rooms (a robot's own, e.g. the Thymio II's 2400 mm
/// ones) so that each room stays 360 px at most.
fn figure_scale<'a>(rooms: impl Iterator<Item = &'a Room>) -> f64 {
    let largest = rooms
        .map(|r| {
            let (lo, hi) = r.bounds();
            (hi.x - lo.x).max(hi.y - lo.y)
        })
        .fold(0.0, f64::max);
    if largest <= 1200.0 {
        0.3
    } else {
        360.0 / largest
    }
}

/// [`trajectories_svg`] with `logs` drawn over their rooms, each dashed in a colour of its own
/// with an end square, and a legend line each under the caption (without logs the figure is
/// [`trajectories_svg`]'s, byte for byte).
pub fn trajectories_svg_with(
    title: &str,
    rooms: &[(&Room, &Trajectory)],
    logs: &[LoggedPath],
) -> String {
    let scale = figure_scale(rooms.iter().map(|(r, _)| *r));
    let pad = 20.0;
    let mut x_off = pad;
    let mut parts = String::new();
    let mut max_h: f64 = 0.0;
    for (i, (room, tr)) in rooms.iter().enumerate() {
        let (lo, hi) = room.bounds();
        let (w, h) = ((hi.x - lo.x) * scale, (hi.y - lo.y) * scale);
        max_h = max_h.max(h);
        // A room narrower than its name is centred in a slot as wide as the name.
        let slot = w.max(text_width(&room.name, false));
        let p = Projection {
            x_off: x_off + (slot - w) / 2.0,
            lo,
            hi,
            scale,
        };
        draw_room(&mut parts, room, &p);
        draw_mission(&mut parts, room, &p);
        draw_path(&mut parts, tr, &p);
        draw_home_and_end(&mut parts, room, tr, &p);
        for (k, log) in logs.iter().enumerate().filter(|(_, l)| l.room == i) {
            draw_logged_path(&mut parts, log, log_colour(k), &p);
        }
        let _ = writeln!(
            parts,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
            x_off + slot / 2.0,
            40.0 + h + 16.0,
            esc(&room.name)
        );
        x_off += slot + pad;
    }
    // Title, caption and scale bar each get a line of their own, and the figure is wide enough
    // for the longest text, so nothing is clipped or overprinted, whatever the number of rooms.
    let caption = format!(
        "green: home pose; blue: home zone; {}red: path, a tick per step; filled circle: the end (ringed: back home)",
        mission_caption(rooms.iter().map(|(r, _)| *r))
    );
    let caption = caption.as_str();
    let legend: Vec<String> = logs
        .iter()
        .map(|l| {
            format!(
                "logged path: {} ({} positions; a square at its end)",
                l.label,
                l.points.len()
            )
        })
        .collect();
    let width = legend.iter().fold(
        x_off
            .max(2.0 * pad + text_width(title, true))
            .max(2.0 * pad + text_width(caption, false)),
        |w, t| w.max(2.0 * pad + LEGEND_SWATCH + text_width(t, false)),
    );
    let (caption_y, bar_y) = (40.0 + max_h + 40.0, 40.0 + max_h + 60.0);
    let height = bar_y + 12.0 + LEGEND_LINE * legend.len() as f64;
    let mut s = open(format_args!("{width:.0}"), format_args!("{height:.0}"), 12);
    let _ = writeln!(
        s,
        r#"<rect width="{width:.0}" height="{height:.0}" fill="white"/>"#
    );
    let _ = writeln!(
        s,
        r#"<text x="{pad}" y="22" font-weight="bold">{}</text>"#,
        esc(title)
    );
    let bar = 100.0 * scale;
    let _ = writeln!(
        s,
        r##"<text x="{pad}" y="{caption_y:.0}" fill="#555">{caption}</text><line x1="{pad}" x2="{:.1}" y1="{:.0}" y2="{:.0}" stroke="#555" stroke-width="2"/><text x="{:.1}" y="{bar_y:.0}" fill="#555">100 mm</text>"##,
        pad + bar,
        bar_y - 4.0,
        bar_y - 4.0,
        pad + bar + 6.0,
    );
    for (k, text) in legend.iter().enumerate() {
        let y = bar_y + LEGEND_LINE * (k + 1) as f64;
        let _ = writeln!(
            s,
            r##"<line x1="{pad}" x2="{:.1}" y1="{:.0}" y2="{:.0}" stroke="{c}" stroke-width="2" stroke-dasharray="5 3"/><text x="{:.1}" y="{y:.0}" fill="{c}">{}</text>"##,
            pad + LEGEND_SWATCH - 6.0,
            y - 4.0,
            y - 4.0,
            pad + LEGEND_SWATCH,
            esc(text),
            c = log_colour(k)
        );
    }
    s.push_str(&parts);
    s.push_str("</svg>\n");
    s
}

/// The height of a logged path's legend line, and the width of its swatch (px).
const LEGEND_LINE: f64 = 18.0;
const LEGEND_SWATCH: f64 = 30.0;

/// The colour of the `k`-th logged path.
fn log_colour(k: usize) -> &'static str {
    LOG_COLOURS[k % LOG_COLOURS.len()]
}

/// A logged path: a dashed polyline through its positions and a square at its end.
fn draw_logged_path(parts: &mut String, log: &LoggedPath, colour: &str, p: &Projection) {
    let path: String = log
        .points
        .iter()
        .map(|&(x, y)| format!("{:.1},{:.1} ", p.x(x), p.y(y)))
        .collect();
    let _ = writeln!(
        parts,
        r##"<polyline class="logged" points="{path}" fill="none" stroke="{colour}" stroke-width="1.5" stroke-dasharray="5 3"/>"##
    );
    if let Some(&(x, y)) = log.points.last() {
        let _ = writeln!(
            parts,
            r##"<rect x="{:.1}" y="{:.1}" width="6" height="6" fill="{colour}"/>"##,
            p.x(x) - 3.0,
            p.y(y) - 3.0
        );
    }
}

/// A room's outline, home zone and obstacles. The zone is its disc within the room's
/// outline (a quarter disc for a zone centred on a corner, a half disc on a straight wall,
/// whatever is left for any other place), its rim dashed where it runs inside the room;
/// obstacles are drawn over it.
fn draw_room(parts: &mut String, room: &Room, p: &Projection) {
    let _ = writeln!(
        parts,
        r##"<polygon points="{}" fill="#fafafa" stroke="#222" stroke-width="2"/>"##,
        p.polygon(&room.outline)
    );
    draw_zone(parts, room, room.home_zone, HOME_COLOUR, p);
    for o in &room.obstacles {
        let _ = writeln!(
            parts,
            r##"<polygon points="{}" fill="#888" stroke="#222"/>"##,
            p.polygon(o)
        );
    }
}

/// The home zone's colour in the figures.
const HOME_COLOUR: &str = "#1f77b4";
/// The goal zone's colour in the figures.
pub const GOAL_COLOUR: &str = "#ff7f0e";
/// The waypoints' colour in the figures.
pub const WAYPOINT_COLOUR: &str = "#9467bd";

/// What the trajectory figure's caption says of the rooms' missions (nothing when no room has
/// one, so the paper's figures keep their bytes).
fn mission_caption<'a>(rooms: impl Iterator<Item = &'a Room> + Clone) -> String {
    let goal = rooms.clone().any(|r| r.mission.goal.is_some());
    let waypoints = rooms.clone().any(|r| !r.mission.waypoints.is_empty());
    let mut s = String::new();
    if goal {
        s.push_str("orange: goal zone; ");
    }
    if waypoints {
        s.push_str("purple: waypoints, numbered in order; ");
    }
    s
}

/// A room's mission: its goal zone and its waypoints (numbered from 1), each a disc within the
/// room with a dashed rim, like the home zone, in colours of their own.
fn draw_mission(parts: &mut String, room: &Room, p: &Projection) {
    if let Some(goal) = room.mission.goal {
        draw_zone(parts, room, goal, GOAL_COLOUR, p);
        let _ = writeln!(
            parts,
            r##"<text x="{:.1}" y="{:.1}" text-anchor="middle" fill="{GOAL_COLOUR}" font-weight="bold">goal</text>"##,
            p.x(goal.centre.x),
            p.y(goal.centre.y) + 4.0
        );
    }
    for (k, w) in room.mission.waypoints.iter().enumerate() {
        draw_zone(parts, room, *w, WAYPOINT_COLOUR, p);
        let _ = writeln!(
            parts,
            r##"<text x="{:.1}" y="{:.1}" text-anchor="middle" fill="{WAYPOINT_COLOUR}" font-weight="bold">{}</text>"##,
            p.x(w.centre.x),
            p.y(w.centre.y) + 4.0,
            k + 1
        );
    }
}

/// A zone drawn as its disc within the room's outline, filled lightly in `colour`, its rim
/// dashed where it runs inside the room.
fn draw_zone(parts: &mut String, room: &Room, zone: Zone, colour: &str, p: &Projection) {
    let (floor, rim) = zone_within(room, zone);
    if floor.len() >= 3 {
        let _ = writeln!(
            parts,
            r##"<polygon points="{}" fill="{colour}" fill-opacity="0.10" stroke="none"/>"##,
            p.polygon(&floor)
        );
    }
    let d: String = rim
        .iter()
        .map(|run| {
            let pts: Vec<String> = run
                .iter()
                .map(|q| format!("{:.1},{:.1}", p.x(q.x), p.y(q.y)))
                .collect();
            format!("M{}", pts.join("L"))
        })
        .collect();
    if !d.is_empty() {
        let _ = writeln!(
            parts,
            r##"<path d="{d}" fill="none" stroke="{colour}" stroke-opacity="0.6" stroke-dasharray="4 3"/>"##
        );
    }
}

/// Sides of the polygon standing for the home zone's circle in the figures (every 1.5°).
const ZONE_SIDES: usize = 240;

/// The home zone within the room, in mm: the room's outline clipped to the zone's disc (a
/// 240-gon; Sutherland–Hodgman, exact for a convex clip region and any simple outline; where
/// the result falls apart in pieces they are joined by zero-width seams along the rim, which
/// the unstroked fill does not show), and the runs of the rim inside the outline.
fn zone_within(room: &Room, zone: Zone) -> (Vec<Vec2>, Vec<Vec<Vec2>>) {
    let circle: Vec<Vec2> = (0..ZONE_SIDES)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / ZONE_SIDES as f64;
            Vec2::new(
                zone.centre.x + zone.radius * a.cos(),
                zone.centre.y + zone.radius * a.sin(),
            )
        })
        .collect();
    // The circle runs counter-clockwise: inside its edge a → b means on the left.
    let mut poly = room.outline.clone();
    for (k, &a) in circle.iter().enumerate() {
        let b = circle[(k + 1) % circle.len()];
        let side = |q: Vec2| (b - a).cross(q - a);
        let mut out = Vec::with_capacity(poly.len() + 2);
        for (i, &cur) in poly.iter().enumerate() {
            let prev = poly[(i + poly.len() - 1) % poly.len()];
            let (sc, sp) = (side(cur), side(prev));
            if (sc >= 0.0) != (sp >= 0.0) {
                out.push(prev + (cur - prev) * (sp / (sp - sc)));
            }
            if sc >= 0.0 {
                out.push(cur);
            }
        }
        poly = out;
        if poly.is_empty() {
            break;
        }
    }
    // The rim's runs of sides inside the outline, each from its first point to its last, so
    // the dashes run on along a run (a path's dashes restart at every move).
    let n = circle.len();
    let inside: Vec<bool> = (0..n)
        .map(|k| point_in_polygon(&room.outline, (circle[k] + circle[(k + 1) % n]) * 0.5))
        .collect();
    let mut rim: Vec<Vec<Vec2>> = Vec::new();
    let start = (0..n).find(|&k| !inside[k]).map_or(0, |k| k + 1);
    for k in (start..start + n).map(|k| k % n) {
        if !inside[k] {
            continue;
        }
        if k == start % n || !inside[(k + n - 1) % n] || rim.is_empty() {
            rim.push(vec![circle[k]]);
        }
        rim.last_mut().expect("a run").push(circle[(k + 1) % n]);
    }
    (poly, rim)
}

/// The path of the executed steps, with a tick per step.
fn draw_path(parts: &mut String, tr: &Trajectory, p: &Projection) {
    let executed = tr.executed();
    let path: String = tr.poses[..=executed]
        .iter()
        .map(|q| format!("{:.1},{:.1} ", p.x(q.x), p.y(q.y)))
        .collect();
    let _ = writeln!(
        parts,
        r##"<polyline points="{path}" fill="none" stroke="#d62728" stroke-width="1"/>"##
    );
    // One marker per executed step: a short tick along the heading after the step, so
    // turns on the spot show as several ticks on one point.
    let ticks: String = tr.poses[1..=executed]
        .iter()
        .map(|q| {
            format!(
                "M{:.1} {:.1}l{:.1} {:.1}",
                p.x(q.x),
                p.y(q.y),
                TICK * q.heading.cos(),
                -TICK * q.heading.sin()
            )
        })
        .collect();
    let _ = writeln!(
        parts,
        r##"<path d="{ticks}" stroke="#7f1d1d" stroke-width="0.8" fill="none"/>"##
    );
}

/// The home pose (circle and heading) and the end of the trial (ringed when it ended at home).
fn draw_home_and_end(parts: &mut String, room: &Room, tr: &Trajectory, p: &Projection) {
    let home = room.home;
    let r = 27.5 * p.scale;
    let _ = writeln!(
        parts,
        r##"<circle cx="{:.1}" cy="{:.1}" r="{r:.1}" fill="none" stroke="#2ca02c" stroke-width="2"/><line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#2ca02c" stroke-width="2"/>"##,
        p.x(home.x),
        p.y(home.y),
        p.x(home.x),
        p.y(home.y),
        p.x(home.x + 2.0 * 27.5 * home.heading.cos()),
        p.y(home.y + 2.0 * 27.5 * home.heading.sin())
    );
    if let Some(end) = tr.poses.last() {
        let executed = tr.executed();
        let at_home = executed < tr.len();
        let _ = writeln!(
            parts,
            r##"<circle cx="{:.1}" cy="{:.1}" r="{r:.1}" fill="#d62728" fill-opacity="0.5" stroke="{}" stroke-width="1.5"><title>{}</title></circle>"##,
            p.x(end.x),
            p.y(end.y),
            if at_home { "#000" } else { "none" },
            if at_home {
                format!("back in the home zone after step {executed}: the trial ended")
            } else {
                format!("end of the trial after {} steps", tr.len())
            }
        );
    }
}

/// The frame of one per-generation panel over the plot area `(x0, x1, y0, y1)`: title, grid
/// lines and labels at round values of F (0, 0.2, …, 1), axes, round generation numbers on
/// the x axis and the axis labels (the x label's baseline 32 px below the axis).
fn panel_frame(
    s: &mut String,
    name: &str,
    (x0, x1, y0, y1): (f64, f64, f64, f64),
    generations: usize,
    y_label: &str,
) {
    let (x0, x1, y0, y1) = (px(x0), px(x1), px(y0), px(y1));
    let y = |f: f64| y0 + (y1 - y0) * f;
    let _ = writeln!(
        s,
        r#"<text x="{}" y="18" text-anchor="middle" font-weight="bold">{}</text>"#,
        px((x0 + x1) / 2.0),
        esc(name)
    );
    let y_ticks = Ticks::nice(0.0, 1.0, 5, false);
    for &f in &y_ticks.values {
        let _ = writeln!(
            s,
            r##"<line x1="{x0}" x2="{x1}" y1="{yy:.1}" y2="{yy:.1}" stroke="#ddd"/><text x="{}" y="{:.1}" text-anchor="end">{}</text>"##,
            x0 - 6.0,
            y(f) + 4.0,
            y_ticks.label(f),
            yy = y(f)
        );
    }
    let _ = writeln!(
        s,
        r##"<line x1="{x0}" x2="{x1}" y1="{y0}" y2="{y0}" stroke="#000"/><line x1="{x0}" x2="{x0}" y1="{y0}" y2="{y1}" stroke="#000"/>"##
    );
    let last = generations.saturating_sub(1);
    let n = last.max(1) as f64;
    let x_ticks = Ticks::nice(0.0, last as f64, 6, true);
    for &g in &x_ticks.values {
        let xx = x0 + (x1 - x0) * g / n;
        let _ = writeln!(
            s,
            r##"<line x1="{xx:.1}" x2="{xx:.1}" y1="{y0}" y2="{}" stroke="#000"/><text x="{xx:.1}" y="{}" text-anchor="middle">{}</text>"##,
            y0 + 4.0,
            y0 + 17.0,
            x_ticks.label(g)
        );
    }
    axis_labels(s, (x0, x1, y0, y1), y0 + 32.0, "generation", y_label);
}

/// The x-axis label under a plot area `(x0, x1, y0, y1)`, its baseline at `x_label_y`, and
/// the y-axis label turned along the left edge.
fn axis_labels(
    s: &mut String,
    (x0, x1, y0, y1): (f64, f64, f64, f64),
    x_label_y: f64,
    x: &str,
    y: &str,
) {
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{x_label_y}" text-anchor="middle">{}</text>"#,
        px((x0 + x1) / 2.0),
        esc(x)
    );
    let (cx, cy) = (px(x0 - 36.0), px((y0 + y1) / 2.0));
    let _ = writeln!(
        s,
        r#"<text x="{cx}" y="{cy}" text-anchor="middle" transform="rotate(-90 {cx} {cy})">{}</text>"#,
        esc(y)
    );
}

/// One panel per run: the population means of the fitness terms a, g, l, b per generation.
pub fn terms_svg(panels: &[(String, Vec<GenerationRecord>)]) -> String {
    terms_svg_of(panels, &term_curves(&[], &[]))
}

/// The paper's terms in the terms figure: term, legend and colour.
const PAPER_TERM_CURVES: [(TermId, &str, &str); 4] = [
    (TermId::A, "a exploration", "#2ca02c"),
    (TermId::G, "g homing", "#9467bd"),
    (TermId::L, "l recognition", "#8c564b"),
    (TermId::B, "b battery", "#ff7f0e"),
];

/// Colours of the terms beyond a, g, l, b in the terms figure, in turn.
const EXTRA_TERM_COLOURS: [&str; 6] = [
    "#d62728", "#17becf", "#bcbd22", "#e377c2", "#7f7f7f", "#1f77b4",
];

/// One curve of the terms figure: its legend, colour and term.
#[derive(Debug, Clone, PartialEq)]
pub struct TermCurve {
    /// The legend.
    pub label: String,
    /// The colour.
    pub colour: &'static str,
    /// The term drawn.
    pub term: TermId,
}

/// The curves of a run's terms figure. The paper's motivations (`table` empty: a run record's
/// [`MotivationsRecord::table`]) give the paper's a, g, l, b. Others give one curve per
/// motivation, in input order, named as its title names it with the term it weighs
/// ([`motivation_label`]: `curiosity (a)`, `urgency`, `hurry (urgency)`), the paper's terms in
/// their colours; the terms no motivation weighs (a mission's `goal` and `safety` when only
/// `urgency` is weighed) are not drawn: `extra` ([`extra_terms`]) resolves the user terms.
///
/// [`MotivationsRecord::table`]: fuzzymotiv_records::records::MotivationsRecord
/// [`extra_terms`]: fuzzymotiv_records::records::extra_terms
pub fn term_curves(table: &[MotivationEntry], extra: &[(String, TermId)]) -> Vec<TermCurve> {
    if table.is_empty() {
        return (PAPER_TERM_CURVES.iter())
            .map(|&(term, label, colour)| TermCurve {
                label: label.into(),
                colour,
                term,
            })
            .collect();
    }
    let mut others = 0;
    let mut curves = Vec::new();
    for m in table {
        let user = || extra.iter().find(|(n, _)| *n == m.term).map(|(_, id)| *id);
        let Some(term) = TermId::library(&m.term).or_else(user) else {
            continue;
        };
        let colour = match PAPER_TERM_CURVES.iter().find(|(t, ..)| *t == term) {
            Some((_, _, c)) => c,
            None => {
                others += 1;
                EXTRA_TERM_COLOURS[(others - 1) % EXTRA_TERM_COLOURS.len()]
            }
        };
        let label = motivation_label(m);
        curves.push(TermCurve {
            label,
            colour,
            term,
        });
    }
    curves
}

/// A motivation with the term it weighs: its name, and the term in brackets when the two
/// differ (`curiosity (a)`, `hurry (urgency)`, `urgency`).
pub fn motivation_label(m: &MotivationEntry) -> String {
    if m.name == m.term {
        m.name.clone()
    } else {
        format!("{} ({})", m.name, m.term)
    }
}

/// The terms figure of `curves` ([`term_curves`]): one panel per run, a curve per term.
pub fn terms_svg_of(panels: &[(String, Vec<GenerationRecord>)], curves: &[TermCurve]) -> String {
    let ph = 300.0;
    // The legend's column: 135 px, wider for a longer name than the paper's.
    let legend = (curves.iter()).map(|c| px(text_width(&c.label, false) + 30.0));
    let (ml, mr, mt, mb) = (50.0, legend.fold(135.0, f64::max), 30.0, 40.0);
    let widths: Vec<f64> = panels
        .iter()
        // The title is centred over the plot area, left of the panel's centre.
        .map(|(title, _)| px(520f64.max(text_width(title, true) + mr - ml + 10.0)))
        .collect();
    let width = px(widths.iter().sum::<f64>().max(1.0));
    let mut s = open(width, ph, 12);
    let _ = writeln!(s, r#"<rect width="{width}" height="{ph}" fill="white"/>"#);
    let mut ox = 0.0;
    for ((name, hist), pw) in panels.iter().zip(&widths) {
        let (x0, x1, y0, y1) = (ox + ml, ox + pw - mr, ph - mb, mt);
        let n = hist.len().max(2) as f64 - 1.0;
        let x = |g: usize| x0 + (x1 - x0) * g as f64 / n;
        let y = |f: f64| y0 + (y1 - y0) * f.clamp(0.0, 1.0);
        panel_frame(
            &mut s,
            name,
            (x0, x1, y0, y1),
            hist.len(),
            "population mean",
        );
        let mut ly = y1 + 10.0;
        for TermCurve {
            label,
            colour,
            term,
        } in curves
        {
            let pick = |r: &GenerationRecord| r.terms.get(*term);
            let pts: String = hist
                .iter()
                .enumerate()
                .map(|(g, r)| format!("{:.1},{:.1} ", x(g), y(pick(r))))
                .collect();
            // A term at 0 throughout (l when O = 0) lies on the x axis: dashed and wider, so
            // it shows there, and its legend says so.
            let zero = !hist.is_empty() && hist.iter().all(|r| pick(r) == 0.0);
            let dash = if zero {
                r#" stroke-width="3" stroke-dasharray="6 4""#
            } else {
                r#" stroke-width="1.8""#
            };
            let _ = writeln!(
                s,
                r#"<polyline points="{pts}" fill="none" stroke="{colour}"{dash} stroke-linejoin="round"/>"#
            );
            let lx = px(x1 + 10.0);
            let _ = writeln!(
                s,
                r#"<line x1="{lx}" x2="{}" y1="{ly}" y2="{ly}" stroke="{colour}"{dash}/><text x="{}" y="{}">{}</text>"#,
                px(lx + 16.0),
                px(lx + 20.0),
                ly + 4.0,
                esc(label)
            );
            if zero {
                ly += 14.0;
                let _ = writeln!(
                    s,
                    r##"<text x="{}" y="{}" font-size="10" fill="#555">(0 throughout)</text>"##,
                    px(lx + 20.0),
                    ly + 4.0
                );
            }
            ly += 16.0;
        }
        ox += pw;
    }
    s.push_str("</svg>\n");
    s
}

/// The title of the shared labels' membership figure.
pub const MEMBERSHIP_TITLE: &str = "Membership of a fitness value y in each label";

/// The triangular membership functions μ(y) of the fuzzy labels (V.L. … V.H. by default), for
/// the paper's four terms (the report names the run's own terms through [`membership_svg_of`]).
pub fn membership_svg(peaks: &[f64], names: &[String]) -> String {
    membership_svg_of(
        peaks,
        names,
        MEMBERSHIP_TITLE,
        "fitness value y (a, g, l or b)",
    )
}

/// [`membership_svg`] with its own title and x-axis label (a motivation's own labels).
pub fn membership_svg_of(peaks: &[f64], names: &[String], title: &str, x_label: &str) -> String {
    let (w, h) = (420.0, 214.0);
    let (x0, x1, y0, y1) = (50.0, w - 15.0, h - 49.0, 48.0);
    let (lo, hi) = (
        peaks.first().copied().unwrap_or(0.0).min(0.0),
        peaks.last().copied().unwrap_or(1.0).max(1.0),
    );
    let x = |v: f64| x0 + (x1 - x0) * (v - lo) / (hi - lo);
    let y = |m: f64| y0 + (y1 - y0) * m;
    let mut s = open(w, h, 12);
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="16" text-anchor="middle" font-weight="bold">{}</text>"#,
        (x0 + x1) / 2.0,
        esc(title)
    );
    let _ = writeln!(
        s,
        r##"<line x1="{x0}" x2="{x1}" y1="{y0}" y2="{y0}" stroke="#000"/><line x1="{x0}" x2="{x0}" y1="{y0}" y2="{y1}" stroke="#000"/>"##
    );
    let y_ticks = Ticks::nice(0.0, 1.0, 2, false);
    for &m in &y_ticks.values {
        let _ = writeln!(
            s,
            r##"<line x1="{}" x2="{x0}" y1="{yy:.1}" y2="{yy:.1}" stroke="#000"/><text x="{}" y="{:.1}" text-anchor="end">{}</text>"##,
            x0 - 4.0,
            x0 - 6.0,
            y(m) + 4.0,
            y_ticks.label(m),
            yy = y(m)
        );
    }
    let x_ticks = Ticks::nice(lo, hi, 5, false);
    for &v in &x_ticks.values {
        let _ = writeln!(
            s,
            r##"<line x1="{xx:.1}" x2="{xx:.1}" y1="{y0}" y2="{}" stroke="#000"/><text x="{xx:.1}" y="{}" text-anchor="middle">{}</text>"##,
            y0 + 4.0,
            y0 + 19.0,
            x_ticks.label(v),
            xx = x(v)
        );
    }
    axis_labels(&mut s, (x0, x1, y0, y1), h - 8.0, x_label, "μ(y)");
    membership_triangles(&mut s, peaks, names, (lo, hi), &x, &y);
    s.push_str("</svg>\n");
    s
}

/// One triangle per label (the outer ones open to the range's ends), named at its peak.
fn membership_triangles(
    s: &mut String,
    peaks: &[f64],
    names: &[String],
    (lo, hi): (f64, f64),
    x: &dyn Fn(f64) -> f64,
    y: &dyn Fn(f64) -> f64,
) {
    for (k, &p) in peaks.iter().enumerate() {
        let left = if k == 0 { lo } else { peaks[k - 1] };
        let right = if k + 1 == peaks.len() {
            hi
        } else {
            peaks[k + 1]
        };
        let (ml, mr) = (
            if k == 0 { 1.0 } else { 0.0 },
            if k + 1 == peaks.len() { 1.0 } else { 0.0 },
        );
        let c = colour(k);
        let _ = writeln!(
            s,
            r#"<polyline points="{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}" fill="none" stroke="{c}" stroke-width="2"/>"#,
            x(left),
            y(ml),
            x(p),
            y(1.0),
            x(right),
            y(mr)
        );
        // Named above the peak; the labels at the ends of the range start or end there, so
        // they stay inside the plot and clear of the y axis's tick labels.
        let name = names.get(k).map_or("", String::as_str);
        let half = text_width(name, true) / 2.0;
        let (lx, anchor) = if x(p) - half < x(lo) {
            (x(lo) + 2.0, "start")
        } else if x(p) + half > x(hi) {
            (x(hi), "end")
        } else {
            (x(p), "middle")
        };
        let _ = writeln!(
            s,
            r#"<text x="{lx:.1}" y="{:.1}" text-anchor="{anchor}" fill="{c}" font-weight="bold">{}</text>"#,
            y(1.0) - 6.0,
            esc(name)
        );
    }
}

/// One room's place on a SOM line: its r-node and the winners of its test runs.
pub struct SomRoom<'a> {
    /// Room name.
    pub name: &'a str,
    /// The stored instance's winning node.
    pub r_node: usize,
    /// Winning nodes of the room's test runs.
    pub winners: Vec<usize>,
}

/// The 1-D SOM as a line of `nodes` nodes; per room its r-node (a labelled marker with the
/// ±`threshold` window a test winner must fall in) and its test runs' winners (dots below).
pub fn som_svg(title: &str, nodes: usize, threshold: usize, rooms: &[SomRoom<'_>]) -> String {
    let w = 840.0;
    let (x0, x1) = (40.0, w - 40.0);
    let line_y = 70.0 + 16.0 * rooms.len() as f64;
    let max_dots = rooms
        .iter()
        .flat_map(|r| {
            r.winners.iter().map(|&n| {
                rooms
                    .iter()
                    .flat_map(|q| q.winners.iter())
                    .filter(|&&m| m == n)
                    .count()
            })
        })
        .max()
        .unwrap_or(0);
    let h = line_y + 40.0 + 9.0 * max_dots as f64 + 46.0;
    let last = nodes.saturating_sub(1).max(1) as f64;
    let x = |n: f64| x0 + (x1 - x0) * n / last;
    let mut s = open(w, format_args!("{h:.0}"), 12);
    let _ = writeln!(s, r#"<rect width="{w}" height="{h:.0}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{x0}" y="18" font-weight="bold">{}</text>"#,
        esc(title)
    );
    som_instances(&mut s, rooms, nodes, threshold, line_y, &x);
    som_axis(&mut s, nodes, line_y, (x0, x1), &x);
    som_winners(&mut s, rooms, nodes, line_y, &x);
    // The caption in two lines, each shorter than the figure is wide.
    let _ = writeln!(
        s,
        r##"<text x="{x0}" y="{:.0}" fill="#555">SOM node index (0–{}). Marker: a room's stored instance (r-node); band: ±{threshold} nodes around it.</text>"##,
        h - 26.0,
        nodes.saturating_sub(1)
    );
    let _ = writeln!(
        s,
        r##"<text x="{x0}" y="{:.0}" fill="#555">Dots: the winning nodes of the test runs, coloured by the room each run was in.</text>"##,
        h - 10.0,
    );
    s.push_str("</svg>\n");
    s
}

/// The last node's index on a SOM line of `nodes` nodes (at least 1, so the line has a length).
fn last_node(nodes: usize) -> f64 {
    nodes.saturating_sub(1).max(1) as f64
}

/// Each room's r-node on the SOM line, with its threshold band and label.
fn som_instances(
    s: &mut String,
    rooms: &[SomRoom<'_>],
    nodes: usize,
    threshold: usize,
    line_y: f64,
    x: &dyn Fn(f64) -> f64,
) {
    for (k, r) in rooms.iter().enumerate() {
        let c = colour(k);
        let (a, b) = (
            r.r_node.saturating_sub(threshold) as f64,
            (r.r_node + threshold).min(nodes.saturating_sub(1)) as f64,
        );
        let _ = writeln!(
            s,
            r#"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="14" fill="{c}" fill-opacity="0.15"/>"#,
            x(a),
            line_y - 7.0,
            (x(b) - x(a)).max(1.0)
        );
        let ly = 40.0 + 16.0 * k as f64;
        let xr = x(r.r_node as f64);
        // The label right of its marker line, or left of it where it would pass the right
        // end of the line.
        let label = format!("{} (r-node {})", r.name, r.r_node);
        let (lx, anchor) = if xr + 4.0 + text_width(&label, true) > x(last_node(nodes)) + 30.0 {
            (xr - 4.0, "end")
        } else {
            (xr + 4.0, "start")
        };
        let _ = writeln!(
            s,
            r#"<line x1="{xr:.1}" x2="{xr:.1}" y1="{:.1}" y2="{:.1}" stroke="{c}" stroke-width="1.5"/><circle cx="{xr:.1}" cy="{line_y}" r="5" fill="{c}"/><text x="{lx:.1}" y="{:.1}" text-anchor="{anchor}" fill="{c}" font-weight="bold">{}</text>"#,
            ly + 2.0,
            line_y,
            ly,
            esc(&label),
        );
    }
}

/// The SOM line with node ticks.
fn som_axis(
    s: &mut String,
    nodes: usize,
    line_y: f64,
    (x0, x1): (f64, f64),
    x: &dyn Fn(f64) -> f64,
) {
    let _ = writeln!(
        s,
        r##"<line x1="{x0}" x2="{x1}" y1="{line_y}" y2="{line_y}" stroke="#222" stroke-width="2"/>"##
    );
    let ticks = Ticks::nice(0.0, last_node(nodes), 10, true);
    for &n in &ticks.values {
        let _ = writeln!(
            s,
            r##"<line x1="{xn:.1}" x2="{xn:.1}" y1="{}" y2="{}" stroke="#222"/><text x="{xn:.1}" y="{}" text-anchor="middle" fill="#555">{}</text>"##,
            line_y - 4.0,
            line_y + 4.0,
            line_y + 18.0,
            ticks.label(n),
            xn = x(n)
        );
    }
}

/// The test runs' winners, stacked below their node, coloured by true room.
fn som_winners(
    s: &mut String,
    rooms: &[SomRoom<'_>],
    nodes: usize,
    line_y: f64,
    x: &dyn Fn(f64) -> f64,
) {
    let mut stack = vec![0usize; nodes.max(1)];
    for (k, r) in rooms.iter().enumerate() {
        for &n in &r.winners {
            let n = n.min(nodes.saturating_sub(1));
            let dy = line_y + 30.0 + 9.0 * stack[n] as f64;
            stack[n] += 1;
            let _ = writeln!(
                s,
                r#"<circle cx="{:.1}" cy="{dy:.1}" r="3.5" fill="{}"/>"#,
                x(n as f64),
                colour(k)
            );
        }
    }
}

/// One sweep setting with its mean outcomes over rooms and replicates.
pub struct SettingPoint {
    /// The setting's key.
    pub label: String,
    /// Its motivations (C, H, O, E).
    pub motivations: [f64; 4],
    /// Mean exploration %, recognition %, battery %, homing % (None when not measured).
    pub values: [Option<f64>; 4],
    /// Their sample standard deviations (None for fewer than two values).
    pub spread: [Option<f64>; 4],
    /// How many values (rooms × replicates) each mean is over.
    pub n: [usize; 4],
}

/// A colour for a value in [0, 100]: dark blue → teal → yellow.
fn value_colour(v: f64) -> String {
    let t = (v / 100.0).clamp(0.0, 1.0);
    let stops = [
        (68.0, 1.0, 84.0),
        (33.0, 145.0, 140.0),
        (253.0, 231.0, 37.0),
    ];
    let (a, b, u) = if t < 0.5 {
        (stops[0], stops[1], t * 2.0)
    } else {
        (stops[1], stops[2], (t - 0.5) * 2.0)
    };
    let mix = |x: f64, y: f64| (x + (y - x) * u).round() as u8;
    format!(
        "#{:02x}{:02x}{:02x}",
        mix(a.0, b.0),
        mix(a.1, b.1),
        mix(a.2, b.2)
    )
}

/// How each motivation shapes the outcomes: one panel per outcome. Many settings are drawn as
/// points on the (C, H, E) simplex coloured by the outcome; a few as labelled bars.
pub fn sweep_summary_svg(points: &[SettingPoint]) -> String {
    const OUTCOMES: [&str; 4] = [
        "% optimal exploration",
        "% recognition",
        "% battery usage",
        "% homing",
    ];
    let ternary = points.len() >= 6;
    let (pw, ph) = if ternary {
        (330.0, 330.0)
    } else {
        (390.0, 60.0 + 22.0 * points.len() as f64)
    };
    let width = pw * 4.0;
    let height = ph + 56.0;
    let mut s = open(width, height, 11);
    let _ = writeln!(
        s,
        r#"<rect width="{width}" height="{height}" fill="white"/>"#
    );
    for (k, name) in OUTCOMES.iter().enumerate() {
        let ox = k as f64 * pw;
        let _ = writeln!(
            s,
            r#"<text x="{}" y="18" text-anchor="middle" font-weight="bold" font-size="13">{name}</text>"#,
            ox + pw / 2.0
        );
        if ternary {
            ternary_panel(&mut s, points, k, ox, pw, height);
        } else {
            bars_panel(&mut s, points, k, ox);
        }
    }
    let _ = writeln!(
        s,
        r##"<text x="8" y="{:.0}" fill="#555">{}</text>"##,
        height - 6.0,
        if ternary {
            "Means over rooms and replicates per motivation setting (C, H, O, E); under each panel the range of their sample std and n; each point's tooltip gives its own."
        } else {
            "Means over rooms and replicates per motivation setting (C, H, O, E); whiskers ± 1 sample std; n values per mean."
        }
    );
    s.push_str("</svg>\n");
    s
}

/// Panel `k` of [`sweep_summary_svg`] for many settings: each a point on the (C, H, E)
/// simplex coloured by outcome `k`, with a colour key.
fn ternary_panel(s: &mut String, points: &[SettingPoint], k: usize, ox: f64, pw: f64, height: f64) {
    let side = pw - 70.0;
    let (x0, y0) = (ox + 35.0, 46.0 + side * 0.866);
    let corner = |c: f64, h: f64, e: f64| {
        let sum = c + h + e;
        let (h, e) = if sum > 0.0 {
            (h / sum, e / sum)
        } else {
            (0.0, 0.0)
        };
        (x0 + side * (h + 0.5 * e), y0 - side * 0.866 * e)
    };
    let (a, b, c) = (
        corner(1.0, 0.0, 0.0),
        corner(0.0, 1.0, 0.0),
        corner(0.0, 0.0, 1.0),
    );
    let _ = writeln!(
        s,
        r##"<polygon points="{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}" fill="none" stroke="#444"/><text x="{:.1}" y="{:.1}" text-anchor="end">C=1</text><text x="{:.1}" y="{:.1}">H=1</text><text x="{:.1}" y="{:.1}" text-anchor="middle">E=1</text>"##,
        a.0,
        a.1,
        b.0,
        b.1,
        c.0,
        c.1,
        a.0 - 8.0,
        a.1 + 14.0,
        b.0 + 8.0,
        b.1 + 14.0,
        c.0,
        c.1 - 10.0
    );
    for p in points {
        let m = p.motivations;
        let (x, y) = corner(m[0], m[1], m[3]);
        match p.values[k] {
            Some(v) => {
                let _ = writeln!(
                    s,
                    r##"<circle cx="{x:.1}" cy="{y:.1}" r="7" fill="{}" stroke="#333" stroke-width="0.5"><title>{}: {}</title></circle>"##,
                    value_colour(v),
                    esc(&p.label),
                    mean_spread_n(p, k)
                );
            }
            None => {
                let _ = writeln!(
                    s,
                    r##"<circle cx="{x:.1}" cy="{y:.1}" r="3" fill="#ccc"/>"##
                );
            }
        }
    }
    let _ = writeln!(
        s,
        r##"<text x="{:.1}" y="{:.1}" fill="#555">{}</text>"##,
        ox + 35.0,
        y0 + 34.0,
        spread_range(points, k)
    );
    // Colour key.
    for i in 0..=10 {
        let v = i as f64 * 10.0;
        let _ = writeln!(
            s,
            r#"<rect x="{:.1}" y="{:.1}" width="20" height="6" fill="{}"/>"#,
            ox + 40.0 + 22.0 * i as f64,
            height - 42.0,
            value_colour(v)
        );
    }
    // The key's scale: value v at ox + 50 + 2.2 v (the swatches' centres), labelled at round
    // values.
    let ticks = Ticks::nice(0.0, 100.0, 5, true);
    for &v in &ticks.values {
        let _ = writeln!(
            s,
            r##"<line x1="{xv:.1}" x2="{xv:.1}" y1="{:.1}" y2="{:.1}" stroke="#333"/><text x="{xv:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
            height - 36.0,
            height - 33.0,
            height - 22.0,
            ticks.label(v),
            xv = ox + 50.0 + 2.2 * v
        );
    }
}

/// "56.7 ± 50.1, n 15": outcome `k` of a setting, its sample std (when there are two values
/// or more) and how many values the mean is over.
fn mean_spread_n(p: &SettingPoint, k: usize) -> String {
    let mean = p.values[k].map_or("—".to_string(), |v| format!("{v:.1}"));
    let spread = p.spread[k].map_or(String::new(), |d| format!(" ± {d:.1}"));
    format!("{mean}{spread}, n {}", p.n[k])
}

/// "± std 12.0 to 50.1, n 15": the range of outcome `k`'s sample std and n over the settings.
fn spread_range(points: &[SettingPoint], k: usize) -> String {
    let range = |v: Vec<f64>, d: usize| match (
        v.iter().copied().reduce(f64::min),
        v.iter().copied().reduce(f64::max),
    ) {
        (Some(lo), Some(hi)) if lo == hi => format!("{lo:.d$}"),
        (Some(lo), Some(hi)) => format!("{lo:.d$} to {hi:.d$}"),
        _ => "—".to_string(),
    };
    let spreads = points.iter().filter_map(|p| p.spread[k]).collect();
    let ns = points.iter().map(|p| p.n[k] as f64).collect();
    format!("± std {}, n {} per point", range(spreads, 1), range(ns, 0))
}

/// Panel `k` of [`sweep_summary_svg`] for a few settings: one labelled bar each (the mean),
/// a whisker of ± 1 sample std and the numbers with n, over a scale from 0 to 100 with ticks
/// at round values.
fn bars_panel(s: &mut String, points: &[SettingPoint], k: usize, ox: f64) {
    const SCALE: f64 = 1.3;
    let axis_y = 40.0 + 22.0 * points.len() as f64;
    let at = |v: f64| ox + 130.0 + SCALE * v.clamp(0.0, 100.0);
    let _ = writeln!(
        s,
        r##"<line x1="{:.1}" x2="{:.1}" y1="{axis_y:.1}" y2="{axis_y:.1}" stroke="#333"/>"##,
        at(0.0),
        at(100.0)
    );
    let ticks = Ticks::nice(0.0, 100.0, 5, true);
    for &v in &ticks.values {
        let _ = writeln!(
            s,
            r##"<line x1="{xv:.1}" x2="{xv:.1}" y1="{axis_y:.1}" y2="{:.1}" stroke="#333"/><text x="{xv:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
            axis_y + 3.0,
            axis_y + 14.0,
            ticks.label(v),
            xv = at(v)
        );
    }
    for (i, p) in points.iter().enumerate() {
        let y = 40.0 + 22.0 * i as f64;
        let m = p.motivations;
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}">({},{},{},{})</text>"#,
            ox + 8.0,
            y + 12.0,
            m[0],
            m[1],
            m[2],
            m[3]
        );
        if let Some(v) = p.values[k] {
            let _ = writeln!(
                s,
                r##"<rect x="{:.1}" y="{y:.1}" width="{:.1}" height="15" fill="{}"/>"##,
                at(0.0),
                at(v) - at(0.0),
                value_colour(v),
            );
            if let Some(d) = p.spread[k] {
                let (lo, hi, mid) = (at(v - d), at(v + d), y + 7.5);
                let _ = writeln!(
                    s,
                    r##"<path d="M{lo:.1},{:.1}V{:.1}M{lo:.1},{mid:.1}H{hi:.1}M{hi:.1},{:.1}V{:.1}" stroke="#000" stroke-width="1.2" fill="none" class="spread"/>"##,
                    mid - 4.0,
                    mid + 4.0,
                    mid - 4.0,
                    mid + 4.0
                );
            }
        }
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}">{}</text>"#,
            at(100.0) + 6.0,
            y + 12.0,
            mean_spread_n(p, k)
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::text_width_at;
    use fuzzymotiv::evolution::Stats;
    use fuzzymotiv::experiment::GenerationRecord;
    use fuzzymotiv::simulation::{BUILTIN_ROOMS, Room};

    /// An attribute's value in an element's start tag (`head`: the text after `<name`).
    fn attr(head: &str, name: &str) -> Option<String> {
        let start = head.find(&format!(" {name}=\""))? + name.len() + 3;
        Some(head[start..].split('"').next()?.to_string())
    }

    /// XML text content back to characters (the escapes [`esc`] writes).
    fn unescape(s: &str) -> String {
        s.replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&quot;", "\"")
            .replace("&amp;", "&")
    }

    /// An estimated text box: `(left, right, top, bottom)` and the text.
    type TextBox = (f64, f64, f64, f64, String);

    /// The estimated box of every `<text>` of a figure, from its x, y, font-size (else the
    /// root's), font-weight, text-anchor and content: 0.62 × size per character (0.68 bold,
    /// [`text_width_at`]), from a full size above the baseline to a quarter below it
    /// (descenders). Text turned by `rotate(-90 x y)` about its own anchor (the y-axis labels)
    /// is turned with it; any other transform fails the test.
    fn text_boxes(svg: &str) -> Vec<TextBox> {
        let root = svg.split('>').next().unwrap();
        let root_size: f64 = attr(root, "font-size").unwrap().parse().unwrap();
        svg.split("<text")
            .skip(1)
            .map(|el| {
                let (head, rest) = el.split_once('>').unwrap();
                let content = unescape(rest.split("</text>").next().unwrap());
                let num = |name: &str| -> f64 { attr(head, name).unwrap().parse().unwrap() };
                let (x, y) = (num("x"), num("y"));
                let size = attr(head, "font-size").map_or(root_size, |v| v.parse().unwrap());
                let bold = attr(head, "font-weight").is_some_and(|w| w == "bold");
                let w = text_width_at(&content, bold, size);
                let (a, b) = match attr(head, "text-anchor").as_deref() {
                    Some("middle") => (-w / 2.0, w / 2.0),
                    Some("end") => (-w, 0.0),
                    _ => (0.0, w),
                };
                match attr(head, "transform") {
                    None => (x + a, x + b, y - size, y + 0.25 * size, content),
                    Some(t) => {
                        assert_eq!(t, format!("rotate(-90 {x} {y})"), "unhandled transform");
                        // Turned a quarter left about (x, y): along the text is up the page.
                        (x - size, x + 0.25 * size, y - b, y - a, content)
                    }
                }
            })
            .collect()
    }

    /// Asserts every text of `svg` lies inside its viewBox and no two texts overlap.
    fn assert_texts_fit(svg: &str, what: &str) {
        let root = svg.split('>').next().unwrap();
        // The widths below are estimated for the font stack's first font: the figure names it.
        assert_eq!(
            attr(root, "font-family").as_deref(),
            Some(crate::plot::FONT_STACK),
            "{what}: {root}"
        );
        let vb: Vec<f64> = attr(root, "viewBox")
            .unwrap()
            .split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect();
        let boxes = text_boxes(svg);
        assert!(!boxes.is_empty(), "{what}: no text");
        for b in &boxes {
            assert!(
                b.0 >= vb[0] && b.1 <= vb[0] + vb[2] && b.2 >= vb[1] && b.3 <= vb[1] + vb[3],
                "{what}: `{}` outside the viewBox {vb:?}: {b:?}",
                b.4
            );
        }
        for (i, a) in boxes.iter().enumerate() {
            for b in &boxes[i + 1..] {
                let apart = a.1 <= b.0 || b.1 <= a.0 || a.3 <= b.2 || b.3 <= a.2;
                assert!(apart, "{what}: `{}` overlaps `{}`: {a:?} {b:?}", a.4, b.4);
            }
        }
    }

    /// A made-up evolution of `n` generations: F rising, the population minimum jumping.
    fn history(n: usize, seed: usize) -> Vec<GenerationRecord> {
        (0..n)
            .map(|g| {
                let t = g as f64 / n.max(1) as f64;
                let best = 0.5 + 0.4 * t + 0.01 * seed as f64;
                let mean = 0.1 + 0.6 * t + 0.02 * ((g + seed) % 3) as f64;
                GenerationRecord {
                    generation: g,
                    stats: Stats {
                        mean,
                        std: 0.1,
                        min: if g % 2 == 0 { 0.1 } else { mean - 0.05 },
                        max: best,
                    },
                    terms: Default::default(),
                }
            })
            .collect()
    }

    /// Built-in rooms, a room with its home on a wall, and the U room (home in an arm, its
    /// zone crossing two walls).
    fn rooms(n: usize) -> Vec<Room> {
        let wall = Room::from_toml_str(
            "name = \"home-on-a-wall\"\noutline = [[0,0],[800,0],[800,500],[0,500]]\nhome = { x = 400, y = 40, heading_deg = 90 }\n",
            "wall.toml",
        )
        .unwrap();
        let u = Room::from_toml_str(include_str!("../../../rooms/U.toml"), "rooms/U.toml").unwrap();
        let mut all: Vec<Room> = BUILTIN_ROOMS
            .iter()
            .map(|name| Room::builtin(name).unwrap())
            .collect();
        all.insert(1, wall);
        all.insert(3, u);
        (0..n).map(|k| all[k % all.len()].clone()).collect()
    }

    /// Every number in an attribute value of `svg` has at most 2 decimals.
    fn assert_compact_numbers(svg: &str, what: &str) {
        for value in svg.split("=\"").skip(1).filter_map(|v| v.split('"').next()) {
            for token in value.split(|c: char| !(c.is_ascii_digit() || c == '.')) {
                let decimals = token.split_once('.').map_or(0, |(_, d)| d.len());
                assert!(decimals <= 2, "{what}: `{token}` in `{value}`");
            }
        }
    }

    #[test]
    fn figure_attributes_print_numbers_with_at_most_two_decimals() {
        let long = "a title long enough to widen its panel by a fraction of a pixel";
        let runs = vec![
            (long.to_string(), history(7, 1)),
            ("b".into(), history(3, 2)),
        ];
        assert_compact_numbers(&fitness_svg(&runs), "fitness");
        assert_compact_numbers(&terms_svg(&runs), "terms");
        assert_compact_numbers(&membership_svg(&[0.0, 0.3, 1.0], &[]), "membership");
    }

    /// Other motivations than the paper's: a curve per motivation, named with its term, in
    /// input order; the terms no motivation weighs (goal, safety) get none. The paper's: a, g,
    /// l, b as always.
    #[test]
    fn term_curves_follow_the_motivations_and_leave_out_unweighted_terms() {
        let m = |name: &str, term: &str| MotivationEntry {
            name: name.into(),
            term: term.into(),
            weight: 0.5,
        };
        let extra = [
            ("goal".to_string(), TermId::Goal),
            ("urgency".to_string(), TermId::Urgency),
            ("safety".to_string(), TermId::Safety),
        ];
        let curves = term_curves(&[m("curiosity", "a"), m("hurry", "urgency")], &extra);
        let shown: Vec<(&str, TermId)> =
            curves.iter().map(|c| (c.label.as_str(), c.term)).collect();
        assert_eq!(
            shown,
            [
                ("curiosity (a)", TermId::A),
                ("hurry (urgency)", TermId::Urgency)
            ]
        );
        assert_eq!(curves[0].colour, "#2ca02c");
        let paper: Vec<String> = term_curves(&[], &extra)
            .into_iter()
            .map(|c| c.label)
            .collect();
        assert_eq!(
            paper,
            ["a exploration", "g homing", "l recognition", "b battery"]
        );
    }

    #[test]
    fn terms_figure_shows_a_term_at_zero_dashed_and_says_so() {
        let svg = terms_svg(&[("run".to_string(), history(5, 1))]);
        // history() has all terms 0: each is dashed, in the plot and in the legend.
        assert_eq!(svg.matches(r#"stroke-dasharray="6 4""#).count(), 8, "{svg}");
        assert_eq!(svg.matches("(0 throughout)").count(), 4, "{svg}");
        let mut hist = history(5, 1);
        hist[2].terms.a = 0.5;
        let svg = terms_svg(&[("run".to_string(), hist)]);
        assert_eq!(svg.matches("(0 throughout)").count(), 3, "{svg}");
        assert_texts_fit(&svg, "terms with zero terms");
    }

    #[test]
    fn sweep_summary_bars_show_spread_and_n() {
        let p = SettingPoint {
            label: "x".into(),
            motivations: [0.8, 0.1, 0.0, 0.1],
            values: [Some(56.7), Some(28.7), None, Some(100.0)],
            spread: [Some(50.1), None, None, Some(0.0)],
            n: [15, 15, 0, 15],
        };
        let svg = sweep_summary_svg(&[p]);
        assert!(svg.contains("56.7 ± 50.1, n 15"), "{svg}");
        assert!(svg.contains("28.7, n 15"), "{svg}");
        assert_eq!(svg.matches(r#"class="spread""#).count(), 2, "{svg}");
        assert_texts_fit(&svg, "sweep summary bars");
        assert_compact_numbers(&svg, "sweep summary");
    }

    #[test]
    fn axis_ticks_at_round_numbers() {
        let t = Ticks::nice(0.0, 199.0, 6, true);
        assert_eq!(t.values, [0.0, 50.0, 100.0, 150.0]);
        let t = Ticks::nice(0.0, 1.0, 5, false);
        let labels: Vec<_> = t.values.iter().map(|&v| t.label(v)).collect();
        assert_eq!(labels, ["0.0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
        assert_eq!(
            Ticks::nice(0.0, 4.0, 6, true).values,
            [0.0, 1.0, 2.0, 3.0, 4.0]
        );
        assert_eq!(Ticks::nice(0.0, 0.0, 6, true).values, [0.0]);
        let t = Ticks::nice(0.0, 127.0, 10, true);
        assert_eq!(t.step, 20.0);
        assert_eq!(t.label(120.0), "120");
        // Any range: a step of 1, 2 or 5 × 10^k, ticks its multiples inside the range.
        for (lo, hi) in [
            (0.0, 29.0),
            (0.0, 7.0),
            (-3.0, 0.37),
            (0.02, 0.09),
            (0.0, 2e4),
        ] {
            for target in [2, 5, 10] {
                let t = Ticks::nice(lo, hi, target, false);
                let m = t.step / 10f64.powf(t.step.log10().floor());
                assert!(
                    [1.0, 2.0, 5.0].iter().any(|r| (m - r).abs() < 1e-9),
                    "{lo}..{hi}: step {}",
                    t.step
                );
                assert!(!t.values.is_empty() && t.values.len() <= target + 1);
                for &v in &t.values {
                    assert!(v >= lo - 1e-12 && v <= hi + 1e-12);
                    assert!(((v / t.step).round() * t.step - v).abs() < 1e-9);
                }
            }
        }
        // The figures' axes: a 200-generation run is labelled 0, 50, 100, 150, not 0 and 199.
        let svg = fitness_svg(&[("run".into(), history(200, 0))]);
        let texts: Vec<String> = text_boxes(&svg).into_iter().map(|b| b.4).collect();
        for label in ["0", "50", "100", "150", "0.0", "0.2", "1.0"] {
            assert!(texts.iter().any(|t| t == label), "no tick {label}");
        }
        assert!(!texts.iter().any(|t| t == "199"));
        let svg = terms_svg(&[("run".into(), history(30, 0))]);
        let texts: Vec<String> = text_boxes(&svg).into_iter().map(|b| b.4).collect();
        for label in ["0", "5", "10", "15", "20", "25"] {
            assert!(texts.iter().any(|t| t == label), "terms: no tick {label}");
        }
    }

    #[test]
    fn study_fitness_draws_median_and_iqr_over_seeds() {
        // (The quantiles: study.rs's tests.) The drawing: medians as lines, the IQR bands as closed paths, the legend saying so.
        let best: Vec<f64> = (0..10).map(|g| 0.5 + 0.03 * g as f64).collect();
        let mean: Vec<f64> = (0..10).map(|g| 0.1 + 0.05 * g as f64).collect();
        let panel = FitnessPanel {
            title: "high-curiosity [0.8, 0.1, 0.0, 0.1]".into(),
            best: (best.clone(), "median of best F over 5 seeds".into()),
            mean: (mean.clone(), "median of mean F over 5 seeds".into()),
            bands: vec![
                (
                    best.iter().map(|b| (b - 0.05, b + 0.02)).collect(),
                    BEST_BAND,
                ),
                (
                    mean.iter().map(|m| (m - 0.04, m + 0.04)).collect(),
                    MEAN_BAND,
                ),
            ],
            band_label: "IQR over seeds (25th–75th percentile)".into(),
        };
        let svg = fitness_panels_svg(&[panel]);
        for text in [
            "median of best F over 5 seeds",
            "median of mean F over 5 seeds",
            "IQR over seeds (25th–75th percentile)",
        ] {
            assert!(svg.contains(text), "legend lacks {text}");
        }
        assert_eq!(
            svg.matches(r#"fill-opacity="0.45" stroke="none""#).count(),
            2
        );
        assert_eq!(svg.matches("<polyline").count(), 2);
        assert_texts_fit(&svg, "study fitness");
    }

    /// Every figure the program makes, at 1, 2, 5 and 8 rooms (panels, settings), with long
    /// titles: each text inside the viewBox, no two texts overlapping.
    #[test]
    fn no_text_clipped_or_overlapping_at_1_to_8_rooms() {
        let title = "Replay of runs/high-curiosity/best_genome.json (seed 9007199254740991)";
        let names: Vec<String> = fuzzymotiv::fitness::PAPER_LABEL_NAMES
            .iter()
            .map(|s| s.to_string())
            .collect();
        assert_texts_fit(
            &membership_svg(&[0.0, 0.25, 0.5, 0.75, 1.0], &names),
            "membership",
        );
        for n in [1, 2, 5, 8] {
            let rooms = rooms(n);
            let trs: Vec<Trajectory> = rooms
                .iter()
                .map(|r| Trajectory {
                    poses: vec![r.home],
                    ..Default::default()
                })
                .collect();
            let pairs: Vec<_> = rooms.iter().zip(&trs).collect();
            assert_texts_fit(
                &trajectories_svg(title, &pairs),
                &format!("trajectories, {n} rooms"),
            );
            // Per-room training: a panel per room, titled by the report's longest form.
            let panels: Vec<(String, Vec<GenerationRecord>)> = rooms
                .iter()
                .enumerate()
                .map(|(k, r)| {
                    (
                        format!(
                            "high-curiosity (C,H,O,E) = [0.8, 0.1, 0.0, 0.1]: robot evolved in {}",
                            r.name
                        ),
                        history([1, 2, 7, 30, 200][k % 5], k),
                    )
                })
                .collect();
            assert_texts_fit(&fitness_svg(&panels), &format!("fitness, {n} panels"));
            assert_texts_fit(&terms_svg(&panels), &format!("terms, {n} panels"));
            for nodes in [2, 16, 128] {
                let som: Vec<SomRoom<'_>> = rooms
                    .iter()
                    .enumerate()
                    .map(|(k, r)| SomRoom {
                        name: &r.name,
                        r_node: [nodes - 1, 0, nodes / 2, nodes - 2][k % 4],
                        winners: vec![nodes - 1, k % nodes, nodes - 1],
                    })
                    .collect();
                let title = "The rooms on the SOM line of the robot evolved in home-on-a-wall";
                assert_texts_fit(
                    &som_svg(title, nodes, 3, &som),
                    &format!("SOM, {n} rooms, {nodes} nodes"),
                );
            }
            let points: Vec<SettingPoint> = (0..n)
                .map(|k| SettingPoint {
                    label: format!("setting-{k}"),
                    motivations: [0.5, 0.25, 0.0, 0.25],
                    values: [Some(100.0), Some(12.5 * k as f64), None, Some(0.0)],
                    spread: [Some(0.0), Some(50.0), None, Some(3.25)],
                    n: [15, 15, 0, 15],
                })
                .collect();
            assert_texts_fit(
                &sweep_summary_svg(&points),
                &format!("sweep summary, {n} settings"),
            );
        }
    }
}
