//! The C99 form of an exported controller: `fm_controller.h` and `fm_controller.c`, with no
//! dependency (no libm, no allocation, no floating-point environment calls), doing the
//! library's operations in the library's order, so that the motor outputs are the
//! simulator's bit for bit.

use super::{ExportedController, KitRobot};
use crate::simulation::math::{
    EXP_MAX, EXP_MIN, EXP2_TABLE, INV_LN2_N, LN2_HI_N, LN2_LO_N, TO_INT,
};
use crate::simulation::robot::Motion;
use crate::simulation::sensor::SENSOR_LAYOUT;

/// The exported C: a header and a source file (file names [`CSources::HEADER_NAME`] and
/// [`CSources::SOURCE_NAME`]; the source includes the header by that name).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CSources {
    /// `fm_controller.h`.
    pub header: String,
    /// `fm_controller.c`.
    pub source: String,
}

impl CSources {
    /// The header's file name.
    pub const HEADER_NAME: &'static str = "fm_controller.h";
    /// The source's file name.
    pub const SOURCE_NAME: &'static str = "fm_controller.c";
}

/// `x` as an exact C99 hexadecimal floating constant (`0x1.8p+52`); `x` is finite.
pub(crate) fn hex_double(x: f64) -> String {
    debug_assert!(x.is_finite());
    let bits = x.to_bits();
    let sign = if bits >> 63 == 1 { "-" } else { "" };
    let exp = ((bits >> 52) & 0x7ff) as i64;
    let mant = bits & ((1u64 << 52) - 1);
    match exp {
        0 if mant == 0 => format!("{sign}0x0p+0"),
        0 => format!("{sign}0x0.{mant:013x}p-1022"),
        _ => format!("{sign}0x1.{mant:013x}p{:+}", exp - 1023),
    }
}

/// A C initialiser list of doubles, `per_line` to a line, indented.
fn c_list(values: impl IntoIterator<Item = f64>, per_line: usize, indent: &str) -> String {
    let values: Vec<String> = values.into_iter().map(hex_double).collect();
    values
        .chunks(per_line)
        .map(|line| format!("{indent}{}", line.join(", ")))
        .collect::<Vec<_>>()
        .join(",\n")
}

const HEADER: &str = r#"/* fm_controller.h: an evolved fuzzymotiv controller (network @N@-@H@-2), exported by
 * @PROVENANCE@.
 *
 * Compile with -O2 -ffp-contract=off (e.g. cc -std=c99 -O2 -ffp-contract=off -c fm_controller.c).
 * Why: the outputs equal the simulator's bit for bit only if every a*b+c is rounded twice, as
 * the library does; a compiler allowed to contract it into one fused multiply-add (GCC's default
 * outside strict ISO modes, -ffp-contract=fast, on any target with an FMA instruction) rounds
 * once and changes the last bits. Any optimisation level is fine; -ffast-math is not.
 *
 * Needs IEEE-754 binary64 `double` with FLT_EVAL_METHOD == 0 (x86-64, ARM, RISC-V; on a
 * single-precision FPU such as the Cortex-M4's, double is done in software, exactly) and the
 * default rounding mode (round to nearest, which every C program starts in: this code neither
 * reads nor changes the floating-point environment). No libm, no allocation, no state.
 *
 * Inputs: the @NWORD@ IR readings in the simulator's scale 0..@RMAX@ (readings above @RMAX@ are
 * taken as @RMAX@; a larger reading means a nearer wall), scaled to reading / @RMAX@, in this
@LAYOUT@
 *
 * Outputs: motors[0] = mL, motors[1] = mR in [0, 1]; the wheel speeds are
 * (2m - 1) * FM_V_MAX mm/s. *action is the step's action label (FM_ACTION_*), taken from
 * @LABELLED@.
 */
#ifndef FM_CONTROLLER_H
#define FM_CONTROLLER_H

#include <stdint.h>

#define FM_INPUTS @N@
#define FM_HIDDEN @H@
#define FM_OUTPUTS 2
/* robot.v_max of the experiment (mm/s). */
#define FM_V_MAX @VMAX@
/* aem.action_tolerance of the experiment. */
#define FM_ACTION_TOLERANCE @TOL@
/* robot.motion of the experiment: 1 "actions" (the robot executes the label), 0 "wheels". */
#define FM_MOTION_ACTIONS @MOTION@

#define FM_ACTION_STRAIGHT 0 /* move v_max * dt forward */
#define FM_ACTION_LEFT30 1   /* rotate on the spot by +30 degrees */
#define FM_ACTION_RIGHT30 2  /* rotate on the spot by -30 degrees */
#define FM_ACTION_TURN180 3  /* rotate on the spot by 180 degrees */

