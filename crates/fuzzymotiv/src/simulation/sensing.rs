//! What the IR sensors read: their rays turned to the robot's heading and cast against
//! the walls near it.
//!
//! [`Eyes`] holds the sensors' rays in the body frame and, for `actions` motion, already turned
//! to each of the twelve headings of the [`Compass`] (the same products a turn per step would
//! compute, done once). [`Eyes::read`] casts them: a wall farther from a sensor than its
//! longest ray cannot change the sensor's value, so it is skipped; the others are tested
//! against every ray of the sensor at once ([`PreparedSegment::lower_ray_hits`]). On the
//! compass with three rays a sensor, on processors with AVX2, four sensors are cast together in
//! vector lanes ([`Eyes::cast_avx2`]), with the same bits. A robot has up to
//! [`crate::simulation::MAX_SENSORS`]
//! sensors; the arrays hold that many, and only the robot's first `n` are read.

use crate::simulation::geom::{PreparedSegment, Vec2};
use crate::simulation::isa::Isa;
use crate::simulation::robot::Compass;
use crate::simulation::robot_spec::RobotSpec;
use crate::simulation::sensor::MAX_SENSORS as INPUTS;
use crate::simulation::sensor::{RayMount, Readings, SensorModel, ray_count, rays};
#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::__m256d;

/// The sensors' rays turned to one heading: each sensor's origin relative to the body centre
/// and its ray directions, in the world frame.
#[derive(Debug, Clone, Copy)]
pub struct TurnedRays {
    origins: [Vec2; INPUTS],
    dirs: [[Vec2; 3]; INPUTS],
    /// The same numbers sensor by sensor side by side.
    side: SideBySide,
}

/// The sensors' rays side by side, for casting them in vector lanes: `origin[c][s]` is
/// coordinate `c` (x, y) of sensor `s`'s origin, `dir[r][c][s]` of its ray `r`'s direction,
/// for the first `W` sensors (a multiple of 4).
#[derive(Debug, Clone, Copy)]
struct SideBySide<const W: usize = INPUTS> {
    origin: [[f64; W]; 2],
    dir: [[[f64; W]; 2]; 3],
}

/// A robot's sensors with one response model, ready to read.
#[derive(Debug, Clone)]
pub struct Eyes {
    mounts: [[RayMount; 3]; INPUTS],
    /// The robot's number of sensors (the first `n` of the arrays).
    n: usize,
    /// The largest value a sensor reads (the robot's `reading_max`).
    max: f64,
    /// The rays at heading 0 (body frame): origins and unit directions.
    body: TurnedRays,
    /// Rays per sensor (3 with `sampled`, 1 with `linear`).
    per_sensor: usize,
    /// Squared longest ray range, with a 10⁻⁶ mm margin over the rounding of the culling test.
    range2: f64,
    /// The rays turned to each compass heading.
    compass: [TurnedRays; 12],
    /// The instructions this processor runs ([`Eyes::cast_avx2`] needs AVX2).
    isa: Isa,
    /// The built-in sample table each of the three rays of every sensor reads, when all
    /// sensors' rays read them alike (the `sampled` model), for [`Eyes::cast_avx2`].
    tables: Option<[&'static [(f64, f64); 5]; 3]>,
}

impl Eyes {
    /// The sensors of `robot` with `model`, their rays turned to each heading of `compass`.
    pub fn new(model: SensorModel, robot: &RobotSpec, compass: &Compass) -> Eyes {
        let mounts = rays(model, robot);
        let n = robot.sensors();
        let per_sensor = ray_count(model, robot);
        let body = TurnedRays::new(
            mounts.map(|m| m[0].origin),
            mounts.map(|m| m.map(|r| Vec2::from_angle(r.angle))),
        );
        let range = mounts[..n]
            .iter()
            .flat_map(|m| m[..per_sensor].iter())
            .map(|r| r.range())
            .fold(0.0, f64::max)
            + 1e-6;
        Eyes {
            mounts,
            n,
            max: robot.reading_max(),
            body,
            per_sensor,
            range2: range * range,
            compass: std::array::from_fn(|k| body.turned(compass.sin[k], compass.cos[k])),
            isa: Isa::detected(),
            tables: shared_tables(&mounts[..n]),
        }
    }

