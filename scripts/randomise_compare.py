#!/usr/bin/env python3
"""Robustness of robots evolved with and without [trial.randomise], paired by seed.

    python3 scripts/randomise_compare.py PLAIN_DIR RANDOMISED_DIR > randomise.csv

Each DIR holds one `fuzzymotiv robustness` table per seed, `seed-NN.csv` (the same seeds in
both). Per seed and robot: F unperturbed (the row `none`), the mean F over the perturbations,
the worst F and, when the tables have it, the share of trials recognised as their room,
unperturbed and over the perturbations; then, per measure, randomised − plain: the mean over
seeds, the two-sided sign-flip permutation p (exact over all 2^n sign patterns) and the number
of seeds where the randomised robot is ahead. Standard library only.
"""
import csv
import itertools
import pathlib
import sys


def measures(path: pathlib.Path) -> dict[str, float]:
    rows = list(csv.DictReader(path.open()))
    none = [float(r["f"]) for r in rows if r["perturbation"] == "none"]
    rest = [float(r["f"]) for r in rows if r["perturbation"] != "none"]
    out = {"f_unperturbed": none[0], "f_mean_perturbed": sum(rest) / len(rest), "f_worst": min(rest)}
    if rows and rows[0].get("recognition"):
        # The share of trials the robot's own (unperturbed) room model recognises.
        none = [float(r["recognition"]) for r in rows if r["perturbation"] == "none"]
        rest = [float(r["recognition"]) for r in rows if r["perturbation"] != "none"]
        out["recognition_unperturbed"] = none[0]
        out["recognition_mean_perturbed"] = sum(rest) / len(rest)
    return out


def sign_flip_p(d: list[float]) -> float:
    observed = abs(sum(d))
    count = total = 0
    for signs in itertools.product((1, -1), repeat=len(d)):
        total += 1
        count += abs(sum(s * x for s, x in zip(signs, d))) >= observed - 1e-12
    return count / total


def main() -> None:
    plain, rand = (pathlib.Path(a) for a in sys.argv[1:3])
    seeds = sorted(p.name for p in plain.glob("seed-*.csv"))
    if not seeds or seeds != sorted(p.name for p in rand.glob("seed-*.csv")):
        sys.exit("error: both directories need the same seed-NN.csv files")
    a = [measures(plain / s) for s in seeds]
    b = [measures(rand / s) for s in seeds]
    w = csv.writer(sys.stdout, lineterminator="\n")
    w.writerow(["measure", "seeds", "plain", "randomised", "difference", "p", "randomised_ahead"])
    for m in (k for k in a[0] if all(k in x for x in a + b)):
        d = [y[m] - x[m] for x, y in zip(a, b)]
        n = len(d)
        w.writerow([m, n, f"{sum(x[m] for x in a) / n:.6f}", f"{sum(y[m] for y in b) / n:.6f}",
                    f"{sum(d) / n:.6f}", f"{sign_flip_p(d):.6f}", sum(x > 0 for x in d)])


if __name__ == "__main__":
    main()
