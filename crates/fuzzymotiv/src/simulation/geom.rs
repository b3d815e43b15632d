//! Plane geometry in millimetres: points, wall segments, rays and polygons.
//!
//! ```
//! use fuzzymotiv::simulation::{Segment, Vec2};
//! // A wall from (10, -5) to (10, 5); a ray from the origin along +x hits it at t = 10.
//! let wall = Segment::new(Vec2::new(10.0, -5.0), Vec2::new(10.0, 5.0));
//! assert_eq!(wall.ray_hit(Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0)), Some(10.0));
//! ```

use serde::{Deserialize, Serialize};

/// A point or vector in the plane (mm).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Vec2 {
    /// x coordinate (mm).
    pub x: f64,
    /// y coordinate (mm).
    pub y: f64,
}

impl Vec2 {
    /// The point (x, y).
    pub const fn new(x: f64, y: f64) -> Self {
        Self { x, y }
    }
    /// The unit vector at angle `theta` (rad) from +x (the project's own sin/cos: ≤ 1 ulp for
    /// `|theta| ≤ 10⁶`, see `simulation/math.rs`).
    #[inline]
    pub fn from_angle(theta: f64) -> Self {
        let (s, c) = crate::simulation::math::sin_cos(theta);
        Self::new(c, s)
    }
    /// Dot product.
    #[inline]
    pub fn dot(self, o: Self) -> f64 {
        self.x * o.x + self.y * o.y
    }
    /// z component of the cross product.
    #[inline]
    pub fn cross(self, o: Self) -> f64 {
        self.x * o.y - self.y * o.x
    }
    /// Euclidean length.
    #[inline]
    pub fn norm(self) -> f64 {
        self.x.hypot(self.y)
    }
    /// Distance to another point.
    #[inline]
    pub fn dist(self, o: Self) -> f64 {
        (self - o).norm()
    }
    /// This vector rotated by `theta` (rad), counter-clockwise.
    #[inline]
    pub fn rotate(self, theta: f64) -> Self {
        let (s, c) = crate::simulation::math::sin_cos(theta);
        self.rotate_by(s, c)
    }
    /// This vector rotated by the angle whose sine is `s` and cosine `c`.
    #[inline]
    pub fn rotate_by(self, s: f64, c: f64) -> Self {
        Self::new(c * self.x - s * self.y, s * self.x + c * self.y)
    }
    /// Whether both coordinates are finite.
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }
}

impl std::ops::Add for Vec2 {
    type Output = Vec2;
    #[inline]
    fn add(self, o: Vec2) -> Vec2 {
        Vec2::new(self.x + o.x, self.y + o.y)
    }
}
impl std::ops::Sub for Vec2 {
    type Output = Vec2;
    #[inline]
    fn sub(self, o: Vec2) -> Vec2 {
        Vec2::new(self.x - o.x, self.y - o.y)
    }
}
impl std::ops::Mul<f64> for Vec2 {
    type Output = Vec2;
    #[inline]
    fn mul(self, k: f64) -> Vec2 {
        Vec2::new(self.x * k, self.y * k)
    }
}

/// A wall: the straight segment from `a` to `b` (mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Segment {
    /// Start point.
    pub a: Vec2,
    /// End point.
    pub b: Vec2,
}

impl Segment {
    /// The segment from `a` to `b`.
    pub const fn new(a: Vec2, b: Vec2) -> Self {
        Self { a, b }
    }

    /// Length (mm).
    pub fn length(&self) -> f64 {
        self.a.dist(self.b)
    }

