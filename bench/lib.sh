# shellcheck shell=bash disable=SC2034  # FM, FM_SOURCE and ENKI are used by the sourcing scripts
# Shared helpers of bench/run.sh and bench/callgrind.sh (sourced, not run).
# Expects ROOT (repo root) and HERE (bench/) to be set.

# install_missing PKG...: apt-get the Debian packages among PKG... that are not installed
# (as root directly, otherwise through sudo), unless NO_INSTALL=1.
install_missing() {
    local missing=() p
    for p in "$@"; do
        case "$p" in
            g++|make|valgrind) command -v "$p" >/dev/null || missing+=("$p") ;;
            *) dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p") ;;
        esac
    done
    [ ${#missing[@]} -eq 0 ] && return 0
    if [ "${NO_INSTALL:-0}" = 1 ]; then
        echo "missing: ${missing[*]} (run without --no-install to apt-get them)" >&2
        exit 1
    fi
    local sudo=""
    [ "$(id -u)" -ne 0 ] && sudo="sudo"
    echo "== installing ${missing[*]}" >&2
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
}

# build_fuzzymotiv: sets FM to a release `fuzzymotiv` binary and FM_SOURCE to what it was built
# from. By default builds the working tree (`cargo build --release -p fuzzymotiv-cli` at the
# repo root). FUZZYMOTIV_BIN=path uses an existing binary instead; FUZZYMOTIV_REV=rev (e.g.
# HEAD) builds that commit from `git archive` under target/bench/ (useful while the working
# tree is mid-edit), leaving the working tree alone.
build_fuzzymotiv() {
    command -v cargo >/dev/null || { echo "cargo not found: install Rust (rustup) first" >&2; exit 1; }
    if [ -n "${FUZZYMOTIV_BIN:-}" ]; then
        FM="$FUZZYMOTIV_BIN"
        FM_SOURCE="binary $FM"
    elif [ -n "${FUZZYMOTIV_REV:-}" ]; then
        local sha src
        sha="$(git -C "$ROOT" rev-parse --short "$FUZZYMOTIV_REV")"
        src="$ROOT/target/bench/src-$sha"
        if [ ! -f "$src/Cargo.toml" ]; then
            mkdir -p "$src"
            git -C "$ROOT" archive "$sha" | tar -x -C "$src"
        fi
        echo "== cargo build --release -p fuzzymotiv-cli (commit $sha)" >&2
        (cd "$src" && CARGO_TARGET_DIR="$ROOT/target/bench/rev-target" \
            cargo build --release -p fuzzymotiv-cli --quiet)
        FM="$ROOT/target/bench/rev-target/release/fuzzymotiv"
        FM_SOURCE="commit $sha"
    else
        echo "== cargo build --release -p fuzzymotiv-cli" >&2
        (cd "$ROOT" && cargo build --release -p fuzzymotiv-cli --quiet) || {
            echo "fuzzymotiv did not build; to measure the last commit instead:" >&2
            echo "  FUZZYMOTIV_REV=HEAD bash bench/$(basename "$0")" >&2
            exit 1
        }
        FM="$ROOT/target/release/fuzzymotiv"
        FM_SOURCE="working tree $(git -C "$ROOT" rev-parse --short HEAD)"
        [ -n "$(git -C "$ROOT" status --porcelain -- crates Cargo.toml Cargo.lock)" ] &&
            FM_SOURCE="$FM_SOURCE (uncommitted changes)"
    fi
    [ -x "$FM" ] || { echo "no fuzzymotiv binary at $FM" >&2; exit 1; }
    export FM_SOURCE
}

# build_enki: builds bench/enki/khepera_h into target/bench/ and sets ENKI to it.
build_enki() {
    echo "== make -C bench/enki" >&2
    make -C "$HERE/enki" --no-print-directory OUT="$ROOT/target/bench" >&2
    ENKI="$ROOT/target/bench/khepera_h"
}

# callgrind_ir NAME CMD...: runs CMD under callgrind with its files in $TMP (NAME.out, its stdout
# in NAME.stdout, valgrind's log in NAME.log); prints the total instruction count.
callgrind_ir() {
    local name="$1"; shift
    valgrind --tool=callgrind --callgrind-out-file="$TMP/$name.out" "$@" \
        >"$TMP/$name.stdout" 2>"$TMP/$name.log" || { cat "$TMP/$name.log" >&2; exit 1; }
    awk '/^(summary|totals):/ {print $2; exit}' "$TMP/$name.out"
}
