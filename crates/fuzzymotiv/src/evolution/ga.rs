//! The genetic algorithm of docs/model.md §6. It knows genomes (weight vectors) and fitness values only
//! — higher fitness is better — and never sees robots, rooms or fuzzy logic.

use serde::{Deserialize, Serialize};

use crate::params::{BIG, FieldError, Num, check, unit};
use crate::random::rng::{Rng, index, standard_normal, uniform, uniform01};

/// A genome: the controller's weights.
pub type Genome = Vec<f64>;

/// `[ga]` in a config, as written (docs/model.md §6 defaults): see [`GaParams`] for each
/// field's unit, default and range; [`GaParams::from_raw`] checks them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawGa {
    /// [`GaParams::population`].
    pub population: usize,
    /// [`GaParams::generations`].
    pub generations: usize,
    /// [`GaParams::elite`].
    pub elite: usize,
    /// [`GaParams::parent_fraction`].
    pub parent_fraction: f64,
    /// [`GaParams::crossover`].
    pub crossover: f64,
    /// [`GaParams::mutation_rate`].
    pub mutation_rate: f64,
    /// [`GaParams::mutation_sigma`].
    pub mutation_sigma: f64,
    /// [`GaParams::weight_limit`].
    pub weight_limit: f64,
    /// [`GaParams::init_range`].
    pub init_range: f64,
}

impl Default for RawGa {
    fn default() -> Self {
        let d = GaParams::default();
        Self {
            population: d.population,
            generations: d.generations,
            elite: d.elite,
            parent_fraction: d.parent_fraction,
            crossover: d.crossover,
            mutation_rate: d.mutation_rate,
            mutation_sigma: d.mutation_sigma,
            weight_limit: d.weight_limit,
            init_range: d.init_range,
        }
    }
}

/// Checked GA parameters (docs/model.md §6): built by [`GaParams::from_raw`] (or
/// [`GaParams::default`]), read through the accessors, each documented with its unit, default
/// and range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaParams {
    population: usize,
    generations: usize,
    elite: usize,
    parent_fraction: f64,
    crossover: f64,
    mutation_rate: f64,
    mutation_sigma: f64,
    weight_limit: f64,
    init_range: f64,
}

impl Default for GaParams {
    fn default() -> Self {
        Self {
            population: 200,
            generations: 200,
            elite: 2,
            parent_fraction: 0.2,
            crossover: 0.5,
            mutation_rate: 0.01,
            mutation_sigma: 0.5,
            weight_limit: 5.0,
            init_range: 1.0,
        }
    }
}

impl GaParams {
    /// Population size (individuals); default 200; range 2..=10⁶.
    pub fn population(&self) -> usize {
        self.population
    }

    /// Generations; default 200; range 1..=10⁶.
    pub fn generations(&self) -> usize {
        self.generations
    }

    /// Best individuals copied unchanged into the next generation; default 2; below
    /// `population`.
    pub fn elite(&self) -> usize {
        self.elite
    }

    /// Parents are drawn uniformly from this best fraction of the population; default 0.2;
    /// range (0, 1].
    pub fn parent_fraction(&self) -> f64 {
        self.parent_fraction
    }

    /// Probability of one-point crossover per child; default 0.5; range [0, 1].
    pub fn crossover(&self) -> f64 {
        self.crossover
    }

    /// Per-gene mutation probability; default 0.01; range [0, 1].
    pub fn mutation_rate(&self) -> f64 {
        self.mutation_rate
    }

    /// Standard deviation of the Gaussian mutation (weight units); default 0.5; ≥ 0, finite.
    pub fn mutation_sigma(&self) -> f64 {
        self.mutation_sigma
    }

    /// Genes are clamped to [−limit, limit] (weight units); default 5; range (0, 10⁶].
    pub fn weight_limit(&self) -> f64 {
        self.weight_limit
    }

    /// Initial genes are drawn from U(−init_range, init_range); default 1; range
    /// [0, `weight_limit`].
    pub fn init_range(&self) -> f64 {
        self.init_range
    }
}

