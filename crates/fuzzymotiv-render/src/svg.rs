//! SVG figures, written with the one builder ([`crate::figure`]): fitness evolution (paper Fig. 6), trajectories (Figs. 7–8), the
//! fitness terms per generation, the membership functions and the rooms' nodes on the SOM line.

use crate::figure::axis::placed;
use crate::figure::room::{
    Projection, draw_room_and_path, figure_scale, log_colour, mission_caption,
};
use crate::figure::{
    Area, Fill, Legend, MUTED, Mark, PathData, Scale, Stroke, Svg, Text, Ticks, colour, px,
    text_width,
};

pub use crate::figure::room::{GOAL_COLOUR, LoggedPath, WAYPOINT_COLOUR};

use fuzzymotiv::experiment::GenerationRecord;
use fuzzymotiv::fitness::TermId;
use fuzzymotiv::simulation::Room;
use fuzzymotiv::simulation::Trajectory;
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
    let y0 = mt + 230.0;
    let widths: Vec<f64> = panels
        .iter()
        // The title is centred over the plot area, which is off the panel's centre.
        .map(|p| px(420f64.max(text_width(&p.title, true) + ml - mr + 10.0)))
        .collect();
    let legends: Vec<Legend<'_>> = panels.iter().map(fitness_legend).collect();
    let legend_top = y0 + 54.0;
    let width = px(widths.iter().sum::<f64>().max(1.0));
    let probe = Svg::new(width, 0.0, 12);
    let rows = (widths.iter().zip(&legends))
        .map(|(w, l)| l.rows(&probe, w - ml - mr))
        .max()
        .unwrap_or(1);
    let mut s = Svg::new(width, legend_top + 16.0 * (rows - 1) as f64 + 10.0, 12);
    let mut ox = 0.0;
    for ((panel, pw), legend) in panels.iter().zip(&widths).zip(&legends) {
        let area = Area {
            x0: ox + ml,
            x1: ox + pw - mr,
            y0,
            y1: mt,
        };
        let generations = panel.best.0.len();
        panel_frame(&mut s, &panel.title, area, generations, "fuzzy fitness F");
        let x = area.x_scale(0.0, generations.max(2) as f64 - 1.0);
        let y = area.y_scale(0.0, 1.0);
        draw_fitness_curves(
            &mut s,
            panel,
            |g| x.at(g as f64),
            |f| y.at(f.clamp(0.0, 1.0)),
        );
        legend.flow(&mut s, (area.x0, area.x1), legend_top, 16.0);
        ox += pw;
    }
    s.finish()
}

/// A fitness panel's legend: the best and the mean F curves, and its bands (one entry).
fn fitness_legend(p: &FitnessPanel) -> Legend<'static> {
    let mut entries = vec![
        (Mark::Line(Stroke::of(BEST).width(2.0)), p.best.1.clone()),
        (Mark::Line(Stroke::of(MEAN).width(2.0)), p.mean.1.clone()),
    ];
    if !p.bands.is_empty() {
        let colours = p.bands.iter().map(|b| b.1).collect();
        entries.push((Mark::Bands(colours), p.band_label.clone()));
    }
    Legend::new(entries)
}