/* One control step from integer readings (0..@RMAX@; larger ones count as @RMAX@). */
void fm_controller_step(const uint16_t ir[@N@], double motors[2], int *action);

/* One control step from readings as doubles in [0, @RMAX@] (the simulator's noisy readings are
 * not whole numbers). */
void fm_controller_step_readings(const double ir[@N@], double motors[2], int *action);

/* fuzzymotiv's own exp (not libm's: ported here so that the results are the same bits on
 * every platform): Cody-Waite reduction x = (128 m + j) ln2/128 + r with |r| <= ln2/256, a
 * 128-entry table of 2^(j/128) as double-doubles and a degree-5 polynomial, no division;
 * within 1 ulp of a correctly rounded exp for normal results, +inf above 709.78, 0 below
 * -745.13. fm_logistic(x) = 1 / (1 + fm_exp(-x)), the hidden and output units' activation.
 * Both give the simulator's bits exactly. */
double fm_exp(double x);
double fm_logistic(double x);

#endif /* FM_CONTROLLER_H */
"#;

const SOURCE: &str = r#"/* fm_controller.c: see fm_controller.h (compile with -O2 -ffp-contract=off).
 * Exported by @PROVENANCE@. */
#include "fm_controller.h"

#include <float.h>

#if !defined(FLT_EVAL_METHOD) || FLT_EVAL_METHOD != 0
#error "fm_controller.c needs FLT_EVAL_METHOD == 0 (double arithmetic rounded to double)"
#endif
#if defined(__FAST_MATH__)
#error "fm_controller.c must not be compiled with -ffast-math"
#endif
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#endif

typedef union {
    double d;
    uint64_t u;
} fm_bits;

/* The constants of fuzzymotiv's exp (see fm_exp in fm_controller.h), exact. */
static const double TO_INT = @TO_INT@;
static const double INV_LN2_N = @INV_LN2_N@;
static const double LN2_HI_N = @LN2_HI_N@;
static const double LN2_LO_N = @LN2_LO_N@;
static const double EXP_MAX = @EXP_MAX@;
static const double EXP_MIN = @EXP_MIN@;
static const double P2 = @P2@;
static const double P3 = @P3@;
static const double P4 = @P4@;
static const double P5 = @P5@;

/* 2^(j/128), j = 0..127, as the double-double hi + lo. */
static const double EXP2_HI[128] = {
@EXP2_HI@
};
static const double EXP2_LO[128] = {
@EXP2_LO@
};

/* Per hidden unit: bias, then the weights from inputs 0..@NM1@ (the genome's order). */
static const double W_HIDDEN[FM_HIDDEN][FM_INPUTS + 1] = {
@W_HIDDEN@
};
/* Per output (mL, mR): bias, then the weights from hidden units 0..FM_HIDDEN-1. */
static const double W_OUT[FM_OUTPUTS][FM_HIDDEN + 1] = {
@W_OUT@
};

static const double SENSOR_MAX = @SENSOR_MAX@;

static double from_bits(uint64_t u)
{
    fm_bits b;
    b.u = u;
    return b.d;
}

static int64_t to_bits(double d)
{
    fm_bits b;
    b.d = d;
    return (int64_t)b.u; /* the patterns used here are below 2^63 */
}

/* 2^k for -1022 <= k <= 1023. */
static double pow2(int64_t k)
{
    return from_bits((uint64_t)(0x3ff + k) << 52);
}

/* k >> 7 rounded down (an arithmetic shift, as the library's). */
static int64_t floor_div_128(int64_t k)
{
    return (k - (k & 127)) / 128;
}

/* exp(x) = y * 2^m, |x| <= 746: x = k ln2/128 + r, y = 2^(j/128) e^r, j = k mod 128. */
static double exp_parts(double x, int64_t *m)
{
    double t = x * INV_LN2_N + TO_INT;
    double kd = t - TO_INT;
    int64_t k = to_bits(t) - to_bits(TO_INT);
    double r = (x - kd * LN2_HI_N) - kd * LN2_LO_N;
    int64_t j = k & 127;
    double hi = EXP2_HI[j];
    double lo = EXP2_LO[j];
    double p = r + r * r * (P2 + r * (P3 + r * (P4 + r * P5)));
    *m = floor_div_128(k);
    return hi + (lo + hi * p);
}

double fm_exp(double x)
{
    int64_t m, m1;
    double y;
    if (x <= 708.0 && x >= -708.0) {
        y = exp_parts(x, &m);
        return y * pow2(m);
    }
    if (x != x) {
        return x;
    }
    if (x > EXP_MAX) {
        return from_bits(UINT64_C(0x7ff0000000000000));
    }
    if (x < EXP_MIN) {
        return 0.0;
    }
    y = exp_parts(x, &m);
    m1 = m / 2;
    return y * pow2(m1) * pow2(m - m1);
}