    /// The rays turned to compass direction `dir` (0..12).
    #[inline]
    pub fn on_compass(&self, dir: usize) -> &TurnedRays {
        &self.compass[dir]
    }

    /// The robot's number of sensors.
    #[inline]
    pub fn count(&self) -> usize {
        self.n
    }

    /// Noise-free sensor values (0 to the robot's `reading_max`) of a robot centred at `pos`
    /// facing `facing`, seeing the walls `near` (indices into `walls`).
    #[inline]
    pub fn read(
        &self,
        pos: Vec2,
        facing: Facing<'_>,
        walls: &[PreparedSegment],
        near: &[u32],
    ) -> Readings {
        match (self.per_sensor, facing) {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: `Isa::Avx2` is only made when the processor has AVX2 (`Isa::detected`).
            (3, _) if self.isa == Isa::Avx2 => unsafe {
                self.read_avx2::<3>(pos, facing, walls, near)
            },
            #[cfg(target_arch = "x86_64")]
            // SAFETY: as above.
            (1, _) if self.isa == Isa::Avx2 => unsafe {
                self.read_avx2::<1>(pos, facing, walls, near)
            },
            (3, _) => self.read_rays::<3>(pos, facing, walls, near),
            _ => self.read_rays::<1>(pos, facing, walls, near),
        }
    }

    /// [`Eyes::read`] with `N` rays per sensor.
    #[inline]
    fn read_rays<const N: usize>(
        &self,
        pos: Vec2,
        facing: Facing<'_>,
        walls: &[PreparedSegment],
        near: &[u32],
    ) -> Readings {
        let mut out = Readings::zeros(self.n);
        for (s, o) in out.iter_mut().enumerate() {
            let origin = pos + facing.origin(&self.body, s);
            let mut nearest = [f64::INFINITY; N];
            // Turned only when a wall is in range (with `Facing::Angle`, most sensors see none).
            let mut dirs = None;
            for &k in near {
                let wall = &walls[k as usize];
                if wall.dist2_to(origin) <= self.range2 {
                    let dirs = dirs.get_or_insert_with(|| facing.dirs(&self.body, s));
                    wall.lower_ray_hits(origin, &dirs[..N], &mut nearest);
                }
            }
            if dirs.is_none() {
                continue; // no wall in range: the sensor reads 0
            }
            *o = self.sensor_value(s, nearest);
        }
        out
    }

    /// Sensor `s`'s value from its rays' nearest hits `hits` (∞ for none): the rays' values
    /// added in order from 0, at most the robot's `reading_max`.
    #[inline]
    fn sensor_value(&self, s: usize, hits: impl IntoIterator<Item = f64>) -> f64 {
        let mut total = 0.0;
        for (ray, d) in self.mounts[s].iter().zip(hits) {
            total += ray.value(d);
        }
        total.min(self.max)
    }

    /// [`Eyes::read`] with `R` rays a sensor (1 or 3) on a processor with AVX2: a compass
    /// heading's rays as turned in advance, any other turned now
    /// ([`Eyes::cast_turned_avx2`]), cast by [`Eyes::cast_avx2`].
    ///
    /// # Safety
    /// The processor must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn read_avx2<const R: usize>(
        &self,
        pos: Vec2,
        facing: Facing<'_>,
        walls: &[PreparedSegment],
        near: &[u32],
    ) -> Readings {
        // SAFETY (each call): this function runs only on processors with AVX2.
        match facing {
            Facing::Compass(t) if self.n <= 8 => unsafe {
                self.cast_avx2::<8, INPUTS, R>(pos, &t.side, walls, near)
            },
            Facing::Compass(t) => unsafe {
                self.cast_avx2::<INPUTS, INPUTS, R>(pos, &t.side, walls, near)
            },
            Facing::Angle { sin, cos } => unsafe {
                self.cast_turned_avx2::<R>(pos, (sin, cos), walls, near)
            },
        }
    }

