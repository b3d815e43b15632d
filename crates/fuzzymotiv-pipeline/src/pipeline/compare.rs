//! `fuzzymotiv compare A B`: two outputs of the same kind and rooms — two run directories (over
//! their test runs, `test_runs.csv`), two studies (over seeds) or settings of sweeps (over
//! replicates) — read from their records, checked, and compared setting by setting
//! ([`crate::render::compare`]): `compare.md`, `compare.csv` and `compare.svg`. Beside the
//! paper's metrics, two runs that follow missions or weigh terms of their own are compared on
//! `% missions done` and each term beyond a, g, l, b that both have (their `test_runs.csv`), and
//! two sweeps on `% missions done` when both follow missions.

use std::path::{Path, PathBuf};

use fuzzymotiv::statistics::Settings;

use crate::files::error::CliError;
use crate::files::guard::{FilesState, check_files_dir, io_err, write_into};
use crate::pipeline::claims::check_alpha;
use crate::records::compare::{self as compare_csv, CompareRow};
use crate::records::{
    METRICS, RunSummary, StudySummary, SweepResults, TableRow, read_json, test_runs,
};
use crate::render::compare::{
    Group, MISSION_DONE, Unit, compare_groups, compare_md, compare_svg, pairing,
};
use crate::render::figures::Rasterise;

/// What an output directory is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// `fuzzymotiv run`: compared over its test runs.
    Run,
    /// `fuzzymotiv reproduce`: compared over seeds, setting by setting.
    Study,
    /// A merged sweep: compared over a setting's replicates.
    Sweep,
}

impl Kind {
    /// The kind in words.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Run => "a run directory",
            Kind::Study => "a study directory (reproduce)",
            Kind::Sweep => "a sweep directory",
        }
    }

    /// What one value of a sample is.
    pub fn unit(self) -> &'static str {
        match self {
            Kind::Run => "test runs",
            Kind::Study => "seeds",
            Kind::Sweep => "replicates",
        }
    }
}

/// One output, read: its kind, rooms and settings.
#[derive(Debug, Clone)]
pub struct Side {
    /// The directory.
    pub dir: PathBuf,
    /// Its kind.
    pub kind: Kind,
    /// Its rooms, in order.
    pub rooms: Vec<String>,
    /// Its settings (a run has one).
    pub groups: Vec<Group>,
}

/// Reads an output directory for a comparison; `which` ("A" or "B") names it in errors.
pub fn load(dir: &Path, which: &str) -> Result<Side, CliError> {
    let at = || format!("{which} ({})", dir.display());
    if !dir.is_dir() {
        return Err(CliError::input(format!(
            "{}: not a directory; give a run, study or sweep directory",
            at()
        )));
    }
    if dir.join("plan.jsonl").is_file() {
        return load_sweep(dir, &at());
    }
    let summary = dir.join("summary.json");
    if !summary.is_file() {
        return Err(CliError::input(format!(
            "{}: no summary.json or plan.jsonl: not a finished run, study or sweep of fuzzymotiv",
            at()
        )));
    }
    let value: serde_json::Value = read_json(&summary)?;
    if value.get("variants").is_some() {
        return Err(CliError::input(format!(
            "{}: an ablation (reproduce --ablation): compare two of its variant directories \
             (each a study) instead",
            at()
        )));
    }
    if value.get("settings").is_some() {
        load_study(dir)
    } else {
        load_run(dir)
    }
}

fn row_values(r: &TableRow) -> Vec<Option<f64>> {
    vec![
        r.average_fitness,
        r.exploration_pct,
        r.recognition_pct,
        r.battery_pct,
        r.homing_pct,
    ]
}

fn load_study(dir: &Path) -> Result<Side, CliError> {
    let s: StudySummary = read_json(&dir.join("summary.json"))?;
    let rooms = s.settings.first().map_or(Vec::new(), |g| {
        g.rows.iter().map(|r| r.room.clone()).collect()
    });
    let groups = s
        .settings
        .iter()
        .map(|g| {
            let units = (g.per_seed.iter())
                .map(|seed| Unit {
                    key: format!("seed {}", seed.seed),
                    rooms: seed.rows.iter().map(row_values).collect(),
                })
                .collect();
            Group::new(g.name.clone(), &[], units)
        })
        .collect();
    Ok(Side {
        dir: dir.into(),
        kind: Kind::Study,
        rooms,
        groups,
    })
}

