//! Hand-written SVG figures: fitness evolution (paper Fig. 6), trajectories (Figs. 7–8), the
//! fitness terms per generation, the membership functions and the rooms' nodes on the SOM line.

use std::fmt::Write as _;

use fuzzymotiv::evolution::GenerationRecord;
use fuzzymotiv::experiment::Experiment;
use fuzzymotiv::room::Room;
use fuzzymotiv::trial::Trajectory;

/// Escapes text for XML/HTML content and attribute values.
pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A generous estimate of the width (px) of `text` at 12 px sans-serif (bold or not): wide
/// enough for DejaVu Sans, the widest of the fonts the PNGs use.
pub fn text_width(text: &str, bold: bool) -> f64 {
    text.chars().count() as f64 * if bold { 8.0 } else { 7.2 }
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

/// One panel per setting: best and mean F per generation, with the min–max band.
pub fn fitness_svg(panels: &[(String, Vec<GenerationRecord>)]) -> String {
    let (pw, ph) = (420.0, 300.0);
    let (ml, mr, mt, mb) = (50.0, 15.0, 30.0, 40.0);
    let width = pw * panels.len() as f64;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{ph}" viewBox="0 0 {width} {ph}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="{width}" height="{ph}" fill="white"/>"#);
    for (p, (name, hist)) in panels.iter().enumerate() {
        let ox = p as f64 * pw;
        let (x0, x1, y0, y1) = (ox + ml, ox + pw - mr, ph - mb, mt);
        let n = hist.len().max(2) as f64 - 1.0;
        let x = |g: usize| x0 + (x1 - x0) * g as f64 / n;
        let y = |f: f64| y0 + (y1 - y0) * f.clamp(0.0, 1.0);
        panel_frame(
            &mut s,
            name,
            (x0, x1, y0, y1),
            ph,
            hist.len(),
            "fuzzy fitness F",
        );
        let mut band = String::new();
        for (g, r) in hist.iter().enumerate() {
            let _ = write!(band, "{:.1},{:.1} ", x(g), y(r.stats.max));
        }
        for (g, r) in hist.iter().enumerate().rev() {
            let _ = write!(band, "{:.1},{:.1} ", x(g), y(r.stats.min));
        }
        let _ = writeln!(
            s,
            r#"<polygon points="{band}" fill="{BAND}" fill-opacity="0.4" stroke="none"/>"#
        );
        for (colour, pick) in [(BEST, 0usize), (MEAN, 1)] {
            let pts: String = hist
                .iter()
                .enumerate()
                .map(|(g, r)| {
                    format!(
                        "{:.1},{:.1} ",
                        x(g),
                        y(if pick == 0 { r.stats.max } else { r.stats.mean })
                    )
                })
                .collect();
            let _ = writeln!(
                s,
                r#"<polyline points="{pts}" fill="none" stroke="{colour}" stroke-width="1.8"/>"#
            );
        }
        fitness_legend(&mut s, x1, y0);
    }
    s.push_str("</svg>\n");
    s
}

/// Colours of the best and mean F curves and of the min–max band.
const BEST: &str = "#d62728";
const MEAN: &str = "#1f77b4";
const BAND: &str = "#9ecae1";

/// The legend of a fitness panel whose plot area ends at `x1` (right) and `y0` (bottom): at the
/// bottom right, on a white box, since the curves rise at the left and run near the top, and
/// below them there is only the band.
fn fitness_legend(s: &mut String, x1: f64, y0: f64) {
    let (lx, ly) = (x1 - 135.0, y0 - 62.0);
    let _ = writeln!(
        s,
        r##"<rect x="{lx}" y="{ly}" width="125" height="54" fill="white" fill-opacity="0.85" stroke="#ccc"/>"##
    );
    for (k, (series, colour)) in [("best", BEST), ("mean", MEAN)].into_iter().enumerate() {
        let row = ly + 12.0 + 16.0 * k as f64;
        let _ = writeln!(
            s,
            r#"<line x1="{}" x2="{}" y1="{row}" y2="{row}" stroke="{colour}" stroke-width="2"/><text x="{}" y="{}">{series} F</text>"#,
            lx + 8.0,
            lx + 28.0,
            lx + 33.0,
            row + 4.0
        );
    }
    let _ = writeln!(
        s,
        r#"<rect x="{}" y="{}" width="20" height="10" fill="{BAND}" fill-opacity="0.4"/><text x="{}" y="{}">min–max band</text>"#,
        lx + 8.0,
        ly + 39.0,
        lx + 33.0,
        ly + 48.0
    );
}

/// Every room of the experiment with the best robot's path in it (`trajectories[r]` for room
/// `r`), as [`trajectories_svg`] draws them.
pub fn best_paths_svg(title: &str, exp: &Experiment, trajectories: &[&Trajectory]) -> String {
    let pairs: Vec<_> = exp
        .arenas()
        .iter()
        .map(|a| a.room())
        .zip(trajectories.iter().copied())
        .collect();
    trajectories_svg(title, &pairs)
}

/// The part of a room's home zone on its floor, as a polygon: the zone's circle sampled every
/// 3°, keeping the points inside the room, closed through the centre when part of the circle
/// lies outside (a zone centred on a corner becomes the paper's quarter circle).
fn zone_outline(room: &Room) -> Vec<fuzzymotiv::geom::Vec2> {
    use fuzzymotiv::geom::Vec2;
    let zone = room.home_zone;
    let circle: Vec<Vec2> = (0..120)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / 120.0;
            Vec2::new(
                zone.centre.x + zone.radius * a.cos(),
                zone.centre.y + zone.radius * a.sin(),
            )
        })
        .collect();
    let inside: Vec<bool> = circle.iter().map(|&p| room.contains(p)).collect();
    if inside.iter().all(|&i| i) {
        return circle;
    }
    // Start just after an outside point so the kept arc is contiguous.
    let start = (0..circle.len()).find(|&i| !inside[i]).unwrap_or(0);
    let mut out = vec![zone.centre];
    out.extend(
        (1..=circle.len())
            .map(|k| (start + k) % circle.len())
            .filter(|&i| inside[i])
            .map(|i| circle[i]),
    );
    out
}

