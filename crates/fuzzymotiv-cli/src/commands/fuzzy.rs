//! `fuzzymotiv fuzzy`: the TSK fuzzy fitness F of motivations X and fitness values Y (with
//! the firing rules), or the TSK as a fuzzylite FLL file.

use std::path::PathBuf;

use crate::console::{note, outln};
use fuzzymotiv_pipeline::files::error::CliError;

/// Arguments of `fuzzymotiv fuzzy`.
#[derive(clap::Args)]
pub struct FuzzyArgs {
    /// Motivations C,H,O,E (each in [0, 1], summing to 1; a sum within 0.001 of 1 is
    /// normalised), e.g. 0.8,0.1,0,0.1; or any number by name, each weighing the term of its
    /// name, e.g. curiosity=0.6,homing=0.1,orientation=0,energy=0.1,urgency=0.2.
    #[arg(long, allow_hyphen_values = true, value_name = "C,H,O,E|name=w,…")]
    motivations: String,
    /// Fitness values a,g,l,b (each in [0, 1]), e.g. 0.95,0.5,0,0.79; or by term,
    /// e.g. a=0.95,g=0.5,l=0,b=0.79,urgency=0.4.
    #[arg(
        long,
        allow_hyphen_values = true,
        value_name = "a,g,l,b|term=y,…",
        required_unless_present = "export_fll"
    )]
    fitness: Option<String>,
    /// Also list the firing rules with their labels, weights and outputs.
    #[arg(long, requires = "fitness")]
    explain: bool,
    /// Write the TSK of these motivations (625 rules for the paper's four) as a fuzzylite FLL file (`-`: standard
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

/// `name=value,…` pairs (the named form of --motivations and --fitness), or `None` for the
/// paper's positional form (no `=`).
fn parse_named(text: &str, option: &str) -> Result<Option<Vec<(String, f64)>>, CliError> {
    if !text.contains('=') {
        return Ok(None);
    }
    let mut out: Vec<(String, f64)> = Vec::new();
    for part in text.split(',').map(str::trim) {
        let bad = |why: &str| {
            CliError::input(format!(
                "{option}: `{part}` {why}; expected name=value pairs separated by commas, e.g. {option} curiosity=0.6,homing=0.1,orientation=0,energy=0.1,urgency=0.2"
            ))
        };
        let (name, value) = part.split_once('=').ok_or_else(|| bad("has no `=`"))?;
        let name = name.trim();
        if name.is_empty() {
            return Err(bad("has no name before `=`"));
        }
        if out.iter().any(|(n, _)| n == name) {
            return Err(bad("names a motivation or term a second time"));
        }
        let value = value
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| bad("is not a finite number"))?;
        out.push((name.to_string(), value));
    }
    Ok(Some(out))
}

/// The motivations of --motivations: the paper's C,H,O,E, or named ones (each weighing the
/// term of its own name; curiosity, homing, orientation and energy weigh a, g, l and b), read
/// as a config's `[motivations]` reads the same names: those named and no others, the paper's
/// first, then the others alphabetically.
fn motivations_of(text: &str) -> Result<fuzzymotiv::fitness::Motivations, CliError> {
    use fuzzymotiv::fitness::{RawMotivation, RawMotivations, TskFitness};
    let raw = match parse_named(text, "--motivations")? {
        None => RawMotivations::paper(parse_four(text, "--motivations", ["C", "H", "O", "E"])?),
        // As a config's [motivations] reads the same names: these and no others, in its order.
        Some(named) => RawMotivations::named(
            named
                .into_iter()
                .map(|(n, w)| (n, RawMotivation::Weight(w))),
        ),
    };
    let mut normalised = raw.clone();
    let paper = !text.contains('=');
    if let Some(sum) = normalised.normalise(&TskFitness::paper()) {
        if paper {
            let x: Vec<f64> = normalised.list.iter().map(|(_, w)| w.weight()).collect();
            note!("note: --motivations summed to {sum}, normalised to (C, H, O, E) = {x:?}");
            return normalised
                .validated(&TskFitness::paper())
                .map_err(|e| CliError::input(format!("--motivations: {}", e.reason)));
        }
        let x: Vec<String> = normalised
            .list
            .iter()
            .map(|(n, w)| format!("{n} = {}", w.weight()))
            .collect();
        note!(
            "note: --motivations summed to {sum}, normalised to {}",
            x.join(", ")
        );
    }
    let m = normalised
        .validated(&TskFitness::paper())
        .map_err(|e| CliError::input(format!("--motivations: {}", e.reason)))?;
    check_library_terms(&m)?;
    Ok(m)
}

