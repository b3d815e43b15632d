//! The e-puck2 deployment kit (`fuzzymotiv export RUN --to c --target epuck2`): the exported
//! network, the actions executor and a ChibiOS thread for GCtronic's `e-puck2_main-processor`
//! firmware (`fm_epuck2.c`) that reads the eight proximity sensors, runs the controller every
//! control period and drives the stepper motors, with golden vectors and a README.
//!
//! The firmware interface it uses (docs/robots-sources.md §1.4, read from
//! `e-puck2/e-puck2_main-processor` at d2e0dbba8f50a0619b01186c5437e3f5ffffae56 and its
//! ChibiOS 3.1 submodule): `get_calibrated_prox` (`src/sensors/proximity.h`),
//! `left_motor_set_speed`, `right_motor_set_speed`, `left_motor_get_pos`, `right_motor_get_pos`
//! and `MOTOR_SPEED_LIMIT` (`src/motors.h`), `THD_WORKING_AREA`, `THD_FUNCTION`,
//! `chRegSetThreadName`, `chThdCreateStatic`, `chVTGetSystemTime`, `chThdSleepUntilWindowed`,
//! `MS2ST` and `NORMALPRIO` (ChibiOS `os/rt/include/`).

use super::c::hex_double;
use super::executor::decimal;
use super::{ExportedController, Kit, KitFile, executor, golden};
use crate::simulation::robot::Motion;

/// Steps of an e-puck2 wheel per turn: "a complete turn is 1000 steps" (GCtronic's ROS driver
/// `gctronic/epuck_driver_cpp`, branch e-puck2, `src/epuck2_driver_cpp.cpp` L53).
pub const EPUCK2_STEPS_PER_TURN: f64 = 1000.0;

/// The e-puck2's wheel diameter (mm): 40, GCtronic's `WHEEL_DIAMETER 4` (cm) in the same driver
/// (L49), as Webots' e-puck model (wheel radius 20 mm). ARGoS and student code use 41 mm and
/// the EPFL MICRO-315 wiki a 13 cm perimeter (41.4 mm): docs/robots-sources.md §1.1 and §1.7.
pub const EPUCK2_WHEEL_DIAMETER_MM: f64 = 40.0;

/// The e-puck2 motors' speed limit (steps/s): `MOTOR_SPEED_LIMIT 1100` in the firmware's
/// `src/motors.h`, which clamps every speed to ±1100.
pub const EPUCK2_MOTOR_SPEED_LIMIT: i32 = 1100;

/// The header of the e-puck2 layer.
const HEADER: &str = r#"/* fm_epuck2.h: the exported controller as a ChibiOS thread of GCtronic's e-puck2 firmware
 * (e-puck2_main-processor). Exported by @PROVENANCE@. See README.txt. */
#ifndef FM_EPUCK2_H
#define FM_EPUCK2_H

#include "fm_executor.h"

/* Starts the controller's thread (NORMALPRIO). Call it once from main, after
 * messagebus_init, motors_init, proximity_start(FAST_UPDATE) and calibrate_ir (the robot in
 * open space, nothing within 10 cm of its sensors, while calibrate_ir runs). */
void fm_epuck2_start(void);

/* The thread's executor: the network's last outputs (motors, label), how many times it ran
 * (steps) and the action under way, for a log; read it from another thread as a snapshot that
 * may be one period old. */
const fm_executor *fm_epuck2_executor(void);

#endif /* FM_EPUCK2_H */
"#;

/// The source of the e-puck2 layer.
const SOURCE: &str = r#"/* fm_epuck2.c: the exported controller as a ChibiOS thread of GCtronic's e-puck2 firmware
 * (e-puck2_main-processor): every FM_EPUCK2_PERIOD_MS ms it reads the proximity sensors, runs
 * the executor (fm_executor.h: the network, and with `actions` motion the step's action) and
 * sets the wheel speeds. Exported by @PROVENANCE@. See README.txt.
 *
 * Units: readings in the firmware's calibrated proximity counts (get_calibrated_prox), wheel
 * positions in motor steps (left_motor_get_pos), wheel speeds in steps/s
 * (left_motor_set_speed). Compile it, fm_executor.c and fm_controller.c with
 * -fno-single-precision-constant -ffp-contract=off after the firmware's flags (README.txt,
 * step 3). */
#include <stddef.h>
#include <stdint.h>

#include "ch.h"
#include "motors.h"
#include "sensors/proximity.h"

#include "fm_epuck2.h"

/* Doubles as written (see fm_executor.c): build the kit's files with
 * -fno-single-precision-constant -ffp-contract=off (README.txt, step 3). */
