//! Why frames or a GIF cannot be drawn ([`FrameError`]): the option or the track's column at
//! fault as typed data ([`FrameError::field`]), the numbers that were wrong, and the message
//! the command line and Python show.

use fuzzymotiv::params::Num;

/// A column of a track ([`super::Track`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Column {
    /// The poses' x.
    X,
    /// The poses' y.
    Y,
    /// The poses' heading.
    Heading,
    /// The IR readings.
    Sensors,
    /// The actions.
    Action,
    /// The idle flags.
    Idle,
}

impl Column {
    /// Its name, as the track names it.
    pub fn name(self) -> &'static str {
        match self {
            Column::X => "x",
            Column::Y => "y",
            Column::Heading => "heading",
            Column::Sensors => "sensors",
            Column::Action => "action",
            Column::Idle => "idle",
        }
    }
}

impl std::fmt::Display for Column {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Why frames, or a GIF, cannot be drawn.
#[derive(Debug, thiserror::Error)]
pub enum FrameError {
    /// The frame side is out of range.
    #[error("must be a frame side in {min}..={max} pixels, got {got}")]
    Size {
        /// The side asked for.
        got: u32,
        /// The smallest side ([`super::scene::MIN_SIZE`]).
        min: u32,
        /// The largest ([`super::scene::MAX_SIZE`]).
        max: u32,
    },
    /// The stride is 0.
    #[error("must be a whole number ≥ 1 (1 = a frame per step), got 0")]
    Stride,
    /// The frame rate is out of range.
    #[error("must be a frame rate in [{min}, {max}] frames per second, got {}", Num(*got))]
    Fps {
        /// The rate asked for.
        got: f64,
        /// The lowest rate ([`super::animate::MIN_FPS`]).
        min: f64,
        /// The highest ([`super::animate::MAX_FPS`]).
        max: f64,
    },
    /// The track has no poses.
    #[error("x: no poses; a rollout has at least its start pose")]
    NoPoses,
    /// A pose's coordinate or heading is not a finite number.
    #[error("{column}[{row}]: `{value}` is not a finite number")]
    NotFinite {
        /// The column (x, y or heading).
        column: Column,
        /// The pose.
        row: usize,
        /// The value.
        value: f64,
    },
    /// An IR reading is not a finite number.
    #[error(
        "sensors[{row}][{sensor}]: `{value}` is not a finite number; expected IR readings 0–1023"
    )]
    Reading {
        /// The step.
        row: usize,
        /// The sensor.
        sensor: usize,
        /// The value.
        value: f64,
    },
    /// An optional column has neither one row per step nor one per pose.
    #[error("{column}: {rows} rows for {poses} poses; expected {} (one per step) or {poses}", poses - 1)]
    Rows {
        /// The column.
        column: Column,
        /// Its rows.
        rows: usize,
        /// The track's poses.
        poses: usize,
    },
    /// The frames would take more memory than they may.
    #[error(
        "{frames} frames of {size} × {size} pixels need {:.1} GiB, {}; draw fewer (a larger \
         stride) or smaller frames (size), or write a GIF, which is drawn a frame at a time",
        *bytes as f64 / (1u64 << 30) as f64,
        if *over_limit { "more than the 8 GiB that frames may take" } else { "more than can be allocated" }
    )]
    TooMuchMemory {
        /// The frames.
        frames: usize,
        /// Their side, pixels.
        size: u32,
        /// The bytes they need.
        bytes: usize,
        /// Over [`super::MAX_FRAME_BYTES`] (else: the allocation failed).
        over_limit: bool,
    },
    /// The frames are too large for a GIF.
    #[error("frames of {width} × {height} pixels are too large for a GIF (65535 at most)")]
    TooLargeForGif {
        /// Frame width.
        width: u32,
        /// Frame height.
        height: u32,
    },
    /// A frame pushed to a GIF has the wrong number of bytes.
    #[error("a frame of {width} × {height} pixels has {expected} bytes, got {got}")]
    FrameBytes {
        /// Frame width.
        width: usize,
        /// Frame height.
        height: usize,
        /// The bytes it should have.
        expected: usize,
        /// The bytes it has.
        got: usize,
    },
    /// The GIF encoder failed.
    #[error(transparent)]
    Encode(#[from] gif::EncodingError),
}

impl FrameError {
    /// The option (`size`, `stride`, `fps`) or track column at fault, if one is.
    pub fn field(&self) -> Option<&'static str> {
        match self {
            FrameError::Size { .. } => Some("size"),
            FrameError::Stride => Some("stride"),
            FrameError::Fps { .. } => Some("fps"),
            FrameError::NoPoses => Some("x"),
            FrameError::NotFinite { column, .. } | FrameError::Rows { column, .. } => {
                Some(column.name())
            }
            FrameError::Reading { .. } => Some("sensors"),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The option or column at fault is data, not a prefix to parse back out of the message.
    #[test]
    fn a_frame_errors_field_is_data_and_its_message_names_the_numbers() {
        let e = FrameError::Size {
            got: 10,
            min: 64,
            max: 2048,
        };
        assert_eq!(e.field(), Some("size"));
        assert_eq!(
            e.to_string(),
            "must be a frame side in 64..=2048 pixels, got 10"
        );
        let e = FrameError::Rows {
            column: Column::Idle,
            rows: 3,
            poses: 10,
        };
        assert_eq!(e.field(), Some("idle"));
        assert_eq!(
            e.to_string(),
            "idle: 3 rows for 10 poses; expected 9 (one per step) or 10"
        );
        let fps = FrameError::Fps {
            got: 0.0,
            min: 0.01,
            max: 50.0,
        };
        assert_eq!(fps.field(), Some("fps"));
        assert_eq!(
            fps.to_string(),
            "must be a frame rate in [0.01, 50] frames per second, got 0"
        );
    }
}
