//! `fuzzymotiv calibrate`: bench measurements of a robot's IR sensors (CSV) → a sensor table
//! file for `trial.sensor_table`, and the readings' spread as the `trial.noise` estimate
//! ([`fuzzymotiv::simulation::calibrate`]; docs/guide/real-robot.md).

use std::path::PathBuf;

use crate::console::{note, out, outln};
use fuzzymotiv::simulation::{Calibration, calibrate};
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::{FilesState, check_files, write_files};
use fuzzymotiv_pipeline::files::measurements::{field_error, read_measurements};

/// Arguments of `fuzzymotiv calibrate`.
#[derive(clap::Args)]
pub struct CalibrateArgs {
    /// Bench measurements: a CSV file with the columns sensor (0 to the robot's last: 0–7 on
    /// the Khepera), distance_mm and reading (0 to the robot's reading_max: 0–1023 on the
    /// Khepera), one row per reading, several readings per distance (other columns are ignored).
    #[arg(value_name = "MEASUREMENTS.csv")]
    pub measurements: PathBuf,
    /// The robot measured: a built-in robot (khepera, epuck2, thymio2) or a robot file; its
    /// sensor count and reading scale check the measurements.
    #[arg(long, value_name = "NAME|ROBOT.toml", default_value = "khepera")]
    pub robot: String,
    /// The sensor table file to write (TOML, for `trial.sensor_table`; `-`: standard output,
    /// and the spread per sensor and distance then goes to standard error).
    #[arg(long, value_name = "TABLE.toml")]
    pub out: PathBuf,
    /// Replace an existing file of that name that holds something else.
    #[arg(long)]
    pub force: bool,
}

/// Entry point of `fuzzymotiv calibrate`.
pub fn calibrate_command(args: CalibrateArgs) -> Result<(), CliError> {
    let source = args.measurements.display().to_string();
    let robot = fuzzymotiv_pipeline::files::inputs::load_robot(&args.robot, "--robot")?;
    let rows = read_measurements(&args.measurements)?;
    let c = calibrate(&rows, robot.scale()).map_err(|e| field_error(e.in_source(&source)))?;
    let header = format!(
        "Sensor table written by `fuzzymotiv calibrate` from {source}:\nper sensor and distance the median reading (rounded; neighbours pooled where medians rose\nwith distance). The simulator reads, per ray, the reading of the first distance at or beyond\nthe wall it sees, 0 beyond the last; name this file in a config as trial.sensor_table.\n{}Relative spread of the readings {:.4}: trial.noise = {:.3}.",
        robot_line(robot),
        c.relative_spread,
        c.noise
    );
    let table = c.table.to_toml(&header);
    if args.out.as_os_str() == "-" {
        out!("{table}")?;
        return show(&c, false);
    }
    let files = [(args.out.clone(), table.into_bytes())];
    if check_files(&files, "--out", args.force)? == FilesState::Write {
        write_files(&files)?;
        note!("wrote {}", args.out.display());
    } else {
        note!(
            "{} already holds this table; nothing to do",
            args.out.display()
        );
    }
    show(&c, true)
}

/// The header line naming the robot a table is for (none for the Khepera, whose tables were
/// written before robots were named).
fn robot_line(robot: &fuzzymotiv::simulation::RobotSpec) -> String {
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

/// The spread per sensor and distance (on standard output, else standard error), then the
/// noise estimate.
fn show(c: &Calibration, on_stdout: bool) -> Result<(), CliError> {
    let line = |text: String| {
        if on_stdout {
            outln!("{text}")
        } else {
            note!("{text}");
            Ok(())
        }
    };
    line("sensor,distance_mm,readings,median,mean,std,std_over_mean".into())?;
    for s in &c.spread {
        let rel = s.relative().map_or(String::new(), |r| format!("{r:.4}"));
        line(format!(
            "{},{},{},{},{:.2},{:.2},{rel}",
            s.sensor, s.distance_mm, s.count, s.median, s.mean, s.std
        ))?;
    }
    for line in &c.notes {
        note!("note: {line}");
    }
    note!(
        "relative spread (sum of std / sum of means over the sensors and distances): {:.4}",
        c.relative_spread
    );
    note!(
        "sensor noise estimate: trial.noise = {:.3} (the simulator multiplies each reading by U(1 − n, 1 + n), relative std n/√3)",
        c.noise
    );
    Ok(())
}
