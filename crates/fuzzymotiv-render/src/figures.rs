//! Figures as files: every SVG, and a PNG beside it when the caller passes a [`Rasterise`]
//! (the command line's `--png` draws with resvg; this crate draws none itself).

use std::path::Path;

use fuzzymotiv_records::files::error::CliError;
use fuzzymotiv_records::files::guard::{StagedDir, io_err, write_atomic};

/// Turns an SVG document into PNG bytes.
pub trait Rasterise: Sync {
    /// The PNG of `svg`, or why it cannot be drawn.
    fn png(&self, svg: &str) -> Result<Vec<u8>, RasterError>;
}

/// Why a figure's PNG cannot be drawn.
#[derive(Debug, thiserror::Error)]
pub enum RasterError {
    /// The SVG cannot be read.
    #[error("invalid SVG: {0}")]
    InvalidSvg(#[source] Box<dyn std::error::Error + Send + Sync>),
    /// The image cannot be allocated.
    #[error("cannot allocate a {width}×{height} image")]
    TooLarge {
        /// Width, pixels.
        width: u32,
        /// Height, pixels.
        height: u32,
    },
    /// The PNG cannot be encoded.
    #[error("PNG encoding failed: {0}")]
    Encode(#[source] Box<dyn std::error::Error + Send + Sync>),
}

/// Writes `STEM.svg` into a staged directory, and `STEM.png` beside it with `png`.
pub fn write_figure(
    staged: &StagedDir,
    stem: &str,
    svg: &str,
    png: Option<&dyn Rasterise>,
) -> Result<(), CliError> {
    staged.write(&format!("{stem}.svg"), svg)?;
    if let Some(png) = png {
        let bytes = png
            .png(svg)
            .map_err(|e| CliError::runtime(format!("{stem}.png: {e}")))?;
        staged.write(&format!("{stem}.png"), bytes)?;
    }
    Ok(())
}

/// Writes an SVG file at `path` (any location), and the PNG beside it with `png`.
pub fn write_figure_at(
    path: &Path,
    svg: &str,
    png: Option<&dyn Rasterise>,
) -> Result<(), CliError> {
    write_atomic(path, svg)?;
    if let Some(png) = png {
        let out = path.with_extension("png");
        let bytes = png
            .png(svg)
            .map_err(|e| io_err(&out, std::io::Error::other(e)))?;
        write_atomic(&out, bytes)?;
    }
    Ok(())
}

/// Draws `X.png` beside the figure `X.svg` at `svg_path`, replacing an older PNG (a merged
/// sweep's `summary.svg` changes with its jobs).
pub fn png_beside(svg_path: &Path, png: &dyn Rasterise) -> Result<(), CliError> {
    let out = svg_path.with_extension("png");
    let svg = std::fs::read_to_string(svg_path).map_err(|e| io_err(svg_path, e))?;
    let bytes = (png.png(&svg)).map_err(|e| io_err(&out, std::io::Error::other(e)))?;
    write_atomic(&out, bytes)
}

/// PNGs for a finished output: writes `X.png` beside every `X.svg` under `dir` (and its
/// subdirectories) that has none, and nothing else. Returns how many were written.
pub fn add_missing_pngs(dir: &Path, png: &dyn Rasterise) -> Result<usize, CliError> {
    let mut written = 0;
    let entries = std::fs::read_dir(dir).map_err(|e| io_err(dir, e))?;
    let mut paths: Vec<_> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    paths.sort();
    for path in paths {
        let meta = std::fs::symlink_metadata(&path).map_err(|e| io_err(&path, e))?;
        if meta.is_dir() {
            written += add_missing_pngs(&path, png)?;
        } else if meta.is_file()
            && path.extension().is_some_and(|e| e == "svg")
            && !path.with_extension("png").exists()
        {
            let svg = std::fs::read_to_string(&path).map_err(|e| io_err(&path, e))?;
            let out = path.with_extension("png");
            let bytes = png
                .png(&svg)
                .map_err(|e| io_err(&out, std::io::Error::other(e)))?;
            write_atomic(&out, bytes)?;
            written += 1;
        }
    }
    Ok(written)
}