struct fm_epuck2_double_constants_check {
    unsigned int doubles_as_written : (0x1.0000000000001p+0 != 1.0) ? 1 : -1;
};

/* Proximity: the sensors are read with get_calibrated_prox(i) (the reflected light minus the
 * ambient light, minus what calibrate_ir measured in open space, at least 0): the latest
 * values of the firmware's 100 Hz proximity thread, read without waiting, as the firmware's
 * own demos read them; the "/proximity" message bus would give the raw delta without the
 * calibration and make the thread wait for the next measurement. A reading is
 * get_calibrated_prox(i) * FM_EPUCK2_PROX_TO_READING in the simulator's scale, taken as
 * FM_EPUCK2_READING_MAX above it. The robot `@ROBOT@` gives its readings in calibrated counts,
 * so the factor is 1: change it only with a robot file of another scale. */
#define FM_EPUCK2_PROX_TO_READING 1.0
/* The simulator's largest reading, the robot's reading_max: @RMAX@. */
#define FM_EPUCK2_READING_MAX @RMAX_HEX@

/* Network input k reads the firmware's sensor PROX_OF_INPUT[k]. The firmware numbers them IR0
 * front-right, then clockwise (IR2 right, IR5 left, IR7 front-left), as Enki's and Webots'
 * e-puck models do; the robot `@ROBOT@` is taken to number them so (fm_controller.h: rewire
 * here if its order differs). */
static const unsigned int PROX_OF_INPUT[FM_INPUTS] = {@PROX_OF_INPUT@};

/* Wheels: 1000 steps per wheel turn (GCtronic's e-puck2 ROS driver, "a complete turn is 1000
 * steps") and a 40 mm wheel diameter (the same driver's WHEEL_DIAMETER 4 cm; other sources say
 * 41 mm: measure yours, e.g. the steps of a 1 m straight run, and change it here). */
#define FM_EPUCK2_STEPS_PER_TURN 1000.0
#define FM_EPUCK2_WHEEL_DIAMETER_MM 40.0
#define FM_EPUCK2_PI 0x1.921fb54442d18p+1
/* Motor steps per mm of wheel travel (7.96 with the values above). */
#define FM_EPUCK2_STEPS_PER_MM \
    (FM_EPUCK2_STEPS_PER_TURN / (FM_EPUCK2_PI * FM_EPUCK2_WHEEL_DIAMETER_MM))

/* The control period: trial.dt of the experiment (@PERIOD_S@ s), in ms (the firmware's ChibiOS
 * tick is 1 ms, chconf.h CH_CFG_ST_FREQUENCY 1000). */
#define FM_EPUCK2_PERIOD_MS @PERIOD_MS@

static THD_WORKING_AREA(fm_epuck2_wa, @STACK@);
static fm_executor executor;

/* The network's inputs: each sensor's calibrated counts as a reading, at most the maximum. */
static void read_proximity(double ir[FM_INPUTS])
{
    int k;
    for (k = 0; k < FM_INPUTS; k++) {
        double r = (double)get_calibrated_prox(PROX_OF_INPUT[k]) * FM_EPUCK2_PROX_TO_READING;
        ir[k] = r > FM_EPUCK2_READING_MAX ? FM_EPUCK2_READING_MAX : r;
    }
}

static THD_FUNCTION(fm_epuck2_thd, arg)
{
    systime_t time;
    (void)arg;
    chRegSetThreadName("fm_epuck2");
    fm_executor_init(&executor, FM_EPUCK2_STEPS_PER_MM, MOTOR_SPEED_LIMIT);
    time = chVTGetSystemTime();
    for (;;) {
        double ir[FM_INPUTS];
        int32_t speeds[2];
        read_proximity(ir);
        fm_executor_step(&executor, ir, left_motor_get_pos(), right_motor_get_pos(), speeds);
        left_motor_set_speed((int)speeds[0]);
        right_motor_set_speed((int)speeds[1]);
        time = chThdSleepUntilWindowed(time, time + MS2ST(FM_EPUCK2_PERIOD_MS));
    }
}

void fm_epuck2_start(void)
{
    chThdCreateStatic(fm_epuck2_wa, sizeof(fm_epuck2_wa), NORMALPRIO, fm_epuck2_thd, NULL);
}

const fm_executor *fm_epuck2_executor(void)
{
    return &executor;
}
"#;

