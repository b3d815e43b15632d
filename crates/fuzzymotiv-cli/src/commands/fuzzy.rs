//! `fuzzymotiv fuzzy`: the TSK fuzzy fitness F of motivations X and fitness values Y (with
//! the firing rules), or the TSK as a fuzzylite FLL file; the values are read and the file
//! written by [`fuzzymotiv_pipeline::pipeline::fuzzy`], this front parses and prints.

use std::path::PathBuf;

use crate::console::{note, out, outln};
use fuzzymotiv::fitness::TskFitness;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::pipeline::fuzzy::{FllWritten, fitness_of, motivations_of, write_fll};

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

/// Entry point of `fuzzymotiv fuzzy`.
pub fn fuzzy(args: FuzzyArgs) -> Result<(), CliError> {
    let (m, said) = motivations_of(&args.motivations)?;
    if let Some(said) = said {
        note!("{said}");
    }
    let tsk = TskFitness::paper();
    if let Some(fitness) = &args.fitness {
        let y = fitness_of(fitness, &m)?;
        let f = tsk.evaluate(&m, &y);
        outln!("{f:.12}")?;
        if args.explain {
            outln!("{}", tsk.explain(&m, &y))?;
        }
    }
    let Some(path) = &args.export_fll else {
        return Ok(());
    };
    match write_fll(path, &tsk, &m, args.force)? {
        FllWritten::Text(text) => out!("{text}"),
        FllWritten::Same => {
            note!(
                "{} already holds this engine; nothing to do",
                path.display()
            );
            Ok(())
        }
        FllWritten::Wrote(rules) => {
            note!("wrote {} ({rules} rules, fuzzylite FLL)", path.display());
            Ok(())
        }
    }
}
