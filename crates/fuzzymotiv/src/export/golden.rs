//! Golden vectors of a deployment kit (`golden.csv`, `fm_golden.c`): sensor readings recorded
//! in the simulator with the motor outputs and action labels the controller gives for them, as
//! exact hexadecimal doubles, and a host program that replays them through the kit's
//! `fm_controller.c` and requires every output bit for bit.

use super::c::hex_double;
use super::{ExportedController, KitFile};
use crate::random::rng::rng_from_seed;
use crate::simulation::controller::{Controller, Mlp};
use crate::simulation::robot::Action;
use crate::simulation::room::Room;
use crate::simulation::sensor::Readings;
use crate::simulation::trial::{Arena, run_trial};

/// The trials the readings are recorded in: room, sensor and wheel noise, seed. Noise 0 gives
/// whole-number readings, 0.06 (the paper's) readings that are not.
const TRIALS: [(&str, f64, u64); 3] = [("H", 0.0, 1), ("L", 0.06, 2), ("square", 0.06, 3)];

/// The most vectors taken from one trial (its first steps with a wall in sight).
const PER_TRIAL: usize = 64;

/// One golden vector: readings in the robot's scale, the motor outputs and the label.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Golden {
    /// The readings, 0..`reading_max` of the kit's robot.
    pub readings: Vec<f64>,
    /// mL, mR.
    pub motors: [f64; 2],
    /// The step's label as the exported C gives it.
    pub action: Action,
}

/// The label the exported C gives `motors` (`fm_controller_step_readings`): with `actions`
/// motion the commanded speeds' fractions of v_max, with `wheels` motion the motor outputs.
pub(crate) fn label_of(c: &ExportedController, motors: [f64; 2]) -> Action {
    let speeds = motors.map(|m| (2.0 * m - 1.0) * c.v_max);
    c.motion.label(motors, speeds, c.v_max, c.tolerance)
}

/// The golden vectors of `c`: all readings 0 (open floor), then readings recorded by the
/// experiment's robot (its robot file, body and motion) driven by `c`'s network in [`TRIALS`]
/// (the first executed steps with some reading above 0), in the kit robot's scale (reading ×
/// the kit's reading_max / the simulated robot's: the same when the kit is the run's robot),
/// each with the network's outputs for them and their label. Empty when the network's inputs
/// are not the simulator's sensors.
pub(crate) fn vectors(c: &ExportedController) -> Vec<Golden> {
    let Ok(mut mlp) = Mlp::from_genome(c.shape, &c.weights) else {
        return Vec::new();
    };
    let simulated = c.trial.robot().spec();
    if simulated.sensors() != c.shape.inputs() {
        return Vec::new();
    }
    let scale = c.robot.reading_max / simulated.reading_max();
    // Open floor first: every reading 0 (the network's outputs at rest).
    let mut out = vec![golden_of(c, &mut mlp, Readings::zeros(c.shape.inputs()))];
    for (room, noise, seed) in TRIALS {
        let params = c.trial.with_noise(noise);
        let room = Room::builtin(room).expect("a built-in room");
        let tr = run_trial(
            &Arena::new(room, &params),
            &mut mlp,
            &mut rng_from_seed(seed),
        );
        let seen = (0..tr.len()).filter(|&t| !tr.idle[t] && tr.sensors[t].iter().any(|&v| v > 0.0));
        for t in seen.take(PER_TRIAL) {
            let mut readings = tr.sensors[t];
            if scale != 1.0 {
                for v in readings.iter_mut() {
                    *v = (*v * scale).min(c.robot.reading_max);
                }
            }
            out.push(golden_of(c, &mut mlp, readings));
        }
    }
    out
}

/// The vector of `readings` (the robot's scale): the inputs as `fm_controller_step_readings`
/// makes them, the network's outputs and their label.
fn golden_of(c: &ExportedController, mlp: &mut Mlp, readings: Readings) -> Golden {
    let mut inputs = readings;
    for v in inputs.iter_mut() {
        if *v != 0.0 {
            *v /= c.robot.reading_max;
        }
    }
    let motors = mlp.step(&inputs);
    Golden {
        readings: readings.to_vec(),
        motors,
        action: label_of(c, motors),
    }
}

/// `golden.csv`: a comment, the header `ir0,…,m_left,m_right,action`, then one vector a line
/// (readings and motors as exact C99 hexadecimal doubles, the label by name).
pub(crate) fn csv(c: &ExportedController) -> String {
    let n = c.shape.inputs();
    let mut text = format!(
        "# golden vectors of this controller, written by {}: the readings (the robot's scale,\n\
         # 0..{}) recorded in the simulator, the motor outputs the controller gives for them and\n\
         # the action label, as exact hexadecimal doubles (C99 strtod reads them). fm_golden.c\n\
         # replays them through fm_controller.c and requires every output bit for bit.\n",
        crate::provenance(),
        c.robot.reading_max
    );
    let names: Vec<String> = (0..n).map(|k| format!("ir{k}")).collect();
    text.push_str(&format!("{},m_left,m_right,action\n", names.join(",")));
    for g in vectors(c) {
        let cells: Vec<String> = (g.readings.iter().chain(&g.motors))
            .map(|&v| hex_double(v))
            .collect();
        text.push_str(&format!("{},{}\n", cells.join(","), g.action.label()));
    }
    text
}

/// The host program that replays `golden.csv`.
const REPLAY: &str = r#"/* fm_golden.c: replays golden.csv through fm_controller.c on the host and requires every
 * motor output bit for bit and every action label. Exported by @PROVENANCE@.
 *
 *   cc -std=c99 -O2 -ffp-contract=off -o fm_golden fm_golden.c fm_controller.c
 *   ./fm_golden golden.csv
 *
 * prints how many vectors were replayed and how many differ (each difference on its own line);
 * exits 0 when none differs, 1 when one does (or the file holds none), 2 on a malformed file. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_controller.h"

