//! `fuzzymotiv export`: an evolved controller for a real robot, as dependency-free C99 (its
//! motor outputs the simulator's bit for bit), a self-describing JSON document or an ONNX model
//! ([`fuzzymotiv::export`], [`fuzzymotiv_pipeline::records::export`]; docs/guide/real-robot.md).

use std::path::{Path, PathBuf};

use crate::console::note;
use crate::console::write_out_bytes;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::records::export::{
    ExportRequest, ExportTarget, KitTarget, build_export, export_controller,
};

/// What `--to` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Target {
    /// C99: `fm_controller.h` and `fm_controller.c` in the directory --out.
    C,
    /// The JSON document (format `fuzzymotiv-controller`) in the file --out.
    Json,
    /// The network as an ONNX model (double precision, inputs the raw readings) in the file
    /// --out.
    Onnx,
}

/// Which robot's files `--to c` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Robot {
    /// The e-puck2 kit: a ChibiOS thread for GCtronic's firmware, the actions executor, golden
    /// vectors and a README (the run's robot must be the e-puck2).
    Epuck2,
    /// The Thymio II kit (the run's robot must be the Thymio II).
    Thymio2,
    /// The kit for a Khepera-like robot: the actions executor and an I/O layer you fill in,
    /// golden vectors and a README (the run's robot must be the Khepera).
    Khepera,
    /// fm_controller.h and fm_controller.c alone, for any robot.
    Generic,
}

impl From<Robot> for KitTarget {
    fn from(robot: Robot) -> KitTarget {
        match robot {
            Robot::Epuck2 => KitTarget::Epuck2,
            Robot::Thymio2 => KitTarget::Thymio2,
            Robot::Khepera => KitTarget::Khepera,
            Robot::Generic => KitTarget::Generic,
        }
    }
}

/// Arguments of `fuzzymotiv export`.
#[derive(clap::Args)]
pub struct ExportArgs {
    /// A run directory (its best_genome.json and config.resolved.toml), or a genome file
    /// (best_genome.json: the robot's v_max, motion and action tolerance come from --config,
    /// else from the config.resolved.toml beside it, else from the built-in defaults).
    #[arg(value_name = "RUN_DIR|GENOME.json")]
    pub source: PathBuf,
    /// What to write.
    #[arg(long, value_enum)]
    pub to: Target,
    /// With `--to c`: the robot whose files to write, a deployment kit with a README
    /// [default: generic, fm_controller.h and fm_controller.c alone].
    #[arg(long, value_enum, value_name = "ROBOT")]
    pub target: Option<Robot>,
    /// Where: a directory for `c` (created if missing; receives fm_controller.h and
    /// fm_controller.c, or the --target kit's files), a file for `json` and `onnx` (`-`:
    /// standard output).
    #[arg(long, value_name = "PATH")]
    pub out: PathBuf,
    /// The config whose robot the controller drives [default: the run's own config].
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// With per-room training: the robot evolved in this room [default: the genome's main
    /// robot].
    #[arg(long, value_name = "ROOM")]
    pub room: Option<String>,
    /// Replace existing files of these names that hold something else (only regular files).
    #[arg(long)]
    pub force: bool,
}

/// Entry point of `fuzzymotiv export`.
pub fn export(args: ExportArgs) -> Result<(), CliError> {
    let req = ExportRequest {
        source: &args.source,
        config: args.config.as_deref(),
        room: args.room.as_deref(),
        to: match args.to {
            Target::C => ExportTarget::C,
            Target::Json => ExportTarget::Json,
            Target::Onnx => ExportTarget::Onnx,
        },
        target: args.target.map(KitTarget::from),
        out: &args.out,
        force: args.force,
        room_option: "--room",
        out_option: "--out",
        target_option: "--target",
    };
    if args.out.as_os_str() == "-" && args.to != Target::C {
        let built = build_export(&req)?;
        said(built.config.as_deref(), &built.notes);
        return write_out_bytes(built.single_file("--out")?);
    }
    let done = export_controller(&req)?;
    said(done.config.as_deref(), &done.notes);
    for path in &done.files {
        crate::console::outln!("{}", path.display())?;
    }
    if done.unchanged {
        note!(
            "{} already holds this export; nothing to do",
            args.out.display()
        );
    } else if let Some(robot) = args.target.filter(|&r| r != Robot::Generic) {
        note!(
            "wrote the {} kit of the {}-{}-2 controller of {}",
            KitTarget::from(robot).name(),
            done.inputs,
            done.hidden,
            done.genome.display()
        );
    } else {
        note!(
            "wrote the {}-{}-2 controller of {}",
            done.inputs,
            done.hidden,
            done.genome.display()
        );
    }
    Ok(())
}

/// The config used and the export's notes, on standard error.
fn said(config: Option<&Path>, notes: &[String]) {
    let config = config.map_or("(built-in defaults)".into(), |p| p.display().to_string());
    note!("config: {config}");
    for line in notes {
        note!("{line}");
    }
}
