#!/usr/bin/env bash
# Kheperax beside fuzzymotiv: robot-steps per second of Kheperax's standard maze task (JAX on
# CPU, an MLP policy, batch sizes 1, 64 and 1024) and of fuzzymotiv's `wheels` robot in a room
# with the same maze walls (bench/kheperax/kheperax-maze.toml), one and two threads. Usage:
#
#   bash bench/kheperax/run.sh [--repeat R] [--rounds K]
#
# Creates its own venv (target/bench/kheperax-venv, `python3 -m venv`) and `pip install
# kheperax` there (JAX for CPU comes with it). K rounds (default 3), alternating: Kheperax on one
# core (`taskset -c 0`), Kheperax on every core, then `fuzzymotiv bench --room
# bench/kheperax/kheperax-maze.toml --motion wheels --set trial.end_at_home=false --population
# 200 --threads 1` and `--threads 2`; each measurement the median of R repetitions (default 5),
# JAX's compilation (first call) excluded. Prints a table of the medians over the rounds and
# writes every raw document to bench/kheperax/results.json. FUZZYMOTIV_BIN / FUZZYMOTIV_REV as in
# bench/run.sh.
set -euo pipefail

HERE="$(cd "$(dirname "$0")/.." && pwd)"
ROOT="$(cd "$HERE/.." && pwd)"
REPEAT=5
ROUNDS=3
while [ $# -gt 0 ]; do
    case "$1" in
        --repeat) REPEAT="$2"; shift 2 ;;
        --rounds) ROUNDS="$2"; shift 2 ;;
        -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
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
STEPS=$((200 * 400 * 10))
for k in $(seq 1 "$ROUNDS"); do
    echo "== round $k/$ROUNDS (load average $(cut -d' ' -f1 /proc/loadavg))" >&2
    JAX_PLATFORMS=cpu taskset -c 0 "$VENV/bin/python" "$HERE/kheperax/kheperax_steps.py" \
        --repeat "$REPEAT" >"$TMP/kx1-$k.json"
    JAX_PLATFORMS=cpu "$VENV/bin/python" "$HERE/kheperax/kheperax_steps.py" \
        --repeat "$REPEAT" >"$TMP/kxall-$k.json"
    for t in 1 2; do
        "$FM" bench --room "$ROOM" --motion wheels --set trial.end_at_home=false \
            --steps "$STEPS" --population 200 --repeat "$REPEAT" --threads "$t" --json \
            >"$TMP/fm$t-$k.json"
    done
done

python3 - "$TMP" "$ROUNDS" "$HERE/kheperax/results.json" "$FM_SOURCE" <<'PY'
import datetime, glob, json, statistics, sys
tmp, rounds, out, source = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
load = lambda p: json.load(open(p))
doc = {"date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
       "fuzzymotiv_source": source, "rounds": {}}
rows = []
for name, label in [("kx1", "Kheperax, 1 core"), ("kxall", "Kheperax, all cores")]:
    docs = [load(f"{tmp}/{name}-{k}.json") for k in range(1, rounds + 1)]
    doc["rounds"][name] = docs
    for i, run in enumerate(docs[0]["runs"]):
        rates = [d["runs"][i]["median_robot_steps_per_sec"] for d in docs]
        rows.append((f"{label}, batch {run['batch']}", rates))
for t in (1, 2):
    docs = [load(f"{tmp}/fm{t}-{k}.json") for k in range(1, rounds + 1)]
    doc["rounds"][f"fuzzymotiv_threads_{t}"] = docs
    rows.append((f"fuzzymotiv wheels, population 200, {t} thread(s)",
                 [d["population_robot_steps_per_sec"] for d in docs]))
    if t == 1:
        rows.append(("fuzzymotiv wheels, 1 robot, 1 thread",
                     [d["robot_steps_per_sec"] for d in docs]))
doc["medians"] = {label: statistics.median(r) for label, r in rows}
print(f"| robot-steps/s | median of {rounds} rounds | min | max |")
print("|---|---:|---:|---:|")
for label, r in rows:
    print(f"| {label} | {statistics.median(r):,.0f} | {min(r):,.0f} | {max(r):,.0f} |")
with open(out, "w") as f:
    json.dump(doc, f, indent=2)
    f.write("\n")
PY
