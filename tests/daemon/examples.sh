#!/bin/sh
# The example configurations (data/examples): each is accepted as it is
# (--check-config), and run on the road clip in place of its camera it
# runs only its path: the vehicle publishes lanes and no grasps, the arm
# grasps and no lanes.
#   examples.sh RTEDGED SUBSCRIBE_PY LCM_PYTHON_TYPES EXAMPLES_DIR TMPDIR Y4M
set -u
rtedged=$1 subscribe=$2 types=$3 examples=$4 tmp=$5/examples_test y4m=$6
mkdir -p "$tmp" || exit 1
failed=0
counts() {
    RTEDGE_LCM_PYTHON=$types /usr/bin/python3 "$subscribe" --summary --quiet --transport builtin "$1" |
        tail -n 1 | /usr/bin/python3 -c 'import json, sys; d = json.load(sys.stdin); print(d["lanes"], d["grasps"])'
}
for example in vehicle:"22 0" arm:"0 22"; do
    name=${example%%:*} want=${example#*:}
    conf=$examples/$name.conf
    if ! "$rtedged" --config "$conf" --check-config >/dev/null; then
        echo "FAIL: $conf refused"; failed=1; continue
    fi
    rm -f "$tmp/$name.lcm"
    "$rtedged" --config "$conf" --source "$y4m" --set source.pace=fast \
        --lcm-url "file://$tmp/$name.lcm" 2>"$tmp/$name.err" || { echo "FAIL: $name run"; cat "$tmp/$name.err"; failed=1; continue; }
    got=$(counts "$tmp/$name.lcm")
    if [ "$got" = "$want" ]; then
        echo "ok: $name.conf: lanes and grasps $got"
    else
        echo "FAIL: $name.conf: lanes and grasps '$got', expected '$want'"; failed=1
    fi
done
exit $failed
