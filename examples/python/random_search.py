"""Random search with plain numpy against fuzzymotiv's TSK fitness: uniform random genomes, then
a (1+λ) local search around the best of them.

    pip install ./python                       # in a virtual environment
    python examples/python/random_search.py    # from the repository root

Deterministic (seeded); checks that the genome found, evaluated again on fresh noise, beats
the mean F of random genomes. `--samples`, `--generations`, `--steps` set the
budget (CI uses a small one).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

import fuzzymotiv as fm

REPO = Path(__file__).resolve().parents[2]


def search(samples: int, generations: int, lam: int, steps: int, threads: int | None) -> dict[str, float]:
    """Random sampling, then a (1+λ) search in which the parent is evaluated again beside its
    children every generation (F is noisy: a lucky evaluation must not stick). Returns the F
    of each phase; the final parent's F is its mean over five fresh evaluations."""
    problem = fm.Problem(REPO / "configs/tiny.toml", {"trial.steps": steps}, threads=threads)
    rng = np.random.default_rng(3)
    genomes = rng.uniform(-1.0, 1.0, (samples, problem.genome_size))
    f = problem.evaluate(genomes).fitness  # F: higher is better
    parent = genomes[f.argmax()]
    result = {"random mean": float(f.mean()), "random best": float(f.max())}
    for generation in range(1, generations + 1):
        children = parent + 0.3 * rng.standard_normal((lam, problem.genome_size))
        batch = np.vstack([parent[None], children])
        fb = problem.evaluate(batch, generation=generation).fitness
        parent = batch[fb.argmax()]
        print(f"generation {generation:3d}  parent F {fb[0]:.4f}  best child F {fb[1:].max():.4f}")
    again = [problem.evaluate(parent[None], generation=1000 + k).fitness[0] for k in range(5)]
    result["(1+λ) final"] = float(np.mean(again))
    return result


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    ap.add_argument("--samples", type=int, default=200)
    ap.add_argument("--generations", type=int, default=40)
    ap.add_argument("--lam", type=int, default=8, help="children per generation")
    ap.add_argument("--steps", type=int, default=200, help="steps per trial")
    ap.add_argument("--threads", type=int, default=None)
    args = ap.parse_args()
    r = search(args.samples, args.generations, args.lam, args.steps, args.threads)
    for name, value in r.items():
        print(f"{name:12s} F {value:.4f}")
    assert r["random best"] > r["random mean"], "the best random genome is no better than the mean"
    assert r["(1+λ) final"] > r["random mean"], "the search found nothing better than random genomes"


if __name__ == "__main__":
    main()