    /// [`Eyes::read_rays`] with `R` rays a sensor (1 or 3), `rays` turned in advance, four
    /// sensors at a time in AVX2 vector lanes ([`nearest_hits_avx2`]), the `sampled` model's
    /// built-in values too ([`table_values`]). The same operations on the same numbers, so the
    /// same bits.
    ///
    /// # Safety
    /// The processor must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn cast_avx2<const M: usize, const W: usize, const R: usize>(
        &self,
        pos: Vec2,
        rays: &SideBySide<W>,
        walls: &[PreparedSegment],
        near: &[u32],
    ) -> Readings {
        use std::arch::x86_64::{
            _mm256_add_pd, _mm256_min_pd, _mm256_set1_pd, _mm256_setzero_pd, _mm256_storeu_pd,
        };
        // `M` (8, or all of `INPUTS` for robots with more sensors) holds the robot's sensors.
        const { assert!(M % 4 == 0 && M <= INPUTS, "blocks of four sensors") };
        const { assert!(R == 1 || R == 3, "one or three rays a sensor") };
        debug_assert!(self.n <= M && self.per_sensor == R);
        let mut nearest = [[f64::INFINITY; M]; R];
        // The built-in tables, read in vector lanes, are the three rays' of `sampled`.
        let tables = self.tables.filter(|_| R == 3);
        let mut out = [0.0; M];
        // Blocks of four sensors; a block's sensors past the robot's last have no rays (their
        // directions are 0: no ray meets a wall) and read 0, which is not kept.
        for half in (0..self.n).step_by(4) {
            let best = nearest_hits_avx2::<W, R>(pos, rays, half, self.range2, walls, near);
            // SAFETY: every store is of four consecutive `f64` from `half`, a multiple of 4 below
            // `n` ≤ `M` (a multiple of 4) in arrays of `M`; the unaligned form needs no alignment.
            unsafe {
                let Some(tables) = tables else {
                    for (n, b) in nearest.iter_mut().zip(best) {
                        _mm256_storeu_pd(n[half..].as_mut_ptr(), b);
                    }
                    continue;
                };
                // `read_rays`' sum in its order, from 0, and its minimum.
                let mut total = _mm256_setzero_pd();
                for (b, table) in best.into_iter().zip(tables) {
                    total = _mm256_add_pd(total, table_values(b, table));
                }
                let total = _mm256_min_pd(total, _mm256_set1_pd(self.max));
                _mm256_storeu_pd(out[half..].as_mut_ptr(), total);
            }
        }
        if tables.is_none() {
            return self.values(&nearest);
        }
        let mut readings = Readings::zeros(self.n);
        readings.copy_from_slice(&out[..self.n]);
        readings
    }

    /// [`Eyes::read`] facing any heading (sine and cosine `sin_cos`), in AVX2 lanes: the
    /// rays turned four sensors at a time with [`Vec2::rotate_by`]'s operations (so the same
    /// numbers `Facing::Angle` turns one by one, and that [`Eyes::on_compass`] holds for a
    /// compass heading), then cast by [`Eyes::cast_avx2`]. The same bits as
    /// [`Eyes::read_rays`].
    ///
    /// # Safety
    /// The processor must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn cast_turned_avx2<const R: usize>(
        &self,
        pos: Vec2,
        (sin, cos): (f64, f64),
        walls: &[PreparedSegment],
        near: &[u32],
    ) -> Readings {
        match self.n <= 8 {
            // SAFETY: this function runs only on processors with AVX2.
            true => unsafe { self.cast_turned_in::<8, R>(pos, (sin, cos), walls, near) },
            // SAFETY: as above.
            false => unsafe { self.cast_turned_in::<INPUTS, R>(pos, (sin, cos), walls, near) },
        }
    }

    /// [`Eyes::cast_turned_avx2`] with the rays of the first `W` sensors, at least the
    /// robot's (a multiple of 4).
    ///
    /// # Safety
    /// The processor must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[inline]
    unsafe fn cast_turned_in<const W: usize, const R: usize>(
        &self,
        pos: Vec2,
        (sin, cos): (f64, f64),
        walls: &[PreparedSegment],
        near: &[u32],
    ) -> Readings {
        use std::arch::x86_64::{
            _mm256_add_pd, _mm256_loadu_pd, _mm256_mul_pd, _mm256_set1_pd, _mm256_storeu_pd,
            _mm256_sub_pd,
        };
        const { assert!(W % 4 == 0 && W <= INPUTS, "blocks of four sensors") };
        debug_assert!(self.n <= W);
        let mut side = SideBySide::<W> {
            origin: [[0.0; W]; 2],
            dir: [[[0.0; W]; 2]; 3],
        };
        let (s, c) = (_mm256_set1_pd(sin), _mm256_set1_pd(cos));
        let body = &self.body.side;
        // Blocks of four sensors (past the robot's last: no rays, which stay 0 turned).
        for half in (0..self.n).step_by(4) {
            // SAFETY: every load and store is of four consecutive `f64` from `half`, a multiple
            // of 4 below the robot's sensors ≤ `W` (a multiple of 4); the unaligned forms need no alignment.
            unsafe {
                // `rotate_by`: (c·x − s·y, s·x + c·y), products and sums in its order.
                let turn = |from: &[[f64; INPUTS]; 2], to: &mut [[f64; W]; 2]| {
                    let x = _mm256_loadu_pd(from[0][half..].as_ptr());
                    let y = _mm256_loadu_pd(from[1][half..].as_ptr());
                    let tx = _mm256_sub_pd(_mm256_mul_pd(c, x), _mm256_mul_pd(s, y));
                    let ty = _mm256_add_pd(_mm256_mul_pd(s, x), _mm256_mul_pd(c, y));
                    _mm256_storeu_pd(to[0][half..].as_mut_ptr(), tx);
                    _mm256_storeu_pd(to[1][half..].as_mut_ptr(), ty);
                };
                turn(&body.origin, &mut side.origin);
                for (from, to) in body.dir.iter().zip(&mut side.dir).take(R) {
                    turn(from, to);
                }
            }
        }
        // SAFETY: this function runs only on processors with AVX2.
        unsafe { self.cast_avx2::<W, W, R>(pos, &side, walls, near) }
    }

    /// The sensors' values from their three rays' nearest hits `nearest[r][s]` (∞ for none),
    /// as [`Eyes::read_rays`] adds them ([`Eyes::sensor_value`]); a sensor none of whose rays hits reads +0, which is
    /// also what its three values of 0 add to.
    #[cfg(target_arch = "x86_64")]
    #[inline]
    fn values<const M: usize, const R: usize>(&self, nearest: &[[f64; M]; R]) -> Readings {
        let mut out = Readings::zeros(self.n);
        for (s, o) in out.iter_mut().enumerate() {
            if nearest.iter().all(|n| n[s] == f64::INFINITY) {
                continue;
            }
            *o = self.sensor_value(s, nearest.iter().map(|n| n[s]));
        }
        out
    }
}

