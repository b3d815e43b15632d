#!/usr/bin/env bash
# Side-by-side benchmark: fuzzymotiv vs the Enki 2D robot simulator, one Khepera in the H room.
# See bench/README.md. Usage:
#
#   bash bench/run.sh [--steps N] [--rounds K] [--repeat R] [--pop-repeat P] [--no-install]
#
# or the same through the environment: STEPS, ROUNDS, REPEAT, POP_REPEAT.
#   N  robot-steps of each single-robot measurement (default 2000000; whole 400-step trials)
#   K  alternating rounds: fuzzymotiv then Enki, K times each (default 5)
#   R  repetitions inside each run; each run reports its median (default 1)
#   P  repetitions of each population measurement (default 101; one is 200 x 400 steps, ~10 ms)
# FUZZYMOTIV_REV=HEAD measures the last commit instead of the working tree (built from
# `git archive` under target/bench/); FUZZYMOTIV_BIN=path measures an existing binary.
# Prints a table and writes bench/results.json with every raw number.
set -euo pipefail

HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/.." && pwd)"

STEPS="${STEPS:-2000000}"
ROUNDS="${ROUNDS:-5}"
REPEAT="${REPEAT:-1}"
POP_REPEAT="${POP_REPEAT:-101}"
NO_INSTALL="${NO_INSTALL:-0}"
while [ $# -gt 0 ]; do
    case "$1" in
        --steps) STEPS="$2"; shift 2 ;;
        --rounds|-k) ROUNDS="$2"; shift 2 ;;
        --repeat) REPEAT="$2"; shift 2 ;;
        --pop-repeat) POP_REPEAT="$2"; shift 2 ;;
        --no-install) NO_INSTALL=1; shift ;;
        -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
        *) echo "unknown argument: $1 (see --help)" >&2; exit 2 ;;
    esac
done
for v in STEPS ROUNDS REPEAT POP_REPEAT; do
    case "${!v}" in ''|*[!0-9]*|0) echo "$v must be a positive integer, got '${!v}'" >&2; exit 2 ;; esac
done

# ---- 1. tools and 2. builds ----------------------------------------------------------------
. "$HERE/lib.sh"
install_missing libenki-dev g++ make
command -v python3 >/dev/null || { echo "python3 not found" >&2; exit 1; }
build_fuzzymotiv
build_enki

# ---- 3. runs -------------------------------------------------------------------------------
RAW="$(mktemp -d)"
trap 'rm -rf "$RAW"' EXIT
NPROC="$(nproc)"
LOAD_BEFORE="$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || true)"
export LOAD_BEFORE

echo "== $ROUNDS alternating rounds, $STEPS robot-steps each, repeat $REPEAT" >&2
for k in $(seq 1 "$ROUNDS"); do
    # The same workload as Enki's: the first release's model (wheels, no end at home) in its H room.
    "$FM" bench --room "$ROOT/rooms/first-release/H.toml" --motion wheels --set trial.end_at_home=false \
        --steps "$STEPS" --population 200 --repeat "$REPEAT" --threads 1 --json \
        > "$RAW/fm_single_$k.json"
    "$ENKI" --steps "$STEPS" --repeat "$REPEAT" --seed 1 > "$RAW/enki_$k.json"
    # The actions model (the paper's robot) on the same workload.
    "$FM" bench --room "$ROOT/rooms/first-release/H.toml" --motion actions --set trial.end_at_home=false \
        --steps "$STEPS" --population 200 --repeat "$REPEAT" --threads 1 --json > "$RAW/fm_actions_$k.json"
    python3 - "$RAW/fm_single_$k.json" "$RAW/enki_$k.json" "$k" >&2 <<'PY'
import json, sys
f, e = (json.load(open(p)) for p in sys.argv[1:3])
print(f"   round {sys.argv[3]}: fuzzymotiv {f['robot_steps_per_sec']:>12,.0f}   "
      f"enki {e['robot_steps_per_sec']:>10,.0f} robot-steps/s")
PY
done

# Population (200 robots x 400 steps, rayon): 1 thread vs all threads, alternately. The
# single-robot part of these runs is cut to one trial (--steps 400).
echo "== population: --threads 1 vs --threads $NPROC, $ROUNDS rounds, repeat $POP_REPEAT" >&2
for k in $(seq 1 "$ROUNDS"); do
    "$FM" bench --room H --steps 400 --population 200 --repeat "$POP_REPEAT" --threads 1 --json \
        > "$RAW/fm_pop1_$k.json"
    "$FM" bench --room H --steps 400 --population 200 --repeat "$POP_REPEAT" --threads "$NPROC" \
        --json > "$RAW/fm_popn_$k.json"
done

# ---- 4. report -----------------------------------------------------------------------------
python3 - "$RAW" "$HERE/results.json" "$ROUNDS" "$STEPS" "$REPEAT" "$POP_REPEAT" "$NPROC" "$ROOT" <<'PY'
import json, os, platform, statistics, subprocess, sys, datetime

