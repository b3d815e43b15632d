"""NSGA-II (pymoo) over the paper's fitness terms as objectives, and where a study's evolved
robots sit against the Pareto front it finds: which trade-off does each motivation setting pick?

    python -m venv target/pyenv-nsga            # its own venv (matplotlib, pymoo's numpy)
    target/pyenv-nsga/bin/pip install ./python "pymoo==0.6.2" "matplotlib==3.11.2"
    target/pyenv-nsga/bin/python examples/python/nsga2_terms.py --out out/nsga2 \\
        --study results                         # a finished `fuzzymotiv reproduce` directory

No weights, no fuzzy combination: the three objectives are the terms the paper's motivations
weigh (docs/model.md §7), each averaged over the rooms and maximised in the direction its
motivation rewards: exploration a (curiosity), homing g (homing) and battery use b (energy:
with `fitness.energy = "use"`, the default, the fuzzy input is b, "the opposite of laziness";
with "conserve" it is 1 − b). Orientation l is 0 during evaluation (measured off-line) and is
left out. `fm.Problem` evaluates each generation in one batched call (genome i of generation g
on the built-in GA's streams for individual i of generation g). Seeded: the same seed gives the
same front.

Then the final population and each setting's best robot per seed (`SETTING/seed-NN/
best_genome.json`, with `--study`) are evaluated again, all on the same streams (individuals
0 … R−1 of a generation no GA reaches, `--repeats` R, in the same rooms), so the placement is a
paired comparison; the front is the population's non-dominated members by that evaluation
(a front picked on one noisy trial per room would flatter itself). Writes `front.svg` (three
2-D projections; `--png` also `front.png`), `front.csv` and `robots.csv` under `--out`, and
prints per setting its robots' mean objectives, the front point nearest
them, and each robot's distance to the front: 0 when no front point dominates it (on the front,
or beyond it where NSGA-II missed something), else the distance of IGD+ (Ishibuchi et al.
2015), min over front points p of sqrt(Σ_k max(p_k − r_k, 0)²): how far, in the objectives'
own units, the robot falls short of the nearest front point where it falls short.
"""

from __future__ import annotations

import argparse
import csv
import importlib
import json
import os
import sys
from pathlib import Path
from typing import Any, NoReturn

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import numpy.typing as npt  # noqa: E402
from pymoo.algorithms.moo.nsga2 import NSGA2  # noqa: E402
from pymoo.core.evaluator import Evaluator  # noqa: E402
from pymoo.core.problem import Problem as MooProblem  # noqa: E402
from pymoo.problems.static import StaticProblem  # noqa: E402

import fuzzymotiv as fm  # noqa: E402

Array = npt.NDArray[np.float64]
WEIGHT_LIMIT = 5.0  # [ga] weight_limit: the GA clips every weight to [-5, 5]
INIT_RANGE = 1.0  # [ga] init_range: the GA's first population is uniform in [-1, 1]
PLACEMENT_GENERATION = 1_000_000  # the placement's streams: a generation no GA reaches
# What the terms of a robot depend on besides its genome: the settings of a study must agree.
SAME_IN_EVERY_SETTING = ("rooms", "training", "trial", "robot", "network", "fitness")