/// Which way the robot faces, as [`Eyes::read`] needs it.
#[derive(Debug, Clone, Copy)]
pub enum Facing<'a> {
    /// A compass heading, its rays turned in advance ([`Eyes::on_compass`]).
    Compass(&'a TurnedRays),
    /// Any heading, by its sine and cosine: the rays are turned as they are needed.
    Angle {
        /// Sine of the heading.
        sin: f64,
        /// Cosine of the heading.
        cos: f64,
    },
}

impl Facing<'_> {
    /// Sensor `s`'s origin relative to the body centre, turned to this heading (`body`: the
    /// rays at heading 0).
    #[inline]
    fn origin(self, body: &TurnedRays, s: usize) -> Vec2 {
        match self {
            Facing::Compass(t) => t.origins[s],
            Facing::Angle { sin, cos } => body.origins[s].rotate_by(sin, cos),
        }
    }

    /// Sensor `s`'s ray directions turned to this heading.
    #[inline]
    fn dirs(self, body: &TurnedRays, s: usize) -> [Vec2; 3] {
        match self {
            Facing::Compass(t) => t.dirs[s],
            Facing::Angle { sin, cos } => body.dirs[s].map(|d| d.rotate_by(sin, cos)),
        }
    }
}

/// The nearest hit of each of the `R` rays (1 or 3) of sensors `half` … `half + 3` (∞ for
/// none), for a robot centred at `pos` with the `near` walls: for each wall the four sensors'
/// distance test ([`PreparedSegment::dist2_to`]), then, when one of them is in range, the hits
/// of their `R` rays ([`lower_hits_avx2`]) with those out of range masked off, as [`Eyes::read_rays`] skips
/// them. A ray's nearest hit is the minimum over the walls, whatever their order (its zero may
/// have either sign, which no ray's value tells apart).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn nearest_hits_avx2<const W: usize, const R: usize>(
    pos: Vec2,
    rays: &SideBySide<W>,
    half: usize,
    range2: f64,
    walls: &[PreparedSegment],
    near: &[u32],
) -> [__m256d; R] {
    use std::arch::x86_64::{
        _CMP_LE_OQ, _mm256_add_pd, _mm256_cmp_pd, _mm256_loadu_pd, _mm256_max_pd, _mm256_min_pd,
        _mm256_movemask_pd, _mm256_mul_pd, _mm256_set1_pd, _mm256_setzero_pd, _mm256_sub_pd,
    };
    // SAFETY: every load is of four consecutive `f64` from `half`, a multiple of 4 below
    // the robot's sensors ≤ `W` (a multiple of 4: the callers' blocks); the unaligned form needs no alignment.
    let four = |a: &[f64; W]| unsafe { _mm256_loadu_pd(a[half..].as_ptr()) };
    let o = (
        _mm256_add_pd(_mm256_set1_pd(pos.x), four(&rays.origin[0])),
        _mm256_add_pd(_mm256_set1_pd(pos.y), four(&rays.origin[1])),
    );
    let dirs: [Pair; R] = std::array::from_fn(|r| (four(&rays.dir[r][0]), four(&rays.dir[r][1])));
    let (zero, one) = (_mm256_setzero_pd(), _mm256_set1_pd(1.0));
    let mut best = [_mm256_set1_pd(f64::INFINITY); R];
    for &k in near {
        let (a, d, inv_len2) = walls[k as usize].parts();
        let a = (_mm256_set1_pd(a.x), _mm256_set1_pd(a.y));
        let d = (_mm256_set1_pd(d.x), _mm256_set1_pd(d.y));
        // `dist2_to`: w = p − a, t = (w·d)/|d|² in [0, 1] (`max` then `min` with the operands
        // in the order that keeps a −0 or a NaN, as `clamp`), e = w − d·t.
        let (px, py) = (_mm256_sub_pd(o.0, a.0), _mm256_sub_pd(o.1, a.1));
        let dot = _mm256_add_pd(_mm256_mul_pd(px, d.0), _mm256_mul_pd(py, d.1));
        let t = _mm256_mul_pd(dot, _mm256_set1_pd(inv_len2));
        let t = _mm256_min_pd(one, _mm256_max_pd(zero, t));
        let ex = _mm256_sub_pd(px, _mm256_mul_pd(d.0, t));
        let ey = _mm256_sub_pd(py, _mm256_mul_pd(d.1, t));
        let dist2 = _mm256_add_pd(_mm256_mul_pd(ex, ex), _mm256_mul_pd(ey, ey));
        let seen = _mm256_cmp_pd::<_CMP_LE_OQ>(dist2, _mm256_set1_pd(range2));
        if _mm256_movemask_pd(seen) != 0 {
            lower_hits_avx2(&mut best, o, &dirs, (a, d), seen);
        }
    }
    best
}

