//! Rollout frames and GIFs (`fuzzymotiv_render::frames`) on a real 400-step trial in the
//! H room: sizes, the body and heading where the robot is, the path, stride, determinism over
//! thread counts, a GIF that decodes back to the frames, bad tracks. The frames are also saved as
//! `target/frames-H-*.png` to look at.

use std::path::PathBuf;

use fuzzymotiv::random::rng_from_seed;
use fuzzymotiv::simulation::Controller;
use fuzzymotiv::simulation::Pose;
use fuzzymotiv::simulation::Room;
use fuzzymotiv::simulation::Vec2;
use fuzzymotiv::simulation::{Arena, Trajectory, TrialParams, run_trial};
use fuzzymotiv_render::frames::animate::{PALETTE, delay_of, palette_index};
use fuzzymotiv_render::frames::scene::{BODY, HEADING, PATH, TEXT};
use fuzzymotiv_render::frames::{FrameOptions, Frames, Track, View, gif, render};

/// Straight on, left when a front sensor sees a wall, about when both do.
struct WallShy;

impl Controller for WallShy {
    fn step(&mut self, s: &[f64]) -> [f64; 2] {
        match (s[2].max(s[1]) > 0.3, s[3].max(s[4]) > 0.3) {
            (true, true) => [0.0, 0.0],
            (false, true) | (true, false) => [0.0, 1.0],
            _ => [1.0, 1.0],
        }
    }
}

fn trial(room: &str) -> (Room, Trajectory) {
    let room = Room::builtin(room).unwrap();
    let arena = Arena::new(room.clone(), &TrialParams::default());
    let tr = run_trial(&arena, &mut WallShy, &mut rng_from_seed(3));
    (room, tr)
}

fn pixel(frames: &Frames, k: usize, (x, y): (u32, u32)) -> [u8; 3] {
    let i = 3 * (y as usize * frames.width as usize + x as usize);
    let f = frames.frame(k);
    [f[i], f[i + 1], f[i + 2]]
}

fn count(frames: &Frames, k: usize, rgb: [u8; 3]) -> usize {
    frames
        .frame(k)
        .chunks_exact(3)
        .filter(|p| **p == rgb)
        .count()
}

/// The build's target directory (wherever `CARGO_TARGET_DIR` puts it): target/tmp's parent.
fn target_dir() -> PathBuf {
    let tmp = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    tmp.parent().map_or(tmp.clone(), |p| p.to_path_buf())
}

fn save_png(frames: &Frames, k: usize, name: &str) {
    let file = std::fs::File::create(target_dir().join(name)).unwrap();
    let mut enc = png::Encoder::new(file, frames.width, frames.height);
    enc.set_color(png::ColorType::Rgb);
    enc.write_header()
        .unwrap()
        .write_image_data(frames.frame(k))
        .unwrap();
}

#[test]
fn frames_show_the_body_heading_and_path() {
    let (room, tr) = trial("H");
    assert_eq!(tr.len(), 400);
    let frames = render(&room, Track::of(&tr), FrameOptions::new(320, 1).unwrap()).unwrap();
    assert_eq!((frames.len(), frames.width, frames.height), (401, 320, 320));
    assert_eq!(frames.rgb.len(), 401 * 320 * 320 * 3);
    for t in [0, 120, 400] {
        save_png(&frames, t, &format!("frames-H-{t:03}.png"));
    }
    let view = View::new(&room, 320);
    for t in [0, 57, 200, 400] {
        let p = tr.poses[t];
        let centre = view.pixel(p.position()).unwrap();
        assert_eq!(pixel(&frames, t, centre), BODY, "body at step {t}");
        let ahead = p.position() + Vec2::from_angle(p.heading) * (27.5 * 0.75);
        assert_eq!(
            pixel(&frames, t, view.pixel(ahead).unwrap()),
            HEADING,
            "heading at step {t}"
        );
    }
    // No path at home; a long one at the end; the step counter in the header.
    assert_eq!(count(&frames, 0, PATH), 0);
    assert!(
        count(&frames, 400, PATH) > 150,
        "{}",
        count(&frames, 400, PATH)
    );
    // The robot's back-and-forth overlaps its path: midway it is drawn, not necessarily shorter.
    assert!(count(&frames, 200, PATH) > 50);
    assert!(count(&frames, 200, TEXT) > 50);
    // A pose the robot left long ago is on the path.
    let (t_old, p_old) = (100, tr.poses[100].position());
    let far =
        tr.poses[400].position().dist(p_old) > 60.0 && tr.poses[200].position().dist(p_old) > 60.0;
    if far {
        // The path is antialiased: its colour is exact within a pixel of the pose.
        let (x, y) = view.pixel(p_old).unwrap();
        let near = (x.saturating_sub(1)..=x + 1)
            .flat_map(|i| (y.saturating_sub(1)..=y + 1).map(move |j| (i, j)))
            .any(|q| pixel(&frames, 400, q) == PATH);
        assert!(
            near,
            "pose {t_old}: no path pixel at or next to {:?}",
            (x, y)
        );
    }
}

