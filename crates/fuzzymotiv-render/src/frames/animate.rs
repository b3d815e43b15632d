//! Animated GIFs of frames with the `gif` crate, in one fixed palette: the 216 colours of the
//! 6 × 6 × 6 cube, the scenes' own colours (exact) and a grey ramp. Each frame after the first
//! stores only the rectangle that changed, so a rollout's GIF is small and quick to write.

use super::error::FrameError;
use std::sync::LazyLock;

use gif::{DisposalMethod, Encoder, Frame, Repeat};

use crate::frames::scene::{
    BODY, FLOOR, HEADING, HOME_RIM, HOME_ZONE, IDLE, OBSTACLE, OUTSIDE, PATH, RAY_HIGH, RAY_LOW,
    TEXT, WALL, action_colour,
};

/// The largest frame rate (frames per second): a GIF's delays are whole hundredths of a
/// second, and viewers slow down delays under 2.
pub const MAX_FPS: f64 = 50.0;
/// The smallest frame rate (frames per second): one frame per 100 s.
pub const MIN_FPS: f64 = 0.01;
/// How long the last frame stays before the animation loops (hundredths of a second, at least).
pub const LAST_FRAME_HOLD: u16 = 100;

/// The palette, 256 colours: the cube, the scenes' colours, then greys.
pub static PALETTE: LazyLock<Vec<[u8; 3]>> = LazyLock::new(|| {
    let levels = [0u8, 51, 102, 153, 204, 255];
    let mut p: Vec<[u8; 3]> = Vec::with_capacity(256);
    for r in levels {
        for g in levels {
            for b in levels {
                p.push([r, g, b]);
            }
        }
    }
    let scene = [
        OUTSIDE, FLOOR, WALL, OBSTACLE, HOME_ZONE, HOME_RIM, PATH, BODY, HEADING, RAY_LOW,
        RAY_HIGH, TEXT, IDLE,
    ];
    let actions = [
        fuzzymotiv::simulation::Action::Straight,
        fuzzymotiv::simulation::Action::Left30,
        fuzzymotiv::simulation::Action::Right30,
        fuzzymotiv::simulation::Action::Turn180,
    ]
    .map(action_colour);
    for c in scene.into_iter().chain(actions) {
        if !p.contains(&c) {
            p.push(c);
        }
    }
    let mut v = 8u32;
    while p.len() < 256 {
        let c = [v as u8; 3];
        if !p.contains(&c) {
            p.push(c);
        }
        v = (v + 6) % 256;
    }
    p
});

/// The palette index of every colour: the nearest palette colour of each 15-bit bucket's
/// centre, and per bucket the palette colours inside it, which map to themselves exactly.
struct Quantiser {
    nearest: Vec<u8>,
    /// Per bucket, the first entry of its exact colours in `exact` (`starts[b]..starts[b + 1]`).
    starts: Vec<u32>,
    exact: Vec<([u8; 3], u8)>,
}

fn bucket([r, g, b]: [u8; 3]) -> usize {
    (usize::from(r >> 3) << 10) | (usize::from(g >> 3) << 5) | usize::from(b >> 3)
}

static QUANTISER: LazyLock<Quantiser> = LazyLock::new(|| {
    let pal = &*PALETTE;
    let nearest = (0..1usize << 15)
        .map(|b| {
            let centre = [b >> 10, (b >> 5) & 31, b & 31].map(|v| (v * 8 + 4) as i32);
            let dist =
                |c: &[u8; 3]| -> i32 { (0..3).map(|k| (i32::from(c[k]) - centre[k]).pow(2)).sum() };
            (0..pal.len())
                .min_by_key(|&i| dist(&pal[i]))
                .expect("256 colours") as u8
        })
        .collect();
    let mut by_bucket: Vec<([u8; 3], u8, usize)> = (pal.iter().enumerate())
        .map(|(i, c)| (*c, i as u8, bucket(*c)))
        .collect();
    by_bucket.sort_by_key(|e| (e.2, e.1));
    let mut starts = vec![0u32; (1 << 15) + 1];
    for e in &by_bucket {
        starts[e.2 + 1] += 1;
    }
    for b in 0..1 << 15 {
        starts[b + 1] += starts[b];
    }
    let exact = by_bucket.into_iter().map(|(c, i, _)| (c, i)).collect();
    Quantiser {
        nearest,
        starts,
        exact,
    }
});

