#!/usr/bin/env bash
# Runs every fuzz_* target in BIN_DIR for SECONDS each on its seed corpus (fuzz/corpus/NAME),
# without writing to the committed corpus. Fails on the first crash, leak or sanitizer report.
set -euo pipefail
bin_dir=${1:?usage: run-fuzzers.sh BIN_DIR SECONDS}
seconds=${2:?usage: run-fuzzers.sh BIN_DIR SECONDS}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for target in "$bin_dir"/fuzz_*; do
    name=$(basename "$target")
    name=${name#fuzz_}
    mkdir -p "$work/$name"
    echo "fuzz $name: ${seconds}s"
    "$target" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 -timeout=10 \
        -artifact_prefix="$work/" -print_final_stats=1 \
        "$work/$name" "$root/fuzz/corpus/$name" 2>"$work/$name.log" || {
        tail -40 "$work/$name.log"
        echo "fuzz $name: FAILED" >&2
        exit 1
    }
    grep -E "stat::number_of_executed_units" "$work/$name.log" || true
done