fn load_run(dir: &Path) -> Result<Side, CliError> {
    let s: RunSummary = read_json(&dir.join("summary.json"))?;
    let rows = test_runs::read(dir)?;
    let rooms: Vec<String> = s.rooms.iter().map(|r| r.room.clone()).collect();
    let tests = rows.iter().map(|r| r.test + 1).max().unwrap_or(0);
    // The run's own measures (missions done, then the terms beyond a, g, l, b in the tables'
    // order), by their columns.
    let (done, terms): (Vec<String>, Vec<String>) =
        rows.first().map_or_else(Default::default, |r| {
            r.extra
                .iter()
                .map(|(c, _)| c.clone())
                .partition(|c| c == MISSION_DONE)
        });
    let mut extra = done;
    extra.extend(test_runs::in_table_order(terms, |c| {
        test_runs::metric_term(c)
    }));
    let values = |r: &test_runs::TestRunRow| {
        let (a, b, g) = (r.exploration_pct, r.battery_pct, r.homing_pct);
        let paper = [None, Some(a), r.recognition_pct, Some(b), Some(g)];
        let own = (extra.iter()).map(|c| r.extra.iter().find(|(k, _)| k == c).map(|e| e.1));
        paper.into_iter().chain(own).collect()
    };
    let units = (0..tests)
        .map(|k| Unit {
            key: format!("seed {} test {k}", s.seed),
            rooms: (rooms.iter())
                .map(|room| {
                    (rows.iter())
                        .find(|r| r.test == k && &r.room == room)
                        .map_or(Vec::new(), values)
                })
                .collect(),
        })
        .collect();
    Ok(Side {
        dir: dir.into(),
        kind: Kind::Run,
        rooms,
        groups: vec![Group::new(s.name, &extra, units)],
    })
}

fn load_sweep(dir: &Path, at: &str) -> Result<Side, CliError> {
    let path = dir.join("results.csv");
    if !path.is_file() {
        return Err(CliError::input(format!(
            "{at}: a sweep directory without results.csv: merge it first (fuzzymotiv merge {})",
            dir.display()
        )));
    }
    let results = SweepResults::read(&path)?;
    let mut rooms: Vec<String> = Vec::new();
    let mut groups: Vec<Group> = Vec::new();
    for r in &results.rows {
        if !rooms.contains(&r.room) {
            rooms.push(r.room.clone());
        }
        let room = rooms.iter().position(|x| *x == r.room).unwrap_or(0);
        let g = match groups.iter().position(|g| g.name == r.setting) {
            Some(g) => g,
            None => {
                let extra = [MISSION_DONE.to_string()];
                let extra = if results.missions { &extra[..] } else { &[] };
                groups.push(Group::new(r.setting.clone(), extra, Vec::new()));
                groups.len() - 1
            }
        };
        let key = format!("seed {}", r.seed);
        let units = &mut groups[g].units;
        if !units.iter().any(|u| u.key == key) {
            units.push(Unit {
                key: key.clone(),
                rooms: Vec::new(),
            });
        }
        let unit = units.iter_mut().find(|u| u.key == key).expect("just added");
        unit.rooms.resize(room + 1, Vec::new());
        unit.rooms[room] = r.values.to_vec();
        if results.missions {
            unit.rooms[room].push(r.mission_done_pct);
        }
    }
    Ok(Side {
        dir: dir.into(),
        kind: Kind::Sweep,
        rooms,
        groups,
    })
}

/// Refuses two outputs of different kinds or rooms, saying what differs.
pub fn check_comparable(a: &Side, b: &Side) -> Result<(), CliError> {
    if a.kind != b.kind {
        return Err(CliError::input(format!(
            "A ({}) is {}, B ({}) is {}: compare two outputs of the same kind",
            a.dir.display(),
            a.kind.name(),
            b.dir.display(),
            b.kind.name()
        )));
    }
    if a.rooms != b.rooms {
        return Err(CliError::input(format!(
            "A ({}) has the rooms {}, B ({}) has {}: compare outputs of the same rooms",
            a.dir.display(),
            a.rooms.join(", "),
            b.dir.display(),
            b.rooms.join(", ")
        )));
    }
    Ok(())
}

