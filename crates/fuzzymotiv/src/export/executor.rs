//! The actions executor of the deployment kits (`fm_executor.h`, `fm_executor.c`): the exported
//! network driving a differential-drive robot one control period at a time, with the robot's
//! own I/O left to the kit's robot layer. With `actions` motion it executes each step's label
//! with the wheels, measured by odometry (straight `v_max · dt`, a `turn_deg` turn on the spot,
//! a half turn), and runs the network again when the action is done; with `wheels` motion it
//! gives the wheels the network's speeds directly.

use super::c::hex_double;
use super::{ExportedController, KitFile};
use crate::simulation::robot::Motion;

/// The executor's header: the robot's kinematics as exact constants and the interface.
const HEADER: &str = r#"/* fm_executor.h: runs the exported controller (fm_controller.h) on a differential-drive
 * robot, one control period at a time. Exported by @PROVENANCE@.
 *
 * The robot layer (fm_epuck2.c, fm_khepera.c or yours) does the I/O: every FM_PERIOD_S seconds
 * it reads the FM_INPUTS proximity readings in the simulator's scale (see fm_controller.h) and
 * the two wheel position counters (odometry, in ticks: motor steps or encoder counts), calls
 * fm_executor_step, and sets the two wheel speeds it returns (ticks/s). Lengths are in mm,
 * times in s, angles in degrees, wheel positions in ticks and wheel speeds in ticks/s;
 * ticks_per_mm (given to fm_executor_init) converts wheel travel.
 *
 * With `actions` motion (FM_MOTION_ACTIONS 1, this controller: @MOTION_NAME@) the robot was
 * evolved executing the label of each step, and so does this executor. When no action is under
 * way, fm_executor_step runs the network on the readings and begins the label's action:
 *
 *   straight  both wheels forward FM_STEP_MM mm (v_max * dt)
 *   left30    on the spot, counter-clockwise by FM_TURN_DEG degrees: each wheel travels
 *             FM_TURN_MM mm (the turn in radians * FM_WHEEL_BASE_MM / 2), the left one backwards
 *   right30   the same, clockwise
 *   turn180   on the spot by 180 degrees (counter-clockwise): each wheel FM_TURN180_MM mm
 *
 * each wheel's travel rounded to whole ticks. Every period, each wheel gets the speed that
 * covers the rest of its travel in one period, at most the cruise speed (the speed that covers
 * a straight step in one period, about FM_V_MAX mm/s, at most the motors' speed limit), so a
 * straight step takes one period as in the simulator and a turn as many as it needs; a wheel
 * stops on its goal (or past it: at most one tick when the wheel follows its speed). The action
 * is done when both wheels are, and the network runs again in that period. An action not done
 * after twice its periods at cruise speed and two more (a wheel blocked) is given up.
 *
 * With `wheels` motion (FM_MOTION_ACTIONS 0) the network runs every period and the wheels get
 * its speeds (2m - 1) * FM_V_MAX mm/s, rounded to whole ticks/s and clamped to the limit.
 *
 * Compile with -O2 -ffp-contract=off, as fm_controller.c. No libm, no allocation.
 */
#ifndef FM_EXECUTOR_H
#define FM_EXECUTOR_H

#include <stdint.h>

#include "fm_controller.h"

/* trial.dt of the experiment: the control period (s). */
#define FM_PERIOD_S @PERIOD@
/* The robot's wheel base, the distance between its wheels (mm): @WHEEL_BASE@. */
#define FM_WHEEL_BASE_MM @WHEEL_BASE_HEX@
/* A straight action (mm): v_max * dt = @STEP@. */
#define FM_STEP_MM @STEP_HEX@
/* A left30/right30 action's turn (degrees): @TURN@. */
#define FM_TURN_DEG @TURN_HEX@
/* Each wheel's travel in a left30/right30 action (mm): @TURN_MM@. */
#define FM_TURN_MM @TURN_MM_HEX@
/* Each wheel's travel in a turn180 action (mm): @HALF_MM@. */
#define FM_TURN180_MM @HALF_MM_HEX@

/* fm_executor.action when no action is under way. */
#define FM_EXECUTOR_IDLE (-1)

typedef struct {
    double ticks_per_mm;   /* odometry ticks per mm of wheel travel */
    int32_t speed_limit;   /* the largest wheel speed the motors take (ticks/s) */
    int32_t cruise;        /* the wheel speed of an action (ticks/s) */
    int action;            /* the FM_ACTION_* under way, or FM_EXECUTOR_IDLE */
    int32_t start[2];      /* the wheel positions when it began (ticks) */
    int32_t goal[2];       /* each wheel's signed travel to make (ticks) */
    int32_t periods_left;  /* periods before the action is given up */
    double motors[2];      /* the network's last outputs mL, mR in [0, 1] */
    int label;             /* the network's last action label (FM_ACTION_*) */
    uint32_t steps;        /* how many times the network has run */
} fm_executor;

/* An idle executor for wheels whose odometry counts ticks_per_mm ticks per mm of travel and
 * whose motors take speeds up to speed_limit ticks/s (> 0). */
void fm_executor_init(fm_executor *e, double ticks_per_mm, int32_t speed_limit);

/* One control period: the wheel speeds (ticks/s) for the readings ir (the simulator's scale)
 * and the wheel positions left, right (ticks). */
void fm_executor_step(fm_executor *e, const double ir[FM_INPUTS], int32_t left, int32_t right,
                      int32_t speeds[2]);

/* Begins the action FM_ACTION_* with the wheels at left, right (ticks); another code makes the
 * executor idle. fm_executor_step calls it; call it yourself to test the robot's actions. */
void fm_executor_begin(fm_executor *e, int action, int32_t left, int32_t right);

/* One period of the action under way: 1 and the wheel speeds (ticks/s) while it runs, 0 and
 * speeds 0 when it is done, given up or there is none (the executor is then idle). */
int fm_executor_tick(fm_executor *e, int32_t left, int32_t right, int32_t speeds[2]);

/* mm of wheel travel as whole ticks, rounded to the nearest. */
int32_t fm_executor_ticks(const fm_executor *e, double mm);

#endif /* FM_EXECUTOR_H */
"#;

/// The executor's source.
const SOURCE: &str = r#"/* fm_executor.c: see fm_executor.h (compile with -O2 -ffp-contract=off).
 * Exported by @PROVENANCE@. */
#include "fm_executor.h"

/* The kit's floating constants are doubles as written only if the compiler reads them so:
 * GCC's -fsingle-precision-constant (which ChibiOS's ARMCMx rules.mk adds whenever USE_FPU is
 * set, as the e-puck2 firmware sets it) makes them floats, rounding the network's weights in
 * fm_controller.c. An error here ("negative width in bit-field doubles_as_written") means that
 * flag is on: compile the kit's files with -fno-single-precision-constant (README.txt). */
struct fm_double_constants_check {
    unsigned int doubles_as_written : (0x1.0000000000001p+0 != 1.0) ? 1 : -1;
};

/* x rounded to the nearest whole number (halves away from zero), |x| < 2^31. */
static int32_t nearest(double x)
{
    return (int32_t)(x < 0.0 ? x - 0.5 : x + 0.5);
}

/* x rounded up to a whole number, 0 <= x < 2^31. */
static int32_t ceiling(double x)
{
    int32_t n = (int32_t)x;
    return (double)n < x ? n + 1 : n;
}

static int32_t clamp_speed(const fm_executor *e, int32_t v)
{
    if (v > e->speed_limit) {
        return e->speed_limit;
    }
    if (v < -e->speed_limit) {
        return -e->speed_limit;
    }
    return v;
}

/* b - a for wheel counters, also across a counter's wrap-around. */
static int32_t travelled(int32_t a, int32_t b)
{
    return (int32_t)((uint32_t)b - (uint32_t)a);
}

int32_t fm_executor_ticks(const fm_executor *e, double mm)
{
    return nearest(mm * e->ticks_per_mm);
}

void fm_executor_init(fm_executor *e, double ticks_per_mm, int32_t speed_limit)
{
    e->ticks_per_mm = ticks_per_mm;
    e->speed_limit = speed_limit > 0 ? speed_limit : 1;
    e->cruise = ceiling((double)fm_executor_ticks(e, FM_STEP_MM) / FM_PERIOD_S);
    e->cruise = clamp_speed(e, e->cruise > 0 ? e->cruise : 1);
    e->action = FM_EXECUTOR_IDLE;
    e->start[0] = e->start[1] = 0;
    e->goal[0] = e->goal[1] = 0;
    e->periods_left = 0;
    e->motors[0] = e->motors[1] = 0.5;
    e->label = FM_ACTION_STRAIGHT;
    e->steps = 0;
}

void fm_executor_begin(fm_executor *e, int action, int32_t left, int32_t right)
{
    int32_t step = fm_executor_ticks(e, FM_STEP_MM);
    int32_t turn = fm_executor_ticks(e, FM_TURN_MM);
    int32_t half = fm_executor_ticks(e, FM_TURN180_MM);
    int32_t longest;
    switch (action) {
    case FM_ACTION_STRAIGHT:
        e->goal[0] = step;
        e->goal[1] = step;
        break;
    case FM_ACTION_LEFT30:
        e->goal[0] = -turn;
        e->goal[1] = turn;
        break;
    case FM_ACTION_RIGHT30:
        e->goal[0] = turn;
        e->goal[1] = -turn;
        break;
    case FM_ACTION_TURN180:
        e->goal[0] = -half;
        e->goal[1] = half;
        break;
    default:
        e->action = FM_EXECUTOR_IDLE;
        return;
    }
    e->action = action;
    e->start[0] = left;
    e->start[1] = right;
    longest = e->goal[0] < 0 ? -e->goal[0] : e->goal[0];
    e->periods_left = 2 * ceiling((double)longest / ((double)e->cruise * FM_PERIOD_S)) + 2;
}

/* The speed of a wheel that has travelled `done` of its `goal` (ticks): the rest in one
 * period, at most the cruise speed; 0 on or past the goal. */
static int32_t wheel_speed(const fm_executor *e, int32_t done, int32_t goal)
{
    int32_t rest = goal - done;
    int32_t v;
    if (goal > 0 ? rest <= 0 : rest >= 0) {
        return 0;
    }
    v = ceiling((double)(rest > 0 ? rest : -rest) / FM_PERIOD_S);
    if (v > e->cruise) {
        v = e->cruise;
    }
    return rest > 0 ? v : -v;
}

int fm_executor_tick(fm_executor *e, int32_t left, int32_t right, int32_t speeds[2])
{
    speeds[0] = 0;
    speeds[1] = 0;
    if (e->action == FM_EXECUTOR_IDLE) {
        return 0;
    }
    if (e->periods_left > 0) {
        speeds[0] = wheel_speed(e, travelled(e->start[0], left), e->goal[0]);
        speeds[1] = wheel_speed(e, travelled(e->start[1], right), e->goal[1]);
    }
    if (speeds[0] == 0 && speeds[1] == 0) {
        e->action = FM_EXECUTOR_IDLE;
        return 0;
    }
    e->periods_left--;
    return 1;
}

void fm_executor_step(fm_executor *e, const double ir[FM_INPUTS], int32_t left, int32_t right,
                      int32_t speeds[2])
{
#if FM_MOTION_ACTIONS
    if (fm_executor_tick(e, left, right, speeds)) {
        return;
    }
    fm_controller_step_readings(ir, e->motors, &e->label);
    e->steps++;
    fm_executor_begin(e, e->label, left, right);
    fm_executor_tick(e, left, right, speeds);
#else
    int k;
    (void)left;
    (void)right;
    fm_controller_step_readings(ir, e->motors, &e->label);
    e->steps++;
    for (k = 0; k < 2; k++) {
        double v = (2.0 * e->motors[k] - 1.0) * FM_V_MAX * e->ticks_per_mm;
        speeds[k] = clamp_speed(e, nearest(v));
    }
#endif
}
"#;

/// `x` (finite) as a short decimal for the header's comments, e.g. `13.875 mm`.
pub(crate) fn decimal(x: f64) -> String {
    let s = format!("{x:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// `fm_executor.h` and `fm_executor.c` for `c`'s robot.
pub(crate) fn files(c: &ExportedController) -> Vec<KitFile> {
    let r = c.robot();
    let turn_mm = r.turn_deg.to_radians() * r.wheel_base / 2.0;
    let half_mm = std::f64::consts::PI * r.wheel_base / 2.0;
    let motion = match c.motion {
        Motion::Actions => "actions",
        Motion::Wheels => "wheels",
    };
    let subst = |template: &str| {
        let mut s = template.to_string();
        for (key, value) in [
            ("@PROVENANCE@", crate::provenance()),
            ("@MOTION_NAME@", motion.to_string()),
            ("@PERIOD@", hex_double(r.dt)),
            ("@WHEEL_BASE_HEX@", hex_double(r.wheel_base)),
            ("@WHEEL_BASE@", decimal(r.wheel_base)),
            ("@STEP_HEX@", hex_double(r.straight_step())),
            ("@STEP@", decimal(r.straight_step())),
            ("@TURN_HEX@", hex_double(r.turn_deg)),
            ("@TURN@", decimal(r.turn_deg)),
            ("@TURN_MM_HEX@", hex_double(turn_mm)),
            ("@TURN_MM@", decimal(turn_mm)),
            ("@HALF_MM_HEX@", hex_double(half_mm)),
            ("@HALF_MM@", decimal(half_mm)),
        ] {
            s = s.replace(key, &value);
        }
        s
    };
    vec![
        KitFile::text("fm_executor.h", subst(HEADER)),
        KitFile::text("fm_executor.c", subst(SOURCE)),
    ]
}
