#!/usr/bin/env bash
# Kheperax beside fuzzymotiv at the same batch sizes: robot-steps per second of Kheperax's
# standard maze task (JAX on CPU, an MLP policy, batch B = 1, 64, 1024) and of fuzzymotiv's
# `wheels` robot in a room with the same maze walls (bench/kheperax/kheperax-maze.toml), its
# lanes' population = B (B = 1: one robot, `bench`'s one-robot measurement), on one core and on
# two. Usage:
#
#   bash bench/kheperax/run.sh [--repeat R] [--rounds K]
#
# Creates its own venv (target/bench/kheperax-venv, `python3 -m venv`) and `pip install
# kheperax` there (JAX for CPU comes with it). K rounds (default 3), alternating: Kheperax on one
# core (`taskset -c 0`), Kheperax on cores 0-1, then `fuzzymotiv bench --room
# bench/kheperax/kheperax-maze.toml --motion wheels --set trial.end_at_home=false --population B
# --threads 1` under `taskset -c 0` and `--threads 2` under `taskset -c 0,1`, B = 64 and 1024;
# each measurement the median of R repetitions (default 5), JAX's compilation (first call)
# excluded. Prints a table of the medians over the rounds and the ratios fuzzymotiv / Kheperax
# per batch and core count, and writes every raw document to bench/kheperax/results.json.
# FUZZYMOTIV_BIN / FUZZYMOTIV_REV as in bench/run.sh.
set -euo pipefail

HERE="$(cd "$(dirname "$0")/.." && pwd)"
ROOT="$(cd "$HERE/.." && pwd)"
REPEAT=5
ROUNDS=3
while [ $# -gt 0 ]; do
    case "$1" in
        --repeat) REPEAT="$2"; shift 2 ;;
        --rounds) ROUNDS="$2"; shift 2 ;;
        -h|--help) sed -n '2,18p' "$0"; exit 0 ;;
        *) echo "unknown argument: $1" >&2; exit 2 ;;
    esac
done
for v in "$REPEAT" "$ROUNDS"; do
    case "$v" in ''|*[!0-9]*|0) echo "--repeat and --rounds must be positive integers" >&2; exit 2 ;; esac
done

. "$HERE/lib.sh"
build_fuzzymotiv
VENV="$ROOT/target/bench/kheperax-venv"
if [ ! -x "$VENV/bin/python" ] || ! "$VENV/bin/python" -c 'import kheperax' 2>/dev/null; then
    echo "== python3 -m venv $VENV; pip install kheperax" >&2
    python3 -m venv "$VENV"
    "$VENV/bin/pip" install -q --upgrade pip
    "$VENV/bin/pip" install -q kheperax
fi

TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
ROOM="$ROOT/bench/kheperax/kheperax-maze.toml"
for k in $(seq 1 "$ROUNDS"); do
    echo "== round $k/$ROUNDS (load average $(cut -d' ' -f1 /proc/loadavg))" >&2
    JAX_PLATFORMS=cpu taskset -c 0 "$VENV/bin/python" "$HERE/kheperax/kheperax_steps.py" \
        --repeat "$REPEAT" >"$TMP/kx1-$k.json"
    JAX_PLATFORMS=cpu taskset -c 0,1 "$VENV/bin/python" "$HERE/kheperax/kheperax_steps.py" \
        --repeat "$REPEAT" >"$TMP/kx2-$k.json"
    for t in 1 2; do
        cpus=0; [ "$t" = 2 ] && cpus=0,1
        for b in 64 1024; do
            # Whole generations of B 400-step trials, at least 800,000 robot-steps.
            steps=$((b * 400 * (b < 2000 ? (2000 + b - 1) / b : 1)))
            taskset -c "$cpus" "$FM" bench --room "$ROOM" --motion wheels \
                --set trial.end_at_home=false --steps "$steps" --population "$b" \
                --repeat "$REPEAT" --threads "$t" --json >"$TMP/fm$t-$b-$k.json"
        done
    done
done

python3 - "$TMP" "$ROUNDS" "$HERE/kheperax/results.json" "$FM_SOURCE" <<'PY'
import datetime, json, statistics, sys
tmp, rounds, out, source = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
load = lambda p: json.load(open(p))
doc = {"date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
       "fuzzymotiv_source": source, "rounds": {}}
rows, med = [], {}
for cores in (1, 2):
    docs = [load(f"{tmp}/kx{cores}-{k}.json") for k in range(1, rounds + 1)]
    doc["rounds"][f"kheperax_cores_{cores}"] = docs
    for i, run in enumerate(docs[0]["runs"]):
        rates = [d["runs"][i]["median_robot_steps_per_sec"] for d in docs]
        rows.append((f"Kheperax, {cores} core(s), batch {run['batch']}", rates))
        med[("kx", cores, run["batch"])] = statistics.median(rates)
    for b in (64, 1024):
        docs = [load(f"{tmp}/fm{cores}-{b}-{k}.json") for k in range(1, rounds + 1)]
        doc["rounds"][f"fuzzymotiv_threads_{cores}_population_{b}"] = docs
        if b == 64:  # one robot, simulate: `bench`'s first measurement, one thread
            rates = [d["robot_steps_per_sec"] for d in docs]
            rows.append((f"fuzzymotiv wheels, {cores} core(s), 1 robot", rates))
            med[("fm", cores, 1)] = statistics.median(rates)
        rates = [d["population_robot_steps_per_sec"] for d in docs]
        rows.append((f"fuzzymotiv wheels, {cores} core(s), population {b}", rates))
        med[("fm", cores, b)] = statistics.median(rates)
doc["medians"] = {label: statistics.median(r) for label, r in rows}
doc["ratios"] = {}
print(f"| robot-steps/s | median of {rounds} rounds | min | max |")
print("|---|---:|---:|---:|")
for label, r in rows:
    print(f"| {label} | {statistics.median(r):,.0f} | {min(r):,.0f} | {max(r):,.0f} |")
print()
print("| fuzzymotiv / Kheperax (medians) | batch 1 | batch 64 | batch 1024 |")
print("|---|---:|---:|---:|")
for cores in (1, 2):
    ratios = {b: med[("fm", cores, b)] / med[("kx", cores, b)] for b in (1, 64, 1024)}
    doc["ratios"][f"cores_{cores}"] = {str(b): r for b, r in ratios.items()}
    print(f"| {cores} core(s) | " + " | ".join(f"{ratios[b]:.1f}x" for b in (1, 64, 1024)) + " |")
with open(out, "w") as f:
    json.dump(doc, f, indent=2)
    f.write("\n")
PY
