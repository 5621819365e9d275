#!/bin/sh
# Runs one libFuzzer target for a bounded time: the seed corpus is read (and
# every seed run: a seed that crashes fails at once), new inputs go to
# WORK/corpus, a crash, leak, timeout or out-of-memory input to
# WORK/artifacts/, and the last line says what was done:
#   fuzz NAME: N runs in S s, coverage C edges (F features), corpus K inputs, no crash
#   run_fuzzer.sh TARGET SEED_DIR WORK_DIR SECONDS [libFuzzer options...]
set -u
target=$1 seeds=$2 work=$3 seconds=$4
shift 4
name=$(basename "$target" | sed 's/^fuzz_//')
mkdir -p "$work/corpus" "$work/artifacts"
log=$work/fuzz.log
# -timeout: one input over 10 s is a hang; -rss_limit_mb: the process over
# 2 GiB (and one malloc over it) is an out-of-memory failure.
"$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$work/artifacts/" "$@" "$work/corpus" "$seeds" >"$log" 2>&1
rc=$?
runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
time=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -1)
last=$(grep -E '^#[0-9]+' "$log" | tail -1)
cov=$(echo "$last" | sed -n 's/.* cov: \([0-9]*\).*/\1/p')
ft=$(echo "$last" | sed -n 's/.* ft: \([0-9]*\).*/\1/p')
corp=$(echo "$last" | sed -n 's/.* corp: \([0-9]*\).*/\1/p')
if [ $rc -ne 0 ] || ls "$work/artifacts" | grep -q .; then
    grep -E 'ERROR|SUMMARY|fuzz:|==[0-9]+==|artifact' "$log" | head -40
    tail -30 "$log"
    echo "fuzz $name: FAILED (exit $rc) after ${runs:-?} runs; reproduce with: $target $(ls -d "$work"/artifacts/* 2>/dev/null | head -1)"
    echo "  (once fixed, keep the input as a regression case in $seeds)"
    exit 1
fi
echo "fuzz $name: ${runs:-?} runs in ${time:-$seconds} s, coverage ${cov:-?} edges (${ft:-?} features), corpus ${corp:-?} inputs, no crash"
