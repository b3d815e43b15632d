//! The self-contained HTML report (`report.html`): config, fitness evolution, the per-room
//! table, the fuzzy fitness of the best robot with its firing rules, the rooms with the best
//! robot's paths and an animated replay, and room recognition (SOM line, confusion matrix).
//!
//! Everything is inline (SVG figures, one JSON data block, one small script, one style sheet);
//! a Content-Security-Policy forbids every network request, so the page opens from disk.

use std::fmt::Write as _;

use fuzzymotiv::experiment::InstanceRun;
use fuzzymotiv::experiment::Training;
use fuzzymotiv::params::joined_list;
use serde_json::{Value, json};

use crate::figure::{colour, esc};
use crate::study::Setting;
use crate::svg::{
    LoggedPath, SomRoom, best_paths_svg, fitness_svg, som_svg, term_curves, terms_svg_of,
    trajectories_svg_with,
};
use crate::tables::{extra_cells, extra_columns};
use crate::terms::NAMES;
use fuzzymotiv_records::records::context::RenderContext;
use fuzzymotiv_records::records::{Finished, RoomRow};

mod fuzzy;

const CSS: &str = include_str!("report/report.css");
const SCRIPT: &str = include_str!("report/replay.js");

/// A page being assembled: HTML body and the replay data its widgets read.
pub struct Page {
    title: String,
    body: String,
    replays: Vec<Value>,
}

impl Page {
    /// An empty page.
    pub fn new(title: impl Into<String>) -> Self {
        Self {
            title: title.into(),
            body: String::new(),
            replays: Vec::new(),
        }
    }

    /// Appends raw HTML.
    pub fn push(&mut self, html: &str) {
        self.body.push_str(html);
    }

    /// Adds a replay widget for the given rooms (from [`replay_room`]) at this point of the page.
    pub fn replay(&mut self, ctx: &RenderContext, rooms: Vec<Value>) {
        let k = self.replays.len();
        let robot = ctx.robot;
        // Each sensor's axis ray, drawn to its range (the farthest wall it can read).
        let axes = fuzzymotiv::simulation::rays(ctx.sensor_model, robot);
        let sensors = (robot.mounts().iter().zip(&axes))
            .map(|(m, r)| [m.x, m.y, m.facing_deg, r[0].range()])
            .collect::<Vec<_>>();
        self.replays.push(json!({
            "robot": {
                "name": robot.name(),
                "radius": ctx.robot_radius,
                "dt": ctx.dt,
                "max": robot.reading_max(),
                "sensors": sensors,
                "names": robot.labels(),
            },
            "rooms": rooms,
        }));
        let _ = writeln!(self.body, r#"<div class="replay" data-replay="{k}"></div>"#);
    }

    /// The finished document.
    pub fn finish(self) -> String {
        let data = serde_json::to_string(&json!({ "replays": self.replays }))
            .expect("serialisable")
            .replace("</", "<\\/");
        format!(
            r#"<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; style-src 'unsafe-inline'; script-src 'unsafe-inline'; img-src data:">
<title>{title}</title>
<style>
{CSS}</style>
<script>window.fuzzymotivErrors = []; window.addEventListener("error", function (e) {{ window.fuzzymotivErrors.push(String(e.message)); }});</script>
</head>
<body>
<main>
{body}
<p class="note">Written by {version}. This page is self-contained: it makes no network requests.</p>
</main>
<script type="application/json" id="fm-data">{data}</script>
<script>
{SCRIPT}</script>
</body>
</html>
"#,
            title = esc(&self.title),
            body = self.body,
            version = fuzzymotiv::provenance(),
        )
    }
}

fn r1(v: f64) -> f64 {
    (v * 10.0).round() / 10.0
}

fn r3(v: f64) -> f64 {
    (v * 1000.0).round() / 1000.0
}

/// One letter per action: S straight, L left30, R right30, T turn180.
fn action_letter(a: fuzzymotiv::modelling::Action) -> char {
    use fuzzymotiv::modelling::Action::*;
    match a {
        Straight => 'S',
        Left30 => 'L',
        Right30 => 'R',
        Turn180 => 'T',
    }
}

/// Compact replay data of one trial (positions to 0.1 mm, angles and motors to 3 decimals,
/// sensors to integers; actions and collisions as one character per step).
pub fn replay_room(ctx: &RenderContext, room: usize, run_label: &str, run: &InstanceRun) -> Value {
    let r = &ctx.rooms[room];
    let pts = |p: &[fuzzymotiv::simulation::Vec2]| {
        p.iter().map(|v| [r1(v.x), r1(v.y)]).collect::<Vec<_>>()
    };
    let (tr, terms, f) = (&run.trajectory, run.terms, run.f);
    let zone = r.home_zone;
    let mut v = json!({
        "room": r.name,
        "run": run_label,
        "steps": tr.len(),
        "outline": pts(&r.outline),
        "obstacles": r.obstacles.iter().map(|o| pts(o)).collect::<Vec<_>>(),
        "home": [r1(r.home.x), r1(r.home.y), r3(r.home.heading)],
        "x": tr.poses.iter().map(|p| r1(p.x)).collect::<Vec<_>>(),
        "y": tr.poses.iter().map(|p| r1(p.y)).collect::<Vec<_>>(),
        "h": tr.poses.iter().map(|p| r3(p.heading)).collect::<Vec<_>>(),
        "s": (tr.sensors.iter())
            .map(|s| s.iter().map(|v| v.round() as i64).collect::<Vec<_>>())
            .collect::<Vec<_>>(),
        "m": tr.motors.iter().map(|m| m.map(r3)).collect::<Vec<_>>(),
        "zone": [r1(zone.centre.x), r1(zone.centre.y), r1(zone.radius)],
        "executed": tr.executed(),
        "a": tr.actions.iter().map(|&a| action_letter(a)).collect::<String>(),
        "i": tr.idle.iter().map(|&i| if i { '1' } else { '0' }).collect::<String>(),
        "c": tr.collisions.iter().map(|&c| if c { '1' } else { '0' }).collect::<String>(),
        "terms": {"a": r3(terms.a), "g": r3(terms.g), "l": r3(terms.l), "b": r3(terms.b)},
        "online_l": ctx.online_orientation(),
        "f": r3(f),
    });
    add_mission(&mut v, r);
    v
}

/// A room's mission in its replay data (only when it has one, so the paper's replays keep
/// their bytes): `goal` as [x, y, radius], `waypoints` as a list of them, in order.
fn add_mission(v: &mut Value, r: &fuzzymotiv::simulation::Room) {
    let disc =
        |z: &fuzzymotiv::simulation::HomeZone| [r1(z.centre.x), r1(z.centre.y), r1(z.radius)];
    if let Some(goal) = &r.mission.goal {
        v["goal"] = json!(disc(goal));
    }
    if !r.mission.waypoints.is_empty() {
        v["waypoints"] = json!(r.mission.waypoints.iter().map(disc).collect::<Vec<_>>());
    }
}

/// One setting (one run directory) to show on a page.
pub struct Section<'a> {
    /// Prefix of the element ids of this section.
    pub id: &'a str,
    /// Heading of the section (reproduce) or of the page (run).
    pub title: String,
    /// The run's setting.
    pub ctx: &'a RenderContext,
    /// The results.
    pub done: &'a Finished,
    /// The paper's values, for the reproduce page.
    pub paper: Option<&'a Setting>,
    /// Link to the run directory's own report, for the reproduce page.
    pub link: Option<String>,
    /// The spread over seeds (an HTML table), for the reproduce page.
    pub spread: Option<&'a str>,
    /// Mean % exploration, % recognition (if measured) and % battery over rooms and seeds, for
    /// the reproduce page's overview (else the section's own table is averaged).
    pub overall: Option<[Option<f64>; 3]>,
}

