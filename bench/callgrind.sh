#!/usr/bin/env bash
# Instructions per robot-step under callgrind: a load-independent cost figure (the machine's
# noise does not change instruction counts). Usage:
#
#   bash bench/callgrind.sh [--steps N] [--no-enki]
#
# fuzzymotiv: `fuzzymotiv bench --steps N --repeat 1 --population 2 --threads 1` (N = 40000 by
# default). Both of its measurements (one robot; populations of 2) run whole 400-step trials
# until they have done N robot-steps, so, counting only executed steps (bench reports them),
#     Ir per robot-step = total Ir / (robot_steps + population_robot_steps).
# That total includes process start-up and config loading; the script also reports the marginal
# figure (Ir(2N) - Ir(N)) / (robot-steps(2N) - robot-steps(N)), which cancels them.
# Enki (unless --no-enki): the same two-point marginal figure for bench/enki's khepera_h (whose
# start-up includes a 200-step sensor calibration and the genome set-up).
# FUZZYMOTIV_REV / FUZZYMOTIV_BIN as in bench/run.sh. Writes bench/callgrind.json.
set -euo pipefail

HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/.." && pwd)"
STEPS="${STEPS:-40000}"
WITH_ENKI=1
while [ $# -gt 0 ]; do
    case "$1" in
        --steps) STEPS="$2"; shift 2 ;;
        --no-enki) WITH_ENKI=0; shift ;;
        -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
        *) echo "unknown argument: $1" >&2; exit 2 ;;
    esac
done
case "$STEPS" in ''|*[!0-9]*|0) echo "--steps must be a positive integer" >&2; exit 2 ;; esac

. "$HERE/lib.sh"
if [ "$WITH_ENKI" -eq 1 ]; then install_missing valgrind libenki-dev g++ make; else install_missing valgrind; fi
build_fuzzymotiv
if [ "$WITH_ENKI" -eq 1 ]; then build_enki; fi

TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

N1="$STEPS"; N2=$((2 * STEPS))
# Enki's workload (the first release's H room, every trial all T steps) with the wheels model and
# with the actions model; `fuzzymotiv bench --room H` measures the paper's H room, whose home
# corner keeps random robots near walls (the study's workload).
FR_H="$ROOT/rooms/first-release/H.toml"
# workload NAME BENCH-ARGS...: prints "Ir(N1) Ir(N2) executed-steps(N1) executed-steps(N2)".
# Executed robot-steps are counted by bench itself (idle steps are not work).
workload() {
    local name="$1"; shift
    local ir1 ir2
    ir1=$(callgrind_ir "${name}1" "$FM" bench "$@" --steps "$N1" --repeat 1 --population 2 --threads 1 --json) || exit 1
    ir2=$(callgrind_ir "${name}2" "$FM" bench "$@" --steps "$N2" --repeat 1 --population 2 --threads 1 --json) || exit 1
    echo "$ir1 $ir2 $(executed "${name}1") $(executed "${name}2")"
}
executed() { python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(d["robot_steps"] + d["population_robot_steps"])' "$TMP/$1.stdout"; }
echo "== callgrind: fuzzymotiv bench --steps $N1 and $N2, wheels and actions" >&2
WHEELS=$(workload fm --room "$FR_H" --motion wheels --set trial.end_at_home=false)
ACTIONS=$(workload fa --room "$FR_H" --motion actions --set trial.end_at_home=false)
PAPER=$(workload fp --room H --motion actions)
EN1=""; EN2=""
if [ "$WITH_ENKI" -eq 1 ]; then
    echo "== callgrind: khepera_h --steps $N1 and $N2" >&2
    EN1=$(callgrind_ir en1 "$ENKI" --steps "$N1" --repeat 1)
    EN2=$(callgrind_ir en2 "$ENKI" --steps "$N2" --repeat 1)
fi

python3 - "$N1" "$N2" "$EN1" "$EN2" "$HERE/callgrind.json" "$WHEELS" "$ACTIONS" "$PAPER" <<'PY'
import datetime, json, os, subprocess, sys
n1, n2 = int(sys.argv[1]), int(sys.argv[2])
en1, en2, out = sys.argv[3:6]
trial = 400
steps = lambda n: -(-n // trial) * trial
bench = f"--steps {n1} --repeat 1 --population 2 --threads 1"

def workload(args, measured):
    """One workload's record from "Ir(N1) Ir(N2) steps(N1) steps(N2)"."""
    ir1, ir2, s1, s2 = (int(x) for x in measured.split())
    return {
        "command": f"fuzzymotiv bench {args} {bench}",
        "total_ir": ir1, "robot_steps": s1,
        "ir_per_robot_step": ir1 / s1,
        "second_run": {"steps_arg": n2, "total_ir": ir2, "robot_steps": s2},
        "marginal_ir_per_robot_step": (ir2 - ir1) / (s2 - s1),
    }

first = "--room rooms/first-release/H.toml"
wheels = workload(f"{first} --motion wheels --set trial.end_at_home=false", sys.argv[6])
actions = workload(f"{first} --motion actions --set trial.end_at_home=false", sys.argv[7])
paper = workload("--room H --motion actions", sys.argv[8])
doc = {
    "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
    "fuzzymotiv_source": os.environ.get("FM_SOURCE", ""),
    "valgrind": subprocess.run(["valgrind", "--version"], capture_output=True,
                               text=True).stdout.strip(),
    "fuzzymotiv_actions": actions,
    "fuzzymotiv_actions_paper_h": paper,
    "fuzzymotiv": wheels,
}
for label, w in [("wheels: ", wheels), ("actions:", actions)]:
    print(f"fuzzymotiv {label} {w['total_ir']:,} Ir / {w['robot_steps']:,} executed robot-steps"
          f" = {w['ir_per_robot_step']:,.0f} Ir per robot-step"
          f" (marginal, start-up cancelled: {w['marginal_ir_per_robot_step']:,.0f})")
print(f"fuzzymotiv actions, the paper's H room (the study's workload): {paper['ir_per_robot_step']:,.0f} Ir per robot-step"
      f" (marginal: {paper['marginal_ir_per_robot_step']:,.0f})")
if en1:
    en1, en2 = int(en1), int(en2)
    e_steps1, e_steps2 = steps(n1), steps(n2)
    marginal = (en2 - en1) / (e_steps2 - e_steps1)
    doc["enki"] = {
        "command": f"khepera_h --steps {n1} --repeat 1",
        "total_ir": en1, "robot_steps": e_steps1, "ir_per_robot_step": en1 / e_steps1,
        "second_run": {"steps_arg": n2, "total_ir": en2, "robot_steps": e_steps2},
        "marginal_ir_per_robot_step": marginal,
        "note": "each 400-step trial also runs 1 zero-speed World::step to refresh the sensors",
    }
    fm_marg = wheels["marginal_ir_per_robot_step"]
    doc["ratio_enki_over_fuzzymotiv_marginal"] = marginal / fm_marg
    print(f"Enki:       {en1:,} Ir / {e_steps1:,} robot-steps = {en1 / e_steps1:,.0f} Ir per robot-step"
          f" (marginal: {marginal:,.0f})")
    print(f"instruction ratio Enki / fuzzymotiv (marginal): {marginal / fm_marg:.2f}")
with open(out, "w") as f:
    json.dump(doc, f, indent=2)
    f.write("\n")
PY
