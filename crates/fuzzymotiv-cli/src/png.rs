//! Figures as files: every SVG, and with `--png` a PNG beside it, rasterised in pure Rust by
//! `resvg`.
//!
//! Text needs a font. The system's fonts are loaded once (`fontdb`'s `load_system_fonts`: the
//! usual font directories and fontconfig's configuration); the generic `sans-serif` family of
//! the SVGs is mapped to the first of DejaVu Sans, Liberation Sans, Noto Sans, FreeSans or
//! Arial that is installed, or else to any installed family. With no font at all the PNGs are
//! drawn without their text (shapes only) and a note says so once; installing a font package
//! (e.g. Debian's `fonts-dejavu-core`, or `fonts-liberation`, which Chromium pulls in) fixes it.

use std::sync::{Arc, OnceLock};

use resvg::usvg::{self, fontdb};

use crate::error::CliError;
use crate::files::{StagedDir, io_err, write_atomic};
use crate::note;

/// PNG pixels per SVG pixel: 2 gives crisp figures on high-density screens and in print.
const PNG_SCALE: f32 = 2.0;

/// Families tried, in order, for the SVGs' generic `sans-serif`.
const SANS_FAMILIES: [&str; 5] = [
    "DejaVu Sans",
    "Liberation Sans",
    "Noto Sans",
    "FreeSans",
    "Arial",
];

fn fonts() -> Arc<fontdb::Database> {
    static FONTS: OnceLock<Arc<fontdb::Database>> = OnceLock::new();
    FONTS
        .get_or_init(|| {
            let mut db = fontdb::Database::new();
            db.load_system_fonts();
            let families: Vec<String> = db
                .faces()
                .flat_map(|f| f.families.iter().map(|(name, _)| name.clone()))
                .collect();
            let pick = SANS_FAMILIES
                .iter()
                .find(|want| families.iter().any(|f| f == *want))
                .map(|s| s.to_string())
                .or_else(|| families.first().cloned());
            match pick {
                Some(family) => db.set_sans_serif_family(family),
                None => note!(
                    "note: no system fonts found, so the PNG figures have no text; install a font package (e.g. fonts-dejavu-core)"
                ),
            }
            Arc::new(db)
        })
        .clone()
}

/// Rasterises an SVG document to PNG bytes.
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>, String> {
    let options = usvg::Options {
        fontdb: fonts(),
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(svg, &options).map_err(|e| format!("invalid SVG: {e}"))?;
    let size = tree.size();
    let (w, h) = (
        (size.width() * PNG_SCALE).ceil() as u32,
        (size.height() * PNG_SCALE).ceil() as u32,
    );
    let mut pixmap = resvg::tiny_skia::Pixmap::new(w.max(1), h.max(1))
        .ok_or_else(|| format!("cannot allocate a {w}×{h} image"))?;
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::from_scale(PNG_SCALE, PNG_SCALE),
        &mut pixmap.as_mut(),
    );
    pixmap
        .encode_png()
        .map_err(|e| format!("PNG encoding failed: {e}"))
}

/// Writes `STEM.svg` into a staged directory, and `STEM.png` beside it when `png`.
pub fn write_figure(staged: &StagedDir, stem: &str, svg: &str, png: bool) -> Result<(), CliError> {
    staged.write(&format!("{stem}.svg"), svg)?;
    if png {
        let bytes = svg_to_png(svg).map_err(|e| CliError::runtime(format!("{stem}.png: {e}")))?;
        staged.write(&format!("{stem}.png"), bytes)?;
    }
    Ok(())
}

/// Writes an SVG file at `path` (any location), and the PNG beside it when `png`.
pub fn write_figure_at(path: &std::path::Path, svg: &str, png: bool) -> Result<(), CliError> {
    write_atomic(path, svg)?;
    if png {
        let out = path.with_extension("png");
        let bytes = svg_to_png(svg).map_err(|e| io_err(&out, std::io::Error::other(e)))?;
        write_atomic(&out, bytes)?;
    }
    Ok(())
}

/// `--png` on a finished output: writes `X.png` beside every `X.svg` under `dir` (and its
/// subdirectories) that has none, and nothing else. Returns how many were written.
pub fn add_missing_pngs(dir: &std::path::Path) -> Result<usize, CliError> {
    let mut written = 0;
    let entries = std::fs::read_dir(dir).map_err(|e| io_err(dir, e))?;
    let mut paths: Vec<_> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    paths.sort();
    for path in paths {
        let meta = std::fs::symlink_metadata(&path).map_err(|e| io_err(&path, e))?;
        if meta.is_dir() {
            written += add_missing_pngs(&path)?;
        } else if meta.is_file()
            && path.extension().is_some_and(|e| e == "svg")
            && !path.with_extension("png").exists()
        {
            let svg = std::fs::read_to_string(&path).map_err(|e| io_err(&path, e))?;
            let out = path.with_extension("png");
            let bytes = svg_to_png(&svg).map_err(|e| io_err(&out, std::io::Error::other(e)))?;
            write_atomic(&out, bytes)?;
            written += 1;
        }
    }
    Ok(written)
}

/// `--png` on a finished output: the PNGs it lacks, and nothing else; says how many.
pub fn add_pngs(dir: &std::path::Path) -> Result<(), CliError> {
    let n = add_missing_pngs(dir)?;
    note!("--png: {n} PNG figure(s) added to {}", dir.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_small_svg_becomes_a_png_of_twice_its_size() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="30" height="20"><rect width="30" height="20" fill="red"/><text x="2" y="15" font-family="sans-serif">F</text></svg>"#;
        let png = svg_to_png(svg).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        // IHDR: width and height, big-endian, at bytes 16..24.
        assert_eq!(u32::from_be_bytes(png[16..20].try_into().unwrap()), 60);
        assert_eq!(u32::from_be_bytes(png[20..24].try_into().unwrap()), 40);
    }

    #[test]
    fn broken_svg_is_an_error_not_a_panic() {
        assert!(svg_to_png("<svg").is_err());
    }
}
