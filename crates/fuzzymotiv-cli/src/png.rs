//! PNG figures for `--png`, rasterised in pure Rust by `resvg`: the [`Rasterise`] that the
//! figure writers of `fuzzymotiv_pipeline` ([`fuzzymotiv_pipeline::render::figures`]) are given.
//!
//! Text needs a font. The system's fonts are loaded once (`fontdb`'s `load_system_fonts`: the
//! usual font directories and fontconfig's configuration); the generic `sans-serif` family of
//! the SVGs is mapped to the first of DejaVu Sans, Liberation Sans, Noto Sans, FreeSans or
//! Arial that is installed, or else to any installed family. With no font at all the PNGs are
//! drawn without their text (shapes only) and a note says so once; installing a font package
//! (e.g. Debian's `fonts-dejavu-core`, or `fonts-liberation`, which Chromium pulls in) fixes it.

use std::sync::{Arc, OnceLock};

use resvg::usvg::{self, fontdb};

use crate::console::note;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::render::figures::{RasterError, Rasterise, add_missing_pngs};

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
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>, RasterError> {
    let options = usvg::Options {
        fontdb: fonts(),
        ..usvg::Options::default()
    };
    let tree =
        usvg::Tree::from_str(svg, &options).map_err(|e| RasterError::InvalidSvg(Box::new(e)))?;
    let size = tree.size();
    let (w, h) = (
        (size.width() * PNG_SCALE).ceil() as u32,
        (size.height() * PNG_SCALE).ceil() as u32,
    );
    let mut pixmap =
        resvg::tiny_skia::Pixmap::new(w.max(1), h.max(1)).ok_or(RasterError::TooLarge {
            width: w,
            height: h,
        })?;
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::from_scale(PNG_SCALE, PNG_SCALE),
        &mut pixmap.as_mut(),
    );
    pixmap
        .encode_png()
        .map_err(|e| RasterError::Encode(Box::new(e)))
}

/// The resvg rasteriser ([`svg_to_png`]) for the writers of `fuzzymotiv_pipeline`.
pub struct Resvg;

impl Rasterise for Resvg {
    fn png(&self, svg: &str) -> Result<Vec<u8>, RasterError> {
        svg_to_png(svg)
    }
}

/// The rasteriser for `--png`: resvg with it, none without.
pub fn rasteriser(png: bool) -> Option<&'static dyn Rasterise> {
    png.then_some(&Resvg as &dyn Rasterise)
}