/// Lowers each ray's `best` hit, in the lanes `seen`, to where it meets the wall from `a` along
/// `d`, when it does, for sensors at `o` with ray directions `dirs`: [`PreparedSegment::
/// lower_ray_hits`]' operations, w = a − origin, t = (w × d)/(dir × d) ≥ 0 and
/// u = (w × dir)/(dir × d) in [0, 1], tested without dividing.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn lower_hits_avx2<const R: usize>(
    best: &mut [__m256d; R],
    o: Pair,
    dirs: &[Pair; R],
    (a, d): Wall4,
    seen: __m256d,
) {
    use std::arch::x86_64::{
        _CMP_GE_OQ, _CMP_GT_OQ, _CMP_LE_OQ, _CMP_LT_OQ, _mm256_and_pd, _mm256_blendv_pd,
        _mm256_cmp_pd, _mm256_div_pd, _mm256_min_pd, _mm256_mul_pd, _mm256_or_pd,
        _mm256_setzero_pd, _mm256_sub_pd,
    };
    let zero = _mm256_setzero_pd();
    let cross = |u: Pair, v: Pair| _mm256_sub_pd(_mm256_mul_pd(u.0, v.1), _mm256_mul_pd(u.1, v.0));
    let w = (_mm256_sub_pd(a.0, o.0), _mm256_sub_pd(a.1, o.1));
    let t_num = cross(w, d);
    let t_ahead = _mm256_cmp_pd::<_CMP_GE_OQ>(t_num, zero);
    let t_behind = _mm256_cmp_pd::<_CMP_LE_OQ>(t_num, zero);
    for (b, &dir) in best.iter_mut().zip(dirs) {
        let (denom, u) = (cross(dir, d), cross(w, dir));
        let ahead = _mm256_and_pd(
            _mm256_and_pd(_mm256_cmp_pd::<_CMP_GT_OQ>(denom, zero), t_ahead),
            _mm256_and_pd(
                _mm256_cmp_pd::<_CMP_GE_OQ>(u, zero),
                _mm256_cmp_pd::<_CMP_LE_OQ>(u, denom),
            ),
        );
        let behind = _mm256_and_pd(
            _mm256_and_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(denom, zero), t_behind),
            _mm256_and_pd(
                _mm256_cmp_pd::<_CMP_LE_OQ>(u, zero),
                _mm256_cmp_pd::<_CMP_GE_OQ>(u, denom),
            ),
        );
        let hit = _mm256_and_pd(_mm256_or_pd(ahead, behind), seen);
        let q = _mm256_div_pd(t_num, denom);
        *b = _mm256_blendv_pd(*b, _mm256_min_pd(q, *b), hit);
    }
}

