//! The kit's `README.txt`: how to load and check the program, its units, its quantisation and
//! its measured size, step counts and agreement, with the Aseba and Thymio facts it rests on
//! quoted (the user has not got our repository).

use super::program::{AeslProgram, UM_PER_UNIT};
use super::{AESL_NAME, GOLDEN_NAME, Golden};
use crate::export::ExportedController;
use crate::simulation::robot::Motion;

fn header(c: &ExportedController, p: &AeslProgram) -> String {
    let r = c.robot();
    let motion = match c.motion {
        Motion::Wheels => "wheels (the network sets the wheel speeds every control period)",
        Motion::Actions => "actions (the network chooses an action; the robot executes it)",
    };
    format!(
        "fuzzymotiv controller for the Thymio II\n\
         =======================================\n\n\
         Exported by {}.\n\
         Network: {}-{}-2 logistic MLP (inputs: prox.horizontal[0..{}]; outputs: left, right motor).\n\
         Evolved for robot \"{}\": {} sensors, reading_max {}, v_max {} mm/s, wheel base {} mm,\n\
         control period dt {} s, turns of {} degrees. Motion: {}.\n\
         Action tolerance: {}.\n\n",
        crate::provenance(),
        p.n,
        p.h,
        p.n - 1,
        r.name,
        r.sensors,
        r.reading_max,
        r.v_max,
        r.wheel_base,
        r.dt,
        r.turn_deg,
        motion,
        c.tolerance
    )
}