/// The palette index of `rgb`: itself when it is a palette colour, else (about) the nearest.
pub fn palette_index(rgb: [u8; 3]) -> u8 {
    let q = &*QUANTISER;
    let b = bucket(rgb);
    let (lo, hi) = (q.starts[b] as usize, q.starts[b + 1] as usize);
    q.exact[lo..hi]
        .iter()
        .find(|(c, _)| *c == rgb)
        .map_or(q.nearest[b], |&(_, i)| i)
}

/// The delay of one frame at `fps` frames per second (hundredths of a second), or why `fps`
/// is not a frame rate.
pub fn delay_of(fps: f64) -> Result<u16, FrameError> {
    if !(MIN_FPS..=MAX_FPS).contains(&fps) {
        return Err(FrameError::Fps {
            got: fps,
            min: MIN_FPS,
            max: MAX_FPS,
        });
    }
    Ok((100.0 / fps).round() as u16)
}

/// An animated GIF being written, frame by frame (RGB, 3 bytes per pixel, row by row), looping
/// forever; the last frame is held for at least [`LAST_FRAME_HOLD`].
pub struct GifWriter {
    encoder: Encoder<Vec<u8>>,
    width: usize,
    height: usize,
    delay: u16,
    previous: Option<Vec<u8>>,
    pending: Option<Frame<'static>>,
}

impl GifWriter {
    /// A GIF of `width × height` frames shown `delay` hundredths of a second each.
    pub fn new(width: u32, height: u32, delay: u16) -> Result<GifWriter, FrameError> {
        let (Ok(w), Ok(h)) = (u16::try_from(width), u16::try_from(height)) else {
            return Err(FrameError::TooLargeForGif { width, height });
        };
        let flat: Vec<u8> = PALETTE.iter().flatten().copied().collect();
        let mut encoder = Encoder::new(Vec::new(), w, h, &flat)?;
        encoder.set_repeat(Repeat::Infinite)?;
        Ok(GifWriter {
            encoder,
            width: width as usize,
            height: height as usize,
            delay,
            previous: None,
            pending: None,
        })
    }

    /// Adds a frame: RGB bytes, `width · height · 3` of them.
    pub fn push(&mut self, rgb: &[u8]) -> Result<(), FrameError> {
        self.push_pixels(rgb, 3)
    }

    /// Adds a frame of opaque RGBA bytes (a pixmap's), `width · height · 4` of them.
    pub fn push_rgba(&mut self, rgba: &[u8]) -> Result<(), FrameError> {
        self.push_pixels(rgba, 4)
    }

    /// Adds a frame of `channels` bytes per pixel (RGB first); only the rectangle that changed
    /// since the previous frame is stored.
    fn push_pixels(&mut self, px: &[u8], channels: usize) -> Result<(), FrameError> {
        let (w, h, c) = (self.width, self.height, channels);
        if px.len() != w * h * c {
            return Err(FrameError::FrameBytes {
                width: w,
                height: h,
                expected: w * h * c,
                got: px.len(),
            });
        }
        let (x0, y0, x1, y1) = match &self.previous {
            Some(prev) if prev.len() == px.len() => {
                changed(prev, px, w, h, c).unwrap_or((0, 0, 1, 1))
            }
            _ => (0, 0, w, h),
        };
        let mut indices = Vec::with_capacity((x1 - x0) * (y1 - y0));
        for y in y0..y1 {
            let row = &px[c * (y * w + x0)..c * (y * w + x1)];
            indices.extend(
                row.chunks_exact(c)
                    .map(|p| palette_index([p[0], p[1], p[2]])),
            );
        }
        let frame = Frame {
            delay: self.delay,
            dispose: DisposalMethod::Keep,
            left: x0 as u16,
            top: y0 as u16,
            width: (x1 - x0) as u16,
            height: (y1 - y0) as u16,
            buffer: indices.into(),
            ..Frame::default()
        };
        self.flush()?;
        self.pending = Some(frame);
        match &mut self.previous {
            Some(prev) if prev.len() == px.len() => prev.copy_from_slice(px),
            _ => self.previous = Some(px.to_vec()),
        }
        Ok(())
    }

