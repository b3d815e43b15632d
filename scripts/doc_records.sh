#!/usr/bin/env bash
# Copy the records the documents quote from finished studies into docs/results/ (verbatim, no
# file made by hand). See docs/results/README.md for the whole procedure.
#
#   scripts/doc_records.sh KIND=DIR ...
#
# KIND is the record folder and DIR the finished study's output directory:
#   five-seed=results-5          (fuzzymotiv reproduce --seeds 5 --out results-5)
#   ten-seed=results-10          (fuzzymotiv reproduce --seeds 10 --out results-10)
#   twenty-seed=results-20       (fuzzymotiv reproduce --seeds 20 --out results-20)
#   twenty-seed-base-11=results-20-base-11 (fuzzymotiv reproduce --seed 11 --seeds 20 --out results-20-base-11)
#   search-strength=results-search-strength   (fuzzymotiv reproduce --search-strength --seeds 10)
#   ablation=results-ablation    (fuzzymotiv reproduce --ablation --seeds 5)
#   orientation=results-orientation           (fuzzymotiv reproduce --orientation)
#   replication=results-replication           (fuzzymotiv reproduce --replication --seeds 20)
#   combination=results-combination           (fuzzymotiv reproduce --combination)
#   combination-base-11=results-combination-base-11 (fuzzymotiv reproduce --combination --seed 11 --out results-combination-base-11)
#   paper-study=out/paper-study                (fuzzymotiv study studies/paper.toml --out out/paper-study)
#   combination-study=out/combination-study    (fuzzymotiv study studies/combination.toml --out out/combination-study)
#   search-strength-study=out/search-strength  (fuzzymotiv study studies/search-strength.toml --out out/search-strength)
#   ablation-study=out/ablation                (fuzzymotiv study studies/ablation.toml --out out/ablation)
#   urgency-study=out/urgency                  (fuzzymotiv study studies/urgency.toml --out out/urgency)
#   orientation-study=out/orientation-study    (fuzzymotiv study studies/orientation.toml --out out/orientation-study)
#   transfer-study=out/transfer-study          (fuzzymotiv study studies/transfer.toml --out out/transfer-study)
#   fetch-urgency-study=out/fetch-urgency      (fuzzymotiv study studies/fetch-urgency.toml --out out/fetch-urgency)
#   urgency=results-urgency                   (fuzzymotiv reproduce --urgency)
#   maps/o-fixed=out/maps/o-fixed   (fuzzymotiv sweep configs/motivation-map.toml … + merge)
#   maps/o-free=out/maps/o-free     (fuzzymotiv sweep configs/motivation-map-o-free.toml … + merge)
#
# A study is refused (exit 2, nothing copied for it) when it is unfinished (a record is
# missing, or DIR.partial exists) or when its summary.json's "model" is not this checkout's
# fuzzymotiv::MODEL_VERSION.
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
records="$here/docs/results"

die() { echo "error: $*" >&2; exit 2; }

