//! `fuzzymotiv calibrate`'s table: bench measurements of a robot's IR sensors (CSV) read and
//! calibrated ([`fuzzymotiv::simulation::calibrate`]) into a sensor table file for
//! `trial.sensor_table` with its header (the source, the robot, the noise estimate;
//! [`calibration_table`]), written through the output guard ([`write_table`]). The command line
//! prints the spread.

use std::path::Path;

use fuzzymotiv::simulation::{Calibration, RobotSpec, calibrate};

use crate::files::error::CliError;
use crate::files::guard::{FilesState, check_files, write_files};
use crate::files::inputs::load_robot;
use crate::files::measurements::{field_error, read_measurements};

/// The calibration of the measurements in `measurements` for the robot `robot` (a built-in
/// robot or a robot file, whose sensor count and reading scale check them), and the sensor
/// table file's text. Errors name the file, row and field (`robot_option` names the robot).
pub fn calibration_table(
    measurements: &Path,
    robot: &str,
    robot_option: &str,
) -> Result<(Calibration, String), CliError> {
    let source = measurements.display().to_string();
    let robot = load_robot(robot, robot_option)?;
    let rows = read_measurements(measurements)?;
    let c = calibrate(&rows, robot.scale()).map_err(|e| field_error(e.in_source(&source)))?;
    let header = format!(
        "Sensor table written by `fuzzymotiv calibrate` from {source}:\nper sensor and distance the median reading (rounded; neighbours pooled where medians rose\nwith distance). The simulator reads, per ray, the reading of the first distance at or beyond\nthe wall it sees, 0 beyond the last; name this file in a config as trial.sensor_table.\n{}Relative spread of the readings {:.4}: trial.noise = {:.3}.",
        robot_line(robot),
        c.relative_spread,
        c.noise
    );
    let table = c.table.to_toml(&header);
    Ok((c, table))
}

/// The header line naming the robot a table is for (none for the Khepera, whose tables were
/// written before robots were named).
fn robot_line(robot: &RobotSpec) -> String {
    if robot.name() == "khepera" {
        String::new()
    } else {
        format!(
            "For the robot {} ({} sensors, readings 0–{}).\n",
            robot.name(),
            robot.sensors(),
            robot.reading_max()
        )
    }
}

/// Writes the table to `out` through the output guard (another file there is kept unless
/// `force`; `out_option` names it): [`FilesState::Same`] when it already holds this table.
pub fn write_table(
    out: &Path,
    table: String,
    out_option: &str,
    force: bool,
) -> Result<FilesState, CliError> {
    let files = [(out.to_path_buf(), table.into_bytes())];
    let state = check_files(&files, out_option, force)?;
    if state == FilesState::Write {
        write_files(&files)?;
    }
    Ok(state)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bench's measurements become a table whose header names its source and noise and,
    /// for a robot other than the Khepera, the robot; written once, then found the same.
    #[test]
    fn measurements_become_a_table_that_names_its_source_and_is_written_once() {
        let csv = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../fuzzymotiv-cli/tests/fixtures/calibrate/bench.csv");
        let (c, table) = calibration_table(&csv, "khepera", "--robot").unwrap();
        assert!(
            table.contains(&format!("from {}:", csv.display())),
            "{table}"
        );
        assert!(
            table.contains(&format!("trial.noise = {:.3}", c.noise)),
            "{table}"
        );
        assert!(!table.contains("For the robot"), "{table}");
        let e = calibration_table(&csv, "no-such-robot", "--robot").unwrap_err();
        assert!(e.to_string().contains("--robot"), "{e}");
        let out = std::env::temp_dir().join(format!("fm-table-{}.toml", std::process::id()));
        let _ = std::fs::remove_file(&out);
        let write = |t: &str| write_table(&out, t.to_string(), "--out", false).unwrap();
        assert_eq!(write(&table), FilesState::Write);
        assert_eq!(write(&table), FilesState::Same);
        std::fs::remove_file(&out).unwrap();
    }
}
