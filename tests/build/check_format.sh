#!/usr/bin/env bash
# Checks that every C and C++ source in the tree is formatted as
# .clang-format says (clang-format --dry-run --Werror): formatting is
# applied by `clang-format -i`, never argued about in review.
#   check_format.sh SOURCE_ROOT
set -u
root=$1
command -v clang-format >/dev/null || { echo "clang-format is not installed"; exit 77; }
cd "$root" || exit 1
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    mapfile -t files < <(git ls-files '*.c' '*.h' '*.cpp')
else
    mapfile -t files < <(find src include tests tools -name '*.c' -o -name '*.h' -o -name '*.cpp')
fi
[ ${#files[@]} -gt 0 ] || { echo "no sources found under $root"; exit 1; }
if clang-format --dry-run --Werror "${files[@]}"; then
    echo "${#files[@]} files formatted as .clang-format says"
else
    echo "run: clang-format -i \$(git ls-files '*.c' '*.h' '*.cpp')"
    exit 1
fi
