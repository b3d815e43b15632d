//! Rollout frames and animated GIFs, drawn in pure Rust (tiny-skia, a built-in bitmap font and
//! the `gif` crate; no system fonts, no resvg), for `fuzzymotiv replay --gif` and Python's
//! `fm.frames` / `fm.save_gif`.
//!
//! A frame shows the room (outline, obstacles, home zone), the path so far, the robot's body
//! and heading, its eight IR sensors as rays (from the sensor to the first wall, at most the
//! ray's range; grey and thin when they read nothing, red and thick at 1023), a step counter
//! and the action taken from that pose. Same rollout and options → the same bytes.
//!
//! ```
//! use fuzzymotiv::simulation::Pose;
//! use fuzzymotiv::simulation::Room;
//! use fuzzymotiv_render::frames::{FrameOptions, Track, render};
//! let room = Room::builtin("square").unwrap();
//! let poses: Vec<Pose> = (0..5).map(|t| Pose::new(room.home.x + 8.0 * t as f64, room.home.y, 0.0)).collect();
//! let track = Track { poses: &poses, sensors: None, actions: None, idle: None };
//! let frames = render(&room, track, FrameOptions::new(96, 2).unwrap()).unwrap();
//! assert_eq!((frames.len(), frames.width, frames.height), (3, 96, 96)); // poses 0, 2, 4
//! assert_eq!(frames.frame(0).len(), 96 * 96 * 3);
//! ```

pub mod animate;
pub mod draw;
pub mod error;
pub mod font;
pub mod scene;

use fuzzymotiv::simulation::Room;
use rayon::prelude::*;
use tiny_skia::Pixmap;

pub use crate::frames::animate::GifWriter;
pub use crate::frames::draw::Painter;
pub use crate::frames::error::{Column, FrameError};
pub use crate::frames::scene::{FrameOptions, Track, View};

/// Rendered frames: RGB bytes, frame after frame, each `width × height` pixels row by row.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Frames {
    /// Frame width (pixels).
    pub width: u32,
    /// Frame height (pixels).
    pub height: u32,
    /// The pose each frame shows ([`FrameOptions::frame_poses`]).
    pub poses: Vec<usize>,
    /// The pixels, `len() · height · width · 3` bytes.
    pub rgb: Vec<u8>,
}

impl Frames {
    /// Number of frames.
    pub fn len(&self) -> usize {
        self.poses.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.poses.is_empty()
    }

    /// Bytes of one frame.
    pub fn frame_bytes(&self) -> usize {
        self.width as usize * self.height as usize * 3
    }

    /// Frame `k`'s RGB bytes.
    pub fn frame(&self, k: usize) -> &[u8] {
        let n = self.frame_bytes();
        &self.rgb[k * n..(k + 1) * n]
    }
}

/// The RGB bytes of an opaque pixmap.
fn rgb_of(pixmap: &Pixmap, out: &mut [u8]) {
    for (o, p) in out.chunks_exact_mut(3).zip(pixmap.data().chunks_exact(4)) {
        o.copy_from_slice(&p[..3]);
    }
}

/// The most memory [`render`]'s frames may take (8 GiB): a longer or larger film is an error
/// rather than a machine brought to a halt.
pub const MAX_FRAME_BYTES: usize = 8 << 30;

/// Every frame of `track` in `room` (drawn in parallel on rayon's pool; the bytes do not depend
/// on the number of threads). The error names the track's bad column, or says that the frames
/// would take more than [`MAX_FRAME_BYTES`].
pub fn render(room: &Room, track: Track<'_>, opts: FrameOptions) -> Result<Frames, FrameError> {
    let painter = Painter::new(room, track, opts)?;
    let poses = opts.frame_poses(track.poses.len());
    let size = opts.size();
    let n = size as usize * size as usize * 3;
    let bytes = n.saturating_mul(poses.len());
    let too_many = |over_limit: bool| FrameError::TooMuchMemory {
        frames: poses.len(),
        size,
        bytes,
        over_limit,
    };
    if bytes > MAX_FRAME_BYTES {
        return Err(too_many(true));
    }
    let mut rgb = Vec::new();
    (rgb.try_reserve_exact(bytes)).map_err(|_| too_many(false))?;
    rgb.resize(bytes, 0);
    rgb.par_chunks_mut(n).zip(poses.par_iter()).for_each_init(
        || Pixmap::new(size, size).expect("size checked"),
        |pixmap, (out, &t)| {
            painter.draw(t, pixmap);
            rgb_of(pixmap, out);
        },
    );
    Ok(Frames {
        width: size,
        height: size,
        poses,
        rgb,
    })
}

/// The one frame of `track`'s last pose (what [`render`] draws last, the same bytes), drawn
/// alone: a live view (the Gymnasium env's `render()`) costs one frame whatever the length.
pub fn render_last(
    room: &Room,
    track: Track<'_>,
    opts: FrameOptions,
) -> Result<Frames, FrameError> {
    let painter = Painter::new(room, track, opts)?;
    let size = opts.size();
    let mut pixmap = Pixmap::new(size, size).expect("size checked");
    let last = track.poses.len() - 1; // Painter::new checked there is a pose
    painter.draw(last, &mut pixmap);
    let mut rgb = vec![0; size as usize * size as usize * 3];
    rgb_of(&pixmap, &mut rgb);
    Ok(Frames {
        width: size,
        height: size,
        poses: vec![last],
        rgb,
    })
}

/// The animated GIF of `track` in `room`, `delay` hundredths of a second per frame
/// ([`animate::delay_of`]), drawn and encoded one frame at a time.
pub fn gif(
    room: &Room,
    track: Track<'_>,
    opts: FrameOptions,
    delay: u16,
) -> Result<Vec<u8>, FrameError> {
    let painter = Painter::new(room, track, opts)?;
    let size = opts.size();
    let mut pixmap = Pixmap::new(size, size).expect("size checked");
    let mut writer = GifWriter::new(size, size, delay)?;
    for t in opts.frame_poses(track.poses.len()) {
        painter.draw(t, &mut pixmap);
        writer.push_rgba(pixmap.data())?;
    }
    writer.finish()
}