const LOADING: &str = "\
Files
-----
@AESL@   the Aseba program (node \"thymio-II\"), with its constants and events
README.txt           this file
@GOLDEN@           readings, the float network's outputs and this program's (see Checking)

Loading
-------
Aseba Studio: connect the Thymio II (USB cable or wireless dongle), start Aseba Studio,
choose the robot, File > Open @AESL@, then Load and Run. The program starts at once.

asebahttp (Aseba's HTTP bridge; needs a UTF-8 locale other than C.UTF-8, e.g.
LC_ALL=en_US.UTF-8, or it aborts with \"locale::facet::_S_create_c_locale name not valid\"):

    asebahttp -p 3000 \"ser:name=Thymio-II\"        # a real robot on USB
    asebahttp -p 3000 \"tcp:localhost;33333\"       # a Thymio in asebaplayground
    curl -X PUT --data-binary @@AESL@ http://localhost:3000/nodes/thymio-II

(asebahttp compiles the program against the robot's own description.) Read a variable with
`curl http://localhost:3000/nodes/thymio-II/VARIABLE`, e.g. fm_m, fm_tgt, fm_act, fm_count.

Checking (golden vectors)
-------------------------
The event fm_test stops the robot and runs the network once on the readings given as its
arguments; fm_run resumes. For a row of @GOLDEN@ (readings r0..):

    curl http://localhost:3000/nodes/thymio-II/fm_test/r0/r1/r2/r3/r4/r5/r6
    curl http://localhost:3000/nodes/thymio-II/fm_m      # = fixed_mL_q12, fixed_mR_q12
    curl http://localhost:3000/nodes/thymio-II/fm_tgt    # = fixed_target_left, _right
    curl http://localhost:3000/nodes/thymio-II/fm_act    # = fixed_action
    curl http://localhost:3000/nodes/thymio-II/fm_run

(in Aseba Studio: emit fm_test with the readings from the events panel and look at the
variables). Columns: case; r0.. the readings; float_mL, float_mR the float network's motor
outputs (0..1); float_target_left, _right its wheel targets (units, not rounded);
float_action; fixed_mL_q12, fixed_mR_q12 the program's fm_m (4096 = 1.0); fixed_target_left,
_right its fm_tgt; fixed_action its fm_act. The readings are first those the simulator
recorded with this robot driven by this controller (open floor, then the first steps with a
wall in sight in three rooms, rounded to whole readings), then probes: none, each sensor alone
at 1/4, 1/2, 3/4 and all of reading_max, all at 1/2 and at reading_max, and 64 pseudo-random
wall-like sets (fixed seed). The fixed_* columns must be equal exactly (the VM's integer arithmetic is the
same on every Thymio); the float_* columns are the evolved network in double precision, the
fixed-point program approximates them within the figures below. fixed_target_* assume the
default FM_UM_PER_UNIT = @UM@. Actions: 0 straight, 1 left30, 2 right30, 3 turn180.

";

fn speed_and_loop(c: &ExportedController) -> String {
    let r = c.robot();
    let mut s = format!(
        "Speeds and units\n\
         ----------------\n\
         The wheel targets motor.left.target / motor.right.target are (2m - 1) * v_max mm/s divided\n\
         by the speed of one target unit, the constant FM_UM_PER_UNIT (micrometres per second per\n\
         unit; edit it in the constants panel or the .aesl file). Default {UM_PER_UNIT}, the simulator's\n\
         conversion: aseba/targets/playground/robots/thymio2/Thymio2.cpp (aseba-community/aseba,\n\
         commit 4c89da4c) sets \"leftSpeed = double(variables.motorLeftTarget) * 16.6 / 500.\"\n\
         (cm/s), i.e. 500 units = 16.6 cm/s. The Thymio documentation says instead \"500\n\
         approximately corresponds to a linear speed of 20 cm/s\" (docs/en/thymio-api.rst), i.e.\n\
         400, and real robots differ (each has its own motor calibration). Measure yours: run\n\
         motor.left.target = motor.right.target = 200 for 10 s, measure the distance D in mm;\n\
         FM_UM_PER_UNIT = D * 1000 / 2000. With the default, v_max = {} mm/s is a target of {:.0}.\n\
         The documented target range is -500..500; the firmware accepts -1000..1000.\n\
         Readings: prox.horizontal[i] is sensor i as the simulator numbers them (0 front left,\n\
         1 front middle-left, 2 front middle, 3 front middle-right, 4 front right, 5 back left,\n\
         6 back right; docs/en/thymio-api.rst), updated at 10 Hz; a reading above reading_max\n\
         = {} counts as reading_max.\n\n",
        r.v_max,
        r.v_max * 1000.0 / UM_PER_UNIT as f64,
        r.reading_max
    );
    s += "Control loop\n------------\n";
    s += &match c.motion {
        Motion::Wheels => format!(
            "timer.period[0] = FM_PERIOD_MS = {} ms (dt): at every timer0 event the program copies\n\
             prox.horizontal, runs the network and sets both wheel targets.\n\n",
            (r.dt * 1000.0).round()
        ),
        Motion::Actions => format!(
            "At a prox event (10 Hz: fresh readings) when no action is running, the program runs the\n\
             network and starts its action: straight = v_max * dt = {:.1} mm forward (FM_STRAIGHT_DMM,\n\
             in 0.1 mm), left30 / right30 = rotate on the spot by +/-{} degrees (each wheel travels\n\
             wheel_base/2 * angle = FM_TURN_DMM), turn180 = rotate by 180 degrees (FM_TURN180_DMM),\n\
             wheels at the v_max target. The action ends by odometry: at the 100 Hz motor event each\n\
             wheel's |motor.*.speed| (target units) is added up for 10 ms, and the wheels stop when\n\
             their mean travel reaches the action's; the next prox event then runs the network again\n\
             (a pause of at most 100 ms, so that the network sees readings taken after the action).\n\
             Why odometry rather than timed moves: motor.*.speed is the speed the wheels actually\n\
             have, so acceleration and a robot slower than its target are accounted for; a timed\n\
             move assumes the target speed is reached at once. Both rest on FM_UM_PER_UNIT. The\n\
             odometer counts in steps of FM_UM_PER_UNIT/6250 mm; a wheel may overrun by one 10 ms\n\
             tick (v_max * 10 ms = {:.1} mm) and by the time it takes to stop. A robot whose wheels\n\
             cannot turn (pushing a wall: the measured speed stays near 0) ends the action after\n\
             FM_TIMEOUT_TICKS ticks of 10 ms (three times the longest action at v_max).\n\n",
            r.straight_step(),
            r.turn_deg,
            r.v_max * 0.01
        ),
    };
    s
}

const MONITORING: &str = "\
Monitoring
----------
Set fm_monitor to 1 (curl http://localhost:3000/nodes/thymio-II/fm_monitor/1, or in Aseba
Studio) and the program emits the event fm_state at each decision: the N readings the network
saw, then the left and right wheel targets it set, from the same handler (so they belong
together). asebahttp streams them: curl -N http://localhost:3000/nodes/thymio-II/events/fm_state
(lines \"data: fm_state r0 ... left right\"). fm_count counts the network's evaluations.

";

const QUANTISATION: &str = "\
Fixed point (Aseba has only signed 16-bit integers)
---------------------------------------------------
The Aseba VM (aseba/vm/vm.c, natives.c) computes + - * << >> in C int and keeps 16 bits
(two's-complement wrap, no saturation), / truncates toward 0, x / 2^k by a constant is
compiled to x >> k (which rounds down), math.muldiv(a, b, c) = (int16)((int32 a*b) / c)
and math.dot(r, A, B, n) adds the products in 32 bits and shifts the sum right by n bits.
The program:
- inputs: the readings themselves, clamped to 0..reading_max (math.clamp): reading_max stands
  for 1.0, so no input is rounded; x[0] = reading_max is the bias input.
- weights: per unit (each hidden unit and each output), u = round(w * 2^(e+12) / one), where
  one = reading_max for the hidden units and 4096 for the outputs (whose inputs, the hidden
  activations, are Q12: 4096 = 1.0), with the largest e <= 20 such that every |u| <= 32767 and
  sum(|u|) * one < 2^31 (the 32-bit accumulator cannot overflow). A very large weight lowers
  its own unit's e: the unit's small weights lose precision instead of wrapping.
- sums: math.dot(s, u, x, shift) with shift = e + 12 - L (fm_sh) gives the sum in Q L,
  L = 10 (1024 = 1.0) unless the unit's largest possible sum would not fit 16 bits, then the
  largest L that fits; clamped to +/-8.0 (fm_lo, fm_hi) and brought to Q10 (x fm_up =
  2^(10-L)).
- logistic: a table of round(4096 / (1 + exp(-i/16))) - 2048, i = 0..128 (fm_t), linear
  interpolation between entries, logistic(-u) = 1 - logistic(u): hidden activations and motor
  outputs m in Q12. (Interpolation error < 5e-5, table rounding 1.2e-4, |sum| > 8 saturates at
  4095/4096.)
- wheel targets: (2m - 1) * v_max with two math.muldiv: p = (2m - 4096) * FM_V_MAX_DMM / 4096
  (0.1 mm/s), target = p * 100 / FM_UM_PER_UNIT.
- action label: a = 2m - 4096 per wheel (Q12); both < 0: turn180; a_R - a_L > FM_TOLERANCE
  = floor(tolerance * 4096): left30; a_L - a_R > FM_TOLERANCE: right30; else straight (the
  float rule on s = 2m - 1 with the same strict comparisons).

";

fn measured(g: Option<&Golden>) -> String {
    let Some(g) = g else {
        return "Measured figures: not available (the program could not be interpreted).\n".into();
    };
    let (dm, dt, labels) = g.agreement();
    format!(
        "Size and time (measured with fuzzymotiv's interpreter of Aseba's 16-bit semantics)\n\
         ----------------------------------------------------------------------------------\n\
         variables: {} words of the Thymio II's 512 (VM_VARIABLES_FREE_SPACE 512,\n\
         aseba-target-thymio2 skel-usb-user.h).\n\
         bytecode: about {} words of 1534 (VM_BYTECODE_SIZE 766+768; estimated from the\n\
         instructions the compiler emits: 4 % above the real size of the 7-6-2 programs whose\n\
         bytecode was measured in asebaplayground; Aseba Studio shows the exact figure).\n\
         VM steps (instructions executed, estimated the same way): initialisation {}; an event\n\
         running the network at most {} (the simulator runs each event for at most 1000 steps:\n\
         \"AsebaVMRun(&vm, 1000)\", targets/playground/robots/thymio2/Thymio2.cpp, and a new\n\
         event kills the running one; the real firmware runs an event to its end,\n\
         \"AsebaVMRun(&vmState, 0xFFFF)\" in a loop, and starts the next one only then:\n\
         aseba-target-thymio2 skel-usb.c, commit eb408bdd).\n\n\
         Agreement with the float network on the {} rows of {GOLDEN_NAME}: motor outputs within\n\
         {:.5} (of the range 0..1), wheel targets within {:.2} units, action labels equal in\n\
         {:.1} % of the rows.\n",
        g.user_words,
        g.bytecode_words,
        g.init_steps,
        g.max_steps,
        g.rows.len(),
        dm,
        dt,
        100.0 * labels
    ) + &g
        .over_limits()
        .iter()
        .map(|w| format!("{w}\n"))
        .collect::<String>()
}

/// The README of `c`'s kit (`p` its program, `g` its golden vectors if they could be made).
pub(super) fn readme(c: &ExportedController, p: &AeslProgram, g: Option<&Golden>) -> String {
    let loading = LOADING
        .replace("@AESL@", AESL_NAME)
        .replace("@GOLDEN@", GOLDEN_NAME)
        .replace("@UM@", &UM_PER_UNIT.to_string());
    let mut s =
        header(c, p) + &loading + &speed_and_loop(c) + MONITORING + QUANTISATION + &measured(g);
    s += "\nConstants of the program (.aesl <constant>s)\n--------------------------------------------\n";
    for (name, value) in &p.constants {
        s += &format!("{name} = {value}\n");
    }
    s
}