    /// Squared distance from `p` to the nearest point of the segment.
    ///
    /// ```
    /// use fuzzymotiv::simulation::{Segment, Vec2};
    /// let s = Segment::new(Vec2::new(0.0, 0.0), Vec2::new(10.0, 0.0));
    /// assert_eq!(s.dist2_to(Vec2::new(5.0, 3.0)), 9.0);   // above the middle
    /// assert_eq!(s.dist2_to(Vec2::new(13.0, 4.0)), 25.0); // beyond the end: 3-4-5
    /// ```
    #[inline]
    pub fn dist2_to(&self, p: Vec2) -> f64 {
        let d = self.b - self.a;
        let len2 = d.dot(d);
        let t = if len2 > 0.0 {
            ((p - self.a).dot(d) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = self.a + d * t;
        let e = p - q;
        e.dot(e)
    }

    /// Distance from `p` to the segment.
    pub fn dist_to(&self, p: Vec2) -> f64 {
        self.dist2_to(p).sqrt()
    }

    /// Distance `t >= 0` along the ray `origin + t·dir` (`dir` a unit vector) to this segment,
    /// or `None` when the ray misses it (parallel rays never hit).
    #[inline]
    pub fn ray_hit(&self, origin: Vec2, dir: Vec2) -> Option<f64> {
        let e = self.b - self.a;
        let denom = dir.cross(e);
        if denom == 0.0 {
            return None;
        }
        let w = self.a - origin;
        let t_num = w.cross(e);
        let u_num = w.cross(dir);
        // t = t_num / denom ≥ 0 and u = u_num / denom ∈ [0, 1], tested without dividing.
        let hit = if denom > 0.0 {
            t_num >= 0.0 && u_num >= 0.0 && u_num <= denom
        } else {
            t_num <= 0.0 && u_num <= 0.0 && u_num >= denom
        };
        if hit { Some(t_num / denom) } else { None }
    }

    /// Whether this segment properly or improperly intersects `other`.
    pub fn intersects(&self, other: &Segment) -> bool {
        let o1 = orient(self.a, self.b, other.a);
        let o2 = orient(self.a, self.b, other.b);
        let o3 = orient(other.a, other.b, self.a);
        let o4 = orient(other.a, other.b, self.b);
        if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
            return true;
        }
        (o1 == 0.0 && on_segment(self.a, self.b, other.a))
            || (o2 == 0.0 && on_segment(self.a, self.b, other.b))
            || (o3 == 0.0 && on_segment(other.a, other.b, self.a))
            || (o4 == 0.0 && on_segment(other.a, other.b, self.b))
    }

    /// Distance between two segments (0 when they touch or cross).
    ///
    /// ```
    /// use fuzzymotiv::simulation::{Segment, Vec2};
    /// let a = Segment::new(Vec2::new(0.0, 0.0), Vec2::new(10.0, 0.0));
    /// let b = Segment::new(Vec2::new(5.0, 3.0), Vec2::new(5.0, 9.0));
    /// assert_eq!(a.dist_to_segment(&b), 3.0);
    /// ```
    pub fn dist_to_segment(&self, other: &Segment) -> f64 {
        if self.intersects(other) {
            return 0.0;
        }
        self.dist2_to(other.a)
            .min(self.dist2_to(other.b))
            .min(other.dist2_to(self.a))
            .min(other.dist2_to(self.b))
            .sqrt()
    }

    /// Axis-aligned bounding box `(min, max)`.
    pub fn bounds(&self) -> (Vec2, Vec2) {
        (
            Vec2::new(self.a.x.min(self.b.x), self.a.y.min(self.b.y)),
            Vec2::new(self.a.x.max(self.b.x), self.a.y.max(self.b.y)),
        )
    }
}

/// A wall prepared for fast distance tests: its start, direction and the reciprocal of its
/// squared length, so that a test needs no division.
///
/// [`PreparedSegment::dist2_to`] multiplies by the stored reciprocal where
/// [`Segment::dist2_to`] divides, so the two can differ in the last bits (the projection
/// parameter by at most 1 ulp, the squared distance by a few ulps of `|b − a|·|p − a|`):
/// use it for culling tests that keep a margin far above that (the arena's margins are
/// 10⁻⁶ mm against rounding errors near 10⁻¹³ mm), never for the collision decision itself.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PreparedSegment {
    a: Vec2,
    d: Vec2,
    inv_len2: f64,
}

impl PreparedSegment {
    /// Prepares `s` (a zero-length segment gets reciprocal 0: the distance to its point).
    pub fn new(s: &Segment) -> Self {
        let d = s.b - s.a;
        let len2 = d.dot(d);
        Self {
            a: s.a,
            d,
            inv_len2: if len2 > 0.0 { 1.0 / len2 } else { 0.0 },
        }
    }

    /// Squared distance from `p` to the segment, without a division (see the type's note on
    /// rounding).
    ///
    /// ```
    /// use fuzzymotiv::simulation::{PreparedSegment, Segment, Vec2};
    /// let s = PreparedSegment::new(&Segment::new(Vec2::new(0.0, 0.0), Vec2::new(10.0, 0.0)));
    /// assert_eq!(s.dist2_to(Vec2::new(5.0, 3.0)), 9.0);
    /// assert_eq!(s.dist2_to(Vec2::new(13.0, 4.0)), 25.0);
    /// ```
    #[inline]
    pub fn dist2_to(&self, p: Vec2) -> f64 {
        let w = p - self.a;
        let t = (w.dot(self.d) * self.inv_len2).clamp(0.0, 1.0);
        let e = w - self.d * t;
        e.dot(e)
    }

    /// The wall's start, its direction `b − a` and the reciprocal of its squared length (0 for
    /// a point), for casts that redo [`PreparedSegment::dist2_to`] and
    /// [`PreparedSegment::lower_ray_hits`] in vector lanes.
    #[inline]
    pub(crate) fn parts(&self) -> (Vec2, Vec2, f64) {
        (self.a, self.d, self.inv_len2)
    }

