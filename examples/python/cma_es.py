"""CMA-ES (the `cma` package) evolving Khepera controllers against fuzzymotiv's TSK fitness.

    pip install ./python cma                  # in a virtual environment
    python examples/python/cma_es.py          # from the repository root; prints F per generation

`fm.Problem` is the batched fitness function: `problem.evaluate(genomes, generation=g)` gives F
(higher is better, so CMA-ES, a minimiser, is told -F), with each genome's noise drawn as the
built-in GA draws individual i of generation g. The run is deterministic (seeded), and it
checks that F improved. `--generations`, `--popsize`, `--steps` set the budget (CI uses a
small one).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import cma
import numpy as np

import fuzzymotiv as fm

REPO = Path(__file__).resolve().parents[2]


def optimise(generations: int, popsize: int, steps: int, threads: int | None) -> tuple[float, float]:
    """Runs CMA-ES; returns the best F of its first generation and the best F found."""
    problem = fm.Problem(REPO / "configs/tiny.toml", {"trial.steps": steps}, threads=threads)
    es = cma.CMAEvolutionStrategy(
        np.zeros(problem.genome_size), 0.5, {"popsize": popsize, "seed": 1, "verbose": -9}
    )
    first = best = -np.inf
    for generation in range(generations):
        genomes = np.asarray(es.ask())
        f = problem.evaluate(genomes, generation=generation).fitness  # F: higher is better
        es.tell(list(genomes), list(-f))  # cma minimises
        best = max(best, float(f.max()))
        if generation == 0:
            first = best
        print(f"generation {generation:3d}  best F {f.max():.4f}  mean F {f.mean():.4f}  sigma {es.sigma:.3f}")
    return first, best


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    ap.add_argument("--generations", type=int, default=30)
    ap.add_argument("--popsize", type=int, default=16)
    ap.add_argument("--steps", type=int, default=200, help="steps per trial")
    ap.add_argument("--threads", type=int, default=None)
    args = ap.parse_args()
    first, best = optimise(args.generations, args.popsize, args.steps, args.threads)
    print(f"CMA-ES: best F {first:.4f} (generation 0) -> {best:.4f}")
    assert best > first, "CMA-ES did not improve F"


if __name__ == "__main__":
    main()