/// Length of a step marker's heading tick in the trajectory figures (px).
const TICK: f64 = 3.0;

/// Millimetres of a room to pixels of its panel: x to the right from `x_off`, y up in the
/// room and down in SVG.
struct Projection {
    x_off: f64,
    lo: fuzzymotiv::geom::Vec2,
    hi: fuzzymotiv::geom::Vec2,
    scale: f64,
}

impl Projection {
    fn x(&self, x: f64) -> f64 {
        self.x_off + (x - self.lo.x) * self.scale
    }

    fn y(&self, y: f64) -> f64 {
        40.0 + (self.hi.y - y) * self.scale
    }

    fn polygon(&self, pts: &[fuzzymotiv::geom::Vec2]) -> String {
        pts.iter()
            .map(|p| format!("{:.1},{:.1}", self.x(p.x), self.y(p.y)))
            .collect::<Vec<_>>()
            .join(" ")
    }
}

/// Rooms drawn to scale side by side, each with its home zone, the path with a marker per
/// executed step, the home pose and the end point (ringed when the trial ended at home).
pub fn trajectories_svg(title: &str, rooms: &[(&Room, &Trajectory)]) -> String {
    let scale = 0.3; // px per mm
    let pad = 20.0;
    let mut x_off = pad;
    let mut parts = String::new();
    let mut max_h: f64 = 0.0;
    for (room, tr) in rooms {
        let (lo, hi) = room.bounds();
        let (w, h) = ((hi.x - lo.x) * scale, (hi.y - lo.y) * scale);
        max_h = max_h.max(h);
        let p = Projection {
            x_off,
            lo,
            hi,
            scale,
        };
        draw_room(&mut parts, room, &p);
        draw_path(&mut parts, tr, &p);
        draw_home_and_end(&mut parts, room, tr, &p);
        let _ = writeln!(
            parts,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
            x_off + w / 2.0,
            40.0 + h + 16.0,
            esc(&room.name)
        );
        x_off += w + pad;
    }
    // Title, caption and scale bar each get a line of their own, and the figure is wide enough
    // for the longest text, so nothing is clipped or overprinted, whatever the number of rooms.
    let caption = "green: home pose; blue quarter: home zone; red: path, a tick per step; filled circle: the end (ringed: back home)";
    let width = x_off
        .max(2.0 * pad + text_width(title, true))
        .max(2.0 * pad + text_width(caption, false));
    let (caption_y, bar_y) = (40.0 + max_h + 40.0, 40.0 + max_h + 60.0);
    let height = bar_y + 12.0;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif" font-size="12">"#
    );
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
    s.push_str(&parts);
    s.push_str("</svg>\n");
    s
}