    fn flush(&mut self) -> Result<(), FrameError> {
        match self.pending.take() {
            Some(f) => Ok(self.encoder.write_frame(&f)?),
            None => Ok(()),
        }
    }

    /// The GIF's bytes (the last frame held for at least [`LAST_FRAME_HOLD`]).
    pub fn finish(mut self) -> Result<Vec<u8>, FrameError> {
        if let Some(f) = &mut self.pending {
            f.delay = f.delay.max(LAST_FRAME_HOLD);
        }
        self.flush()?;
        Ok(self.encoder.into_inner()?)
    }
}

/// The smallest rectangle `(x0, y0, x1, y1)` (ends excluded) holding every pixel that differs
/// between two frames of `c` bytes per pixel, or `None` when they are equal.
fn changed(
    a: &[u8],
    b: &[u8],
    w: usize,
    h: usize,
    c: usize,
) -> Option<(usize, usize, usize, usize)> {
    let row = |y: usize| c * y * w..c * (y + 1) * w;
    let y0 = (0..h).find(|&y| a[row(y)] != b[row(y)])?;
    let y1 = (y0..h).rev().find(|&y| a[row(y)] != b[row(y)])? + 1;
    let (mut x0, mut x1) = (w, 0);
    for y in y0..y1 {
        let (ra, rb) = (&a[row(y)], &b[row(y)]);
        let differs = |x: &usize| ra[c * x..c * x + c] != rb[c * x..c * x + c];
        if let Some(x) = (0..x0).find(differs) {
            x0 = x;
        }
        if let Some(x) = (x1..w).rev().find(differs) {
            x1 = x + 1;
        }
    }
    Some((x0, y0, x1.max(x0 + 1), y1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_palette_holds_the_scene_colours_exactly() {
        assert_eq!(PALETTE.len(), 256);
        for c in [BODY, PATH, WALL, FLOOR, RAY_HIGH, HOME_ZONE] {
            assert_eq!(PALETTE[usize::from(palette_index(c))], c, "{c:?}");
        }
        // Another colour maps to a near one.
        let near = PALETTE[usize::from(palette_index([250, 10, 10]))];
        assert!(
            near.iter()
                .zip([250u8, 10, 10])
                .all(|(a, b)| a.abs_diff(b) < 40),
            "{near:?}"
        );
    }

    #[test]
    fn frame_rates_become_delays() {
        assert_eq!(delay_of(25.0).unwrap(), 4);
        assert_eq!(delay_of(1.0).unwrap(), 100);
        assert!(delay_of(0.0).is_err() && delay_of(60.0).is_err() && delay_of(f64::NAN).is_err());
    }

    #[test]
    fn only_the_changed_rectangle_is_found() {
        let (w, h) = (5, 4);
        let a = vec![0u8; w * h * 3];
        let mut b = a.clone();
        assert_eq!(changed(&a, &b, w, h, 3), None);
        b[3 * (w + 1)] = 9; // (1, 1)
        b[3 * (2 * w + 3) + 2] = 9; // (3, 2)
        assert_eq!(changed(&a, &b, w, h, 3), Some((1, 1, 4, 3)));
    }
}