/// Four lanes of x and y.
#[cfg(target_arch = "x86_64")]
type Pair = (__m256d, __m256d);

/// A wall's start and direction, each coordinate in all four lanes.
#[cfg(target_arch = "x86_64")]
type Wall4 = (Pair, Pair);

/// The sample table each ray `r` of every sensor reads, when each reads a built-in one and all
/// sensors alike.
fn shared_tables(mounts: &[[RayMount; 3]]) -> Option<[&'static [(f64, f64); 5]; 3]> {
    let tables = [0, 1, 2].map(|r| mounts[0][r].builtin_table());
    let alike = mounts
        .iter()
        .all(|m| (0..3).all(|r| m[r].builtin_table() == tables[r]));
    match tables {
        [Some(a), Some(b), Some(c)] if alike => Some([a, b, c]),
        _ => None,
    }
}

/// [`RayMount::value`] of each lane's distance `d` for a ray reading `table`: the value of the
/// first sample at or beyond it, 0 beyond the last (and for ∞), chosen from the last sample to
/// the first. (Like the other AVX2 helpers here, safe to call only from code compiled for AVX2,
/// which the compiler checks.)
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn table_values(d: __m256d, table: &[(f64, f64); 5]) -> __m256d {
    use std::arch::x86_64::{
        _CMP_LE_OQ, _mm256_blendv_pd, _mm256_cmp_pd, _mm256_set1_pd, _mm256_setzero_pd,
    };
    let mut value = _mm256_setzero_pd();
    for &(s, v) in table.iter().rev() {
        let within = _mm256_cmp_pd::<_CMP_LE_OQ>(d, _mm256_set1_pd(s));
        value = _mm256_blendv_pd(value, _mm256_set1_pd(v), within);
    }
    value
}

impl TurnedRays {
    /// The rays with sensor origins `origins` and directions `dirs`.
    fn new(origins: [Vec2; INPUTS], dirs: [[Vec2; 3]; INPUTS]) -> TurnedRays {
        let side = SideBySide {
            origin: [origins.map(|o| o.x), origins.map(|o| o.y)],
            dir: std::array::from_fn(|r| [dirs.map(|d| d[r].x), dirs.map(|d| d[r].y)]),
        };
        TurnedRays {
            origins,
            dirs,
            side,
        }
    }

