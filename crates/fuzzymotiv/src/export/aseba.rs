//! The Thymio II deployment kit ([`thymio2_kit`]): an exported controller as an Aseba program
//! (`fm_controller.aesl`, for Aseba Studio or `asebahttp`) in 16-bit fixed point, with a
//! `README.txt` and golden vectors (`golden.csv`).
//!
//! The Aseba VM has one type, the signed 16-bit integer, with wrapping arithmetic, C division
//! and natives that multiply in 32 bits (`math.muldiv`, `math.dot`); a Thymio II gives a
//! program 512 words of variables and 1534 words of bytecode, and the simulator
//! (`asebaplayground`) cuts an event's handler after 1000 VM steps (docs/robots-sources.md
//! §2.2–2.3; the real firmware runs a handler to its end: aseba-target-thymio2 `skel-usb.c`,
//! `AsebaVMRun(&vmState, 0xFFFF)` in a loop). The network is quantised per unit so that every sum fits ([`quant`]), the
//! logistic is a 66-word table with linear interpolation, and the program
//! ([`program`]) is interpreted here ([`interp`], the language's 16-bit semantics) to write
//! its own outputs into `golden.csv` and to measure its size and step counts.
//!
//! Units: readings in the robot's own units (`prox.horizontal`, 0 … 4505 in Enki's model),
//! wheel targets in Thymio target units at `FM_UM_PER_UNIT` µm/s each (default 332, the
//! playground's 500 ↔ 16.6 cm/s), lengths in mm (0.1 mm in the program's constants), the
//! control period in ms.

pub(crate) mod interp;
pub(crate) mod program;
pub(crate) mod quant;

use super::ExportedController;
use super::kit::{Kit, KitFile};
use crate::simulation::robot::{Action, Motion};
use interp::{AsebaError, Machine};
use program::{AeslProgram, Source, THYMIO_PROX, UM_PER_UNIT};

/// The kit's program file.
pub const AESL_NAME: &str = "fm_controller.aesl";
/// The kit's golden vectors.
pub const GOLDEN_NAME: &str = "golden.csv";
/// The kit's instructions.
pub const README_NAME: &str = "README.txt";

/// The Thymio II kit of `c`: `fm_controller.aesl`, `README.txt`, `golden.csv`.
///
/// The network reads `prox.horizontal[0 … N−1]` (a controller with more than the Thymio's 7
/// inputs sees 0 on the others, and the notes say so).
pub fn thymio2_kit(c: &ExportedController) -> Kit {
    kit_reading(c, THYMIO_PROX)
}

/// Most network inputs the program takes: `fm_test` carries the readings as event arguments,
/// of which the Thymio II has 32 words.
pub(crate) const MAX_INPUTS: usize = 32;

/// The kit of `c` reading its sensors from `src`.
fn kit_reading(c: &ExportedController, src: Source) -> Kit {
    let n = c.robot().sensors;
    if n == 0 || n > MAX_INPUTS {
        let why = format!(
            "warning: no Thymio II program for a network of {n} inputs (1..={MAX_INPUTS} can be exported)"
        );
        return Kit {
            files: vec![KitFile {
                name: README_NAME.into(),
                contents: format!("{why}\n").into_bytes(),
            }],
            notes: vec![why],
        };
    }
    let prog = program::generate(c, src);
    let mut notes = vec![
        format!(
            "load {AESL_NAME} in Aseba Studio (File > Open, then Load and Run), or PUT it to asebahttp: see {README_NAME}"
        ),
        format!(
            "{GOLDEN_NAME}: readings, the float network's outputs and the program's, to check a robot with the fm_test event"
        ),
    ];
    if prog.n > src.len {
        notes.push(format!(
            "warning: the controller has {} inputs but the Thymio II has {} horizontal proximity sensors; inputs {}..{} read 0",
            prog.n,
            src.len,
            src.len,
            prog.n - 1
        ));
    }
    let golden = Golden::of(c, &prog, src);
    let golden_csv = match &golden {
        Ok(g) => {
            notes.extend(g.over_limits());
            g.csv(c)
        }
        Err(e) => {
            notes.push(format!("warning: the program could not be interpreted ({e}); {GOLDEN_NAME} has no fixed-point columns"));
            String::new()
        }
    };
    let readme = readme(c, &prog, golden.as_ref().ok());
    Kit {
        files: vec![
            KitFile {
                name: AESL_NAME.into(),
                contents: prog.aesl().into_bytes(),
            },
            KitFile {
                name: README_NAME.into(),
                contents: readme.into_bytes(),
            },
            KitFile {
                name: GOLDEN_NAME.into(),
                contents: golden_csv.into_bytes(),
            },
        ],
        notes,
    }
}

/// The target variables of the Thymio II the program uses, with their sizes (`src`'s length
/// for the readings).
fn target_vars(src: Source) -> Vec<(&'static str, usize)> {
    vec![
        ("event.args", 32),
        (src.var, src.len),
        ("motor.left.target", 1),
        ("motor.right.target", 1),
        ("motor.left.speed", 1),
        ("motor.right.speed", 1),
        ("timer.period", 2),
    ]
}

