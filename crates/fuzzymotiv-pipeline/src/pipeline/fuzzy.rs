//! The TSK fuzzy fitness by hand (`fuzzymotiv fuzzy`): motivations and fitness values read
//! from their text (the paper's positional C,H,O,E and a,g,l,b, or `name=value` pairs,
//! [`motivations_of`], [`fitness_of`]), and the TSK of the motivations written as a fuzzylite
//! FLL file through the output guard ([`write_fll`]). The errors name the command line's
//! options (`--motivations`, `--fitness`, `--export-fll`).

use std::path::Path;

use fuzzymotiv::fitness::{
    LIBRARY_TERMS, Motivations, RawMotivation, RawMotivations, TermId, TskFitness, to_fll,
};

use crate::files::error::CliError;
use crate::files::guard::{FilesState, check_files, write_files};

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

/// The motivations of --motivations, and the note that says how they were normalised (a sum
/// within 0.001 of 1): the paper's C,H,O,E, or named ones (each weighing the
/// term of its own name; curiosity, homing, orientation and energy weigh a, g, l and b), read
/// as a config's `[motivations]` reads the same names: those named and no others, the paper's
/// first, then the others alphabetically.
pub fn motivations_of(text: &str) -> Result<(Motivations, Option<String>), CliError> {
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
    let mut said = None;
    if let Some(sum) = normalised.normalise(&TskFitness::paper()) {
        if paper {
            let x: Vec<f64> = normalised.list.iter().map(|(_, w)| w.weight()).collect();
            let said =
                format!("note: --motivations summed to {sum}, normalised to (C, H, O, E) = {x:?}");
            let m = (normalised.validated(&TskFitness::paper()))
                .map_err(|e| CliError::input(format!("--motivations: {}", e.reason)))?;
            return Ok((m, Some(said)));
        }
        let x: Vec<String> = normalised
            .list
            .iter()
            .map(|(n, w)| format!("{n} = {}", w.weight()))
            .collect();
        said = Some(format!(
            "note: --motivations summed to {sum}, normalised to {}",
            x.join(", ")
        ));
    }
    let m = normalised
        .validated(&TskFitness::paper())
        .map_err(|e| CliError::input(format!("--motivations: {}", e.reason)))?;
    check_library_terms(&m)?;
    Ok((m, said))
}

/// Each motivation named by --motivations weighs a term of the library (there are no user
/// terms here).
fn check_library_terms(m: &Motivations) -> Result<(), CliError> {
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
pub fn fitness_of(text: &str, m: &Motivations) -> Result<Vec<f64>, CliError> {
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

/// What [`write_fll`] did.
#[derive(Debug, Clone, PartialEq)]
pub enum FllWritten {
    /// The path was `-`: the engine's text, for standard output.
    Text(String),
    /// The file already held this engine; nothing was written.
    Same,
    /// The file was written; the engine has this many rules.
    Wrote(usize),
}

/// The TSK of `m` as a fuzzylite FLL engine named after the file's stem, written to `path`
/// through the output guard (another file there is kept unless `force`), or returned as text
/// for `-` (standard output).
pub fn write_fll(
    path: &Path,
    tsk: &TskFitness,
    m: &Motivations,
    force: bool,
) -> Result<FllWritten, CliError> {
    let stdout = path.as_os_str() == "-";
    let name = match path.file_stem() {
        Some(s) if !stdout => s.to_string_lossy().into_owned(),
        _ => "fuzzymotiv".into(),
    };
    let text = to_fll(tsk, m, &name);
    if stdout {
        return Ok(FllWritten::Text(text));
    }
    let files = [(path.to_path_buf(), text.into_bytes())];
    if check_files(&files, "--export-fll", force)? == FilesState::Same {
        return Ok(FllWritten::Same);
    }
    write_files(&files)?;
    Ok(FllWritten::Wrote(tsk.rule_count(m)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Motivations summing to within 0.001 of 1 are normalised and the note says so; exact
    /// ones say nothing; named fitness values follow the motivations' inputs.
    #[test]
    fn motivations_near_one_are_normalised_with_a_note_and_fitness_follows_their_inputs() {
        let (m, said) = motivations_of("0.8,0.1,0,0.1").unwrap();
        assert!(said.is_none() && m.is_paper());
        let (_, said) = motivations_of("0.8,0.1,0,0.1005").unwrap();
        assert!(said.unwrap().contains("normalised to (C, H, O, E)"));
        let (m, _) = motivations_of("curiosity=0.7,urgency=0.3").unwrap();
        let y = fitness_of("urgency=0.25,a=0.5", &m).unwrap();
        assert_eq!(y, vec![0.5, 0.25]);
        let e = fitness_of("a=0.5", &m).unwrap_err().to_string();
        assert!(e.contains("no value for `urgency`"), "{e}");
    }

    /// `-` returns the engine's text; a file is written, then found the same.
    #[test]
    fn the_fll_engine_is_text_for_a_dash_and_a_file_written_once() {
        let (m, _) = motivations_of("0.8,0.1,0,0.1").unwrap();
        let tsk = TskFitness::paper();
        let FllWritten::Text(text) = write_fll(Path::new("-"), &tsk, &m, false).unwrap() else {
            panic!("text for -");
        };
        assert!(text.contains("Engine: fuzzymotiv"), "{}", &text[..200]);
        let path = std::env::temp_dir().join(format!("fm-fll-{}.fll", std::process::id()));
        let _ = std::fs::remove_file(&path);
        assert_eq!(
            write_fll(&path, &tsk, &m, false).unwrap(),
            FllWritten::Wrote(625)
        );
        assert_eq!(write_fll(&path, &tsk, &m, false).unwrap(), FllWritten::Same);
        std::fs::remove_file(&path).unwrap();
    }
}