double fm_logistic(double x)
{
    return 1.0 / (1.0 + fm_exp(-x));
}

static int label(double sl, double sr)
{
    if (sl < 0.0 && sr < 0.0) {
        return FM_ACTION_TURN180;
    } else if (sr - sl > FM_ACTION_TOLERANCE) {
        return FM_ACTION_LEFT30;
    } else if (sl - sr > FM_ACTION_TOLERANCE) {
        return FM_ACTION_RIGHT30;
    }
    return FM_ACTION_STRAIGHT;
}

void fm_controller_step_readings(const double ir[@N@], double motors[2], int *action)
{
    double x[FM_INPUTS];
    double h[FM_HIDDEN];
    int i, j, o;
    for (i = 0; i < FM_INPUTS; i++) {
        x[i] = ir[i] == 0.0 ? 0.0 : ir[i] / SENSOR_MAX;
    }
    for (j = 0; j < FM_HIDDEN; j++) {
        double s = W_HIDDEN[j][0];
        for (i = 0; i < FM_INPUTS; i++) {
            if (x[i] != 0.0) { /* w * 0 adds +-0: skipping it changes no result */
                s += W_HIDDEN[j][i + 1] * x[i];
            }
        }
        h[j] = fm_logistic(s);
    }
    for (o = 0; o < FM_OUTPUTS; o++) {
        double s = W_OUT[o][0];
        for (j = 0; j < FM_HIDDEN; j++) {
            s += W_OUT[o][j + 1] * h[j];
        }
        motors[o] = fm_logistic(s);
    }
    if (action) {
#if FM_MOTION_ACTIONS
        double v = FM_V_MAX;
        *action = label(((2.0 * motors[0] - 1.0) * v) / v, ((2.0 * motors[1] - 1.0) * v) / v);
#else
        *action = label(2.0 * motors[0] - 1.0, 2.0 * motors[1] - 1.0);
#endif
    }
}

void fm_controller_step(const uint16_t ir[@N@], double motors[2], int *action)
{
    double v[FM_INPUTS];
    int i;
    for (i = 0; i < FM_INPUTS; i++) {
        v[i] = ir[i] > @RMAX@ ? @RMAXF@ : (double)ir[i];
    }
    fm_controller_step_readings(v, motors, action);
}
"#;

/// Where the header says each input comes from: for the Khepera, the simulator's sensor
/// layout (one comment line per input: its position and facing); for another robot, its robot
/// file's numbering.
fn layout_comment(robot: &KitRobot) -> String {
    if robot.name != "khepera" || robot.sensors != SENSOR_LAYOUT.len() {
        return format!(
            " * order: the robot `{}`'s {} sensors, numbered as its robot file numbers them (wire\n \
             * its sensor k to ir[k]).",
            robot.name, robot.sensors
        );
    }
    let mut lines = vec![
        " * order: the sensors as the simulator places them on the body, in mm from the robot's centre".to_string(),
        " * (x forward, y to the left) and facing in degrees counter-clockwise from forward (the".to_string(),
        " * classic Khepera layout; wire your robot's sensors to these slots):".to_string(),
        " *".to_string(),
        " *   ir[k]   x (mm)   y (mm)   facing".to_string(),
    ];
    for (k, m) in SENSOR_LAYOUT.iter().enumerate() {
        lines.push(format!(
            " *   ir[{k}] {:>8} {:>8} {:>7}",
            format!("{:.1}", m.x),
            format!("{:.1}", m.y),
            format!("{:+}", m.facing_deg)
        ));
    }
    lines.join("\n")
}

/// A count in words, as the header's prose writes it ("eight"), in digits beyond twelve.
fn count_word(n: usize) -> String {
    const WORDS: [&str; 13] = [
        "no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten",
        "eleven", "twelve",
    ];
    WORDS
        .get(n)
        .map_or_else(|| n.to_string(), |w| w.to_string())
}

