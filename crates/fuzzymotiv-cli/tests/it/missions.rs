//! Runs of more (or other) motivations than the paper's four and runs with missions: their
//! records carry the extra terms by name, their figures draw the missions; the paper's runs
//! keep their bytes (the goldens of `model.rs`).

use crate::common;

use std::path::{Path, PathBuf};

use common::{SMALL, ok, repo};

/// A small run of `configs/fetch.toml` (the paper's four motivations + urgency, a goal per
/// room) into `dir/run`, with `extra` `--set` values.
fn fetch_run(dir: &Path, extra: &[&str]) -> PathBuf {
    let out = dir.join("run");
    let config = repo().join("configs/fetch.toml");
    let mut args = vec!["run", config.to_str().unwrap()];
    for s in SMALL.iter().chain(extra) {
        args.extend(["--set", s]);
    }
    args.extend(["--set", "aem.enabled=false", "--out", out.to_str().unwrap()]);
    ok(&args);
    out
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&read(path)).unwrap()
}

#[test]
fn five_motivation_run_records_urgency_and_goal_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let run = fetch_run(dir.path(), &[]);
    let csv = read(&run.join("generations.csv"));
    let header = csv.lines().next().unwrap();
    assert_eq!(
        header,
        "generation,best,mean,std,min,max,a,g,l,b,goal,urgency,safety,room"
    );
    let genome = json(&run.join("best_genome.json"));
    let terms = &genome["terms"][0]["terms"];
    for name in ["goal", "urgency", "safety"] {
        let v = terms[name]
            .as_f64()
            .unwrap_or_else(|| panic!("no {name}: {terms}"));
        assert!((0.0..=1.0).contains(&v), "{name} = {v}");
    }
    let summary = json(&run.join("summary.json"));
    let table = summary["motivations"]["table"].as_array().unwrap();
    let names: Vec<&str> = table.iter().map(|m| m["name"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        ["curiosity", "homing", "orientation", "energy", "urgency"]
    );
    assert_eq!(table[4]["term"], "urgency");
    assert_eq!(table[4]["weight"], 0.3);
    let room = &summary["rooms"][0];
    assert!(room["mission_done_pct"].is_number(), "{room}");
    assert!(room["terms_pct"]["goal"].is_number(), "{room}");
    let md = read(&run.join("table.md"));
    assert!(
        md.lines()
            .next()
            .unwrap()
            .ends_with("| % missions done | % goal | % safety | % urgency |"),
        "{md}"
    );
}

#[test]
fn paper_run_records_have_no_extra_terms() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let config = repo().join("configs/high-curiosity.toml");
    let mut args = vec!["run", config.to_str().unwrap()];
    for s in SMALL {
        args.extend(["--set", s]);
    }
    args.extend(["--set", "aem.enabled=false", "--out", out.to_str().unwrap()]);
    ok(&args);
    let header = read(&out.join("generations.csv"));
    assert!(header.starts_with("generation,best,mean,std,min,max,a,g,l,b,room\n"));
    let summary = read(&out.join("summary.json"));
    for word in ["table", "terms_pct", "mission_done_pct"] {
        assert!(!summary.contains(word), "{word} in {summary}");
    }
    assert!(!read(&out.join("best_genome.json")).contains("\"terms\": {"));
    // The paper's words, table and curves: the four terms, named by their symbols.
    let page = read(&out.join("report.html"));
    assert!(page.contains("F combines four measured fitness terms (exploration a, homing g"));
    assert!(page.contains("<th>% homing</th></tr>"));
    let terms = read(&out.join("terms.svg"));
    for name in ["a exploration", "g homing", "l recognition", "b battery"] {
        assert!(terms.contains(&format!(">{name}</text>")), "no {name}");
    }
}

