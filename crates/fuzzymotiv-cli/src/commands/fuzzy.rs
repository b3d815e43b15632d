//! `fuzzymotiv fuzzy`: the TSK fuzzy fitness F of motivations X and fitness values Y (with
//! the firing rules), or the TSK as a fuzzylite FLL file.

use std::path::PathBuf;

use fuzzymotiv_io::files::error::CliError;
use fuzzymotiv_io::{note, outln};

/// Arguments of `fuzzymotiv fuzzy`.
#[derive(clap::Args)]
pub struct FuzzyArgs {
    /// Motivations C,H,O,E (each in [0, 1], summing to 1; a sum within 0.001 of 1 is
    /// normalised), e.g. 0.8,0.1,0,0.1.
    #[arg(long, allow_hyphen_values = true, value_name = "C,H,O,E")]
    motivations: String,
    /// Fitness values a,g,l,b (each clamped to [0, 1]), e.g. 0.95,0.5,0,0.79.
    #[arg(
        long,
        allow_hyphen_values = true,
        value_name = "a,g,l,b",
        required_unless_present = "export_fll"
    )]
    fitness: Option<String>,
    /// Also list the firing rules with their labels, weights and outputs.
    #[arg(long, requires = "fitness")]
    explain: bool,
    /// Write the 625-rule TSK of these motivations as a fuzzylite FLL file (`-`: standard
    /// output). The same file again is left as it is; another file there is kept unless --force.
    #[arg(long, value_name = "FILE")]
    export_fll: Option<PathBuf>,
    /// Replace an existing --export-fll FILE with other contents (only a regular file: a
    /// directory, device or link is never replaced).
    #[arg(long, requires = "export_fll")]
    force: bool,
}

fn parse_four(text: &str, option: &str, names: [&str; 4]) -> Result<[f64; 4], CliError> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let usage = || {
        format!(
            "expected four comma-separated numbers {}, e.g. {option} 0.8,0.1,0,0.1",
            names.join(",")
        )
    };
    if parts.len() != 4 {
        return Err(CliError::input(format!(
            "{option}: got {} values; {}",
            parts.len(),
            usage()
        )));
    }
    let mut out = [0.0; 4];
    for (k, p) in parts.iter().enumerate() {
        out[k] = p
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| {
                CliError::input(format!(
                    "{option}: `{p}` ({}) is not a finite number; {}",
                    names[k],
                    usage()
                ))
            })?;
    }
    Ok(out)
}

/// Entry point of `fuzzymotiv fuzzy`.
pub fn fuzzy(args: FuzzyArgs) -> Result<(), CliError> {
    use fuzzymotiv::fitness::{Motivations, TskFitness};
    let x = parse_four(&args.motivations, "--motivations", ["C", "H", "O", "E"])?;
    let (m, sum) = Motivations::normalised(x[0], x[1], x[2], x[3])
        .map_err(|e| CliError::input(format!("--motivations: {e}")))?;
    if let Some(sum) = sum {
        note!(
            "note: --motivations summed to {sum}, normalised to (C, H, O, E) = {:?}",
            m.as_array()
        );
    }
    let tsk = TskFitness::paper();
    if let Some(fitness) = &args.fitness {
        let y = parse_four(fitness, "--fitness", ["a", "g", "l", "b"])?;
        let f = tsk.evaluate(&m, y);
        outln!("{f:.12}")?;
        if args.explain {
            fuzzymotiv_io::out!("{}", tsk.explain(&m, y))?;
        }
    }
    if let Some(path) = &args.export_fll {
        export_fll(path, &tsk, &m, args.force)?;
    }
    Ok(())
}

/// Writes the FLL engine to `path` (`-`: standard output) through the output guard.
fn export_fll(
    path: &std::path::Path,
    tsk: &fuzzymotiv::fitness::TskFitness,
    m: &fuzzymotiv::fitness::Motivations,
    force: bool,
) -> Result<(), CliError> {
    use fuzzymotiv_io::files::guard::{FilesState, check_files, write_files};
    let stdout = path.as_os_str() == "-";
    let name = match path.file_stem() {
        Some(s) if !stdout => s.to_string_lossy().into_owned(),
        _ => "fuzzymotiv".into(),
    };
    let text = fuzzymotiv::fitness::to_fll(tsk, m, &name);
    if stdout {
        return fuzzymotiv_io::out!("{text}");
    }
    let files = [(path.to_path_buf(), text.into_bytes())];
    if check_files(&files, "--export-fll", force)? == FilesState::Same {
        note!(
            "{} already holds this engine; nothing to do",
            path.display()
        );
        return Ok(());
    }
    write_files(&files)?;
    note!(
        "wrote {} ({} rules, fuzzylite FLL)",
        path.display(),
        tsk.rule_count()
    );
    Ok(())
}