/// A room's outline, obstacles and home zone.
fn draw_room(parts: &mut String, room: &Room, p: &Projection) {
    let _ = writeln!(
        parts,
        r##"<polygon points="{}" fill="#fafafa" stroke="#222" stroke-width="2"/>"##,
        p.polygon(&room.outline)
    );
    for o in &room.obstacles {
        let _ = writeln!(
            parts,
            r##"<polygon points="{}" fill="#888" stroke="#222"/>"##,
            p.polygon(o)
        );
    }
    let _ = writeln!(
        parts,
        r##"<polygon points="{}" fill="#1f77b4" fill-opacity="0.10" stroke="#1f77b4" stroke-opacity="0.6" stroke-dasharray="4 3"/>"##,
        p.polygon(&zone_outline(room))
    );
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

/// The frame of one per-generation panel over the plot area `(x0, x1, y0, y1)` of a figure
/// `height` tall: title, grid lines at 0, 0.2, …, 1, axes, axis labels and the first and last
/// generation.
fn panel_frame(
    s: &mut String,
    name: &str,
    (x0, x1, y0, y1): (f64, f64, f64, f64),
    height: f64,
    generations: usize,
    y_label: &str,
) {
    let y = |f: f64| y0 + (y1 - y0) * f;
    let _ = writeln!(
        s,
        r#"<text x="{}" y="18" text-anchor="middle" font-weight="bold">{}</text>"#,
        (x0 + x1) / 2.0,
        esc(name)
    );
    for k in 0..=5 {
        let f = k as f64 / 5.0;
        let _ = writeln!(
            s,
            r##"<line x1="{x0}" x2="{x1}" y1="{yy:.1}" y2="{yy:.1}" stroke="#ddd"/><text x="{}" y="{:.1}" text-anchor="end">{f:.1}</text>"##,
            x0 - 4.0,
            y(f) + 4.0,
            yy = y(f)
        );
    }
    let _ = writeln!(
        s,
        r##"<line x1="{x0}" x2="{x1}" y1="{y0}" y2="{y0}" stroke="#000"/><line x1="{x0}" x2="{x0}" y1="{y0}" y2="{y1}" stroke="#000"/>"##
    );
    axis_labels(s, (x0, x1, y0, y1), height, "generation", y_label);
    let _ = writeln!(
        s,
        r#"<text x="{x0}" y="{}" text-anchor="start">0</text><text x="{x1}" y="{}" text-anchor="end">{}</text>"#,
        y0 + 16.0,
        y0 + 16.0,
        generations.saturating_sub(1)
    );
}

/// The x-axis label under a plot area `(x0, x1, y0, y1)` of a figure `height` tall, and the
/// y-axis label turned along the left edge.
fn axis_labels(
    s: &mut String,
    (x0, x1, y0, y1): (f64, f64, f64, f64),
    height: f64,
    x: &str,
    y: &str,
) {
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
        (x0 + x1) / 2.0,
        height - 8.0,
        esc(x)
    );
    let (cx, cy) = (x0 - 36.0, (y0 + y1) / 2.0);
    let _ = writeln!(
        s,
        r#"<text x="{cx}" y="{cy}" text-anchor="middle" transform="rotate(-90 {cx} {cy})">{}</text>"#,
        esc(y)
    );
}

