#!/usr/bin/env python3
"""What decides a study's claims, from its records (EXPERIMENTS.md): per setting of a
`fuzzymotiv reproduce` directory (or of every `pop-N/` of a `--search-strength` one), the
test runs recognised, not recognised (the SOM gate) and given to the wrong room; the
exploration per room; and the last generation's best and mean F. Reads summary.json only.

    python3 scripts/study_details.py results
    python3 scripts/study_details.py results-search-strength
"""

import json
import statistics
import sys
from pathlib import Path


def confusion_counts(setting):
    """(correct, not recognised, wrong) test runs over every seed and room."""
    correct = gate = wrong = 0
    for seed in setting["per_seed"]:
        for robot in seed["confusion"]:
            for true, row in enumerate(robot):
                for answer, n in enumerate(row):
                    if answer == len(row) - 1:
                        gate += n
                    elif answer == true:
                        correct += n
                    else:
                        wrong += n
    return correct, gate, wrong


def seed_mean(seed, key):
    values = [r[key] for r in seed["rows"] if r[key] is not None]
    return statistics.mean(values) if values else float("nan")


def describe(label, summary):
    print(f"## {label}: GA {summary['population']} x {summary['generations']}, "
          f"{len(summary['seeds'])} seeds")
    for s in summary["settings"]:
        c, g, w = confusion_counts(s)
        total = c + g + w
        expl = [seed_mean(x, "exploration_pct") for x in s["per_seed"]]
        print(f"- {s['name']}: test runs {total}: correct {c}, not recognised {g}, "
              f"wrong room {w}; exploration per seed min {min(expl):.1f} "
              f"median {statistics.median(expl):.1f} max {max(expl):.1f}; "
              f"last generation best F {s['last_generation']['best']:.3f}, "
              f"mean F {s['last_generation']['mean']:.3f}")
        rooms = ", ".join(f"{r['room']} {r['exploration_pct']:.1f}" for r in s["rows"])
        print(f"  exploration per room (mean over seeds): {rooms}")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    root = Path(sys.argv[1])
    if (root / "summary.json").is_file() and not (root / "search_strength.md").exists():
        describe(root.name, json.loads((root / "summary.json").read_text()))
        return
    dirs = sorted(root.glob("pop-*/summary.json"), key=lambda p: int(p.parent.name[4:]))
    if not dirs:
        sys.exit(f"{root}: neither a study (summary.json) nor a search-strength study (pop-N/)")
    for p in dirs:
        describe(p.parent.name, json.loads(p.read_text()))


if __name__ == "__main__":
    main()
