#!/usr/bin/env bash
# The transfer study (issue 54 item 3; EXPERIMENTS.md "The reality gap in Enki (Khepera)" and
# its e-puck2 and Thymio II subsections): the paper's two settings' evolved controllers run in
# fuzzymotiv and in Enki, each measure compared world against world, paired by seed, with the
# engine's statistics.
#
# Usage: scripts/transfer_study.sh [--robot NAME] [--study DIR] [--seeds N] [--runs N]
#                                  [--rooms "H T …"] [--work DIR] [--records DIR]
#                                  [--set KEY=VALUE …] [--against RECORDS]
#
#   --robot NAME   khepera (the paper's robot), epuck2 or thymio2 [default khepera]; the study
#                  is made with `reproduce --set robot=NAME`; the Thymio II's also with its
#                  rooms and steps as configs/thymio2.toml has them (--set rooms=[the five
#                  rooms/thymio2/*.toml, absolute paths] --set trial.steps=600), whose rooms are
#                  named H-x3 … rectangle-x3. Sets the defaults of --rooms, --work and --records
#   --study DIR    a `fuzzymotiv reproduce` directory to reuse (DIR/high-curiosity/seed-K/ and
#                  DIR/low-curiosity/seed-K/ run directories); without it the study is made:
#                  `fuzzymotiv reproduce --seeds N --threads 1 --out WORK/study` (paper scale,
#                  GA 200 × 200: 90 s for ten seeds here; `--quick`, GA 30 × 30, 0.8 s for one)
#   --seeds N      seeds per setting when the study is made [default 10]
#   --runs N       Enki test runs per room (`transfer --runs`) [default 10]; the simulator's
#                  side is each run's own test runs (its aem.test_runs: 10 in the paper configs)
#   --rooms LIST   the rooms, space separated [default "H T L square rectangle"; Thymio II:
#                  "H-x3 T-x3 L-x3 square-x3 rectangle-x3"]
#   --work DIR     where the transfers go (WORK/transfer/SETTING/seed-K/ROOM/) [default
#                  out/transfer-study, out/transfer-study-ROBOT for another robot]; a room
#                  already transferred there is kept
#   --records DIR  where the records go [default docs/results/transfer, for another robot
#                  docs/results/transfer/ROBOT]
#   --set KEY=VAL  (repeatable) passed to `reproduce` when the study is made: robots evolved
#                  another way, e.g. `--set trial.randomise.noise=[0.0,0.2]` or
#                  `--set trial.sensor_table=configs/sensors/khepera-enki.toml`
#   --against DIR  the records of a transfer study of the same seeds evolved the plain way:
#                  also RECORDS/pair.csv, this study against that one, paired by seed
#                  (`transfer_study pair`: Enki, fuzzymotiv and |Enki − fuzzymotiv|)
#
# Needs Enki (Debian: libenki-dev) and g++ for `fuzzymotiv transfer`
# (docs/guide/transfer.md). The binary is $FUZZYMOTIV_BIN, else target/release/fuzzymotiv
# built by `cargo build --release -p fuzzymotiv-cli`. The statistics are the engine's
# (fuzzymotiv::statistics::paired, as `reproduce`'s claims), run by the example
# crates/fuzzymotiv-cli/examples/transfer_study.rs ($TRANSFER_STUDY_BIN, else built by
# `cargo build --release -p fuzzymotiv-cli --example transfer_study`).
#
# Records (RECORDS/):
#   transfer.csv    setting, seed, room, measure, fuzzymotiv, enki: each measure's mean over
#                   the room's test runs in each world (exploration_pct, homing_pct,
#                   battery_pct, recognition_pct, blocked_steps, home_pct = % of runs home)
#   comparison.csv  per setting and measure, Enki against fuzzymotiv paired by seed (each
#                   seed's mean over rooms): means, difference = Enki − fuzzymotiv, 95 % CI, p,
#                   detectable difference, verdict (higher/lower: Enki's side)
#   claims.csv      per world, the paper's comparison claims, high against low curiosity
#                   paired by seed, computed as `reproduce` computes them (homing among them)
#   paths.svg       a path in both worlds: high curiosity's first seed in the first room, its
#                   simulated path (`replay`, the run's seed) and its first Enki test run
#                   (`replay --log`) in one figure
#   pair.csv        with --against: per setting, measure and world (enki, fuzzymotiv, gap),
#                   this study (b) against the other (a), paired by seed
set -euo pipefail

