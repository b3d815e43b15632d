//! The Khepera deployment kit (`fuzzymotiv export RUN --to c --target khepera`): the exported
//! network and the actions executor for a Khepera-like differential-drive robot whose I/O the
//! user supplies (`fm_khepera.c`: three functions and two numbers in an `fm_robot_io`), with
//! golden vectors and a README. The Khepera I, the paper's robot, is discontinued; the kit
//! names what any robot with proximity sensors and wheel odometry must provide.

use super::epuck2::{c_kit, motion_name, motion_text};
use super::executor::decimal;
use super::{ExportedController, Kit, KitFile};

/// The header of the Khepera layer.
const HEADER: &str = r#"/* fm_khepera.h: the exported controller on a Khepera-like robot whose I/O you supply.
 * Exported by @PROVENANCE@. See README.txt. */
#ifndef FM_KHEPERA_H
#define FM_KHEPERA_H

#include <stdint.h>

#include "fm_executor.h"

/* What the kit needs of the robot: fill one in with your robot's functions and numbers. */
typedef struct {
    /* Passed to the three functions as they are (your driver's handle, or NULL). */
    void *ctx;
    /* The FM_INPUTS proximity readings, in the simulator's scale: 0 (nothing in sight) to
     * @RMAX@ (a wall at the sensor), larger nearer; input k is the sensor the robot file numbers
     * k (fm_controller.h). Scale and clamp your sensors' values here. */
    void (*read_proximity)(void *ctx, double ir[FM_INPUTS]);
    /* The wheels' position counters (odometry ticks: encoder counts or motor steps), growing
     * when the wheel turns forward. */
    void (*read_positions)(void *ctx, int32_t *left, int32_t *right);
    /* Sets the wheel speeds, in ticks/s (forward positive). */
    void (*set_speeds)(void *ctx, int32_t left, int32_t right);
    /* Ticks per mm of wheel travel: ticks per wheel turn / (pi * wheel diameter in mm). */
    double ticks_per_mm;
    /* The largest wheel speed your motors take (ticks/s). */
    int32_t speed_limit;
} fm_robot_io;

typedef struct {
    const fm_robot_io *io;
    fm_executor executor;
} fm_khepera;

/* Prepares k to drive the robot of io (which must outlive k); sets the wheels still. */
void fm_khepera_init(fm_khepera *k, const fm_robot_io *io);

/* One control period: reads the sensors and the wheel positions, runs the executor (the
 * network, and with `actions` motion the step's action) and sets the wheel speeds. Call it
 * every FM_PERIOD_S seconds (@PERIOD_S@ s), from a timer or a loop that waits for the next
 * period (not a fixed sleep after the work, which drifts). */
void fm_khepera_period(fm_khepera *k);

#endif /* FM_KHEPERA_H */
"#;

/// The source of the Khepera layer.
const SOURCE: &str = r#"/* fm_khepera.c: see fm_khepera.h. Exported by @PROVENANCE@. */
#include <stddef.h>

#include "fm_khepera.h"

void fm_khepera_init(fm_khepera *k, const fm_robot_io *io)
{
    k->io = io;
    fm_executor_init(&k->executor, io->ticks_per_mm, io->speed_limit);
    io->set_speeds(io->ctx, 0, 0);
}

void fm_khepera_period(fm_khepera *k)
{
    const fm_robot_io *io = k->io;
    double ir[FM_INPUTS];
    int32_t left, right, speeds[2];
    io->read_proximity(io->ctx, ir);
    io->read_positions(io->ctx, &left, &right);
    fm_executor_step(&k->executor, ir, left, right, speeds);
    io->set_speeds(io->ctx, speeds[0], speeds[1]);
}
"#;

/// The kit's README.
const README: &str = r#"fuzzymotiv controller for a Khepera-like robot, exported by @PROVENANCE@.
Robot `@ROBOT@`: @N@ proximity sensors (readings 0..@RMAX@), v_max @VMAX@ mm/s, wheel base
@WHEEL_BASE@ mm, control period @PERIOD_S@ s, motion `@MOTION@`.

