#!/bin/sh
# heapcount preloaded into a program not linked with it: the exit report
# counts its heap calls.
#   test_preload.sh LIBHEAPCOUNT PROGRAM TMPDIR
set -eu
lib=$1 prog=$2 tmp=$3
report="$tmp/heapcount-report.$$"
log="$tmp/heapcount-preload.$$.lcmlog"
rm -f "$report"
LD_PRELOAD="$lib" HEAPCOUNT_REPORT="$report" "$prog" "$log"
cat "$report"
# The publisher allocates its buffer once: at least one malloc, and as many
# frees as allocations are not required (libc keeps some), but some.
awk '{ if ($2 < 1 || $8 < 1) exit 1 }' "$report"
# Without the variable, no report.
rm -f "$report"
LD_PRELOAD="$lib" "$prog" "$log"
[ ! -e "$report" ]
rm -f "$log"