impl GaParams {
    /// Checks `[ga]` against the ranges documented on the accessors, naming the first field
    /// out of range as `ga.FIELD`.
    pub fn from_raw(raw: &RawGa) -> Result<GaParams, FieldError> {
        check((2..=BIG).contains(&raw.population), "ga.population", || {
            format!("must be an integer in 2..={BIG}, got {}", raw.population)
        })?;
        check(
            (1..=BIG).contains(&raw.generations),
            "ga.generations",
            || format!("must be an integer in 1..={BIG}, got {}", raw.generations),
        )?;
        check(raw.elite < raw.population, "ga.elite", || {
            format!(
                "must be smaller than ga.population ({}), got {}",
                raw.population, raw.elite
            )
        })?;
        check(
            raw.parent_fraction.is_finite()
                && raw.parent_fraction > 0.0
                && raw.parent_fraction <= 1.0,
            "ga.parent_fraction",
            || format!("must be in (0, 1], got {}", Num(raw.parent_fraction)),
        )?;
        check(unit(raw.crossover), "ga.crossover", || {
            format!(
                "must be a probability in [0, 1], got {}",
                Num(raw.crossover)
            )
        })?;
        check(unit(raw.mutation_rate), "ga.mutation_rate", || {
            format!(
                "must be a probability in [0, 1], got {}",
                Num(raw.mutation_rate)
            )
        })?;
        Self::check_weights(raw)?;
        Ok(GaParams {
            population: raw.population,
            generations: raw.generations,
            elite: raw.elite,
            parent_fraction: raw.parent_fraction,
            crossover: raw.crossover,
            mutation_rate: raw.mutation_rate,
            mutation_sigma: raw.mutation_sigma,
            weight_limit: raw.weight_limit,
            init_range: raw.init_range,
        })
    }

    /// The checks of the fields in weight units: `mutation_sigma`, `weight_limit`,
    /// `init_range`.
    fn check_weights(raw: &RawGa) -> Result<(), FieldError> {
        check(
            raw.mutation_sigma.is_finite() && raw.mutation_sigma >= 0.0,
            "ga.mutation_sigma",
            || {
                format!(
                    "must be a finite number ≥ 0, got {}",
                    Num(raw.mutation_sigma)
                )
            },
        )?;
        check(
            raw.weight_limit.is_finite() && raw.weight_limit > 0.0 && raw.weight_limit <= 1e6,
            "ga.weight_limit",
            || format!("must be in (0, 1e6], got {}", Num(raw.weight_limit)),
        )?;
        check(
            raw.init_range.is_finite()
                && raw.init_range >= 0.0
                && raw.init_range <= raw.weight_limit,
            "ga.init_range",
            || {
                format!(
                    "must be in [0, ga.weight_limit], got {}",
                    Num(raw.init_range)
                )
            },
        )
    }
}

/// A random initial population of `params.population` genomes of length `len`.
pub fn initial_population<R: Rng + ?Sized>(
    params: &GaParams,
    len: usize,
    rng: &mut R,
) -> Vec<Genome> {
    (0..params.population)
        .map(|_| {
            (0..len)
                .map(|_| uniform(rng, -params.init_range, params.init_range))
                .collect()
        })
        .collect()
}

/// Indices sorted best first (ties broken by index, so the order is total and deterministic).
pub fn ranking(fitness: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..fitness.len()).collect();
    order.sort_by(|&a, &b| fitness[b].total_cmp(&fitness[a]).then(a.cmp(&b)));
    order
}

