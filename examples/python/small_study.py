"""A small study from Python: both of the paper's motivation settings on a shrunken GA, their
fitness curves, and the best high-curiosity robot's path in the H room.

    pip install ./python matplotlib pandas     # in a virtual environment
    python examples/python/small_study.py      # writes small_study.png (about a minute)

Set FUZZYMOTIV_QUICK=1 for a seconds-long version (as the tests do).
"""

import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import fuzzymotiv as fm  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
QUICK = os.environ.get("FUZZYMOTIV_QUICK") == "1"
SHRINK = {
    "ga.population": 12 if QUICK else 40,
    "ga.generations": 4 if QUICK else 30,
    "trial.steps": 100 if QUICK else 400,
    "rooms": ["H", "square"],
    "aem.enabled": False,
}


def main(out: Path = Path("small_study.png")) -> None:
    results = {}
    for name in ("high-curiosity", "low-curiosity"):
        results[name] = fm.run(REPO / "configs" / f"{name}.toml", SHRINK, progress=None)
        print(results[name])

    fig, (curves, path) = plt.subplots(1, 2, figsize=(11, 4.5))
    for name, res in results.items():
        g = res.generations  # a dict of numpy arrays (fm.Table)
        curves.plot(g["generation"], g["best"], label=f"{name} best")
        curves.plot(g["generation"], g["mean"], "--", label=f"{name} mean")
    curves.set(xlabel="generation", ylabel="fuzzy fitness F", title="Fitness evolution")
    curves.legend()

    room = next(r for r in fm.rooms() if r["name"] == "H")
    outline = room["outline"]
    path.fill(outline[:, 0], outline[:, 1], facecolor="#eee", edgecolor="black")
    best = results["high-curiosity"].best_genome
    tr = fm.simulate(best, "H", seed=1, config=REPO / "configs/high-curiosity.toml",
                     overrides={"trial.steps": SHRINK["trial.steps"]})
    path.plot(tr["x"], tr["y"], lw=1)
    path.plot(tr["x"][0], tr["y"][0], "go", label="home")
    path.set(aspect="equal", title=f"Best high-curiosity robot in H: F = {tr['F']:.3f}",
             xlabel="x (mm)", ylabel="y (mm)")
    path.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}; F(a, g, l, b) of that trial: {tr['F']:.4f} "
          f"({tr['a']:.3f}, {tr['g']:.3f}, {tr['l']:.3f}, {tr['b']:.3f})")


if __name__ == "__main__":
    main()
