#!/bin/sh
# rtedged as a program: rtedged.conf is what --help-config prints, every
# kind of bad configuration exits 2 with file:line, SIGTERM finishes with a
# final status and exit 0, SIGHUP applies a runtime key and refuses a size.
#   daemon_cli.sh RTEDGED SUBSCRIBE_PY TYPES_DIR TMPDIR Y4M CONF
set -u
RTEDGED=$1 SUB=$2 TYPES=$3 TMP=$4/daemon_cli.$$ Y4M=$5 CONF=$6
PY=/usr/bin/python3
mkdir -p "$TMP"
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
summary() { $PY "$SUB" --types "$TYPES" --quiet --summary "$1"; }
field() { $PY -c 'import json,sys; d=json.loads(sys.argv[1]); exec("print(" + sys.argv[2] + ")")' "$1" "$2"; }

# The documented default file is the table's own output.
"$RTEDGED" --help-config | diff -u "$CONF" - >/dev/null ||
    fail "rtedged.conf differs from rtedged --help-config (regenerate it)"
"$RTEDGED" --config "$CONF" --check-config >"$TMP/eff" || fail "--check-config on rtedged.conf"
grep -q '^\[realtime\]' "$TMP/eff" || fail "--check-config prints no [realtime]"
echo "ok: rtedged.conf and --check-config"

# Bad configurations: exit 2 and the file:line in the message.
bad() { # NAME LINE EXPECTED-TEXT CONTENT
    printf '%b' "$4" >"$TMP/$1.conf"
    "$RTEDGED" --config "$TMP/$1.conf" --check-config >/dev/null 2>"$TMP/err"
    rc=$?
    [ $rc -eq 2 ] || fail "$1: exit $rc, not 2"
    grep -q "$TMP/$1.conf:$2: .*$3" "$TMP/err" || fail "$1: message '$(cat "$TMP/err")'"
    echo "ok: $1: $(cat "$TMP/err")"
}
bad unknown_key 2 "unknown key 'foo'" '[lane]\nfoo = 1\n'
bad wrong_type 3 "not an integer" '# c\n[lane]\ncanny_low = abc\n'
bad bad_bool 2 "not a boolean" '[source]\nloop = maybe\n'
bad out_of_range 2 "out of range 0..255" '[grasp]\nthreshold = 300\n'
bad real_range 2 "out of range" '[source]\nspeed = 0\n'
bad bad_enum 2 "not one of" '[source]\npace = warp\n'
bad bad_section 1 "unknown section \[nosuch\]" '[nosuch]\nx = 1\n'
bad broken_header 1 "bad section header" '[lane\n'
bad duplicate 3 "duplicate key grasp.threshold" '[grasp]\nthreshold = 3\nthreshold = 4\n'
bad no_equals 2 "expected 'key = value'" '[grasp]\nthreshold\n'
bad no_section 1 "outside a \[section\]" 'threshold = 3\n'
# Command-line and cross-key errors: exit 2 too.
"$RTEDGED" --set grasp.threshold=-1 --check-config 2>"$TMP/err" >/dev/null
[ $? -eq 2 ] && grep -q "out of range" "$TMP/err" || fail "--set out of range"
"$RTEDGED" --set lane.canny_low=100 --set lane.canny_high=50 --check-config 2>"$TMP/err" >/dev/null
[ $? -eq 2 ] && grep -q "exceeds" "$TMP/err" || fail "canny low > high"
"$RTEDGED" --deadline-ms abc --check-config 2>/dev/null >/dev/null
[ $? -eq 2 ] || fail "--deadline-ms abc"
"$RTEDGED" --bogus 2>/dev/null >/dev/null
[ $? -eq 2 ] || fail "unknown option"
echo "ok: command-line errors"

