//! Hand-written SVG figures: fitness evolution (paper Fig. 6) and trajectories (Figs. 7–8).

use std::fmt::Write as _;

use fuzzymotiv::experiment::GenerationRecord;
use fuzzymotiv::room::Room;
use fuzzymotiv::trial::Trajectory;

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// One panel per setting: best and mean F per generation, with the min–max band.
pub fn fitness_svg(panels: &[(String, Vec<GenerationRecord>)]) -> String {
    let (pw, ph) = (420.0, 300.0);
    let (ml, mr, mt, mb) = (50.0, 15.0, 30.0, 40.0);
    let width = pw * panels.len() as f64;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{ph}" viewBox="0 0 {width} {ph}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="{width}" height="{ph}" fill="white"/>"#);
    for (p, (name, hist)) in panels.iter().enumerate() {
        let ox = p as f64 * pw;
        let (x0, x1, y0, y1) = (ox + ml, ox + pw - mr, ph - mb, mt);
        let n = hist.len().max(2) as f64 - 1.0;
        let x = |g: usize| x0 + (x1 - x0) * g as f64 / n;
        let y = |f: f64| y0 + (y1 - y0) * f.clamp(0.0, 1.0);
        let _ = writeln!(
            s,
            r#"<text x="{}" y="18" text-anchor="middle" font-weight="bold">{}</text>"#,
            (x0 + x1) / 2.0,
            esc(name)
        );
        for k in 0..=5 {
            let f = k as f64 / 5.0;
            let _ = writeln!(
                s,
                r##"<line x1="{x0}" x2="{x1}" y1="{yy:.1}" y2="{yy:.1}" stroke="#ddd"/><text x="{}" y="{:.1}" text-anchor="end">{f:.1}</text>"##,
                x0 - 4.0,
                y(f) + 4.0,
                yy = y(f)
            );
        }
        let _ = writeln!(
            s,
            r##"<line x1="{x0}" x2="{x1}" y1="{y0}" y2="{y0}" stroke="#000"/><line x1="{x0}" x2="{x0}" y1="{y0}" y2="{y1}" stroke="#000"/>"##
        );
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle">generation</text>"#,
            (x0 + x1) / 2.0,
            ph - 8.0
        );
        let _ = writeln!(
            s,
            r#"<text x="{x0}" y="{}" text-anchor="start">0</text><text x="{x1}" y="{}" text-anchor="end">{}</text>"#,
            y0 + 16.0,
            y0 + 16.0,
            hist.len().saturating_sub(1)
        );
        let mut band = String::new();
        for (g, r) in hist.iter().enumerate() {
            let _ = write!(band, "{:.1},{:.1} ", x(g), y(r.stats.max));
        }
        for (g, r) in hist.iter().enumerate().rev() {
            let _ = write!(band, "{:.1},{:.1} ", x(g), y(r.stats.min));
        }
        let _ = writeln!(
            s,
            r##"<polygon points="{band}" fill="#9ecae1" fill-opacity="0.4" stroke="none"/>"##
        );
        for (series, colour, pick) in [("best", "#d62728", 0usize), ("mean", "#1f77b4", 1)] {
            let pts: String = hist
                .iter()
                .enumerate()
                .map(|(g, r)| {
                    format!(
                        "{:.1},{:.1} ",
                        x(g),
                        y(if pick == 0 {
                            r.stats.best
                        } else {
                            r.stats.mean
                        })
                    )
                })
                .collect();
            let _ = writeln!(
                s,
                r#"<polyline points="{pts}" fill="none" stroke="{colour}" stroke-width="1.8"/>"#
            );
            let ly = y1 + 14.0 + 16.0 * pick as f64;
            let _ = writeln!(
                s,
                r#"<line x1="{}" x2="{}" y1="{ly}" y2="{ly}" stroke="{colour}" stroke-width="2"/><text x="{}" y="{}">{series} F</text>"#,
                x0 + 10.0,
                x0 + 30.0,
                x0 + 35.0,
                ly + 4.0
            );
        }
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}">min–max band</text>"#,
            x0 + 35.0,
            y1 + 50.0
        );
    }
    s.push_str("</svg>\n");
    s
}

