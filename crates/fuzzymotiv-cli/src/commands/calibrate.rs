//! `fuzzymotiv calibrate`: bench measurements of a robot's IR sensors (CSV) → a sensor table
//! file for `trial.sensor_table`, and the readings' spread as the `trial.noise` estimate
//! ([`fuzzymotiv_pipeline::pipeline::calibrate`] over [`fuzzymotiv::simulation::calibrate`];
//! docs/guide/real-robot.md). This front parses the arguments and prints the spread.

use std::path::PathBuf;

use crate::console::{note, out, outln};
use fuzzymotiv::simulation::Calibration;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::FilesState;
use fuzzymotiv_pipeline::pipeline::calibrate::{calibration_table, write_table};

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
    let (c, table) = calibration_table(&args.measurements, &args.robot, "--robot")?;
    if args.out.as_os_str() == "-" {
        out!("{table}")?;
        return show(&c, false);
    }
    if write_table(&args.out, table, "--out", args.force)? == FilesState::Write {
        note!("wrote {}", args.out.display());
    } else {
        note!(
            "{} already holds this table; nothing to do",
            args.out.display()
        );
    }
    show(&c, true)
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