/// Picks one fitness term of a generation record.
type TermOf = fn(&GenerationRecord) -> f64;

/// One panel per run: the population means of the fitness terms a, g, l, b per generation.
pub fn terms_svg(panels: &[(String, Vec<GenerationRecord>)]) -> String {
    let (pw, ph) = (520.0, 300.0);
    let (ml, mr, mt, mb) = (50.0, 115.0, 30.0, 40.0);
    let width = pw * panels.len() as f64;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{ph}" viewBox="0 0 {width} {ph}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="{width}" height="{ph}" fill="white"/>"#);
    let series: [(&str, &str, TermOf); 4] = [
        ("a exploration", "#2ca02c", |r| r.terms.a),
        ("g homing", "#9467bd", |r| r.terms.g),
        ("l recognition", "#8c564b", |r| r.terms.l),
        ("b battery", "#ff7f0e", |r| r.terms.b),
    ];
    for (p, (name, hist)) in panels.iter().enumerate() {
        let ox = p as f64 * pw;
        let (x0, x1, y0, y1) = (ox + ml, ox + pw - mr, ph - mb, mt);
        let n = hist.len().max(2) as f64 - 1.0;
        let x = |g: usize| x0 + (x1 - x0) * g as f64 / n;
        let y = |f: f64| y0 + (y1 - y0) * f.clamp(0.0, 1.0);
        panel_frame(
            &mut s,
            name,
            (x0, x1, y0, y1),
            ph,
            hist.len(),
            "population mean",
        );
        for (k, (label, colour, pick)) in series.iter().enumerate() {
            let pts: String = hist
                .iter()
                .enumerate()
                .map(|(g, r)| format!("{:.1},{:.1} ", x(g), y(pick(r))))
                .collect();
            let _ = writeln!(
                s,
                r#"<polyline points="{pts}" fill="none" stroke="{colour}" stroke-width="1.8"/>"#
            );
            let (lx, ly) = (x1 + 10.0, y1 + 10.0 + 16.0 * k as f64);
            let _ = writeln!(
                s,
                r#"<line x1="{lx}" x2="{}" y1="{ly}" y2="{ly}" stroke="{colour}" stroke-width="2"/><text x="{}" y="{}">{label}</text>"#,
                lx + 16.0,
                lx + 20.0,
                ly + 4.0
            );
        }
    }
    s.push_str("</svg>\n");
    s
}

