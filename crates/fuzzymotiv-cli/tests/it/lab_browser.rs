//! The lab in headless Chromium (WebDriver): a person's path through the page, clicking only
//! visible, labelled controls. Moves a slider, draws and saves a room, presses Evolve on the
//! quick preset, sees the fitness curve grow and a path drawn, waits for the end, saves the run,
//! compares, starts another run and stops it. Prints the time from pressing Evolve to the first
//! generation drawn and to the finished run, and saves `target/lab-screenshot.png`.
//!
//! Needs the Debian packages `chromium` and `chromium-driver`, so it is ignored by default;
//! `.ci/run` installs them and runs it (`cargo test -- --ignored`).

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

use crate::common;

use common::webdriver::{Driver, ELEMENT, require_browser, target_dir};

/// `fuzzymotiv lab` on a free port; stopped on drop.
struct LabProcess {
    child: Child,
    url: String,
}

impl LabProcess {
    fn start(dir: &std::path::Path) -> LabProcess {
        LabProcess::start_with(dir, &[])
    }

    /// With more arguments (`--config FILE`).
    fn start_with(dir: &std::path::Path, more: &[&str]) -> LabProcess {
        let mut child = Command::new(env!("CARGO_BIN_EXE_fuzzymotiv"))
            .args(["lab", "--port", "0", "--threads", "2", "--dir"])
            .arg(dir)
            .args(more)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("fuzzymotiv lab starts");
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        let url = line
            .trim()
            .strip_prefix("fuzzymotiv lab: ")
            .unwrap_or_else(|| panic!("no address printed: {line:?}"))
            .to_string();
        assert!(
            url.starts_with("http://127.0.0.1:") && url.contains("/?token="),
            "{url}"
        );
        LabProcess { child, url }
    }
}