/// Rooms drawn to scale side by side, each with a path, the home pose and the end point.
pub fn trajectories_svg(title: &str, rooms: &[(&Room, &Trajectory)]) -> String {
    let scale = 0.3; // px per mm
    let pad = 20.0;
    let mut x_off = pad;
    let mut parts = String::new();
    let mut max_h: f64 = 0.0;
    for (room, tr) in rooms {
        let (lo, hi) = room.bounds();
        let (w, h) = ((hi.x - lo.x) * scale, (hi.y - lo.y) * scale);
        max_h = max_h.max(h);
        let tx = |x: f64| x_off + (x - lo.x) * scale;
        // y up in the room, down in SVG.
        let ty = |y: f64| 40.0 + (hi.y - y) * scale;
        let poly = |pts: &[fuzzymotiv::geom::Vec2]| {
            pts.iter()
                .map(|p| format!("{:.1},{:.1}", tx(p.x), ty(p.y)))
                .collect::<Vec<_>>()
                .join(" ")
        };
        let _ = writeln!(
            parts,
            r##"<polygon points="{}" fill="#fafafa" stroke="#222" stroke-width="2"/>"##,
            poly(&room.outline)
        );
        for o in &room.obstacles {
            let _ = writeln!(
                parts,
                r##"<polygon points="{}" fill="#888" stroke="#222"/>"##,
                poly(o)
            );
        }
        let path: String = tr
            .poses
            .iter()
            .map(|p| format!("{:.1},{:.1} ", tx(p.x), ty(p.y)))
            .collect();
        let _ = writeln!(
            parts,
            r##"<polyline points="{path}" fill="none" stroke="#d62728" stroke-width="1.2"/>"##
        );
        let home = room.home;
        let r = 27.5 * scale;
        let _ = writeln!(
            parts,
            r##"<circle cx="{:.1}" cy="{:.1}" r="{r:.1}" fill="none" stroke="#2ca02c" stroke-width="2"/><line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#2ca02c" stroke-width="2"/>"##,
            tx(home.x),
            ty(home.y),
            tx(home.x),
            ty(home.y),
            tx(home.x + 2.0 * 27.5 * home.heading.cos()),
            ty(home.y + 2.0 * 27.5 * home.heading.sin())
        );
        if let Some(end) = tr.poses.last() {
            let _ = writeln!(
                parts,
                r##"<circle cx="{:.1}" cy="{:.1}" r="{r:.1}" fill="#d62728" fill-opacity="0.5"/>"##,
                tx(end.x),
                ty(end.y)
            );
        }
        let _ = writeln!(
            parts,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
            x_off + w / 2.0,
            40.0 + h + 16.0,
            esc(&room.name)
        );
        x_off += w + pad;
    }
    let width = x_off;
    let height = 40.0 + max_h + 50.0;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(
        s,
        r#"<rect width="{width:.0}" height="{height:.0}" fill="white"/>"#
    );
    let _ = writeln!(
        s,
        r#"<text x="{pad}" y="22" font-weight="bold">{}</text>"#,
        esc(title)
    );
    let _ = writeln!(
        s,
        r##"<text x="{:.0}" y="{:.0}" fill="#555">green: home pose; red: path of the best robot, filled circle: where it ended; 1 px = {:.1} mm</text>"##,
        pad,
        height - 12.0,
        1.0 / scale
    );
    s.push_str(&parts);
    s.push_str("</svg>\n");
    s
}

/// One sweep setting with its mean outcomes over rooms and replicates.
pub struct SettingPoint {
    /// The setting's key.
    pub label: String,
    /// Its motivations (C, H, O, E).
    pub motivations: [f64; 4],
    /// Mean exploration %, recognition %, battery %, homing % (None when not measured).
    pub values: [Option<f64>; 4],
}

/// A colour for a value in [0, 100]: dark blue → teal → yellow.
fn colour(v: f64) -> String {
    let t = (v / 100.0).clamp(0.0, 1.0);
    let stops = [
        (68.0, 1.0, 84.0),
        (33.0, 145.0, 140.0),
        (253.0, 231.0, 37.0),
    ];
    let (a, b, u) = if t < 0.5 {
        (stops[0], stops[1], t * 2.0)
    } else {
        (stops[1], stops[2], (t - 0.5) * 2.0)
    };
    let mix = |x: f64, y: f64| (x + (y - x) * u).round() as u8;
    format!(
        "#{:02x}{:02x}{:02x}",
        mix(a.0, b.0),
        mix(a.1, b.1),
        mix(a.2, b.2)
    )
}