    /// Lowers each `nearest[r]` to the distance at which the ray from `origin` along `dirs[r]`
    /// hits this wall, when it does. The same arithmetic, bit for bit, as
    /// [`Segment::ray_hit`]; the part that does not depend on the direction (`a − origin` and
    /// the numerator of `t`) is computed once for all the rays.
    ///
    /// ```
    /// use fuzzymotiv::simulation::{PreparedSegment, Segment, Vec2};
    /// let wall = PreparedSegment::new(&Segment::new(Vec2::new(10.0, -5.0), Vec2::new(10.0, 5.0)));
    /// let mut nearest = [f64::INFINITY; 2];
    /// wall.lower_ray_hits(Vec2::new(0.0, 0.0), &[Vec2::new(1.0, 0.0), Vec2::new(-1.0, 0.0)], &mut nearest);
    /// assert_eq!(nearest, [10.0, f64::INFINITY]);
    /// ```
    #[inline]
    pub fn lower_ray_hits(&self, origin: Vec2, dirs: &[Vec2], nearest: &mut [f64]) {
        let e = self.d;
        let w = self.a - origin;
        let t_num = w.cross(e);
        for (&dir, best) in dirs.iter().zip(nearest) {
            let denom = dir.cross(e);
            if denom == 0.0 {
                continue;
            }
            let u_num = w.cross(dir);
            let hit = if denom > 0.0 {
                t_num >= 0.0 && u_num >= 0.0 && u_num <= denom
            } else {
                t_num <= 0.0 && u_num <= 0.0 && u_num >= denom
            };
            if hit {
                *best = best.min(t_num / denom);
            }
        }
    }
}

fn orient(a: Vec2, b: Vec2, c: Vec2) -> f64 {
    (b - a).cross(c - a)
}

fn on_segment(a: Vec2, b: Vec2, p: Vec2) -> bool {
    p.x >= a.x.min(b.x) && p.x <= a.x.max(b.x) && p.y >= a.y.min(b.y) && p.y <= a.y.max(b.y)
}

/// Signed area of a closed polygon (mm²): positive when counter-clockwise.
///
/// ```
/// use fuzzymotiv::simulation::{signed_area, Vec2};
/// let square = [Vec2::new(0.0, 0.0), Vec2::new(2.0, 0.0), Vec2::new(2.0, 2.0), Vec2::new(0.0, 2.0)];
/// assert_eq!(signed_area(&square), 4.0);
/// ```
pub fn signed_area(poly: &[Vec2]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| poly[i].cross(poly[(i + 1) % n]))
        .sum::<f64>()
        / 2.0
}

/// Perimeter of a closed polygon (mm).
pub fn perimeter(poly: &[Vec2]) -> f64 {
    let n = poly.len();
    (0..n).map(|i| poly[i].dist(poly[(i + 1) % n])).sum()
}

/// The edges of a closed polygon, last point joined to the first.
pub fn edges(poly: &[Vec2]) -> impl Iterator<Item = Segment> + '_ {
    let n = poly.len();
    (0..n).map(move |i| Segment::new(poly[i], poly[(i + 1) % n]))
}

