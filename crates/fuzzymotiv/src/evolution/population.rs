//! A population checked against a network: at least one genome, each of the network's length,
//! so evaluating it cannot fail. Built by the experiment ([`Experiment::population`]).
//!
//! [`Experiment::population`]: crate::experiment::Experiment::population

use crate::evolution::ga::Genome;
use crate::simulation::controller::{GenomeError, Mlp, MlpShape};

/// A population checked against an experiment's network ([`Experiment::population`](crate::experiment::Experiment::population),
/// [`Experiment::initial_population`](crate::experiment::Experiment::initial_population), [`Experiment::breed`](crate::experiment::Experiment::breed)): at least one genome, each of the
/// network's length, so evaluating it cannot fail. Read it as a slice of genomes.
#[derive(Debug, Clone, PartialEq)]
pub struct Population {
    pub(crate) shape: MlpShape,
    pub(crate) genomes: Vec<Genome>,
}

impl Population {
    /// The shape of the network the genomes are weights of.
    pub fn shape(&self) -> MlpShape {
        self.shape
    }

    /// The network of genome `k` (panics if there is no genome `k`, as indexing does).
    pub fn network(&self, k: usize) -> Mlp {
        Mlp::of_checked(self.shape, &self.genomes[k])
    }

    /// The genomes.
    pub fn into_genomes(self) -> Vec<Genome> {
        self.genomes
    }
}

impl std::ops::Deref for Population {
    type Target = [Genome];

    fn deref(&self) -> &[Genome] {
        &self.genomes
    }
}

/// Genomes that are not a population of an experiment's network ([`Experiment::population`](crate::experiment::Experiment::population)).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum PopulationError {
    /// No genome at all.
    #[error("a population needs at least one genome, got none")]
    Empty,
    /// A genome of the wrong length.
    #[error("genome {index} of the population: {source}")]
    Genome {
        /// Its index in the population.
        index: usize,
        /// Its length and the network's.
        source: GenomeError,
    },
    /// Fitness values given for breeding, not one per genome.
    #[error("{got} fitness values for a population of {expected} genomes (one per genome)")]
    Fitness {
        /// The population's size.
        expected: usize,
        /// The number of fitness values given.
        got: usize,
    },
}
