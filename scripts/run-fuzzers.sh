#!/usr/bin/env bash
# Runs every fuzz_* target in BIN_DIR for SECONDS each on its seed corpus (fuzz/corpus/NAME),
# without writing to the committed corpus, JOBS targets at a time (default: the number of cores;
# each libFuzzer run is single-threaded). Fails on the first crash, leak or sanitizer report: its
# log's tail is printed and no further target is started.
set -euo pipefail
bin_dir=${1:?usage: run-fuzzers.sh BIN_DIR SECONDS [JOBS]}
seconds=${2:?usage: run-fuzzers.sh BIN_DIR SECONDS [JOBS]}
jobs=${3:-$(nproc)}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

fuzz_one() {
    local target=$1 name
    name=$(basename "$target")
    name=${name#fuzz_}
    [ -e "$work/failed" ] && return 0
    mkdir -p "$work/$name"
    if "$target" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 -timeout=10 \
        -artifact_prefix="$work/$name." -print_final_stats=1 \
        "$work/$name" "$root/fuzz/corpus/$name" 2>"$work/$name.log"; then
        echo "fuzz $name: ${seconds}s, $(grep -oE "stat::number_of_executed_units: *[0-9]+" "$work/$name.log" | tail -1 | grep -oE "[0-9]+$" || echo '?') runs"
    else
        {
            tail -40 "$work/$name.log"
            echo "fuzz $name: FAILED"
        } >&2
        touch "$work/failed"
        return 1
    fi
}
export -f fuzz_one
export work seconds root

ls "$bin_dir"/fuzz_* >/dev/null
ls "$bin_dir"/fuzz_* | xargs -P "$jobs" -n 1 bash -c 'fuzz_one "$0"' || exit 1