/// The triangular membership functions μ(y) of the fuzzy labels (V.L. … V.H. by default).
pub fn membership_svg(peaks: &[f64], names: &[String]) -> String {
    let (w, h) = (420.0, 205.0);
    let (x0, x1, y0, y1) = (50.0, w - 15.0, h - 40.0, 48.0);
    let (lo, hi) = (
        peaks.first().copied().unwrap_or(0.0).min(0.0),
        peaks.last().copied().unwrap_or(1.0).max(1.0),
    );
    let x = |v: f64| x0 + (x1 - x0) * (v - lo) / (hi - lo);
    let y = |m: f64| y0 + (y1 - y0) * m;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="16" text-anchor="middle" font-weight="bold">Membership of a fitness value y in each label</text>"#,
        (x0 + x1) / 2.0
    );
    let _ = writeln!(
        s,
        r##"<line x1="{x0}" x2="{x1}" y1="{y0}" y2="{y0}" stroke="#000"/><line x1="{x0}" x2="{x0}" y1="{y0}" y2="{y1}" stroke="#000"/>"##
    );
    for m in [0.0, 0.5, 1.0] {
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{:.1}" text-anchor="end">{m}</text>"#,
            x0 - 4.0,
            y(m) + 4.0
        );
    }
    for v in [0.0, 0.25, 0.5, 0.75, 1.0] {
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{}" text-anchor="middle">{v}</text>"#,
            x(v),
            y0 + 15.0
        );
    }
    axis_labels(
        &mut s,
        (x0, x1, y0, y1),
        h,
        "fitness value y (a, g, l or b)",
        "μ(y)",
    );
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
        let name = names.get(k).map_or("", String::as_str);
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle" fill="{c}" font-weight="bold">{}</text>"#,
            x(p),
            y(1.0) - 5.0,
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
    let h = line_y + 40.0 + 9.0 * max_dots as f64 + 30.0;
    let last = nodes.saturating_sub(1).max(1) as f64;
    let x = |n: f64| x0 + (x1 - x0) * n / last;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h:.0}" viewBox="0 0 {w} {h:.0}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h:.0}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{x0}" y="18" font-weight="bold">{}</text>"#,
        esc(title)
    );
    som_instances(&mut s, rooms, nodes, threshold, line_y, &x);
    som_axis(&mut s, nodes, line_y, (x0, x1), &x);
    som_winners(&mut s, rooms, nodes, line_y, &x);
    let _ = writeln!(
        s,
        r##"<text x="{x0}" y="{:.0}" fill="#555">SOM node index (0–{}). Marker: a room's stored instance (r-node), band: ±{threshold} nodes; dots: winners of test runs, coloured by true room.</text>"##,
        h - 10.0,
        nodes.saturating_sub(1)
    );
    s.push_str("</svg>\n");
    s
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
        let _ = writeln!(
            s,
            r#"<line x1="{xr:.1}" x2="{xr:.1}" y1="{:.1}" y2="{:.1}" stroke="{c}" stroke-width="1.5"/><circle cx="{xr:.1}" cy="{line_y}" r="5" fill="{c}"/><text x="{:.1}" y="{:.1}" fill="{c}" font-weight="bold">{} (r-node {})</text>"#,
            ly + 2.0,
            line_y,
            x(r.r_node as f64) + 4.0,
            ly,
            esc(r.name),
            r.r_node,
            xr = x(r.r_node as f64)
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
    let step = if nodes > 64 { 16 } else { 8 };
    for n in (0..nodes)
        .step_by(step)
        .chain(std::iter::once(nodes.saturating_sub(1)))
    {
        let _ = writeln!(
            s,
            r##"<line x1="{xn:.1}" x2="{xn:.1}" y1="{}" y2="{}" stroke="#222"/><text x="{xn:.1}" y="{}" text-anchor="middle" fill="#555">{n}</text>"##,
            line_y - 4.0,
            line_y + 4.0,
            line_y + 18.0,
            xn = x(n as f64)
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
        (330.0, 60.0 + 22.0 * points.len() as f64)
    };
    let width = pw * 4.0;
    let height = ph + 56.0;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="11">"#
    );
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
        r##"<text x="8" y="{:.0}" fill="#555">Means over rooms and replicates per motivation setting (C, H, O, E).</text>"##,
        height - 2.0
    );
    s.push_str("</svg>\n");
    s
}

