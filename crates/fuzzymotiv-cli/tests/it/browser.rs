//! The report pages in a real browser: headless Chromium driven through chromedriver's WebDriver
//! HTTP API (a tiny client on `std::net::TcpStream`). Checks that `report.html` runs its script
//! without console errors or network requests, that pressing play moves the robot, and saves
//! screenshots to `target/report-screenshot.png` (whole page),
//! `target/report-replay-screenshot.png` (the replay widget) and
//! `target/reproduce-report-screenshot.png` (the page of `reproduce`).
//!
//! Needs the Debian packages `chromium` and `chromium-driver`, so it is ignored by default;
//! `.ci/run` installs them and runs it (`cargo test -- --ignored`).

use std::time::{Duration, Instant};

use serde_json::json;

use crate::common;

use common::webdriver::{Driver, base64, require_browser, target_dir};
use common::{Fm, SMALL, ok};

/// The page loaded without script errors, console errors or network requests, with `widgets`
/// replay widgets.
fn check_page_health(driver: &Driver, widgets: u64, what: &str) {
    let v = driver.script(
        "return {errors: window.fuzzymotivErrors || ['page script did not start'],
                 widgets: (window.fuzzymotivReplays || []).length,
                 requests: performance.getEntriesByType('resource').map(function (e) { return e.name; })};",
    );
    assert_eq!(v["errors"], json!([]), "{what}: script errors");
    assert_eq!(v["widgets"], widgets, "{what}: replay widgets");
    assert_eq!(v["requests"], json!([]), "{what}: network requests");
    let console = driver.console_errors();
    assert!(console.is_empty(), "{what}: console errors: {console:?}");
}

#[test]
#[ignore = "needs chromium: run by .ci/run"]
fn report_page_runs_and_replays_in_chromium() {
    require_browser();
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("small.toml");
    std::fs::write(&cfg, "name = \"browser-test\"\nseed = 11\n").unwrap();
    let out = dir.path().join("run");
    Fm::new(["run", cfg.to_str().unwrap()])
        .out(&out)
        .sets(&SMALL)
        .ok();
    let report = out.join("report.html");
    assert!(report.is_file(), "run wrote no report.html");

    let mut driver = Driver::start();
    driver.new_session(&dir.path().join("chromium-profile"));
    driver.open(&report);
    check_page_health(&driver, 1, "run report");

    // The replay starts at step 0, at home; pressing play must move the drawn robot.
    let state = "var s = window.fuzzymotivReplays[0];
                 var c = document.querySelector('.replay canvas.room');
                 return {step: s.step, playing: s.playing, pose: c.getAttribute('data-pose'),
                         steps: +document.querySelector('.replay .slider').max};";
    let before = driver.script(state);
    assert_eq!(before["step"], 0, "{before}");
    assert_eq!(before["steps"], 100, "{before}");
    let play = driver.element(".replay button.play");
    driver.cmd("POST", &format!("/element/{play}/click"), json!({}));
    let deadline = Instant::now() + Duration::from_secs(20);
    let after = loop {
        std::thread::sleep(Duration::from_millis(200));
        let now = driver.script(state);
        if now["pose"] != before["pose"] && now["step"].as_u64().unwrap_or(0) >= 5 {
            break now;
        }
        assert!(
            Instant::now() < deadline,
            "pressing play did not move the robot: before {before}, now {now}"
        );
    };
    assert!(
        after["playing"] == true || after["step"] == 100,
        "the replay stopped early: {after}"
    );
    // The drawn pose is the recorded pose of the drawn step.
    let consistent = driver.script(
        "var s = window.fuzzymotivReplays[0];
         s.pause(); s.setStep(40);
         var d = JSON.parse(document.getElementById('fm-data').textContent).replays[0].rooms[0];
         var c = document.querySelector('.replay canvas.room');
         return c.getAttribute('data-pose') === d.x[40].toFixed(1) + ',' + d.y[40].toFixed(1) + ',' + d.h[40].toFixed(3);",
    );
    assert_eq!(consistent, true, "drawn pose differs from the data");
    check_page_health(&driver, 1, "run report after playing");

    let target = target_dir();
    let full = target.join("report-screenshot.png");
    std::fs::write(&full, driver.full_page_png()).unwrap();
    let widget = driver.element(".replay");
    driver.script("document.querySelector('.replay').scrollIntoView();");
    let shot = driver.cmd("GET", &format!("/element/{widget}/screenshot"), json!({}));
    let replay_png = target.join("report-replay-screenshot.png");
    std::fs::write(&replay_png, base64(shot.as_str().expect("base64 PNG"))).unwrap();
    for p in [&full, &replay_png] {
        let bytes = std::fs::read(p).unwrap();
        assert!(
            bytes.len() > 10_000 && &bytes[1..4] == b"PNG",
            "{}",
            p.display()
        );
    }
    eprintln!(
        "screenshots: {} and {}",
        full.display(),
        replay_png.display()
    );

    // The replay page of `fuzzymotiv replay` uses the same widget.
    let page = dir.path().join("replay/replay.html");
    ok(&[
        "replay",
        out.to_str().unwrap(),
        "--out",
        page.to_str().unwrap(),
    ]);
    driver.open(&page);
    check_page_health(&driver, 1, "replay page");
    let rooms =
        driver.script("return document.querySelectorAll('.replay .room-select option').length;");
    assert_eq!(rooms, 5, "one entry per room of the config");

    // The reproduce page: one widget per setting.
    let results = dir.path().join("results");
    Fm::new(["reproduce", "--seeds", "2"])
        .out(&results)
        .sets(&SMALL)
        .ok();
    driver.open(&results.join("report.html"));
    check_page_health(&driver, 2, "reproduce report");
    std::fs::write(
        target.join("reproduce-report-screenshot.png"),
        driver.full_page_png(),
    )
    .unwrap();
}
