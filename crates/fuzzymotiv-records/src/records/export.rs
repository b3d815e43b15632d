//! `fuzzymotiv export` and `fm.export_controller`: a run's (or a genome file's) controller as
//! C99 (the generic files or a robot's deployment kit), JSON or ONNX files
//! ([`fuzzymotiv::export`]), checked and written through the output guard.

use std::path::{Path, PathBuf};

use fuzzymotiv::export::{CSources, ExportedController, Kit, KitFile};
use fuzzymotiv::simulation::MlpShape;

use crate::files::error::CliError;
use crate::files::guard::{FilesState, check_files, check_files_dir, write_files, write_into};
use crate::files::inputs::load_config;
use crate::records::genome::{SavedGenome, locate, read_genome};

/// What an export writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExportTarget {
    /// `fm_controller.h` and `fm_controller.c` in a directory.
    C,
    /// The JSON document in a file.
    Json,
    /// The ONNX model in a file.
    Onnx,
}

impl ExportTarget {
    /// Its name, as `--to` takes it: `c`, `json` or `onnx`.
    pub fn name(self) -> &'static str {
        match self {
            ExportTarget::C => "c",
            ExportTarget::Json => "json",
            ExportTarget::Onnx => "onnx",
        }
    }

    /// `"c"` or `"json"`; an error names `option` and the accepted values.
    pub fn parse(option: &str, value: &str) -> Result<ExportTarget, CliError> {
        match value {
            "c" => Ok(ExportTarget::C),
            "json" => Ok(ExportTarget::Json),
            "onnx" => Ok(ExportTarget::Onnx),
            _ => Err(CliError::input(format!(
                "{option}: `{value}` is not an export format; use \"c\", \"json\" or \"onnx\""
            ))),
        }
    }
}

/// Which robot's files a C export writes (`--target`): the generic `fm_controller.h` and
/// `fm_controller.c`, or a robot's deployment kit ([`fuzzymotiv::export::Kit`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KitTarget {
    /// `fm_controller.h` and `fm_controller.c` alone, for any robot (the default).
    Generic,
    /// The e-puck2 kit: a ChibiOS thread for GCtronic's firmware
    /// ([`fuzzymotiv::export::epuck2_kit`]).
    Epuck2,
    /// The Thymio II kit (Aseba).
    Thymio2,
    /// The kit for a Khepera-like robot with an I/O layer of the user's
    /// ([`fuzzymotiv::export::khepera_kit`]).
    Khepera,
}

impl KitTarget {
    /// Its name: `generic`, or the robot's name (`epuck2`, `thymio2`, `khepera`), which a kit's
    /// controller must have been evolved for.
    pub fn name(self) -> &'static str {
        match self {
            KitTarget::Generic => "generic",
            KitTarget::Epuck2 => "epuck2",
            KitTarget::Thymio2 => "thymio2",
            KitTarget::Khepera => "khepera",
        }
    }

    /// Every target, in the order messages list them.
    pub const ALL: [KitTarget; 4] = [
        KitTarget::Generic,
        KitTarget::Epuck2,
        KitTarget::Thymio2,
        KitTarget::Khepera,
    ];

    /// The target named `value` (`generic`, `epuck2`, `thymio2`, `khepera`); an error names
    /// `option`, the value and the accepted names.
    pub fn parse(option: &str, value: &str) -> Result<KitTarget, CliError> {
        (KitTarget::ALL.into_iter())
            .find(|t| t.name() == value)
            .ok_or_else(|| {
                let names: Vec<String> = (KitTarget::ALL.iter())
                    .map(|t| format!("\"{}\"", t.name()))
                    .collect();
                CliError::input(format!(
                    "{option}: `{value}` is not a deployment kit; use {}",
                    names.join(", ")
                ))
            })
    }
}

/// A request: the run directory or genome file, the config (else the one beside it), the room
/// of a per-room robot, the format and where to write.
#[derive(Debug, Clone)]
pub struct ExportRequest<'a> {
    /// A run directory or a `best_genome.json`.
    pub source: &'a Path,
    /// The config whose robot the controller drives.
    pub config: Option<&'a Path>,
    /// With per-room training: the robot evolved in this room.
    pub room: Option<&'a str>,
    /// The format.
    pub to: ExportTarget,
    /// With `C`: the robot whose files to write (`None`: not given, the generic files); with
    /// another format an input error.
    pub target: Option<KitTarget>,
    /// A directory (`C`) or a file (`Json`, `Onnx`).
    pub out: &'a Path,
    /// Replace other files of these names.
    pub force: bool,
    /// The name of the out option in messages (`--out`, `out`).
    pub out_option: &'a str,
    /// The name of the room option in messages (`--room`, `room`).
    pub room_option: &'a str,
    /// The name of the target option in messages (`--target`, `target`).
    pub target_option: &'a str,
}