The Khepera I (K-Team), the robot of the paper and of the simulator, is discontinued. This kit
runs the controller on any differential-drive robot with proximity sensors and wheel odometry
through an I/O layer you write: fm_robot_io in fm_khepera.h.

Files
  fm_controller.h/.c  the evolved network (@N@ inputs, @H@ hidden units, 2 outputs), its
                      outputs the simulator's bit for bit
  fm_executor.h/.c    runs the network every period and, with `actions` motion, executes each
                      step's action with the wheels and odometry (see fm_executor.h)
  fm_khepera.h/.c     one control period through your fm_robot_io
  golden.csv          readings recorded in the simulator and the controller's outputs for them
  fm_golden.c         replays golden.csv on your computer

1. Check the network on your computer (and on the robot's compiler if it can run a program
   that reads a file):

     cc -std=c99 -O2 -ffp-contract=off -o fm_golden fm_golden.c fm_controller.c
     ./fm_golden golden.csv

   It prints "N golden vectors, 0 differ".

2. Fill in an fm_robot_io (fm_khepera.h) for your robot:
   - read_proximity: the @N@ readings on the simulator's scale 0..@RMAX@ (larger = nearer),
     in the robot file's order (fm_controller.h lists it). A Khepera I's 10-bit proximity
     values are that scale as they are; another robot's need scaling (measure them: the
     fuzzymotiv guide "From the simulator to a real robot", section "Your robot's sensors").
   - read_positions: the two wheels' position counters, forward positive.
   - set_speeds: wheel speeds in ticks/s (the position counters' ticks per second).
   - ticks_per_mm: the counters' ticks per mm of wheel travel.
   - speed_limit: the largest speed set_speeds takes, in ticks/s.
   Take these numbers from your robot's manual or measure them (drive 1 m straight and count
   the ticks); wrong ones make every action too long or too short.

3. Build with your robot's toolchain, keeping doubles unfused and constants double:

     cc -std=c99 -O2 -ffp-contract=off -c fm_controller.c fm_executor.c fm_khepera.c

   (never -ffast-math or -fsingle-precision-constant; fm_executor.c refuses the latter).

4. Call fm_khepera_init once with your fm_robot_io, then fm_khepera_period every @PERIOD_S@ s:

     static fm_khepera robot;
     fm_khepera_init(&robot, &my_io);
     for (;;) {
         fm_khepera_period(&robot);
         wait_until_next_period();   /* your timer: every @PERIOD_S@ s */
     }

   robot.executor.label and robot.executor.motors hold the network's last action and outputs
   (log them to recognise the room with `fuzzymotiv recognise`).

Units: readings 0..@RMAX@, wheel positions in ticks, speeds in ticks/s, lengths in mm.
Motion `@MOTION@`: @MOTION_TEXT@
"#;

/// The Khepera kit of `c`: `fm_controller.h/.c`, `fm_executor.h/.c`, `fm_khepera.h/.c`,
/// `golden.csv`, `fm_golden.c` and `README.txt`.
pub fn khepera_kit(c: &ExportedController) -> Kit {
    let r = c.robot();
    let subst = |template: &str| {
        let mut s = template.to_string();
        for (key, value) in [
            ("@PROVENANCE@", crate::provenance()),
            ("@ROBOT@", r.name.clone()),
            ("@N@", c.shape().inputs().to_string()),
            ("@H@", c.shape().hidden().to_string()),
            ("@RMAX@", decimal(r.reading_max)),
            ("@VMAX@", decimal(r.v_max)),
            ("@WHEEL_BASE@", decimal(r.wheel_base)),
            ("@PERIOD_S@", decimal(r.dt)),
            ("@MOTION@", motion_name(c.motion).to_string()),
            ("@MOTION_TEXT@", motion_text(c)),
        ] {
            s = s.replace(key, &value);
        }
        s
    };
    let layer = [
        KitFile::text("fm_khepera.h", subst(HEADER)),
        KitFile::text("fm_khepera.c", subst(SOURCE)),
    ];
    c_kit(
        c,
        layer,
        subst(README),
        "then fill in fm_robot_io (fm_khepera.h) for your robot as README.txt says",
    )
}