/// `report.html` of a run directory.
pub fn run_page(ctx: &RenderContext, done: &Finished) -> String {
    let mut page = Page::new(format!("fuzzymotiv run report — {}", ctx.name));
    let _ = writeln!(
        page.body,
        "<h1>Run report: {}</h1>\n<p class=\"meta\">{} · seed {} · wall time {:.2} s · {}</p>",
        esc(&ctx.name),
        fuzzymotiv::provenance(),
        ctx.seed,
        done.wall_seconds,
        esc(&setting_line(ctx))
    );
    page.push(&intro(Some(ctx)));
    let section = Section {
        id: "run",
        title: ctx.name.clone(),
        ctx,
        done,
        paper: None,
        link: None,
        spread: None,
        overall: None,
    };
    page.push(&toc("run"));
    render_section(&mut page, &section, 2);
    page.push(&files_list());
    page.finish()
}

/// `report.html` of `reproduce`: both settings, with the paper's values beside ours; `fitness`
/// is the study's fitness figure (medians and inter-quartile bands over seeds, `fitness.svg`).
pub fn reproduce_page(
    sections: &[Section<'_>],
    provenance: &str,
    overrides: &[String],
    wall: f64,
    claims: &str,
    fitness: &str,
) -> String {
    let mut page = Page::new("fuzzymotiv — the paper's study reproduced");
    let _ = writeln!(
        page.body,
        "<h1>The paper's study, reproduced</h1>\n<p class=\"meta\">{} · wall time {wall:.2} s{}</p>",
        esc(provenance),
        if overrides.is_empty() {
            String::new()
        } else {
            format!(" · overrides: {}", esc(&overrides.join(", ")))
        }
    );
    page.push(&intro(None));
    page.push(
        "<p>Two motivation settings from the paper are evolved separately: <b>high curiosity</b> \
         (C, H, O, E) = (0.8, 0.1, 0, 0.1) and <b>low curiosity</b> (0.5, 0.3, 0, 0.2). The paper \
         reports that high curiosity explores 92–100 % of the optimum and recognises rooms well, \
         while low curiosity explores less and recognises rooms poorly. Trends, not digits, are the \
         target: the numbers below come from the simulation, not from tuning.</p>\n",
    );
    let _ = writeln!(page.body, "<nav class=\"toc\"><b>Settings:</b> ");
    for s in sections {
        let _ = write!(page.body, r##"<a href="#{}">{}</a>"##, s.id, esc(&s.title));
    }
    page.push("</nav>\n");
    // Overview: both settings' fitness curves side by side, then the headline numbers.
    page.push("<h2 id=\"overview\">Overview</h2>\n");
    figure(
        &mut page,
        fitness,
        "Fitness evolution of both settings over all seeds: in every generation, the median over seeds of the population's best F (red) and of its mean F (blue), each with its inter-quartile band (25th to 75th percentile over seeds); with one seed, that seed's curves.",
    );
    overview_table(&mut page, sections);
    page.push(claims);
    for s in sections {
        let _ = writeln!(
            page.body,
            "<h2 id=\"{}\">Setting: {}</h2>\n<p class=\"meta\">{}{}</p>",
            s.id,
            esc(&s.title),
            esc(&setting_line(s.ctx)),
            s.link.as_ref().map_or(String::new(), |l| format!(
                " · its run directory's own report: <a href=\"{}\">{}</a>",
                esc(l),
                esc(l)
            ))
        );
        if let Some(spread) = s.spread {
            let _ = writeln!(
                page.body,
                "<h3 id=\"{}-seeds\">Over all seeds</h3>\n{spread}",
                s.id
            );
        }
        page.push(&toc(s.id));
        render_section(&mut page, s, 3);
    }
    page.finish()
}

/// `report.html` of a study of studies (`reproduce --combination`, `--replication`,
/// `--urgency`): its tables (the Markdown it prints, [`markdown_html`]), its figures with their
/// captions, and links to the reports of its parts (relative paths).
pub fn study_page(
    title: &str,
    wall: f64,
    markdown: &str,
    figures: &[(&str, &str)],
    links: &[(String, String)],
) -> String {
    let mut page = Page::new(format!("fuzzymotiv — {title}"));
    let _ = writeln!(
        page.body,
        "<h1>{}</h1>\n<p class=\"meta\">{} · wall time of this invocation {wall:.2} s</p>",
        esc(title),
        esc(&fuzzymotiv::provenance())
    );
    page.push(&markdown_html(markdown));
    for (svg, caption) in figures {
        figure(&mut page, svg, caption);
    }
    if !links.is_empty() {
        page.push("<h2 id=\"parts\">Its parts' own reports</h2>\n<ul>\n");
        for (href, label) in links {
            let _ = writeln!(
                page.body,
                "<li><a href=\"{}\">{}</a></li>",
                esc(href),
                esc(label)
            );
        }
        page.push("</ul>\n");
    }
    page.finish()
}

/// The Markdown the study commands print, as HTML: each run of `|` lines a table (its second
/// line, the `|---|` rule, dropped; the first the header), every other non-empty line a
/// paragraph of its own; everything escaped, `**bold**` cells kept bold.
pub fn markdown_html(md: &str) -> String {
    let cells = |line: &str| -> Vec<String> {
        let inner = line.trim().trim_start_matches('|').trim_end_matches('|');
        inner.split('|').map(|c| bold(&esc(c.trim()))).collect()
    };
    let mut html = String::new();
    let mut table: Vec<&str> = Vec::new();
    let flush = |table: &mut Vec<&str>, html: &mut String| {
        if table.is_empty() {
            return;
        }
        html.push_str("<table>\n");
        for (k, line) in table.iter().enumerate() {
            if k == 1 && line.trim_start_matches('|').starts_with("---") {
                continue;
            }
            let tag = if k == 0 { "th" } else { "td" };
            html.push_str("<tr>");
            for c in cells(line) {
                let _ = write!(html, "<{tag}>{c}</{tag}>");
            }
            html.push_str("</tr>\n");
        }
        html.push_str("</table>\n");
        table.clear();
    };
    for line in md.lines() {
        if line.trim_start().starts_with('|') {
            table.push(line);
            continue;
        }
        flush(&mut table, &mut html);
        if !line.trim().is_empty() {
            let _ = writeln!(html, "<p>{}</p>", bold(&esc(line.trim())));
        }
    }
    flush(&mut table, &mut html);
    html
}

/// `**x**` (already escaped text) as `<b>x</b>`.
fn bold(text: &str) -> String {
    let parts: Vec<&str> = text.split("**").collect();
    if parts.len() < 3 || parts.len().is_multiple_of(2) {
        return text.to_string();
    }
    parts
        .iter()
        .enumerate()
        .map(|(k, p)| {
            if k % 2 == 1 {
                format!("<b>{p}</b>")
            } else {
                (*p).to_string()
            }
        })
        .collect()
}

/// The headline numbers of every setting: mean % exploration, % recognition and % battery,
/// with the paper's beside them.
fn overview_table(page: &mut Page, sections: &[Section<'_>]) {
    page.push("<table><tr><th>setting</th><th>mean % optimal exploration</th><th>mean % recognition</th><th>mean % battery usage</th></tr>\n");
    for s in sections {
        let rows = &s.done.rows;
        let n = rows.len().max(1) as f64;
        let mean = |f: &dyn Fn(&RoomRow) -> f64| rows.iter().map(f).sum::<f64>() / n;
        let paper = s.paper.map(|p| {
            let m = |k: usize| {
                p.paper.iter().map(|r| [r.2, r.3, r.4][k]).sum::<f64>() / p.paper.len() as f64
            };
            [m(0), m(1), m(2)]
        });
        let cell = |v: f64, k: usize| match paper {
            Some(p) => format!("{v:.1} <span class=\"paper\">(paper {:.1})</span>", p[k]),
            None => format!("{v:.1}"),
        };
        let own = [
            Some(mean(&|r| r.exploration_pct)),
            rows.iter()
                .all(|r| r.recognition_pct.is_some())
                .then(|| mean(&|r| r.recognition_pct.unwrap_or(0.0))),
            Some(mean(&|r| r.battery_pct)),
        ];
        let [explore, rec, battery] = s.overall.unwrap_or(own);
        let rec = rec.map_or("n/a".into(), |v| cell(v, 1));
        let _ = writeln!(
            page.body,
            r##"<tr><td><a href="#{}">{}</a></td><td>{}</td><td>{}</td><td>{}</td></tr>"##,
            s.id,
            esc(&s.title),
            explore.map_or("n/a".into(), |v| cell(v, 0)),
            rec,
            battery.map_or("n/a".into(), |v| cell(v, 2))
        );
    }
    page.push(
        "</table>\n<p class=\"caption\">Means over the rooms (and over the seeds, on a multi-seed study) of each setting.</p>\n",
    );
}

/// A replay page for trajectories replayed by `fuzzymotiv replay`.
pub fn replay_page(
    title: &str,
    about: &str,
    ctx: &RenderContext,
    trials: &[(usize, String, InstanceRun)],
) -> String {
    replay_page_with(title, about, ctx, trials, &[])
}

/// [`replay_page`] with logged paths drawn over their rooms in the figure
/// ([`trajectories_svg_with`]; `fuzzymotiv replay --log`).
pub fn replay_page_with(
    title: &str,
    about: &str,
    ctx: &RenderContext,
    trials: &[(usize, String, InstanceRun)],
    logs: &[LoggedPath],
) -> String {
    let mut page = Page::new(title.to_string());
    let _ = writeln!(
        page.body,
        "<h1>{}</h1>\n<p class=\"meta\">{}</p>",
        esc(title),
        esc(about)
    );
    page.push(&format!(
        "<p>The robot ({}) is replayed step by step from its home pose: the circle is its body \
         ({} mm radius), the dark line its heading, the coloured rays its {} infrared \
         sensors (grey = nothing seen, red and thick = a wall very close). Green cells are the 50 mm \
         cells its centre has entered so far, which is what the exploration term a counts. Each step \
         also shows the action label the controller's motor outputs give (straight, left30, right30, \
         turn180), the symbols room recognition works with.</p>\n",
        robot_title(ctx.robot),
        ctx.robot_radius,
        count_word(ctx.robot.sensors())
    ));
    let pairs: Vec<_> = trials
        .iter()
        .map(|(r, _, run)| (&ctx.rooms[*r], &run.trajectory))
        .collect();
    let caption = "Top-down view of every replayed room: green circle = home pose, red line = path, filled circle = where the trial ended.";
    let logged = " Dashed, in a colour of its own: a logged path (--log), a square at its end.";
    figure(
        &mut page,
        &trajectories_svg_with("Replayed paths", &pairs, logs),
        &if logs.is_empty() {
            caption.to_string()
        } else {
            format!("{caption}{logged}")
        },
    );
    let rooms = trials
        .iter()
        .map(|(r, label, tr)| replay_room(ctx, *r, label, tr))
        .collect();
    page.replay(ctx, rooms);
    page.finish()
}

/// The motivations as "(C, H, O, E)" numbers, or "(name = weight, …)" for others.
pub fn xs(ctx: &RenderContext) -> String {
    let m = &ctx.motivations;
    if m.table.is_empty() {
        format!(
            "({}, {}, {}, {})",
            m.curiosity, m.homing, m.orientation, m.energy
        )
    } else {
        format!("({})", m.label())
    }
}

fn setting_line(ctx: &RenderContext) -> String {
    let motivations = if ctx.motivations.table.is_empty() {
        format!("(C, H, O, E) = {}", xs(ctx))
    } else {
        ctx.motivations.label()
    };
    format!(
        "motivations {motivations} · rooms {} · {} · population {} × {} generations · {} steps per trial",
        ctx.room_names().join(", "),
        match ctx.training {
            Training::AllRooms => "one robot evolved in all rooms",
            Training::PerRoom => "one robot evolved per room",
        },
        ctx.population,
        ctx.generations,
        ctx.steps
    )
}

/// The page's opening paragraph: the paper's words, or for a run of other motivations (`ctx`
/// with a motivation table) the number and names of its terms and motivations.
fn intro(ctx: Option<&RenderContext>) -> String {
    if let Some(ctx) = ctx.filter(|c| !c.motivations.table.is_empty()) {
        return motivations_intro(ctx);
    }
    let names: Vec<String> = NAMES
        .iter()
        .map(|(symbol, name, _)| format!("{name} {symbol}"))
        .collect();
    format!(
        "<p>A population of simulated {} robots, each controlled by a small neural network, is \
         evolved by a genetic algorithm. A robot's fitness F combines four measured fitness terms \
         ({}) through a fuzzy rule base weighted by the \
         robot's <i>motivations</i> (curiosity C, homing H, orientation O, energy E). The best robot of \
         the last generation is then asked to recognise rooms from its own sequence of actions.</p>\n",
        robot_words(ctx),
        names.join(", ")
    )
}

/// What the opening paragraph calls the robots: the paper's "Khepera", else the robot file's
/// title (e.g. "GCtronic e-puck2") and its sensor count.
fn robot_words(ctx: Option<&RenderContext>) -> String {
    match ctx.map(|c| c.robot) {
        Some(robot) if robot.name() != "khepera" => {
            format!(
                "{} ({} proximity sensors)",
                robot_title(robot),
                robot.sensors()
            )
        }
        _ => "Khepera".to_string(),
    }
}

/// A robot as the pages name it: "Khepera" for the paper's, else its file's title (escaped).
fn robot_title(robot: &fuzzymotiv::simulation::RobotSpec) -> String {
    if robot.name() == "khepera" {
        "Khepera".to_string()
    } else {
        esc(robot.title())
    }
}

/// [`intro`] of a run whose motivations are not the paper's four: F combines the terms its
/// motivations weigh (their number and names), and the terms it measures besides are named.
fn motivations_intro(ctx: &RenderContext) -> String {
    let table = &ctx.motivations.table;
    let mut terms: Vec<&str> = Vec::new();
    for m in table {
        if !terms.contains(&m.term.as_str()) {
            terms.push(&m.term);
        }
    }
    let term_words: Vec<String> = (terms.iter())
        .map(|t| match NAMES.iter().find(|(symbol, ..)| symbol == t) {
            Some((symbol, name, _)) => format!("{name} {symbol}"),
            None => t.to_string(),
        })
        .collect();
    let names: Vec<&str> = table.iter().map(|m| m.name.as_str()).collect();
    let unweighted = unweighted_terms(ctx);
    let besides = if unweighted.is_empty() {
        String::new()
    } else {
        format!(
            " The run also measures {}, which no motivation weighs: they are reported in the results per room, not combined into F.",
            esc(&joined_list(&unweighted, "and"))
        )
    };
    format!(
        "<p>A population of simulated {} robots, each controlled by a small neural network, is \
         evolved by a genetic algorithm. A robot's fitness F combines {} measured fitness terms \
         ({}) through a fuzzy rule base weighted by the robot's {} <i>motivations</i> ({}), each \
         weighing one of these terms.{besides} The best robot of the last generation is then \
         asked to recognise rooms from its own sequence of actions.</p>\n",
        robot_words(Some(ctx)),
        count_word(terms.len()),
        esc(&term_words.join(", ")),
        count_word(names.len()),
        esc(&names.join(", "))
    )
}

/// The terms a run measures beyond a, g, l, b that none of its motivations weighs (a
/// mission's `goal` and `safety` when only `urgency` is weighed).
fn unweighted_terms(ctx: &RenderContext) -> Vec<&str> {
    let weighed = |name: &str| ctx.motivations.table.iter().any(|m| m.term == name);
    (ctx.extra_terms.iter())
        .map(|(name, _)| name.as_str())
        .filter(|name| !weighed(name))
        .collect()
}

/// A count (of motivations, terms or sensors) in words, in digits past eight.
fn count_word(n: usize) -> String {
    const WORDS: [&str; 9] = [
        "no", "one", "two", "three", "four", "five", "six", "seven", "eight",
    ];
    WORDS.get(n).map_or(n.to_string(), |w| w.to_string())
}

/// The caption of the terms figure: the paper's, or for other motivations what its curves
/// are and which measured terms it leaves out.
fn terms_caption(ctx: &RenderContext) -> String {
    const PAPER: &str = "The population's mean fitness terms per generation: which behaviour the motivations pushed the population towards.";
    if ctx.motivations.table.is_empty() {
        return PAPER.to_string();
    }
    let unweighted = unweighted_terms(ctx);
    let left_out = if unweighted.is_empty() {
        String::new()
    } else {
        format!(
            " The terms no motivation weighs ({}) are not drawn: the results per room give their values.",
            joined_list(&unweighted, "and")
        )
    };
    format!(
        "The population's mean of each motivation's term per generation, one curve per motivation, named with the term it weighs in brackets when the two names differ: which behaviour the motivations pushed the population towards.{left_out}"
    )
}

fn toc(id: &str) -> String {
    let items = [
        ("fitness", "Fitness evolution"),
        ("rooms", "Results per room"),
        ("fuzzy", "Fuzzy fitness of the best robot"),
        ("paths", "Paths and replay"),
        ("aem", "Room recognition"),
        ("config", "Configuration"),
    ];
    let mut s = String::from("<nav class=\"toc\">");
    for (k, name) in items {
        let _ = write!(s, r##"<a href="#{id}-{k}">{name}</a>"##);
    }
    s.push_str("</nav>\n");
    s
}

fn figure(page: &mut Page, svg: &str, caption: &str) {
    let _ = writeln!(
        page.body,
        "<div class=\"figure\">{svg}</div>\n<p class=\"caption\">{}</p>",
        esc(caption)
    );
}

fn heading(page: &mut Page, level: u8, id: &str, part: &str, text: &str) {
    let _ = writeln!(page.body, "<h{level} id=\"{id}-{part}\">{text}</h{level}>");
}

fn render_section(page: &mut Page, s: &Section<'_>, level: u8) {
    let done = s.done;
    let names = s.ctx.room_names();
    let label = |evo: &fuzzymotiv::experiment::Evolution| match s.ctx.training {
        Training::AllRooms => s.title.clone(),
        Training::PerRoom => format!("{}: robot evolved in {}", s.title, evo.run.label),
    };

    // Fitness evolution.
    heading(page, level, s.id, "fitness", "Fitness evolution");
    let panels: Vec<_> = done
        .outcome
        .evolutions
        .iter()
        .map(|e| (label(e), e.history.clone()))
        .collect();
    figure(
        page,
        &fitness_svg(&panels),
        "Best F (red) and mean F (blue) of the population in every generation; the shaded band spans the population's minimum to maximum F. Evaluations are noisy (6 % sensor and motor noise), so the best F can drop between generations.",
    );
    figure(
        page,
        &terms_svg_of(
            &panels,
            &term_curves(&s.ctx.motivations.table, &s.ctx.extra_terms),
        ),
        &terms_caption(s.ctx),
    );

    // Per-room table.
    heading(page, level, s.id, "rooms", "Results per room");
    rooms_table(page, s);

    // Fuzzy fitness.
    heading(
        page,
        level,
        s.id,
        "fuzzy",
        "Fuzzy fitness of the best robot",
    );
    fuzzy::fuzzy_part(page, s);

    // Paths and replay.
    heading(page, level, s.id, "paths", "Paths and replay");
    paths_part(page, s);

    // Room recognition.
    heading(
        page,
        level,
        s.id,
        "aem",
        "Room recognition (action-based environment modelling)",
    );
    aem_part(page, s, &names);

    // Configuration.
    heading(page, level, s.id, "config", "Configuration");
    let _ = writeln!(
        page.body,
        "<p>The fully resolved configuration (every key, with the seed); run it again with <code>fuzzymotiv run config.resolved.toml</code>. Wall time of this run: {:.2} s.</p>\n<details><summary>config.resolved.toml</summary><pre class=\"config\">{}</pre></details>",
        done.wall_seconds,
        esc(&s.ctx.config_text)
    );
}

/// The per-room table, with the paper's values on the reproduce page; a run that follows
/// missions or measures more terms has `table.md`'s further columns ([`extra_columns`]).
fn rooms_table(page: &mut Page, s: &Section<'_>) {
    let done = s.done;
    let extra = extra_columns(&done.rows);
    let head: String = (extra.iter())
        .map(|c| format!("<th>{}</th>", esc(c)))
        .collect();
    let _ = writeln!(
        page.body,
        "<table><tr><th>room</th><th>average fitness</th><th>% optimal exploration</th><th>% recognition</th><th>% battery usage</th><th>% homing</th>{head}</tr>"
    );
    for r in &done.rows {
        let p = s
            .paper
            .and_then(|set| set.paper.iter().find(|p| p.0 == r.room));
        let paper = |v: Option<f64>, digits: usize| match v {
            Some(v) => format!(" <span class=\"paper\">(paper {v:.digits$})</span>"),
            None => String::new(),
        };
        let cells: String = (extra_cells(r).iter())
            .map(|c| format!("<td>{c}</td>"))
            .collect();
        let _ = writeln!(
            page.body,
            "<tr><td>{}</td><td>{:.4}{}</td><td>{:.1}{}</td><td>{}{}</td><td>{:.1}{}</td><td>{:.1}</td>{cells}</tr>",
            esc(&r.room),
            r.average_fitness,
            paper(p.map(|p| p.1), 4),
            r.exploration_pct,
            paper(p.map(|p| p.2), 2),
            r.recognition_pct
                .map_or("n/a".to_string(), |v| format!("{v:.0}")),
            paper(p.map(|p| p.3), 0),
            r.battery_pct,
            paper(p.map(|p| p.4), 2),
            r.homing_pct
        );
    }
    let _ = writeln!(
        page.body,
        "</table>\n<p class=\"caption\"><b>average fitness</b>: mean F of the final generation's population in that room. The other columns come from {} test runs of the best robot per room (fresh noise each): <b>% optimal exploration</b> = mean 100·a, <b>% recognition</b> = share of test runs whose room was recognised correctly, <b>% battery usage</b> = mean 100·b, <b>% homing</b> = mean 100·g.{}{}</p>",
        s.ctx.aem.test_runs,
        if extra.is_empty() {
            ""
        } else {
            " <b>% missions done</b> = share of test runs whose mission was done (the room's waypoints visited and its goal reached); <b>% <i>term</i></b> = mean 100·term of each term beyond a, g, l, b the run measures (whether a motivation weighs it or not)."
        },
        if s.paper.is_some() {
            " Grey: the paper's value (Tables 1 and 2)."
        } else {
            ""
        }
    );
}

/// The best robot's paths (its room-modelling runs) and their replay.
fn paths_part(page: &mut Page, s: &Section<'_>) {
    let (ctx, done) = (s.ctx, s.done);
    figure(
        page,
        &best_paths_svg(
            &format!("Best robot, {}", s.title),
            &ctx.rooms,
            &done.trajectories(),
        ),
        "Each room to scale, seen from above: green circle and line = home pose (start of every trial), red line = the best robot's path in its room-modelling run (the run whose actions became the room's stored instance), filled circle = where it ended.",
    );
    page.push(
        "<p>The replay below animates those same runs. The circle is the robot's body, the dark \
         line its heading, the coloured rays its eight infrared sensors (grey and thin = nothing \
         within reach, red and thick = a wall very close). Green cells are the 50 mm cells its \
         centre has entered so far, which is what the exploration term a counts. The panel on the \
         right shows the sensor readings and motor outputs at the current step and the action label \
         the motors give (straight, left30, right30, turn180): the sequence of these labels is what \
         room recognition works with. The strip under the room shows the actions of all steps; \
         click it, drag the slider or use the arrow keys to move in time.</p>\n",
    );
    let rooms = (0..ctx.rooms.len())
        .map(|r| {
            let (evo, _) = done.outcome.robot_for_room(r);
            replay_room(ctx, r, &evo.run.label, done.outcome.instance(r))
        })
        .collect();
    page.replay(ctx, rooms);
}

fn aem_part(page: &mut Page, s: &Section<'_>, names: &[String]) {
    let (ctx, done) = (s.ctx, s.done);
    if !ctx.aem.enabled || done.outcome.modelling.iter().all(|a| a.som_nodes == 0) {
        page.push("<p>Room recognition was not run (<code>aem.enabled = false</code>).</p>\n");
        return;
    }
    let _ = writeln!(
        page.body,
        "<p>The best robot runs once in every room. Its sequence of actions becomes a chain code \
         (its cumulative heading change after every step) — the room's <b>environment vector</b>. A \
         one-dimensional self-organising map (SOM) of {} nodes is trained on these vectors; each \
         room's vector wins one node, its <b>r-node</b>. In a test run the robot's new vector wins \
         some node; rooms whose r-node lies within {} nodes of it are candidates, and the candidate \
         whose stored vector is nearest is the answer (no candidate = not recognised). Rooms whose \
         paths look alike get nearby r-nodes and are easily confused.</p>",
        ctx.aem.som_nodes, ctx.aem.threshold
    );
    for (k, rep) in done.outcome.modelling.iter().enumerate() {
        let rooms: Vec<SomRoom<'_>> = rep
            .rooms
            .iter()
            .filter_map(|r| {
                Some(SomRoom {
                    name: &r.room,
                    r_node: r.r_node?,
                    winners: r.tests.iter().filter_map(|t| t.winner).collect(),
                })
            })
            .collect();
        let title = match ctx.training {
            Training::AllRooms => "The rooms on the SOM line".to_string(),
            Training::PerRoom => format!(
                "The rooms on the SOM line of the robot evolved in {}",
                done.outcome.evolutions[k].run.label
            ),
        };
        figure(
            page,
            &som_svg(&title, rep.som_nodes, ctx.aem.threshold, &rooms),
            "Each room's r-node on the line of SOM nodes, with the window of nodes a test run's winner must fall in for that room to be a candidate; dots are the winners of the test runs, coloured by the room the robot was really in.",
        );
    }
    confusion_table(page, ctx, done, names);
}

fn confusion_table(page: &mut Page, ctx: &RenderContext, done: &Finished, names: &[String]) {
    page.push(
        "<h4>Confusion matrix</h4>\n<table class=\"cm\"><tr><th>true room ↓ / recognised as →</th>",
    );
    for (k, n) in names.iter().enumerate() {
        let _ = write!(
            page.body,
            "<th style=\"color:{}\">{}</th>",
            colour(k),
            esc(n)
        );
    }
    page.push("<th>not recognised</th><th>% correct</th></tr>\n");
    for (r, n) in names.iter().enumerate() {
        let rep = done.outcome.aem_for_room(r);
        let counts = &rep.confusion.counts[r];
        let total: u32 = counts.iter().sum();
        let _ = write!(
            page.body,
            "<tr><th class=\"left\" style=\"color:{}\">{}</th>",
            colour(r),
            esc(n)
        );
        for (a, &c) in counts.iter().enumerate() {
            let share = if total == 0 {
                0.0
            } else {
                f64::from(c) / f64::from(total)
            };
            let bg = if a == r {
                format!("rgba(44,160,44,{:.2})", 0.1 + 0.5 * share)
            } else if c > 0 {
                format!("rgba(214,39,40,{:.2})", 0.1 + 0.5 * share)
            } else {
                "transparent".to_string()
            };
            let _ = write!(
                page.body,
                "<td{} style=\"background:{bg}\">{c}</td>",
                if a == r { " class=\"hit\"" } else { "" }
            );
        }
        let _ = writeln!(page.body, "<td>{:.0}</td></tr>", rep.confusion.percent(r));
    }
    let _ = writeln!(
        page.body,
        "</table>\n<p class=\"caption\">Counts of test runs ({} per room, fresh noise each): row = the room the robot was in, column = the room it was recognised as. The diagonal (green outline) counts correct answers. The same numbers are in <code>recognition.csv</code>.</p>",
        ctx.aem.test_runs
    );
}

fn files_list() -> String {
    let files = [
        (
            "config.resolved.toml",
            "the resolved configuration (with seed and program version)",
        ),
        (
            "generations.csv",
            "per generation: best, mean, std, min, max F and mean a, g, l, b",
        ),
        (
            "best_genome.json",
            "the best robot's network weights (replay it with fuzzymotiv replay)",
        ),
        (
            "recognition.csv",
            "per room: test runs, correct answers, confusion counts",
        ),
        (
            "test_runs.csv",
            "every test run: room, % exploration, recognised or not, % battery, % homing (fuzzymotiv compare reads it)",
        ),
        ("table.md", "the per-room table"),
        ("summary.json", "headline numbers and wall time"),
        (
            "fitness.svg, terms.svg, trajectories.svg",
            "the figures of this page (PNG too with --png)",
        ),
    ];
    let mut s = String::from("<h2 id=\"files\">Files in this run directory</h2>\n<ul>\n");
    for (f, what) in files {
        let link = if f.contains(',') {
            esc(f)
        } else {
            format!("<a href=\"{f}\">{f}</a>")
        };
        let _ = writeln!(s, "<li>{link}: {what}</li>");
    }
    s.push_str("</ul>\n");
    s
}

#[cfg(test)]
mod tests {
    /// A study's Markdown becomes paragraphs and tables (the rule line dropped, the first line
    /// the header), escaped, bold kept; the page holds its figures, captions and links.
    #[test]
    fn a_study_page_holds_its_tables_figures_and_parts() {
        let md = "GA 10 × 3 <seeds>\n\n| a | b |\n|---|---|\n| 1 | **higher** |\n| 2 | x |\ntail";
        let html = super::markdown_html(md);
        assert_eq!(
            html,
            "<p>GA 10 × 3 &lt;seeds&gt;</p>\n<table>\n<tr><th>a</th><th>b</th></tr>\n<tr><td>1</td><td><b>higher</b></td></tr>\n<tr><td>2</td><td>x</td></tr>\n</table>\n<p>tail</p>\n"
        );
        let page = super::study_page(
            "The study",
            1.5,
            md,
            &[("<svg id=\"f\"></svg>", "The figure.")],
            &[("default/report.html".into(), "default".into())],
        );
        assert!(page.contains("<h1>The study</h1>"), "{page}");
        assert!(page.contains("<svg id=\"f\"></svg>") && page.contains("The figure."));
        assert!(page.contains(r#"<a href="default/report.html">default</a>"#));
        assert!(page.contains("<td><b>higher</b></td>"));
    }
}