fn find<'a>(side: &'a Side, which: &str, name: &str) -> Result<&'a Group, CliError> {
    side.groups.iter().find(|g| g.name == name).ok_or_else(|| {
        CliError::input(format!(
            "--setting {name}: {which} ({}) has no such setting; its settings: {}",
            side.dir.display(),
            names(side)
        ))
    })
}

fn names(side: &Side) -> String {
    side.groups
        .iter()
        .map(|g| g.name.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The settings to compare: a run's one with the other's; with `--setting S` (once) S of
/// both, with `--setting S1 --setting S2` S1 of A with S2 of B; else every setting of A with
/// B's of the same name (the two must have the same settings).
pub fn choose<'a>(
    a: &'a Side,
    b: &'a Side,
    setting: &[String],
) -> Result<Vec<(&'a Group, &'a Group)>, CliError> {
    match (a.kind, setting) {
        (Kind::Run, []) => Ok(vec![(&a.groups[0], &b.groups[0])]),
        (Kind::Run, _) => Err(CliError::input(
            "--setting picks a setting of a study or a sweep; A and B are run directories, \
             which have one each: leave --setting out",
        )),
        (_, [s]) => Ok(vec![(find(a, "A", s)?, find(b, "B", s)?)]),
        (_, [s, t]) => Ok(vec![(find(a, "A", s)?, find(b, "B", t)?)]),
        (_, [_, _, _, ..]) => Err(CliError::input(format!(
            "--setting was given {} times: give it once (the same setting of A and B) or twice \
             (A's setting, then B's)",
            setting.len()
        ))),
        (_, []) => {
            let same = a.groups.len() == b.groups.len()
                && a.groups
                    .iter()
                    .all(|g| b.groups.iter().any(|h| h.name == g.name));
            if !same || same_dir(a, b) {
                return Err(CliError::input(format!(
                    "A's settings are {}, B's are {}: name the settings to compare with \
                     --setting S (S of both) or --setting S1 --setting S2 (S1 of A, S2 of B)",
                    names(a),
                    names(b)
                )));
            }
            Ok(a.groups
                .iter()
                .map(|g| (g, find(b, "B", &g.name).expect("checked")))
                .collect())
        }
    }
}

fn same_dir(a: &Side, b: &Side) -> bool {
    match (a.dir.canonicalize(), b.dir.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    }
}

/// A comparison's outputs.
pub struct Compared {
    /// `compare.csv`'s rows.
    pub rows: Vec<CompareRow>,
    /// `compare.md`.
    pub md: String,
    /// `compare.csv`.
    pub csv: String,
    /// `compare.svg`.
    pub svg: String,
}

/// Compares the chosen settings of A and B at level `alpha` (resampling seeded with 0, so
/// the same inputs give the same bytes).
pub fn compare(
    a: &Side,
    b: &Side,
    pairs: &[(&Group, &Group)],
    alpha: f64,
) -> Result<Compared, CliError> {
    let settings = Settings {
        alpha,
        ..Settings::default()
    };
    settings
        .check()
        .map_err(|e| CliError::input(format!("--alpha: {e}")))?;
    let mut rows = Vec::new();
    let mut designs = String::new();
    for (g, h) in pairs {
        let found = compare_groups(g, h, &a.rooms, &settings)
            .map_err(|e| CliError::input(format!("setting {} against {}: {e}", g.name, h.name)))?;
        rows.extend(found);
        designs.push_str(&design_line(a.kind, g, h));
    }
    let own = rows.iter().any(|r| !METRICS.contains(&r.metric.as_str()));
    let head = head(a, b, &designs, alpha) + if own { OWN_METRICS } else { "" };
    let md = compare_md(&head, &rows, alpha);
    let title = format!("A − B per room: {} vs {}", a.dir.display(), b.dir.display());
    let svg = compare_svg(&title, &rows, alpha);
    let csv = compare_csv::to_text(&rows);
    Ok(Compared { rows, md, csv, svg })
}

/// The design of one pair of settings, as a Markdown list item.
fn design_line(kind: Kind, g: &Group, h: &Group) -> String {
    let unit = kind.unit();
    let what = if g.name == h.name {
        format!("`{}`", g.name)
    } else {
        format!("`{}` (A) against `{}` (B)", g.name, h.name)
    };
    match pairing(g, h) {
        Some(_) if kind == Kind::Run => format!(
            "- {what}: **paired** over {} {unit}: both runs have the same seed, so test run k \
             in a room uses the same random streams in both (sign-flip permutation test)\n",
            g.units.len()
        ),
        Some(_) => format!(
            "- {what}: **paired** over {} {unit}: A and B share their seeds, so each seed's \
             values are compared with the same seed's (sign-flip permutation test)\n",
            g.units.len()
        ),
        None => format!(
            "- {what}: **unpaired**, {} against {} {unit}: {}, so the samples are taken as \
             independent (two-sample permutation test)\n",
            g.units.len(),
            h.units.len(),
            if g.units.len() == h.units.len() {
                "their seeds differ"
            } else {
                "their numbers differ (no pairing)"
            }
        ),
    }
}

/// What `compare.md` says of the metrics beyond the paper's, when it has some.
const OWN_METRICS: &str = "\nBeyond the paper's metrics, the measures both sides have of runs \
    that follow missions or weigh terms of their own: `% missions done` (per test run 100 if its \
    mission was done, else 0) and `% NAME`, the mean 100·term, for each term beyond a, g, l, b \
    (the columns of their `table.md`).\n";

fn head(a: &Side, b: &Side, designs: &str, alpha: f64) -> String {
    format!(
        "# Comparison: A − B\n\n- A: `{}` ({})\n- B: `{}` ({})\n\n{designs}\n\
         Per room and over all rooms (per {unit_one}, the mean over rooms), each metric's means, \
         A − B with a 95 % percentile bootstrap interval (10 000 resamples), the two-sided \
         permutation p-value (exact up to 2^16 arrangements, else 99 999 random ones; resampling \
         seeded with 0), the room p-values Holm-adjusted over the rooms of each metric (the \
         overall row: its own p), `*` where the (adjusted) p < α = {alpha}, and the minimum \
         detectable difference at 80 % power and α (normal approximation). Computed by \
         `fuzzymotiv::statistics`.{fitness}\n",
        a.dir.display(),
        a.kind.name(),
        b.dir.display(),
        b.kind.name(),
        unit_one = match a.kind {
            Kind::Run => "test run",
            Kind::Study => "seed",
            Kind::Sweep => "replicate",
        },
        fitness = if a.kind == Kind::Run {
            " A test run has no average fitness (the mean F of the final population), so runs \
             are compared on the test runs' metrics only."
        } else {
            ""
        }
    )
}
/// What `fuzzymotiv compare A B --out DIR` asks for.
pub struct CompareRequest<'a> {
    /// The two outputs (run directories, studies or sweeps).
    pub a: &'a Path,
    /// See [`CompareRequest::a`].
    pub b: &'a Path,
    /// The directory of `compare.md`, `compare.csv`, `compare.svg` (and `compare.png`).
    pub out: &'a Path,
    /// The settings to compare (`--setting`; none: every shared one).
    pub settings: &'a [String],
    /// The significance level.
    pub alpha: f64,
    /// Draws `compare.png` beside the figure, if given.
    pub png: Option<&'a dyn Rasterise>,
    /// Replace other files of those names.
    pub force: bool,
}

