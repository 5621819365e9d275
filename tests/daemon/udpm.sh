#!/bin/sh
# rtedged over udpm:// (run inside tests/lcm/netns.sh: a private network
# namespace with multicast on lo). lcm-logger records the daemon's channels
# and a Python subscriber listens live; both must see every frame. Then the
# logged image_t frames are replayed into the daemon (LCM log source) and
# give the same lanes.
#   udpm.sh RTEDGED SUBSCRIBE_PY TYPES_DIR TMPDIR Y4M
set -u
RTEDGED=$1 SUB=$2 TYPES=$3 TMP=$4/daemon_udpm.$$ Y4M=$5
PY=/usr/bin/python3
URL='udpm://239.255.76.67:7667?ttl=0'
command -v lcm-logger >/dev/null || { echo "skipped: lcm-logger (liblcm-bin) missing"; exit 77; }
mkdir -p "$TMP"
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
field() { $PY -c 'import json,sys; d=json.loads(sys.argv[1]); exec("print(" + sys.argv[2] + ")")' "$1" "$2"; }
frames=$(grep -c FRAME "$Y4M")

lcm-logger --lcm-url="$URL" -c 'RTEDGE_.*' -q "$TMP/logger.lcm" &
logger=$!
$PY "$SUB" --types "$TYPES" --timeout 4 --quiet --summary --transport builtin "$URL" >"$TMP/live.json" &
sub=$!
# The same through the lcm Python package, when tools/test could install it.
pkg=
if PYTHONPATH=${RTE_PYTHON_LCM:-} $PY -c 'import lcm' 2>/dev/null; then
    PYTHONPATH=$RTE_PYTHON_LCM $PY "$SUB" --types "$TYPES" --timeout 4 --quiet --summary \
        --transport lcm "$URL" >"$TMP/live_pkg.json" &
    pkg=$!
else
    echo "SKIP (part): no lcm Python package (RTE_PYTHON_LCM=${RTE_PYTHON_LCM:-unset}); the built-in receiver is tested"
fi
sleep 1
"$RTEDGED" --source "$Y4M" --fps 40 --deadline-ms 1000 --set deadline.max_late_ms=-1 --lcm-url "$URL" --set publish.images=true \
    2>"$TMP/daemon.err" || fail "rtedged: $(cat "$TMP/daemon.err")"
sleep 1
kill -INT $logger
wait $logger
wait $sub
[ -z "$pkg" ] || wait $pkg
live=$(cat "$TMP/live.json")
[ "$(field "$live" 'd["lanes"]')" -eq "$frames" ] || fail "live subscriber: $live"
[ "$(field "$live" 'd["grasps"]')" -eq "$frames" ] || fail "live subscriber: $live"
[ "$(field "$live" 'd["last_status"]["frames_processed"]')" -eq "$frames" ] || fail "live: $live"
echo "ok: live subscriber over udpm: $frames frames"
if [ -n "$pkg" ]; then
    live=$(cat "$TMP/live_pkg.json")
    [ "$(field "$live" 'd["transport"]')" = lcm ] || fail "lcm package subscriber: $live"
    [ "$(field "$live" 'd["lanes"]')" -eq "$frames" ] || fail "lcm package subscriber: $live"
    [ "$(field "$live" 'd["grasps"]')" -eq "$frames" ] || fail "lcm package subscriber: $live"
    echo "ok: live subscriber through the lcm Python package: $frames frames"
fi
logged=$($PY "$SUB" --types "$TYPES" --quiet --summary "$TMP/logger.lcm")
[ "$(field "$logged" 'd["lanes"]')" -eq "$frames" ] || fail "lcm-logger: $logged"
[ "$(field "$logged" 'd["images"]')" -eq "$frames" ] || fail "lcm-logger images: $logged"
echo "ok: lcm-logger recorded $frames lane, grasp and image messages"

# Replay the recorded image_t frames into the daemon.
"$RTEDGED" --set source.kind=lcm-log --source "$TMP/logger.lcm" --set source.channel=RTEDGE_IMAGE \
    --fast --lcm-url "file://$TMP/replay.lcm" 2>"$TMP/replay.err" || fail "replay: $(cat "$TMP/replay.err")"
$PY "$SUB" --types "$TYPES" "$TMP/logger.lcm" | grep '^frame' | cut -c1-40 >"$TMP/a"
$PY "$SUB" --types "$TYPES" "$TMP/replay.lcm" | grep '^frame' | cut -c1-40 >"$TMP/b"
[ "$(wc -l <"$TMP/b")" -eq "$frames" ] || fail "replay: $(wc -l <"$TMP/b") frames"
diff "$TMP/a" "$TMP/b" >/dev/null || fail "replayed lanes differ: $(diff "$TMP/a" "$TMP/b" | head -5)"
echo "ok: the LCM log source replays the recording with the same lanes and offsets"

# A live LCM source: a second daemon analyses the first one's image_t frames
# as they arrive over udpm:// (what a camera process publishing image_t would be).
"$RTEDGED" --set source.kind=lcm --source "$URL" --set source.channel=RTEDGE_IMAGE \
    --set source.format=grey --set source.width=480 --set source.height=270 \
    --deadline-ms 1000 --lcm-url "file://$TMP/live_in.lcm" 2>"$TMP/live_in.err" &
live=$!
sleep 1
"$RTEDGED" --source "$Y4M" --fps 20 --deadline-ms 1000 --set deadline.max_late_ms=-1 \
    --lcm-url "$URL" --set publish.images=true 2>"$TMP/daemon2.err" || fail "rtedged (images)"
sleep 1
kill -TERM $live
wait $live || fail "live-source daemon: exit $?: $(cat "$TMP/live_in.err")"
got=$($PY "$SUB" --types "$TYPES" --quiet --summary "$TMP/live_in.lcm")
n=$(field "$got" 'd["lanes"]')
[ "$n" -ge $((frames * 3 / 4)) ] || fail "live LCM source: $n of $frames frames: $(cat "$TMP/live_in.err")"
echo "ok: live LCM image_t source: $n of $frames frames analysed"
