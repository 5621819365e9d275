#!/bin/bash
# The bash completions (data/bash-completion) on the built programs: each
# case sets COMP_WORDS and COMP_CWORD as bash does for a line with the
# cursor at its end (bash splits `--set key=value` into key, '=', value),
# calls the completion function and compares COMPREPLY with what the
# programs' own --help, --help-config=json and a folder of files give.
# Once on their own, once more under bash-completion's loader (found by
# its name in a completions folder) when bash-completion is installed.
#   test_completion.sh COMPLETION_DIR RTEDGE [RTEDGED]
set -u
dir=$(cd "$1" && pwd)
rtedge=$(realpath "$2")
rtedged=${3:+$(realpath "$3")}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
cases=0
# In a cross build meson test sets MESON_EXE_WRAPPER (qemu-user): the
# completions run the programs through a script by the program's name.
if [ -n "${MESON_EXE_WRAPPER:-}" ]; then
    mkdir "$tmp/bin"
    for p in rtedge rtedged; do
        real=${!p}
        [ -n "$real" ] || continue
        printf '#!/bin/sh\nexec %s %s "$@"\n' "$MESON_EXE_WRAPPER" "$real" >"$tmp/bin/$p"
        chmod +x "$tmp/bin/$p"
        printf -v "$p" '%s' "$tmp/bin/$p"
    done
fi

# complete FUNCTION WORD...: COMPREPLY for the words, the last being
# completed, sorted, one a line.
complete_words() {
    local fn=$1
    shift
    COMP_WORDS=("$@")
    COMP_CWORD=$(($# - 1))
    COMP_LINE="$*"
    COMP_POINT=${#COMP_LINE}
    COMPREPLY=()
    "$fn" "$1" "${COMP_WORDS[COMP_CWORD]}" "${COMP_WORDS[COMP_CWORD - 1]}"
    [ ${#COMPREPLY[@]} -eq 0 ] || printf '%s\n' "${COMPREPLY[@]}" | LC_ALL=C sort
}

# check WANT FUNCTION WORD...: WANT (lines, any order) is what completes.
check() {
    local want got
    want=$(printf '%s\n' "$1" | sed '/^$/d' | LC_ALL=C sort)
    shift
    got=$(complete_words "$@")
    cases=$((cases + 1))
    if [ "$got" != "$want" ]; then
        echo "FAIL: ${*:2} <TAB>: got [$(echo $got)], want [$(echo $want)]"
        failures=$((failures + 1))
    fi
}

# What the programs say, parsed here independently of the completions.
commands=$("$rtedge" --help | awk '/^commands:/ { on = 1; next } on && NF { print $1 }')
[ "$(echo "$commands" | wc -l)" -ge 20 ] || { echo "FAIL: rtedge --help lists no commands"; exit 1; }
grasp_options=$("$rtedge" grasp --help | grep -o '^  --[a-z0-9-]*' | tr -d ' ')
json() { "$rtedged" --help-config=json | /usr/bin/python3 -c "import json, sys
keys = json.load(sys.stdin)['keys']
$1"; }

mkdir "$tmp/files" "$tmp/files/sub dir"
touch "$tmp/files/a.png" "$tmp/files/b.JPG" "$tmp/files/c.txt" "$tmp/files/d.y4m" "$tmp/files/e f.pgm"

run_cases() {
    cd "$tmp/files" || exit 1
    check canny _rtedge "$rtedge" can
    check "$commands"$'\n--help\n--version' _rtedge "$rtedge" ''
    check $'--auto\n--auto-sigma' _rtedge "$rtedge" canny --au
    check $'none\nmedian\notsu' _rtedge "$rtedge" canny in.png --auto ''
    check $'binary\nbinary_inv' _rtedge "$rtedge" threshold a.png b.png --type binary
    check $'lsq\ntheil-sen' _rtedge "$rtedge" lanes --fit ''
    check '' _rtedge "$rtedge" canny --low ''
    check "$grasp_options" _rtedge "$rtedge" grasp a.png --
    check $'a.png\nb.JPG\nd.y4m\ne f.pgm\nsub dir' _rtedge "$rtedge" canny ''
    check $'a.png\nb.JPG\nd.y4m\ne f.pgm\nsub dir' _rtedge "$rtedge" grasp a.png --overlay ''
    check 'e f.pgm' _rtedge "$rtedge" blur e
    check '' _rtedge "$rtedge" no-such-command --
    [ -n "$rtedged" ] || return 0
    check --set _rtedged "$rtedged" --se
    check $'--help-config\n--help-config=json' _rtedged "$rtedged" --help-c
    check "$("$rtedged" --help | grep -o '^  --[a-z=-]*' | tr -d ' ')" _rtedged "$rtedged" --
    check "$(json 'print("\n".join(k["section"] + "." + k["key"] + "=" for k in keys))')" \
        _rtedged "$rtedged" --config x.conf --set ''
    check "$(json 'print("\n".join("lane." + k["key"] + "=" for k in keys
        if k["section"] == "lane" and k["key"].startswith("canny_")))')" \
        _rtedged "$rtedged" --set lane.canny_
    check "$(json 'print("\n".join(next(k["choices"] for k in keys if k["key"] == "pace")))')" \
        _rtedged "$rtedged" --set source.pace =
    check $'fast\nfps' _rtedged "$rtedged" --set source.pace = f
    check $'false\ntrue' _rtedged "$rtedged" --fast --set lane.enabled =
    check '' _rtedged "$rtedged" --set lane.canny_low =
    check json _rtedged "$rtedged" --help-config =
    check $'a.png\nb.JPG\nc.txt\nd.y4m\ne f.pgm\nsub dir' _rtedged "$rtedged" --config ''
    check '' _rtedged "$rtedged" --fps ''
    check '' _rtedged "$rtedged" --set lane.roi=0,1 --lcm-url ''
    check 'sub dir' _rtedged "$rtedged" --source s
    check 'e f.pgm' _rtedged "$rtedged" --dump-config e
    # '=' not a word break: the whole word is completed
    check $'source.pace=fast\nsource.pace=fps' _rtedged "$rtedged" --set source.pace=f
}

# shellcheck source=/dev/null
source "$dir/rtedge" && source "$dir/rtedged" || { echo "FAIL: the completions do not load"; exit 1; }
run_cases
framework=/usr/share/bash-completion/bash_completion
if [ -f "$framework" ]; then
    # bash-completion loads a command's completion from a folder
    # `completions` by the command's name.
    mkdir "$tmp/user"
    ln -s "$dir" "$tmp/user/completions"
    unset -f _rtedge _rtedged
    complete -r rtedge rtedged
    export BASH_COMPLETION_USER_DIR=$tmp/user
    # shellcheck source=/dev/null
    source "$framework"
    for p in rtedge rtedged; do
        __load_completion "$p" && complete -p "$p" | grep -q -- "-F _$p $p\$" ||
            { echo "FAIL: bash-completion does not load the completion of $p from $dir"; failures=$((failures + 1)); }
    done
    run_cases
else
    echo "note: bash-completion not installed: its loader not tried"
fi
echo "$cases cases, $failures failed"
[ "$failures" -eq 0 ]
