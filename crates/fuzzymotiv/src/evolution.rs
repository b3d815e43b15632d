//! The genetic algorithm's operators on genomes and fitness values: the initial population,
//! selection, elitism, crossover and mutation; a population checked against its network. The generation loop that drives them is
//! [`crate::experiment::Evolution`].

pub(crate) mod ga;
pub(crate) mod population;

pub use ga::{GaParams, Genome, Stats, next_generation, ranking};
pub use population::{Population, PopulationError};