/// Panel `k` of [`sweep_summary_svg`] for many settings: each a point on the (C, H, E)
/// simplex coloured by outcome `k`, with a colour key.
fn ternary_panel(s: &mut String, points: &[SettingPoint], k: usize, ox: f64, pw: f64, height: f64) {
    let side = pw - 70.0;
    let (x0, y0) = (ox + 35.0, 40.0 + side * 0.866);
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
        a.0 - 4.0,
        a.1 + 12.0,
        b.0 + 4.0,
        b.1 + 12.0,
        c.0,
        c.1 - 6.0
    );
    for p in points {
        let m = p.motivations;
        let (x, y) = corner(m[0], m[1], m[3]);
        match p.values[k] {
            Some(v) => {
                let _ = writeln!(
                    s,
                    r##"<circle cx="{x:.1}" cy="{y:.1}" r="7" fill="{}" stroke="#333" stroke-width="0.5"><title>{}: {v:.1}</title></circle>"##,
                    value_colour(v),
                    esc(&p.label)
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
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="{:.1}">0</text><text x="{:.1}" y="{:.1}">100</text>"#,
        ox + 40.0,
        height - 24.0,
        ox + 250.0,
        height - 24.0
    );
}

/// Panel `k` of [`sweep_summary_svg`] for a few settings: one labelled bar each.
fn bars_panel(s: &mut String, points: &[SettingPoint], k: usize, ox: f64) {
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
            let w = 160.0 * (v / 100.0).clamp(0.0, 1.0);
            let _ = writeln!(
                s,
                r##"<rect x="{:.1}" y="{y:.1}" width="{w:.1}" height="15" fill="{}"/><text x="{:.1}" y="{:.1}">{v:.1}</text>"##,
                ox + 130.0,
                value_colour(v),
                ox + 134.0 + w,
                y + 12.0
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fuzzymotiv::room::{BUILTIN_ROOMS, Room};

    /// Text boxes `(x0, x1, y0, y1)` of every `<text>` of a figure (estimated widths).
    fn text_boxes(svg: &str) -> Vec<(f64, f64, f64, f64, String)> {
        let attr = |el: &str, name: &str| -> Option<String> {
            let start = el.find(&format!(" {name}=\""))? + name.len() + 3;
            Some(el[start..].split('"').next()?.to_string())
        };
        svg.split("<text")
            .skip(1)
            .map(|el| {
                let (head, rest) = el.split_once('>').unwrap();
                let content = rest.split("</text>").next().unwrap().to_string();
                let x: f64 = attr(head, "x").unwrap().parse().unwrap();
                let y: f64 = attr(head, "y").unwrap().parse().unwrap();
                let w = text_width(&content, head.contains("bold"));
                let x0 = match attr(head, "text-anchor").as_deref() {
                    Some("middle") => x - w / 2.0,
                    Some("end") => x - w,
                    _ => x,
                };
                (x0, x0 + w, y - 12.0, y + 3.0, content)
            })
            .collect()
    }

    /// Every trajectory figure lays out cleanly with 1 to 8 rooms: each text inside the figure,
    /// no two texts overlapping (title, room names, caption, scale bar label).
    #[test]
    fn trajectory_figures_lay_out_cleanly_with_1_to_8_rooms() {
        let rooms: Vec<Room> = (0..8)
            .map(|k| Room::builtin(BUILTIN_ROOMS[k % BUILTIN_ROOMS.len()]).unwrap())
            .collect();
        let title = "Replay of runs/high-curiosity/best_genome.json (seed 9007199254740991)";
        for n in 1..=8 {
            let trs: Vec<Trajectory> = rooms[..n]
                .iter()
                .map(|r| Trajectory {
                    poses: vec![r.home],
                    ..Default::default()
                })
                .collect();
            let pairs: Vec<_> = rooms[..n].iter().zip(&trs).collect();
            let svg = trajectories_svg(title, &pairs);
            let head = svg.split('>').next().unwrap();
            let attr = |name: &str| -> f64 {
                let value = head.split(&format!(" {name}=\"")).nth(1).unwrap();
                value.split('"').next().unwrap().parse().unwrap()
            };
            let (width, height) = (attr("width"), attr("height"));
            let boxes = text_boxes(&svg);
            for b in &boxes {
                assert!(
                    b.0 >= 0.0 && b.1 <= width && b.2 >= 0.0 && b.3 <= height,
                    "{n} rooms: `{}` outside {width}×{height}: {b:?}",
                    b.4
                );
            }
            for (i, a) in boxes.iter().enumerate() {
                for b in &boxes[i + 1..] {
                    let apart = a.1 <= b.0 || b.1 <= a.0 || a.3 <= b.2 || b.3 <= a.2;
                    assert!(apart, "{n} rooms: `{}` overlaps `{}`", a.4, b.4);
                }
            }
        }
    }
}