/// Whether `p` lies strictly inside the closed polygon (even–odd rule; points on an edge may go
/// either way).
pub fn point_in_polygon(poly: &[Vec2], p: Vec2) -> bool {
    let n = poly.len();
    let mut inside = false;
    let mut j = n.wrapping_sub(1);
    for i in 0..n {
        let (a, b) = (poly[i], poly[j]);
        if (a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x {
            inside = !inside;
        }
        j = i;
    }
    inside
}

/// The first pair of non-adjacent edges (by index) that intersect, if the polygon is not simple.
pub fn self_intersection(poly: &[Vec2]) -> Option<(usize, usize)> {
    let n = poly.len();
    let segs: Vec<Segment> = edges(poly).collect();
    for i in 0..n {
        for j in (i + 1)..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            if adjacent {
                // Adjacent edges share a vertex; they only "intersect" if they fold back.
                let (s, t) = (segs[i], segs[j]);
                let shared = if j == i + 1 { s.b } else { s.a };
                let (p, q) = if j == i + 1 { (s.a, t.b) } else { (s.b, t.a) };
                let folded = orient(p, shared, q) == 0.0 && (p - shared).dot(q - shared) > 0.0;
                if folded && n > 3 {
                    return Some((i, j));
                }
                continue;
            }
            if segs[i].intersects(&segs[j]) {
                return Some((i, j));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_hits_wall_at_hand_computed_distances() {
        let wall = Segment::new(Vec2::new(10.0, -5.0), Vec2::new(10.0, 5.0));
        assert_eq!(
            wall.ray_hit(Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0)),
            Some(10.0)
        );
        // 45° ray from origin hits x = 10 at y = 10: outside the wall (|y| <= 5).
        let d = Vec2::from_angle(std::f64::consts::FRAC_PI_4);
        assert_eq!(wall.ray_hit(Vec2::new(0.0, 0.0), d), None);
        // From (0, 0) at 26.565° (slope 1/2) it hits at (10, 5): t = sqrt(125).
        let d = Vec2::new(2.0, 1.0) * (1.0 / 5f64.sqrt());
        let t = wall.ray_hit(Vec2::new(0.0, 0.0), d).unwrap();
        assert!((t - 125f64.sqrt()).abs() < 1e-12);
        // Pointing away or parallel: no hit.
        assert_eq!(
            wall.ray_hit(Vec2::new(0.0, 0.0), Vec2::new(-1.0, 0.0)),
            None
        );
        assert_eq!(wall.ray_hit(Vec2::new(0.0, 0.0), Vec2::new(0.0, 1.0)), None);
    }

    #[test]
    fn distance_to_segment() {
        let s = Segment::new(Vec2::new(0.0, 0.0), Vec2::new(10.0, 0.0));
        assert_eq!(s.dist_to(Vec2::new(-3.0, -4.0)), 5.0);
        assert_eq!(s.dist_to(Vec2::new(7.0, -2.0)), 2.0);
        let degenerate = Segment::new(Vec2::new(1.0, 1.0), Vec2::new(1.0, 1.0));
        assert_eq!(degenerate.dist_to(Vec2::new(4.0, 5.0)), 5.0);
    }

    /// Walls of every kind for the prepared-segment tests: axis-aligned, oblique, a point.
    const TEST_WALLS: [Segment; 4] = [
        Segment::new(Vec2::new(0.0, 0.0), Vec2::new(900.0, 0.0)),
        Segment::new(Vec2::new(200.0, 300.0), Vec2::new(700.0, 300.0)),
        Segment::new(Vec2::new(13.7, 451.2), Vec2::new(388.1, 97.3)),
        Segment::new(Vec2::new(5.0, 5.0), Vec2::new(5.0, 5.0)),
    ];

    #[test]
    fn prepared_ray_hits_equal_ray_hit_bit_for_bit() {
        for w in &TEST_WALLS {
            let pw = PreparedSegment::new(w);
            for i in 0..3000 {
                let o = Vec2::new((i * 37 % 1000) as f64 * 0.93, (i * 53 % 700) as f64 * 0.71);
                let dirs = [0.0, 1.3, 2.9].map(|a: f64| Vec2::from_angle(a + i as f64 * 0.1));
                let mut nearest = [f64::INFINITY; 3];
                pw.lower_ray_hits(o, &dirs, &mut nearest);
                for (d, got) in dirs.iter().zip(nearest) {
                    let want = w.ray_hit(o, *d).unwrap_or(f64::INFINITY);
                    assert_eq!(got.to_bits(), want.to_bits(), "{w:?} {o:?} {d:?}");
                }
            }
        }
    }

    #[test]
    fn prepared_distance_matches_the_dividing_one() {
        for w in &TEST_WALLS {
            let pw = PreparedSegment::new(w);
            for i in 0..2000 {
                let p = Vec2::new(
                    (i * 37 % 1000) as f64 * 0.913,
                    (i * 91 % 1000) as f64 * 0.77,
                );
                let (exact, fast) = (w.dist2_to(p), pw.dist2_to(p));
                // Well inside the arena's 1e-6 mm margins (distances up to ~1.3 m).
                assert!((exact.sqrt() - fast.sqrt()).abs() < 1e-9, "{w:?} {p:?}");
            }
        }
    }

    #[test]
    fn polygons() {
        let l = [
            (0., 0.),
            (800., 0.),
            (800., 300.),
            (300., 300.),
            (300., 800.),
            (0., 800.),
        ]
        .map(|(x, y)| Vec2::new(x, y));
        assert_eq!(signed_area(&l), 800.0 * 300.0 + 300.0 * 500.0);
        assert_eq!(perimeter(&l), 3200.0);
        assert!(point_in_polygon(&l, Vec2::new(100.0, 700.0)));
        assert!(!point_in_polygon(&l, Vec2::new(500.0, 500.0)));
        assert_eq!(self_intersection(&l), None);
        let bowtie = [(0., 0.), (10., 10.), (10., 0.), (0., 10.)].map(|(x, y)| Vec2::new(x, y));
        assert!(self_intersection(&bowtie).is_some());
    }

    #[test]
    fn rotation() {
        let v = Vec2::new(1.0, 0.0).rotate(std::f64::consts::FRAC_PI_2);
        assert!(v.x.abs() < 1e-15 && (v.y - 1.0).abs() < 1e-15);
    }
}
