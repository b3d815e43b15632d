#!/usr/bin/env python3
"""How often the best robot of configs/fetch.toml reaches the goal, per evolution and seed.

    python3 scripts/fetch_missions.py docs/results/fetch-small > docs/results/fetch-small/missions.csv

DIR holds one folder per evolution size (e.g. `p30-g20`), each with one `fuzzymotiv run`
per seed, `seed-N/summary.json`. A run's summary gives, per room, `mission_done_pct`: the share
of the best robot's test runs (`aem.test_runs`, 10 by default) whose mission was done, here
its centre in the room's goal zone. A room counts as *reached* when more than half of its test
runs reach the goal; a seed reaches *most rooms* when more than half of its rooms are reached.

One row per evolution and seed: the rooms, the rooms reached, whether that is most of them
(1 or 0) and the mean `mission_done_pct` over the rooms; then a row `seed = all` per
evolution: every seed's rooms, rooms reached, the number of seeds that reach most rooms, and
the mean `mission_done_pct` over every seed and room. Standard library only.
"""
import csv
import json
import pathlib
import sys


def seed_of(path: pathlib.Path) -> int:
    return int(path.name.removeprefix("seed-"))


def room_pcts(summary: pathlib.Path) -> list[float]:
    rooms = json.loads(summary.read_text())["rooms"]
    missing = [r["room"] for r in rooms if r.get("mission_done_pct") is None]
    if missing:
        sys.exit(f"{summary}: no mission_done_pct for {missing} (a run of configs/fetch.toml with aem enabled?)")
    return [float(r["mission_done_pct"]) for r in rooms]


def rows_of(evolution: pathlib.Path):
    seeds = sorted((p for p in evolution.iterdir() if p.name.startswith("seed-")), key=seed_of)
    if not seeds:
        sys.exit(f"{evolution}: no seed-N run folders")
    every, most = [], 0
    for seed in seeds:
        pcts = room_pcts(seed / "summary.json")
        reached = sum(p > 50 for p in pcts)
        most += 2 * reached > len(pcts)
        every += pcts
        yield [evolution.name, seed_of(seed), len(pcts), reached, int(2 * reached > len(pcts)),
               f"{sum(pcts) / len(pcts):.1f}"]
    yield [evolution.name, "all", len(every), sum(p > 50 for p in every), most,
           f"{sum(every) / len(every):.1f}"]


def main() -> None:
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    root = pathlib.Path(sys.argv[1])
    out = csv.writer(sys.stdout, lineterminator="\n")
    out.writerow(["evolution", "seed", "rooms", "rooms_reached", "most_rooms", "mission_done_pct"])
    for evolution in sorted(p for p in root.iterdir() if p.is_dir()):
        out.writerows(rows_of(evolution))


if __name__ == "__main__":
    main()
