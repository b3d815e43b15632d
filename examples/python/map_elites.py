"""MAP-Elites (pyribs, PyPI name `ribs`) over fuzzymotiv's descriptors: where the robot ends
its trial in the H room (`x`, `y`, normalised to the room's box, docs/model.md), keeping the
controller of highest TSK fitness F in each cell of a 10 × 10 grid.

    python -m venv target/pyenv-ribs           # ribs 0.12 needs numpy >= 2: its own venv
    target/pyenv-ribs/bin/pip install ./python "ribs>=0.12"
    target/pyenv-ribs/bin/python examples/python/map_elites.py

Prints the archive as a map (F of each cell's elite; `.` empty) and checks that the archive
filled beyond its first batch. Deterministic (seeded). `--iterations`, `--batch`, `--steps`
set the budget (CI uses a small one).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from ribs.archives import GridArchive
from ribs.emitters import GaussianEmitter
from ribs.schedulers import Scheduler

import fuzzymotiv as fm

REPO = Path(__file__).resolve().parents[2]
CELLS = 10


def illuminate(iterations: int, batch: int, steps: int, threads: int | None) -> tuple[GridArchive, int]:
    """Runs MAP-Elites; returns the archive and its number of elites after the first batch."""
    overrides = {"rooms": ["H"], "trial.steps": steps, "aem.enabled": False}
    problem = fm.Problem(REPO / "configs/tiny.toml", overrides, threads=threads)
    archive = GridArchive(
        solution_dim=problem.genome_size, dims=[CELLS, CELLS], ranges=[(0.0, 1.0), (0.0, 1.0)], seed=5
    )
    emitter = GaussianEmitter(
        archive, sigma=0.5, x0=np.zeros(problem.genome_size), batch_size=batch, seed=6
    )
    scheduler = Scheduler(archive, [emitter])
    first = 0
    for it in range(iterations):
        genomes = scheduler.ask()
        ev = problem.evaluate(genomes, generation=it, descriptors=["x", "y"])
        assert ev.descriptors is not None
        scheduler.tell(ev.fitness, ev.descriptors[:, 0, :])  # the one room's (x, y)
        if it == 0:
            first = int(archive.stats.num_elites)
        if it % 10 == 0 or it == iterations - 1:
            s = archive.stats
            print(f"iteration {it:4d}  elites {s.num_elites:3d}  coverage {s.coverage:.2f}  best F {s.obj_max:.4f}")
    return archive, first


def show(archive: GridArchive) -> None:
    """The archive as text: rows from y = 1 (top) to 0, columns x = 0 to 1."""
    grid = np.full((CELLS, CELLS), np.nan)
    data = archive.data()
    for idx, f in zip(data["index"], data["objective"]):
        cx, cy = np.unravel_index(int(idx), (CELLS, CELLS))
        grid[cy, cx] = f
    for row in reversed(range(CELLS)):
        print(" ".join("  . " if np.isnan(v) else f"{v:.2f}" for v in grid[row]))


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    ap.add_argument("--iterations", type=int, default=100)
    ap.add_argument("--batch", type=int, default=32, help="genomes per iteration")
    ap.add_argument("--steps", type=int, default=200, help="steps per trial")
    ap.add_argument("--threads", type=int, default=None)
    args = ap.parse_args()
    archive, first = illuminate(args.iterations, args.batch, args.steps, args.threads)
    show(archive)
    s = archive.stats
    print(f"MAP-Elites: {first} elites after the first batch -> {s.num_elites} ({s.coverage:.0%} of the grid), best F {s.obj_max:.4f}")
    assert s.num_elites > first, "the archive did not fill"


if __name__ == "__main__":
    main()
