//! `fuzzymotiv replay RUN --gif`: one animated GIF per room that decodes with the right size and
//! frame count, written through the output guard; bad `--size`, `--stride`, `--fps` are named.

use crate::common;

use std::path::Path;

use common::{Fm, SMALL, repo, stderr};

/// (width, height, frames) of a GIF file.
fn decode(path: &Path) -> (u16, u16, usize) {
    let file = std::fs::File::open(path).unwrap();
    let mut d = gif::DecodeOptions::new().read_info(file).unwrap();
    let (w, h) = (d.width(), d.height());
    let mut n = 0;
    while d.read_next_frame().unwrap().is_some() {
        n += 1;
    }
    (w, h, n)
}

#[test]
fn replay_gif_writes_one_gif_per_room_through_the_guard() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tmp.path().join("run");
    let cfg = repo().join("configs/tiny.toml");
    Fm::new(["run".as_ref(), cfg.as_os_str()])
        .out(&run)
        .sets(&SMALL)
        .arg("--quiet")
        .ok();
    let page = tmp.path().join("r/replay.html");
    let replay = |extra: &[&str]| {
        let fm = Fm::new([
            "replay".as_ref(),
            run.as_os_str(),
            "--out".as_ref(),
            page.as_os_str(),
        ]);
        extra.iter().fold(fm, |fm, a| fm.arg(a)).run()
    };
    let o = replay(&["--gif", "--size", "96", "--stride", "10"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut gifs: Vec<_> = std::fs::read_dir(tmp.path().join("r"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "gif"))
        .collect();
    gifs.sort();
    let names: Vec<_> = gifs
        .iter()
        .map(|p| p.file_name().unwrap().to_owned())
        .collect();
    assert_eq!(names, ["replay-H.gif", "replay-U.gif", "replay-square.gif"]);
    for g in &gifs {
        // 100 steps: poses 0, 10, …, 100.
        assert_eq!(decode(g), (96, 96, 11), "{}", g.display());
    }
    assert!(stderr(&o).contains("replay-H.gif"), "{}", stderr(&o));
    let before = std::fs::read(&gifs[0]).unwrap();
    // The same replay again: nothing to do.
    let o = replay(&["--gif", "--size", "96", "--stride", "10"]);
    assert!(stderr(&o).contains("nothing to do"), "{}", stderr(&o));
    // Other GIFs of those names are kept unless --force.
    let o = replay(&["--gif", "--size", "128", "--stride", "10"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("pass --force"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&gifs[0]).unwrap(), before);
    let o = replay(&["--gif", "--size", "128", "--stride", "10", "--force"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(decode(&gifs[0]), (128, 128, 11));
}

#[test]
fn bad_gif_options_are_named() {
    let tmp = tempfile::tempdir().unwrap();
    let genome = tmp.path().join("g.json");
    let weights = vec!["0.1"; 68].join(",");
    std::fs::write(
        &genome,
        format!(r#"{{"shape": {{"hidden": 6}}, "weights": [{weights}]}}"#),
    )
    .unwrap();
    let out = tmp.path().join("replay.html");
    for (args, want) in [
        (
            &["--gif", "--size", "10"][..],
            "--size: must be a frame side in 64..=2048 pixels, got 10",
        ),
        (
            &["--gif", "--stride", "0"][..],
            "--stride: must be a whole number ≥ 1",
        ),
        (
            &["--gif", "--fps", "0"][..],
            "--fps: must be a frame rate in [0.01, 50]",
        ),
        (&["--size", "100"][..], "--gif"),
    ] {
        let fm = Fm::new([
            "replay".as_ref(),
            genome.as_os_str(),
            "--out".as_ref(),
            out.as_os_str(),
        ]);
        let o = args.iter().fold(fm, |fm, a| fm.arg(a)).run();
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(want), "{args:?}: {}", stderr(&o));
        assert!(!out.exists());
    }
}