/// The code of an action label (0 straight, 1 left30, 2 right30, 3 turn180).
fn action_code(a: Action) -> i16 {
    match a {
        Action::Straight => 0,
        Action::Left30 => 1,
        Action::Right30 => 2,
        Action::Turn180 => 3,
    }
}

/// The float network's result for one set of readings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FloatOut {
    /// Motor outputs `[mL, mR]` ∈ [0, 1].
    pub m: [f64; 2],
    /// Wheel targets (Thymio units, at [`UM_PER_UNIT`]), not rounded.
    pub target: [f64; 2],
    /// Action code.
    pub action: i16,
}

/// The float controller on integer `readings`, as the simulator would label it.
pub(crate) fn float_out(c: &ExportedController, readings: &[i16]) -> FloatOut {
    let r = c.robot();
    let x: Vec<f64> = readings.iter().map(|&v| f64::from(v)).collect();
    let m = quant::float_step(
        c.weights(),
        r.sensors,
        c.shape().hidden(),
        &x,
        r.reading_max,
    );
    let s = m.map(|mi| 2.0 * mi - 1.0);
    let action = match c.motion {
        Motion::Actions => Action::from_speeds(
            (s[0] * c.v_max) / c.v_max,
            (s[1] * c.v_max) / c.v_max,
            c.tolerance,
        ),
        Motion::Wheels => Action::from_motors(m[0], m[1], c.tolerance),
    };
    FloatOut {
        m,
        target: s.map(|si| si * r.v_max * 1000.0 / UM_PER_UNIT as f64),
        action: action_code(action),
    }
}

/// The program's result for one set of readings (from its `fm_test` handler).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct FixedOut {
    /// `fm_m`: motor outputs in Q12.
    pub m: [i16; 2],
    /// `fm_tgt`: wheel targets.
    pub target: [i16; 2],
    /// `fm_act`: action code.
    pub action: i16,
    /// VM steps of the `fm_test` handler.
    pub steps: usize,
}

/// Run `fm_test` with `readings` on `m`.
pub(crate) fn fixed_out(m: &mut Machine, readings: &[i16]) -> Result<FixedOut, AsebaError> {
    m.set("event.args", readings)?;
    let steps = m.run_event("fm_test")?;
    let get = |name: &str, k: usize| m.get(name).and_then(|v| v.get(k).copied()).unwrap_or(0);
    Ok(FixedOut {
        m: [get("fm_m", 0), get("fm_m", 1)],
        target: [get("fm_tgt", 0), get("fm_tgt", 1)],
        action: get("fm_act", 0),
        steps,
    })
}

/// VM steps of the control handler (`timer0`, or `prox` with no action running) when the
/// sensors read `readings` (the program resumed first, as after `fm_run`).
fn control_event_steps(
    m: &mut Machine,
    motion: Motion,
    src: Source,
    readings: &[i16],
) -> Result<usize, AsebaError> {
    m.run_event("fm_run")?;
    let mut prox = vec![0; src.len];
    for (p, r) in prox.iter_mut().zip(readings) {
        *p = *r;
    }
    m.set(src.var, &prox)?;
    let control = match motion {
        Motion::Wheels => "timer0",
        Motion::Actions => {
            m.set("fm_busy", &[0])?;
            "prox"
        }
    };
    m.run_event(control)
}

/// The readings of `golden.csv`: those the simulator recorded with the run's own robot
/// driven by the controller ([`crate::export::golden::vectors`]: open floor, then the first
/// steps with a wall in sight in three rooms), rounded to whole readings, then the probes
/// ([`probe_readings`]).
pub(crate) fn golden_readings(c: &ExportedController, n: usize, r_max: i16) -> Vec<Vec<i16>> {
    let recorded = crate::export::golden::vectors(c).into_iter().map(|g| {
        (g.readings.iter())
            .map(|v| v.round().clamp(0.0, f64::from(r_max)) as i16)
            .collect::<Vec<i16>>()
    });
    let mut rows: Vec<Vec<i16>> = recorded.filter(|r| r.len() == n).collect();
    rows.extend(probe_readings(n, r_max));
    rows
}

/// The probe readings of `golden.csv`: none, each sensor alone at ¼, ½, ¾ and all of
/// `reading_max`, all at ½ and at the maximum, and 64 pseudo-random wall-like sets (each sensor
/// seeing something with probability 0.4, at a uniform level), from a fixed seed.
pub(crate) fn probe_readings(n: usize, r_max: i16) -> Vec<Vec<i16>> {
    let mut rows = vec![vec![0; n]];
    for k in 0..n {
        for q in 1..=4 {
            let mut r = vec![0; n];
            r[k] = (i32::from(r_max) * q / 4) as i16;
            rows.push(r);
        }
    }
    rows.push(vec![r_max / 2; n]);
    rows.push(vec![r_max; n]);
    let mut rng = crate::random::rng_from_seed(20_261_207);
    for _ in 0..64 {
        rows.push(
            (0..n)
                .map(|_| {
                    let sees = crate::random::uniform01(&mut rng) < 0.4;
                    let level = crate::random::uniform01(&mut rng) * f64::from(r_max);
                    if sees { level.round() as i16 } else { 0 }
                })
                .collect(),
        );
    }
    rows
}