def fail(message: str) -> NoReturn:
    """A usage error: the message, exit code 2, nothing written."""
    print(f"nsga2_terms.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_toml(path: Path) -> dict[str, Any]:
    """A TOML file (tomllib, Python 3.11+; tomli before)."""
    try:
        toml: Any = importlib.import_module("tomllib")
    except ImportError:
        toml = importlib.import_module("tomli")
    with open(path, "rb") as f:
        doc: dict[str, Any] = toml.load(f)
    return doc


class Objectives:
    """The objectives (a, g and b or 1 − b) from `fm.Problem`'s terms, averaged over rooms."""

    def __init__(self, term_names: list[str], energy: str) -> None:
        missing = [t for t in ("a", "g", "b") if t not in term_names]
        if missing:
            fail(f"the config's motivations weigh no term {', '.join(missing)}: NSGA-II here "
                 "needs curiosity (a), homing (g) and energy (b)")
        if energy not in ("use", "conserve"):
            fail(f"fitness.energy = {energy!r}: expected \"use\" or \"conserve\"")
        self.columns = [term_names.index(t) for t in ("a", "g", "b")]
        self.l_column = term_names.index("l") if "l" in term_names else None
        self.conserve = energy == "conserve"
        battery = "battery saving 1 − b" if self.conserve else "battery use b"
        self.labels = ["exploration a", "homing g", battery]
        self.keys = ["a", "g", "1-b" if self.conserve else "b"]

    def of(self, terms: Array) -> Array:
        """(pop, rooms, N) terms -> (pop, 3) objectives, higher is better."""
        if self.l_column is not None and np.any(terms[:, :, self.l_column] != 0.0):
            fail("orientation l is not 0 in evaluation (fitness.orientation = \"online\"?): "
                 "this example leaves l out and needs it off-line")
        y = terms[:, :, self.columns].mean(axis=1)
        if self.conserve:
            y[:, 2] = 1.0 - y[:, 2]
        return np.asarray(y, dtype=np.float64)


def evolve(problem: fm.Problem, obj: Objectives, population: int, generations: int, seed: int) -> Array:
    """NSGA-II, ask/tell, one batched evaluate per generation; returns the final population
    (its front is picked after the placement's less noisy evaluation)."""
    bounds = MooProblem(n_var=problem.genome_size, n_obj=3, xl=-WEIGHT_LIMIT, xu=WEIGHT_LIMIT)
    start = np.random.default_rng(seed).uniform(-INIT_RANGE, INIT_RANGE, (population, problem.genome_size))
    algorithm = NSGA2(pop_size=population, sampling=start)
    algorithm.setup(bounds, termination=("n_gen", generations), seed=seed, verbose=False)
    for generation in range(generations):
        pop = algorithm.ask()
        y = obj.of(problem.evaluate(pop.get("X"), generation=generation).terms)
        Evaluator().eval(StaticProblem(bounds, F=-y), pop)  # pymoo minimises
        algorithm.tell(infills=pop)
        front = -algorithm.opt.get("F")
        if generation % 5 == 0 or generation == generations - 1:
            best = "  ".join(f"max {k} {v:.3f}" for k, v in zip(obj.keys, front.max(axis=0)))
            print(f"generation {generation:3d}  front {len(front):3d}  {best}")
    genomes: Array = np.asarray(algorithm.pop.get("X"), dtype=np.float64)
    return genomes


def place(problem: fm.Problem, obj: Objectives, genomes: Array, repeats: int) -> Array:
    """Each genome's objectives on the same streams: individuals 0 … repeats−1 of
    PLACEMENT_GENERATION, in every room of the problem, averaged."""
    out = np.empty((len(genomes), 3))
    for i, genome in enumerate(genomes):
        copies = np.repeat(genome[None, :], repeats, axis=0)
        out[i] = obj.of(problem.evaluate(copies, generation=PLACEMENT_GENERATION).terms).mean(axis=0)
    return out


def nondominated(y: Array) -> npt.NDArray[np.bool_]:
    """Which rows no other row dominates (maximising every column)."""
    ge = (y[:, None, :] >= y[None, :, :]).all(axis=2)
    gt = (y[:, None, :] > y[None, :, :]).any(axis=2)
    dominated_by = ge & gt  # [j, i]: row j dominates row i
    return np.asarray(~dominated_by.any(axis=0))


def dominates(p: Array, r: Array) -> bool:
    """p is at least r in every objective and above it in one."""
    return bool((p >= r).all() and (p > r).any())


def position(robot: Array, front: Array) -> tuple[float, str]:
    """The robot's distance to the front (0 unless dominated; then IGD+'s distance, min over p
    of the norm of max(p − r, 0)) and where it is: dominated, on the front, or beyond it."""
    if any(dominates(p, robot) for p in front):
        shortfall = np.maximum(front - robot[None, :], 0.0)
        return float(np.sqrt((shortfall**2).sum(axis=1)).min()), "dominated"
    return 0.0, "beyond the front" if any(dominates(robot, p) for p in front) else "on the front"


class Study:
    """A finished `fuzzymotiv reproduce` directory's settings and best robots per seed."""

    def __init__(self, root: Path) -> None:
        if not root.is_dir():
            fail(f"--study {root}: not a directory; give a finished `fuzzymotiv reproduce` directory")
        self.runs: dict[str, list[tuple[str, Path]]] = {}
        for folder in sorted(p for p in root.iterdir() if p.is_dir()):
            seeds = sorted((d for d in folder.glob("seed-*") if (d / "best_genome.json").is_file()),
                           key=lambda d: (len(d.name), d.name))
            if seeds:
                self.runs[folder.name] = [(d.name.removeprefix("seed-"), d) for d in seeds]
        if not self.runs:
            fail(f"--study {root}: no SETTING/seed-NN/best_genome.json in it; give a finished "
                 "`fuzzymotiv reproduce` directory")
        self.configs = {s: read_toml(self._file(runs[0][1], "config.resolved.toml")) for s, runs in self.runs.items()}
        first, config = next(iter(self.configs.items()))
        for setting, other in self.configs.items():
            for key in SAME_IN_EVERY_SETTING:
                if other.get(key) != config.get(key):
                    fail(f"--study {root}: setting {setting!r} has another {key!r} than {first!r} "
                         f"({other.get(key)!r} vs {config.get(key)!r}); its robots' terms are not comparable")
        if config.get("training") != "all-rooms":
            fail(f"--study {root}: training = {config.get('training')!r}; this example needs \"all-rooms\" "
                 "(one robot per seed for every room)")
        self.config_file = self._file(self.runs[first][0][1], "config.resolved.toml")
        self.config = config

    @staticmethod
    def _file(run: Path, name: str) -> Path:
        if not (run / name).is_file():
            fail(f"--study: {run / name} is missing; is the study finished?")
        return run / name

    def genomes(self, setting: str, size: int) -> Array:
        """The setting's best robot per seed, as rows."""
        rows = []
        for _, run in self.runs[setting]:
            path = run / "best_genome.json"
            try:
                weights = json.loads(path.read_text())["weights"]
            except (OSError, ValueError, KeyError, TypeError) as e:
                fail(f"--study: {path}: cannot read its \"weights\" ({e})")
            if len(weights) != size:
                fail(f"--study: {path}: {len(weights)} weights, but the problem's network has {size}")
            rows.append(weights)
        return np.asarray(rows, dtype=np.float64)


def write_csv(path: Path, header: list[str], rows: list[list[Any]]) -> None:
    """Written whole or not at all (a temporary file renamed)."""
    tmp = path.with_name(path.name + ".tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows([[f"{v:.6f}" if isinstance(v, float) else v for v in row] for row in rows])
    os.replace(tmp, path)


def figure(path: Path, obj: Objectives, front: Array, robots: dict[str, Array]) -> None:
    """Three 2-D projections of the objectives: the front, and a marker per setting."""
    pairs = [(0, 1), (0, 2), (1, 2)]
    fig, axes = plt.subplots(1, 3, figsize=(13.5, 4.4), constrained_layout=True)
    markers = ["o", "s", "^", "D", "v", "P", "X", "*"]
    for ax, (i, j) in zip(axes, pairs):
        order = np.argsort(front[:, i])
        ax.scatter(front[order, i], front[order, j], s=18, c="0.55", label="NSGA-II front", zorder=2)
        for k, (setting, y) in enumerate(robots.items()):
            ax.scatter(y[:, i], y[:, j], s=34, marker=markers[k % len(markers)], label=setting,
                       edgecolors="black", linewidths=0.5, zorder=3)
        ax.set_xlabel(obj.labels[i])
        ax.set_ylabel(obj.labels[j])
        ax.grid(True, lw=0.3)
    axes[0].legend(loc="best", fontsize=8)
    fig.suptitle("NSGA-II front over the terms (higher is better), and each setting's robots (one point per seed)",
                 fontsize=10)
    tmp = path.with_name(path.name + ".tmp")
    fig.savefig(tmp, format=path.suffix.lstrip("."))
    plt.close(fig)
    os.replace(tmp, path)


def report(obj: Objectives, front: Array, study: Study, robots: dict[str, Array]) -> list[list[Any]]:
    """Prints where each setting's robots sit; returns robots.csv's rows."""
    rows: list[list[Any]] = []

    def fmt(y: Array) -> str:
        return ", ".join(f"{k} {v:.3f}" for k, v in zip(obj.keys, y))

    for setting, y in robots.items():
        mean = y.mean(axis=0)
        nearest = int(np.linalg.norm(front - mean, axis=1).argmin())
        print(f"{setting}: robots' mean ({fmt(mean)}); nearest front point {nearest} ({fmt(front[nearest])})")
        dists, wheres = [], []
        for (seed, _), r in zip(study.runs[setting], y):
            d, where = position(r, front)
            near = int(np.linalg.norm(front - r, axis=1).argmin())
            dists.append(d)
            wheres.append(where)
            rows.append([setting, seed, *[float(v) for v in r], d, where, near])
        counts = ", ".join(f"{wheres.count(w)} {w}" for w in ("dominated", "on the front", "beyond the front"))
        print(f"  distance to the front per seed: {' '.join(f'{d:.3f}' for d in dists)} "
              f"(mean {np.mean(dists):.3f}; {counts})")
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    ap.add_argument("--population", type=int, default=40)
    ap.add_argument("--generations", type=int, default=15)
    ap.add_argument("--steps", type=int, default=None,
                    help="steps per trial (default: the study's, else the paper's 400)")
    ap.add_argument("--repeats", type=int, default=5, help="streams per genome in the placement")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--study", type=Path, default=None, help="a finished `fuzzymotiv reproduce` directory")
    ap.add_argument("--out", type=Path, required=True, help="directory for front.svg, front.csv, robots.csv")
    ap.add_argument("--force", action="store_true", help="replace front.* and robots.csv already in --out")
    ap.add_argument("--png", action="store_true", help="also write front.png (to look at)")
    args = ap.parse_args()
    for name in ("population", "generations", "repeats"):
        if getattr(args, name) < 1:
            fail(f"--{name} {getattr(args, name)}: expected a whole number of at least 1")
    if args.steps is not None and args.steps < 1:
        fail(f"--steps {args.steps}: expected a whole number of at least 1")
    outputs = [args.out / n for n in ("front.svg", "front.csv", "robots.csv", "front.png")][: 4 if args.png else 3]
    if args.out.exists() and not args.out.is_dir():
        fail(f"--out {args.out}: a file, not a directory")
    if not args.force and any(p.exists() for p in outputs):
        fail(f"--out {args.out}: holds earlier results ({', '.join(p.name for p in outputs if p.exists())}); "
             "add --force to replace them")
    study = None if args.study is None else Study(args.study)
    config_file = None if study is None else study.config_file
    steps = args.steps if args.steps is not None else 400 if study is None else int(study.config["trial"]["steps"])
    energy = "use" if study is None else str(study.config["fitness"]["energy"])
    if study is not None and steps != study.config["trial"]["steps"]:
        print(f"note: the study's robots evolved with trial.steps = {study.config['trial']['steps']}, "
              f"placed here with {steps}")
    try:
        problem = fm.Problem(config_file, {"trial.steps": steps}, seed=args.seed, threads=args.threads)
    except fm.FuzzymotivError as e:
        fail(str(e))
    obj = Objectives(problem.term_names, energy)
    print(f"NSGA-II: population {args.population}, {args.generations} generations, {steps} steps, "
          f"rooms {', '.join(problem.rooms)}, seed {args.seed}; objectives {', '.join(obj.labels)}")
    genomes = evolve(problem, obj, args.population, args.generations, args.seed)

    print(f"placement: every genome on the same streams (individuals 0..{args.repeats - 1} of generation "
          f"{PLACEMENT_GENERATION}, seed {args.seed}), averaged over them and the rooms")
    placed = place(problem, obj, genomes, args.repeats)
    keep = nondominated(placed)
    front, genomes = placed[keep], genomes[keep]
    print(f"front: {len(front)} of the final population's {len(placed)} non-dominated when evaluated again")
    robots = {} if study is None else {s: place(problem, obj, study.genomes(s, problem.genome_size), args.repeats)
                                       for s in study.runs}
    rows = [] if study is None else report(obj, front, study, robots)

    args.out.mkdir(parents=True, exist_ok=True)
    write_csv(outputs[1], ["point", *obj.keys], [[i, *map(float, y)] for i, y in enumerate(front)])
    write_csv(outputs[2], ["setting", "seed", *obj.keys, "distance_to_front", "position", "nearest_front_point"], rows)
    for picture in [outputs[0], *outputs[3:]]:
        figure(picture, obj, front, robots)
    print(f"wrote {', '.join(str(p) for p in outputs)}")
    assert len(front) > 0, "the front is empty"
    assert all(p.is_file() and p.stat().st_size > 0 for p in outputs), "an output is missing"
    if study is not None:
        assert len(rows) == sum(len(r) for r in study.runs.values()), "a robot was not placed"


if __name__ == "__main__":
    main()