[[ $# -gt 0 ]] || die "name at least one study as KIND=DIR (see the top of $0)"

# The model version of this checkout (fuzzymotiv::MODEL_VERSION): the documents describe it.
source_model=$(sed -n 's/^pub const MODEL_VERSION: u32 = \([0-9][0-9]*\);/\1/p' \
    "$here/crates/fuzzymotiv/src/lib.rs")
[[ -n $source_model ]] || die "cannot read MODEL_VERSION from crates/fuzzymotiv/src/lib.rs"

# The "model" field of a study's summary.json.
study_model() {
    sed -n 's/^[[:space:]]*"model":[[:space:]]*\([0-9][0-9]*\).*/\1/p' "$1" | tail -n 1
}

check_model() { # SUMMARY
    [[ -f $1 ]] || die "$1 is missing: the study is not finished"
    local model
    model=$(study_model "$1")
    [[ -n $model ]] || die "$1 names no model: it was written by a build before model versions"
    [[ $model == "$source_model" ]] ||
        die "$1 is of model $model, this checkout is model $source_model: run the study again with this build"
}

# Files of a study, relative to its directory; every one must exist.
files_of() { # KIND DIR
    local kind=$1 dir=$2
    case $kind in
        five-seed | ten-seed | twenty-seed | twenty-seed-base-11)
            echo table1.csv table2.csv table1_seeds.csv table2_seeds.csv claims.csv summary.json ;;
        search-strength)
            echo search_strength.csv summary.json
            for pop in "$dir"/pop-*/; do
                pop=$(basename "$pop")
                echo "$pop/claims.csv $pop/table1.csv $pop/table2.csv"
            done ;;
        ablation)
            echo ablation.csv summary.json
            tail -n +2 "$dir/ablation.csv" | cut -d, -f1 | while read -r variant; do
                echo "$variant/table1.csv $variant/table2.csv $variant/claims.csv"
            done ;;
        orientation)
            echo results.csv aggregate.csv
            for job in "$dir"/jobs/*/; do echo "jobs/$(basename "$job")/generations.csv"; done ;;
        maps/o-fixed | maps/o-free)
            echo results.csv aggregate.csv ;;
        replication)
            echo replication.csv replication_seeds.csv summary.json
            for base in "$dir"/base-*/; do
                echo "$(basename "$base")/claims.csv"
            done ;;
        urgency)
            echo urgency.csv urgency_seeds.csv summary.json ;;
        *-study)
            # Every study file writes per_seed.csv, study.json and arms.csv; claims.csv and
            # rooms.csv when it has hypotheses, agreement.csv when it has several base seeds.
            echo per_seed.csv study.json arms.csv
            for f in claims.csv rooms.csv agreement.csv; do
                [[ ! -s $dir/$f ]] || echo "$f"
            done ;;
        combination | combination-base-11)
            echo behaviour.csv claim_differences.csv summary.json
            for c in default weighted-sum weighted-squares; do
                echo "$c/claims.csv $c/table1.csv $c/table2.csv"
            done ;;
        *) die "unknown record folder \`$kind\`; the folders are five-seed, ten-seed, twenty-seed, twenty-seed-base-11, search-strength, ablation, orientation, maps/o-fixed, maps/o-free, replication, combination, combination-base-11, urgency, any NAME-study (a study file's out folder)" ;;
    esac
}

# Check every study first, then copy: a refused study leaves docs/results/ as it was.
declare -a plans=()
for arg in "$@"; do
    [[ $arg == *=* ]] || die "\`$arg\` is not KIND=DIR"
    kind=${arg%%=*} dir=${arg#*=}
    [[ -d $dir ]] || die "$dir (for $kind) is not a directory"
    [[ ! -e $dir.partial ]] || die "$dir.partial exists: the study $dir is not finished"
    files=$(files_of "$kind" "$dir" | tr '\n' ' ')
    for f in $files; do
        [[ -f $dir/$f ]] || die "$dir/$f is missing: the study is not finished (or not a $kind study)"
        case $(basename "$f") in summary.json | study.json) check_model "$dir/$f" ;; esac
    done
    case $kind in
        orientation | maps/*)
            for job in "$dir"/jobs/*/; do check_model "$job/summary.json"; done ;;
    esac
    plans+=("$kind|$dir|$files")
done

for plan in "${plans[@]}"; do
    IFS='|' read -r kind dir files <<<"$plan"
    rm -rf "${records:?}/$kind"
    for f in $files; do
        mkdir -p "$(dirname "$records/$kind/$f")"
        cp "$dir/$f" "$records/$kind/$f"
    done
    echo "copied $(wc -w <<<"$files") records of $dir into docs/results/$kind"
done
echo "now: FUZZYMOTIV_BLESS=1 cargo test -p fuzzymotiv-cli --test it documents::, then review git diff"