robot=khepera study="" seeds=10 runs=10 rooms="" work="" records="" against=""
extra=()
while [ $# -gt 0 ]; do
    case "$1" in
        --robot) robot="$2"; shift 2 ;;
        --study) study="$2"; shift 2 ;;
        --seeds) seeds="$2"; shift 2 ;;
        --runs) runs="$2"; shift 2 ;;
        --rooms) rooms="$2"; shift 2 ;;
        --work) work="$2"; shift 2 ;;
        --records) records="$2"; shift 2 ;;
        --set) extra+=(--set "$2"); shift 2 ;;
        --against) against="$2"; shift 2 ;;
        -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
        *) echo "transfer_study.sh: unknown argument \`$1\` (see --help)" >&2; exit 2 ;;
    esac
done

# The robot's study: its `reproduce --set`s and default rooms, work and records.
root="$(cd "$(dirname "$0")/.." && pwd)"
sets=()
case "$robot" in
    khepera)
        default_rooms="H T L square rectangle"
        default_work="out/transfer-study" default_records="docs/results/transfer" ;;
    epuck2)
        sets=(--set robot=epuck2)
        default_rooms="H T L square rectangle" ;;
    thymio2)
        files=""
        for room in H T L square rectangle; do
            files="$files${files:+,}\"$root/rooms/thymio2/$room.toml\""
        done
        sets=(--set robot=thymio2 --set "rooms=[$files]" --set trial.steps=600)
        default_rooms="H-x3 T-x3 L-x3 square-x3 rectangle-x3" ;;
    *) echo "transfer_study.sh: --robot \`$robot\`: not khepera, epuck2 or thymio2" >&2; exit 2 ;;
esac
rooms="${rooms:-$default_rooms}"
work="${work:-${default_work:-out/transfer-study-$robot}}"
records="${records:-${default_records:-docs/results/transfer/$robot}}"

bin="${FUZZYMOTIV_BIN:-}"
if [ -z "$bin" ]; then
    cargo build --release -p fuzzymotiv-cli
    bin=target/release/fuzzymotiv
fi
stats="${TRANSFER_STUDY_BIN:-}"
if [ -z "$stats" ]; then
    cargo build --release -p fuzzymotiv-cli --example transfer_study
    stats=target/release/examples/transfer_study
fi

if [ -z "$study" ]; then
    study="$work/study"
    "$bin" reproduce --seeds "$seeds" --threads 1 --quiet ${sets[@]+"${sets[@]}"} \
        ${extra[@]+"${extra[@]}"} --out "$study"
fi

for setting in high-curiosity low-curiosity; do
    for run in "$study/$setting"/seed-*/; do
        run="${run%/}"
        for room in $rooms; do
            dest="$work/transfer/$setting/$(basename "$run")/$room"
            if [ -f "$dest/measures.csv" ]; then
                continue
            fi
            mkdir -p "$(dirname "$dest")"
            if ! "$bin" transfer "$run" --room "$room" --runs "$runs" --out "$dest" >"$dest.log" 2>&1; then
                cat "$dest.log" >&2
                exit 2
            fi
            echo "$setting $(basename "$run") $(grep -h "Enki (" "$dest.log")" >&2
        done
    done
done

mkdir -p "$records"
"$stats" collect "$study" "$work/transfer" >"$records/transfer.csv"
"$stats" compare "$records/transfer.csv" "$records"
# A path in both worlds (the figure's file names are the work directory's).
first_room="${rooms%% *}"
first_run="$(find "$study/high-curiosity" -mindepth 1 -maxdepth 1 -name 'seed-*' | sort | head -1)"
tmp="$(mktemp -d)"
"$bin" replay "$first_run" --room "$first_room" --out "$tmp/paths.html" \
    --log "$work/transfer/high-curiosity/$(basename "$first_run")/$first_room/run-0.csv" >/dev/null
cp "$tmp/paths.svg" "$records/paths.svg"
rm -rf "$tmp"
if [ -n "$against" ]; then
    "$stats" pair "$against/transfer.csv" "$records/transfer.csv" >"$records/pair.csv"
fi
echo "transfer_study.sh: records in $records" >&2