impl Drop for LabProcess {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Waits (up to `secs`) until the script returns something truthy; returns it.
fn wait_for(d: &Driver, secs: u64, what: &str, script: &str) -> Value {
    let deadline = Instant::now() + Duration::from_secs(secs);
    loop {
        let v = d.script(script);
        if !(v.is_null() || v == false || v == 0) {
            return v;
        }
        assert!(Instant::now() < deadline, "timed out waiting for {what}");
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// Clicks inside `element` at `(dx, dy)` CSS pixels from its centre (WebDriver actions).
fn click_at(d: &Driver, element: &str, dx: f64, dy: f64) {
    let origin = json!({ ELEMENT: element });
    d.cmd("POST", "/actions", json!({"actions": [{"type": "pointer", "id": "mouse",
        "parameters": {"pointerType": "mouse"}, "actions": [
            {"type": "pointerMove", "origin": origin, "x": dx.round() as i64, "y": dy.round() as i64},
            {"type": "pointerDown", "button": 0}, {"type": "pointerUp", "button": 0}]}]}));
}

/// The control labelled `label` (a `<label>` holding it or naming it).
fn labelled(d: &Driver, label: &str) -> String {
    let xpath = format!(
        "//label[normalize-space()='{label}']/following-sibling::input[1] | //label[starts-with(normalize-space(), '{label}')]/input | //label[starts-with(normalize-space(), '{label}')]/select"
    );
    let e = d
        .find_xpath(&xpath)
        .unwrap_or_else(|| panic!("no control labelled `{label}`"));
    assert!(d.displayed(&e), "`{label}` is not visible");
    e
}

fn type_into(d: &Driver, element: &str, text: &str) {
    d.cmd("POST", &format!("/element/{element}/clear"), json!({}));
    d.cmd(
        "POST",
        &format!("/element/{element}/value"),
        json!({ "text": text }),
    );
}

/// Draws a 1 m × 0.8 m room with its home, names it and saves it.
fn draw_room(d: &Driver) {
    let summary = d
        .find_xpath("//summary[normalize-space()='Draw a room']")
        .expect("Draw a room");
    d.cmd("POST", &format!("/element/{summary}/click"), json!({}));
    let editor = d.element("#room-editor");
    d.script("document.getElementById('room-editor').scrollIntoView({block: 'center'});");
    let w =
        d.script("return document.getElementById('room-editor').getBoundingClientRect().width;");
    let w = w.as_f64().unwrap();
    let at = |x: f64, y: f64| {
        (
            (x + 100.0) * w / 1400.0 - w / 2.0,
            (1300.0 - y) * w / 1400.0 - w / 2.0,
        )
    };
    for (x, y) in [(0.0, 0.0), (1000.0, 0.0), (1000.0, 800.0), (0.0, 800.0)] {
        let (dx, dy) = at(x, y);
        click_at(d, &editor, dx, dy);
    }
    let home = d
        .find_xpath("//select[@id='draw-mode']/option[normalize-space()='Home']")
        .unwrap();
    d.cmd("POST", &format!("/element/{home}/click"), json!({}));
    let (dx, dy) = at(300.0, 400.0);
    click_at(d, &editor, dx, dy);
    type_into(d, &labelled(d, "Room name"), "drawn1");
    d.click_button("Save room");
    let msg = wait_for(
        d,
        20,
        "the room saved",
        "var m = document.getElementById('room-message').textContent; return m ? m : null;",
    );
    assert!(
        msg.as_str().unwrap().starts_with("Saved as drawn1.toml"),
        "{msg}"
    );
    wait_for(
        d,
        10,
        "the drawn room listed",
        "return document.getElementById('room-drawn1.toml');",
    );
}

#[test]
#[ignore = "needs chromium: run by .ci/run"]
fn the_lab_evolves_stops_saves_and_compares_in_chromium() {
    require_browser();
    let tmp = tempfile::tempdir().unwrap();
    let lab = LabProcess::start(&tmp.path().join("lab"));
    let mut d = Driver::start();
    d.new_session(&tmp.path().join("chromium-profile"));
    d.goto(&lab.url);
    wait_for(
        &d,
        30,
        "the page",
        "return document.querySelectorAll('#room-choices .thumb').length >= 5;",
    );

    // A slider: homing up; the four weights still sum to 1.
    let homing = labelled(&d, "Homing H");
    d.cmd(
        "POST",
        &format!("/element/{homing}/value"),
        json!({"text": "\u{E014}".repeat(10)}),
    );
    let x = d.script("return ['curiosity','homing','orientation','energy'].map(function (n) { return +document.getElementById('value-' + n).textContent; });");
    let x: Vec<f64> = serde_json::from_value(x).unwrap();
    assert!(x[1] > 0.15, "the homing slider did not move: {x:?}");
    assert!((x.iter().sum::<f64>() - 1.0).abs() < 0.011, "{x:?}");
    d.click_button("Explain F");
    wait_for(
        &d,
        10,
        "F explained",
        "return document.getElementById('explain-f');",
    );

    draw_room(&d);

    // Evolve on the quick preset (30 × 30, the five rooms and the drawn one).
    assert_eq!(
        d.script("return document.getElementById('ga-preset').value;"),
        "quick"
    );
    d.click_button("Evolve");
    let grow = "var l = document.getElementById('fitness-chart-best'); return l ? +l.getAttribute('data-points') : 0;";
    wait_for(&d, 60, "a first generation", grow);
    wait_for(
        &d,
        60,
        "a path drawn",
        "return document.querySelectorAll('#paths .robot-path').length >= 6;",
    );
    let later = wait_for(
        &d,
        120,
        "the curve to grow",
        &grow.replace("? +l", "&& +l.getAttribute('data-points') >= 3 ? +l"),
    );
    assert!(later.as_u64().unwrap() >= 3);
    wait_for(
        &d,
        600,
        "the run to finish",
        "return window.labTimes.finished;",
    );
    let t = d.script("return window.labTimes;");
    let first = t["firstGeneration"].as_f64().unwrap() - t["evolve"].as_f64().unwrap();
    let done = t["finished"].as_f64().unwrap() - t["evolve"].as_f64().unwrap();
    eprintln!(
        "lab timing (quick preset 30 × 30, 6 rooms, --threads 2): Evolve → first generation drawn {:.0} ms, → finished run {:.0} ms",
        first, done
    );
    let status = d.script("return document.getElementById('run-status').textContent;");
    assert!(status.as_str().unwrap().ends_with("finished"), "{status}");

    d.click_button("Save as run directory");
    let saved = wait_for(
        &d,
        30,
        "saved",
        "var m = document.getElementById('save-message').textContent; return m ? m : null;",
    );
    assert!(saved.as_str().unwrap().starts_with("Saved: "), "{saved}");
    let id = d.script("return document.getElementById('save-name').value;");
    let saved_dir = tmp.path().join("lab/saved").join(id.as_str().unwrap());
    assert!(saved_dir.join("summary.json").is_file() && saved_dir.join("report.html").is_file());

    d.click_button("Compare");
    wait_for(
        &d,
        30,
        "the comparison",
        "return document.querySelectorAll('#compare-out table').length >= 3;",
    );
    d.script("window.scrollTo(0, 0);");
    let shot = target_dir().join("lab-screenshot.png");
    std::fs::write(&shot, d.full_page_png()).unwrap();
    eprintln!("screenshot: {}", shot.display());

    // Another run, stopped after its first generation: 400 generations (the lab's limit) so
    // that it cannot end before Stop is pressed, however fast the machine.
    type_into(&d, &labelled(&d, "Generations"), "400");
    d.click_button("Evolve");
    wait_for(
        &d,
        60,
        "a first generation",
        "return window.labTimes.firstGeneration !== undefined;",
    );
    d.click_button("Stop");
    let status = wait_for(
        &d,
        30,
        "the run stopped",
        "var s = document.getElementById('run-status').textContent; return /stopped$/.test(s) ? s : null;",
    );
    assert!(status.as_str().unwrap().contains("stopped"));
    let console = d.console_errors();
    assert!(console.is_empty(), "console errors: {console:?}");
}

/// Starts a small run from the page's own script (as Evolve would, with small sizes); its id
/// lands in `window.started`.
fn start_small_run(d: &Driver, generations: usize, seed: u64) -> String {
    let before = d.script("return (window.started || []).length;");
    d.script(&format!(
        "window.started = window.started || []; api('POST', '/api/runs', {{ name: 'b', seed: {seed}, \
         population: 6, generations: {generations}, steps: 100, rooms: ['H', 'square'], \
         motivations: {{ curiosity: 0.5, homing: 0.3, orientation: 0, energy: 0.2 }} }})\
         .then(function (r) {{ window.started.push(r.id); }});"
    ));
    let script = format!(
        "var s = window.started || []; return s.length > {before} ? s[s.length - 1] : null;"
    );
    let id = wait_for(d, 30, "a run started", &script);
    id.as_str().unwrap().to_string()
}

#[test]
#[ignore = "needs chromium: run by .ci/run"]
fn the_lab_page_shows_axis_ticks_queue_places_whole_tables_and_a_lost_token() {
    require_browser();
    let tmp = tempfile::tempdir().unwrap();
    let lab = LabProcess::start(&tmp.path().join("lab"));
    let mut d = Driver::start();
    d.new_session(&tmp.path().join("chromium-profile"));
    d.goto(&lab.url);
    wait_for(
        &d,
        30,
        "the page",
        "return typeof api === 'function' && document.querySelectorAll('#room-choices .thumb').length >= 5;",
    );

    // Two small runs to compare, then a long one that keeps the worker busy.
    let (a, b) = (start_small_run(&d, 2, 1), start_small_run(&d, 2, 2));
    let finished = |id: &str| {
        format!(
            "var r = Array.from(document.querySelectorAll('#run-list td:first-child')).find(function (t) {{ return t.textContent === '{id}'; }}); return r && r.parentNode.textContent.indexOf('finished') >= 0;"
        )
    };
    wait_for(&d, 120, "run A finished", &finished(&a));
    wait_for(&d, 120, "run B finished", &finished(&b));
    let long = start_small_run(&d, 400, 3);
    let queued = start_small_run(&d, 2, 4);
    d.script(&format!("follow('{queued}');"));
    let status = wait_for(
        &d,
        30,
        "the queue place",
        "var s = document.getElementById('run-status').textContent; return /place 1 in the queue/.test(s) ? s : null;",
    );
    assert!(
        status.as_str().unwrap().contains("(1 run before it)"),
        "{status}"
    );
    d.script(&format!("api('POST', '/api/runs/{long}/cancel');"));
    wait_for(
        &d,
        120,
        "the queued run finished",
        "return /finished$/.test(document.getElementById('run-status').textContent);",
    );

    // The charts: ticks and labels on both axes, F from 0 to 1; l at 0 throughout is labelled.
    let y = d.script("return Array.from(document.querySelectorAll('#fitness-chart .y-tick')).map(function (t) { return t.textContent; });");
    assert_eq!(y, json!(["0.0", "0.2", "0.4", "0.6", "0.8", "1.0"]));
    let x = d.script("return Array.from(document.querySelectorAll('#fitness-chart .x-tick')).map(function (t) { return t.textContent; });");
    assert_eq!(x, json!(["0", "1"]));
    let legend = d.script("return Array.from(document.querySelectorAll('#terms-chart .legend')).map(function (t) { return t.textContent; });");
    assert!(
        legend
            .as_array()
            .unwrap()
            .contains(&json!("l = 0 throughout")),
        "{legend}"
    );

    // The comparison: every column of both tables shows (nothing scrolled away) at 1280 px.
    d.script(&format!("document.getElementById('compare-a').value = '{a}'; document.getElementById('compare-b').value = '{b}';"));
    d.click_button("Compare");
    wait_for(
        &d,
        30,
        "the differences",
        "return document.getElementById('differences');",
    );
    let clipped = d.script("return Array.from(document.querySelectorAll('.compare > *')).filter(function (c) { return c.scrollWidth > c.clientWidth; }).map(function (c) { return [c.scrollWidth, c.clientWidth]; });");
    assert_eq!(clipped, json!([]), "a side of the comparison scrolls");
    let heads = d.script("return document.querySelector('.compare table').textContent;");
    assert!(heads.as_str().unwrap().contains("% recognition"), "{heads}");
    let measures = d.script("return document.getElementById('differences').textContent;");
    assert!(
        measures.as_str().unwrap().contains("% recognition"),
        "{measures}"
    );
    d.script("document.getElementById('runs-panel').scrollIntoView();");
    let shot = target_dir().join("lab-compare-screenshot.png");
    std::fs::write(&shot, d.full_page_png()).unwrap();
    eprintln!("screenshot: {}", shot.display());

    // A lost token (as after a restart): the page says so instead of failing silently.
    d.cmd("DELETE", "/cookie", json!({}));
    let said = wait_for(
        &d,
        30,
        "the token message",
        "var b = document.getElementById('error-bar'); return !b.hidden && b.textContent;",
    );
    assert!(said.as_str().unwrap().contains("--token"), "{said}");
}

/// Drags inside `element` from `from` to `to` (CSS pixels from its centre).
fn drag(d: &Driver, element: &str, from: (f64, f64), to: (f64, f64)) {
    let origin = json!({ ELEMENT: element });
    let at = |p: (f64, f64)| (p.0.round() as i64, p.1.round() as i64);
    let ((x0, y0), (x1, y1)) = (at(from), at(to));
    d.cmd("POST", "/actions", json!({"actions": [{"type": "pointer", "id": "mouse",
        "parameters": {"pointerType": "mouse"}, "actions": [
            {"type": "pointerMove", "origin": origin, "x": x0, "y": y0},
            {"type": "pointerDown", "button": 0},
            {"type": "pointerMove", "origin": origin, "x": (x0 + x1) / 2, "y": (y0 + y1) / 2, "duration": 50},
            {"type": "pointerMove", "origin": origin, "x": x1, "y": y1, "duration": 50},
            {"type": "pointerUp", "button": 0}]}]}));
}

fn choose(d: &Driver, option: &str) {
    let o = d
        .find_xpath(&format!(
            "//select[@id='draw-mode']/option[normalize-space()='{option}']"
        ))
        .unwrap_or_else(|| panic!("no drawing mode `{option}`"));
    d.cmd("POST", &format!("/element/{o}/click"), json!({}));
}

/// Draws a 1 m × 0.8 m room, its home near one corner, a goal dragged to size near the
/// opposite one and a waypoint; saves it as `goalroom`.
fn draw_room_with_goal(d: &Driver) {
    let summary = d
        .find_xpath("//summary[normalize-space()='Draw a room']")
        .expect("Draw a room");
    d.cmd("POST", &format!("/element/{summary}/click"), json!({}));
    let editor = d.element("#room-editor");
    d.script("document.getElementById('room-editor').scrollIntoView({block: 'center'});");
    let w =
        d.script("return document.getElementById('room-editor').getBoundingClientRect().width;");
    let w = w.as_f64().unwrap();
    let at = |x: f64, y: f64| {
        (
            (x + 100.0) * w / 1400.0 - w / 2.0,
            (1300.0 - y) * w / 1400.0 - w / 2.0,
        )
    };
    for (x, y) in [(0.0, 0.0), (1000.0, 0.0), (1000.0, 800.0), (0.0, 800.0)] {
        let (dx, dy) = at(x, y);
        click_at(d, &editor, dx, dy);
    }
    choose(d, "Home");
    let (dx, dy) = at(200.0, 200.0);
    click_at(d, &editor, dx, dy);
    choose(d, "Goal");
    drag(d, &editor, at(800.0, 600.0), at(920.0, 600.0));
    choose(d, "Waypoints");
    let (dx, dy) = at(500.0, 400.0);
    click_at(d, &editor, dx, dy);
    let goal =
        d.script("return document.querySelector('#room-editor circle.goal').getAttribute('r');");
    let r: f64 = goal.as_str().unwrap().parse().unwrap();
    assert!(
        (90.0..=150.0).contains(&r),
        "the goal was not dragged to size: r = {r}"
    );
    assert_eq!(
        d.script("return document.querySelectorAll('#room-editor circle.waypoint').length;"),
        1
    );
    type_into(d, &labelled(d, "Room name"), "goalroom");
    d.click_button("Save room");
    let msg = wait_for(
        d,
        20,
        "the room saved",
        "var m = document.getElementById('room-message').textContent; return m ? m : null;",
    );
    assert!(
        msg.as_str().unwrap().starts_with("Saved as goalroom.toml"),
        "{msg}"
    );
    wait_for(
        d,
        10,
        "the room listed with its goal",
        "return document.querySelector('#room-choices .thumb circle.goal');",
    );
}

#[test]
#[ignore = "needs chromium: run by .ci/run"]
fn a_fetch_config_shows_five_sliders_and_evolves_towards_a_goal_drawn_on_the_canvas() {
    require_browser();
    let tmp = tempfile::tempdir().unwrap();
    let lab = LabProcess::start(&tmp.path().join("lab"));
    let mut d = Driver::start();
    d.new_session(&tmp.path().join("chromium-profile"));
    d.goto(&lab.url);
    wait_for(
        &d,
        30,
        "the page",
        "return document.querySelectorAll('#room-choices .thumb').length >= 5;",
    );
    let sliders = "return document.querySelectorAll('#sliders input[type=range]').length;";
    assert_eq!(d.script(sliders), 4);
    d.click_button("Fetch (.5, .1, 0, .1, urgency .3)");
    assert_eq!(d.script(sliders), 5);
    let urgency = labelled(&d, "Urgency (urgency)");
    d.cmd(
        "POST",
        &format!("/element/{urgency}/value"),
        json!({"text": "\u{E014}".repeat(10)}),
    );
    let x = d.script("return Array.from(document.querySelectorAll('#sliders output')).map(function (o) { return +o.textContent; });");
    let x: Vec<f64> = serde_json::from_value(x).unwrap();
    assert_eq!(x.len(), 5);
    assert!(x[4] > 0.35, "the urgency slider did not move: {x:?}");
    assert!((x.iter().sum::<f64>() - 1.0).abs() < 0.011, "{x:?}");
    d.click_button("Explain F");
    wait_for(
        &d,
        10,
        "F explained",
        "return document.getElementById('explain-f');",
    );
    let heads = d.script("return Array.from(document.querySelectorAll('#explain-out th')).map(function (h) { return h.textContent; }).join('|');");
    assert!(heads.as_str().unwrap().contains("urgency is"), "{heads}");

    draw_room_with_goal(&d);
    // Only the room with a goal: the built-in rooms have none for urgency to weigh.
    for room in ["H", "T", "L", "square", "rectangle"] {
        let cb = d.element(&format!("#room-{room}"));
        d.cmd("POST", &format!("/element/{cb}/click"), json!({}));
    }
    // The quick preset (30 × 30): in one room without recognition, a few seconds.
    d.click_button("Evolve");
    let grow = "var l = document.getElementById('terms-chart-urgency'); return l && +l.getAttribute('data-points') >= 3 ? +l.getAttribute('data-points') : 0;";
    wait_for(&d, 120, "the urgency curve to grow", grow);
    wait_for(
        &d,
        300,
        "the run to finish",
        "return window.labTimes.finished;",
    );
    let status = d.script("return document.getElementById('run-status').textContent;");
    assert!(status.as_str().unwrap().ends_with("finished"), "{status}");
    assert_eq!(
        d.script(
            "return +document.getElementById('fitness-chart-best').getAttribute('data-points');"
        ),
        30
    );
    let heads = d.script("return document.getElementById('result-table').textContent;");
    assert!(
        heads.as_str().unwrap().contains("goal reached (step)"),
        "{heads}"
    );
    assert!(d.script("return document.querySelectorAll('#paths .thumb circle.goal').length;") == 1);
    // Edit under the built-in H copies it into the editor, under a name of its own.
    let edit = d
        .find_xpath(
            "//input[@id='room-H']/ancestor::div[@class='thumb']/button[normalize-space()='Edit']",
        )
        .expect("Edit under H");
    d.cmd("POST", &format!("/element/{edit}/click"), json!({}));
    assert_eq!(
        d.script("return document.getElementById('room-name').value;"),
        "H-mission"
    );
    assert_eq!(
        d.script("return document.querySelector('#room-editor polygon').getAttribute('points').split(' ').length;"),
        12
    );
    d.script("window.scrollTo(0, 0);");
    let shot = target_dir().join("lab-fetch-screenshot.png");
    std::fs::write(&shot, d.full_page_png()).unwrap();
    eprintln!("screenshot: {}", shot.display());
    let console = d.console_errors();
    assert!(console.is_empty(), "console errors: {console:?}");
}

/// The checkbox of the listed room whose label starts with `label`.
fn room_box(d: &Driver, label: &str) -> String {
    d.find_xpath(&format!(
        "//div[@id='room-choices']//label[starts-with(normalize-space(), '{label}')]/input"
    ))
    .unwrap_or_else(|| panic!("no room labelled `{label}`"))
}

#[test]
#[ignore = "needs chromium: run by .ci/run"]
fn the_lab_started_on_fetch_toml_shows_its_sliders_and_rooms_with_goals_and_runs_in_them() {
    require_browser();
    let tmp = tempfile::tempdir().unwrap();
    let config = concat!(env!("CARGO_MANIFEST_DIR"), "/../../configs/fetch.toml");
    let lab = LabProcess::start_with(&tmp.path().join("lab"), &["--config", config]);
    let mut d = Driver::start();
    d.new_session(&tmp.path().join("chromium-profile"));
    d.goto(&lab.url);
    wait_for(
        &d,
        30,
        "the page",
        "return document.querySelectorAll('#room-choices .thumb').length >= 10;",
    );

    // Five sliders at the fetch weights, urgency labelled with its term.
    let sliders = d.script("return Array.from(document.querySelectorAll('#sliders input[type=range]')).map(function (s) { return [s.id, +s.value]; });");
    assert_eq!(
        sliders,
        json!([
            ["slider-curiosity", 0.5],
            ["slider-homing", 0.1],
            ["slider-orientation", 0],
            ["slider-energy", 0.1],
            ["slider-urgency", 0.3]
        ])
    );
    labelled(&d, "Urgency (urgency)");
    let note = d.script(
        "var p = document.getElementById('start-config'); return p.hidden ? null : p.textContent;",
    );
    let note = note.as_str().unwrap();
    assert!(
        note.starts_with("Started on ") && note.contains("configs/fetch.toml"),
        "{note}"
    );
    assert!(
        note.contains("5 motivations") && note.contains("5 rooms chosen"),
        "{note}"
    );

    // Its rooms first, chosen, each with its goal drawn; the built-in rooms listed, not chosen.
    let rooms = d.script("return Array.from(document.querySelectorAll('#room-choices .thumb')).slice(0, 6).map(function (t) { return [t.querySelector('label').textContent.trim(), t.querySelector('input').checked, t.querySelectorAll('circle.goal').length]; });");
    assert_eq!(
        rooms,
        json!([
            ["fetch-H (config) (goal)", true, 1],
            ["fetch-T (config) (goal)", true, 1],
            ["fetch-L (config) (goal)", true, 1],
            ["fetch-square (config) (goal)", true, 1],
            ["fetch-rectangle (config) (goal)", true, 1],
            ["H", false, 0]
        ])
    );
    // The form: the config's name, GA size (200 × 200, the paper preset) and trial steps.
    let form = d.script("return ['run-name', 'ga-preset', 'population', 'generations', 'steps', 'motion'].map(function (i) { return document.getElementById(i).value; });");
    assert_eq!(
        form,
        json!(["fetch", "paper", "200", "200", "400", "actions"])
    );

    // A small run in two of its rooms: the paths drawn in them, goals and all.
    for label in [
        "fetch-T (config)",
        "fetch-L (config)",
        "fetch-rectangle (config)",
    ] {
        let b = room_box(&d, label);
        d.cmd("POST", &format!("/element/{b}/click"), json!({}));
    }
    type_into(&d, &labelled(&d, "Population"), "6");
    type_into(&d, &labelled(&d, "Generations"), "2");
    type_into(&d, &labelled(&d, "Steps"), "100");
    d.click_button("Evolve");
    wait_for(
        &d,
        300,
        "the run to finish",
        "return window.labTimes.finished;",
    );
    let status = d.script("return document.getElementById('run-status').textContent;");
    assert!(status.as_str().unwrap().ends_with("finished"), "{status}");
    let paths = d.script("return Array.from(document.querySelectorAll('#paths .thumb')).map(function (t) { return [t.querySelector('svg').getAttribute('aria-label'), t.querySelectorAll('circle.goal').length]; });");
    assert_eq!(
        paths,
        json!([["path in fetch-H", 1], ["path in fetch-square", 1]])
    );
    d.script("window.scrollTo(0, 0);");
    let shot = target_dir().join("lab-config-screenshot.png");
    std::fs::write(&shot, d.full_page_png()).unwrap();
    eprintln!("screenshot: {}", shot.display());
    let console = d.console_errors();
    assert!(console.is_empty(), "console errors: {console:?}");
}

#[test]
#[ignore = "needs chromium: run by .ci/run"]
fn the_fitness_combination_is_chosen_explained_and_reported_in_chromium() {
    require_browser();
    let tmp = tempfile::tempdir().unwrap();
    let lab = LabProcess::start(&tmp.path().join("lab"));
    let mut d = Driver::start();
    d.new_session(&tmp.path().join("chromium-profile"));
    d.goto(&lab.url);
    wait_for(
        &d,
        30,
        "the page",
        "return document.querySelectorAll('#room-choices .thumb').length >= 5;",
    );
    let select = labelled(&d, "Fitness combination");
    assert_eq!(
        d.script("return document.getElementById('combine').value;"),
        "tsk",
        "the TSK by default"
    );

    // What would F be: the TSK's F, then the weighted sum's beside it once chosen.
    d.click_button("Explain F");
    let tsk = wait_for(
        &d,
        10,
        "F explained",
        "var p = document.getElementById('explain-f'); return p ? p.textContent : null;",
    );
    assert!(tsk.as_str().unwrap().contains("firing rule"), "{tsk}");
    let option = d
        .find_xpath(
            "//select[@id='combine']/option[starts-with(normalize-space(), 'weighted sum')]",
        )
        .expect("a weighted sum option");
    d.cmd("POST", &format!("/element/{option}/click"), json!({}));
    assert!(d.displayed(&select));
    let sum = wait_for(
        &d,
        10,
        "F under the weighted sum",
        "var p = document.getElementById('explain-f'); return p && /under a weighted sum/.test(p.textContent) ? p.textContent : null;",
    );
    assert!(
        sum.as_str().unwrap().contains("The TSK would give F = "),
        "{sum}"
    );

    // A small run under it: the result, the run list and the downloaded config say so.
    type_into(&d, &labelled(&d, "Population"), "6");
    type_into(&d, &labelled(&d, "Generations"), "2");
    type_into(&d, &labelled(&d, "Steps"), "100");
    d.click_button("Evolve");
    wait_for(
        &d,
        300,
        "the run to finish",
        "return window.labTimes.finished;",
    );
    let said = d.script("return document.getElementById('result-combine').textContent;");
    assert_eq!(said, "F combined by a weighted sum (F = Σ Xᵢ·Yᵢ).");
    let listed = wait_for(
        &d,
        10,
        "the run listed",
        "var c = document.querySelector('#run-list tbody td:nth-child(2)'); return c && /weighted-sum/.test(c.textContent) ? c.textContent : null;",
    );
    assert!(
        listed.as_str().unwrap().ends_with(" by weighted-sum"),
        "{listed}"
    );
    let config = d.script("var x = new XMLHttpRequest(); x.open('GET', document.getElementById('download-config').href, false); x.send(); return x.responseText;");
    assert!(
        config
            .as_str()
            .unwrap()
            .contains("combine = \"weighted-sum\""),
        "{config}"
    );
    d.script("window.scrollTo(0, 0);");
    let shot = target_dir().join("lab-combine-screenshot.png");
    std::fs::write(&shot, d.full_page_png()).unwrap();
    eprintln!("screenshot: {}", shot.display());
    let console = d.console_errors();
    assert!(console.is_empty(), "console errors: {console:?}");
}

/// Picks the robot `name` in the run form's robot picker, as a person does.
fn pick_robot(d: &Driver, name: &str) {
    let o = d
        .find_xpath(&format!("//select[@id='robot']/option[@value='{name}']"))
        .unwrap_or_else(|| panic!("no robot `{name}` in the picker"));
    d.cmd("POST", &format!("/element/{o}/click"), json!({}));
}

#[test]
#[ignore = "needs chromium: run by .ci/run"]
fn the_robot_picker_lists_the_robots_and_the_chosen_robot_runs_and_is_drawn_in_chromium() {
    require_browser();
    let tmp = tempfile::tempdir().unwrap();
    let lab = LabProcess::start(&tmp.path().join("lab"));
    let mut d = Driver::start();
    d.new_session(&tmp.path().join("chromium-profile"));
    d.goto(&lab.url);
    wait_for(
        &d,
        30,
        "the page",
        "return document.querySelectorAll('#room-choices .thumb').length >= 5 && document.querySelectorAll('#robot option').length;",
    );

    // The picker: the three built-in robots, the Khepera first and chosen, drawn to scale.
    let select = labelled(&d, "Robot");
    assert!(d.displayed(&select));
    let options = d.script("return Array.from(document.querySelectorAll('#robot option')).map(function (o) { return [o.value, o.textContent]; });");
    let options: Vec<(String, String)> = serde_json::from_value(options).unwrap();
    let values: Vec<&str> = options.iter().map(|o| o.0.as_str()).collect();
    assert_eq!(values, ["khepera", "epuck2", "thymio2"]);
    for ((_, text), n) in options.iter().zip([8, 8, 7]) {
        assert!(text.contains(&format!("{n} sensors")), "{text}");
    }
    let drawn = "var g = document.querySelector('#robot-preview g.robot'); return [g.getAttribute('data-robot'), g.querySelectorAll('.sensor-ray').length, +g.querySelector('.robot-body').getAttribute('r')];";
    assert_eq!(d.script(drawn), json!(["khepera", 8, 27.5]));
    pick_robot(&d, "thymio2");
    assert_eq!(d.script(drawn), json!(["thymio2", 7, 80]));

    // The Thymio in the paper's rooms: refused with the engine's clearance error, beside Evolve.
    d.click_button("Evolve");
    let status = wait_for(
        &d,
        30,
        "the refusal",
        "var s = document.getElementById('run-status'); return s.className === 'error' && s.textContent;",
    );
    let status = status.as_str().unwrap();
    assert!(
        status.starts_with("Not started: lab settings: field `rooms[0]`: home of room \"H\"")
            && status.contains("closer than robot.radius 80")
            && status.contains("rooms/thymio2/"),
        "{status}"
    );
    let refused = d.console_errors();
    assert!(
        refused.len() == 1 && refused[0].contains("400"),
        "only the refused request is logged: {refused:?}"
    );

    // The e-puck2, a small run in two rooms: its body and sensors drawn where each path ends.
    pick_robot(&d, "epuck2");
    for room in ["T", "L", "rectangle"] {
        let cb = d.element(&format!("#room-{room}"));
        d.cmd("POST", &format!("/element/{cb}/click"), json!({}));
    }
    type_into(&d, &labelled(&d, "Population"), "6");
    type_into(&d, &labelled(&d, "Generations"), "2");
    type_into(&d, &labelled(&d, "Steps"), "100");
    d.click_button("Evolve");
    wait_for(
        &d,
        300,
        "the run to finish",
        "return window.labTimes.finished;",
    );
    let status = d.script("return document.getElementById('run-status').textContent;");
    assert!(status.as_str().unwrap().ends_with("finished"), "{status}");
    let ends = d.script("return Array.from(document.querySelectorAll('#paths .thumb')).map(function (t) { var g = t.querySelector('g.robot'), b = g.querySelector('.robot-body'); var p = t.querySelector('.robot-path').getAttribute('points').split(' ').pop().split(','); return [g.getAttribute('data-robot'), g.querySelectorAll('.sensor-ray').length, +b.getAttribute('r'), +b.getAttribute('cx') === +p[0] && +b.getAttribute('cy') === +p[1]]; });");
    let radius = fuzzymotiv::simulation::RobotSpec::builtin("epuck2")
        .unwrap()
        .radius();
    let ends = ends.as_array().unwrap();
    assert_eq!(ends.len(), 2, "a path in H and one in square: {ends:?}");
    for e in ends {
        assert_eq!(
            (e[0].as_str(), e[1].as_u64(), e[2].as_f64(), e[3].as_bool()),
            (Some("epuck2"), Some(8), Some(radius), Some(true)),
            "the e-puck2's body and 8 rays at the path's end: {e}"
        );
    }
    let config = d.script("var x = new XMLHttpRequest(); x.open('GET', document.getElementById('download-config').href, false); x.send(); return x.responseText;");
    assert!(
        config.as_str().unwrap().contains("file = \"epuck2\""),
        "{config}"
    );
    wait_for(
        &d,
        10,
        "the run listed with its robot",
        "var c = document.querySelector('#run-list tbody td:nth-child(3)'); return c && /, epuck2$/.test(c.textContent);",
    );
    d.script("document.getElementById('evolve-panel').scrollIntoView();");
    let shot = target_dir().join("lab-robot-screenshot.png");
    std::fs::write(&shot, d.full_page_png()).unwrap();
    eprintln!("screenshot: {}", shot.display());
    let console = d.console_errors();
    assert!(console.is_empty(), "console errors: {console:?}");
}

/// A tiny study of the fetch mission on an e-puck2: three arms of urgency's weight, a
/// comparison of the mission's time and a trend of exploration (its config by absolute path).
fn tiny_study() -> String {
    let text = std::fs::read_to_string(common::repo().join("studies/fetch-urgency.toml")).unwrap();
    let config = common::repo().join("configs/fetch.toml");
    let text = text.replace("seeds = 10\n", "seeds = 2\n").replace(
        "config = \"../configs/fetch.toml\"",
        &format!(
            "config = {:?}\nset = {{ robot = \"epuck2\", ga = {{ population = 6, generations = 2 }}, trial = {{ steps = 60 }}, aem = {{ enabled = false }} }}",
            config.display().to_string()
        ),
    );
    assert!(text.contains("robot = \"epuck2\"") && text.contains("seeds = 2\n"));
    text
}

/// The Studies panel: a study file picked from the lab's study folder fills the text box; a
/// broken one pasted is refused on the page naming its field; the picked one starts, its
/// progress shows as runs done of the total, and once analysed its claims table (effect,
/// interval, p, detectable difference, verdict) and forest plot appear. Saves
/// `target/lab-study-screenshot.png`.
#[test]
#[ignore = "needs chromium: run by .ci/run"]
fn a_study_picked_in_the_lab_runs_and_shows_its_claims_table_and_forest_plot_in_chromium() {
    require_browser();
    let tmp = tempfile::tempdir().unwrap();
    let folder = tmp.path().join("studies");
    std::fs::create_dir_all(&folder).unwrap();
    let text = tiny_study();
    std::fs::write(folder.join("epuck2-fetch.toml"), &text).unwrap();
    let lab = LabProcess::start_with(
        &tmp.path().join("lab"),
        &["--studies", folder.to_str().unwrap()],
    );
    let mut d = Driver::start();
    d.new_session(&tmp.path().join("chromium-profile"));
    d.goto(&lab.url);
    wait_for(
        &d,
        30,
        "the study files",
        "return document.querySelectorAll('#study-file option').length === 2;",
    );

    // Pasted with a bad field: refused on the page, naming it.
    let area = d.element("#study-text");
    type_into(&d, &area, &text.replace("seeds = 2\n", "seeds = 0\n"));
    d.click_button("Start study");
    let refused = wait_for(
        &d,
        30,
        "the refusal",
        "var m = document.getElementById('study-message'); return m.className === 'error' && m.textContent;",
    );
    assert!(
        refused
            .as_str()
            .unwrap()
            .starts_with("(pasted study): field `study.seeds`"),
        "{refused}"
    );

    // Picked from the list: its text in the box, started, followed to its claims.
    let select = labelled(&d, "Study file");
    let option = d.element("#study-file option[value='epuck2-fetch.toml']");
    d.cmd("POST", &format!("/element/{select}/click"), json!({}));
    d.cmd("POST", &format!("/element/{option}/click"), json!({}));
    let shown = d.script("return document.getElementById('study-text').value;");
    assert_eq!(shown.as_str().unwrap(), text);
    d.click_button("Start study");
    wait_for(
        &d,
        300,
        "the claims table",
        "return document.querySelectorAll('#study-claims tbody tr').length > 0;",
    );
    // Every run of the plan finished: "… N of N runs, analysed."
    let status = d.script("return document.getElementById('study-status').textContent;");
    let status = status.as_str().unwrap();
    let counts = (status.strip_suffix(" runs, analysed.")).and_then(|s| s.rsplit_once(": "));
    let (done, total) = counts
        .and_then(|(_, c)| c.split_once(" of "))
        .unwrap_or_default();
    assert!(!done.is_empty() && done == total, "{status}");
    let rows = d.script("return Array.from(document.querySelectorAll('#study-claims tbody tr')).map(function (r) { return Array.from(r.cells).map(function (c) { return c.textContent; }); });");
    let rows: Vec<Vec<String>> = serde_json::from_value(rows).unwrap();
    let ids: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    let declared: Vec<&str> = (text.lines())
        .filter_map(|l| l.strip_prefix("id = \""))
        .map(|l| l.split('"').next().unwrap())
        .collect();
    assert_eq!(ids, declared);
    for r in &rows {
        assert_eq!(r.len(), 7, "{r:?}");
        assert!(r[3].starts_with('[') && r[3].ends_with(']'), "{r:?}");
        assert!(
            [
                "supported",
                "contradicted",
                "not significant",
                "inconclusive"
            ]
            .contains(&r[6].as_str()),
            "{r:?}"
        );
    }
    wait_for(
        &d,
        30,
        "the forest plot",
        "var i = document.getElementById('study-forest'); return i.complete && i.naturalWidth > 0;",
    );
    d.script("document.getElementById('studies-panel').scrollIntoView();");
    let shot = target_dir().join("lab-study-screenshot.png");
    std::fs::write(&shot, d.full_page_png()).unwrap();
    eprintln!("screenshot: {}", shot.display());
    let console = d.console_errors();
    assert!(
        console.len() == 1 && console[0].contains("400"),
        "only the refused request is logged: {console:?}"
    );
}