/// What an export did.
#[derive(Debug, Clone)]
pub struct Exported {
    /// The files, in order.
    pub files: Vec<PathBuf>,
    /// Whether they already held this export (nothing written).
    pub unchanged: bool,
    /// The genome file.
    pub genome: PathBuf,
    /// The config used (`None`: the built-in defaults).
    pub config: Option<PathBuf>,
    /// Network inputs (the robot's sensors).
    pub inputs: usize,
    /// Hidden units.
    pub hidden: usize,
    /// Notes for the user (e.g. which robot of a per-room genome).
    pub notes: Vec<String>,
}

/// An export built and not yet written: its files (paths and contents) and what it was made
/// of.
#[derive(Debug, Clone)]
pub struct Export {
    /// The files, in order, with their contents.
    pub files: Vec<(PathBuf, Vec<u8>)>,
    /// The genome file.
    pub genome: PathBuf,
    /// The config used (`None`: the built-in defaults).
    pub config: Option<PathBuf>,
    /// Network inputs (the robot's sensors).
    pub inputs: usize,
    /// Hidden units.
    pub hidden: usize,
    /// Notes for the user (e.g. which robot of a per-room genome).
    pub notes: Vec<String>,
}

impl Export {
    /// The bytes of an export of one file (JSON, ONNX), for standard output; an export of more
    /// (C: a header and a source) is an input error naming `out_option`, since `-` takes one
    /// file.
    pub fn single_file(&self, out_option: &str) -> Result<&[u8], CliError> {
        match self.files.as_slice() {
            [(_, bytes)] => Ok(bytes),
            files => {
                let names: Vec<String> = (files.iter())
                    .map(|(path, _)| path.file_name().unwrap_or(path.as_os_str()))
                    .map(|name| name.to_string_lossy().into_owned())
                    .collect();
                Err(CliError::input(format!(
                    "{out_option}: `-` (standard output) takes one file, but this export has {} \
                     ({}); pass a directory",
                    files.len(),
                    names.join(", ")
                )))
            }
        }
    }
}

/// Loads the genome and config and builds the export's files, writing nothing; the generic C
/// export's directory is checked first, a kit's once its files are known ([`check_files_dir`]:
/// not `-`, the current directory or something other than a directory). `target` with another
/// format than C is an input error, and so is a kit for another robot than the controller's.
pub fn build_export(req: &ExportRequest) -> Result<Export, CliError> {
    let target = match (req.to, req.target) {
        (ExportTarget::C, target) => target.unwrap_or(KitTarget::Generic),
        (to, Some(target)) => {
            return Err(CliError::input(format!(
                "{} {}: a deployment kit is C code; a {} export takes no {}",
                req.target_option,
                target.name(),
                to.name(),
                req.target_option
            )));
        }
        (_, None) => KitTarget::Generic,
    };
    if req.to == ExportTarget::C && target == KitTarget::Generic {
        let names = [CSources::HEADER_NAME, CSources::SOURCE_NAME];
        check_files_dir(req.out, req.out_option, &names)?;
    }
    let (genome_path, found_config) = locate(req.source)?;
    let config = req.config.map(Path::to_path_buf).or(found_config);
    let genome = read_genome(&genome_path)?;
    let loaded = load_config(config.as_deref(), &[], None)?;
    if config.is_some() && loaded.raw.network.hidden != genome.hidden {
        return Err(CliError::input(format!(
            "{}: field `shape.hidden`: the genome has {} hidden units but the config says network.hidden = {}",
            genome_path.display(),
            genome.hidden,
            loaded.raw.network.hidden
        )));
    }
    let mut notes = Vec::new();
    let weights = chosen_weights(&genome, req, &mut notes)?;
    let in_file =
        |e: &dyn std::fmt::Display| CliError::input(format!("{}: {e}", genome_path.display()));
    // The robot's sensors are the network's inputs (7 on the Thymio II, not the Khepera's 8).
    let sensors = loaded.experiment.trial_params().robot().sensors();
    let shape = (MlpShape::with_hidden(genome.hidden).and_then(|s| s.with_inputs(sensors)))
        .map_err(|e| in_file(&e))?;
    let controller = ExportedController::new(shape, weights, loaded.experiment.trial_params())
        .map_err(|e| in_file(&format!("field `weights`: {e}")))?;
    let files = match req.to {
        ExportTarget::C => {
            let kit = kit_of(target, &controller, req.target_option)?;
            let names: Vec<&str> = kit.files.iter().map(|f| f.name.as_str()).collect();
            check_files_dir(req.out, req.out_option, &names)?;
            notes.extend(kit.notes.iter().cloned());
            (kit.files.into_iter())
                .map(|f| (req.out.join(&f.name), f.contents))
                .collect()
        }
        ExportTarget::Json => vec![(req.out.to_path_buf(), controller.json().into_bytes())],
        ExportTarget::Onnx => vec![(req.out.to_path_buf(), controller.onnx())],
    };
    Ok(Export {
        files,
        genome: genome_path,
        config,
        inputs: sensors,
        hidden: genome.hidden,
        notes,
    })
}