# SIGTERM: finish the frame, final status, exit 0.
"$RTEDGED" --source "$Y4M" --loop --fps 50 --lcm-url "file://$TMP/term.lcm" 2>"$TMP/term.err" &
pid=$!
sleep 1.5
kill -TERM $pid
wait $pid
rc=$?
[ $rc -eq 0 ] || fail "SIGTERM: exit $rc: $(cat "$TMP/term.err")"
s=$(summary "$TMP/term.lcm")
lanes=$(field "$s" 'd["lanes"]')
final=$(field "$s" 'd["last_status"]["frames_processed"]')
[ "$lanes" -gt 10 ] || fail "SIGTERM: only $lanes lane messages"
[ "$final" -eq "$lanes" ] || fail "SIGTERM: final status says $final frames, $lanes published"
tail -c 400 "$TMP/term.lcm" | grep -q RTEDGE_STATUS || fail "SIGTERM: the log does not end with a status"
echo "ok: SIGTERM after $lanes frames, final status, exit 0"

# SIGHUP: a runtime key applied at the next frame, a size change refused.
cat >"$TMP/hup.conf" <<EOC
[source]
path = $Y4M
loop = true
pace = fps
fps = 50
[publish]
url = file://$TMP/hup.lcm
EOC
"$RTEDGED" --config "$TMP/hup.conf" 2>"$TMP/hup.err" &
pid=$!
sleep 1
printf '[grasp]\nmin_area = 100000000\n' >>"$TMP/hup.conf"
kill -HUP $pid
sleep 1
printf 'max_objects = 5\n' >>"$TMP/hup.conf"
kill -HUP $pid
sleep 1
kill -TERM $pid
wait $pid || fail "SIGHUP run: exit $?"
grep -q "re-read and applied" "$TMP/hup.err" || fail "SIGHUP: not applied: $(cat "$TMP/hup.err")"
grep -q "refused: grasp.max_objects cannot change" "$TMP/hup.err" ||
    fail "SIGHUP: size change not refused: $(cat "$TMP/hup.err")"
grep -q "1 reloads, 1 refused" "$TMP/hup.err" || fail "SIGHUP counters: $(tail -1 "$TMP/hup.err")"
s=$(summary "$TMP/hup.lcm")
[ "$(field "$s" 'd["objects_last"]')" -eq 0 ] || fail "SIGHUP: min_area not applied"
[ "$(field "$s" 'len(d["config_hashes"])')" -eq 2 ] || fail "SIGHUP: status hashes $s"
echo "ok: SIGHUP applied grasp.min_area, refused grasp.max_objects"

# [realtime]: SCHED_FIFO, affinity and mlockall are applied or warned about, never fatal.
"$RTEDGED" --source "$Y4M" --fast --max-frames 3 --lcm-url "file://$TMP/rt.lcm" \
    --set realtime.priority=10 --set realtime.cpu=0 --set realtime.mlockall=true 2>"$TMP/rt.err" ||
    fail "realtime: exit $?: $(cat "$TMP/rt.err")"
grep -q "3 processed" "$TMP/rt.err" || fail "realtime: $(cat "$TMP/rt.err")"
echo "ok: realtime settings: $(grep -c warning "$TMP/rt.err") warnings: $(grep warning "$TMP/rt.err" | tr '\n' ' ')"

# A slow recorded pace still stops at once on SIGTERM (no wait for the next frame's time).
"$RTEDGED" --source "$Y4M" --speed 0.01 --lcm-url "file://$TMP/slow.lcm" 2>"$TMP/slow.err" &
pid=$!
sleep 1
kill -TERM $pid
start=$(date +%s)
wait $pid || fail "slow: exit $?"
[ $(( $(date +%s) - start )) -le 1 ] || fail "slow pace: SIGTERM took too long"
echo "ok: SIGTERM during a long wait for a frame's time"

# A camera that is not there: a clear message and exit 1 (not a configuration error).
"$RTEDGED" --source /dev/video99 --lcm-url "file://$TMP/cam.lcm" 2>"$TMP/cam.err" >/dev/null
rc=$?
[ $rc -eq 1 ] && grep -q "cannot open v4l2 source /dev/video99" "$TMP/cam.err" ||
    fail "missing camera: exit $rc: $(cat "$TMP/cam.err")"
echo "ok: missing camera: $(tail -1 "$TMP/cam.err")"
