#!/usr/bin/env bash
# Instructions per robot-step under callgrind: a load-independent cost figure (the machine's
# noise does not change instruction counts). Usage:
#
#   bash bench/callgrind.sh [--steps N] [--no-enki]
#
# fuzzymotiv: `fuzzymotiv bench --steps N --repeat 1 --population 2 --threads 1` (N = 40000 by
# default). Its robot-steps are N rounded up to whole 400-step trials, plus the population part
# (2 robots x 400 steps per repeat), so
#     Ir per robot-step = total Ir / (ceil(N/400)*400 + 2*400).
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

# total_ir NAME CMD...: runs CMD under callgrind, prints its total instruction count.
total_ir() {
    local name="$1"; shift
    valgrind --tool=callgrind --callgrind-out-file="$TMP/$name.out" "$@" \
        >"$TMP/$name.stdout" 2>"$TMP/$name.log" || { cat "$TMP/$name.log" >&2; exit 1; }
    awk '/^(summary|totals):/ {print $2; exit}' "$TMP/$name.out"
}

N1="$STEPS"; N2=$((2 * STEPS))
# Enki's workload (the first release's H room, every trial all T steps) with the wheels model and
# with the actions model; `fuzzymotiv bench --room H` measures the paper's H room, whose home
# corner keeps random robots near walls (about 4 500 Ir per step for either model).
WHEELS=(--room "$ROOT/rooms/first-release/H.toml" --motion wheels --set trial.end_at_home=false)
ACTIONS=(--room "$ROOT/rooms/first-release/H.toml" --motion actions --set trial.end_at_home=false)
echo "== callgrind: fuzzymotiv bench --steps $N1 and $N2, wheels and actions" >&2
FM1=$(total_ir fm1 "$FM" bench "${WHEELS[@]}" --steps "$N1" --repeat 1 --population 2 --threads 1 --json)
FM2=$(total_ir fm2 "$FM" bench "${WHEELS[@]}" --steps "$N2" --repeat 1 --population 2 --threads 1 --json)
FA1=$(total_ir fa1 "$FM" bench "${ACTIONS[@]}" --steps "$N1" --repeat 1 --population 2 --threads 1 --json)
FA2=$(total_ir fa2 "$FM" bench "${ACTIONS[@]}" --steps "$N2" --repeat 1 --population 2 --threads 1 --json)
# The study's workload: the paper's H room with the default model (home in a corner).
PAPER=(--room H --motion actions)
FP1=$(total_ir fp1 "$FM" bench "${PAPER[@]}" --steps "$N1" --repeat 1 --population 2 --threads 1 --json)
FP2=$(total_ir fp2 "$FM" bench "${PAPER[@]}" --steps "$N2" --repeat 1 --population 2 --threads 1 --json)
# Executed robot-steps of each run, as bench counted them (idle steps are not work).
executed() { python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(d["robot_steps"] + d["population_robot_steps"])' "$TMP/$1.stdout"; }
SW1=$(executed fm1); SW2=$(executed fm2); SA1=$(executed fa1); SA2=$(executed fa2)
SP1=$(executed fp1); SP2=$(executed fp2)
EN1=""; EN2=""
if [ "$WITH_ENKI" -eq 1 ]; then
    echo "== callgrind: khepera_h --steps $N1 and $N2" >&2
    EN1=$(total_ir en1 "$ENKI" --steps "$N1" --repeat 1)
    EN2=$(total_ir en2 "$ENKI" --steps "$N2" --repeat 1)
fi

python3 - "$N1" "$N2" "$FM1" "$FM2" "$EN1" "$EN2" "$HERE/callgrind.json" "$ROOT" \
    "$SW1" "$SW2" "$FA1" "$FA2" "$SA1" "$SA2" "$FP1" "$FP2" "$SP1" "$SP2" <<'PY'
import datetime, json, os, subprocess, sys
n1, n2, fm1, fm2 = (int(x) for x in sys.argv[1:5])
en1, en2, out, root = sys.argv[5:9]
fm_steps1, fm_steps2, fa1, fa2, fa_steps1, fa_steps2 = (int(x) for x in sys.argv[9:15])
fp1, fp2, fp_steps1, fp_steps2 = (int(x) for x in sys.argv[15:19])
trial = 400
steps = lambda n: -(-n // trial) * trial
doc = {
    "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
    "fuzzymotiv_source": os.environ.get("FM_SOURCE", ""),
    "valgrind": subprocess.run(["valgrind", "--version"], capture_output=True,
                               text=True).stdout.strip(),
    "fuzzymotiv_actions": {
        "command": f"fuzzymotiv bench --room rooms/first-release/H.toml --motion actions --set trial.end_at_home=false --steps {n1} --repeat 1 --population 2 --threads 1",
        "total_ir": fa1, "robot_steps": fa_steps1,
        "ir_per_robot_step": fa1 / fa_steps1,
        "second_run": {"steps_arg": n2, "total_ir": fa2, "robot_steps": fa_steps2},
        "marginal_ir_per_robot_step": (fa2 - fa1) / (fa_steps2 - fa_steps1),
    },
    "fuzzymotiv_actions_paper_h": {
        "command": f"fuzzymotiv bench --room H --motion actions --steps {n1} --repeat 1 --population 2 --threads 1",
        "total_ir": fp1, "robot_steps": fp_steps1,
        "ir_per_robot_step": fp1 / fp_steps1,
        "second_run": {"steps_arg": n2, "total_ir": fp2, "robot_steps": fp_steps2},
        "marginal_ir_per_robot_step": (fp2 - fp1) / (fp_steps2 - fp_steps1),
    },
    "fuzzymotiv": {
        "command": f"fuzzymotiv bench --room rooms/first-release/H.toml --motion wheels --set trial.end_at_home=false --steps {n1} --repeat 1 --population 2 --threads 1",
        "total_ir": fm1, "robot_steps": fm_steps1,
        "ir_per_robot_step": fm1 / fm_steps1,
        "second_run": {"steps_arg": n2, "total_ir": fm2, "robot_steps": fm_steps2},
        "marginal_ir_per_robot_step": (fm2 - fm1) / (fm_steps2 - fm_steps1),
    },
}
print(f"fuzzymotiv wheels:  {fm1:,} Ir / {fm_steps1:,} robot-steps = {fm1 / fm_steps1:,.0f} Ir per robot-step"
      f" (marginal, start-up cancelled: {(fm2 - fm1) / (fm_steps2 - fm_steps1):,.0f})")
print(f"fuzzymotiv actions: {fa1:,} Ir / {fa_steps1:,} executed robot-steps = {fa1 / fa_steps1:,.0f} Ir per robot-step"
      f" (marginal: {(fa2 - fa1) / (fa_steps2 - fa_steps1):,.0f})")
print(f"fuzzymotiv actions, the paper's H room (the study's workload): {fp1 / fp_steps1:,.0f} Ir per robot-step"
      f" (marginal: {(fp2 - fp1) / (fp_steps2 - fp_steps1):,.0f})")
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
    fm_marg = doc["fuzzymotiv"]["marginal_ir_per_robot_step"]
    doc["ratio_enki_over_fuzzymotiv_marginal"] = marginal / fm_marg
    print(f"Enki:       {en1:,} Ir / {e_steps1:,} robot-steps = {en1 / e_steps1:,.0f} Ir per robot-step"
          f" (marginal: {marginal:,.0f})")
    print(f"instruction ratio Enki / fuzzymotiv (marginal): {marginal / fm_marg:.2f}")
with open(out, "w") as f:
    json.dump(doc, f, indent=2)
    f.write("\n")
PY