/// The files of `target` for `controller`: the generic C, or a robot's deployment kit, whose
/// robot must be the controller's (an input error naming `option`, the target and the
/// controller's robot otherwise).
fn kit_of(
    target: KitTarget,
    controller: &ExportedController,
    option: &str,
) -> Result<Kit, CliError> {
    let robot = &controller.robot().name;
    if target != KitTarget::Generic && robot != target.name() {
        return Err(CliError::input(format!(
            "{option} {}: the controller was evolved for the robot `{robot}`, not `{}`; export \
             its own kit with {option} {robot} (if there is one) or the plain C with {option} \
             generic",
            target.name(),
            target.name()
        )));
    }
    match target {
        KitTarget::Generic => {
            let c = controller.c();
            Ok(Kit {
                files: vec![
                    KitFile::text(CSources::HEADER_NAME, c.header),
                    KitFile::text(CSources::SOURCE_NAME, c.source),
                ],
                notes: Vec::new(),
            })
        }
        KitTarget::Epuck2 => Ok(fuzzymotiv::export::epuck2_kit(controller)),
        KitTarget::Khepera => Ok(fuzzymotiv::export::khepera_kit(controller)),
        KitTarget::Thymio2 => Ok(fuzzymotiv::export::thymio2_kit(controller)),
    }
}

/// Loads the genome and config, builds the export and writes it through the output guard
/// (another file is kept unless `force`; the same export again writes nothing; nothing is
/// written half-way).
pub fn export_controller(req: &ExportRequest) -> Result<Exported, CliError> {
    let built = build_export(req)?;
    let (option, force) = (req.out_option, req.force);
    let state = match req.to {
        ExportTarget::C => write_into(req.out, &built.files, option, force)?,
        ExportTarget::Json | ExportTarget::Onnx => {
            let state = check_files(&built.files, option, force)?;
            if state == FilesState::Write {
                write_files(&built.files)?;
            }
            state
        }
    };
    Ok(Exported {
        files: built.files.into_iter().map(|(p, _)| p).collect(),
        unchanged: state == FilesState::Same,
        genome: built.genome,
        config: built.config,
        inputs: built.inputs,
        hidden: built.hidden,
        notes: built.notes,
    })
}

/// The weights to export: the main robot's, or with `room` the one evolved in that room.
fn chosen_weights<'a>(
    genome: &'a SavedGenome,
    req: &ExportRequest,
    notes: &mut Vec<String>,
) -> Result<&'a [f64], CliError> {
    let option = req.room_option;
    // An all-rooms run lists its one robot under `runs` too: that is no robot per room.
    let all_rooms = fuzzymotiv::experiment::ALL_ROOMS_RUN;
    let per_room = (genome.runs.iter()).any(|(label, _)| label != all_rooms);
    let Some(room) = req.room else {
        if per_room {
            notes.push(format!(
                "note: the genome file holds a robot per room; exporting its main robot ({option} ROOM picks one)"
            ));
        }
        return Ok(&genome.weights);
    };
    match genome.runs.iter().find(|(label, _)| label == room) {
        Some((_, w)) => Ok(w),
        None if !per_room => Err(CliError::input(format!(
            "{option} {room}: {} holds one robot for all rooms (trained in all rooms); leave {option} out",
            genome.path.display()
        ))),
        None => Err(CliError::input(format!(
            "{option} {room}: {} has no robot evolved in that room; its rooms are {}",
            genome.path.display(),
            (genome.runs.iter().map(|(l, _)| l.as_str()))
                .collect::<Vec<_>>()
                .join(", ")
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn export_of(files: &[&str]) -> Export {
        Export {
            files: (files.iter())
                .map(|name| (PathBuf::from(name), name.as_bytes().to_vec()))
                .collect(),
            genome: PathBuf::from("best_genome.json"),
            config: None,
            inputs: 8,
            hidden: 6,
            notes: Vec::new(),
        }
    }

    #[test]
    fn a_kit_target_is_read_by_its_name_and_an_unknown_one_names_the_option() {
        for t in KitTarget::ALL {
            assert_eq!(KitTarget::parse("target", t.name()).unwrap(), t);
        }
        let e = KitTarget::parse("target", "thymio").unwrap_err();
        assert!(e.is_input());
        assert_eq!(
            e.to_string(),
            "target: `thymio` is not a deployment kit; use \"generic\", \"epuck2\", \"thymio2\", \"khepera\""
        );
    }

    #[test]
    fn an_export_of_one_file_gives_its_bytes_and_one_of_two_files_is_refused_for_standard_output() {
        let one = export_of(&["controller.json"]);
        assert_eq!(one.single_file("--out").unwrap(), b"controller.json");
        let two = export_of(&["out/fm_controller.h", "out/fm_controller.c"]);
        let e = two.single_file("--out").unwrap_err();
        assert!(e.is_input());
        assert_eq!(
            e.to_string(),
            "--out: `-` (standard output) takes one file, but this export has 2 \
             (fm_controller.h, fm_controller.c); pass a directory"
        );
    }
}