/// The next generation: the `elite` best unchanged, the rest bred from parents drawn uniformly
/// from the best `parent_fraction` by one-point crossover (probability `crossover`, otherwise a
/// copy of the first parent) and per-gene Gaussian mutation.
pub fn next_generation<R: Rng + ?Sized>(
    population: &[Genome],
    fitness: &[f64],
    params: &GaParams,
    rng: &mut R,
) -> Vec<Genome> {
    assert_eq!(population.len(), fitness.len(), "one fitness per genome");
    let order = ranking(fitness);
    let n = params.population;
    let parents = ((params.parent_fraction * population.len() as f64).ceil() as usize)
        .clamp(1, population.len());
    let mut next: Vec<Genome> = order
        .iter()
        .take(params.elite.min(n))
        .map(|&i| population[i].clone())
        .collect();
    while next.len() < n {
        let a = &population[order[index(rng, parents)]];
        let b = &population[order[index(rng, parents)]];
        let mut child = a.clone();
        if uniform01(rng) < params.crossover && a.len() > 1 {
            let cut = 1 + index(rng, a.len() - 1);
            child[cut..].copy_from_slice(&b[cut..]);
        }
        mutate(&mut child, params, rng);
        next.push(child);
    }
    next
}

/// Per-gene mutation: with probability `mutation_rate` add N(0, σ), then clamp.
pub fn mutate<R: Rng + ?Sized>(genome: &mut [f64], params: &GaParams, rng: &mut R) {
    for g in genome.iter_mut() {
        if uniform01(rng) < params.mutation_rate {
            *g = (*g + params.mutation_sigma * standard_normal(rng))
                .clamp(-params.weight_limit, params.weight_limit);
        }
    }
}

/// Summary of one generation's fitness values.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Stats {
    /// Mean.
    pub mean: f64,
    /// Population standard deviation.
    pub std: f64,
    /// Lowest.
    pub min: f64,
    /// Highest: the best individual's fitness (higher is better).
    pub max: f64,
}

impl Stats {
    /// Statistics of `values`, summed in index order.
    pub fn of(values: &[f64]) -> Stats {
        if values.is_empty() {
            return Stats::default();
        }
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
        let min = values.iter().copied().fold(f64::INFINITY, f64::min);
        let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Stats {
            mean,
            std: var.sqrt(),
            min,
            max,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::rng::rng_from_seed;

    #[test]
    fn elites_survive_and_sizes_hold() {
        let p = GaParams::from_raw(&RawGa {
            population: 10,
            ..RawGa::default()
        })
        .unwrap();
        let mut rng = rng_from_seed(5);
        let pop = initial_population(&p, 4, &mut rng);
        let fit: Vec<f64> = (0..10).map(|i| i as f64).collect();
        let next = next_generation(&pop, &fit, &p, &mut rng);
        assert_eq!(next.len(), 10);
        assert_eq!(next[0], pop[9]);
        assert_eq!(next[1], pop[8]);
        assert!(next.iter().flatten().all(|g| g.abs() <= 5.0));
    }

    #[test]
    fn ranking_breaks_ties_by_index() {
        assert_eq!(ranking(&[1.0, 3.0, 3.0, 0.5]), vec![1, 2, 0, 3]);
    }

    #[test]
    fn ga_climbs_a_simple_function() {
        // Maximise −Σ(g − 1)²: the GA must get closer to all-ones.
        let p = GaParams::from_raw(&RawGa {
            population: 30,
            ..RawGa::default()
        })
        .unwrap();
        let f = |g: &Genome| -g.iter().map(|x| (x - 1.0) * (x - 1.0)).sum::<f64>();
        let mut rng = rng_from_seed(11);
        let mut pop = initial_population(&p, 5, &mut rng);
        let first = Stats::of(&pop.iter().map(f).collect::<Vec<_>>()).max;
        for _ in 0..40 {
            let fit: Vec<f64> = pop.iter().map(f).collect();
            pop = next_generation(&pop, &fit, &p, &mut rng);
        }
        let last = Stats::of(&pop.iter().map(f).collect::<Vec<_>>()).max;
        assert!(last > first, "{first} -> {last}");
    }

    #[test]
    fn stats_by_hand() {
        let s = Stats::of(&[1.0, 2.0, 3.0, 4.0]);
        assert_eq!((s.mean, s.min, s.max), (2.5, 1.0, 4.0));
        assert!((s.std - 1.25f64.sqrt()).abs() < 1e-15);
    }
}