/// A fitness panel's shaded bands, then its best and mean F curves, at `x(generation)` and
/// `y(F)`.
fn draw_fitness_curves(
    s: &mut Svg,
    panel: &FitnessPanel,
    x: impl Fn(usize) -> f64,
    y: impl Fn(f64) -> f64,
) {
    for (band, colour) in &panel.bands {
        // One closed outline: along the highs, back along the lows.
        let mut d = PathData::new();
        for (g, (_, hi)) in band.iter().enumerate() {
            d = d.line_to((x(g), y(*hi)));
        }
        for (g, (lo, _)) in band.iter().enumerate().rev() {
            d = d.line_to((x(g), y(*lo)));
        }
        let fill = Fill::of(colour).opacity(0.45).stroked(Stroke::of("none"));
        s.path(&d.close(), fill, None);
    }
    for (values, colour) in [(&panel.best.0, BEST), (&panel.mean.0, MEAN)] {
        let pts: Vec<(f64, f64)> = values
            .iter()
            .enumerate()
            .map(|(g, &f)| (x(g), y(f)))
            .collect();
        s.polyline(&pts, Stroke::of(colour).width(1.8), None);
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

/// Every room of the experiment with the best robot's path in it (`trajectories[r]` for room
/// `r`), as [`trajectories_svg`] draws them.
pub fn best_paths_svg(title: &str, rooms: &[Room], trajectories: &[&Trajectory]) -> String {
    let pairs: Vec<_> = rooms.iter().zip(trajectories.iter().copied()).collect();
    trajectories_svg(title, &pairs)
}

/// Rooms drawn to scale side by side, each with its home zone, the path with a marker per
/// executed step, the home pose and the end point (ringed when the trial ended at home).
pub fn trajectories_svg(title: &str, rooms: &[(&Room, &Trajectory)]) -> String {
    trajectories_svg_with(title, rooms, &[])
}

/// The rooms' top edge in the trajectories figure, and the room between and around them (px).
const ROOMS_TOP: f64 = 40.0;
const PAD: f64 = 20.0;
/// The height of a logged path's legend line, and the width of its swatch (px).
const LEGEND_LINE: f64 = 18.0;
const LEGEND_SWATCH: f64 = 30.0;

/// Where each room of the trajectories figure goes: its projection, and its slot's left edge
/// and width (a room narrower than its name is centred in a slot as wide as the name); the
/// figure's width so far and the tallest room's height.
fn room_slots(rooms: &[(&Room, &Trajectory)]) -> (Vec<(Projection, f64, f64)>, f64, f64) {
    let scale = figure_scale(rooms.iter().map(|(r, _)| *r));
    let (mut x_off, mut max_h) = (PAD, 0.0f64);
    let mut slots = Vec::new();
    for (room, _) in rooms {
        let (lo, hi) = room.bounds();
        let (w, h) = ((hi.x - lo.x) * scale, (hi.y - lo.y) * scale);
        max_h = max_h.max(h);
        let slot = w.max(text_width(&room.name, false));
        let p = Projection::of(room, (x_off + (slot - w) / 2.0, ROOMS_TOP), scale);
        slots.push((p, x_off, slot));
        x_off += slot + PAD;
    }
    (slots, x_off, max_h)
}

/// The legend of the logged paths: a dashed line in each one's colour, its file and length.
fn logs_legend(logs: &[LoggedPath]) -> Legend<'static> {
    Legend::new(
        (logs.iter().enumerate())
            .map(|(k, l)| {
                let mark = Mark::Line(Stroke::of(log_colour(k)).width(2.0).dashed("5 3"));
                let text = format!(
                    "logged path: {} ({} positions; a square at its end)",
                    l.label,
                    l.points.len()
                );
                (mark, text)
            })
            .collect(),
    )
}

/// [`trajectories_svg`] with `logs` drawn over their rooms, each dashed in a colour of its own
/// with an end square, and a legend line each under the caption.
pub fn trajectories_svg_with(
    title: &str,
    rooms: &[(&Room, &Trajectory)],
    logs: &[LoggedPath],
) -> String {
    let (slots, rooms_w, max_h) = room_slots(rooms);
    // Title, caption and scale bar each get a line of their own, and the figure is wide enough
    // for the longest text, so nothing is clipped or overprinted, whatever the number of rooms.
    let caption = format!(
        "green: home pose; blue: home zone; {}red: path, a tick per step; filled circle: the end (ringed: back home)",
        mission_caption(rooms.iter().map(|(r, _)| *r))
    );
    let legend = logs_legend(logs);
    let width = (legend.entries.iter()).fold(
        rooms_w
            .max(2.0 * PAD + text_width(title, true))
            .max(2.0 * PAD + text_width(&caption, false)),
        |w, (_, t)| w.max(2.0 * PAD + LEGEND_SWATCH + text_width(t, false)),
    );
    let (caption_y, bar_y) = (ROOMS_TOP + max_h + 40.0, ROOMS_TOP + max_h + 60.0);
    let height = bar_y + 12.0 + LEGEND_LINE * logs.len() as f64;
    let mut s = Svg::new(width.round(), height.round(), 12);
    s.text((PAD, 22.0), title, Text::START.bold());
    let grey = Text::START.fill(MUTED);
    s.text((PAD, caption_y.round()), &caption, grey);
    let bar = 100.0 * slots.first().map_or(0.3, |(p, ..)| p.scale);
    s.line(
        (PAD, bar_y - 4.0),
        (PAD + bar, bar_y - 4.0),
        Stroke::of(MUTED).width(2.0),
    );
    s.text((PAD + bar + 6.0, bar_y.round()), "100 mm", grey);
    legend.column(&mut s, PAD, bar_y + LEGEND_LINE, LEGEND_LINE);
    for (i, ((room, tr), (p, left, slot))) in rooms.iter().zip(&slots).enumerate() {
        let mine: Vec<(&LoggedPath, &str)> = (logs.iter().enumerate())
            .filter(|(_, l)| l.room == i)
            .map(|(k, l)| (l, log_colour(k)))
            .collect();
        draw_room_and_path(&mut s, (room, tr), p, &mine);
        let name_y = ROOMS_TOP + (p.hi.y - p.lo.y) * p.scale + 16.0;
        s.text((left + slot / 2.0, name_y), &room.name, Text::MIDDLE);
    }
    s.finish()
}

/// The frame of one per-generation panel over `area`: title, grid lines and labels at round
/// values of F (0, 0.2, …, 1), axes, round generation numbers on the x axis and the axis
/// labels (the x label's baseline 32 px below the axis).
fn panel_frame(s: &mut Svg, name: &str, area: Area, generations: usize, y_label: &str) {
    area.title(s, 18.0, name);
    let y_ticks = Ticks::nice(0.0, 1.0, 5, false);
    area.y_grid(s, &y_ticks, area.y_scale(0.0, 1.0), Text::END, None);
    area.axes(s);
    let last = generations.saturating_sub(1);
    let x_ticks = Ticks::nice(0.0, last as f64, 6, true);
    let x = area.x_scale(0.0, last.max(1) as f64);
    area.x_ticks(s, &placed(&x_ticks, x), 17.0, true, Text::MIDDLE);
    area.labels(s, ("generation", 32.0), (y_label, 36.0), Text::MIDDLE);
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
    let mut s = Svg::new(widths.iter().sum::<f64>().max(1.0), ph, 12);
    let mut ox = 0.0;
    for ((name, hist), pw) in panels.iter().zip(&widths) {
        let area = Area {
            x0: ox + ml,
            x1: ox + pw - mr,
            y0: ph - mb,
            y1: mt,
        };
        panel_frame(&mut s, name, area, hist.len(), "population mean");
        term_curves_of(&mut s, area, hist, curves);
        ox += pw;
    }
    s.finish()
}

/// A panel's curves, one per term, and their legend right of `area`.
fn term_curves_of(s: &mut Svg, area: Area, hist: &[GenerationRecord], curves: &[TermCurve]) {
    let x = area.x_scale(0.0, hist.len().max(2) as f64 - 1.0);
    let y = area.y_scale(0.0, 1.0);
    let mut entries = Vec::new();
    let mut zeros = Vec::new();
    for c in curves {
        let pick = |r: &GenerationRecord| r.terms.get(c.term);
        let pts: Vec<(f64, f64)> = (hist.iter().enumerate())
            .map(|(g, r)| (x.at(g as f64), y.at(pick(r).clamp(0.0, 1.0))))
            .collect();
        // A term at 0 throughout (l when O = 0) lies on the x axis: dashed and wider, so it
        // shows there, and its legend says so.
        let zero = !hist.is_empty() && hist.iter().all(|r| pick(r) == 0.0);
        let stroke = match zero {
            true => Stroke::of(c.colour).width(3.0).dashed("6 4"),
            false => Stroke::of(c.colour).width(1.8),
        };
        s.polyline(&pts, stroke, None);
        entries.push((Mark::Line(stroke), c.label.clone()));
        zeros.push(zero);
    }
    // One entry a line, 16 px apart, and a note line under a term at 0.
    let (lx, mut ly) = (area.x1 + 10.0, area.y1 + 14.0);
    for ((mark, text), zero) in entries.into_iter().zip(zeros) {
        Legend::new(vec![(mark, text)]).column(s, lx, ly, 16.0);
        if zero {
            ly += 14.0;
            let note = Text::START.size(10.0).fill(MUTED);
            s.text((lx + 26.0, ly), "(0 throughout)", note);
        }
        ly += 16.0;
    }
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
    let area = Area {
        x0: 50.0,
        x1: w - 15.0,
        y0: h - 49.0,
        y1: 48.0,
    };
    let (lo, hi) = (
        peaks.first().copied().unwrap_or(0.0).min(0.0),
        peaks.last().copied().unwrap_or(1.0).max(1.0),
    );
    let (x, y) = (area.x_scale(lo, hi), area.y_scale(0.0, 1.0));
    let mut s = Svg::new(w, h, 12);
    area.title(&mut s, 16.0, title);
    area.axes(&mut s);
    let y_ticks = Ticks::nice(0.0, 1.0, 2, false);
    for &m in &y_ticks.values {
        s.line(
            (area.x0 - 4.0, y.at(m)),
            (area.x0, y.at(m)),
            Stroke::of("#000"),
        );
        s.text((area.x0 - 6.0, y.at(m) + 4.0), &y_ticks.label(m), Text::END);
    }
    let x_ticks = Ticks::nice(lo, hi, 5, false);
    area.x_ticks(&mut s, &placed(&x_ticks, x), 19.0, true, Text::MIDDLE);
    area.labels(&mut s, (x_label, 41.0), ("μ(y)", 36.0), Text::MIDDLE);
    membership_triangles(&mut s, peaks, names, (lo, hi), &|v| x.at(v), &|m| y.at(m));
    s.finish()
}

/// One triangle per label (the outer ones open to the range's ends), named at its peak.
fn membership_triangles(
    s: &mut Svg,
    peaks: &[f64],
    names: &[String],
    (lo, hi): (f64, f64),
    x: &dyn Fn(f64) -> f64,
    y: &dyn Fn(f64) -> f64,
) {
    for (k, &p) in peaks.iter().enumerate() {
        let (first, last) = (k == 0, k + 1 == peaks.len());
        let left = if first { lo } else { peaks[k - 1] };
        let right = if last { hi } else { peaks[k + 1] };
        let (ml, mr) = (f64::from(u8::from(first)), f64::from(u8::from(last)));
        let c = colour(k);
        let pts = [(x(left), y(ml)), (x(p), y(1.0)), (x(right), y(mr))];
        s.polyline(&pts, Stroke::of(c).width(2.0), None);
        // Named above the peak; the labels at the ends of the range start or end there, so
        // they stay inside the plot and clear of the y axis's tick labels.
        let name = names.get(k).map_or("", String::as_str);
        let half = text_width(name, true) / 2.0;
        let (lx, anchor) = if x(p) - half < x(lo) {
            (x(lo) + 2.0, Text::START)
        } else if x(p) + half > x(hi) {
            (x(hi), Text::END)
        } else {
            (x(p), Text::MIDDLE)
        };
        s.text((lx, y(1.0) - 6.0), name, anchor.fill(c).bold());
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
    let h = (line_y + 40.0 + 9.0 * max_dots as f64 + 46.0).round();
    let last = nodes.saturating_sub(1).max(1) as f64;
    let scale = Scale::new((0.0, last), (x0, x1));
    let x = |n: f64| scale.at(n);
    let mut s = Svg::new(w, h, 12);
    s.text((x0, 18.0), title, Text::START.bold());
    som_instances(&mut s, rooms, nodes, threshold, line_y, &x);
    som_axis(&mut s, nodes, line_y, (x0, x1), &x);
    som_winners(&mut s, rooms, nodes, line_y, &x);
    // The caption in two lines, each shorter than the figure is wide.
    let grey = Text::START.fill(MUTED);
    let first = format!(
        "SOM node index (0–{}). Marker: a room's stored instance (r-node); band: ±{threshold} nodes around it.",
        nodes.saturating_sub(1)
    );
    s.text((x0, h - 26.0), &first, grey);
    let second = "Dots: the winning nodes of the test runs, coloured by the room each run was in.";
    s.text((x0, h - 10.0), second, grey);
    s.finish()
}

/// The last node's index on a SOM line of `nodes` nodes (at least 1, so the line has a length).
fn last_node(nodes: usize) -> f64 {
    nodes.saturating_sub(1).max(1) as f64
}

/// Each room's r-node on the SOM line, with its threshold band and label.
fn som_instances(
    s: &mut Svg,
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
        let band = ((x(b) - x(a)).max(1.0), 14.0);
        s.rect((x(a), line_y - 7.0), band, Fill::of(c).opacity(0.15));
        let ly = 40.0 + 16.0 * k as f64;
        let xr = x(r.r_node as f64);
        // The label right of its marker line, or left of it where it would pass the right
        // end of the line.
        let label = format!("{} (r-node {})", r.name, r.r_node);
        let (lx, anchor) = if xr + 4.0 + text_width(&label, true) > x(last_node(nodes)) + 30.0 {
            (xr - 4.0, Text::END)
        } else {
            (xr + 4.0, Text::START)
        };
        s.line((xr, ly + 2.0), (xr, line_y), Stroke::of(c).width(1.5));
        s.circle((xr, line_y), 5.0, Fill::of(c), None);
        s.text((lx, ly), &label, anchor.fill(c).bold());
    }
}

/// The SOM line with node ticks.
fn som_axis(s: &mut Svg, nodes: usize, line_y: f64, (x0, x1): (f64, f64), x: &dyn Fn(f64) -> f64) {
    s.line((x0, line_y), (x1, line_y), Stroke::of("#222").width(2.0));
    let ticks = Ticks::nice(0.0, last_node(nodes), 10, true);
    for &n in &ticks.values {
        s.line(
            (x(n), line_y - 4.0),
            (x(n), line_y + 4.0),
            Stroke::of("#222"),
        );
        s.text(
            (x(n), line_y + 18.0),
            &ticks.label(n),
            Text::MIDDLE.fill(MUTED),
        );
    }
}

/// The test runs' winners, stacked below their node, coloured by true room.
fn som_winners(
    s: &mut Svg,
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
            s.circle((x(n as f64), dy), 3.5, Fill::of(colour(k)), None);
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
    let height = ph + 56.0;
    let mut s = Svg::new(pw * 4.0, height, 11);
    for (k, name) in OUTCOMES.iter().enumerate() {
        let ox = k as f64 * pw;
        s.text((ox + pw / 2.0, 18.0), name, Text::MIDDLE.bold().size(13.0));
        if ternary {
            ternary_panel(&mut s, points, k, (ox, pw));
            colour_key(&mut s, ox, height);
        } else {
            bars_panel(&mut s, points, k, ox);
        }
    }
    let caption = if ternary {
        "Means over rooms and replicates per motivation setting (C, H, O, E); under each panel the range of their sample std and n; each point's tooltip gives its own."
    } else {
        "Means over rooms and replicates per motivation setting (C, H, O, E); whiskers ± 1 sample std; n values per mean."
    };
    s.text(
        (8.0, (height - 6.0).round()),
        caption,
        Text::START.fill(MUTED),
    );
    s.finish()
}

/// Panel `k` of [`sweep_summary_svg`] for many settings, from `ox`, `pw` wide: each setting a
/// point on the (C, H, E) simplex coloured by outcome `k`.
fn ternary_panel(s: &mut Svg, points: &[SettingPoint], k: usize, (ox, pw): (f64, f64)) {
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
    s.polygon(&[a, b, c], Fill::outline(Stroke::of("#444")));
    s.text((a.0 - 8.0, a.1 + 14.0), "C=1", Text::END);
    s.text((b.0 + 8.0, b.1 + 14.0), "H=1", Text::START);
    s.text((c.0, c.1 - 10.0), "E=1", Text::MIDDLE);
    for p in points {
        let m = p.motivations;
        let at = corner(m[0], m[1], m[3]);
        match p.values[k] {
            Some(v) => {
                let colour = value_colour(v);
                let fill = Fill::of(&colour).stroked(Stroke::of("#333").width(0.5));
                let title = format!("{}: {}", p.label, mean_spread_n(p, k));
                s.circle(at, 7.0, fill, Some(&title));
            }
            None => s.circle(at, 3.0, Fill::of("#ccc"), None),
        }
    }
    let range = spread_range(points, k);
    s.text((ox + 35.0, y0 + 34.0), &range, Text::START.fill(MUTED));
}

/// A ternary panel's colour key at `ox`, near the figure's bottom (`height`): swatches for 0,
/// 10, …, 100, value v at ox + 50 + 2.2 v (the swatches' centres), labelled at round values.
fn colour_key(s: &mut Svg, ox: f64, height: f64) {
    for i in 0..=10 {
        let x = ox + 40.0 + 22.0 * i as f64;
        let fill = value_colour(i as f64 * 10.0);
        s.rect((x, height - 42.0), (20.0, 6.0), Fill::of(&fill));
    }
    let ticks = Ticks::nice(0.0, 100.0, 5, true);
    for &v in &ticks.values {
        let xv = ox + 50.0 + 2.2 * v;
        s.line((xv, height - 36.0), (xv, height - 33.0), Stroke::of("#333"));
        s.text((xv, height - 22.0), &ticks.label(v), Text::MIDDLE);
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
fn bars_panel(s: &mut Svg, points: &[SettingPoint], k: usize, ox: f64) {
    const SCALE: f64 = 1.3;
    let axis_y = 40.0 + 22.0 * points.len() as f64;
    let at = |v: f64| ox + 130.0 + SCALE * v.clamp(0.0, 100.0);
    let dark = Stroke::of("#333");
    s.line((at(0.0), axis_y), (at(100.0), axis_y), dark);
    let ticks = Ticks::nice(0.0, 100.0, 5, true);
    for &v in &ticks.values {
        s.line((at(v), axis_y), (at(v), axis_y + 3.0), dark);
        s.text((at(v), axis_y + 14.0), &ticks.label(v), Text::MIDDLE);
    }
    for (i, p) in points.iter().enumerate() {
        let y = 40.0 + 22.0 * i as f64;
        let m = p.motivations;
        let label = format!("({},{},{},{})", m[0], m[1], m[2], m[3]);
        s.text((ox + 8.0, y + 12.0), &label, Text::START);
        if let Some(v) = p.values[k] {
            let fill = value_colour(v);
            s.rect((at(0.0), y), (at(v) - at(0.0), 15.0), Fill::of(&fill));
            if let Some(d) = p.spread[k] {
                let (lo, hi, mid) = (at(v - d), at(v + d), y + 7.5);
                let whisker = PathData::new()
                    .move_to((lo, mid - 4.0))
                    .line_to((lo, mid + 4.0))
                    .move_to((lo, mid))
                    .line_to((hi, mid))
                    .move_to((hi, mid - 4.0))
                    .line_to((hi, mid + 4.0));
                let stroke = Stroke::of("#000").width(1.2);
                s.path(&whisker, Fill::outline(stroke), Some("spread"));
            }
        }
        s.text(
            (at(100.0) + 6.0, y + 12.0),
            &mean_spread_n(p, k),
            Text::START,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::text_width_at;
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
    /// root's), font-weight, text-anchor and content: its width measured from the font
    /// ([`text_width_at`]), from a full size above the baseline to a quarter below it
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
            Some(crate::figure::FONT_STACK),
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