/// How each motivation shapes the outcomes: one panel per outcome. Many settings are drawn as
/// points on the (C, H, E) simplex coloured by the outcome; a few as labelled bars.
pub fn sweep_summary_svg(points: &[SettingPoint]) -> String {
    const OUTCOMES: [&str; 4] = [
        "% optimal exploration",
        "% recognition",
        "% battery usage",
        "% homing",
    ];
    let ternary = points.len() >= 6;
    let (pw, ph) = if ternary {
        (330.0, 330.0)
    } else {
        (330.0, 60.0 + 22.0 * points.len() as f64)
    };
    let width = pw * 4.0;
    let height = ph + 40.0;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="11">"#
    );
    let _ = writeln!(
        s,
        r#"<rect width="{width}" height="{height}" fill="white"/>"#
    );
    for (k, name) in OUTCOMES.iter().enumerate() {
        let ox = k as f64 * pw;
        let _ = writeln!(
            s,
            r#"<text x="{}" y="18" text-anchor="middle" font-weight="bold" font-size="13">{name}</text>"#,
            ox + pw / 2.0
        );
        if ternary {
            let side = pw - 70.0;
            let (x0, y0) = (ox + 35.0, 40.0 + side * 0.866);
            let corner = |c: f64, h: f64, e: f64| {
                let sum = c + h + e;
                let (h, e) = if sum > 0.0 {
                    (h / sum, e / sum)
                } else {
                    (0.0, 0.0)
                };
                (x0 + side * (h + 0.5 * e), y0 - side * 0.866 * e)
            };
            let (a, b, c) = (
                corner(1.0, 0.0, 0.0),
                corner(0.0, 1.0, 0.0),
                corner(0.0, 0.0, 1.0),
            );
            let _ = writeln!(
                s,
                r##"<polygon points="{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}" fill="none" stroke="#444"/><text x="{:.1}" y="{:.1}" text-anchor="end">C=1</text><text x="{:.1}" y="{:.1}">H=1</text><text x="{:.1}" y="{:.1}" text-anchor="middle">E=1</text>"##,
                a.0,
                a.1,
                b.0,
                b.1,
                c.0,
                c.1,
                a.0 - 4.0,
                a.1 + 12.0,
                b.0 + 4.0,
                b.1 + 12.0,
                c.0,
                c.1 - 6.0
            );
            for p in points {
                let m = p.motivations;
                let (x, y) = corner(m[0], m[1], m[3]);
                match p.values[k] {
                    Some(v) => {
                        let _ = writeln!(
                            s,
                            r##"<circle cx="{x:.1}" cy="{y:.1}" r="7" fill="{}" stroke="#333" stroke-width="0.5"><title>{}: {v:.1}</title></circle>"##,
                            colour(v),
                            esc(&p.label)
                        );
                    }
                    None => {
                        let _ = writeln!(
                            s,
                            r##"<circle cx="{x:.1}" cy="{y:.1}" r="3" fill="#ccc"/>"##
                        );
                    }
                }
            }
            // Colour key.
            for i in 0..=10 {
                let v = i as f64 * 10.0;
                let _ = writeln!(
                    s,
                    r#"<rect x="{:.1}" y="{:.1}" width="20" height="6" fill="{}"/>"#,
                    ox + 40.0 + 22.0 * i as f64,
                    height - 26.0,
                    colour(v)
                );
            }
            let _ = writeln!(
                s,
                r#"<text x="{:.1}" y="{:.1}">0</text><text x="{:.1}" y="{:.1}">100</text>"#,
                ox + 40.0,
                height - 8.0,
                ox + 250.0,
                height - 8.0
            );
        } else {
            for (i, p) in points.iter().enumerate() {
                let y = 40.0 + 22.0 * i as f64;
                let m = p.motivations;
                let _ = writeln!(
                    s,
                    r#"<text x="{:.1}" y="{:.1}">({},{},{},{})</text>"#,
                    ox + 8.0,
                    y + 12.0,
                    m[0],
                    m[1],
                    m[2],
                    m[3]
                );
                if let Some(v) = p.values[k] {
                    let w = 160.0 * (v / 100.0).clamp(0.0, 1.0);
                    let _ = writeln!(
                        s,
                        r##"<rect x="{:.1}" y="{y:.1}" width="{w:.1}" height="15" fill="{}"/><text x="{:.1}" y="{:.1}">{v:.1}</text>"##,
                        ox + 130.0,
                        colour(v),
                        ox + 134.0 + w,
                        y + 12.0
                    );
                }
            }
        }
    }
    let _ = writeln!(
        s,
        r##"<text x="8" y="{:.0}" fill="#555">Means over rooms and replicates per motivation setting (C, H, O, E).</text>"##,
        height - 2.0
    );
    s.push_str("</svg>\n");
    s
}