#[test]
fn fetch_run_draws_its_goal_in_the_figure_the_replay_and_the_report() {
    let dir = tempfile::tempdir().unwrap();
    let run = fetch_run(dir.path(), &[]);
    let svg = read(&run.join("trajectories.svg"));
    let goal_rims = svg
        .lines()
        .filter(|l| l.contains(r##"stroke="#ff7f0e""##) && l.contains("stroke-dasharray"))
        .count();
    assert_eq!(goal_rims, 5, "one dashed goal rim per room:\n{svg}");
    assert!(svg.contains("orange: goal zone"), "{svg}");
    assert!(read(&run.join("report.html")).contains(r#""goal":[730.0,730.0,60.0]"#));
    let page = dir.path().join("replay.html");
    ok(&[
        "replay",
        run.to_str().unwrap(),
        "--out",
        page.to_str().unwrap(),
    ]);
    let replay = json(&dir.path().join("replay.json"));
    let goal = &replay["rooms"][0]["goal"];
    assert_eq!(
        (goal["x"].as_f64(), goal["radius"].as_f64()),
        (Some(730.0), Some(60.0))
    );
}

/// `replay` of a run whose rooms have a goal and no waypoints prints each room's goal term and
/// leaves out the waypoints term, which does not apply there (no `waypoints = 0.000`).
#[test]
fn replay_of_rooms_without_waypoints_prints_no_waypoints_term() {
    let dir = tempfile::tempdir().unwrap();
    let run = fetch_run(dir.path(), &[]);
    let page = dir.path().join("replay.html");
    let out = ok(&[
        "replay",
        run.to_str().unwrap(),
        "--out",
        page.to_str().unwrap(),
    ]);
    let text = common::stdout(&out) + &common::stderr(&out);
    let lines: Vec<&str> = text.lines().filter(|l| l.contains(", F = ")).collect();
    assert_eq!(lines.len(), 5, "one line per room:\n{text}");
    for line in lines {
        assert!(
            line.contains(", goal = ") && line.contains(", urgency = "),
            "{line}"
        );
        assert!(!line.contains("waypoints"), "{line}");
    }
}

#[test]
fn paper_figures_draw_no_mission() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let config = repo().join("configs/tiny.toml");
    ok(&[
        "run",
        config.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let svg = read(&out.join("trajectories.svg"));
    assert!(!svg.contains("#ff7f0e") && !svg.contains("goal"), "{svg}");
}

/// A small merged sweep of the fetch mission over two motivation settings (curiosity 0.7 with
/// urgency 0.1; fetch's own) in two rooms, into `dir/out`.
fn fetch_sweep(dir: &Path) -> PathBuf {
    let rooms = repo().join("rooms");
    let sweep = format!(
        "rooms = [\"{}\", \"{}\"]\n[aem]\nenabled = false\n[ga]\npopulation = 6\ngenerations = 2\n\
         [trial]\nsteps = 60\n[motivations]\ncuriosity = 0.5\nhoming = 0.1\norientation = 0.0\n\
         energy = 0.1\nurgency = 0.3\n[sweep]\nmotivations = [{{ curiosity = 0.7, urgency = 0.1 }}, \
         [0.5, 0.1, 0.0, 0.1, 0.3]]\n",
        rooms.join("fetch-H.toml").display(),
        rooms.join("fetch-T.toml").display(),
    );
    let file = dir.join("sweep.toml");
    std::fs::write(&file, sweep).unwrap();
    let out = dir.join("out");
    ok(&[
        "sweep",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    ok(&["merge", out.to_str().unwrap()]);
    out
}

#[test]
fn a_sweep_over_named_motivations_merges_their_weights_and_missions_done() {
    let dir = tempfile::tempdir().unwrap();
    let out = fetch_sweep(dir.path());
    let csv = read(&out.join("results.csv"));
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    assert_eq!(
        header[5..10],
        [
            "curiosity",
            "homing",
            "orientation",
            "energy",
            "motivation.urgency"
        ]
    );
    assert_eq!(header.last(), Some(&"mission_done_pct"), "{csv}");
    let results =
        fuzzymotiv_pipeline::records::SweepResults::read(&out.join("results.csv")).unwrap();
    assert_eq!(results.motivations, ["urgency"]);
    let weights: Vec<(f64, Option<f64>)> = (results.rows.iter())
        .map(|r| (r.motivations.curiosity, r.other_weights[0]))
        .collect();
    assert_eq!(
        weights,
        [
            (0.7, Some(0.1)),
            (0.7, Some(0.1)),
            (0.5, Some(0.3)),
            (0.5, Some(0.3))
        ]
    );
    assert!(
        (results.rows.iter()).all(|r| r
            .mission_done_pct
            .is_some_and(|p| (0.0..=100.0).contains(&p))),
        "{csv}"
    );
    // Written and read by the same code: the file reads back to its own bytes.
    assert_eq!(results.to_csv(), csv);
}

/// `report.html` of a small run in fetch-H and fetch-T under the `[motivations]` table
/// `motivations` (its lines, TOML).
fn report_of_fetch_run(motivations: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let rooms = repo().join("rooms");
    let config = format!(
        "rooms = [\"{}\", \"{}\"]\n[aem]\nenabled = false\n[ga]\npopulation = 6\ngenerations = 2\n\
         [trial]\nsteps = 60\n[motivations]\n{motivations}",
        rooms.join("fetch-H.toml").display(),
        rooms.join("fetch-T.toml").display(),
    );
    let file = dir.path().join("motivations.toml");
    std::fs::write(&file, config).unwrap();
    let out = dir.path().join("run");
    ok(&[
        "run",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    read(&out.join("report.html"))
}

#[test]
fn the_report_shows_every_motivation_and_a_motivations_own_labels() {
    let page = report_of_fetch_run(
        "curiosity = 0.5\nhoming = 0.1\norientation = 0.0\nenergy = 0.1\n\
         hurry = { weight = 0.3, term = \"urgency\", peaks = [0, 0.5, 1] }\n",
    );
    for bar in ["<span>curiosity C</span>", "<span>hurry (urgency)</span>"] {
        assert!(page.contains(bar), "no bar {bar}");
    }
    // Four inputs of five labels and hurry's three: 5⁴ · 3 rules, at most 2⁵ firing.
    assert!(
        page.contains("M₁ × … × M_N = 5 × 5 × 5 × 5 × 3 = 1875 rules")
            && page.contains("at most 2^5 = 32 rules fire at once"),
        "the rule text does not follow the five inputs"
    );
    assert!(
        page.contains(">Membership of hurry&#39;s input (urgency) in its own labels</text>")
            || page.contains(">Membership of hurry's input (urgency) in its own labels</text>")
    );
    assert!(
        page.contains("<th>urgency</th>"),
        "no urgency column in the table of F"
    );
    assert!(page.contains(
        "motivations curiosity = 0.5, homing = 0.1, orientation = 0, energy = 0.1, hurry = 0.3"
    ));
}

/// `report.html` of a run of two motivations, curiosity and urgency, counts two inputs in its
/// rule text (5 × 5 rules, the smallest of two labels, at most 2² firing) and its membership
/// figure names their terms a and urgency, not the paper's four.
#[test]
fn report_of_a_two_motivation_run_counts_two_inputs_and_names_their_terms() {
    let page = report_of_fetch_run("curiosity = 0.7\nurgency = 0.3\n");
    for text in [
        "M₁ × … × M_N = 5 × 5 = 25 rules",
        "the smallest membership of its 2 labels",
        "at most 2^2 = 4 rules fire at once",
        "fitness value y (a or urgency)",
    ] {
        assert!(page.contains(text), "the report lacks {text:?}");
    }
    for text in ["× 5 × 5 × 5", "of its 4 labels", "2^4", "a, g, l or b"] {
        assert!(!page.contains(text), "the report still says {text:?}");
    }
}

/// `fuzzymotiv run c.toml` with `[motivations]` `table` (and the built-in rooms) is refused:
/// exit 2, nothing written, no panic; its stderr.
fn run_refused_with_motivations(dir: &Path, table: &str) -> String {
    let cfg = dir.join("c.toml");
    std::fs::write(&cfg, format!("[motivations]\n{table}")).unwrap();
    let out = dir.join("o");
    let o = common::Fm::new(["run", cfg.to_str().unwrap()])
        .out(&out)
        .sets(&SMALL)
        .run();
    let e = common::stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(!out.exists(), "a refused run wrote {}", out.display());
    assert!(!e.contains("panicked"), "{e}");
    assert!(e.contains("c.toml"), "the file is named: {e}");
    e
}

/// Nine motivations (at most eight), five whose weights sum to 1.2, and a motivation bound to
/// a term that does not exist: each exits 2 naming the file and the field, writing nothing.
#[test]
fn bad_motivation_tables_exit_2_naming_the_file_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let nine: String = (0..9)
        .map(|k| format!("m{k} = {{ weight = 0.1, term = \"a\" }}\n"))
        .collect();
    let e = run_refused_with_motivations(dir.path(), &nine);
    assert!(
        e.contains("`motivations`") && e.contains("from 1 to 8"),
        "{e}"
    );
    let five = "curiosity = 0.5\nhoming = 0.2\norientation = 0.0\nenergy = 0.2\n\
                care = { weight = 0.3, term = \"safety\" }\n";
    let e = run_refused_with_motivations(dir.path(), five);
    assert!(
        e.contains("`motivations`") && e.contains("sum to 1") && e.contains("1.2"),
        "{e}"
    );
    assert!(e.contains("care 0.3"), "each weight is shown: {e}");
    let e = run_refused_with_motivations(
        dir.path(),
        "curiosity = 0.5\nhoming = 0.0\nenergy = 0.0\nrush = { weight = 0.5, term = \"speed\" }\n",
    );
    assert!(
        e.contains("`motivations.rush`") && e.contains("\"speed\"") && e.contains("does not exist"),
        "{e}"
    );
}

/// `robustness` of a five-motivation mission run reports, beside F, a, g and b, the share of
/// missions done and every term beyond a, g, l, b that `table.md` shows (urgency, the fifth
/// motivation's, among them): in the CSV, the Markdown and the figure.
#[test]
fn robustness_of_a_mission_run_reports_urgency_and_missions_done_in_table_md_order() {
    let dir = tempfile::tempdir().unwrap();
    let run = fetch_run(dir.path(), &[]);
    let out = dir.path().join("rob");
    common::Fm::new(["robustness", run.to_str().unwrap(), "--trials", "2"])
        .out(&out)
        .ok();
    let csv = read(&out.join("robustness.csv"));
    let header = csv.lines().next().unwrap();
    let extra = ["missions_done", "goal", "safety", "urgency"]
        .map(|m| format!("{m},{m}_lo,{m}_hi"))
        .join(",");
    assert!(
        header.ends_with(&format!(",battery_hi,{extra}")),
        "{header}"
    );
    for line in csv.lines().skip(1) {
        let v: Vec<f64> = (line.split(',').skip(2))
            .map(|x| x.parse().unwrap())
            .collect();
        assert_eq!(v.len(), 3 * 8, "{line}");
        for c in v.chunks(3) {
            assert!(c[1] <= c[0] && c[0] <= c[2], "{line}");
        }
    }
    let md = read(&out.join("robustness.md"));
    assert!(
        md.lines()
            .next()
            .unwrap()
            .ends_with("| battery b | missions done | goal | safety | urgency |"),
        "{md}"
    );
    // The same terms in the same order as the run's table.md.
    let table = read(&run.join("table.md"));
    let columns = |line: &str| -> Vec<String> {
        let cells = line.split('|').map(|c| c.trim().trim_start_matches("% "));
        cells
            .skip_while(|c| *c != "missions done")
            .map(String::from)
            .collect()
    };
    let table_header = table
        .lines()
        .find(|l| l.contains("% missions done"))
        .unwrap();
    assert_eq!(
        columns(md.lines().next().unwrap()),
        columns(table_header),
        "{table}"
    );
    let stems: Vec<String> = (header.split(',').skip_while(|c| *c != "missions_done"))
        .filter(|c| !c.ends_with("_lo") && !c.ends_with("_hi"))
        .map(|c| c.replace('_', " "))
        .collect();
    let mut in_table = columns(table_header);
    in_table.retain(|c| !c.is_empty());
    assert_eq!(stems, in_table, "{header}");
    let svg = read(&out.join("robustness.svg"));
    for panel in ["missions done", "urgency"] {
        assert!(
            svg.contains(&format!(">{panel}</text>")),
            "no {panel} panel"
        );
    }
}

/// `compare` of two five-motivation mission runs compares, beside the paper's measures, the
/// share of missions done and every term beyond a, g, l, b that both runs' `table.md` shows
/// (urgency, the fifth motivation's, among them): in compare.csv, compare.md and the figure.
#[test]
fn compare_of_two_mission_runs_compares_urgency_and_missions_done() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    std::fs::create_dir_all(&a).unwrap();
    std::fs::create_dir_all(&b).unwrap();
    let run_a = fetch_run(&a, &[]);
    let run_b = fetch_run(&b, &["seed=2"]);
    let out = dir.path().join("cmp");
    common::Fm::new(["compare", run_a.to_str().unwrap(), run_b.to_str().unwrap()])
        .out(&out)
        .ok();
    let rows = fuzzymotiv_pipeline::records::compare::read(&out.join("compare.csv")).unwrap();
    let mut metrics: Vec<&str> = rows.iter().map(|r| r.metric.as_str()).collect();
    metrics.dedup();
    assert_eq!(
        metrics,
        [
            "exploration_pct",
            "battery_pct",
            "homing_pct",
            "mission_done_pct",
            "goal_pct",
            "safety_pct",
            "urgency_pct"
        ]
    );
    let urgency: Vec<&str> = (rows.iter())
        .filter(|r| r.metric == "urgency_pct")
        .map(|r| r.room.as_str())
        .collect();
    assert_eq!(urgency.len(), 6, "five rooms and overall: {urgency:?}");
    let md = read(&out.join("compare.md"));
    for heading in ["## fetch: % missions done", "## fetch: % urgency"] {
        assert!(md.contains(heading), "no {heading}:\n{md}");
    }
    let svg = read(&out.join("compare.svg"));
    assert!(svg.contains(">% urgency</text>"), "no urgency panel");
}

/// The terms figure of a five-motivation mission run draws one curve per motivation, its
/// legend naming the motivation as the title does, with the term it weighs (`curiosity (a)`,
/// `urgency`); the mission terms no motivation weighs (goal, safety) are not drawn.
#[test]
fn terms_figure_of_a_mission_run_names_each_motivation_with_its_term_and_draws_no_unweighted_term()
{
    let dir = tempfile::tempdir().unwrap();
    let run = fetch_run(dir.path(), &[]);
    let svg = read(&run.join("terms.svg"));
    assert!(svg.contains("energy = 0.1, urgency = 0.3</text>"), "{svg}");
    let legends = [
        "curiosity (a)",
        "homing (g)",
        "orientation (l)",
        "energy (b)",
        "urgency",
    ];
    for name in legends {
        assert!(
            svg.contains(&format!(">{name}</text>")),
            "no {name}:\n{svg}"
        );
    }
    assert_eq!(svg.matches("<polyline").count(), legends.len(), "{svg}");
    for name in ["goal", "safety", "a exploration"] {
        assert!(!svg.contains(&format!(">{name}</text>")), "{name}:\n{svg}");
    }
}

/// `report.html` of a five-motivation mission run says how many terms F combines and names
/// them with the five motivations and the terms it measures besides; its table of results per
/// room has `table.md`'s further columns, "% missions done" and each term's.
#[test]
fn report_of_a_mission_run_names_its_five_terms_and_has_the_missions_done_column() {
    let dir = tempfile::tempdir().unwrap();
    let run = fetch_run(dir.path(), &[]);
    let page = read(&run.join("report.html"));
    assert!(
        page.contains(
            "F combines five measured fitness terms (exploration a, homing g, recognition l, \
             battery b, urgency) through a fuzzy rule base weighted by the robot's five \
             <i>motivations</i> (curiosity, homing, orientation, energy, urgency)"
        ),
        "the intro does not name the run's terms"
    );
    assert!(page.contains("also measures goal and safety, which no motivation weighs"));
    assert!(!page.contains("combines four"));
    let md = read(&run.join("table.md"));
    let header = md.lines().next().unwrap();
    let further: Vec<&str> = (header.split(" | "))
        .skip_while(|c| *c != "% homing")
        .skip(1)
        .map(|c| c.trim_end_matches(" |"))
        .collect();
    assert_eq!(
        further,
        ["% missions done", "% goal", "% safety", "% urgency"]
    );
    let th: String = further.iter().map(|c| format!("<th>{c}</th>")).collect();
    assert!(
        page.contains(&format!("<th>% homing</th>{th}</tr>")),
        "the table of results per room lacks {th}"
    );
}

/// `compare` of two settings of a mission sweep compares their % missions done too.
#[test]
fn compare_of_two_mission_sweep_settings_compares_missions_done() {
    let dir = tempfile::tempdir().unwrap();
    let sweep = fetch_sweep(dir.path());
    let out = dir.path().join("cmp");
    let (a, b) = (
        "curiosity=0.7,urgency=0.1",
        "curiosity=0.5,homing=0.1,orientation=0,energy=0.1,urgency=0.3",
    );
    let s = sweep.to_str().unwrap();
    common::Fm::new(["compare", s, s, "--setting", a, "--setting", b])
        .out(&out)
        .ok();
    let rows = fuzzymotiv_pipeline::records::compare::read(&out.join("compare.csv")).unwrap();
    let done = rows
        .iter()
        .filter(|r| r.metric == "mission_done_pct")
        .count();
    assert_eq!(done, 3, "two rooms and overall");
    assert!(read(&out.join("compare.md")).contains(": % missions done\n"));
}
