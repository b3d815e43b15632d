"""A term of your own, in Python: smoothness of the path, weighed by a fifth motivation beside
the paper's four, in a small evolution with the built-in GA (ask/tell).

    pip install ./python                    # in a virtual environment
    python examples/python/own_term.py      # from the repository root

Smoothness of one trial = 1 − mean |Δheading| / π over the steps it executed (1: never turned;
0: turned 180° at every step). `fm.Problem(..., terms={"smoothness": fn})` calls `fn` once per
generation with all the generation's evaluation trials (`fm.Trials`: numpy arrays
`(pop, rooms, ...)`); it returns `(pop, rooms)` values in [0, 1], which set F. Prints the
smoothness and F of the population before and after; `--generations`, `--population`,
`--steps` set the budget (CI uses a small one).
"""

from __future__ import annotations

import argparse

import numpy as np
import numpy.typing as npt

import fuzzymotiv as fm

CONFIG = """
name = "smooth"
rooms = ["H", "T", "square"]

[aem]
enabled = false

[motivations]
curiosity = 0.5
homing = 0.1
orientation = 0.0
energy = 0.1
smooth = { weight = 0.3, term = "smoothness" }
"""


def smoothness(trials: fm.Trials) -> npt.NDArray[np.float64]:
    """1 − mean |Δheading| / π over each trial's executed steps, shape (pop, rooms)."""
    turn = np.abs(np.angle(np.exp(1j * np.diff(trials.heading, axis=-1))))  # in [0, π]
    executed = ~trials.idle
    mean_turn = (turn * executed).sum(-1) / np.maximum(executed.sum(-1), 1)
    values: npt.NDArray[np.float64] = 1.0 - mean_turn / np.pi
    return values


def evolve(generations: int, population: int, steps: int, threads: int | None) -> dict[str, float]:
    problem = fm.Problem(
        config_text=CONFIG,
        overrides={"ga.population": population, "ga.generations": generations, "trial.steps": steps},
        terms={"smoothness": smoothness},
        threads=threads,
    )
    print("inputs of the fuzzy fitness:", problem.term_names)
    smooth = problem.term_names.index("smoothness")
    ga = fm.GA(problem)
    result: dict[str, float] = {}
    for g in range(generations):
        ev = problem.evaluate(ga.ask(), generation=ga.generation, seed=ga.seed)
        ga.tell(ev.fitness, ev.terms)
        s = ev.terms[..., smooth].mean(axis=1)  # per robot, over the rooms
        best = int(ev.fitness.argmax())
        print(f"generation {g:3d}  mean F {ev.fitness.mean():.4f}  best F {ev.fitness[best]:.4f}  "
              f"smoothness mean {s.mean():.3f} best robot's {s[best]:.3f}")
        if g == 0:
            result["before: mean F"], result["before: smoothness"] = float(ev.fitness.mean()), float(s.mean())
    result["after: mean F"], result["after: smoothness"] = float(ev.fitness.mean()), float(s.mean())
    assert ga.best is not None
    result["best F"] = ga.best.fitness
    return result


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    ap.add_argument("--generations", type=int, default=30)
    ap.add_argument("--population", type=int, default=40)
    ap.add_argument("--steps", type=int, default=400, help="steps per trial")
    ap.add_argument("--threads", type=int, default=None)
    args = ap.parse_args()
    r = evolve(args.generations, args.population, args.steps, args.threads)
    for name, value in r.items():
        print(f"{name:20s} {value:.4f}")
    assert 0.0 <= r["after: smoothness"] <= 1.0
    assert r["best F"] > r["before: mean F"], "evolution found nothing better than the first generation's mean"


if __name__ == "__main__":
    main()