static const char *const LABELS[4] = {"straight", "left30", "right30", "turn180"};

/* Reads `count` comma-terminated doubles from *p into out; 0 when one is missing. */
static int read_doubles(char **p, double *out, int count)
{
    int i;
    for (i = 0; i < count; i++) {
        char *end;
        out[i] = strtod(*p, &end);
        if (end == *p || *end != ',') {
            return 0;
        }
        *p = end + 1;
    }
    return 1;
}

int main(int argc, char **argv)
{
    char line[2048];
    long lineno = 0, vectors = 0, differ = 0;
    FILE *f;
    if (argc != 2) {
        fprintf(stderr, "usage: %s golden.csv\n", argv[0]);
        return 2;
    }
    f = fopen(argv[1], "r");
    if (!f) {
        perror(argv[1]);
        return 2;
    }
    while (fgets(line, sizeof line, f)) {
        double ir[FM_INPUTS], want[2], got[2];
        char *p = line;
        int action;
        lineno++;
        if (line[0] == '#' || strncmp(line, "ir0,", 4) == 0) {
            continue;
        }
        line[strcspn(line, "\r\n")] = '\0';
        if (!read_doubles(&p, ir, FM_INPUTS) || !read_doubles(&p, want, 2)) {
            fprintf(stderr, "%s:%ld: expected %d readings, m_left, m_right, action\n", argv[1],
                    lineno, FM_INPUTS);
            fclose(f);
            return 2;
        }
        fm_controller_step_readings(ir, got, &action);
        vectors++;
        if (memcmp(got, want, sizeof got) != 0 || strcmp(LABELS[action], p) != 0) {
            differ++;
            printf("line %ld: got %a %a %s, want %a %a %s\n", lineno, got[0], got[1],
                   LABELS[action], want[0], want[1], p);
        }
    }
    fclose(f);
    printf("%ld golden vectors, %ld differ\n", vectors, differ);
    return differ == 0 && vectors > 0 ? 0 : 1;
}
"#;

/// `golden.csv` and `fm_golden.c` for `c`.
pub(crate) fn files(c: &ExportedController) -> Vec<KitFile> {
    vec![
        KitFile::text("golden.csv", csv(c)),
        KitFile::text(
            "fm_golden.c",
            REPLAY.replace("@PROVENANCE@", &crate::provenance()),
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulation::controller::MlpShape;
    use crate::simulation::robot::{Motion, RawRobot, Robot};
    use crate::simulation::trial::TrialParams;

    fn controller(motion: Motion) -> ExportedController {
        let shape = MlpShape::default();
        let genome: Vec<f64> = (0..shape.genome_len())
            .map(|i| 3.0 * (i as f64 * 1.7).sin())
            .collect();
        let robot = RawRobot {
            motion,
            ..RawRobot::default()
        };
        let params = TrialParams::default()
            .with_robot(Robot::from_raw(&robot, crate::simulation::RobotSpec::khepera()).unwrap());
        ExportedController::new(shape, &genome, &params).unwrap()
    }

    /// For the Khepera (the simulator's own scale) the golden motor outputs are the ones the
    /// simulator recorded for the same readings, and at noise 0 the labels are its actions.
    #[test]
    fn khepera_golden_vectors_are_the_simulators_recorded_steps() {
        for motion in [Motion::Actions, Motion::Wheels] {
            let c = controller(motion);
            let golden = vectors(&c);
            let body = Robot::from_raw(
                &RawRobot {
                    motion,
                    ..RawRobot::default()
                },
                crate::simulation::RobotSpec::khepera(),
            )
            .unwrap();
            let params = TrialParams::default().with_noise(0.0).with_robot(body);
            let mut mlp = Mlp::from_genome(c.shape, &c.weights).unwrap();
            let room = Room::builtin("H").unwrap();
            let tr = run_trial(&Arena::new(room, &params), &mut mlp, &mut rng_from_seed(1));
            let mut matched = 0;
            for g in &golden {
                let found = (0..tr.len())
                    .find(|&t| !tr.idle[t] && *tr.sensors[t] == *g.readings.as_slice());
                if let Some(t) = found {
                    assert_eq!(tr.motors[t].map(f64::to_bits), g.motors.map(f64::to_bits));
                    assert_eq!(tr.actions[t], g.action, "{motion:?} step {t}");
                    matched += 1;
                }
            }
            assert!(matched > 10, "{motion:?}: {matched} of {}", golden.len());
            assert!(golden.len() > 100, "{}", golden.len());
            assert!(golden.iter().any(|g| g.readings.iter().all(|&v| v == 0.0)));
        }
    }

    /// Readings of another robot's scale are the simulator's scaled, never above its maximum.
    #[test]
    fn golden_readings_are_in_the_robots_scale() {
        let mut c = controller(Motion::Actions);
        c.robot.reading_max = 4095.0;
        let golden = vectors(&c);
        let top = golden
            .iter()
            .flat_map(|g| g.readings.iter().copied())
            .fold(0.0, f64::max);
        assert!(top > 1023.0 && top <= 4095.0, "{top}");
        let text = csv(&c);
        assert_eq!(
            text.lines().filter(|l| !l.starts_with('#')).count(),
            golden.len() + 1
        );
        assert!(text.contains("\nir0,ir1,ir2,ir3,ir4,ir5,ir6,ir7,m_left,m_right,action\n"));
    }
}
