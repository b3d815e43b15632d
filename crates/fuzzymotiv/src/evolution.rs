//! The genetic algorithm's operators on genomes and fitness values: the initial population,
//! selection, elitism, crossover and mutation; a population checked against its network. The generation loop that drives them is
//! [`crate::experiment::evolution`].

pub mod ga;
pub mod population;