#[test]
fn stride_picks_frames_and_keeps_the_last() {
    let (room, tr) = trial("T");
    let every = render(&room, Track::of(&tr), FrameOptions::new(128, 1).unwrap()).unwrap();
    let strided = render(&room, Track::of(&tr), FrameOptions::new(128, 7).unwrap()).unwrap();
    let want: Vec<usize> = (0..=400).step_by(7).chain([400]).collect();
    assert_eq!(strided.poses, want);
    for (k, &t) in strided.poses.iter().enumerate() {
        assert_eq!(strided.frame(k), every.frame(t), "pose {t}");
    }
}

#[test]
fn the_bytes_do_not_depend_on_threads() {
    let (room, tr) = trial("L");
    let opts = FrameOptions::new(160, 3).unwrap();
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| render(&room, Track::of(&tr), opts).unwrap())
    };
    let one = on(1);
    assert_eq!(one, on(2));
    assert_eq!(one, on(3));
    let delay = delay_of(25.0).unwrap();
    assert_eq!(
        gif(&room, Track::of(&tr), opts, delay).unwrap(),
        gif(&room, Track::of(&tr), opts, delay).unwrap()
    );
}

/// Decodes a GIF, composing its frames on the canvas: the palette indices of every frame.
fn decode(bytes: &[u8]) -> (u16, u16, Vec<Vec<u8>>, Vec<u16>) {
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::Indexed);
    let mut d = opts.read_info(bytes).unwrap();
    let (w, h) = (d.width(), d.height());
    let mut canvas = vec![0u8; usize::from(w) * usize::from(h)];
    let (mut out, mut delays) = (Vec::new(), Vec::new());
    while let Some(f) = d.read_next_frame().unwrap() {
        for y in 0..usize::from(f.height) {
            for x in 0..usize::from(f.width) {
                let at = (usize::from(f.top) + y) * usize::from(w) + usize::from(f.left) + x;
                canvas[at] = f.buffer[y * usize::from(f.width) + x];
            }
        }
        out.push(canvas.clone());
        delays.push(f.delay);
    }
    (w, h, out, delays)
}

#[test]
fn the_gif_decodes_to_the_frames() {
    let (room, tr) = trial("square");
    let opts = FrameOptions::new(200, 5).unwrap();
    let frames = render(&room, Track::of(&tr), opts).unwrap();
    let bytes = gif(&room, Track::of(&tr), opts, 4).unwrap();
    assert!(bytes.starts_with(b"GIF89a"));
    let (w, h, decoded, delays) = decode(&bytes);
    assert_eq!((w, h, decoded.len()), (200, 200, frames.len()));
    assert_eq!(delays[0], 4);
    assert_eq!(*delays.last().unwrap(), 100, "the last frame is held");
    for (k, canvas) in decoded.iter().enumerate() {
        let want: Vec<u8> = (frames.frame(k).chunks_exact(3))
            .map(|p| palette_index([p[0], p[1], p[2]]))
            .collect();
        assert!(canvas == &want, "frame {k} differs after decoding");
    }
    // The body colour is in the palette as itself.
    assert_eq!(PALETTE[usize::from(palette_index(BODY))], BODY);
}

#[test]
fn bad_tracks_are_named() {
    let room = Room::builtin("H").unwrap();
    let opts = FrameOptions::new(96, 1).unwrap();
    let track = |poses: &'static [Pose]| Track {
        poses,
        sensors: None,
        actions: None,
        idle: None,
    };
    let err = render(&room, track(&[]), opts).unwrap_err().to_string();
    assert!(err.starts_with("x: no poses"), "{err}");
    static NAN: [Pose; 2] = [
        Pose {
            x: 0.0,
            y: 0.0,
            heading: 0.0,
        },
        Pose {
            x: 0.0,
            y: 0.0,
            heading: f64::NAN,
        },
    ];
    let err = render(&room, track(&NAN), opts).unwrap_err().to_string();
    assert!(
        err.starts_with("heading[1]: `NaN` is not a finite number"),
        "{err}"
    );
    let one = [Pose::new(room.home.x, room.home.y, 0.0)];
    let sensors = [fuzzymotiv::simulation::Readings::zeros(8); 3];
    let t = Track {
        poses: &one,
        sensors: Some(&sensors),
        actions: None,
        idle: None,
    };
    let err = render(&room, t, opts).unwrap_err().to_string();
    assert!(err.starts_with("sensors: 3 rows for 1 poses"), "{err}");
    // One pose alone is one frame.
    let single = render(&room, track_of(&one), opts).unwrap();
    assert_eq!(single.len(), 1);
}

fn track_of(poses: &[Pose]) -> Track<'_> {
    Track {
        poses,
        sensors: None,
        actions: None,
        idle: None,
    }
}
