#!/usr/bin/env python3
"""Mean ± sample std (n − 1) over several `fuzzymotiv reproduce` output directories (one per seed).

Usage: scripts/seeds_table.py results-s1 results-s2 ...   (prints Markdown tables)

Refuses (exit status 1) to average studies of different kinds: quick and full runs, other GA sizes, or
other program versions, and names the file and the field of a summary.json that lacks one it needs.
The field names are those of `StudySummary` in crates/fuzzymotiv-records/src/records/mod.rs; a summary written
before % homing was named `homing_pct` (it was `homing`, like the motivation weight) is read too.
"""
import json
import statistics
import sys

COLS = [("average_fitness", "average fitness", 3), ("exploration_pct", "% optimal exploration", 1),
        ("recognition_pct", "% recognition", 0), ("battery_pct", "% battery usage", 1), ("homing_pct", "% homing", 1)]

OLD_NAMES = {"homing_pct": "homing"}


def cell(row, key):
    """`row[key]`, or its value under the old name; KeyError if neither is there."""
    if key not in row and OLD_NAMES.get(key) in row:
        return row[OLD_NAMES[key]]
    return row[key]


def mean_std(vals, p):
    """`mean ± std` with p decimals; the std is the sample one (n − 1), a dash for one value."""
    if not vals:
        return "n/a"
    mean = statistics.mean(vals)
    return f"{mean:.{p}f} ± " + (f"{statistics.stdev(vals):.{p}f}" if len(vals) > 1 else "—")


SETTING_FIELDS = ("name", "motivations", "population", "generations", "rows", "first_generation", "last_generation")


def missing_field(summary):
    """The path of the first field this script needs that `summary` lacks, or None."""
    for key in ("seed", "version", "quick", "settings", "wall_seconds"):
        if key not in summary:
            return key
    for k, setting in enumerate(summary["settings"]):
        for key in SETTING_FIELDS:
            if key not in setting:
                return f"settings[{k}].{key}"
        for key in ("curiosity", "homing", "orientation", "energy"):
            if key not in setting["motivations"]:
                return f"settings[{k}].motivations.{key}"
        for key in ("mean", "best"):
            for gen in ("first_generation", "last_generation"):
                if key not in setting[gen]:
                    return f"settings[{k}].{gen}.{key}"
        for i, row in enumerate(setting["rows"]):
            for key in ["room"] + [c[0] for c in COLS]:
                if key not in row and OLD_NAMES.get(key) not in row:
                    return f"settings[{k}].rows[{i}].{key}"
    return None


def kind(summary):
    """What must agree between averaged studies: quick flag, GA size per setting, version."""
    sizes = [(s.get("name"), s.get("population"), s.get("generations")) for s in summary.get("settings", [])]
    return {"quick": summary.get("quick"), "GA size": sizes, "version": summary.get("version")}


def check_same_kind(dirs, summaries):
    first = kind(summaries[0])
    for d, s in zip(dirs[1:], summaries[1:]):
        k = kind(s)
        for key in first:
            if k[key] != first[key]:
                sys.exit(f"error: {dirs[0]} and {d} differ in {key} ({first[key]} vs {k[key]}); "
                         "averaging them would mix different studies (e.g. a --quick run and a full one). "
                         "Pass only directories of the same kind.")


def main(dirs):
    if not dirs:
        sys.exit("usage: scripts/seeds_table.py RESULTS_DIR...")
    summaries = []
    for d in dirs:
        try:
            summaries.append(json.load(open(f"{d}/summary.json")))
        except (OSError, ValueError) as e:
            sys.exit(f"error: {d}: not a `fuzzymotiv reproduce` directory ({e})")
    check_same_kind(dirs, summaries)
    for d, summary in zip(dirs, summaries):
        missing = missing_field(summary)
        if missing:
            sys.exit(f"error: {d}/summary.json: missing field `{missing}`")
    seeds = [s["seed"] for s in summaries]
    quick = " (quick: GA 30 × 30)" if summaries[0].get("quick") else ""
    print(f"fuzzymotiv {summaries[0].get('version')}, {len(dirs)} studies{quick}\n")
    for k, setting in enumerate(summaries[0]["settings"]):
        m = setting["motivations"]
        print(f"### {setting['name']} (C, H, O, E) = ({m['curiosity']}, {m['homing']}, {m['orientation']}, {m['energy']}), seeds {seeds}\n")
        print("| room | " + " | ".join(c[1] for c in COLS) + " |")
        print("|---|" + "---|" * len(COLS))
        rows = [s["settings"][k]["rows"] for s in summaries]
        for i, row in enumerate(rows[0]):
            cells = []
            for key, _, p in COLS:
                vals = [cell(r[i], key) for r in rows if cell(r[i], key) is not None]
                cells.append(mean_std(vals, p))
            print(f"| {row['room']} | " + " | ".join(cells) + " |")
        print("\nMean ± std over the studies (std: the sample standard deviation, n − 1; — for one value).")
        firsts = [s["settings"][k]["first_generation"]["mean"] for s in summaries]
        lasts = [s["settings"][k]["last_generation"]["mean"] for s in summaries]
        bests = [s["settings"][k]["last_generation"]["best"] for s in summaries]
        print(f"\nmean F of the population: first generation {mean_std(firsts, 3)}, "
              f"last generation {mean_std(lasts, 3)}; "
              f"best F in the last generation {mean_std(bests, 3)}\n")
    print("wall time per reproduce (s): " + ", ".join(f"{s['wall_seconds']:.1f}" for s in summaries))


if __name__ == "__main__":
    main(sys.argv[1:])