/// The Thymio II's variable space for a program (words).
pub(crate) const VARIABLE_WORDS: usize = 512;
/// The Thymio II's bytecode space (words).
pub(crate) const BYTECODE_WORDS: usize = 1534;
/// The steps after which the simulator cuts an event's handler.
pub(crate) const EVENT_STEPS: usize = 1000;

/// The golden vectors and the program's measured figures.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Golden {
    rows: Vec<(Vec<i16>, FloatOut, FixedOut)>,
    /// Words of the program's variables.
    pub user_words: usize,
    /// Estimated bytecode words.
    pub bytecode_words: usize,
    /// VM steps of the initialisation.
    pub init_steps: usize,
    /// Most VM steps of one event running the network (`fm_test` or the control handler).
    pub max_steps: usize,
}

impl Golden {
    fn of(c: &ExportedController, prog: &AeslProgram, src: Source) -> Result<Golden, AsebaError> {
        let mut m = Machine::load(&prog.code, &prog.constants, &target_vars(src))?;
        let init_steps = m.run_init()?;
        let r_max = c.robot().reading_max.round().clamp(1.0, 32767.0) as i16;
        let mut rows = Vec::new();
        let mut control_steps = 0;
        for r in golden_readings(c, prog.n, r_max) {
            let fixed = fixed_out(&mut m, &r)?;
            rows.push((r.clone(), float_out(c, &r), fixed));
            control_steps = control_steps.max(control_event_steps(&mut m, c.motion, src, &r)?);
        }
        Ok(Golden {
            max_steps: rows
                .iter()
                .map(|r| r.2.steps)
                .max()
                .unwrap_or(0)
                .max(control_steps),
            rows,
            user_words: m.user_words(),
            bytecode_words: interp::bytecode_words(&prog.code, &prog.constants)?,
            init_steps,
        })
    }

    /// Warnings for each of the Thymio II's limits the program exceeds.
    pub(crate) fn over_limits(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.user_words > VARIABLE_WORDS {
            out.push(format!(
                "warning: the program needs {} words of variables, more than the Thymio II's {VARIABLE_WORDS}: use fewer hidden units",
                self.user_words
            ));
        }
        if self.bytecode_words > BYTECODE_WORDS {
            out.push(format!(
                "warning: the program needs about {} words of bytecode, more than the Thymio II's {BYTECODE_WORDS}: use fewer hidden units",
                self.bytecode_words
            ));
        }
        if self.max_steps.max(self.init_steps) >= EVENT_STEPS {
            out.push(format!(
                "warning: one network evaluation takes about {} VM steps (initialisation {}); asebaplayground cuts an event after {EVENT_STEPS} (a real Thymio II runs it to its end): use fewer hidden units to run it in the simulator",
                self.max_steps, self.init_steps
            ));
        }
        out
    }

    /// Largest |fixed − float| over the rows: motor output (fraction of 1) and wheel target
    /// (units); and the share of rows whose action labels agree.
    pub(crate) fn agreement(&self) -> (f64, f64, f64) {
        let mut dm: f64 = 0.0;
        let mut dt: f64 = 0.0;
        let mut same = 0;
        for (_, f, q) in &self.rows {
            for o in 0..2 {
                dm = dm.max((f64::from(q.m[o]) / f64::from(quant::ONE) - f.m[o]).abs());
                dt = dt.max((f64::from(q.target[o]) - f.target[o]).abs());
            }
            same += usize::from(f.action == q.action);
        }
        (dm, dt, same as f64 / self.rows.len().max(1) as f64)
    }

    fn csv(&self, c: &ExportedController) -> String {
        let n = c.robot().sensors;
        let mut s: String = (0..n).map(|k| format!("r{k},")).collect();
        s = format!(
            "case,{s}float_mL,float_mR,float_target_left,float_target_right,float_action,\
             fixed_mL_q12,fixed_mR_q12,fixed_target_left,fixed_target_right,fixed_action\n"
        );
        for (i, (r, f, q)) in self.rows.iter().enumerate() {
            let readings: String = r.iter().map(|v| format!("{v},")).collect();
            s += &format!(
                "{i},{readings}{:.6},{:.6},{:.3},{:.3},{},{},{},{},{},{}\n",
                f.m[0],
                f.m[1],
                f.target[0],
                f.target[1],
                f.action,
                q.m[0],
                q.m[1],
                q.target[0],
                q.target[1],
                q.action
            );
        }
        s
    }
}

mod readme;
use readme::readme;

#[cfg(test)]
mod playground;
#[cfg(test)]
mod tests;
