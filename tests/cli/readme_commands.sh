#!/bin/sh
# README.md's command lines for `rtedge`, `rtedged` and tools/subscribe.py,
# run as written from a scratch directory that looks like the source tree,
# with the built programs on PATH as `meson devenv` puts them. Each must
# succeed, but `rtedged --list-cameras`, which may find no camera (exit 1,
# "no camera found").
#   readme_commands.sh SOURCE_DIR RTEDGE RTEDGED LCM_PYTHON_TYPES
set -u
src=$1
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
ln -s "$src/fixtures" "$src/tools" "$scratch/" && cp "$src/rtedged.conf" "$scratch/" || exit 1
PATH=$(cd "$(dirname "$2")" && pwd):$(cd "$(dirname "$3")" && pwd):$PATH
RTEDGE_LCM_PYTHON=$4
export PATH RTEDGE_LCM_PYTHON
awk '/^```sh$/ { block = 1; next } /^```$/ { block = 0 } block' "$src/README.md" |
    grep -E '^(rtedge|rtedged|tools/subscribe\.py) ' | sed 's/ *#.*//' >"$scratch/commands"
n=$(wc -l <"$scratch/commands")
[ "$n" -ge 8 ] || { echo "FAIL: only $n command lines found in README.md"; exit 1; }
cd "$scratch" || exit 1
failed=0
while read -r line; do
    if sh -c "$line" >out.txt 2>&1; then
        echo "ok: $line"
    elif [ "$line" = "rtedged --list-cameras" ] && grep -q 'no camera found' out.txt; then
        echo "ok: $line (no camera here)"
    else
        echo "FAIL: $line"; tail -5 out.txt; failed=$((failed + 1))
    fi
done <commands
[ "$failed" -eq 0 ] && echo "ok: README.md's $n command lines work as written"