/// The header and source of `c`.
pub(crate) fn sources(c: &ExportedController) -> CSources {
    let h = c.shape.hidden();
    let n = c.shape.inputs();
    let (hidden_w, out_w) = c.weights.split_at(h * (n + 1));
    let rows = |w: &[f64], len: usize| {
        w.chunks_exact(len)
            .map(|row| {
                format!(
                    "    {{\n{}\n    }}",
                    c_list(row.iter().copied(), 3, "        ")
                )
            })
            .collect::<Vec<_>>()
            .join(",\n")
    };
    let labelled = match c.motion {
        Motion::Actions => {
            "the commanded speeds ((2m - 1) * FM_V_MAX) / FM_V_MAX, as the simulator's\n * `actions` motion labels them (without its wheel noise); the robot executes the label"
        }
        Motion::Wheels => {
            "the motor outputs 2m - 1, as the simulator's `wheels` motion records them (the\n * wheels drive the robot; the label only records the step)"
        }
    };
    let table = |f: fn(&(u64, u64)) -> u64| {
        c_list(EXP2_TABLE.iter().map(|e| f64::from_bits(f(e))), 3, "    ")
    };
    let subst = |template: &str| {
        let mut s = template.to_string();
        for (key, value) in [
            ("@H@", h.to_string()),
            ("@PROVENANCE@", crate::provenance()),
            ("@LABELLED@", labelled.to_string()),
            ("@LAYOUT@", layout_comment(&c.robot)),
            ("@NWORD@", count_word(n)),
            ("@NM1@", (n - 1).to_string()),
            ("@N@", n.to_string()),
            ("@RMAXF@", format!("{:?}", c.robot.reading_max)),
            ("@RMAX@", format!("{}", c.robot.reading_max)),
            ("@VMAX@", hex_double(c.v_max)),
            ("@TOL@", hex_double(c.tolerance)),
            (
                "@MOTION@",
                u8::from(c.motion == Motion::Actions).to_string(),
            ),
            ("@TO_INT@", hex_double(TO_INT)),
            ("@INV_LN2_N@", hex_double(INV_LN2_N)),
            ("@LN2_HI_N@", hex_double(LN2_HI_N)),
            ("@LN2_LO_N@", hex_double(LN2_LO_N)),
            ("@EXP_MAX@", hex_double(EXP_MAX)),
            ("@EXP_MIN@", hex_double(EXP_MIN)),
            ("@P2@", hex_double(0.5)),
            ("@P3@", hex_double(1.0 / 6.0)),
            ("@P4@", hex_double(1.0 / 24.0)),
            ("@P5@", hex_double(1.0 / 120.0)),
            ("@EXP2_HI@", table(|e| e.0)),
            ("@EXP2_LO@", table(|e| e.1)),
            ("@W_HIDDEN@", rows(hidden_w, n + 1)),
            ("@W_OUT@", rows(out_w, h + 1)),
            ("@SENSOR_MAX@", hex_double(c.robot.reading_max)),
        ] {
            s = s.replace(key, &value);
        }
        s
    };
    let header = subst(HEADER);
    let source = subst(SOURCE);
    debug_assert!(!header.contains('@') && !source.contains('@'));
    CSources { header, source }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_doubles_are_exact_c_constants() {
        assert_eq!(hex_double(1.0), "0x1.0000000000000p+0");
        assert_eq!(hex_double(-0.5), "-0x1.0000000000000p-1");
        assert_eq!(hex_double(0.0), "0x0p+0");
        assert_eq!(hex_double(-0.0), "-0x0p+0");
        assert_eq!(hex_double(TO_INT), "0x1.8000000000000p+52");
        assert_eq!(hex_double(f64::from_bits(1)), "0x0.0000000000001p-1022");
        assert_eq!(hex_double(f64::MAX), "0x1.fffffffffffffp+1023");
    }

    /// Someone handed the two files (or the JSON) has no repository: they name no path of it,
    /// and the header lists every input's sensor position and facing itself.
    #[test]
    fn the_exported_files_stand_alone() {
        use crate::simulation::controller::MlpShape;
        use crate::simulation::trial_params::TrialParams;
        let shape = MlpShape::with_hidden(2).unwrap();
        let genome = vec![0.25; shape.genome_len()];
        let c = ExportedController::new(shape, &genome, &TrialParams::default()).unwrap();
        let CSources { header, source } = c.c();
        for text in [&header, &source, &c.json()] {
            for path in ["docs/", "crates/", ".rs", ".md"] {
                assert!(!text.contains(path), "{path} in:\n{text}");
            }
        }
        for (k, m) in SENSOR_LAYOUT.iter().enumerate() {
            let row = format!(
                " *   ir[{k}] {:>8} {:>8} {:>7}\n",
                format!("{:.1}", m.x),
                format!("{:.1}", m.y),
                format!("{:+}", m.facing_deg)
            );
            assert!(header.contains(&row), "no row for sensor {k}:\n{header}");
        }
        assert!(
            header.contains(" *   ir[2]     24.5      5.5      +0\n"),
            "{header}"
        );
        assert!(header.contains("fm_logistic(x) = 1 / (1 + fm_exp(-x))"));
    }
}