/// Compares A and B as `fuzzymotiv compare` does (α checked, the output directory checked
/// before anything is read, both loaded and checked comparable, the settings chosen) and
/// writes the files through the output guard; returns `compare.md` and whether the files
/// were written or already held it.
pub fn compare_into(req: &CompareRequest) -> Result<(String, FilesState), CliError> {
    check_alpha(req.alpha)?;
    let out = req.out;
    let names = ["compare.md", "compare.csv", "compare.svg"];
    check_files_dir(out, "--out", &names)?;
    let a = load(req.a, "A")?;
    let b = load(req.b, "B")?;
    check_comparable(&a, &b)?;
    let pairs = choose(&a, &b, req.settings)?;
    let done = compare(&a, &b, &pairs, req.alpha)?;
    let mut files = vec![
        (out.join("compare.md"), done.md.clone().into_bytes()),
        (out.join("compare.csv"), done.csv.into_bytes()),
    ];
    if let Some(png) = req.png {
        let path = out.join("compare.png");
        let bytes = png
            .png(&done.svg)
            .map_err(|e| io_err(&path, std::io::Error::other(e)))?;
        files.push((path, bytes));
    }
    files.push((out.join("compare.svg"), done.svg.into_bytes()));
    let state = write_into(out, &files, "--out", req.force)?;
    Ok((done.md, state))
}
