#!/usr/bin/env bash
# `problem.evaluate` (Python) against `fuzzymotiv bench --population` (the CLI), same workload:
# 200 robots x the five built-in rooms x 400-step trials, no AEM, the initial population with a
# new generation number (fresh noise) per evaluation. K alternated rounds (CLI, then Python),
# each the median of R repetitions of one whole-population evaluation (400,000 robot-steps
# when no trial ends early). Usage:
#
#   bash bench/python_vs_cli.sh [--rounds K] [--repeat R] [--threads T] [--rooms N]
#   bash bench/python_vs_cli.sh --callgrind [--rooms N]
#
# --callgrind counts instructions instead of timing (the machine's load does not change them):
# both sides once under valgrind's callgrind for one and for two whole-population evaluations
# (one thread), and prints the marginal instructions per executed robot-step,
# (Ir(2) - Ir(1)) / (steps(2) - steps(1)), which cancels start-up (imports, config loading).
# The CLI's figure covers its two measurements (one robot; the population), both of which
# grow by one population's robot-steps.
#
# PYTHON is the interpreter with fuzzymotiv installed (default target/pyenv/bin/python; install
# it with `pip install ./python`, a release build). FUZZYMOTIV_BIN / FUZZYMOTIV_REV as in
# bench/run.sh. Prints every round and the ratio of the medians (Python / CLI).
set -euo pipefail

HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/.." && pwd)"
ROUNDS=11; REPEAT=9; THREADS=1; NROOMS=5; CALLGRIND=0
while [ $# -gt 0 ]; do
    case "$1" in
        --rounds) ROUNDS="$2"; shift 2 ;;
        --repeat) REPEAT="$2"; shift 2 ;;
        --threads) THREADS="$2"; shift 2 ;;
        --rooms) NROOMS="$2"; shift 2 ;;
        --callgrind) CALLGRIND=1; shift ;;
        -h|--help) sed -n '2,21p' "$0"; exit 0 ;;
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
if [ "$CALLGRIND" -eq 1 ]; then
    install_missing valgrind
    TMP="$(mktemp -d)"
    trap 'rm -rf "$TMP"' EXIT
    measured=()
    for n in 1 2; do
        measured+=("$(callgrind_ir "cli$n" "$FM" bench --population 200 --steps $((n * STEPS)) --repeat 1 \
            --threads 1 --set "rooms=$ROOMS" --json)")
        measured+=("$(callgrind_ir "py$n" "$PYTHON" "$HERE/python_evaluate.py" --rooms "$NROOMS" \
            --steps $((n * STEPS)) --repeat 1 --threads 1)")
    done
    "$PYTHON" - "$TMP" "$FM_SOURCE" "$ROOMS" "${measured[@]}" <<'PY'
import json, sys
tmp, source, rooms = sys.argv[1:4]
cli1, py1, cli2, py2 = (int(v) for v in sys.argv[4:8])
load = lambda name: json.load(open(f"{tmp}/{name}.stdout"))
cli_steps = [load(n)["robot_steps"] + load(n)["population_robot_steps"] for n in ("cli1", "cli2")]
py_steps = [load(n)["robot_steps"] for n in ("py1", "py2")]
cli = (cli2 - cli1) / (cli_steps[1] - cli_steps[0])
py = (py2 - py1) / (py_steps[1] - py_steps[0])
print(f"fuzzymotiv {source}, 1 thread, rooms {rooms}, callgrind")
print(f"CLI    Ir {cli1:,} / {cli2:,} for {cli_steps[0]:,} / {cli_steps[1]:,} robot-steps: "
      f"marginal {cli:,.1f} Ir per robot-step")
print(f"Python Ir {py1:,} / {py2:,} for {py_steps[0]:,} / {py_steps[1]:,} robot-steps: "
      f"marginal {py:,.1f} Ir per robot-step")
print(f"throughput ratio Python / CLI by instructions (CLI Ir / Python Ir per robot-step): {cli / py:.3f}")
PY
    exit 0
fi
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