/// `--png` on a finished output: the PNGs it lacks, and nothing else; says how many.
pub fn add_pngs(dir: &std::path::Path) -> Result<(), CliError> {
    let n = add_missing_pngs(dir, &Resvg)?;
    note!("--png: {n} PNG figure(s) added to {}", dir.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use fuzzymotiv::simulation::Trajectory;
    use fuzzymotiv::simulation::{BUILTIN_ROOMS, Room};
    use fuzzymotiv_pipeline::render::figure::text_width;
    use fuzzymotiv_pipeline::render::svg::trajectories_svg;

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
        assert!(matches!(
            svg_to_png("<svg"),
            Err(RasterError::InvalidSvg(_))
        ));
    }

    /// Built-in rooms, a room with its home on a wall, and the U room (home in an arm, its
    /// zone crossing two walls).
    fn rooms(n: usize) -> Vec<Room> {
        let wall = Room::from_toml_str(
            "name = \"home-on-a-wall\"\noutline = [[0,0],[800,0],[800,500],[0,500]]\nhome = { x = 400, y = 40, heading_deg = 90 }\n",
            "wall.toml",
        )
        .unwrap();
        let u = Room::from_toml_str(include_str!("../../../rooms/U.toml"), "rooms/U.toml").unwrap();
        let mut all: Vec<Room> = BUILTIN_ROOMS
            .iter()
            .map(|name| Room::builtin(name).unwrap())
            .collect();
        all.insert(1, wall);
        all.insert(3, u);
        (0..n).map(|k| all[k % all.len()].clone()).collect()
    }

    #[test]
    fn home_zone_is_the_disc_within_the_room() {
        let all = rooms(7);
        for room in &all {
            let tr = Trajectory {
                poses: vec![room.home],
                ..Default::default()
            };
            let svg = trajectories_svg("t", &[(room, &tr)]);
            assert!(svg.contains("blue: home zone") && !svg.contains("quarter"));
            // Rendered: blue inside both the disc and the room, nowhere else.
            let png = svg_to_png(&svg).unwrap();
            let pixmap = resvg::tiny_skia::Pixmap::decode_png(&png).unwrap();
            let (lo, hi) = room.bounds();
            let scale = 0.3;
            let slot = ((hi.x - lo.x) * scale).max(text_width(&room.name, false));
            let x_off = 20.0 + (slot - (hi.x - lo.x) * scale) / 2.0;
            let blue = |x: f64, y: f64| {
                let px = (2.0 * (x_off + (x - lo.x) * scale)).round() as u32;
                let py = (2.0 * (40.0 + (hi.y - y) * scale)).round() as u32;
                let c = pixmap.pixel(px, py).unwrap();
                i32::from(c.blue()) - i32::from(c.red()) > 8
            };
            let zone = room.home_zone;
            // 36 points on a circle of `f` times the zone's radius around its centre.
            let ring = |f: f64| {
                (0..36).map(move |k| {
                    let a = k as f64 * std::f64::consts::TAU / 36.0;
                    let r = f * zone.radius;
                    fuzzymotiv::simulation::Vec2::new(
                        zone.centre.x + r * a.cos(),
                        zone.centre.y + r * a.sin(),
                    )
                })
            };
            // Points on a ring inside the zone's rim, clear of walls, home marker and the
            // zone's dashed edge.
            for p in ring(0.75) {
                let clear = room.contains(p)
                    && fuzzymotiv::simulation::edges(&room.outline).all(|e| e.dist_to(p) > 15.0)
                    && p.dist(room.home.position()) > 40.0;
                if clear {
                    assert!(
                        blue(p.x, p.y),
                        "{}: ({:.0}, {:.0}) in zone and room, not blue",
                        room.name,
                        p.x,
                        p.y
                    );
                }
            }
            // Inside the disc but outside the room (beyond a wall): not blue.
            for p in ring(0.9) {
                let (plo, phi) = room.bounds();
                let beyond = !room.contains(p)
                    && fuzzymotiv::simulation::edges(&room.outline).all(|e| e.dist_to(p) > 15.0)
                    && p.x > plo.x - 50.0
                    && p.y < phi.y + 50.0;
                if beyond {
                    assert!(
                        !blue(p.x, p.y),
                        "{}: ({:.0}, {:.0}) outside the room but blue",
                        room.name,
                        p.x,
                        p.y
                    );
                }
            }
            // Outside the disc, inside the room (towards the room's far corner): not blue.
            let far = if zone.centre.dist(hi) > zone.centre.dist(lo) {
                hi
            } else {
                lo
            };
            let d = far - zone.centre;
            let p = zone.centre + d * ((zone.radius + 30.0) / d.x.hypot(d.y));
            if room.contains(p) {
                assert!(!blue(p.x, p.y), "{}: outside the zone but blue", room.name);
            }
        }
    }

    /// Renders every `*.svg` in `$FIGS_DIR` to a PNG beside it with the program's renderer, to
    /// look at figures that only appear inline in report pages:
    /// `FIGS_DIR=/tmp/x cargo test -p fuzzymotiv-cli --bin fuzzymotiv png -- --ignored`.
    #[test]
    #[ignore = "a tool, not a test: renders $FIGS_DIR's SVGs (see its doc)"]
    fn render_svgs_in_figs_dir() {
        let Ok(dir) = std::env::var("FIGS_DIR") else {
            return;
        };
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "svg") {
                let svg = std::fs::read_to_string(&path).unwrap();
                std::fs::write(path.with_extension("png"), svg_to_png(&svg).unwrap()).unwrap();
            }
        }
    }
}