/// The kit's README.
const README: &str = r#"fuzzymotiv controller for the e-puck2 (GCtronic), exported by @PROVENANCE@.
Robot `@ROBOT@`: @N@ proximity sensors (readings 0..@RMAX@), v_max @VMAX@ mm/s, wheel base
@WHEEL_BASE@ mm, control period @PERIOD_S@ s, motion `@MOTION@`.

Files
  fm_controller.h/.c  the evolved network (@N@ inputs, @H@ hidden units, 2 outputs), its
                      outputs the simulator's bit for bit
  fm_executor.h/.c    runs the network every period and, with `actions` motion, executes each
                      step's action with the wheels and odometry (see fm_executor.h)
  fm_epuck2.h/.c      the firmware thread: reads the proximity sensors, runs the executor, sets
                      the motor speeds
  golden.csv          readings recorded in the simulator and the controller's outputs for them
  fm_golden.c         replays golden.csv on your computer (not on the robot)

1. Check the network on your computer (any C99 compiler):

     cc -std=c99 -O2 -ffp-contract=off -o fm_golden fm_golden.c fm_controller.c
     ./fm_golden golden.csv

   It prints "N golden vectors, 0 differ".

2. Make a project beside the firmware, from its template:

     git clone --recursive https://github.com/e-puck2/e-puck2_main-processor.git
     cp -r e-puck2_main-processor/Project_template fm_project
     cp fm_controller.h fm_controller.c fm_executor.h fm_executor.c fm_epuck2.h fm_epuck2.c fm_project/

   (or copy the six files into e-puck2_main-processor/src/ and call fm_epuck2_start from the
   firmware's main.c instead of running its selector demos, which drive the motors too).

3. In fm_project/Makefile, list the sources after main.c:

     CSRC += ./main.c ./fm_controller.c ./fm_executor.c ./fm_epuck2.c

   and after its last line (include $(GLOBAL_PATH)/Makefile) compile the kit's files with
   doubles as written and unfused:

     $(addprefix $(BUILDDIR)/obj/,fm_controller.o fm_executor.o fm_epuck2.o): \
         CFLAGS += -fno-single-precision-constant -ffp-contract=off

   The firmware's ChibiOS rules (os/common/ports/ARMCMx/compilers/GCC/rules.mk) add
   -fsingle-precision-constant to every file when USE_FPU is set, as it is: every floating
   constant would become a float and the network's weights lose their last bits
   (fm_executor.c and fm_epuck2.c refuse to compile then: "negative width in bit-field").

4. In fm_project/main.c, start the bus, the motors and the sensors, calibrate in open space,
   then the controller:

     #include "motors.h"
     #include "sensors/proximity.h"
     #include "fm_epuck2.h"

     messagebus_t bus;
     MUTEX_DECL(bus_lock);
     CONDVAR_DECL(bus_condvar);
     parameter_namespace_t parameter_root;

     int main(void)
     {
         halInit();
         chSysInit();
         mpu_init();
         messagebus_init(&bus, &bus_lock, &bus_condvar);
         motors_init();
         proximity_start(FAST_UPDATE);
         calibrate_ir();            /* about 1 s: nothing within 10 cm of the robot */
         fm_epuck2_start();
         while (1) {
             chThdSleepMilliseconds(1000);
         }
     }

   (keep the template's __stack_chk_guard and __stack_chk_fail). Build with `make` in
   fm_project and flash as GCtronic's documentation says.

Units
  readings   get_calibrated_prox(i) counts, times FM_EPUCK2_PROX_TO_READING (1: the robot file
             gives the e-puck2's readings in these counts), at most @RMAX@; network input k
             reads firmware sensor IR k (IR0 front-right, then clockwise): PROX_OF_INPUT in
             fm_epuck2.c
  wheels     steps: 1000 per wheel turn, wheel diameter 40 mm (GCtronic's driver; 41 mm in
             other sources: measure yours and set FM_EPUCK2_WHEEL_DIAMETER_MM), so
             @STEPS_PER_MM@ steps per mm; speeds in steps/s, clamped to MOTOR_SPEED_LIMIT 1100
             (@SPEED_LIMIT_MM@ mm/s)
  period     FM_EPUCK2_PERIOD_MS = @PERIOD_MS@ ms (trial.dt), kept by chThdSleepUntilWindowed

Motion `@MOTION@`: @MOTION_TEXT@
"#;

/// What the README says of the motion model.
pub(crate) fn motion_text(c: &ExportedController) -> String {
    let r = c.robot();
    match c.motion {
        Motion::Actions => format!(
            "the robot was evolved executing the label of each step, and so does\n\
             fm_executor.c: straight drives both wheels {} mm (v_max * dt), left30/right30 turn\n\
             {} degrees on the spot (each wheel {} mm), turn180 half a turn (each wheel {} mm),\n\
             measured by the wheel positions; the network runs again when the action is done. A\n\
             straight step takes one period; a turn takes longer on the robot than in the\n\
             simulator, where it takes one step.",
            decimal(r.straight_step()),
            decimal(r.turn_deg),
            decimal(r.turn_deg.to_radians() * r.wheel_base / 2.0),
            decimal(std::f64::consts::PI * r.wheel_base / 2.0),
        ),
        Motion::Wheels => "the network runs every period and the wheels get its speeds\n\
             (2m - 1) * v_max directly (fm_executor.c)."
            .to_string(),
    }
}

/// The e-puck2 kit of `c`: `fm_controller.h/.c`, `fm_executor.h/.c`, `fm_epuck2.h/.c`,
/// `golden.csv`, `fm_golden.c` and `README.txt`. The robot's values (`c.robot()`) go into
/// the files as they are; the caller checks that the robot is the e-puck2.
pub fn epuck2_kit(c: &ExportedController) -> Kit {
    let r = c.robot();
    let n = c.shape().inputs();
    let steps_per_mm = EPUCK2_STEPS_PER_TURN / (std::f64::consts::PI * EPUCK2_WHEEL_DIAMETER_MM);
    let period_ms = (r.dt * 1000.0).round().max(1.0);
    let stack = 1024 + 16 * (n + c.shape().hidden());
    let subst = |template: &str| {
        let mut s = template.to_string();
        for (key, value) in [
            ("@PROVENANCE@", crate::provenance()),
            ("@ROBOT@", r.name.clone()),
            ("@N@", n.to_string()),
            ("@H@", c.shape().hidden().to_string()),
            ("@RMAX_HEX@", hex_double(r.reading_max)),
            ("@RMAX@", decimal(r.reading_max)),
            ("@VMAX@", decimal(r.v_max)),
            ("@WHEEL_BASE@", decimal(r.wheel_base)),
            ("@PERIOD_S@", decimal(r.dt)),
            ("@PERIOD_MS@", format!("{period_ms}")),
            ("@STACK@", stack.to_string()),
            ("@STEPS_PER_MM@", decimal(steps_per_mm)),
            (
                "@SPEED_LIMIT_MM@",
                decimal(f64::from(EPUCK2_MOTOR_SPEED_LIMIT) / steps_per_mm),
            ),
            ("@MOTION@", motion_name(c.motion).to_string()),
            ("@MOTION_TEXT@", motion_text(c)),
            (
                "@PROX_OF_INPUT@",
                (0..n).map(|k| k.to_string()).collect::<Vec<_>>().join(", "),
            ),
        ] {
            s = s.replace(key, &value);
        }
        s
    };
    let layer = [
        KitFile::text("fm_epuck2.h", subst(HEADER)),
        KitFile::text("fm_epuck2.c", subst(SOURCE)),
    ];
    c_kit(
        c,
        layer,
        subst(README),
        "then build it into GCtronic's e-puck2_main-processor firmware as README.txt says (fm_epuck2_start() after proximity_start, calibrate_ir and motors_init)",
    )
}

/// A kit in C: the generic network, the actions executor, the robot's own `layer` (a header and
/// a source), the golden vectors and their replay, the `readme`; its notes say how to check the
/// golden vectors, then `next`.
pub(crate) fn c_kit(
    c: &ExportedController,
    layer: [KitFile; 2],
    readme: String,
    next: &str,
) -> Kit {
    let mut files = controller_files(c);
    files.extend(executor::files(c));
    files.extend(layer);
    files.extend(golden::files(c));
    files.push(KitFile::text("README.txt", readme));
    Kit {
        files,
        notes: vec![
            "check the network on this computer: cc -std=c99 -O2 -ffp-contract=off -o fm_golden fm_golden.c fm_controller.c && ./fm_golden golden.csv".into(),
            next.into(),
        ],
    }
}

/// `actions` or `wheels`, as a config writes it.
pub(crate) fn motion_name(motion: Motion) -> &'static str {
    match motion {
        Motion::Actions => "actions",
        Motion::Wheels => "wheels",
    }
}

/// The generic `fm_controller.h` and `fm_controller.c` of `c`, as kit files.
pub(crate) fn controller_files(c: &ExportedController) -> Vec<KitFile> {
    let sources = c.c();
    vec![
        KitFile::text(super::CSources::HEADER_NAME, sources.header),
        KitFile::text(super::CSources::SOURCE_NAME, sources.source),
    ]
}
