#!/usr/bin/env bash
# `problem.evaluate` (Python) against `fuzzymotiv bench --population` (the CLI), same workload:
# 200 robots x the five built-in rooms x 400-step trials, no AEM, the initial population with a
# new generation number (fresh noise) per evaluation. K alternated rounds (CLI, then Python),
# each the median of R repetitions of one whole-population evaluation (400,000 robot-steps
# when no trial ends early). Usage:
#
#   bash bench/python_vs_cli.sh [--rounds K] [--repeat R] [--threads T] [--rooms N]
#
# PYTHON is the interpreter with fuzzymotiv installed (default target/pyenv/bin/python; install
# it with `pip install ./python`, a release build). FUZZYMOTIV_BIN / FUZZYMOTIV_REV as in
# bench/run.sh. Prints every round and the ratio of the medians (Python / CLI).
set -euo pipefail

HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/.." && pwd)"
ROUNDS=11; REPEAT=9; THREADS=1; NROOMS=5
while [ $# -gt 0 ]; do
    case "$1" in
        --rounds) ROUNDS="$2"; shift 2 ;;
        --repeat) REPEAT="$2"; shift 2 ;;
        --threads) THREADS="$2"; shift 2 ;;
        --rooms) NROOMS="$2"; shift 2 ;;
        -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
        *) echo "unknown argument: $1" >&2; exit 2 ;;
    esac
done
PYTHON="${PYTHON:-$ROOT/target/pyenv/bin/python}"
"$PYTHON" -c "import fuzzymotiv" || { echo "$PYTHON: fuzzymotiv is not installed (pip install ./python)" >&2; exit 1; }

. "$HERE/lib.sh"
build_fuzzymotiv

ALL='"H","T","L","square","rectangle"'
ROOMS="[$(echo "$ALL" | cut -d, -f1-"$NROOMS")]"
STEPS=$((200 * NROOMS * 400))
cli=(); py=()
for k in $(seq 1 "$ROUNDS"); do
    c="$("$FM" bench --population 200 --steps "$STEPS" --repeat "$REPEAT" --threads "$THREADS" \
        --set "rooms=$ROOMS" --json | "$PYTHON" -c 'import json,sys; print(json.load(sys.stdin)["population_robot_steps_per_sec"])')"
    p="$("$PYTHON" "$HERE/python_evaluate.py" --rooms "$NROOMS" --steps "$STEPS" --repeat "$REPEAT" \
        --threads "$THREADS" | "$PYTHON" -c 'import json,sys; print(json.load(sys.stdin)["robot_steps_per_sec"])')"
    cli+=("$c"); py+=("$p")
    printf 'round %2d  CLI %12.0f  Python %12.0f  robot-steps/s  ratio %.3f\n' "$k" "$c" "$p" "$(echo "$p / $c" | bc -l)"
done
"$PYTHON" - "${cli[*]}" "${py[*]}" "$FM_SOURCE" "$THREADS" "$ROOMS" <<'PY'
import statistics, sys
cli = [float(v) for v in sys.argv[1].split()]
py = [float(v) for v in sys.argv[2].split()]
ratios = [p / c for p, c in zip(py, cli)]
print(f"fuzzymotiv {sys.argv[3]}, threads {sys.argv[4]}, rooms {sys.argv[5]}, {len(cli)} rounds")
print(f"CLI    median {statistics.median(cli):12.0f}  min {min(cli):12.0f}  max {max(cli):12.0f}")
print(f"Python median {statistics.median(py):12.0f}  min {min(py):12.0f}  max {max(py):12.0f}")
print(f"ratio of medians Python / CLI {statistics.median(py) / statistics.median(cli):.3f}; "
      f"median of per-round ratios {statistics.median(ratios):.3f}")
PY