raw, out, rounds, steps, repeat, pop_repeat, nproc, root = sys.argv[1:]
rounds, nproc = int(rounds), int(nproc)
load = lambda name: [json.load(open(os.path.join(raw, f"{name}_{k}.json"))) for k in range(1, rounds + 1)]
fm, enki, pop1, popn = load("fm_single"), load("enki"), load("fm_pop1"), load("fm_popn")
act = load("fm_actions")

def sh(*cmd):
    try:
        return subprocess.run(cmd, capture_output=True, text=True, cwd=root).stdout.strip()
    except OSError:
        return ""

def cpu():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()

def loadavg():
    try:
        return " ".join(open("/proc/loadavg").read().split()[:3])
    except OSError:
        return ""

med = statistics.median
fm_sps = [r["robot_steps_per_sec"] for r in fm]
en_sps = [r["robot_steps_per_sec"] for r in enki]
p1 = [r["population_robot_steps_per_sec"] for r in pop1]
pn = [r["population_robot_steps_per_sec"] for r in popn]
act_sps = [r["robot_steps_per_sec"] for r in act]
fm_m, en_m, p1_m, pn_m = med(fm_sps), med(en_sps), med(p1), med(pn)
act_m = med(act_sps)
threads_n = popn[0]["threads"]

doc = {
    "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
    "machine": {"cpu": cpu(), "nproc": nproc, "kernel": platform.release(),
                "loadavg_before": os.environ.get("LOAD_BEFORE", ""), "loadavg_after": loadavg()},
    "versions": {
        "fuzzymotiv": fm[0].get("version"),
        "fuzzymotiv_source": os.environ.get("FM_SOURCE", ""),
        "rustc": sh("rustc", "--version"),
        "libenki": sh("dpkg-query", "-W", "-f=${Version}", "libenki-dev"),
        "gxx": sh("g++", "-dumpfullversion"),
    },
    "parameters": {"steps": int(steps), "rounds": rounds, "repeat": int(repeat),
                   "pop_repeat": int(pop_repeat), "population": 200, "trial_steps": 400,
                   "room": "H"},
    "summary": {
        "fuzzymotiv_robot_steps_per_sec_median": fm_m,
        "enki_robot_steps_per_sec_median": en_m,
        "ratio_fuzzymotiv_over_enki": fm_m / en_m,
        "actions_robot_steps_per_sec_median": act_m,
        "ratio_actions_over_enki": act_m / en_m,
        "population_1_thread_robot_steps_per_sec_median": p1_m,
        "population_all_threads_robot_steps_per_sec_median": pn_m,
        "population_threads": threads_n,
        "population_speedup": pn_m / p1_m,
    },
    "raw": {
        "fuzzymotiv_single_thread": fm,
        "enki": enki,
        "fuzzymotiv_actions_single_thread": act,
        "fuzzymotiv_population_1_thread": pop1,
        "fuzzymotiv_population_all_threads": popn,
    },
}
with open(out, "w") as f:
    json.dump(doc, f, indent=2)
    f.write("\n")

def row(name, vals, m):
    lo, hi = min(vals), max(vals)
    print(f"{name:<44} {m:>14,.0f} {lo:>14,.0f} {hi:>14,.0f}")

print()
print(f"H room, {fm[0]['robot_steps']:,} robot-steps per run, {rounds} alternating rounds "
      f"({doc['date']}, {doc['machine']['cpu']}, {nproc} cores)")
print(f"{'robot-steps/s':<44} {'median':>14} {'min':>14} {'max':>14}")
row("fuzzymotiv wheels, 1 robot, 1 thread", fm_sps, fm_m)
row("Enki (libenki " + doc["versions"]["libenki"] + "), 1 robot, 1 thread", en_sps, en_m)
print(f"{'ratio of medians fuzzymotiv wheels / Enki':<44} {fm_m / en_m:>14.2f}")
row("fuzzymotiv actions, 1 robot, 1 thread", act_sps, act_m)
print(f"{'ratio of medians fuzzymotiv actions / Enki':<44} {act_m / en_m:>14.2f}")
row("fuzzymotiv population 200x400, 1 thread", p1, p1_m)
row(f"fuzzymotiv population 200x400, {threads_n} threads", pn, pn_m)
print(f"{'population speed-up ' + str(threads_n) + ' threads / 1':<44} {pn_m / p1_m:>14.2f}")
print(f"fuzzymotiv: {doc['versions']['fuzzymotiv_source']}; load average before/after: "
      f"{doc['machine']['loadavg_before']} / {doc['machine']['loadavg_after']} "
      f"(other processes' load skews the numbers, the thread speed-up most)")
print(f"raw numbers: {os.path.relpath(out, root)}")
PY