    /// These rays turned by the rotation with sine `s` and cosine `c`.
    fn turned(&self, s: f64, c: f64) -> TurnedRays {
        TurnedRays::new(
            self.origins.map(|v| v.rotate_by(s, c)),
            self.dirs.map(|d| d.map(|v| v.rotate_by(s, c))),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulation::geom::Segment;

    /// The compass table holds exactly the products a per-step turn computes.
    #[test]
    fn compass_rays_equal_rays_turned_per_step() {
        let compass = Compass::new(0.3);
        let eyes = Eyes::new(SensorModel::Sampled, RobotSpec::khepera(), &compass);
        for k in 0..12 {
            let (sin, cos) = (compass.sin[k], compass.cos[k]);
            let (fresh, table) = (
                Facing::Angle { sin, cos },
                Facing::Compass(eyes.on_compass(k)),
            );
            for s in 0..eyes.n {
                assert_eq!(fresh.origin(&eyes.body, s), table.origin(&eyes.body, s));
                assert_eq!(fresh.dirs(&eyes.body, s), table.dirs(&eyes.body, s));
            }
        }
    }

    /// The AVX2 cast reads, bit for bit, what the scalar one reads: every room's walls, listed
    /// in order, backwards and a few at a time, from poses in and around the rooms (on walls,
    /// at corners, outside), on all twelve headings, with the built-in sensors and a sensor
    /// table's.
    #[test]
    fn vector_cast_reads_what_the_scalar_cast_reads() {
        use crate::simulation::room::{BUILTIN_ROOMS, Room};
        use crate::simulation::sensor::TableRef;
        use crate::simulation::sensor_table::SensorTable;
        if Isa::detected() == Isa::Baseline {
            return; // nothing to compare
        }
        let table = SensorModel::Table(TableRef(SensorTable::khepera().intern()));
        let mut lit = 0;
        for model in [SensorModel::Sampled, table] {
            let compass = Compass::new(0.7);
            let eyes = Eyes::new(model, RobotSpec::khepera(), &compass);
            assert_eq!(eyes.per_sensor, 3);
            for name in BUILTIN_ROOMS {
                let room = Room::builtin(name).unwrap();
                let walls: Vec<_> = room.walls().iter().map(PreparedSegment::new).collect();
                let all: Vec<u32> = (0..walls.len() as u32).collect();
                let backwards: Vec<u32> = all.iter().rev().copied().collect();
                let (lo, hi) = room.bounds();
                for i in 0..1500 {
                    let f = |n: usize, m: usize| (i * n % m) as f64 / m as f64;
                    let mut pos = Vec2::new(
                        lo.x - 60.0 + (hi.x - lo.x + 120.0) * f(37, 997),
                        lo.y - 60.0 + (hi.y - lo.y + 120.0) * f(53, 991),
                    );
                    if i % 5 == 0 {
                        pos = walls[i % walls.len()].parts().0; // on a wall's end
                    }
                    let dir = i % 12;
                    let facing = Facing::Compass(eyes.on_compass(dir));
                    let few = &all[i % all.len()..(i % all.len() + 3).min(all.len())];
                    for near in [&all[..], &backwards[..], few] {
                        let scalar = eyes.read_rays::<3>(pos, facing, &walls, near);
                        let vector = eyes.read(pos, facing, &walls, near);
                        let bits = |r: &Readings| r.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                        assert_eq!(bits(&scalar), bits(&vector));
                        lit += scalar.iter().filter(|&&v| v > 0.0).count();
                    }
                }
            }
        }
        assert!(
            lit > 10_000,
            "{lit}: too few sensors saw a wall to test anything"
        );
    }

    /// Facing any heading, the AVX2 cast (its rays turned in vector lanes) reads, bit for
    /// bit, what the scalar cast reads with the rays turned one by one: every room's walls,
    /// from poses in and around the rooms, on headings all round (the compass's among them).
    #[test]
    fn vector_cast_at_any_heading_reads_what_the_scalar_cast_reads() {
        use crate::simulation::room::{BUILTIN_ROOMS, Room};
        if Isa::detected() == Isa::Baseline {
            return; // nothing to compare
        }
        let eyes = Eyes::new(
            SensorModel::Sampled,
            RobotSpec::khepera(),
            &Compass::new(0.0),
        );
        let mut lit = 0;
        for name in BUILTIN_ROOMS {
            let room = Room::builtin(name).unwrap();
            let walls: Vec<_> = room.walls().iter().map(PreparedSegment::new).collect();
            let all: Vec<u32> = (0..walls.len() as u32).collect();
            let (lo, hi) = room.bounds();
            for i in 0..3000 {
                let f = |n: usize, m: usize| (i * n % m) as f64 / m as f64;
                let pos = Vec2::new(
                    lo.x - 60.0 + (hi.x - lo.x + 120.0) * f(37, 997),
                    lo.y - 60.0 + (hi.y - lo.y + 120.0) * f(53, 991),
                );
                let heading = match i % 7 {
                    0 => (i % 12) as f64 * std::f64::consts::FRAC_PI_6,
                    _ => -3.2 + 6.4 * f(61, 1009),
                };
                let (sin, cos) = crate::simulation::math::sin_cos(heading);
                let facing = Facing::Angle { sin, cos };
                let scalar = eyes.read_rays::<3>(pos, facing, &walls, &all);
                let vector = eyes.read(pos, facing, &walls, &all);
                let bits = |r: &Readings| r.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&scalar), bits(&vector), "{pos:?} {heading}");
                lit += scalar.iter().filter(|&&v| v > 0.0).count();
            }
        }
        assert!(lit > 5_000, "{lit}: too few sensors saw a wall");
    }