/// Each motivation named by --motivations weighs a term of the library (there are no user
/// terms here).
fn check_library_terms(m: &fuzzymotiv::fitness::Motivations) -> Result<(), CliError> {
    use fuzzymotiv::fitness::{LIBRARY_TERMS, TermId};
    match m.iter().find(|x| TermId::library(x.term()).is_none()) {
        None => Ok(()),
        Some(x) => Err(CliError::input(format!(
            "--motivations: `{}` weighs the term `{}`, which does not exist; a motivation named here weighs the term of its own name, one of {} (curiosity, homing, orientation and energy weigh a, g, l and b){}",
            x.name(),
            x.term(),
            LIBRARY_TERMS.join(", "),
            fuzzymotiv::experiment::case_hint(x.term(), &LIBRARY_TERMS)
        ))),
    }
}

/// Each fitness value in [0, 1] (a term outside is an error, not clamped).
fn check_range(names: &[String], y: &[f64]) -> Result<(), CliError> {
    match names.iter().zip(y).find(|(_, v)| !(0.0..=1.0).contains(*v)) {
        None => Ok(()),
        Some((name, v)) => Err(CliError::input(format!(
            "--fitness: `{name}` is {v}, outside [0, 1]; a fitness term is a value from 0 to 1"
        ))),
    }
}

/// The fitness values of --fitness, one per motivation: a,g,l,b positionally for the paper's
/// four, or named by term (`goal=0.7,…`).
fn fitness_of(text: &str, m: &fuzzymotiv::fitness::Motivations) -> Result<Vec<f64>, CliError> {
    let Some(named) = parse_named(text, "--fitness")? else {
        if !m.is_paper() {
            return Err(CliError::input(format!(
                "--fitness: give the terms by name for these motivations, e.g. --fitness {}",
                m.input_names()
                    .iter()
                    .map(|t| format!("{t}=0.5"))
                    .collect::<Vec<_>>()
                    .join(",")
            )));
        }
        let y = parse_four(text, "--fitness", ["a", "g", "l", "b"])?;
        check_range(&["a", "g", "l", "b"].map(String::from), &y)?;
        return Ok(y.to_vec());
    };
    let inputs = m.input_names();
    if let Some((extra, _)) = named.iter().find(|(n, _)| !inputs.contains(n)) {
        return Err(CliError::input(format!(
            "--fitness: `{extra}` is not an input of these motivations; the inputs are {}",
            inputs.join(", ")
        )));
    }
    let y = inputs
        .iter()
        .map(|i| {
            named
                .iter()
                .find(|(n, _)| n == i)
                .map(|(_, v)| *v)
                .ok_or_else(|| {
                    CliError::input(format!(
                        "--fitness: no value for `{i}`; give one per input: {}",
                        inputs.join(", ")
                    ))
                })
        })
        .collect::<Result<Vec<f64>, CliError>>()?;
    check_range(&inputs, &y)?;
    Ok(y)
}

/// Entry point of `fuzzymotiv fuzzy`.
pub fn fuzzy(args: FuzzyArgs) -> Result<(), CliError> {
    use fuzzymotiv::fitness::TskFitness;
    let m = motivations_of(&args.motivations)?;
    let tsk = TskFitness::paper();
    if let Some(fitness) = &args.fitness {
        let y = fitness_of(fitness, &m)?;
        let f = tsk.evaluate(&m, &y);
        outln!("{f:.12}")?;
        if args.explain {
            outln!("{}", tsk.explain(&m, &y))?;
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
    use fuzzymotiv_pipeline::files::guard::{FilesState, check_files, write_files};
    let stdout = path.as_os_str() == "-";
    let name = match path.file_stem() {
        Some(s) if !stdout => s.to_string_lossy().into_owned(),
        _ => "fuzzymotiv".into(),
    };
    let text = fuzzymotiv::fitness::to_fll(tsk, m, &name);
    if stdout {
        return crate::console::out!("{text}");
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
        tsk.rule_count(m)
    );
    Ok(())
}
