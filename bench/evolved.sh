#!/usr/bin/env bash
# The step loop on evolved robots: CPU time of generations 101-200 of the high-curiosity run
# (configs/high-curiosity.toml, one thread), the paper study's second half. Usage:
#
#   bash bench/evolved.sh [--rounds R] [--against REV]
#
# `fuzzymotiv bench --population` steps random networks, which mostly turn on the spot, and a
# reduced study (20 generations) stops before the robots explore; the paper's study spends its
# time on robots that do. This evolves the run to generation 100 once with each build (a
# build continues only a run of its own model), then times `run --continue BASE --generations
# 200 --threads 1`, R rounds (default 5), alternating with REV's build when --against is
# given, and prints each round and the median user CPU of each build. FUZZYMOTIV_REV /
# FUZZYMOTIV_BIN as in bench/run.sh choose the build measured (default: the working tree).
set -euo pipefail

HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/.." && pwd)"
ROUNDS=5
AGAINST=""
while [ $# -gt 0 ]; do
    case "$1" in
        --rounds) ROUNDS="$2"; shift 2 ;;
        --against) AGAINST="$2"; shift 2 ;;
        -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
        *) echo "unknown argument: $1" >&2; exit 2 ;;
    esac
done
case "$ROUNDS" in ''|*[!0-9]*|0) echo "--rounds must be a positive integer" >&2; exit 2 ;; esac
command -v /usr/bin/time >/dev/null || { echo "/usr/bin/time not found (Debian: apt-get install time)" >&2; exit 1; }

. "$HERE/lib.sh"
build_fuzzymotiv
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
cp "$FM" "$TMP/measured"
builds=("$TMP/measured")
names=("$FM_SOURCE")
if [ -n "$AGAINST" ]; then
    FUZZYMOTIV_BIN="" FUZZYMOTIV_REV="$AGAINST" build_fuzzymotiv
    cp "$FM" "$TMP/against"
    builds+=("$TMP/against")
    names+=("$FM_SOURCE")
fi

# Generation 100 of the run, by each build.
for k in "${!builds[@]}"; do
    "${builds[$k]}" run "$ROOT/configs/high-curiosity.toml" --set ga.generations=100 \
        --out "$TMP/base$k" -q > /dev/null 2> "$TMP/err" || { cat "$TMP/err" >&2; exit 1; }
done

for round in $(seq "$ROUNDS"); do
    for k in "${!builds[@]}"; do
        out="$TMP/round"
        rm -rf "$out"
        /usr/bin/time -o "$TMP/time" -f "%e %U" "${builds[$k]}" run --continue "$TMP/base$k" \
            --generations 200 --out "$out" --threads 1 -q > /dev/null 2> "$TMP/err" ||
            { cat "$TMP/err" >&2; exit 1; }
        read -r wall user < "$TMP/time"
        echo "round $round  ${names[$k]}  wall ${wall} s  user ${user} s"
        echo "$k $user" >> "$TMP/all"
    done
done
for k in "${!builds[@]}"; do
    median="$(awk -v k="$k" '$1 == k {print $2}' "$TMP/all" | sort -n |
        awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}')"
    echo "median user CPU, ${names[$k]}: ${median} s (${ROUNDS} rounds)"
done