    /// Robots of one ray a sensor (the e-puck2's eight, the Thymio II's seven, their own
    /// tables) read in AVX2 lanes, bit for bit, what the scalar cast reads, on the compass's
    /// headings (rays turned in advance) and on any other (turned per read).
    #[test]
    fn one_ray_robots_read_alike_in_vector_lanes() {
        use crate::simulation::room::{BUILTIN_ROOMS, Room};
        if Isa::detected() == Isa::Baseline {
            return; // nothing to compare
        }
        for robot in ["epuck2", "thymio2"] {
            let spec = RobotSpec::builtin(robot).unwrap();
            let compass = Compass::new(0.4);
            let eyes = Eyes::new(SensorModel::Sampled, spec, &compass);
            assert_eq!(eyes.per_sensor, 1, "{robot}");
            let mut lit = 0;
            for name in BUILTIN_ROOMS {
                let room = Room::builtin(name).unwrap();
                let walls: Vec<_> = room.walls().iter().map(PreparedSegment::new).collect();
                let all: Vec<u32> = (0..walls.len() as u32).collect();
                let (lo, hi) = room.bounds();
                for i in 0..2000 {
                    let f = |n: usize, m: usize| (i * n % m) as f64 / m as f64;
                    let pos = Vec2::new(
                        lo.x - 60.0 + (hi.x - lo.x + 120.0) * f(37, 997),
                        lo.y - 60.0 + (hi.y - lo.y + 120.0) * f(53, 991),
                    );
                    let (sin, cos) = crate::simulation::math::sin_cos(-3.2 + 6.4 * f(61, 1009));
                    for facing in [
                        Facing::Compass(eyes.on_compass(i % 12)),
                        Facing::Angle { sin, cos },
                    ] {
                        let scalar = eyes.read_rays::<1>(pos, facing, &walls, &all);
                        let vector = eyes.read(pos, facing, &walls, &all);
                        let bits = |r: &Readings| r.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                        assert_eq!(bits(&scalar), bits(&vector), "{robot} at {pos:?}");
                        lit += scalar.iter().filter(|&&v| v > 0.0).count();
                    }
                }
            }
            assert!(lit > 5_000, "{robot}: {lit}: too few sensors saw a wall");
        }
    }

    /// A wall beyond every ray's range is skipped and reads 0, as a wall not listed at all.
    #[test]
    fn far_walls_read_zero() {
        let eyes = Eyes::new(
            SensorModel::Sampled,
            RobotSpec::khepera(),
            &Compass::new(0.0),
        );
        let far =
            PreparedSegment::new(&Segment::new(Vec2::new(90.0, -50.0), Vec2::new(90.0, 50.0)));
        let near =
            PreparedSegment::new(&Segment::new(Vec2::new(60.0, -50.0), Vec2::new(60.0, 50.0)));
        let turned = Facing::Compass(eyes.on_compass(0));
        assert_eq!(eyes.read(Vec2::default(), turned, &[far], &[0]), [0.0; 8]);
        // 60 − 24.5 = 35.5 mm along the front axes → 44 mm sample (160); the side rays hit at
        // 35.5 / cos 24.2° = 38.9 mm → 43.9 mm sample (60 each).
        let s = eyes.read(Vec2::default(), turned, &[far, near], &[0, 1]);
        assert_eq!((s[2], s[3], s[0], s[6]), (280.0, 280.0, 0.0, 0.0));
    }
}
